// An interior volume as OpenVDB grids, for Houdini and Blender (which imports .vdb files as
// volume objects and renders their "density" and "color" grids).
#pragma once

#include <string>

#include "volume/interior_volume.h"

namespace cutaway {

/// `volume` as the bytes of an OpenVDB file (OpenVDB's own writer, its stream form), sparse
/// (only voxels whose value is not the background 0 are stored), with the grids
/// - "density" (float): 1 where solid, absent (0) where empty;
/// - "color" (vec3s): the colour, linear RGB (the dilated colour of empty voxels beside solid
///   ones too, so that filtering at the skin does not darken);
/// - "roughness", "translucency" (float, 0..1);
/// - "region" (int32): the region id, absent (0) where empty;
/// - "sheet_distance" (float, metres);
/// - "outline_distance" (float, metres; stored within a voxel of the outline, one voxel
///   elsewhere);
/// each with the same transform, index (i, j, k) at the voxel's centre in metres of the object
/// frame (+Y up), and the file metadata "template", "seed" and "creator". OpenVDB puts a
/// random UUID in every file's header; here it is made of the content's hash instead, so the
/// same volume gives the same bytes.
/// @throws EnvironmentError when OpenVDB fails to write
std::string encode_vdb(const InteriorVolume& volume, const std::string& name, int64_t seed);

}  // namespace cutaway
