#include "base/colour.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/common.hpp>

namespace cutaway {

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

namespace {

/// c^(5/12) = c^(1/2.4) for c in [0.0031308, 1]: the cube root by four Newton steps from a
/// guess made of c's bits (its exponent divided by three; about 3 % off, so the steps leave
/// it at rounding error), to the fifth power, then two square roots. Additions,
/// multiplications, divisions and square roots round the same on every CPU (the build keeps
/// the compiler from fusing them).
double power_five_twelfths(double c) {
  double y = std::bit_cast<double>(std::bit_cast<uint64_t>(c) / 3 + 0x2A9F7893782DA1CEull);
  for (int step = 0; step < 4; ++step) y = (2 * y + c / (y * y)) / 3;
  const double y2 = y * y;
  return std::sqrt(std::sqrt(y2 * y2 * y));
}

}  // namespace

double linear_to_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * power_five_twelfths(c) - 0.055;
}

namespace {

/// The 8-bit code of linear_to_srgb(c), by the formula with pow(), which rounds monotonically
/// there (the table's bisection needs that; linear_to_srgb's own power may wobble by an ulp).
uint8_t srgb8_by_formula(double c) {
  c = std::clamp(c, 0.0, 1.0);
  const double srgb = c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
  return static_cast<uint8_t>(std::lround(255.0 * srgb));
}

/// step[k - 1]: the smallest double c with srgb8_by_formula(c) >= k, k = 1..255. Non-negative
/// doubles order as their bit patterns, so bisection on the bits finds the exact step.
std::array<double, 255> srgb8_steps() {
  std::array<double, 255> step{};
  for (int k = 1; k <= 255; ++k) {
    uint64_t lo = std::bit_cast<uint64_t>(0.0),
             hi = std::bit_cast<uint64_t>(1.0);  // f(lo) < k <= f(hi)
    while (hi - lo > 1) {
      const uint64_t mid = lo + (hi - lo) / 2;
      (srgb8_by_formula(std::bit_cast<double>(mid)) >= k ? hi : lo) = mid;
    }
    step[static_cast<size_t>(k - 1)] = std::bit_cast<double>(hi);
  }
  return step;
}

}  // namespace

uint8_t linear_to_srgb8(double c) {
  static const std::array<double, 255> step = srgb8_steps();
  if (!(c > 0)) return 0;  // and NaN
  return static_cast<uint8_t>(std::upper_bound(step.begin(), step.end(), c) - step.begin());
}

uint8_t unit_to_byte(double v) {
  return static_cast<uint8_t>(std::lround(255.0 * std::clamp(v, 0.0, 1.0)));
}

glm::dvec3 srgb_to_linear(const glm::dvec3& c) {
  return {srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z)};
}

glm::dvec3 linear_to_srgb(const glm::dvec3& c) {
  return {linear_to_srgb(c.x), linear_to_srgb(c.y), linear_to_srgb(c.z)};
}

double colour_difference(const glm::dvec3& colour, const glm::dvec3& colour_ref) {
  const glm::dvec3 d = glm::abs(linear_to_srgb(colour) - linear_to_srgb(colour_ref));
  return 255.0 * std::max({d.x, d.y, d.z});
}

double material_difference(const glm::dvec2& material, const glm::dvec2& material_ref) {
  const glm::dvec2 d = glm::abs(material - material_ref);
  return 255.0 * std::max(d.x, d.y);
}

double visible_difference(const glm::dvec3& colour, const glm::dvec2& material,
                          const glm::dvec3& colour_ref, const glm::dvec2& material_ref) {
  return std::max(colour_difference(colour, colour_ref),
                  material_difference(material, material_ref));
}

}  // namespace cutaway
