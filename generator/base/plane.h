// The plane type every cutting stage shares (cut specs, cut segments, clipping, the command
// line's plane notation), kept apart from the algorithms so its users need no mesh library.
#pragma once

#include <glm/vec3.hpp>

namespace cutaway {

/// A cutting plane: the points x with dot(x - point, normal) = 0. Metres, object frame.
struct Plane {
  glm::dvec3 point{0.0};
  glm::dvec3 normal{0, 0, 1};  ///< unit length
};

}  // namespace cutaway
