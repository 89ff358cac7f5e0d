#include "base/colour.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>

namespace cutaway {

double srgb_to_linear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

double linear_to_srgb(double c) {
  c = std::clamp(c, 0.0, 1.0);
  return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055;
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
