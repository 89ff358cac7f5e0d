// An interior volume's files: the flipbook PNGs laid out as their sidecar says, and the
// OpenVDB grids at the voxel centres in metres (export/volume_flipbook.h, export/vdb_export.h).
#include <gtest/gtest.h>

#include <sstream>

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include "base/colour.h"
#include "export/vdb_export.h"
#include "export/volume_flipbook.h"
#include "render/image/image.h"

namespace cutaway {
namespace {

/// A 3 x 2 x 5 volume whose every voxel differs: region, colour, material and distance are
/// functions of (i, j, k); voxel (0, 0, 0) is empty.
InteriorVolume numbered_volume() {
  InteriorVolume v;
  v.size = {3, 2, 5};
  v.voxel_m = 0.002;
  v.origin = {-0.01, 0.005, 0.02};
  const size_t n = v.voxels();
  v.colour.resize(n);
  v.material.resize(n);
  v.region.resize(n);
  v.sheet_distance.resize(n);
  v.outline_distance.resize(n);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) {
        const size_t at = v.index(i, j, k);
        v.region[at] = at == 0 ? 0 : static_cast<uint32_t>(300 * i + 20 * j + k);
        v.colour[at] = glm::vec3(0.1f * i, 0.2f * j, 0.05f * k);
        v.material[at] = glm::vec2(0.1f * k, 0.3f * j);
        v.sheet_distance[at] = static_cast<float>(v.voxel_m * (i + 1) / 4.0);
        v.outline_distance[at] = static_cast<float>(v.voxel_m * (k + 1) / 5.0);
      }
  v.regions = 300 * 2 + 20 + 4;
  v.solid = n - 1;
  return v;
}

TEST(InteriorVolumeFlipbook, TilesSlicesAsTheSidecarSays) {
  const InteriorVolume v = numbered_volume();
  const Outcome<VolumeFlipbooks> encoded = encode_flipbooks(v);
  ASSERT_TRUE(encoded);
  const Image colour = decode_png(encoded->colour);
  const Image structure = decode_png(encoded->structure);
  const Image material = decode_png(encoded->material);
  const nlohmann::ordered_json sidecar =
      volume_sidecar(v, "numbered", 7, {"n.colour.png", "n.structure.png", "n.material.png", ""});
  const int columns = sidecar["tiling"]["columns"], rows = sidecar["tiling"]["rows"];
  EXPECT_EQ(columns, 3);  // ceil(sqrt(5)) columns, then as few rows as hold 5 slices
  EXPECT_EQ(rows, 2);
  EXPECT_EQ(colour.width, columns * 3);
  EXPECT_EQ(colour.height, rows * 2);
  EXPECT_EQ(structure.width, colour.width);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) {
        const size_t at = v.index(i, j, k);
        // The sidecar's layout: tile (k % columns, k / columns), row tile_height - 1 - j.
        const int x = k % columns * 3 + i, y = k / columns * 2 + (2 - 1 - j);
        const size_t px = 4 * (static_cast<size_t>(y) * colour.width + x);
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(colour.rgba[px + c], linear_to_srgb8(v.colour[at][c]));
        EXPECT_EQ(colour.rgba[px + 3], at == 0 ? 0 : 255);
        EXPECT_EQ(structure.rgba[px] + 256 * structure.rgba[px + 1], v.region[at]);
        EXPECT_EQ(structure.rgba[px + 2], std::lround(255.0 * (i + 1) / 4.0));
        EXPECT_EQ(structure.rgba[px + 3], std::lround(255.0 * (k + 1) / 5.0));
        EXPECT_EQ(material.rgba[px], std::lround(255.0 * 0.1 * k));
        EXPECT_EQ(material.rgba[px + 1], std::lround(255.0 * 0.3 * j));
      }
  // The tile left over in the last row is transparent black.
  const size_t spare = 4 * (static_cast<size_t>(2) * colour.width + 2 * 3);
  EXPECT_EQ(colour.rgba[spare + 3], 0);
  // The frame: voxel (0, 0, 0)'s centre, the voxel, and the box the voxels fill, in metres.
  EXPECT_EQ(sidecar["grid"]["size"], nlohmann::json::array({3, 2, 5}));
  EXPECT_DOUBLE_EQ(sidecar["grid"]["voxel_m"].get<double>(), 0.002);
  EXPECT_DOUBLE_EQ(sidecar["grid"]["first_centre_m"][1].get<double>(), 0.005);
  EXPECT_DOUBLE_EQ(sidecar["grid"]["bounds_m"]["min"][0].get<double>(), -0.011);
  EXPECT_NEAR(sidecar["grid"]["bounds_m"]["max"][2].get<double>(), 0.02 - 0.001 + 0.01, 1e-15);
  EXPECT_EQ(sidecar["images"]["structure"], "n.structure.png");
  EXPECT_EQ(sidecar["seed"], 7);
  EXPECT_EQ(sidecar["regions"], v.regions);
  EXPECT_FALSE(sidecar.contains("vdb"));  // none written
}

TEST(InteriorVolumeFlipbook, RefusesMoreRegionsThanTwoBytesNumber) {
  InteriorVolume v = numbered_volume();
  v.regions = kMaxFlipbookRegions + 1;
  const Outcome<VolumeFlipbooks> encoded = encode_flipbooks(v);
  ASSERT_FALSE(encoded);
  EXPECT_NE(encoded.reason().find("65535"), std::string::npos) << encoded.reason();
}

TEST(InteriorVolumeFlipbook, TilingHoldsEverySliceInANearlySquareSheet) {
  for (int slices : {1, 2, 4, 5, 9, 10, 99, 100, 101}) {
    const FlipbookTiling t = flipbook_tiling({7, 7, slices});
    EXPECT_GE(t.columns * t.rows, slices);
    EXPECT_LT(t.columns * (t.rows - 1), slices);  // no empty row
    EXPECT_LE(t.rows, t.columns);
  }
}

TEST(InteriorVolumeVdb, GridsHoldTheVolumeAtTheVoxelCentresInMetres) {
  const InteriorVolume v = numbered_volume();
  const std::string bytes = encode_vdb(v, "numbered", 7);
  openvdb::initialize();
  std::istringstream in(bytes, std::ios::binary);
  openvdb::io::Stream stream(in);
  const openvdb::GridPtrVecPtr grids = stream.getGrids();
  std::map<std::string, openvdb::GridBase::Ptr> by_name;
  for (const auto& g : *grids) by_name[g->getName()] = g;
  for (const char* name : {"density", "color", "roughness", "translucency", "region",
                           "sheet_distance", "outline_distance"})
    ASSERT_TRUE(by_name.count(name)) << name;
  EXPECT_EQ(stream.getMetadata()->metaValue<std::string>("template"), "numbered");
  EXPECT_EQ(stream.getMetadata()->metaValue<std::string>("seed"), "7");
  const auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(by_name["density"]);
  const auto color = openvdb::gridPtrCast<openvdb::Vec3SGrid>(by_name["color"]);
  const auto region = openvdb::gridPtrCast<openvdb::Int32Grid>(by_name["region"]);
  const auto rough = openvdb::gridPtrCast<openvdb::FloatGrid>(by_name["roughness"]);
  ASSERT_TRUE(density && color && region && rough);
  for (int k = 0; k < 5; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) {
        const size_t at = v.index(i, j, k);
        const openvdb::Coord ijk(i, j, k);
        const openvdb::Vec3d world = density->transform().indexToWorld(ijk);
        const glm::dvec3 centre = v.centre(i, j, k);
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(world[a], centre[a], 1e-12);
        EXPECT_EQ(density->tree().getValue(ijk), at == 0 ? 0.0f : 1.0f);
        EXPECT_EQ(region->tree().getValue(ijk), static_cast<int32_t>(v.region[at]));
        EXPECT_EQ(color->tree().getValue(ijk),
                  openvdb::Vec3s(v.colour[at].x, v.colour[at].y, v.colour[at].z));
        EXPECT_EQ(rough->tree().getValue(ijk), v.material[at].x);
      }
}

TEST(InteriorVolumeVdb, TheSameVolumeGivesTheSameBytes) {
  const InteriorVolume v = numbered_volume();
  const std::string a = encode_vdb(v, "numbered", 7), b = encode_vdb(v, "numbered", 7);
  EXPECT_EQ(a, b);  // OpenVDB's random UUID replaced by one from the content
  InteriorVolume w = v;
  w.colour[5].x += 0.5f;
  EXPECT_NE(encode_vdb(w, "numbered", 7).substr(21, 36), a.substr(21, 36));
}

}  // namespace
}  // namespace cutaway
