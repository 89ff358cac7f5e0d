#include "export/volume_flipbook.h"

#include <algorithm>
#include <cmath>

#include "assets/scene_assets.h"
#include "base/colour.h"
#include "base/error.h"
#include "export/texture_image.h"

namespace cutaway {

namespace {

/// An RGBA texture of the flipbook's size, every byte 0.
AssetTexture blank_flipbook(const InteriorVolume& volume, const FlipbookTiling& tiling) {
  AssetTexture texture;
  texture.width = tiling.columns * volume.size.x;
  texture.height = tiling.rows * volume.size.y;
  texture.channels = 4;
  texture.pixels.assign(static_cast<size_t>(texture.width) * texture.height * 4, 0);
  return texture;
}

uint8_t unit_byte(double v) {
  return static_cast<uint8_t>(std::lround(std::clamp(v, 0.0, 1.0) * 255.0));
}

/// The stones as the sidecar lists them: points in whole micrometres, triangles, and 8-bit
/// sRGB colours, each a flat array.
nlohmann::ordered_json stones_json(const std::vector<VolumeStone>& stones) {
  nlohmann::ordered_json out = nlohmann::ordered_json::array();
  for (const VolumeStone& stone : stones) {
    nlohmann::ordered_json points = nlohmann::ordered_json::array(),
                           triangles = nlohmann::ordered_json::array(),
                           own = nlohmann::ordered_json::array(),
                           flesh = nlohmann::ordered_json::array();
    for (const glm::dvec3& p : stone.points)
      for (int a = 0; a < 3; ++a) points.push_back(std::llround(p[a] * 1e6));
    for (const glm::uvec3& t : stone.triangles)
      for (int a = 0; a < 3; ++a) triangles.push_back(t[a]);
    for (size_t v = 0; v < stone.points.size(); ++v) {
      for (int a = 0; a < 3; ++a) {
        own.push_back(linear_to_srgb8(stone.stone[v][a]));
        flesh.push_back(linear_to_srgb8(stone.flesh[v][a]));
      }
    }
    out.push_back({{"surface", stone.surface},
                   {"points_um", std::move(points)},
                   {"triangles", std::move(triangles)},
                   {"stone_srgb", std::move(own)},
                   {"flesh_srgb", std::move(flesh)}});
  }
  return out;
}

}  // namespace

FlipbookTiling flipbook_tiling(const glm::ivec3& size) {
  FlipbookTiling tiling;
  tiling.columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(size.z))));
  while (tiling.columns * tiling.columns < size.z) ++tiling.columns;  // sqrt's rounding
  tiling.rows = (size.z + tiling.columns - 1) / tiling.columns;
  return tiling;
}

Outcome<VolumeFlipbooks> encode_flipbooks(const InteriorVolume& volume) {
  if (volume.regions > kMaxFlipbookRegions)
    return Outcome<VolumeFlipbooks>::none(
        "the volume has " + std::to_string(volume.regions) + " regions, more than the " +
        std::to_string(kMaxFlipbookRegions) + " a structure flipbook numbers");
  const FlipbookTiling tiling = flipbook_tiling(volume.size);
  AssetTexture colour = blank_flipbook(volume, tiling);
  AssetTexture structure = colour, material = colour;
  for (int k = 0; k < volume.size.z; ++k) {
    const int x0 = k % tiling.columns * volume.size.x, y0 = k / tiling.columns * volume.size.y;
    for (int j = 0; j < volume.size.y; ++j) {
      for (int i = 0; i < volume.size.x; ++i) {
        const size_t v = volume.index(i, j, k);
        const size_t px =
            4 * (static_cast<size_t>(y0 + volume.size.y - 1 - j) * colour.width + x0 + i);
        const uint32_t region = volume.region[v];
        for (int c = 0; c < 3; ++c) colour.pixels[px + c] = linear_to_srgb8(volume.colour[v][c]);
        colour.pixels[px + 3] = region == kEmptyRegion ? 0 : 255;
        structure.pixels[px + 0] = static_cast<uint8_t>(region & 0xffu);
        structure.pixels[px + 1] = static_cast<uint8_t>(region >> 8);
        structure.pixels[px + 2] = unit_byte(volume.sheet_distance[v] / volume.voxel_m);
        structure.pixels[px + 3] = unit_byte(volume.outline_distance[v] / volume.voxel_m);
        material.pixels[px + 0] = unit_byte(volume.material[v].x);
        material.pixels[px + 1] = unit_byte(volume.material[v].y);
        material.pixels[px + 3] = 255;
      }
    }
  }
  return VolumeFlipbooks{encode_texture(colour, TextureFormat::Png),
                         encode_texture(structure, TextureFormat::Png),
                         encode_texture(material, TextureFormat::Png)};
}

nlohmann::ordered_json volume_sidecar(const InteriorVolume& volume, const std::string& name,
                                      int64_t seed, const VolumeFileNames& files) {
  const FlipbookTiling tiling = flipbook_tiling(volume.size);
  const glm::dvec3 lo = volume.origin - 0.5 * volume.voxel_m;
  const glm::dvec3 hi = lo + volume.voxel_m * glm::dvec3(volume.size);
  auto vec = [](const glm::dvec3& v) { return nlohmann::ordered_json::array({v.x, v.y, v.z}); };
  nlohmann::ordered_json images = {
      {"colour", files.colour}, {"structure", files.structure}, {"material", files.material}};
  nlohmann::ordered_json sidecar = {
      {"asset", "cutaway interior volume"},
      {"version", 1},
      {"template", name},
      {"seed", seed >= 0 ? nlohmann::ordered_json(seed) : nlohmann::ordered_json(nullptr)},
      {"frame", "object frame of the template's model and of the whole-object glTF: metres, +Y up"},
      {"grid",
       {{"size", {volume.size.x, volume.size.y, volume.size.z}},
        {"voxel_m", volume.voxel_m},
        {"first_centre_m", vec(volume.origin)},
        {"bounds_m", {{"min", vec(lo)}, {"max", vec(hi)}}}}},
      {"tiling",
       {{"columns", tiling.columns},
        {"rows", tiling.rows},
        {"tile_width", volume.size.x},
        {"tile_height", volume.size.y},
        {"slices", volume.size.z},
        {"layout",
         "slice k holds z index k and is the tile at column k % columns, row k / columns from "
         "the top left; in a tile, pixel column i is x index i and pixel row r is y index "
         "tile_height - 1 - r"}}},
      {"images", images},
      {"channels",
       {{"colour", "RGB: diffused colour, sRGB; A: 255 solid, 0 empty (outside or a cavity)"},
        {"structure",
         "R + 256 G: region id, 0 empty; B: distance from the voxel centre to the nearest "
         "sheet bounding its region, A: to the outline (solid against empty), 255 = one "
         "voxel"},
        {"material", "R: roughness, G: translucency, linear 0..1; B: 0; A: 255"}}},
      {"reading",
       "of the 8 voxels around a point with trilinear weights w: empty (draw nothing) unless "
       "sum w * (A if solid, else -A) > 0; then per solid region r among them, score = sum w * "
       "(B if the voxel is in r, else -B); take the region with the highest score (ties: the "
       "lower id) and the trilinear blend of that region's voxels only"},
      {"regions", volume.regions},
      {"solid_voxels", volume.solid}};
  if (!files.vdb.empty()) sidecar["vdb"] = files.vdb;
  if (!volume.stones.empty()) sidecar["stones"] = stones_json(volume.stones);
  return sidecar;
}

}  // namespace cutaway
