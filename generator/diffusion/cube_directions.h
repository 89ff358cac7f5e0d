// The discretised sphere of directions of the PMVC colour diffusion, shared by every backend
// (doc/algorithms.md §2): the texel centres of a cube map and their exact solid angles.
#pragma once

#include <vector>

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace cutaway {

/// 6 * n * n directions, face-major (+X, -X, +Y, -Y, +Z, -Z), then rows, then columns.
struct CubeDirections {
  int n = 0;                         ///< texels per cube face edge
  std::vector<glm::vec3> direction;  ///< unit direction through each texel centre
  std::vector<double> solid_angle;   ///< exact solid angle of each texel, steradians
};

/// The directions and solid angles of an n x n per face cube map. The solid angle of the texel
/// [x0, x1] x [y0, y1] on a face at distance 1 is A(x0,y0) - A(x0,y1) - A(x1,y0) + A(x1,y1)
/// with A(x, y) = atan2(x y, sqrt(x^2 + y^2 + 1)); they sum to 4 pi.
/// @pre n >= 1
CubeDirections make_cube_directions(int n);

/// The rotation of the cube map at `point` (metres): a uniformly random rotation (Shoemake's
/// unit quaternion from three uniforms of a pcg32 stream) seeded by the bits of the point's
/// coordinates (-0 as +0), so the same point always gets the same rotation whatever the thread
/// count or batch. Turning every point's cube differently keeps the texel grid from lining up
/// with an object's symmetry, where the errors of the texels would add up instead of
/// cancelling. A ray goes along R d for each
/// cube direction d.
glm::dmat3 cube_rotation(const glm::dvec3& point);

}  // namespace cutaway
