// Physically based material properties in the field's terms (the glTF 2.0 metallic-roughness
// model and its KHR material extensions): what the skin of a fruit and its cut flesh look like
// beyond their colours; paper §6 suggests "assigning translucent material information to DSs in
// addition to colors". Templates write them (README, Templates: materials), exporters map them.
#pragma once

#include <string_view>

#include <glm/vec3.hpp>

namespace cutaway {

/// One material. Colours come from the diffusion surfaces (vertex colours); these are the
/// other channels. Every value but scatter_m is dimensionless; the default is today's plain look.
struct PbrMaterial {
  double roughness = 0.6;          ///< perceptual roughness 0..1 (glTF roughnessFactor)
  double translucency = 0;         ///< diffuse transmission weight 0..1, light through thin
                                   ///< flesh (KHR_materials_diffuse_transmission)
  double clearcoat = 0;            ///< weight 0..1 of a clear layer on top: wax on an apple,
                                   ///< the wet film on cut flesh (KHR_materials_clearcoat)
  double clearcoat_roughness = 0;  ///< perceptual roughness 0..1 of that layer
  glm::dvec3 sheen{0.0};           ///< sheen colour, linear RGB 0..1, the soft back-scatter of
                                   ///< fuzz (peach, kiwi); black: none (KHR_materials_sheen)
  double sheen_roughness = 0.3;    ///< 0..1
  /// How far red light travels under the surface before it leaves, metres (0: no translucency;
  /// green and blue less: subsurface_scatter.h). Not written in templates: the parser derives it
  /// from the translucency, the skin's size and the dark grains (subsurface_scatter_m).
  double scatter_m = 0;

  bool operator==(const PbrMaterial&) const = default;
};

/// The first field of `m` outside 0..1 ("roughness", "translucency", "clearcoat",
/// "clearcoat_roughness", "sheen_roughness", "sheen", "scatter_m": metres), or "" when every
/// value is in range.
inline std::string_view out_of_range_field(const PbrMaterial& m) {
  auto bad = [](double v) { return !(v >= 0 && v <= 1); };
  if (bad(m.roughness)) return "roughness";
  if (bad(m.translucency)) return "translucency";
  if (bad(m.clearcoat)) return "clearcoat";
  if (bad(m.clearcoat_roughness)) return "clearcoat_roughness";
  if (bad(m.sheen_roughness)) return "sheen_roughness";
  if (bad(m.sheen.r) || bad(m.sheen.g) || bad(m.sheen.b)) return "sheen";
  if (!(m.scatter_m >= 0 && m.scatter_m <= 1)) return "scatter_m";
  return "";
}

}  // namespace cutaway
