// Coarse caps: once a cut face's colour lives in a texture (cap_atlas.h), its geometry only has
// to follow its outline. This re-triangulates a cap part from its boundary alone.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "pieces/shaded_mesh.h"

namespace cutaway {

/// The constrained Delaunay triangulation (CGAL, exact predicates) of the outline of `cap`: the
/// edges used by one of its triangles, seen in the plane with in-plane axes u, v (unit,
/// cross(u, v) = the side the cap faces or its opposite). Only the regions inside an odd
/// number of outline loops are kept (holes stay holes), the triangles wound like the cap's,
/// over the cap's own vertex indices (interior vertices are no longer used; of several vertices
/// at one position, the copies a cut vertex has per colour side, the first). So a piece stays
/// closed with its coarse caps: the seams are the same edges.
/// Returns the cap's triangles unchanged when it has no outline or its outline crosses itself
/// in the plane (then coarsening would change the surface).
std::vector<glm::uvec3> coarse_cap_triangles(const ShadedMesh& cap, const glm::dvec3& u,
                                             const glm::dvec3& v);

}  // namespace cutaway
