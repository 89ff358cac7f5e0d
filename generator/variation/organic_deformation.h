// Organic deformation of a variant (doc/algorithms.md §5, Organic deformation): a seeded,
// smooth, low-frequency map of space applied to the whole DS model of a variant (every surface,
// sheet and grain), so that a variant is lumpy, lopsided and leaning instead of a perfect sweep.
// The map is a composition of three maps that are each one-to-one, so it keeps every surface's
// nesting by construction: nothing that did not cross before can cross after, and the colour
// inside is still diffused from the same surfaces.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "base/outcome.h"
#include "model/ds_model.h"
#include "model/template.h"

namespace cutaway {

/// Plane waves the lumps are made of (more look like noise but keep less of the amplitude in
/// each variant: the sum of n random-phase waves has about 1 / sqrt(2 n) of their summed
/// amplitude as its rms).
inline constexpr int kLumpWaves = 3;

/// The largest Lipschitz constant of the lumps' displacement (2 pi amplitude / size at the
/// amount): below 1 the lumps map space one-to-one; at 0.8 no length is squeezed to under a
/// fifth or stretched to over 1.8 times itself.
inline constexpr double kMaxLumpStrain = 0.8;
/// The largest lopsided fraction at the amount: the fuller side stretched by up to 1.5, the
/// flatter squeezed to 0.5.
inline constexpr double kMaxLopsided = 0.5;
/// The largest lean at the amount, radians (30 degrees).
inline constexpr double kMaxLeanRad = 0.5235987755982988;

/// Passes when the largest draw of a template's `variation` (lumps, lopsided, lean) at
/// variation amount `amount` keeps each part one-to-one: 2 pi amplitude amount / size <=
/// kMaxLumpStrain, lopsided amount <= kMaxLopsided, lean amount <= kMaxLeanRad; otherwise fails
/// naming the part, its value and the limit (with the largest lump amplitude that would fit, in
/// template units of `metres_per_unit` metres): such a map could fold space, turning a surface
/// inside out.
Check check_organic(const OrganicSpec& spec, double amount, double metres_per_unit);

/// The farthest any point can move sideways, metres, at variation amount `amount`, for an
/// object of horizontal reach `radius_m` from its axis and height `height_m`: the lumps'
/// amplitude, the lopsided shift (lopsided (radius + amplitude) / 3) and the lean at the top
/// (tan(lean) times the height). Up or down a point moves by at most the lumps' amplitude.
double organic_reach_m(const OrganicSpec& spec, double amount, double radius_m, double height_m);

/// One plane wave of the lumps: displacement amplitude sin(dot(wave, p) + phase) direction.
struct LumpWave {
  glm::dvec3 wave{0.0};       ///< wave vector, 2 pi / size long, radians per metre
  glm::dvec3 direction{0.0};  ///< unit displacement direction
  double amplitude = 0.0;     ///< metres
  double phase = 0.0;         ///< radians
};

/// A drawn organic deformation, metres, object frame: the lumps, then the lopsided stretch,
/// then the lean, each one-to-one on its own, so their composition is too:
///   lumps(p)    = p + sum of the kLumpWaves plane waves; one-to-one because the waves'
///                 displacement is a contraction (lump_strain() < 1)
///   lopsided(q) = q + f / (2 R) (u^2 - R^2 / 3) d, u = dot(q - c, d): along the horizontal unit
///                 direction d the side towards d is fuller, the other flatter (f: the fraction,
///                 c: the skin's horizontal centre, R: the lumped model's horizontal reach
///                 from c); it moves points along d only, by an amount increasing in u (slope
///                 1 + f u / R > 0 for |u| <= R, f <= 0.5), so it is one-to-one
///   lean(r)     = r + (r.y - base) t: a shear that moves each height sideways along the
///                 horizontal vector t (|t| = tan of the lean angle), the base staying where it
///                 is; its determinant is 1
/// Horizontal planes stay horizontal under the lean; the lumps and the lopsided stretch bend
/// them by at most their amplitude.
struct OrganicDeformation {
  std::array<LumpWave, kLumpWaves> lumps{};
  glm::dvec3 lopsided_direction{1, 0, 0};  ///< d, horizontal unit
  double lopsided = 0.0;                   ///< f, 0..kMaxLopsided
  glm::dvec3 centre{0.0};                  ///< c (y = 0)
  double reach_m = 0.0;                    ///< R, metres (> 0 where lopsided > 0)
  glm::dvec3 lean{0.0};                    ///< t, horizontal
  double base_y = 0.0;                     ///< the height that does not move sideways, metres

  /// The deformed position of `p` (metres).
  glm::dvec3 map(const glm::dvec3& p) const;
  /// The map's Jacobian at `p` (glm column-major: column j holds d map / d p_j).
  glm::dmat3 jacobian(const glm::dvec3& p) const;
  /// The Lipschitz constant of the lumps' displacement: sum |amplitude| |wave|.
  double lump_strain() const;
  /// True when the draw moves nothing (every amplitude, lopsided and lean 0).
  bool identity() const;
};

/// Draws the organic deformation of variant `seed` of `tmpl` for its `model` (the straight or
/// bent sweep with its grains): each lump wave gets a uniform direction on the sphere for its
/// wave vector and for its displacement, a uniform phase and a share of the amplitude
/// tmpl.organic.lump_amplitude_m x tmpl.variation_amount x U(0.6, 1) (shares U(0.5, 1),
/// normalised); lopsided and lean get a uniform horizontal direction and tmpl's value x amount
/// x U(0.3, 1). From a pcg32 stream of its own (derive_seed(seed, {organic purpose})), so adding
/// the deformation to a template leaves the sections its seeds draw as they were.
/// Deterministic in (tmpl, model, seed). Returns the identity when the template asks for none.
/// @pre check_organic(tmpl.organic, tmpl.variation_amount) passes (the draw's lump_strain is
///      then at most kMaxLumpStrain, its lopsided at most kMaxLopsided)
OrganicDeformation draw_organic(const Template& tmpl, const DsModel& model, uint64_t seed);

/// Moves every vertex of every surface of `model` (skin, sheets, grains) by `d`, updates its
/// bounds, and where d leans the axis sets model.cut_axis to the leaned axis (the line the
/// straight axis x = z = 0 goes to), which halves and wedges then cut along.
/// @pre d is one-to-one on the model (lump_strain() < 1, lopsided <= kMaxLopsided, reach_m the
///      lumped model's reach: draw_organic's draws are)
void deform_model(const OrganicDeformation& d, DsModel& model);

}  // namespace cutaway
