#include "material/cap_atlas.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <stb/stb_rect_pack.h>

#include "base/error.h"
#include "material/texel_bake.h"

namespace cutaway {

namespace {

/// One cap part of one piece, mapped to the plane frame of its section.
struct CapPart {
  size_t piece = 0;  ///< index into the input pieces
  const PiecePart* part = nullptr;
  unsigned first_vertex = 0;     ///< of the part in merge_parts(piece)
  std::vector<glm::dvec2> uv_m;  ///< per part vertex: plane coordinates, metres
};

/// A rectangle of one cut plane, in its frame (metres), baked once: the caps on the two sides
/// of a cut cover the same region of the plane and carry the same diffused field there, so
/// both address the same texels.
struct Island {
  int plane = -1;               ///< index into the sections
  glm::dvec2 lo{0.0}, hi{0.0};  ///< bounds of its caps' uv_m
  std::vector<size_t> caps;     ///< indices into the cap parts, in piece and part order
};

/// Whether the rectangles of islands `a` and `b` share an area wider than `eps` each way.
bool overlap(const Island& a, const Island& b, double eps) {
  const glm::dvec2 lo = glm::max(a.lo, b.lo), hi = glm::min(a.hi, b.hi);
  return hi.x - lo.x > eps && hi.y - lo.y > eps;
}

/// One island per cap part, then islands of one plane whose rectangles overlap merged until
/// none do (the two caps of a cut have the same rectangle; caps of different faces of one plane
/// that merge only cost the texels between them). Islands keep the order of their first cap.
std::vector<Island> group_islands(const std::vector<CapPart>& caps) {
  std::vector<Island> islands;
  for (size_t c = 0; c < caps.size(); ++c) {
    Island island;
    island.plane = caps[c].part->plane;
    island.lo = island.hi = caps[c].uv_m.front();
    for (const glm::dvec2& q : caps[c].uv_m) {
      island.lo = glm::min(island.lo, q);
      island.hi = glm::max(island.hi, q);
    }
    island.caps.push_back(c);
    islands.push_back(std::move(island));
  }
  constexpr double eps = 1e-6;  // metres: touching rectangles (adjacent faces) stay apart
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t a = 0; a < islands.size(); ++a)
      for (size_t b = a + 1; b < islands.size(); ++b) {
        if (islands[a].plane != islands[b].plane || !overlap(islands[a], islands[b], eps)) continue;
        islands[a].lo = glm::min(islands[a].lo, islands[b].lo);
        islands[a].hi = glm::max(islands[a].hi, islands[b].hi);
        islands[a].caps.insert(islands[a].caps.end(), islands[b].caps.begin(),
                               islands[b].caps.end());
        islands.erase(islands.begin() + static_cast<std::ptrdiff_t>(b));
        merged = true;
        --b;
      }
  }
  for (Island& island : islands) std::sort(island.caps.begin(), island.caps.end());
  return islands;
}

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

/// The side at or above `n` texels an atlas may have: a multiple of kAtlasStep, or with
/// `power_of_two` a power of two (at least kAtlasStep).
int round_up_side(int n, bool power_of_two) {
  if (!power_of_two) return (n + kAtlasStep - 1) / kAtlasStep * kAtlasStep;
  int side = kAtlasStep;
  while (side < n) side *= 2;
  return side;
}

struct Packing {
  int width = 0, height = 0;   ///< round_up_side's sides; 0 x 0 when nothing fits
  std::vector<glm::ivec2> at;  ///< per rectangle, its lowest corner
};

/// The packing of `sizes` (their total area `area`, the widest `widest` texels across) whose
/// atlas, both sides round_up_side's and at most max_size, has the fewest texels: the widths
/// from the square root of the area (or the widest) up to twice that, in steps of an eighth (or
/// doubling, for powers of two), are tried; the first of equal areas wins. Nothing fits: an
/// empty packing.
Packing smallest_packing(const std::vector<glm::ivec2>& sizes, int widest, double area,
                         int max_size, bool power_of_two) {
  Packing best;
  const int start =
      round_up_side(std::max(widest, static_cast<int>(std::ceil(std::sqrt(area)))), power_of_two);
  long best_texels = 0;
  for (int width = start; width <= max_size && width <= 2 * start;
       width = power_of_two ? 2 * width
                            : round_up_side(width + std::max(kAtlasStep, width / 8), false)) {
    std::vector<glm::ivec2> at = pack(sizes, width, max_size);
    if (at.empty()) continue;
    int height = 0;
    for (size_t k = 0; k < sizes.size(); ++k) height = std::max(height, at[k].y + sizes[k].y);
    height = round_up_side(height, power_of_two);
    if (height > max_size) continue;
    const long texels = static_cast<long>(width) * height;
    if (best.at.empty() || texels < best_texels) {
      best = {width, height, std::move(at)};
      best_texels = texels;
    }
  }
  return best;
}

}  // namespace

CapAtlas bake_cap_atlas(const std::vector<const Piece*>& pieces,
                        const std::vector<CrossSection>& sections,
                        const ColourModulation* modulation, double strength,
                        const CapAtlasOptions& options) {
  if (!(options.texels_per_m > 0) || options.padding < 0 || options.max_size < 16 ||
      options.max_size % kAtlasStep != 0 ||
      (options.power_of_two && round_up_side(options.max_size, true) != options.max_size))
    throw InternalError("bake_cap_atlas: bad options");
  CapAtlas atlas;
  std::vector<CapPart> caps;
  for (size_t i = 0; i < pieces.size(); ++i) {
    const std::vector<unsigned> offsets = part_vertex_offsets(*pieces[i]);
    atlas.uv.emplace_back(offsets.back(), glm::dvec2(0.0));
    for (size_t k = 0; k < pieces[i]->parts.size(); ++k) {
      const PiecePart& part = pieces[i]->parts[k];
      if (part.kind == PartKind::Cap && !part.mesh.triangle.empty()) {
        const CrossSection& section = sections.at(static_cast<size_t>(part.plane));
        CapPart cap;
        cap.piece = i;
        cap.part = &part;
        cap.first_vertex = offsets[k];
        for (const glm::dvec3& p : part.mesh.position) {
          const glm::dvec3 d = p - section.plane.point;
          cap.uv_m.emplace_back(glm::dot(d, section.u_axis), glm::dot(d, section.v_axis));
        }
        caps.push_back(std::move(cap));
      }
    }
  }
  if (caps.empty()) return atlas;
  const std::vector<Island> islands = group_islands(caps);

  // Pack at the asked density, or at 0.8 of it until everything fits in max_size squared.
  const int pad = options.padding;
  double density = options.texels_per_m;
  std::vector<glm::ivec2> sizes, at;
  int width = 0, height = 0;
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
    const auto [w, h, placed] =
        smallest_packing(sizes, widest, area, options.max_size, options.power_of_two);
    width = w;
    height = h;
    at = placed;
    if (!at.empty()) break;
  }
  if (at.empty()) throw InternalError("bake_cap_atlas: the caps do not fit");
  atlas.width = width;
  atlas.height = height;
  atlas.texels_per_m = density;

  // Rasterise every cap triangle at texel centres, then dilate and fill the background.
  TexelCanvas canvas(width, height, false);
  for (size_t k = 0; k < islands.size(); ++k) {
    for (const size_t c : islands[k].caps) {
      const CapPart& cap = caps[c];
      std::vector<glm::dvec2> texel(cap.uv_m.size());
      for (size_t v = 0; v < texel.size(); ++v) {
        texel[v] = (cap.uv_m[v] - islands[k].lo) * density + glm::dvec2(pad) + glm::dvec2(at[k]);
        atlas.uv[cap.piece][cap.first_vertex + v] =
            texel[v] / glm::dvec2(static_cast<double>(width), static_cast<double>(height));
      }
      rasterise(cap.part->mesh, texel, nullptr, modulation, strength, canvas);
    }
  }
  const MaterialStats stats = material_stats(canvas);
  dilate(canvas, pad);
  atlas.covered.assign(canvas.covered.begin(), canvas.covered.end());
  fill_background(canvas);
  atlas.srgb = srgb_pixels(canvas);
  // To 1e-6: the diffusion's single-precision sheets give 0.30000001 for 0.3.
  atlas.material_mean = glm::round(stats.mean * 1e6) / 1e6;
  if (std::max(stats.spread.x, stats.spread.y) >= kMaterialMapSpread) {
    const TexelCanvas half = half_size(canvas);
    atlas.material = material_pixels(half);
    atlas.material_width = half.width;
    atlas.material_height = half.height;
  }
  return atlas;
}

}  // namespace cutaway
