// Skin patterns (doc/template-format.md, Skin patterns): stripes along the profile (a
// watermelon's, a zucchini's), speckles (a pear's lenticels, a banana's ripening spots) and a
// net (a cantaloupe's netting: the walls of a 3D Voronoi diagram, after Worley 1996) and spots
// where grains sit under the skin (a strawberry's achenes)
// laid over the skin's outside colour, baked into the skin texture per texel (and into vertex
// colours when cut faces are not textured), and their relief (an orange's pores, the netting's
// ridges), baked into the skin's normal map. They are the skin's surface only: the colour that
// diffuses into the volume is the skin's back, which they leave alone.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/point_grid.h"
#include "material/perlin_noise.h"
#include "model/ds_model.h"
#include "model/template.h"

namespace cutaway {

/// The pattern layers of one object, seeded (stripes turn and wobble, speckles move, per seed).
class SkinPatterns {
 public:
  /// @param layers the template's skin_patterns (copied)
  /// @param seed   identifies the object, e.g. its Perlin modulation seed
  /// @param model  the object's DS model, whose grain surfaces' sites (DsSurface::grain_sites)
  ///               the grains layers spot; null, or a set it lacks: those layers cover nothing
  SkinPatterns(const std::vector<SkinPatternLayer>& layers, uint64_t seed,
               const DsModel* model = nullptr);

  bool empty() const { return layers_.empty(); }

  /// The skin colour with every layer laid over it in order: c = mix(c, layer colour, opacity *
  /// coverage), in linear RGB.
  /// @param param    (t_profile, t_section) of the point on the skin, each 0..1 (the skin
  ///                 texture's v flipped and u; the sweep parameters of a skin vertex)
  /// @param position the point in the object frame, metres (speckles are placed in space, so
  ///                 every piece of the object agrees)
  /// @param colour   the skin's front colour there, linear RGB
  glm::dvec3 operator()(const glm::dvec2& param, const glm::dvec3& position,
                        const glm::dvec3& colour) const;

  /// Whether any layer has a relief (SkinPatternLayer::relief_m), so the skin gets a normal map.
  bool has_relief() const;

  /// What the layers make of the point: the colour operator() gives, and the skin's relief
  /// there, the sum over the layers of relief_m * coverage, metres above (> 0) or below (< 0)
  /// the swept skin; each layer's coverage evaluated once for both. Arguments as for
  /// operator().
  struct Shade {
    glm::dvec3 colour{0.0};
    double height = 0;
  };
  Shade shade(const glm::dvec2& param, const glm::dvec3& position, const glm::dvec3& colour) const;

  /// How much of layer `k` covers the point, 0..1 (before its opacity).
  double coverage(size_t k, const glm::dvec2& param, const glm::dvec3& position) const;

 private:
  struct Layer {
    SkinPatternLayer spec;
    PerlinNoise noise;              ///< stripes: the wobble
    double phase = 0;               ///< stripes: turn, in periods
    uint64_t cells = 0;             ///< speckles, net: the seed of the lattice's points
    std::vector<glm::dvec3> sites;  ///< grains: the grains' sites on the skin, metres
    PointGrid near{1.0, {}};        ///< grains: the sites in cubes of the spot radius
  };
  std::vector<Layer> layers_;
};

}  // namespace cutaway
