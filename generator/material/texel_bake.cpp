#include "material/texel_bake.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "base/colour.h"
#include "base/parallel_chunks.h"

namespace cutaway {

TexelCanvas::TexelCanvas(int w, int h, bool wrap)
    : width(w), height(h), wrap_u(wrap), colour(static_cast<size_t>(w) * h, glm::dvec3(0.0)),
      material(colour.size(), glm::dvec2(0.0)), covered(colour.size(), 0) {}

void rasterise(const ShadedMesh& mesh, std::span<const glm::dvec2> texel,
               const SkinPatterns* patterns, const ColourModulation* modulation, double strength,
               TexelCanvas& canvas) {
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
      const int x_to = canvas.wrap_u ? std::min(hi.x, lo.x + width - 1) : std::min(hi.x, width - 1);
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
          glm::dvec3 colour = wa * mesh.colour[t.x] + wb * mesh.colour[t.y] + wc * mesh.colour[t.z];
          const glm::dvec3 where =
              wa * mesh.position[t.x] + wb * mesh.position[t.y] + wc * mesh.position[t.z];
          if (patterns) {
            const glm::dvec2 param(1 - (y + 0.5) / height, (column + 0.5) / width);
            const SkinPatterns::Shade shaded = patterns->shade(param, where, colour);
            colour = shaded.colour;
            if (!canvas.relief.empty()) canvas.relief[i] = {shaded.height, texel_metres};
          }
          glm::dvec2 material =
              wa * mesh.material[t.x] + wb * mesh.material[t.y] + wc * mesh.material[t.z];
          if (modulation) colour = (*modulation)(where, colour, strength, material);
          canvas.colour[i] = colour;
          canvas.material[i] = material;
          canvas.covered[i] = 1;
        }
    }
  });
}

void dilate(TexelCanvas& canvas, int rings) {
  const int width = canvas.width, height = canvas.height;
  for (int ring = 0; ring < rings; ++ring) {
    const HugePageVector<uint8_t> before = canvas.covered;
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
  // One pyramid level: per texel a mean and whether it holds one. Weights are 0 or 1 at every
  // level (a coarse texel's weight is the sum of its children's, clamped to 1), so a flag
  // holds them; level 0 is the canvas itself.
  struct Level {
    int width = 0, height = 0;
    HugePageVector<glm::dvec3> colour;
    HugePageVector<glm::dvec2> material;
    HugePageVector<uint8_t> filled;
  };
  if (std::find(canvas.covered.begin(), canvas.covered.end(), 1) == canvas.covered.end()) return;
  struct View {
    int width, height;
    glm::dvec3* colour;
    glm::dvec2* material;
    const uint8_t* filled;
  };
  std::vector<Level> coarser;
  auto view = [&](size_t k) {  // level k: 0 the canvas, k > 0 coarser[k - 1]
    if (k == 0)
      return View{canvas.width, canvas.height, canvas.colour.data(), canvas.material.data(),
                  canvas.covered.data()};
    Level& l = coarser[k - 1];
    return View{l.width, l.height, l.colour.data(), l.material.data(), l.filled.data()};
  };
  // Pull: each coarser texel is the mean of its filled (up to) 2 x 2 finer ones, summed in
  // row order, and filled where any of them is.
  for (size_t k = 0;; ++k) {
    const View fine = view(k);
    if (fine.width <= 1 && fine.height <= 1) break;
    Level coarse;
    coarse.width = (fine.width + 1) / 2;
    coarse.height = (fine.height + 1) / 2;
    const size_t n = static_cast<size_t>(coarse.width) * coarse.height;
    coarse.colour.assign(n, glm::dvec3(0.0));
    coarse.material.assign(n, glm::dvec2(0.0));
    coarse.filled.assign(n, 0);
    parallel_chunks(static_cast<size_t>(coarse.height), 64, 0, [&](size_t y0, size_t y1) {
      for (int y = static_cast<int>(y0); y < static_cast<int>(y1); ++y)
        for (int x = 0; x < coarse.width; ++x) {
          const size_t c = static_cast<size_t>(y) * coarse.width + x;
          int count = 0;
          for (int fy = 2 * y; fy < std::min(2 * y + 2, fine.height); ++fy)
            for (int fx = 2 * x; fx < std::min(2 * x + 2, fine.width); ++fx) {
              const size_t f = static_cast<size_t>(fy) * fine.width + fx;
              if (!fine.filled[f]) continue;
              coarse.colour[c] += fine.colour[f];
              coarse.material[c] += fine.material[f];
              ++count;
            }
          if (count > 0) {
            coarse.colour[c] /= static_cast<double>(count);
            coarse.material[c] /= static_cast<double>(count);
            coarse.filled[c] = 1;
          }
        }
    });
    coarser.push_back(std::move(coarse));
  }
  // Push: from the coarsest level down, an empty texel takes the bilinear upsampling of the
  // (already filled) coarser level; filled texels keep their means.
  for (size_t k = coarser.size(); k-- > 0;) {
    const View fine = view(k), coarse = view(k + 1);
    auto at = [&coarse](int x, int y) {
      return static_cast<size_t>(std::clamp(y, 0, coarse.height - 1)) * coarse.width +
             static_cast<size_t>(std::clamp(x, 0, coarse.width - 1));
    };
    parallel_chunks(static_cast<size_t>(fine.height), 64, 0, [&](size_t y0, size_t y1) {
      for (int y = static_cast<int>(y0); y < static_cast<int>(y1); ++y)
        for (int x = 0; x < fine.width; ++x) {
          const size_t f = static_cast<size_t>(y) * fine.width + x;
          if (fine.filled[f]) continue;
          // The fine texel's centre in coarse texel units, and its four nearest coarse centres.
          const double cx = (x + 0.5) / 2 - 0.5, cy = (y + 0.5) / 2 - 0.5;
          const int x0 = static_cast<int>(std::floor(cx)), y0 = static_cast<int>(std::floor(cy));
          const double tx = cx - x0, ty = cy - y0;
          const size_t i00 = at(x0, y0), i10 = at(x0 + 1, y0), i01 = at(x0, y0 + 1),
                       i11 = at(x0 + 1, y0 + 1);
          fine.colour[f] = (1 - ty) * ((1 - tx) * coarse.colour[i00] + tx * coarse.colour[i10]) +
                           ty * ((1 - tx) * coarse.colour[i01] + tx * coarse.colour[i11]);
          fine.material[f] =
              (1 - ty) * ((1 - tx) * coarse.material[i00] + tx * coarse.material[i10]) +
              ty * ((1 - tx) * coarse.material[i01] + tx * coarse.material[i11]);
        }
    });
  }
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
