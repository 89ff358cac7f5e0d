// An interior volume as flipbook textures: its z slices tiled in one PNG per channel group,
// with a JSON sidecar giving the grid, the object frame in metres and the tiling (the layout
// Unity and Unreal import as 3D / volume textures and three.js uploads as a Data3DTexture;
// doc/interior-volume.md).
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "base/outcome.h"
#include "volume/interior_volume.h"

namespace cutaway {

/// How the slices lie in a flipbook: slice k (the voxels of z index k) is the tile in column
/// k % columns and row k / columns, from the top left; within a tile, pixel column i is x
/// index i and pixel row r is y index size.y - 1 - r (so each tile shows its slice upright,
/// +Y up, seen from +Z). Tiles left over in the last row are transparent black.
struct FlipbookTiling {
  int columns = 0, rows = 0;
};

/// The tiling of a grid of `size` voxels: the fewest rows for ceil(sqrt(size.z)) columns.
FlipbookTiling flipbook_tiling(const glm::ivec3& size);

/// The three flipbooks of a volume, as PNG bytes (8-bit RGBA, same tiling).
struct VolumeFlipbooks {
  /// RGB: the colour, sRGB; A: 255 where the voxel is solid, 0 where empty.
  std::string colour;
  /// R + 256 G: the region id (0: empty); B: the sheet distance, A: the outline distance,
  /// 255 = one voxel.
  std::string structure;
  /// R: roughness, G: translucency (linear, 0..1 as 0..255); B: 0; A: 255.
  std::string material;
};

/// The most regions a structure flipbook can number (two bytes).
inline constexpr uint32_t kMaxFlipbookRegions = 65535;

/// Encodes `volume` as flipbooks laid out by flipbook_tiling(volume.size); none, with the
/// reason, when the volume has more than kMaxFlipbookRegions regions.
Outcome<VolumeFlipbooks> encode_flipbooks(const InteriorVolume& volume);

/// The file names a volume's files get beside each other.
struct VolumeFileNames {
  std::string colour, structure, material;  ///< the flipbook PNGs
  std::string vdb;                          ///< the OpenVDB file, or empty when not written
};

/// The JSON sidecar of a volume (format in doc/interior-volume.md): the template and seed
/// it samples (seed < 0: the template itself), the grid in metres in the object frame, the
/// tiling, the files, what each channel holds and how to read it, and the counts.
nlohmann::ordered_json volume_sidecar(const InteriorVolume& volume, const std::string& name,
                                      int64_t seed, const VolumeFileNames& files);

}  // namespace cutaway
