// sRGB <-> linear RGB conversion (IEC 61966-2-1). Templates are sRGB; everything inside cutaway
// is linear RGB (doc/algorithms.md §7).
#pragma once

#include <cstdint>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace cutaway {

/// One sRGB-encoded component in 0..1 to linear 0..1 (IEC 61966-2-1 transfer function).
double srgb_to_linear(double c);

/// One linear component in 0..1 to sRGB 0..1; input is clamped to 0..1. Its power c^(1/2.4)
/// is taken with basic IEEE operations (a cube root by Newton's iteration, then two square
/// roots), within 3 ulp of pow() and the same bits on every CPU, about 4.5 times faster than
/// the portable pow(): the baked textures' colour modulation takes it for every texel.
double linear_to_srgb(double c);

/// One linear component to an 8-bit sRGB code: lround(255 * linear_to_srgb(c)) with the power
/// taken by pow() (clamped to 0..1; NaN gives 0), the same bits as that formula, found by binary
/// search in the table of the 255 linear values where the code steps up (made once, by bisection on
/// that formula): eight comparisons instead of a pow() per texel.
uint8_t linear_to_srgb8(double c);

/// A value in 0..1 (clamped) as an 8-bit code, lround(255 v), with no transfer curve: for
/// linear data (material, normal and height maps).
uint8_t unit_to_byte(double v);

/// Component-wise srgb_to_linear.
glm::dvec3 srgb_to_linear(const glm::dvec3& c);

/// Component-wise linear_to_srgb.
glm::dvec3 linear_to_srgb(const glm::dvec3& c);

/// How far apart two colours look, in steps of 1/255: the largest difference over the
/// sRGB-encoded channels (linear RGB in). A tolerance in these steps is the same visible step in
/// dark and light flesh (in linear RGB, 0.02 is 17/255 near black and 3/255 near white).
double colour_difference(const glm::dvec3& colour, const glm::dvec3& colour_ref);

/// How far apart two samples of the material channels (roughness, translucency; 0..1, stored
/// linearly in 8-bit maps) lie, in steps of 1/255: the larger channel difference.
double material_difference(const glm::dvec2& material, const glm::dvec2& material_ref);

/// How far apart two samples of a cap's field look, in steps of 1/255: the larger of
/// colour_difference and material_difference.
double visible_difference(const glm::dvec3& colour, const glm::dvec2& material,
                          const glm::dvec3& colour_ref, const glm::dvec2& material_ref);

/// The largest differences between a diffused sample and its interpolation that adaptive cap
/// sampling accepts, in steps of 1/255.
struct VisibleTolerance {
  double colour = 0;    ///< colour_difference
  double material = 0;  ///< material_difference
  /// Whether (colour, material) lies within both tolerances of (colour_ref, material_ref).
  bool accepts(const glm::dvec3& colour, const glm::dvec2& material, const glm::dvec3& colour_ref,
               const glm::dvec2& material_ref) const {
    return colour_difference(colour, colour_ref) <= this->colour &&
           material_difference(material, material_ref) <= this->material;
  }
};

}  // namespace cutaway
