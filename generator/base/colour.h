// sRGB <-> linear RGB conversion (IEC 61966-2-1). Templates are sRGB; everything inside cutaway
// is linear RGB (doc/algorithms.md §7).
#pragma once

#include <glm/vec2.hpp>
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

/// How far apart two samples of a cap's field look, in steps of 1/255: the largest difference
/// over the sRGB-encoded colour channels (`colour`, linear RGB in) and the material channels
/// (`material`, 0..1 as they are). Adaptive sampling's tests use it, so that a tolerance is the
/// same visible step in dark and light flesh (in linear RGB, 0.02 is 17/255 near black and
/// 3/255 near white).
double visible_difference(const glm::dvec3& colour, const glm::dvec2& material,
                          const glm::dvec3& colour_ref, const glm::dvec2& material_ref);

}  // namespace cutaway
