// The camera and lights every picture of assets shares (scenes, piece views, batch thumbnails):
// a camera framing a box, and a studio's three lights and sky around it.
#pragma once

#include <glm/vec3.hpp>

#include "assets/scene_assets.h"

namespace cutaway {

/// A camera looking at the centre of the box lo..hi from direction `to_camera`, as close as
/// lets all eight corners of the box into the view (vertical field of view `fov_deg`, `aspect`
/// = width / height) with a 4 % margin.
AssetCamera frame_box(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& to_camera,
                      double fov_deg, double aspect);

/// Lights `assets` as every scene and asset view is lit, around `assets.camera` (set it first):
/// three directional lights, a key from above left of the camera (1639.2 lux, a sun of strength
/// 2.4 W/m^2 in Blender), a fill from the right (655.7 lux) and a rim light from behind (546.4
/// lux), and a uniform sky of 257.5 lux (`ambient_lux`: Blender world strength 0.12); the
/// key and rim are 12 degrees across (a softbox: soft-edged shadows), the fill 30. Indoor
/// studio levels chosen for pale flesh (doc/lighting.md): with exposure 1 / kLumensPerWatt
/// (Blender's Standard view; three.js's toneMappingExposure) a white face turned up shows
/// 0.98 under all of them together, and at its brightest turn 1.04, so flesh of albedo 0.9
/// stays below white.
void light_like_studio(SceneAssets& assets);

}  // namespace cutaway
