#include "export/vdb_export.h"

#include <cstdio>
#include <sstream>

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include "base/error.h"
#include "base/hash.h"

namespace cutaway {

namespace {

/// The header bytes that hold OpenVDB's UUID (36 ASCII characters): after the magic number
/// (8 bytes), the file format version (4), the library version (4 + 4) and the grid offsets
/// flag (1).
constexpr size_t kUuidOffset = 21, kUuidLength = 36;

/// A grid named `name` with `volume`'s transform, of value v(voxel index) wherever that is not
/// `background`.
template <typename GridT, typename ValueOf>
typename GridT::Ptr make_grid(const InteriorVolume& volume, const char* name,
                              typename GridT::ValueType background, ValueOf value_of) {
  typename GridT::Ptr grid = GridT::create(background);
  grid->setName(name);
  openvdb::math::Transform::Ptr transform =
      openvdb::math::Transform::createLinearTransform(volume.voxel_m);
  transform->postTranslate(openvdb::Vec3d(volume.origin.x, volume.origin.y, volume.origin.z));
  grid->setTransform(transform);
  auto accessor = grid->getAccessor();
  for (int k = 0; k < volume.size.z; ++k)
    for (int j = 0; j < volume.size.y; ++j)
      for (int i = 0; i < volume.size.x; ++i) {
        const typename GridT::ValueType v = value_of(volume.index(i, j, k));
        if (v != background) accessor.setValue(openvdb::Coord(i, j, k), v);
      }
  return grid;
}

}  // namespace

std::string encode_vdb(const InteriorVolume& volume, const std::string& name, int64_t seed) {
  openvdb::initialize();
  using openvdb::FloatGrid;
  openvdb::GridPtrVec grids;
  grids.push_back(make_grid<FloatGrid>(volume, "density", 0.0f, [&](size_t v) {
    return volume.region[v] == kEmptyRegion ? 0.0f : 1.0f;
  }));
  grids.push_back(
      make_grid<openvdb::Vec3SGrid>(volume, "color", openvdb::Vec3s(0.0f), [&](size_t v) {
        return openvdb::Vec3s(volume.colour[v].x, volume.colour[v].y, volume.colour[v].z);
      }));
  grids.push_back(make_grid<FloatGrid>(volume, "roughness", 0.0f,
                                       [&](size_t v) { return volume.material[v].x; }));
  grids.push_back(make_grid<FloatGrid>(volume, "translucency", 0.0f,
                                       [&](size_t v) { return volume.material[v].y; }));
  grids.push_back(make_grid<openvdb::Int32Grid>(volume, "region", 0, [&](size_t v) {
    return static_cast<int32_t>(volume.region[v]);
  }));
  grids.push_back(make_grid<FloatGrid>(volume, "sheet_distance", 0.0f, [&](size_t v) {
    return volume.region[v] == kEmptyRegion ? 0.0f : volume.sheet_distance[v];
  }));
  const float far = static_cast<float>(volume.voxel_m);
  grids.push_back(make_grid<FloatGrid>(volume, "outline_distance", far,
                                       [&](size_t v) { return volume.outline_distance[v]; }));
  openvdb::MetaMap meta;
  meta.insertMeta("template", openvdb::StringMetadata(name));
  meta.insertMeta("seed", openvdb::StringMetadata(seed >= 0 ? std::to_string(seed) : ""));
  meta.insertMeta("creator", openvdb::StringMetadata("cutaway"));
  std::ostringstream out(std::ios::binary);
  try {
    openvdb::io::Stream(out).write(grids, meta);
  } catch (const std::exception& e) {
    throw EnvironmentError(std::string("OpenVDB could not write the volume: ") + e.what());
  }
  std::string bytes = out.str();
  if (bytes.size() < kUuidOffset + kUuidLength || bytes[kUuidOffset + 8] != '-')
    throw InternalError("OpenVDB's header is not laid out as expected (no UUID at byte 21)");
  // The UUID from the content's hash: version-4 layout, the same bytes for the same volume.
  const std::string body = bytes.substr(kUuidOffset + kUuidLength);
  const std::string h = hex64(fnv1a64(body)) + hex64(fnv1a64(body + name));
  char uuid[kUuidLength + 1];
  std::snprintf(uuid, sizeof uuid, "%.8s-%.4s-4%.3s-8%.3s-%.12s", h.c_str(), h.c_str() + 8,
                h.c_str() + 12, h.c_str() + 15, h.c_str() + 18);
  bytes.replace(kUuidOffset, kUuidLength, uuid, kUuidLength);
  return bytes;
}

}  // namespace cutaway
