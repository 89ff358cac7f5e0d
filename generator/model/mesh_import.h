// `mesh` surfaces (doc/template-format.md, Surfaces): triangle meshes read from PLY with
// OpenMesh, with optional per-vertex DS attributes.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "base/error.h"
#include "model/ds_model.h"
#include "model/template.h"

namespace cutaway {

/// Most vertices a `mesh` surface's PLY file may declare: the model's whole budget
/// (kMaxModelVertices in ds_model.h; import_mesh_surface gets what the surfaces before it left).
inline constexpr size_t kMaxMeshVertices = kMaxModelVertices;
/// Most faces a `mesh` surface's PLY file may declare, and most triangles its polygons may make:
/// a closed triangle mesh has about twice as many faces as vertices.
inline constexpr size_t kMaxMeshFaces = 2 * kMaxMeshVertices;
/// Most corners one PLY face (a polygon, triangulated on import) may have.
inline constexpr size_t kMaxMeshFaceCorners = 256;
/// Largest PLY file a `mesh` surface may name, bytes (256 MiB: the largest mesh allowed, with
/// per-vertex colours, written as ASCII, is about half of that).
inline constexpr size_t kMaxMeshFileBytes = size_t{256} << 20;

/// What check_ply found in a PLY file that passed it.
struct PlyCheck {
  bool binary = false;     ///< binary_little_endian or binary_big_endian (else ascii)
  size_t header_end = 0;   ///< byte offset of the `end_header` line
  size_t vertices = 0;     ///< vertices declared (and present)
  size_t faces = 0;        ///< faces (polygons) declared (and present)
  size_t triangles = 0;    ///< triangles the faces make (a face of n corners makes n - 2)
};

/// The guard in front of OpenMesh's PLY reader, which trusts the header's counts (it reserves
/// memory for them before reading: a header claiming 1e9 vertices costs gigabytes) and silently
/// drops faces whose vertex indices are out of range. Checks, without allocating per declared
/// element, that `bytes` is a PLY file OpenMesh reads as its header says:
///  - the header: `ply`, `format ascii|binary_little_endian|binary_big_endian 1.0`, then
///    `comment`, `obj_info`, `element NAME COUNT` and `property TYPE NAME` /
///    `property list COUNT_TYPE TYPE NAME` lines up to `end_header` (within the first 64 KiB);
///    counts are whole numbers >= 0; the types are the PLY ones; one `vertex` element with x, y
///    and z (float or double) before one `face` element whose first property is the list
///    `vertex_indices` (or `vertex_index`) of integers; lists only in those two elements;
///  - the sizes: the elements up to `face` need at least (binary) their exact fixed sizes plus
///    each list's count and three indices per face, or (ascii) two bytes per number, and the
///    file must be that long; at most kMaxMeshVertices vertices and kMaxMeshFaces faces;
///  - the body, element by element up to the faces: every number parses as its type (ascii)
///    or is there (binary); every face has 3..kMaxMeshFaceCorners corners, each a vertex index
///    in 0..V-1 used once in the face; the faces make at most kMaxMeshFaces triangles.
/// Elements after `face` are not read (neither does OpenMesh). Faces and vertices in messages
/// are counted from 0, as PLY indices are.
/// @param bytes       the whole file
/// @param loc, field  where the template names the file (for errors)
/// @return the counts found
/// @throws InputError at `loc` naming `field` and the broken rule, e.g. "the PLY header declares
///         1000000000 vertices but the file has only 93766 bytes (they need at least ...)" or
///         "face 2553 has vertex index 99999999999, but the file has only 2612 vertices"
PlyCheck check_ply(std::string_view bytes, const FileLoc& loc, const std::string& field);

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
