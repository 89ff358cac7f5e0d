// The PLY file of a `mesh` surface (doc/template-format.md, Surfaces), read with OpenMesh behind
// the PLY guard (ply_guard.h) into plain data (MeshData); model/mesh_surface.h makes the DS
// surface of it.
#pragma once

#include <string>

#include "base/error.h"
#include "model/template.h"

namespace cutaway {

/// Reads the PLY at `file`: its points, triangles (polygons are triangulated), whether it is
/// closed and its signed volume, and the optional per-vertex properties front_red/green/blue,
/// back_red/green/blue (uchar or other integer sRGB 0..255, or float/double sRGB 0..1, each
/// component by its own type; ASCII or binary; stored linear) and `blur` (template units).
/// @param loc, field  where the template names the file (for errors)
/// @throws InputError when the file is not a .ply path, missing, larger than
///         kMaxMeshFileBytes, refused by check_ply (more than kMaxMeshVertices vertices
///         included), not read by OpenMesh as its header declares (a complex edge or vertex,
///         or a face flipping orientation), or has no triangles
MeshData read_mesh_file(const std::string& file, const FileLoc& loc, const std::string& field);

}  // namespace cutaway
