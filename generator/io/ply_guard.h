// The guard in front of OpenMesh's PLY reader (`mesh` surfaces' files, doc/template-format.md):
// input checking of the file's bytes, header and body, before any mesh is built from them.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

#include "base/error.h"

namespace cutaway {

/// Most vertices a `mesh` surface's PLY file may declare: the DS model's whole budget
/// (kMaxModelVertices in model/ds_model.h, checked equal in io/mesh_file.cpp; mesh_surface gets
/// what the surfaces before it left).
inline constexpr size_t kMaxMeshVertices = 1'000'000;
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
  bool binary = false;    ///< binary_little_endian or binary_big_endian (else ascii)
  size_t header_end = 0;  ///< byte offset of the `end_header` line
  size_t vertices = 0;    ///< vertices declared (and present)
  size_t faces = 0;       ///< faces (polygons) declared (and present)
  size_t triangles = 0;   ///< triangles the faces make (a face of n corners makes n - 2)
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

/// The bytes of a PLY file that passed check_ply, ready for OpenMesh 9's reader. Its ASCII
/// reader reads a custom 8-bit property (char, uchar, int8, uint8) as one character instead of
/// a number, which corrupts that value and everything after it (binary files are read
/// correctly). In an ASCII file such a property's text is also a valid `int`, so its
/// declaration is widened to `int`; colours stored as integers are 0..255 either way. Other
/// bytes are unchanged.
/// @param binary, header_end  as check_ply found them (PlyCheck)
std::string prepare_ply(std::string ply, bool binary, size_t header_end);

}  // namespace cutaway
