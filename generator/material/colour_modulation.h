// NPR colour modulation with improved Perlin noise (doc/algorithms.md §6; paper §5, Fig. 10:
// "color modulation based on 3D Perlin noise with manually adjusted weights on different
// frequency bands based on the unmodulated color"). Template parameters: NprSettings
// (template.h, doc/npr.md); the scene's render.perlin is the strength. The same modulation carries
// the interior texture (doc/algorithms.md §6, Interior texture): bands stretched along a
// direction field of the object (texture_field.h) and layers of cells (Worley 1996,
// cellular_noise.h) with colours of their own for walls and centres.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "material/perlin_noise.h"
#include "model/template.h"
#include "pieces/shaded_mesh.h"

namespace cutaway {

/// The weight of `band` for the unmodulated colour `colour_linear` (linear RGB):
/// amplitude * closeness, where closeness is 1 for an untinted band, and for a tinted one
/// (1 - (d / reach)^2)^2 when d < reach, else 0, with d the Euclidean distance between the
/// colour and the tint in sRGB components 0..1 (the colour is clamped to 0..1 first).
/// So a band with tint "#c8281e" and reach 0.3 acts fully on that red, half at d = 0.16, and not
/// at all on a yellow gel 0.5 away. Result in [0, amplitude].
double band_weight(const TextureBand& band, const glm::dvec3& colour_linear);

/// Where a point lies in a layer of cells: 0..1 masks.
struct CellMasks {
  double wall = 0.0;    ///< 1 within half the wall width of a wall between two cells, 0 beyond it
  double centre = 0.0;  ///< 1 - 2 F1 / (F1 + F2): 1 at a cell's feature point, 0 on a wall
};

/// The masks of `band` at the object-frame point `position_m` (metres) on the lattice seeded
/// `cells`: Worley's F1, F2 (cellular_noise.h) at band_lattice_point (texture_field.h).
CellMasks cell_masks(const CellBand& band, uint64_t cells, const glm::dvec3& position_m);

class BandWeights;

/// The modulation of one object: one PerlinNoise per band with its own permutation and a
/// random lattice offset, both from `seed`. Build one per object and apply it to all of the
/// object's meshes (skin, caps, every piece), so that points they share get the same colour.
class ColourModulation {
 public:
  /// @param npr  the template's bands and cells (copied)
  /// @param seed identifies the object, e.g. derive_seed(scene seed, {item, object, purpose});
  ///             band b uses derive_seed(seed, {b}) for its permutation and offset, cell layer
  ///             c derive_seed(seed, {"cell", c}) for its lattice
  ColourModulation(const NprSettings& npr, uint64_t seed);

  /// c' = clamp(c * (1 + strength * sum_b w_b(c) * noise_b(q_b(p) + offset_b)), 0, 1) per
  /// component, where w_b = band_weight(band b, c), q_b the band's lattice point
  /// (band_lattice_point: f_b p for an isotropic band) and offset_b in [0, 256)^3 lattice
  /// units. The change is a brightness change of the colour (all components scaled alike) of at
  /// most strength * sum_b amplitude_b * PerlinNoise::kBound, relative. Then each layer of
  /// cells in turn, with k = min(1, strength * band_weight(layer, c)) and its masks m at p:
  /// c' += (centre - c') k m.centre, then c' += (wall - c') k m.wall, for the colours the layer
  /// has. Both stay within 0..1.
  /// @param position_m the point in the OBJECT frame, metres (not the scene frame: the pieces of
  ///                   one object are placed differently but must agree)
  /// @param colour_linear the unmodulated colour, linear RGB
  /// @param strength  >= 0, finite (the scene's render.perlin, 0..10); 0 returns the colour
  ///                  unchanged (not even clamped)
  glm::dvec3 operator()(const glm::dvec3& position_m, const glm::dvec3& colour_linear,
                        double strength) const;

  /// The same colour, and the material channels (x: perceptual roughness, y: translucency;
  /// 0..1) at the point moved as the colour is by each layer of cells with its own roughness
  /// (CellBand::wall_roughness, centre_roughness): x' += (centre_roughness - x') k m.centre,
  /// then x' += (wall_roughness - x') k m.wall, with the layer's k and masks. Layers without
  /// them, and the bands, leave the channels as they are. For baked cut faces (texel_bake.h),
  /// whose material map carries the result.
  /// @param material the channels before, replaced by the channels after
  glm::dvec3 operator()(const glm::dvec3& position_m, const glm::dvec3& colour_linear,
                        double strength, glm::dvec2& material) const;

  /// The sum over bands of w_b(c) * noise_b at the point: the relative brightness change at
  /// strength 1 before clamping (for tests and diagnostics).
  double relative_change(const glm::dvec3& position_m, const glm::dvec3& colour_linear) const;

 private:
  struct Band {
    PerlinBand params;
    PerlinNoise noise;
    glm::dvec3 offset;     ///< lattice units
    glm::dvec3 tint_srgb;  ///< params.tint encoded as sRGB (band_weight compares in sRGB)
  };
  struct Cells {
    CellBand params;
    uint64_t seed;         ///< the lattice's
    glm::dvec3 tint_srgb;  ///< as Band's
  };
  double relative_change(const glm::dvec3& position_m, BandWeights& weight) const;
  glm::dvec3 modulate(const glm::dvec3& position_m, const glm::dvec3& colour_linear,
                      double strength, glm::dvec2* material) const;
  std::vector<Band> bands_;
  std::vector<Cells> cells_;
};

/// Modulates the colours of parallel arrays in place (a CrossSection's position and colour,
/// for example). Deterministic and independent of the order and grouping of the points: a point
/// gets the same colour in whatever array it is.
/// @param position_m #V points in the object frame, metres, finite
/// @param colour     #V linear RGB colours, replaced by the modulated ones
/// @param npr, seed  as ColourModulation; strength as its operator()
/// @throws InternalError when the sizes differ or strength is negative or not finite
void modulate_colours(std::span<const glm::dvec3> position_m, std::span<glm::dvec3> colour,
                      const NprSettings& npr, double strength, uint64_t seed);

/// Modulates mesh.colour in place from mesh.position (object frame, metres): the pipeline's
/// call, once per mesh of an object with the object's seed, before export (so glTF COLOR_0 and
/// POV-Ray per-vertex colours carry it).
/// @throws InternalError as above
void modulate_colours(ShadedMesh& mesh, const NprSettings& npr, double strength, uint64_t seed);

}  // namespace cutaway
