// The grains of a model one by one: each connected component of a grain surface
// (SurfaceRole::Grain) is one grain, a seed or a pip that scatter_grains placed.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/vec3.hpp>

#include "model/ds_model.h"

namespace cutaway {

/// One grain: a connected component of a grain surface's mesh.
struct GrainComponent {
  size_t surface = 0;              ///< index into DsModel::surfaces
  std::vector<glm::dvec3> points;  ///< its vertices (#V, metres, object frame), in flood order
  glm::dvec3 centre{0.0};          ///< the centre of their axis-aligned bounding box
  glm::dvec3 farthest{0.0};        ///< the vertex farthest from `centre` (the first of equals)
  double radius = 0;               ///< the bounding sphere's about `centre` (to `farthest`), metres
};

/// Every grain of `model`'s grain surfaces, in surface order and, within a surface, in the
/// order of each component's lowest vertex index (a flood over vertex neighbours from it).
std::vector<GrainComponent> grain_components(const DsModel& model);

}  // namespace cutaway
