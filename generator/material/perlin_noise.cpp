#include "material/perlin_noise.h"

#include <cmath>

#include "base/error.h"
#include "base/finite.h"
#include "base/random.h"

namespace cutaway {

namespace {

/// Perlin 2002's quintic fade: 6t^5 - 15t^4 + 10t^3 (zero first and second derivatives at 0, 1).
double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

double lerp(double a, double b, double t) { return a + t * (b - a); }

/// The 12 directions from the centre of a cube to its edges' midpoints, padded to 16 with four
/// of them repeated (Perlin 2002, §3) so that a 4-bit hash picks one without a division; the
/// padding keeps the set symmetric enough to add no visible bias.
constexpr double kGradients[16][3] = {
    {1, 1, 0}, {-1, 1, 0}, {1, -1, 0}, {-1, -1, 0},  //
    {1, 0, 1}, {-1, 0, 1}, {1, 0, -1}, {-1, 0, -1},  //
    {0, 1, 1}, {0, -1, 1}, {0, 1, -1}, {0, -1, -1},  //
    {1, 1, 0}, {-1, 1, 0}, {0, -1, 1}, {0, -1, -1},
};

/// The gradient selected by `hash` dotted with the offset (x, y, z) from its lattice point.
double grad(unsigned hash, double x, double y, double z) {
  const double* g = kGradients[hash & 15u];
  return g[0] * x + g[1] * y + g[2] * z;
}

}  // namespace

PerlinNoise::PerlinNoise(uint64_t seed) {
  for (int i = 0; i < 256; ++i) perm_[i] = static_cast<uint8_t>(i);
  Rng rng(seed);
  for (uint32_t i = 255; i > 0; --i) {  // Fisher-Yates: swap i with a uniform j in [0, i]
    const uint32_t j = rng.below(i + 1);
    std::swap(perm_[i], perm_[j]);
  }
}

double PerlinNoise::operator()(const glm::dvec3& p) const { return periodic(p, 256); }

double PerlinNoise::periodic(const glm::dvec3& p, unsigned period_x) const {
  CUTAWAY_CHECK(all_finite(p));
  CUTAWAY_CHECK(period_x >= 1 && period_x <= 256);
  const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
  // Lattice cell, wrapped to 0..period - 1 (the table's 256 for y and z); floor first, so
  // negatives wrap too.
  const auto wrap = [](double f, unsigned period) {
    const double n = period;
    const double m = f - n * std::floor(f / n);
    return static_cast<unsigned>(m) % period;
  };
  const unsigned X = wrap(fx, period_x), Y = wrap(fy, 256), Z = wrap(fz, 256);
  const unsigned X1 = (X + 1) % period_x;
  const double x = p.x - fx, y = p.y - fy, z = p.z - fz;  // position inside the cell, 0..1
  const double u = fade(x), v = fade(y), w = fade(z);

  // Hash of a lattice corner: nested permutation lookups, indices wrapped to 0..255.
  const auto hash = [this](unsigned i, unsigned j, unsigned k) -> unsigned {
    return perm_[(perm_[(perm_[i & 255u] + j) & 255u] + k) & 255u];
  };
  const double n000 = grad(hash(X, Y, Z), x, y, z);
  const double n100 = grad(hash(X1, Y, Z), x - 1, y, z);
  const double n010 = grad(hash(X, Y + 1, Z), x, y - 1, z);
  const double n110 = grad(hash(X1, Y + 1, Z), x - 1, y - 1, z);
  const double n001 = grad(hash(X, Y, Z + 1), x, y, z - 1);
  const double n101 = grad(hash(X1, Y, Z + 1), x - 1, y, z - 1);
  const double n011 = grad(hash(X, Y + 1, Z + 1), x, y - 1, z - 1);
  const double n111 = grad(hash(X1, Y + 1, Z + 1), x - 1, y - 1, z - 1);
  return lerp(lerp(lerp(n000, n100, u), lerp(n010, n110, u), v),
              lerp(lerp(n001, n101, u), lerp(n011, n111, u), v), w);
}

}  // namespace cutaway
