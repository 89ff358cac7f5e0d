// `mesh` surfaces (doc/template-format.md, Surfaces): triangle meshes read from PLY with
// OpenMesh, with optional per-vertex DS attributes.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "base/error.h"
#include "io/ply_guard.h"
#include "model/ds_model.h"
#include "model/template.h"

namespace cutaway {

/// Axis-aligned bounds of a mesh file's vertices, metres.
struct MeshBounds {
  glm::dvec3 min{0.0}, max{0.0};
};

/// Reads the PLY at `file` and returns its bounds in metres.
/// @param metres_per_unit  the template's unit scale
/// @param loc, field        where the template names the file (for errors)
/// @throws InputError when the file is missing, larger than kMaxMeshFileBytes, refused by
///         check_ply, not read by OpenMesh as its header declares, or has no triangles
MeshBounds read_mesh_bounds(const std::string& file, double metres_per_unit, const FileLoc& loc,
                            const std::string& field);

/// Builds the DS surface of a `mesh` surface: vertices scaled to metres; per-vertex colours
/// from the PLY properties front_red/green/blue and back_red/green/blue (uchar or other integer
/// sRGB 0..255, or float/double sRGB 0..1, each component by its own type; ASCII or binary) and
/// `blur` (template units) where present, else the surface's front, back
/// and blur (gradients are evaluated at parameter 0: imported meshes have no sweep parameters).
/// Polygons are triangulated. A closed mesh wound inwards is turned so that its normals point
/// outwards (its front is its outside); an open mesh keeps the file's winding. Vertices no face
/// uses are left out. A skin must be closed.
/// @param max_vertices the vertices left of the model's budget (kMaxModelVertices): a file
///        declaring more is refused after its header is checked, before its body is read
/// @throws InputError when the file is unreadable (as in read_mesh_bounds), non-manifold (a
///         complex edge or vertex, or a face flipping orientation), (skin) not closed, or
///         declares more than max_vertices vertices
DsSurface import_mesh_surface(const SurfaceSpec& spec, const Template& tmpl,
                              size_t max_vertices = kMaxModelVertices);

}  // namespace cutaway
