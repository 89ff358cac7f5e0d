#include "texel_bake.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

#include "colour.h"

namespace cutaway {

TexelCanvas::TexelCanvas(int w, int h, bool wrap)
    : width(w),
      height(h),
      wrap_u(wrap),
      colour(static_cast<size_t>(w) * h, glm::dvec3(0.0)),
      material(colour.size(), glm::dvec2(0.0)),
      covered(colour.size(), 0) {}

void rasterise(const ShadedMesh& mesh, std::span<const glm::dvec2> texel,
               const ColourModulation* modulation, double strength, TexelCanvas& canvas) {
  const int width = canvas.width, height = canvas.height;
  for (const glm::uvec3& t : mesh.triangle) {
    const glm::dvec2 a = texel[t.x], b = texel[t.y], c = texel[t.z];
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (area == 0) continue;
    const glm::ivec2 lo(static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))),
                        static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
    const glm::ivec2 hi(static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))),
                        static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
    const int x_from = canvas.wrap_u ? lo.x : std::max(lo.x, 0);
    const int x_to = canvas.wrap_u ? std::min(hi.x, lo.x + width - 1) : std::min(hi.x, width - 1);
    for (int y = std::max(lo.y, 0); y <= std::min(hi.y, height - 1); ++y)
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
        if (modulation) {
          const glm::dvec3 where =
              wa * mesh.position[t.x] + wb * mesh.position[t.y] + wc * mesh.position[t.z];
          colour = (*modulation)(where, colour, strength);
        }
        canvas.colour[i] = colour;
        canvas.material[i] =
            wa * mesh.material[t.x] + wb * mesh.material[t.y] + wc * mesh.material[t.z];
        canvas.covered[i] = 1;
      }
  }
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

namespace {
uint8_t byte_of(double v) {
  return static_cast<uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
}
}  // namespace

std::vector<uint8_t> srgb_pixels(const TexelCanvas& canvas) {
  std::vector<uint8_t> out(canvas.colour.size() * 3);
  for (size_t i = 0; i < canvas.colour.size(); ++i) {
    const glm::dvec3 s = linear_to_srgb(glm::clamp(canvas.colour[i], 0.0, 1.0));
    for (int k = 0; k < 3; ++k) out[3 * i + k] = byte_of(s[k]);
  }
  return out;
}

std::vector<uint8_t> material_pixels(const TexelCanvas& canvas) {
  std::vector<uint8_t> out(canvas.material.size() * 4);
  for (size_t i = 0; i < canvas.material.size(); ++i) {
    out[4 * i + 0] = 255;
    out[4 * i + 1] = byte_of(canvas.material[i].x);
    out[4 * i + 2] = 0;
    out[4 * i + 3] = byte_of(canvas.material[i].y);
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
