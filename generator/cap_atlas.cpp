#include "cap_atlas.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <stb/stb_rect_pack.h>

#include "colour.h"

namespace cutaway {

namespace {

/// One cap part of one piece, mapped to the plane frame of its section.
struct Island {
  size_t piece = 0;  ///< index into the input pieces
  const PiecePart* part = nullptr;
  unsigned first_vertex = 0;     ///< of the part in merge_parts(piece)
  std::vector<glm::dvec2> uv_m;  ///< per part vertex: plane coordinates, metres
  glm::dvec2 lo{0.0}, hi{0.0};   ///< bounds of uv_m
};

/// Packs rectangles of w x h texels (in order) into width x max_height; returns the packed
/// positions, or an empty vector when they do not all fit.
std::vector<glm::ivec2> pack(const std::vector<glm::ivec2>& sizes, int width, int max_height) {
  std::vector<stbrp_rect> rects(sizes.size());
  for (size_t i = 0; i < sizes.size(); ++i) {
    rects[i].id = static_cast<int>(i);
    rects[i].w = sizes[i].x;
    rects[i].h = sizes[i].y;
  }
  std::vector<stbrp_node> nodes(static_cast<size_t>(width));
  stbrp_context context;
  stbrp_init_target(&context, width, max_height, nodes.data(), width);
  if (!stbrp_pack_rects(&context, rects.data(), static_cast<int>(rects.size()))) return {};
  std::vector<glm::ivec2> at(sizes.size());
  for (const stbrp_rect& r : rects) at[static_cast<size_t>(r.id)] = {r.x, r.y};
  return at;
}

}  // namespace

CapAtlas bake_cap_atlas(const std::vector<const Piece*>& pieces,
                        const std::vector<CrossSection>& sections,
                        const ColourModulation* modulation, double strength,
                        const CapAtlasOptions& options) {
  if (!(options.texels_per_m > 0) || options.padding < 0 || options.max_size < 16)
    throw std::invalid_argument("bake_cap_atlas: bad options");
  CapAtlas atlas;
  std::vector<Island> islands;
  for (size_t i = 0; i < pieces.size(); ++i) {
    unsigned offset = 0;
    size_t vertices = 0;
    for (const PiecePart& part : pieces[i]->parts) vertices += part.mesh.position.size();
    atlas.uv.emplace_back(vertices, glm::dvec2(0.0));
    for (const PiecePart& part : pieces[i]->parts) {
      if (part.kind == PartKind::Cap && !part.mesh.triangle.empty()) {
        const CrossSection& section = sections.at(static_cast<size_t>(part.plane));
        Island island;
        island.piece = i;
        island.part = &part;
        island.first_vertex = offset;
        for (const glm::dvec3& p : part.mesh.position) {
          const glm::dvec3 d = p - section.plane.point;
          island.uv_m.emplace_back(glm::dot(d, section.u_axis), glm::dot(d, section.v_axis));
        }
        island.lo = island.hi = island.uv_m.front();
        for (const glm::dvec2& q : island.uv_m) {
          island.lo = glm::min(island.lo, q);
          island.hi = glm::max(island.hi, q);
        }
        islands.push_back(std::move(island));
      }
      offset += static_cast<unsigned>(part.mesh.position.size());
    }
  }
  if (islands.empty()) return atlas;

  // Pack at the asked density, or at 0.8 of it until everything fits in max_size squared.
  const int pad = options.padding;
  double density = options.texels_per_m;
  std::vector<glm::ivec2> sizes, at;
  int width = 0;
  for (int attempt = 0; attempt < 64; ++attempt, density *= 0.8) {
    sizes.clear();
    double area = 0;
    int widest = 0;
    for (const Island& island : islands) {
      const glm::dvec2 extent = (island.hi - island.lo) * density;
      const glm::ivec2 size(static_cast<int>(std::ceil(extent.x)) + 1 + 2 * pad,
                            static_cast<int>(std::ceil(extent.y)) + 1 + 2 * pad);
      sizes.push_back(size);
      area += static_cast<double>(size.x) * size.y;
      widest = std::max(widest, size.x);
    }
    width = 16;
    while (width < options.max_size && (width < widest || width * width < 1.3 * area)) width *= 2;
    width = std::min(width, options.max_size);
    if (widest > width) continue;
    at = pack(sizes, width, options.max_size);
    if (!at.empty()) break;
  }
  if (at.empty()) throw std::invalid_argument("bake_cap_atlas: the caps do not fit");
  int height = 1;
  for (size_t k = 0; k < islands.size(); ++k) height = std::max(height, at[k].y + sizes[k].y);
  atlas.width = width;
  atlas.height = height;
  atlas.texels_per_m = density;

  // Rasterise every cap triangle at texel centres.
  std::vector<glm::dvec3> colour(static_cast<size_t>(width) * height, glm::dvec3(0.0));
  std::vector<uint8_t> filled(colour.size(), 0);
  for (size_t k = 0; k < islands.size(); ++k) {
    const Island& island = islands[k];
    const ShadedMesh& mesh = island.part->mesh;
    std::vector<glm::dvec2> texel(island.uv_m.size());
    for (size_t v = 0; v < texel.size(); ++v) {
      texel[v] = (island.uv_m[v] - island.lo) * density + glm::dvec2(pad) + glm::dvec2(at[k]);
      atlas.uv[island.piece][island.first_vertex + v] =
          texel[v] / glm::dvec2(static_cast<double>(width), static_cast<double>(height));
    }
    for (const glm::uvec3& t : mesh.triangle) {
      const glm::dvec2 a = texel[t.x], b = texel[t.y], c = texel[t.z];
      const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      if (area == 0) continue;
      const glm::ivec2 lo(static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))),
                          static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
      const glm::ivec2 hi(static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))),
                          static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
      for (int y = std::max(lo.y, 0); y <= std::min(hi.y, height - 1); ++y)
        for (int x = std::max(lo.x, 0); x <= std::min(hi.x, width - 1); ++x) {
          const glm::dvec2 p(x + 0.5, y + 0.5);
          // Barycentric weights; a small tolerance closes hairline gaps on shared edges.
          const double wa = ((b.x - p.x) * (c.y - p.y) - (b.y - p.y) * (c.x - p.x)) / area;
          const double wb = ((c.x - p.x) * (a.y - p.y) - (c.y - p.y) * (a.x - p.x)) / area;
          const double wc = 1 - wa - wb;
          if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
          const size_t i = static_cast<size_t>(y) * width + x;
          glm::dvec3 c_lin = wa * mesh.colour[t.x] + wb * mesh.colour[t.y] + wc * mesh.colour[t.z];
          if (modulation) {
            const glm::dvec3 where =
                wa * mesh.position[t.x] + wb * mesh.position[t.y] + wc * mesh.position[t.z];
            c_lin = (*modulation)(where, c_lin, strength);
          }
          colour[i] = c_lin;
          filled[i] = 1;
        }
    }
  }
  // Dilation: `pad` rings, each texel taking the mean of its filled 8-neighbours.
  for (int ring = 0; ring < pad; ++ring) {
    std::vector<uint8_t> before = filled;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t i = static_cast<size_t>(y) * width + x;
        if (before[i]) continue;
        glm::dvec3 sum(0.0);
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int xx = x + dx, yy = y + dy;
            if (xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
            const size_t j = static_cast<size_t>(yy) * width + xx;
            if (before[j]) sum += colour[j], ++n;
          }
        if (n > 0) {
          colour[i] = sum / static_cast<double>(n);
          filled[i] = 1;
        }
      }
  }
  atlas.srgb.resize(colour.size() * 3);
  for (size_t i = 0; i < colour.size(); ++i) {
    const glm::dvec3 s = linear_to_srgb(glm::clamp(colour[i], 0.0, 1.0));
    for (int k = 0; k < 3; ++k)
      atlas.srgb[3 * i + k] = static_cast<uint8_t>(std::lround(255.0 * s[k]));
  }
  return atlas;
}

}  // namespace cutaway
