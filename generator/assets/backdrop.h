// The ground and backdrop a scene stands on in pictures: a photographer's paper sweep, a floor
// that curves up into a wall behind the food, so that a picture shows a table and its shadows
// instead of a void (doc/scene-format.md, Backdrop).
#pragma once

#include <optional>

#include <glm/vec3.hpp>

#include "assets/scene_assets.h"

namespace cutaway {

/// A sweep (an infinity cove) for the view of `camera` over the content box `lo`..`hi` (scene
/// frame: +Y up, metres, the content standing on y = 0):
/// - the floor is the plane y = 0 from behind the camera to the cove;
/// - the cove is a quarter circle of radius max(2 reach, 0.05 m) rising from the floor at
///   1.2 reach beyond the content's centre (reach: half the diagonal of the box's footprint, at
///   least 0.05 m) away from the camera, into a vertical wall;
/// - the wall rises high enough, and the whole sweep runs wide enough, that every ray of the
///   camera's view that misses the content meets the sweep: the frame's corner rays are
///   followed to the wall (a ray rising more steeply than 80 degrees is taken at 80).
/// "Away from the camera" is the view direction projected onto the floor, or -Z when the camera
/// looks straight down. Normals face the camera's side (up on the floor, toward the camera on
/// the wall, smooth through the cove); the colour is `colour` (linear RGB) at every vertex; no uv.
/// @pre check_camera(camera) holds; lo <= hi componentwise, all finite
/// @return the mesh named "backdrop" (a few dozen triangles), in the scene frame; nothing when
///         the camera's eye is at or below the floor (y <= 0), where the table would hide the
///         content
std::optional<AssetMesh> backdrop_sweep(const AssetCamera& camera, const glm::dvec3& lo,
                                        const glm::dvec3& hi, const glm::dvec3& colour);

/// The farthest distance (metres) from `camera.eye` to a vertex of `mesh`: the far clipping
/// distance that keeps all of it in view.
double farthest_vertex(const AssetCamera& camera, const AssetMesh& mesh);

}  // namespace cutaway
