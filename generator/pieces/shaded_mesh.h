// A plain indexed triangle mesh with per-vertex shading data: what pieces are made of.
#pragma once

#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/coloured_mesh.h"

namespace cutaway {

/// Plain data: all per-vertex arrays have the same length #V (param: #V or empty).
struct ShadedMesh : ColouredMesh {
  std::vector<glm::dvec2> material;  ///< #V, material channels (roughness, translucency) 0..1
  /// #V or empty: the sweep parameters (t_profile, t_section) of the DS surface a vertex lies
  /// on (ds_model.h), t_section cyclic (0 and 1 are one); (0, 0) off swept surfaces.
  std::vector<glm::dvec2> param;
};

/// Appends vertex i of `from` to `to`, returns its index in `to`.
unsigned copy_vertex(const ShadedMesh& from, unsigned i, ShadedMesh& to);

/// Appends the vertex (1 - t) * a + t * b of `mesh` (normal renormalised; t_section
/// interpolated the short way round its cycle) and returns its index.
unsigned add_interpolated_vertex(ShadedMesh& mesh, unsigned a, unsigned b, double t);

/// Drops vertices that no triangle uses, keeping the others' order.
void remove_unused_vertices(ShadedMesh& mesh);

/// Reverses every triangle's winding and negates the normals.
void flip(ShadedMesh& mesh);

/// The signed volume enclosed by the triangles (divergence theorem: sum of det(a, b, c) / 6);
/// positive for a closed surface wound counter-clockwise seen from outside. Cubic metres.
double signed_volume(const ShadedMesh& mesh);

}  // namespace cutaway
