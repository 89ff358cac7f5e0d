#include "material/texel_bake.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "base/colour.h"
#include "base/parallel_chunks.h"

namespace cutaway {

TexelCanvas::TexelCanvas(int w, int h, bool wrap)
    : width(w),
      height(h),
      wrap_u(wrap),
      colour(static_cast<size_t>(w) * h, glm::dvec3(0.0)),
      material(colour.size(), glm::dvec2(0.0)),
      covered(colour.size(), 0) {}

void rasterise(const ShadedMesh& mesh, std::span<const glm::dvec2> texel,
               const SkinPatterns* patterns, const ColourModulation* modulation,
               double strength, TexelCanvas& canvas) {
  const int width = canvas.width, height = canvas.height;
  // Bands of rows on TBB's threads, each walking every triangle in order: a texel is written by
  // the same triangles in the same order as in one pass, whatever the threads.
  parallel_chunks(static_cast<size_t>(height), 16, 0, [&](size_t row_begin, size_t row_end) {
    const int first_row = static_cast<int>(row_begin), last_row = static_cast<int>(row_end) - 1;
    for (const glm::uvec3& t : mesh.triangle) {
      const glm::dvec2 a = texel[t.x], b = texel[t.y], c = texel[t.z];
      const glm::ivec2 lo(static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))),
                          static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
      const glm::ivec2 hi(static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))),
                          static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
      if (hi.y < first_row || lo.y > last_row) continue;
      const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
      if (area == 0) continue;
      // The surface's metres per texel across and down: the lengths of d(position)/d(texel),
      // constant over the triangle (its map from texels to the surface is affine).
      const glm::dvec2 e1 = b - a, e2 = c - a;
      const glm::dvec3 p1 = mesh.position[t.y] - mesh.position[t.x],
                       p2 = mesh.position[t.z] - mesh.position[t.x];
      const glm::dvec2 texel_metres(glm::length((p1 * e2.y - p2 * e1.y) / area),
                                    glm::length((p2 * e1.x - p1 * e2.x) / area));
      const int x_from = canvas.wrap_u ? lo.x : std::max(lo.x, 0);
      const int x_to =
          canvas.wrap_u ? std::min(hi.x, lo.x + width - 1) : std::min(hi.x, width - 1);
      for (int y = std::max({lo.y, 0, first_row}); y <= std::min({hi.y, height - 1, last_row}); ++y)
        for (int x = x_from; x <= x_to; ++x) {
          const glm::dvec2 p(x + 0.5, y + 0.5);
          // Barycentric weights; a small tolerance closes hairline gaps on shared edges.
          const double wa = ((b.x - p.x) * (c.y - p.y) - (b.y - p.y) * (c.x - p.x)) / area;
          const double wb = ((c.x - p.x) * (a.y - p.y) - (c.y - p.y) * (a.x - p.x)) / area;
          const double wc = 1 - wa - wb;
          if (wa < -1e-9 || wb < -1e-9 || wc < -1e-9) continue;
          const int column = ((x % width) + width) % width;
          const size_t i = static_cast<size_t>(y) * width + column;
          glm::dvec3 colour =
              wa * mesh.colour[t.x] + wb * mesh.colour[t.y] + wc * mesh.colour[t.z];
          const glm::dvec3 where =
              wa * mesh.position[t.x] + wb * mesh.position[t.y] + wc * mesh.position[t.z];
          if (patterns) {
            const glm::dvec2 param(1 - (y + 0.5) / height, (column + 0.5) / width);
            const SkinPatterns::Shade shaded = patterns->shade(param, where, colour);
            colour = shaded.colour;
            if (!canvas.relief.empty()) canvas.relief[i] = {shaded.height, texel_metres};
          }
          if (modulation) colour = (*modulation)(where, colour, strength);
          canvas.colour[i] = colour;
          canvas.material[i] =
              wa * mesh.material[t.x] + wb * mesh.material[t.y] + wc * mesh.material[t.z];
          canvas.covered[i] = 1;
        }
    }
  });
}

void dilate(TexelCanvas& canvas, int rings) {
  const int width = canvas.width, height = canvas.height;
  for (int ring = 0; ring < rings; ++ring) {
    const std::vector<uint8_t> before = canvas.covered;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x) {
        const size_t i = static_cast<size_t>(y) * width + x;
        if (before[i]) continue;
        glm::dvec3 colour(0.0);
        glm::dvec2 material(0.0);
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            int xx = x + dx;
            const int yy = y + dy;
            if (canvas.wrap_u) xx = (xx + width) % width;
            if (xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
            const size_t j = static_cast<size_t>(yy) * width + xx;
            if (!before[j]) continue;
            colour += canvas.colour[j];
            material += canvas.material[j];
            ++n;
          }
        if (n > 0) {
          canvas.colour[i] = colour / static_cast<double>(n);
          canvas.material[i] = material / static_cast<double>(n);
          canvas.covered[i] = 1;
        }
      }
  }
}

void fill_background(TexelCanvas& canvas) {
  // One pyramid level: weighted sums turned into means, a weight in 0..1 per texel.
  struct Level {
    int width = 0, height = 0;
    std::vector<glm::dvec3> colour;
    std::vector<glm::dvec2> material;
    std::vector<double> weight;
  };
  if (std::find(canvas.covered.begin(), canvas.covered.end(), 1) == canvas.covered.end()) return;
  std::vector<Level> levels(1);
  levels[0].width = canvas.width;
  levels[0].height = canvas.height;
  levels[0].colour = std::move(canvas.colour);
  levels[0].material = std::move(canvas.material);
  for (const uint8_t c : canvas.covered) levels[0].weight.push_back(c ? 1.0 : 0.0);
  // Pull: each coarser texel is the weighted mean of its (up to) 2 x 2 finer ones, its weight
  // their summed weight clamped to 1.
  while (levels.back().width > 1 || levels.back().height > 1) {
    const Level& fine = levels.back();
    Level coarse;
    coarse.width = (fine.width + 1) / 2;
    coarse.height = (fine.height + 1) / 2;
    const size_t n = static_cast<size_t>(coarse.width) * coarse.height;
    coarse.colour.assign(n, glm::dvec3(0.0));
    coarse.material.assign(n, glm::dvec2(0.0));
    coarse.weight.assign(n, 0.0);
    for (int y = 0; y < fine.height; ++y)
      for (int x = 0; x < fine.width; ++x) {
        const size_t f = static_cast<size_t>(y) * fine.width + x;
        const size_t c = static_cast<size_t>(y / 2) * coarse.width + x / 2;
        coarse.colour[c] += fine.weight[f] * fine.colour[f];
        coarse.material[c] += fine.weight[f] * fine.material[f];
        coarse.weight[c] += fine.weight[f];
      }
    for (size_t c = 0; c < n; ++c) {
      if (coarse.weight[c] > 0) {
        coarse.colour[c] /= coarse.weight[c];
        coarse.material[c] /= coarse.weight[c];
      }
      coarse.weight[c] = std::min(coarse.weight[c], 1.0);
    }
    levels.push_back(std::move(coarse));
  }
  // Push: from the coarsest level down, a texel of weight w keeps w of its own mean and takes
  // 1 - w from the bilinear upsampling of the (already filled) coarser level.
  for (size_t k = levels.size() - 1; k-- > 0;) {
    Level& fine = levels[k];
    const Level& coarse = levels[k + 1];
    auto at = [&coarse](int x, int y) {
      return static_cast<size_t>(std::clamp(y, 0, coarse.height - 1)) * coarse.width +
             static_cast<size_t>(std::clamp(x, 0, coarse.width - 1));
    };
    for (int y = 0; y < fine.height; ++y)
      for (int x = 0; x < fine.width; ++x) {
        const size_t f = static_cast<size_t>(y) * fine.width + x;
        if (fine.weight[f] >= 1) continue;
        // The fine texel's centre in coarse texel units, and its four nearest coarse centres.
        const double cx = (x + 0.5) / 2 - 0.5, cy = (y + 0.5) / 2 - 0.5;
        const int x0 = static_cast<int>(std::floor(cx)), y0 = static_cast<int>(std::floor(cy));
        const double tx = cx - x0, ty = cy - y0;
        const size_t i00 = at(x0, y0), i10 = at(x0 + 1, y0), i01 = at(x0, y0 + 1),
                     i11 = at(x0 + 1, y0 + 1);
        const glm::dvec3 colour =
            (1 - ty) * ((1 - tx) * coarse.colour[i00] + tx * coarse.colour[i10]) +
            ty * ((1 - tx) * coarse.colour[i01] + tx * coarse.colour[i11]);
        const glm::dvec2 material =
            (1 - ty) * ((1 - tx) * coarse.material[i00] + tx * coarse.material[i10]) +
            ty * ((1 - tx) * coarse.material[i01] + tx * coarse.material[i11]);
        const double w = fine.weight[f];
        fine.colour[f] = w * fine.colour[f] + (1 - w) * colour;
        fine.material[f] = w * fine.material[f] + (1 - w) * material;
        fine.weight[f] = 1;
      }
  }
  canvas.colour = std::move(levels[0].colour);
  canvas.material = std::move(levels[0].material);
}

TexelCanvas half_size(const TexelCanvas& canvas) {
  TexelCanvas half((canvas.width + 1) / 2, (canvas.height + 1) / 2, canvas.wrap_u);
  std::vector<int> count(half.colour.size(), 0);
  for (int y = 0; y < canvas.height; ++y)
    for (int x = 0; x < canvas.width; ++x) {
      const size_t i = static_cast<size_t>(y) * canvas.width + x;
      const size_t h = static_cast<size_t>(y / 2) * half.width + x / 2;
      half.colour[h] += canvas.colour[i];
      half.material[h] += canvas.material[i];
      half.covered[h] = half.covered[h] | canvas.covered[i];
      ++count[h];
    }
  for (size_t h = 0; h < half.colour.size(); ++h) {
    half.colour[h] /= static_cast<double>(count[h]);
    half.material[h] /= static_cast<double>(count[h]);
  }
  return half;
}

std::vector<uint8_t> srgb_pixels(const TexelCanvas& canvas) {
  std::vector<uint8_t> out(canvas.colour.size() * 3);
  for (size_t i = 0; i < canvas.colour.size(); ++i) {
    for (int k = 0; k < 3; ++k) out[3 * i + k] = linear_to_srgb8(canvas.colour[i][k]);
  }
  return out;
}

std::vector<uint8_t> material_pixels(const TexelCanvas& canvas) {
  std::vector<uint8_t> out(canvas.material.size() * 4);
  for (size_t i = 0; i < canvas.material.size(); ++i) {
    out[4 * i + 0] = 255;
    out[4 * i + 1] = unit_to_byte(canvas.material[i].x);
    out[4 * i + 2] = 0;
    out[4 * i + 3] = unit_to_byte(canvas.material[i].y);
  }
  return out;
}

MaterialStats material_stats(const TexelCanvas& canvas) {
  MaterialStats stats;
  glm::dvec2 lo(1e300), hi(-1e300), sum(0.0);
  size_t n = 0;
  for (size_t i = 0; i < canvas.material.size(); ++i) {
    if (!canvas.covered[i]) continue;
    lo = glm::min(lo, canvas.material[i]);
    hi = glm::max(hi, canvas.material[i]);
    sum += canvas.material[i];
    ++n;
  }
  if (n == 0) return stats;
  stats.mean = sum / static_cast<double>(n);
  stats.spread = hi - lo;
  return stats;
}

}  // namespace cutaway
