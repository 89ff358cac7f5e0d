#include "export/gltf_buffers.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include <glm/common.hpp>
#include <meshoptimizer.h>

#include "base/hash.h"

namespace cutaway::gltf {

int add_view(tinygltf::Model& m, const void* data, size_t bytes, int target) {
  auto& buf = m.buffers[0].data;
  while (buf.size() % 4) buf.push_back(0);
  tinygltf::BufferView view;
  view.buffer = 0;
  view.byteOffset = buf.size();
  view.byteLength = bytes;
  view.target = target;
  const auto* p = static_cast<const unsigned char*>(data);
  buf.insert(buf.end(), p, p + bytes);
  m.bufferViews.push_back(view);
  return static_cast<int>(m.bufferViews.size()) - 1;
}

int add_vec3_accessor(tinygltf::Model& m, const std::vector<float>& xyz, bool with_bounds) {
  tinygltf::Accessor a;
  a.bufferView = add_view(m, xyz.data(), xyz.size() * sizeof(float), TINYGLTF_TARGET_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_FLOAT;
  a.type = TINYGLTF_TYPE_VEC3;
  a.count = xyz.size() / 3;
  if (with_bounds) {
    a.minValues = {xyz[0], xyz[1], xyz[2]};
    a.maxValues = a.minValues;
    for (size_t i = 0; i < xyz.size(); ++i) {
      a.minValues[i % 3] = std::min<double>(a.minValues[i % 3], xyz[i]);
      a.maxValues[i % 3] = std::max<double>(a.maxValues[i % 3], xyz[i]);
    }
  }
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

int add_index_accessor(tinygltf::Model& m, const std::vector<uint32_t>& idx) {
  tinygltf::Accessor a;
  a.bufferView =
      add_view(m, idx.data(), idx.size() * sizeof(uint32_t), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
  a.componentType = TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  a.type = TINYGLTF_TYPE_SCALAR;
  a.count = idx.size();
  m.accessors.push_back(a);
  return static_cast<int>(m.accessors.size()) - 1;
}

MeshoptGrid meshopt_grid(const std::vector<const AssetMesh*>& meshes,
                         const std::vector<AssetTexture>& textures) {
  MeshoptGrid grid;
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  glm::dvec2 uv_lo(INFINITY), uv_hi(-INFINITY);
  for (const AssetMesh* mesh : meshes) {
    for (const glm::dvec3& p : mesh->position) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    for (const glm::dvec2& uv : mesh->uv) {
      uv_lo = glm::min(uv_lo, uv);
      uv_hi = glm::max(uv_hi, uv);
    }
  }
  const glm::dvec3 side = hi - lo;
  const double extent = std::max({side.x, side.y, side.z});
  if (extent > 0 && std::isfinite(extent)) grid.position_step = extent / 16383;
  int texels = 0;
  for (const AssetTexture& t : textures) texels = std::max({texels, t.width, t.height});
  if (texels > 0 && std::isfinite(uv_lo.x) && std::isfinite(uv_lo.y)) {
    grid.uv_steps = 2.0 * texels;
    grid.uv_origin = glm::floor(uv_lo);
    const glm::dvec2 span = (uv_hi - grid.uv_origin) * grid.uv_steps;
    if (!(span.x <= 65535 && span.y <= 65535)) grid = {grid.position_step, 0, glm::dvec2(0.0)};
  }
  return grid;
}

namespace {

/// The box (lo, hi) that holds #V x 3 `xyz`.
std::pair<glm::dvec3, glm::dvec3> bounds(const std::vector<float>& xyz) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (size_t i = 0; i + 2 < xyz.size(); i += 3) {
    const glm::dvec3 p(xyz[i], xyz[i + 1], xyz[i + 2]);
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  return {lo, hi};
}

}  // namespace

int SceneBuffers::positions(const std::vector<float>& xyz, const std::vector<float>& extent_of,
                            MeshFrame& frame, const glm::dvec3* pivot) {
  if (pivot) return positions_about(xyz, extent_of, *pivot, frame);
  const size_t count = xyz.size() / 3;
  if (compression_ == GltfCompression::None) {
    const auto [lo, hi] = bounds(xyz);
    frame = {};
    return accessor(xyz.data(), count, 12, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, false,
                    {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
  }
  const auto [lo, hi] = bounds(extent_of);
  if (compression_ == GltfCompression::Meshopt) return grid_positions(xyz, lo, hi, frame);
  frame.offset = (lo + hi) * 0.5;
  const glm::dvec3 half = (hi - lo) * 0.5;
  frame.scale = std::max({half.x, half.y, half.z});
  return quantized_positions(xyz, frame);
}

int SceneBuffers::grid_positions(const std::vector<float>& xyz, const glm::dvec3& lo,
                                 const glm::dvec3& hi, MeshFrame& frame) {
  const size_t count = xyz.size() / 3;
  const double side = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  frame.offset = lo;
  frame.scale = grid_.position_step > 0 ? grid_.position_step : side > 0 ? side / 16383 : 1.0;
  std::vector<uint16_t> q(count * 4, 0);
  std::vector<double> qlo(3, 65535), qhi(3, 0);
  for (size_t i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k) {
      const double v = (xyz[3 * i + k] - frame.offset[k]) / frame.scale;
      q[4 * i + k] = static_cast<uint16_t>(std::clamp<long>(std::lround(v), 0, 65535));
      qlo[k] = std::min<double>(qlo[k], q[4 * i + k]);
      qhi[k] = std::max<double>(qhi[k], q[4 * i + k]);
    }
  return accessor(q.data(), count, 8, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC3,
                  false, qlo, qhi);
}

int SceneBuffers::positions_about(const std::vector<float>& xyz,
                                  const std::vector<float>& extent_of, const glm::dvec3& pivot,
                                  MeshFrame& frame) {
  const size_t count = xyz.size() / 3;
  frame.offset = pivot;
  if (compression_ == GltfCompression::None) {
    frame.scale = 1.0;
    std::vector<float> moved(xyz.size());
    for (size_t i = 0; i < xyz.size(); ++i) moved[i] = static_cast<float>(xyz[i] - pivot[i % 3]);
    const auto [lo, hi] = bounds(moved);
    return accessor(moved.data(), count, 12, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                    false, {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
  }
  frame.scale = 0;
  for (size_t i = 0; i < extent_of.size(); ++i)
    frame.scale = std::max(frame.scale, std::fabs(extent_of[i] - pivot[i % 3]));
  return quantized_positions(xyz, frame);
}

int SceneBuffers::quantized_positions(const std::vector<float>& xyz, MeshFrame& frame) {
  const size_t count = xyz.size() / 3;
  if (!(frame.scale > 0)) frame.scale = 1.0;
  // Steps over each half extent: 16 bits; with meshopt, the scene grid's steps (or 14 bits
  // without one), whose smaller integers the codec stores in fewer bytes. The node's scale
  // then stretches the integers read as normalized SHORT (q / 32767) back to the extent.
  double steps = 32767;
  if (compression_ == GltfCompression::Meshopt)
    steps = grid_.position_step > 0 ? std::clamp(frame.scale / grid_.position_step, 1.0, 32767.0)
                                    : 8191;
  std::vector<int16_t> q(count * 4, 0);
  std::vector<double> qlo(3, steps), qhi(3, -steps);
  for (size_t i = 0; i < count; ++i)
    for (int k = 0; k < 3; ++k) {
      const double v = (xyz[3 * i + k] - frame.offset[k]) / frame.scale;
      q[4 * i + k] = static_cast<int16_t>(std::lround(std::clamp(v, -1.0, 1.0) * steps));
      qlo[k] = std::min<double>(qlo[k], q[4 * i + k]);
      qhi[k] = std::max<double>(qhi[k], q[4 * i + k]);
    }
  frame.scale *= 32767 / steps;
  return accessor(q.data(), count, 8, TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, true, qlo,
                  qhi);
}

int SceneBuffers::normals(const std::vector<float>& xyz) {
  if (compression_ != GltfCompression::Meshopt)
    return vec3(xyz, std::vector<int8_t>{}, TINYGLTF_COMPONENT_TYPE_BYTE, -1.f);
  const size_t count = xyz.size() / 3;
  std::vector<float> xyzw(count * 4, 0.f);
  for (size_t i = 0; i < 3 * count; ++i) xyzw[i / 3 * 4 + i % 3] = xyz[i];
  std::vector<int8_t> q(count * 4);
  meshopt_encodeFilterOct(q.data(), count, 4, 8, xyzw.data());
  return accessor(q.data(), count, 4, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC3, true, {},
                  {}, "OCTAHEDRAL");
}

int SceneBuffers::tangents(const std::vector<float>& xyzw) {
  const size_t count = xyzw.size() / 4;
  if (compression_ == GltfCompression::None)
    return accessor(xyzw.data(), count, 16, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4,
                    false);
  std::vector<int8_t> q(xyzw.size());
  if (compression_ == GltfCompression::Meshopt) {
    meshopt_encodeFilterOct(q.data(), count, 4, 8, xyzw.data());
    return accessor(q.data(), count, 4, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC4, true, {},
                    {}, "OCTAHEDRAL");
  }
  for (size_t i = 0; i < xyzw.size(); ++i)
    q[i] = static_cast<int8_t>(std::lround(std::clamp(xyzw[i], -1.f, 1.f) * 127.f));
  return accessor(q.data(), count, 4, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC4, true);
}

int SceneBuffers::colours(const std::vector<float>& rgb) {
  return vec3(rgb, std::vector<uint16_t>{}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 0.f);
}

int SceneBuffers::uvs(const std::vector<float>& xy) {
  const size_t count = xy.size() / 2;
  if (uvs_on_grid()) {  // steps from the origin, which uv_transform() maps back
    std::vector<uint16_t> q(xy.size());
    for (size_t i = 0; i < xy.size(); ++i)
      q[i] = static_cast<uint16_t>(std::clamp<long>(
          std::lround((xy[i] - grid_.uv_origin[i % 2]) * grid_.uv_steps), 0, 65535));
    return accessor(q.data(), count, 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2,
                    true);
  }
  const bool unit = std::all_of(xy.begin(), xy.end(), [](float v) { return v >= 0 && v <= 1; });
  if (compression_ == GltfCompression::None || !unit)
    return accessor(xy.data(), count, 8, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2, false);
  std::vector<uint16_t> q(xy.size());
  for (size_t i = 0; i < xy.size(); ++i) q[i] = static_cast<uint16_t>(std::lround(xy[i] * 65535.0));
  return accessor(q.data(), count, 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2,
                  true);
}

int SceneBuffers::indices(const std::vector<uint32_t>& idx, size_t vertices) {
  const bool narrow = vertices <= 65535;
  const size_t size = narrow ? 2 : 4;
  const bool meshopt = compression_ == GltfCompression::Meshopt;
  // The values as they are kept until written: meshopt holds uint32 back for its codec, a
  // plain view holds them at their size.
  const std::vector<uint16_t> shorts =
      narrow && !meshopt ? std::vector<uint16_t>(idx.begin(), idx.end()) : std::vector<uint16_t>{};
  const std::span<const unsigned char> bytes =
      shorts.empty()
          ? std::span(reinterpret_cast<const unsigned char*>(idx.data()), idx.size() * 4)
          : std::span(reinterpret_cast<const unsigned char*>(shorts.data()), shorts.size() * 2);
  const uint64_t key = content_key("indices " + std::to_string(size), bytes);
  if (const int same = written_before(key, bytes); same >= 0) return same;
  tinygltf::Accessor a;
  a.type = TINYGLTF_TYPE_SCALAR;
  a.count = idx.size();
  a.componentType =
      narrow ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
  Held held{static_cast<int>(m_.accessors.size()), Held::Buffer, 0, 0, bytes.size()};
  if (meshopt) {  // its view is written by finish()
    auto it = std::find_if(shared_indices_.begin(), shared_indices_.end(),
                           [&](const SharedIndices& s) { return s.size == size; });
    if (it == shared_indices_.end())
      it = shared_indices_.insert(shared_indices_.end(), {size, {}, 0, {}});
    a.byteOffset = it->idx.size() * size;
    held = {held.accessor, Held::Indices, static_cast<size_t>(it - shared_indices_.begin()),
            it->idx.size() * sizeof(uint32_t), bytes.size()};
    it->idx.insert(it->idx.end(), idx.begin(), idx.end());
    it->vertices = std::max(it->vertices, vertices);
    it->accessors.push_back(held.accessor);
  } else {
    a.bufferView = add_view(m_, bytes.data(), bytes.size(), TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    held.offset = m_.bufferViews.back().byteOffset;
  }
  m_.accessors.push_back(a);
  written_.emplace(key, held);
  return held.accessor;
}

template <typename T>
int SceneBuffers::vec3(const std::vector<float>& xyz, std::vector<T> q, int component, float lo) {
  const size_t count = xyz.size() / 3;
  if (compression_ == GltfCompression::None)
    return accessor(xyz.data(), count, 12, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                    false);
  const double top = std::numeric_limits<T>::max();
  q.assign(count * 4, 0);
  for (size_t i = 0; i < 3 * count; ++i)
    q[i / 3 * 4 + i % 3] = static_cast<T>(std::lround(std::clamp(xyz[i], lo, 1.f) * top));
  return accessor(q.data(), count, 4 * sizeof(T), component, TINYGLTF_TYPE_VEC3, true);
}

int SceneBuffers::accessor(const void* data, size_t count, size_t stride, int component, int type,
                           bool normalized, std::vector<double> lo, std::vector<double> hi,
                           const char* filter) {
  const std::string named = filter ? filter : "";
  const std::span<const unsigned char> bytes(static_cast<const unsigned char*>(data),
                                             count * stride);
  const uint64_t key =
      content_key("attribute " + std::to_string(component) + " " + std::to_string(type) + " " +
                      std::to_string(normalized) + " " + std::to_string(stride) + " " + named,
                  bytes);
  if (const int same = written_before(key, bytes); same >= 0) return same;
  tinygltf::Accessor a;
  a.componentType = component;
  a.type = type;
  a.normalized = normalized;
  a.count = count;
  a.minValues = std::move(lo);
  a.maxValues = std::move(hi);
  const int target = TINYGLTF_TARGET_ARRAY_BUFFER;
  Held held{static_cast<int>(m_.accessors.size()), Held::Buffer, 0, 0, bytes.size()};
  if (compression_ == GltfCompression::Meshopt) {  // its view is written by finish()
    auto it = std::find_if(shared_.begin(), shared_.end(), [&](const SharedStream& s) {
      return s.stride == stride && s.filter == named;
    });
    if (it == shared_.end()) it = shared_.insert(shared_.end(), {stride, named, {}, {}});
    a.byteOffset = it->bytes.size();
    held = {held.accessor, Held::Attributes, static_cast<size_t>(it - shared_.begin()),
            it->bytes.size(), bytes.size()};
    it->bytes.insert(it->bytes.end(), bytes.begin(), bytes.end());
    it->accessors.push_back(held.accessor);
  } else {
    a.bufferView = add_view(m_, data, count * stride, target);
    held.offset = m_.bufferViews.back().byteOffset;
    if (compression_ != GltfCompression::None) m_.bufferViews.back().byteStride = stride;
  }
  m_.accessors.push_back(a);
  written_.emplace(key, held);
  return held.accessor;
}

uint64_t SceneBuffers::content_key(const std::string& description,
                                   std::span<const unsigned char> bytes) {
  return fnv1a64(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                 fnv1a64(description + '\n'));
}

int SceneBuffers::written_before(uint64_t key, std::span<const unsigned char> bytes) const {
  const auto [first, last] = written_.equal_range(key);
  for (auto it = first; it != last; ++it) {
    const Held& h = it->second;
    if (h.bytes != bytes.size()) continue;
    const unsigned char* at = nullptr;
    switch (h.where) {
      case Held::Buffer: at = m_.buffers[0].data.data(); break;
      case Held::Attributes: at = shared_[h.stream].bytes.data(); break;
      case Held::Indices:
        at = reinterpret_cast<const unsigned char*>(shared_indices_[h.stream].idx.data());
        break;
    }
    if (std::equal(bytes.begin(), bytes.end(), at + h.offset)) return h.accessor;
  }
  return -1;
}

void SceneBuffers::finish() {
  for (const SharedStream& s : shared_) {
    const size_t count = s.bytes.size() / s.stride;
    std::vector<unsigned char> packed(meshopt_encodeVertexBufferBound(count, s.stride));
    packed.resize(
        meshopt_encodeVertexBuffer(packed.data(), packed.size(), s.bytes.data(), count, s.stride));
    const int view =
        encoded_view(packed, count, s.stride, s.stride, "ATTRIBUTES", TINYGLTF_TARGET_ARRAY_BUFFER,
                     s.filter.empty() ? nullptr : s.filter.c_str());
    for (const int accessor : s.accessors)
      m_.accessors[static_cast<size_t>(accessor)].bufferView = view;
  }
  shared_.clear();
  // EXT_meshopt_compression reads triangle streams of codec version 1 (header 0xe1);
  // meshoptimizer before 0.19 writes version 0 unless told. Set once, before any thread
  // encodes.
  static const bool version_1 = (meshopt_encodeIndexVersion(1), true);
  (void)version_1;
  for (const SharedIndices& s : shared_indices_) {
    std::vector<unsigned char> packed(meshopt_encodeIndexBufferBound(s.idx.size(), s.vertices));
    packed.resize(
        meshopt_encodeIndexBuffer(packed.data(), packed.size(), s.idx.data(), s.idx.size()));
    const int view = encoded_view(packed, s.idx.size(), s.size, 0, "TRIANGLES",
                                  TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
    for (const int accessor : s.accessors)
      m_.accessors[static_cast<size_t>(accessor)].bufferView = view;
  }
  shared_indices_.clear();
  written_.clear();  // what they held is written now
}

int SceneBuffers::encoded_view(const std::vector<unsigned char>& packed, size_t count, size_t size,
                               size_t view_stride, const char* mode, int target,
                               const char* filter) {
  auto& buf = m_.buffers[0].data;
  while (buf.size() % 4) buf.push_back(0);
  const size_t offset = buf.size();
  buf.insert(buf.end(), packed.begin(), packed.end());
  fallback_ = (fallback_ + 3) / 4 * 4;
  tinygltf::BufferView view;
  view.buffer = 1;
  view.byteOffset = fallback_;
  view.byteLength = count * size;
  view.byteStride = view_stride;
  view.target = target;
  fallback_ += view.byteLength;
  m_.bufferViews.push_back(view);
  const int index = static_cast<int>(m_.bufferViews.size()) - 1;
  nlohmann::json encoding = {
      {"buffer", 0},        {"byteOffset", offset}, {"byteLength", packed.size()},
      {"byteStride", size}, {"count", count},       {"mode", mode}};
  if (filter) encoding["filter"] = filter;
  view_extensions_.emplace_back(index, nlohmann::json{{"EXT_meshopt_compression", encoding}});
  return index;
}

}  // namespace cutaway::gltf
