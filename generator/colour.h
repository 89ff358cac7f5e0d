// sRGB <-> linear RGB conversion (IEC 61966-2-1). Templates are sRGB; everything inside cutaway
// is linear RGB (design/algorithms.md §7).
#pragma once

#include <glm/vec3.hpp>

namespace cutaway {

/// One sRGB-encoded component in 0..1 to linear 0..1 (IEC 61966-2-1 transfer function).
double srgb_to_linear(double c);

/// One linear component in 0..1 to sRGB 0..1; input is clamped to 0..1.
double linear_to_srgb(double c);

/// Component-wise srgb_to_linear.
glm::dvec3 srgb_to_linear(const glm::dvec3& c);

/// Component-wise linear_to_srgb.
glm::dvec3 linear_to_srgb(const glm::dvec3& c);

}  // namespace cutaway
