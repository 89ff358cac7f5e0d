// `mesh` surfaces (doc/template-format.md, Surfaces): the DS surface of a triangle mesh read
// from PLY (io/mesh_file.h), with its optional per-vertex DS attributes.
#pragma once

#include <cstddef>

#include <glm/vec3.hpp>

#include "model/ds_model.h"
#include "model/template.h"

namespace cutaway {

/// Axis-aligned bounds of a mesh's points, metres.
struct MeshBounds {
  glm::dvec3 min{0.0}, max{0.0};
};

/// The bounds of every point of `mesh` (those no triangle uses too), scaled to metres.
/// @param metres_per_unit  the template's unit scale
/// @pre mesh has at least one point
MeshBounds mesh_bounds(const MeshData& mesh, double metres_per_unit);

/// Builds the DS surface of a `mesh` surface: vertices scaled to metres; per-vertex colours
/// and blur from the file where present, else the surface's front, back and blur (gradients
/// are evaluated at parameter 0: imported meshes have no sweep parameters). A closed mesh
/// wound inwards is turned so that its normals point outwards (its front is its outside); an
/// open mesh keeps the file's winding. Vertices no triangle uses are left out. A skin must be
/// closed.
/// @param max_vertices the vertices left of the model's budget (kMaxModelVertices): a mesh
///        with more points is refused before any is added
/// @pre spec.mesh is set (parse_template reads every mesh file)
/// @throws InputError at the surface's `file` field when the mesh has more than max_vertices
///         points, a point that is not finite, is non-manifold (a complex edge or vertex, or
///         a face flipping orientation) or (skin) not closed
DsSurface mesh_surface(const SurfaceSpec& spec, const Template& tmpl,
                       size_t max_vertices = kMaxModelVertices);

}  // namespace cutaway
