#include "export/gltf_export.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <meshoptimizer.h>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/parallel_for.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "export/ktx2_texture.h"
#include "export/texture_image.h"
#include "export/vertex_tangents.h"
#include "model/pbr_material.h"

namespace cutaway {

namespace {

/// Appends raw data to buffer 0 as a new buffer view (4-byte aligned); returns the view index.
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

int add_material(tinygltf::Model& m, const std::string& name, double alpha,
                 bool double_sided = false, double roughness = 0.8) {
  tinygltf::Material mat;
  mat.name = name;
  mat.pbrMetallicRoughness.baseColorFactor = {1.0, 1.0, 1.0, alpha};
  mat.pbrMetallicRoughness.metallicFactor = 0.0;
  mat.pbrMetallicRoughness.roughnessFactor = roughness;
  mat.alphaMode = alpha < 1.0 ? "BLEND" : "OPAQUE";
  mat.doubleSided = double_sided;
  m.materials.push_back(mat);
  return static_cast<int>(m.materials.size()) - 1;
}

/// An empty glTF 2.0 model with one (empty) buffer and scene 0 as the default.
tinygltf::Model new_model() {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "cutaway";
  m.buffers.emplace_back();
  m.defaultScene = 0;
  return m;
}

/// The model as .glb bytes.
std::string to_glb(tinygltf::Model& m) {
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  writer.WriteGltfSceneToStream(&m, out, false, true);
  return out.str();
}

// ---- scenes -------------------------------------------------------------------------------

/// The unit quaternion turning a node so that its local -Z points along `forward` and its +Y
/// lies in the plane of `forward` and `up` (towards `up`). When `up` is (nearly) parallel to
/// `forward`, +Y of the scene is tried next, then -Z of the scene. Returned with w >= 0.
glm::dquat look_rotation(glm::dvec3 forward, glm::dvec3 up) {
  const glm::dvec3 f = glm::normalize(forward);
  glm::dvec3 right(0.0);
  for (const glm::dvec3& u : {up, glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1)}) {
    const glm::dvec3 r = glm::cross(f, u);
    if (glm::length(r) > 1e-9 * std::max(1.0, glm::length(u))) {
      right = glm::normalize(r);
      break;
    }
  }
  const glm::dvec3 true_up = glm::cross(right, f);
  const glm::dmat3 worldFromNode(right, true_up, -f);  // columns: the node's +X, +Y, +Z
  glm::dquat q = glm::normalize(glm::quat_cast(worldFromNode));
  if (q.w < 0) q = -q;
  return q;
}

/// glTF's [x, y, z, w] order of a glm quaternion (+ 0.0 turns -0 into 0 in the JSON).
std::vector<double> gltf_rotation(const glm::dquat& q) {
  return {q.x + 0.0, q.y + 0.0, q.z + 0.0, q.w + 0.0};
}

std::vector<double> gltf_vec3(const glm::dvec3& v) { return {v.x + 0.0, v.y + 0.0, v.z + 0.0}; }

/// What glTF tolerates beyond the rules of check_assets: zero normals (written as +Y), a
/// camera without `up` (its look rotation does not use it); and what it needs: triangles in
/// every mesh, uv wherever a material is textured.
constexpr AssetRules kGltfRules{.camera_needs_up = false,
                                .normals_repaired = true,
                                .meshes_need_triangles = true,
                                .textures_need_uv = true};

/// How a quantized mesh's positions map back to metres: p = offset + scale * q, where q is the
/// stored normalized value (each component in -1..1). Identity for float positions.
struct MeshFrame {
  glm::dvec3 offset{0.0};
  double scale = 1.0;
};

/// Writes a scene's vertex attributes and indices as the compression mode asks:
/// - None: float32 attributes, one tightly packed buffer view each, in buffer 0;
/// - Quantize (KHR_mesh_quantization): POSITION as normalized SHORT over the mesh's bounding
///   cube (MeshFrame, stride 8), NORMAL as normalized BYTE (stride 4), COLOR_0 as normalized
///   UNSIGNED_SHORT (stride 8), TEXCOORD_0 as normalized UNSIGNED_SHORT when every coordinate
///   lies in 0..1 (else float); still one plain buffer view each, in buffer 0;
/// - Meshopt: the Quantize data (positions on 14-bit steps, stored as SHORT; normals through
///   the OCTAHEDRAL filter), each view encoded by meshoptimizer's vertex or index codec
///   into buffer 0 (EXT_meshopt_compression); the views themselves lie in buffer 1, a fallback
///   that holds no bytes (its byteLength is fallback_bytes()).
/// Indices are UNSIGNED_SHORT when the mesh has at most 65535 vertices (65535 is the primitive
/// restart value, never an index), else UNSIGNED_INT.
class SceneBuffers {
 public:
  SceneBuffers(tinygltf::Model& m, GltfCompression compression)
      : m_(m), compression_(compression) {}

  tinygltf::Model& model() { return m_; }
  size_t fallback_bytes() const { return fallback_; }
  /// (buffer view, its "extensions" object) of each encoded view: tinygltf does not write
  /// extensions of buffer views, so they are added to the serialised JSON.
  const std::vector<std::pair<int, nlohmann::json>>& view_extensions() const {
    return view_extensions_;
  }

  /// #V x 3 positions (metres); returns the accessor and sets `frame`. With a `pivot`
  /// (metres), the frame's offset is the pivot: float positions are stored relative to it, and
  /// quantized ones over the cube about it that holds them.
  int positions(const std::vector<float>& xyz, MeshFrame& frame, const glm::dvec3* pivot) {
    if (pivot) return positions_about(xyz, *pivot, frame);
    const size_t count = xyz.size() / 3;
    glm::dvec3 lo(xyz[0], xyz[1], xyz[2]), hi = lo;
    for (size_t i = 0; i < count; ++i)
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min<double>(lo[k], xyz[3 * i + k]);
        hi[k] = std::max<double>(hi[k], xyz[3 * i + k]);
      }
    if (compression_ == GltfCompression::None) {
      frame = {};
      return accessor(xyz.data(), count, 12, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                      false, {lo.x, lo.y, lo.z}, {hi.x, hi.y, hi.z});
    }
    frame.offset = (lo + hi) * 0.5;
    const glm::dvec3 half = (hi - lo) * 0.5;
    frame.scale = std::max({half.x, half.y, half.z});
    return quantized_positions(xyz, frame);
  }

  /// positions() about `pivot`.
  int positions_about(const std::vector<float>& xyz, const glm::dvec3& pivot, MeshFrame& frame) {
    const size_t count = xyz.size() / 3;
    frame.offset = pivot;
    if (compression_ == GltfCompression::None) {
      frame.scale = 1.0;
      std::vector<float> moved(xyz.size());
      std::vector<double> lo(3, INFINITY), hi(3, -INFINITY);
      for (size_t i = 0; i < count; ++i)
        for (int k = 0; k < 3; ++k) {
          moved[3 * i + k] = static_cast<float>(xyz[3 * i + k] - pivot[k]);
          lo[k] = std::min<double>(lo[k], moved[3 * i + k]);
          hi[k] = std::max<double>(hi[k], moved[3 * i + k]);
        }
      return accessor(moved.data(), count, 12, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3,
                      false, lo, hi);
    }
    frame.scale = 0;
    for (size_t i = 0; i < count; ++i)
      for (int k = 0; k < 3; ++k)
        frame.scale = std::max(frame.scale, std::fabs(xyz[3 * i + k] - pivot[k]));
    return quantized_positions(xyz, frame);
  }

  /// The positions quantized over the cube of half size frame.scale about frame.offset (a
  /// scale of 0 taken as 1); frame.scale then maps the stored integers back to metres.
  int quantized_positions(const std::vector<float>& xyz, MeshFrame& frame) {
    const size_t count = xyz.size() / 3;
    if (!(frame.scale > 0)) frame.scale = 1.0;
    // Steps over each half extent: 16 bits, or 14 for meshopt, whose codec stores the deltas of
    // the smaller integers in fewer bytes; the node's scale then stretches 14-bit integers read
    // as normalized SHORT (q / 32767) back to the extent.
    const double steps = compression_ == GltfCompression::Meshopt ? 8191 : 32767;
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
    return accessor(q.data(), count, 8, TINYGLTF_COMPONENT_TYPE_SHORT, TINYGLTF_TYPE_VEC3, true,
                    qlo, qhi);
  }

  /// #V x 3 unit normals: normalized BYTE; with meshopt through the codec's octahedral filter
  /// (8-bit X/Y of the octahedral map, Z 1: the constant bytes cost nearly nothing and the
  /// directions are spread more evenly than on the cube of three BYTEs).
  int normals(const std::vector<float>& xyz) {
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

  /// #V x 4 tangents (unit xyz, w +-1): float without compression, else normalized BYTE (the
  /// codec alone with meshopt).
  int tangents(const std::vector<float>& xyzw) {
    const size_t count = xyzw.size() / 4;
    if (compression_ == GltfCompression::None)
      return accessor(xyzw.data(), count, 16, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC4,
                      false);
    std::vector<int8_t> q(xyzw.size());
    for (size_t i = 0; i < xyzw.size(); ++i)
      q[i] = static_cast<int8_t>(std::lround(std::clamp(xyzw[i], -1.f, 1.f) * 127.f));
    return accessor(q.data(), count, 4, TINYGLTF_COMPONENT_TYPE_BYTE, TINYGLTF_TYPE_VEC4, true);
  }

  /// #V x 3 linear RGB colours in 0..1: normalized UNSIGNED_SHORT.
  int colours(const std::vector<float>& rgb) {
    return vec3(rgb, std::vector<uint16_t>{}, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, 0.f);
  }

  /// #V x 2 texture coordinates.
  int uvs(const std::vector<float>& xy) {
    const size_t count = xy.size() / 2;
    const bool unit = std::all_of(xy.begin(), xy.end(), [](float v) { return v >= 0 && v <= 1; });
    if (compression_ == GltfCompression::None || !unit)
      return accessor(xy.data(), count, 8, TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC2,
                      false);
    std::vector<uint16_t> q(xy.size());
    for (size_t i = 0; i < xy.size(); ++i)
      q[i] = static_cast<uint16_t>(std::lround(xy[i] * 65535.0));
    return accessor(q.data(), count, 4, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, TINYGLTF_TYPE_VEC2,
                    true);
  }

  /// A triangle list over `vertices` vertices.
  int indices(const std::vector<uint32_t>& idx, size_t vertices) {
    tinygltf::Accessor a;
    a.type = TINYGLTF_TYPE_SCALAR;
    a.count = idx.size();
    const bool narrow = vertices <= 65535;
    a.componentType =
        narrow ? TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT : TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
    const size_t size = narrow ? 2 : 4;
    const int target = TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER;
    if (compression_ == GltfCompression::Meshopt) {
      std::vector<unsigned char> packed(meshopt_encodeIndexBufferBound(idx.size(), vertices));
      packed.resize(
          meshopt_encodeIndexBuffer(packed.data(), packed.size(), idx.data(), idx.size()));
      a.bufferView = encoded_view(packed, idx.size(), size, 0, "TRIANGLES", target);
    } else if (narrow) {
      const std::vector<uint16_t> shorts(idx.begin(), idx.end());
      a.bufferView = add_view(m_, shorts.data(), shorts.size() * 2, target);
    } else {
      a.bufferView = add_view(m_, idx.data(), idx.size() * 4, target);
    }
    m_.accessors.push_back(a);
    return static_cast<int>(m_.accessors.size()) - 1;
  }

 private:
  /// A VEC3 accessor of `xyz` (each in lo..1): float without compression, else normalized
  /// components of T (BYTE or UNSIGNED_SHORT, glTF type `component`), each element padded to
  /// 4 of them so that it is 4-byte aligned.
  template <typename T>
  int vec3(const std::vector<float>& xyz, std::vector<T> q, int component, float lo) {
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

  /// An accessor over `count` elements `stride` bytes apart (the element itself first); with
  /// meshopt, `filter` names the EXT_meshopt_compression filter `data` was encoded with.
  int accessor(const void* data, size_t count, size_t stride, int component, int type,
               bool normalized, std::vector<double> lo = {}, std::vector<double> hi = {},
               const char* filter = nullptr) {
    tinygltf::Accessor a;
    a.componentType = component;
    a.type = type;
    a.normalized = normalized;
    a.count = count;
    a.minValues = std::move(lo);
    a.maxValues = std::move(hi);
    const int target = TINYGLTF_TARGET_ARRAY_BUFFER;
    if (compression_ == GltfCompression::Meshopt) {
      std::vector<unsigned char> packed(meshopt_encodeVertexBufferBound(count, stride));
      packed.resize(meshopt_encodeVertexBuffer(packed.data(), packed.size(), data, count, stride));
      a.bufferView = encoded_view(packed, count, stride, stride, "ATTRIBUTES", target, filter);
    } else {
      a.bufferView = add_view(m_, data, count * stride, target);
      if (compression_ != GltfCompression::None) m_.bufferViews.back().byteStride = stride;
    }
    m_.accessors.push_back(a);
    return static_cast<int>(m_.accessors.size()) - 1;
  }

  /// A view of `count` elements of `size` bytes in the fallback buffer (byteStride
  /// `view_stride`, 0 for none) whose bytes are `packed`, meshoptimizer's encoding in `mode`
  /// (with `filter`, when not null).
  int encoded_view(const std::vector<unsigned char>& packed, size_t count, size_t size,
                   size_t view_stride, const char* mode, int target, const char* filter = nullptr) {
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

  tinygltf::Model& m_;
  GltfCompression compression_;
  size_t fallback_ = 0;
  std::vector<std::pair<int, nlohmann::json>> view_extensions_;
};

/// A triangle list (indices into #V x 3 float `xyz`) simplified by meshoptimizer's edge
/// collapse (Garland-Heckbert quadrics) towards `fraction` of its triangles, the edges on its
/// border locked (meshopt_SimplifyLockBorder: a primitive's border is a cut outline or the seam
/// to the next primitive, so a closed piece stays closed), the error at most `error` of the
/// mesh's extent; then ordered for the vertex cache.
std::vector<uint32_t> simplified(const std::vector<uint32_t>& idx, const std::vector<float>& xyz,
                                 double fraction, double error) {
  const size_t vertices = xyz.size() / 3;
  std::vector<uint32_t> out(idx.size());
  const size_t target = static_cast<size_t>(static_cast<double>(idx.size() / 3) * fraction) * 3;
  out.resize(meshopt_simplify(out.data(), idx.data(), idx.size(), xyz.data(), vertices,
                              3 * sizeof(float), target, static_cast<float>(error),
                              meshopt_SimplifyLockBorder, nullptr));
  const std::vector<uint32_t> input = out;
  meshopt_optimizeVertexCache(out.data(), input.data(), input.size(), vertices);
  return out;
}

/// A scene mesh as written: its glTF mesh, the frame its positions need, its coarser levels.
struct AddedMesh {
  int index = -1;
  MeshFrame frame;
  std::vector<int> lods;  ///< glTF meshes of levels 1, 2, ... (names ending _LOD1, _LOD2, ...)
};

/// The vertices of a scene mesh as written: float32 attributes (#V x 3; uv #V x 2, empty when
/// the mesh has none; tangent #V x 4, empty unless a primitive is normal-mapped) and where each
/// of the mesh's vertices went.
struct WrittenVertices {
  std::vector<unsigned> remap;  ///< per mesh vertex, its written index (~0u: not written)
  unsigned count = 0;           ///< #V
  std::vector<float> position, normal, colour, uv, tangent;
};

/// Only the vertices of `mesh` some triangle of `lists` uses, each written once (ordered for
/// fetching by cache_ordered_triangles()): a vertex whose written attributes (float position,
/// normal, colour, uv and, `with_tangents`, its vertex_tangents() one) equal an earlier one's is
/// welded to it (the copies of cut vertices on both sides of a seam that show the same colour).
WrittenVertices welded_vertices(const AssetMesh& mesh,
                                const std::vector<std::span<const glm::uvec3>>& lists,
                                bool with_tangents) {
  const std::vector<glm::dvec4> tangent =
      with_tangents ? vertex_tangents(mesh.position, mesh.normal, mesh.uv, lists)
                    : std::vector<glm::dvec4>{};
  const size_t n = mesh.position.size();
  std::vector<bool> needed(n, false);
  for (const auto& list : lists)
    for (const glm::uvec3& t : list)
      for (int k = 0; k < 3; ++k) needed[t[k]] = true;
  WrittenVertices out;
  out.remap.assign(n, ~0u);
  const size_t key_floats = with_tangents ? 15 : 11;  // the tangent keys only where written
  std::unordered_map<std::string, unsigned> written;
  for (size_t i = 0; i < n; ++i) {
    if (!needed[i]) continue;
    const glm::dvec3& p = mesh.position[i];
    const double len = glm::length(mesh.normal[i]);
    const glm::dvec3 nrm =
        len > 0 && std::isfinite(len) ? mesh.normal[i] / len : glm::dvec3(0, 1, 0);
    const glm::dvec3 c = glm::clamp(mesh.colour[i], 0.0, 1.0);
    float vertex[15] = {};  // position, normal, colour, uv, tangent (with_tangents only)
    for (int k = 0; k < 3; ++k) {
      vertex[k] = static_cast<float>(p[k]);
      vertex[3 + k] = static_cast<float>(nrm[k]);
      vertex[6 + k] = static_cast<float>(c[k]);
    }
    if (!mesh.uv.empty()) {
      const glm::dvec2 q = mesh.uv[i];
      vertex[9] = static_cast<float>(q.x);
      vertex[10] = static_cast<float>(q.y);
    }
    if (with_tangents)
      for (int k = 0; k < 4; ++k) vertex[11 + k] = static_cast<float>(tangent[i][k]);
    for (float& v : vertex) v += 0.0f;  // -0 and +0 write alike
    const auto [it, added] = written.emplace(
        std::string(reinterpret_cast<const char*>(vertex), key_floats * sizeof(float)), out.count);
    out.remap[i] = it->second;
    if (!added) continue;
    ++out.count;
    out.position.insert(out.position.end(), vertex, vertex + 3);
    out.normal.insert(out.normal.end(), vertex + 3, vertex + 6);
    out.colour.insert(out.colour.end(), vertex + 6, vertex + 9);
    if (!mesh.uv.empty()) out.uv.insert(out.uv.end(), vertex + 9, vertex + 11);
    if (with_tangents) out.tangent.insert(out.tangent.end(), vertex + 11, vertex + 15);
  }
  return out;
}

/// Per primitive, its triangles (`lists`) in written vertex indices, reordered for the GPU's
/// post-transform vertex cache (meshoptimizer: Forsyth-style greedy order); then the vertices
/// renumbered in the order the primitives first use them (fewer cache misses when vertices are
/// fetched): `vertices`' attributes are reordered to match.
std::vector<std::vector<uint32_t>> cache_ordered_triangles(
    const std::vector<std::span<const glm::uvec3>>& lists, WrittenVertices& vertices) {
  const std::vector<unsigned>& remap = vertices.remap;
  const unsigned used = vertices.count;
  std::vector<std::vector<uint32_t>> idx(lists.size());
  std::vector<uint32_t> all;
  for (size_t k = 0; k < lists.size(); ++k) {
    for (const glm::uvec3& t : lists[k])
      idx[k].insert(idx[k].end(), {remap[t.x], remap[t.y], remap[t.z]});
    const std::vector<uint32_t> input = idx[k];
    meshopt_optimizeVertexCache(idx[k].data(), input.data(), input.size(), used);
    all.insert(all.end(), idx[k].begin(), idx[k].end());
  }
  std::vector<uint32_t> fetch(used);
  meshopt_optimizeVertexFetchRemap(fetch.data(), all.data(), all.size(), used);
  for (std::vector<uint32_t>& list : idx)
    meshopt_remapIndexBuffer(list.data(), std::vector<uint32_t>(list).data(), list.size(),
                             fetch.data());
  for (std::vector<float>* stream :
       {&vertices.position, &vertices.normal, &vertices.colour, &vertices.uv, &vertices.tangent}) {
    if (stream->empty()) continue;
    const std::vector<float> input = *stream;
    meshopt_remapVertexBuffer(stream->data(), input.data(), used,
                              input.size() / used * sizeof(float), fetch.data());
  }
  return idx;
}

/// The levels of detail of one scene mesh, each one glTF mesh, all over the same vertex
/// accessors: positions and normals are added at construction, colours and texture coordinates
/// when some primitive first uses them.
class MeshLevels {
 public:
  /// `primitives` of the mesh, `textured` and `relief` (normal-mapped) per primitive,
  /// `vertices` as written; `frame` receives the frame of the positions (about `pivot` when
  /// given: SceneBuffers::positions).
  MeshLevels(SceneBuffers& out, const std::vector<AssetPrimitive>& primitives,
             const std::vector<int>& gltf_material, const std::vector<bool>& textured,
             const std::vector<bool>& relief, const WrittenVertices& vertices, MeshFrame& frame,
             const glm::dvec3* pivot)
      : out_(out), primitives_(primitives), gltf_material_(gltf_material), textured_(textured),
        relief_(relief), vertices_(vertices),
        positions_(out.positions(vertices.position, frame, pivot)),
        normals_(out.normals(vertices.normal)) {}

  /// Adds the glTF mesh `name` with `lists` (per primitive, its triangles' indices); returns
  /// its index.
  int add(const std::string& name, const std::vector<std::vector<uint32_t>>& lists) {
    tinygltf::Model& m = out_.model();
    tinygltf::Mesh gm;
    gm.name = name;
    for (size_t k = 0; k < primitives_.size(); ++k) {
      tinygltf::Primitive prim;
      prim.mode = TINYGLTF_MODE_TRIANGLES;
      prim.material = gltf_material_[static_cast<size_t>(primitives_[k].material)];
      prim.attributes["POSITION"] = positions_;
      prim.attributes["NORMAL"] = normals_;
      // A textured material takes its colour from TEXCOORD_0, never also from COLOR_0 (glTF
      // would multiply the two).
      if (textured_[k]) {
        if (uvs_ < 0) uvs_ = out_.uvs(vertices_.uv);
        prim.attributes["TEXCOORD_0"] = uvs_;
      } else {
        if (colours_ < 0) colours_ = out_.colours(vertices_.colour);
        prim.attributes["COLOR_0"] = colours_;
      }
      if (relief_[k]) {
        if (tangents_ < 0) tangents_ = out_.tangents(vertices_.tangent);
        prim.attributes["TANGENT"] = tangents_;
      }
      prim.indices = out_.indices(lists[k], vertices_.count);
      gm.primitives.push_back(prim);
    }
    m.meshes.push_back(gm);
    return static_cast<int>(m.meshes.size()) - 1;
  }

 private:
  SceneBuffers& out_;
  const std::vector<AssetPrimitive>& primitives_;
  const std::vector<int>& gltf_material_;
  const std::vector<bool>& textured_;
  const std::vector<bool>& relief_;
  const WrittenVertices& vertices_;
  const int positions_, normals_;
  int colours_ = -1, uvs_ = -1, tangents_ = -1;  // added when some primitive uses them
};

/// Adds mesh `mesh` through `out` (one primitive per AssetPrimitive, sharing the vertex
/// attributes; material k of the assets is glTF material gltf_material[k]), and `lods` coarser
/// levels over the same vertices: level l has about 2^-l of each primitive's triangles
/// (simplified(), error at most 2^(l-1) % of the mesh's extent, so a level may keep more).
/// `pivot_at_centroid`: the positions about the mesh's volume_centroid (GltfSceneOptions).
AddedMesh add_asset_mesh(SceneBuffers& out, const AssetMesh& mesh,
                         const std::vector<int>& gltf_material, int lods, bool pivot_at_centroid) {
  const tinygltf::Model& m = out.model();
  const std::vector<AssetPrimitive> plain{{0, mesh.triangle.size(), 0, {}}};
  const std::vector<AssetPrimitive>& primitives = mesh.primitives.empty() ? plain : mesh.primitives;
  // Per primitive: textured or not, and its triangles (the coarse ones of a textured primitive
  // that has them: its colour is in the texture).
  std::vector<bool> textured, relief;
  std::vector<std::span<const glm::uvec3>> lists;
  for (const AssetPrimitive& p : primitives) {
    const tinygltf::Material& material =
        m.materials[static_cast<size_t>(gltf_material[static_cast<size_t>(p.material)])];
    textured.push_back(material.pbrMetallicRoughness.baseColorTexture.index >= 0);
    relief.push_back(material.normalTexture.index >= 0 && !mesh.uv.empty());
    lists.push_back(primitive_triangles(mesh, p, textured.back()));
  }
  const bool with_tangents = std::find(relief.begin(), relief.end(), true) != relief.end();
  WrittenVertices vertices = welded_vertices(mesh, lists, with_tangents);
  const std::vector<std::vector<uint32_t>> idx = cache_ordered_triangles(lists, vertices);

  AddedMesh added;
  const glm::dvec3 centroid = pivot_at_centroid ? volume_centroid(mesh) : glm::dvec3(0.0);
  MeshLevels levels(out, primitives, gltf_material, textured, relief, vertices, added.frame,
                    pivot_at_centroid ? &centroid : nullptr);
  added.index = levels.add(mesh.name, idx);
  for (int level = 1; level <= lods; ++level) {
    std::vector<std::vector<uint32_t>> coarser(idx.size());
    for (size_t k = 0; k < idx.size(); ++k)
      coarser[k] = simplified(idx[k], vertices.position, std::ldexp(1.0, -level),
                              0.01 * std::ldexp(1.0, level - 1));
    added.lods.push_back(levels.add(mesh.name + "_LOD" + std::to_string(level), coarser));
  }
  return added;
}

/// `name` as a relative URI: every byte outside RFC 3986's unreserved set percent-encoded.
std::string uri_encode(const std::string& name) {
  std::string out;
  for (unsigned char c : name) {
    if (std::isalnum(c) || c == '-' || c == '.' || c == '_' || c == '~') {
      out += static_cast<char>(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      out += hex;
    }
  }
  return out;
}

/// Adds `material` to `m` as an opaque, single-sided metallic-roughness material (white base
/// colour: vertex colours give the colour, metallic 0) with KHR_materials_clearcoat,
/// KHR_materials_sheen and KHR_materials_diffuse_transmission where its values ask for them
/// (each added to extensionsUsed once); its base colour, material map and normal map are glTF
/// textures textures[base_colour_texture] etc. (a height map is not written: glTF has none).
void add_pbr_material(tinygltf::Model& m, const AssetMaterial& material,
                      const std::vector<int>& textures) {
  const PbrMaterial& pbr = material.pbr;
  const int index = add_material(m, material.name, 1.0, false, pbr.roughness);
  tinygltf::Material& mat = m.materials[static_cast<size_t>(index)];
  if (material.base_colour_texture >= 0) {
    mat.pbrMetallicRoughness.baseColorTexture.index =
        textures[static_cast<size_t>(material.base_colour_texture)];
    mat.pbrMetallicRoughness.baseColorTexture.texCoord = 0;
  }
  if (material.normal_texture >= 0) {  // the relief: tangents from MikkTSpace (none written)
    mat.normalTexture.index = textures[static_cast<size_t>(material.normal_texture)];
    mat.normalTexture.texCoord = 0;
  }
  const int material_map =
      material.material_texture < 0 ? -1 : textures[static_cast<size_t>(material.material_texture)];
  if (material_map >= 0) {  // the map holds the values: factors 1
    mat.pbrMetallicRoughness.roughnessFactor = 1.0;
    mat.pbrMetallicRoughness.metallicRoughnessTexture.index = material_map;
  }
  auto use = [&m, &mat](const std::string& extension, tinygltf::Value::Object values) {
    mat.extensions[extension] = tinygltf::Value(std::move(values));
    if (std::find(m.extensionsUsed.begin(), m.extensionsUsed.end(), extension) ==
        m.extensionsUsed.end())
      m.extensionsUsed.push_back(extension);
  };
  if (pbr.clearcoat > 0) {
    use("KHR_materials_clearcoat",
        {{"clearcoatFactor", tinygltf::Value(pbr.clearcoat)},
         {"clearcoatRoughnessFactor", tinygltf::Value(pbr.clearcoat_roughness)}});
  }
  if (pbr.sheen != glm::dvec3(0.0)) {
    use("KHR_materials_sheen",
        {{"sheenColorFactor", tinygltf::Value(tinygltf::Value::Array{
                                  tinygltf::Value(pbr.sheen.x), tinygltf::Value(pbr.sheen.y),
                                  tinygltf::Value(pbr.sheen.z)})},
         {"sheenRoughnessFactor", tinygltf::Value(pbr.sheen_roughness)}});
  }
  if (material_map >= 0 && pbr.translucency > 0) {
    use("KHR_materials_diffuse_transmission",
        {{"diffuseTransmissionFactor", tinygltf::Value(1.0)},
         {"diffuseTransmissionTexture",
          tinygltf::Value(tinygltf::Value::Object{{"index", tinygltf::Value(material_map)}})}});
  } else if (pbr.translucency > 0) {
    use("KHR_materials_diffuse_transmission",
        {{"diffuseTransmissionFactor", tinygltf::Value(pbr.translucency)}});
  }
}

/// A scene as a tinygltf model (scene_model()) and what tinygltf does not write itself.
struct SceneModel {
  tinygltf::Model model;  ///< all binary data in buffer 0 (no URI)
  /// With Meshopt compression, buffer 1 is the fallback: its byteLength.
  size_t fallback_bytes = 0;
  /// (buffer view, its "extensions" object) of each encoded view (SceneBuffers).
  std::vector<std::pair<int, nlohmann::json>> view_extensions;
  /// With image files: (file name, image bytes) of each used texture.
  std::vector<std::pair<std::string, std::string>> images;
};

/// The steps of scene_model over the state they share: the model and scene being filled and
/// which glTF material, texture and mesh each of the assets' became. Each step is one method,
/// run once, in order (scene_model).
class SceneModelBuilder {
 public:
  /// `assets` are valid (kGltfRules); `image_files` as scene_model's.
  SceneModelBuilder(const SceneAssets& assets, const GltfSceneOptions& options,
                    const std::vector<std::string>* image_files)
      : assets_(assets), options_(options), image_files_(image_files), m_(new_model()),
        gltf_material_(used_materials(assets)) {
    if (options.compression == GltfCompression::Meshopt) m_.buffers.emplace_back();
    scene_.name = assets.name;
  }

  /// The textures of the used materials, as images in the buffer (JPEG or PNG,
  /// texture_image.h; KTX2, ktx2_texture.h, several encoded at once) or image files, in the
  /// assets' order.
  void add_textures();
  /// The used materials, in their order.
  void add_materials();
  /// The meshes (add_asset_mesh()) and the extensions their compression requires.
  void add_meshes();
  /// The root node and each instance's nodes.
  void add_instances();
  /// The camera and the lights, and how a viewer shows the lights' units.
  void add_camera_and_lights();
  /// The model, once every step has run.
  SceneModel finish();

 private:
  /// Which materials some mesh uses (an unused one is a validator notice): 0 for those, -1
  /// for the others.
  static std::vector<int> used_materials(const SceneAssets& assets);
  /// The sampler of a texture: clamped, or repeating in u where it wraps in u (a texture
  /// that runs around, the skin's); each added once.
  int sampler_index(bool wrap_u);
  /// Adds texture `t` of the assets with its image, `bytes` (encoded as options.textures
  /// says); returns the glTF texture.
  int add_texture(size_t t, std::string bytes);
  /// Adds `node` and lists it in the scene.
  void add_node(tinygltf::Node node);
  /// Adds the node of `inst`, its mesh node and its hull nodes, in this order.
  void add_instance(const AssetInstance& inst);
  /// The node of `inst`'s mesh; its levels of detail go to lod_nodes_.
  tinygltf::Node mesh_node(const AssetInstance& inst);
  /// The collision hull nodes of `inst` (none without collision), their meshes added.
  std::vector<tinygltf::Node> hull_nodes(const AssetInstance& inst);

  const SceneAssets& assets_;
  const GltfSceneOptions& options_;
  const std::vector<std::string>* image_files_;
  tinygltf::Model m_;
  tinygltf::Scene scene_;
  size_t fallback_bytes_ = 0;
  std::vector<std::pair<int, nlohmann::json>> view_extensions_;
  std::vector<std::pair<std::string, std::string>> images_;
  std::vector<int> gltf_material_;         // per material of the assets; -1: unused
  std::vector<int> gltf_texture_;          // per texture of the assets; -1: unused
  std::vector<AddedMesh> added_;           // per mesh of the assets
  size_t main_nodes_ = 0;                  // the nodes in the scene's list
  std::vector<tinygltf::Node> lod_nodes_;  // after the others
  int hull_material_ = -1;                 // the collision hulls' one material, once needed
};

std::vector<int> SceneModelBuilder::used_materials(const SceneAssets& assets) {
  std::vector<int> gltf_material(assets.materials.size(), -1);
  for (const AssetMesh& mesh : assets.meshes) {
    if (mesh.primitives.empty()) gltf_material[0] = 0;
    for (const AssetPrimitive& p : mesh.primitives)
      gltf_material[static_cast<size_t>(p.material)] = 0;
  }
  return gltf_material;
}

void SceneModelBuilder::add_textures() {
  gltf_texture_.assign(assets_.textures.size(), -1);
  std::vector<Ktx2Content> content(assets_.textures.size(), Ktx2Content::Colour);
  for (size_t k = 0; k < assets_.materials.size(); ++k) {
    const AssetMaterial& material = assets_.materials[k];
    for (const int t :
         {material.base_colour_texture, material.material_texture, material.normal_texture})
      if (gltf_material_[k] >= 0 && t >= 0) gltf_texture_[static_cast<size_t>(t)] = 0;
    if (material.normal_texture >= 0)
      content[static_cast<size_t>(material.normal_texture)] = Ktx2Content::Normal;
  }
  std::vector<std::string> bytes(assets_.textures.size());
  if (options_.textures == TextureFormat::Ktx2) {
    if (options_.basisu.empty()) throw InternalError("KTX2 textures asked for without basisu");
    // Each texture by its own single-threaded basisu, several at once: the same bytes in any
    // order.
    oneapi::tbb::parallel_for(size_t{0}, assets_.textures.size(), [&](size_t t) {
      if (gltf_texture_[t] < 0) return;
      const AssetTexture& texture = assets_.textures[t];
      const Ktx2Content kind = content[t] == Ktx2Content::Normal ? Ktx2Content::Normal
                               : texture.linear                  ? Ktx2Content::Data
                                                                 : Ktx2Content::Colour;
      bytes[t] = encode_ktx2(texture, kind, options_.basisu);
    });
    m_.extensionsUsed.push_back("KHR_texture_basisu");
    m_.extensionsRequired.push_back("KHR_texture_basisu");
  } else {
    for (size_t t = 0; t < assets_.textures.size(); ++t)
      if (gltf_texture_[t] >= 0) bytes[t] = encode_texture(assets_.textures[t], options_.textures);
  }
  for (size_t t = 0; t < assets_.textures.size(); ++t)
    if (gltf_texture_[t] >= 0) gltf_texture_[t] = add_texture(t, std::move(bytes[t]));
}

int SceneModelBuilder::sampler_index(bool wrap_u) {
  const int wrap_s = wrap_u ? TINYGLTF_TEXTURE_WRAP_REPEAT : TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  for (size_t k = 0; k < m_.samplers.size(); ++k)
    if (m_.samplers[k].wrapS == wrap_s) return static_cast<int>(k);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  sampler.wrapS = wrap_s;
  sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  m_.samplers.push_back(sampler);
  return static_cast<int>(m_.samplers.size()) - 1;
}

int SceneModelBuilder::add_texture(size_t t, std::string bytes) {
  const AssetTexture& asset = assets_.textures[t];
  const int sampler = sampler_index(asset.wrap_u);
  tinygltf::Image image;
  image.name = asset.name;
  image.mimeType = texture_mime_type(asset, options_.textures);
  if (image_files_) {
    image.uri = uri_encode(image_files_->at(t));
    images_.emplace_back(image_files_->at(t), std::move(bytes));
  } else {
    image.bufferView = add_view(m_, bytes.data(), bytes.size(), 0);
  }
  m_.images.push_back(image);
  tinygltf::Texture texture;
  texture.name = asset.name;
  texture.sampler = sampler;
  const int source = static_cast<int>(m_.images.size()) - 1;
  if (options_.textures == TextureFormat::Ktx2)  // no fallback: the image only there
    texture.extensions["KHR_texture_basisu"] =
        tinygltf::Value(tinygltf::Value::Object{{"source", tinygltf::Value(source)}});
  else texture.source = source;
  m_.textures.push_back(texture);
  return static_cast<int>(m_.textures.size()) - 1;
}

void SceneModelBuilder::add_materials() {
  for (size_t k = 0; k < assets_.materials.size(); ++k) {
    if (gltf_material_[k] < 0) continue;
    gltf_material_[k] = static_cast<int>(m_.materials.size());
    add_pbr_material(m_, assets_.materials[k], gltf_texture_);
  }
}

void SceneModelBuilder::add_meshes() {
  SceneBuffers out(m_, options_.compression);
  for (const AssetMesh& mesh : assets_.meshes)
    added_.push_back(
        add_asset_mesh(out, mesh, gltf_material_, options_.lods, options_.pivot_at_centre_of_mass));
  fallback_bytes_ = out.fallback_bytes();
  view_extensions_ = out.view_extensions();
  auto require = [this](const std::string& extension) {
    m_.extensionsUsed.push_back(extension);
    m_.extensionsRequired.push_back(extension);
  };
  if (options_.compression != GltfCompression::None) require("KHR_mesh_quantization");
  if (options_.compression == GltfCompression::Meshopt) require("EXT_meshopt_compression");
}

void SceneModelBuilder::add_node(tinygltf::Node node) {
  m_.nodes.push_back(std::move(node));
  scene_.nodes.push_back(static_cast<int>(m_.nodes.size()) - 1);
}

void SceneModelBuilder::add_instances() {
  // Node order: the root, each instance's node followed by its mesh node and hull nodes, the
  // camera, the lights (those in the scene's list: the root, the camera, the lights); then the
  // level nodes, outside the scene's list.
  main_nodes_ = 1 + 2 * assets_.instances.size() +
                (options_.camera_and_lights ? 1 + assets_.lights.size() : 0);
  if (options_.collision != GltfCollision::None)
    for (const AssetInstance& inst : assets_.instances) main_nodes_ += inst.collision.size();
  tinygltf::Node root;
  root.name = assets_.name;
  m_.nodes.push_back(root);
  scene_.nodes.push_back(0);
  for (const AssetInstance& inst : assets_.instances) add_instance(inst);
}

void SceneModelBuilder::add_instance(const AssetInstance& inst) {
  const double qlen = glm::length(inst.rotation);
  glm::dquat q = inst.rotation / qlen;
  if (q.w < 0) q = -q;
  tinygltf::Node node;
  node.name = inst.name;
  node.rotation = gltf_rotation(q);
  node.translation = gltf_vec3(inst.translation);
  tinygltf::Node mesh = mesh_node(inst);
  if (!inst.piece.template_name.empty()) {
    const PieceInfo& info = inst.piece;
    tinygltf::Value::Array parts;
    for (const std::string& kind : info.parts) parts.emplace_back(kind);
    tinygltf::Value::Object extras;
    extras["template"] = tinygltf::Value(info.template_name);
    // A decimal string: a 64-bit seed does not fit a JSON number exactly.
    extras["seed"] = tinygltf::Value(std::to_string(info.seed));
    extras["cut"] = tinygltf::Value(info.cut);
    extras["piece"] = tinygltf::Value(info.cell);
    extras["parts"] = tinygltf::Value(parts);
    extras["volume_m3"] = tinygltf::Value(info.volume_m3);
    node.extras = tinygltf::Value(std::move(extras));
  } else if (inst.backdrop) {  // staging, which an engine or a viewer may drop
    node.extras = tinygltf::Value(tinygltf::Value::Object{{"backdrop", tinygltf::Value(true)}});
  }
  const int index = static_cast<int>(m_.nodes.size());
  node.children = {index + 1};
  std::vector<tinygltf::Node> hulls = hull_nodes(inst);
  for (size_t k = 0; k < hulls.size(); ++k)
    node.children.push_back(index + 2 + static_cast<int>(k));
  m_.nodes.push_back(std::move(node));
  m_.nodes.push_back(std::move(mesh));
  for (tinygltf::Node& hull_node : hulls) m_.nodes.push_back(std::move(hull_node));
  m_.nodes[0].children.push_back(index);
}

tinygltf::Node SceneModelBuilder::mesh_node(const AssetInstance& inst) {
  // The mesh below the instance, with the mesh's frame (quantized positions back to metres:
  // offset + scale q) as its own transform: the instance's transform is the same whatever
  // the compression.
  const AddedMesh& mesh = added_[static_cast<size_t>(inst.mesh)];
  tinygltf::Node node;
  node.name = inst.name + "_mesh";
  // Only pieces are loose: a board or plate stays where it is.
  if (options_.collision == GltfCollision::GodotRigid && !inst.piece.template_name.empty())
    node.name += "-rigid";
  node.mesh = mesh.index;
  if (mesh.frame.offset != glm::dvec3(0.0)) node.translation = gltf_vec3(mesh.frame.offset);
  if (mesh.frame.scale != 1.0) node.scale = {mesh.frame.scale, mesh.frame.scale, mesh.frame.scale};
  // Levels of detail (MSFT_lod): a node per level, placed as the mesh node, outside the
  // scene's list; level l is shown down to 0.2 * 4^-l of the screen's height, the last one
  // always.
  if (!mesh.lods.empty()) {
    tinygltf::Value::Array ids, coverage;
    for (size_t l = 0; l < mesh.lods.size(); ++l) {
      tinygltf::Node level = node;
      level.name = inst.name + "_LOD" + std::to_string(l + 1);
      level.mesh = mesh.lods[l];
      ids.emplace_back(static_cast<int>(main_nodes_ + lod_nodes_.size()));
      lod_nodes_.push_back(std::move(level));
      coverage.emplace_back(0.2 * std::ldexp(1.0, -2 * static_cast<int>(l)));
    }
    coverage.emplace_back(0.0);
    node.extensions["MSFT_lod"] =
        tinygltf::Value(tinygltf::Value::Object{{"ids", tinygltf::Value(ids)}});
    node.extras = tinygltf::Value(
        tinygltf::Value::Object{{"MSFT_screencoverage", tinygltf::Value(coverage)}});
  }
  return node;
}

std::vector<tinygltf::Node> SceneModelBuilder::hull_nodes(const AssetInstance& inst) {
  std::vector<tinygltf::Node> nodes;
  if (!writes_hull_nodes(options_.collision)) return nodes;
  const std::string& mesh_name = assets_.meshes[static_cast<size_t>(inst.mesh)].name;
  // Hulls are see-through (alpha 0, blended) where a viewer does not read their names as
  // collision: Blender, three.js and model viewers draw nothing over the piece.
  if (!inst.collision.empty() && hull_material_ < 0)
    hull_material_ = add_material(m_, "collision", 0.0);
  for (size_t k = 0; k < inst.collision.size(); ++k) {
    const AssetHull& hull = inst.collision[k];
    char number[24];
    std::snprintf(number, sizeof number, "%02zu", k);
    tinygltf::Mesh hull_mesh;
    hull_mesh.name = options_.collision == GltfCollision::Godot
                         ? inst.name + "_collision" + std::to_string(k) + "-convcolonly"
                         : "UCX_" + mesh_name + "_" + number;
    std::vector<float> xyz;
    for (const glm::dvec3& p : hull.position)
      for (int c = 0; c < 3; ++c) xyz.push_back(static_cast<float>(p[c]) + 0.0f);
    std::vector<uint32_t> idx;
    for (const glm::uvec3& t : hull.triangle) idx.insert(idx.end(), {t.x, t.y, t.z});
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = add_vec3_accessor(m_, xyz, true);
    prim.indices = add_index_accessor(m_, idx);
    prim.material = hull_material_;
    hull_mesh.primitives.push_back(prim);
    m_.meshes.push_back(hull_mesh);
    tinygltf::Node hull_node;
    hull_node.name = hull_mesh.name;
    hull_node.mesh = static_cast<int>(m_.meshes.size()) - 1;
    hull_node.extras = tinygltf::Value(
        tinygltf::Value::Object{{"collision", tinygltf::Value(std::string("convex"))}});
    nodes.push_back(std::move(hull_node));
  }
  return nodes;
}

void SceneModelBuilder::add_camera_and_lights() {
  // How to show the lights' physical units (doc/lighting.md): three.js's
  // toneMappingExposure, and the sky a viewer adds as its world or ambient light.
  tinygltf::Value::Object view;
  view["exposure"] = tinygltf::Value(1 / kLumensPerWatt);
  if (assets_.ambient_lux > 0) view["ambient_lux"] = tinygltf::Value(assets_.ambient_lux);
  scene_.extras = tinygltf::Value(std::move(view));
  const AssetCamera& cam = assets_.camera;
  tinygltf::Camera camera;
  camera.name = "camera";
  camera.type = "perspective";
  camera.perspective.yfov = glm::radians(cam.fov_y_deg);
  camera.perspective.aspectRatio = cam.aspect;
  camera.perspective.znear = cam.znear;
  camera.perspective.zfar = cam.zfar;
  m_.cameras.push_back(camera);
  tinygltf::Node camera_node;
  camera_node.name = "camera";
  camera_node.camera = 0;
  camera_node.rotation = gltf_rotation(look_rotation(cam.target - cam.eye, cam.up));
  camera_node.translation = gltf_vec3(cam.eye);
  add_node(camera_node);

  for (const AssetLight& light : assets_.lights) {
    tinygltf::Light gl;
    gl.name = light.name;
    gl.color = gltf_vec3(light.colour);
    gl.intensity = light.intensity;
    tinygltf::Node node;
    node.name = light.name;
    if (light.type == LightType::Directional) {
      gl.type = "directional";
      node.rotation = gltf_rotation(look_rotation(light.direction, glm::dvec3(0, 1, 0)));
      if (light.angle_deg > 0)  // glTF's lights have no size: Blender's sun angle, as extras
        node.extras = tinygltf::Value(
            tinygltf::Value::Object{{"angle_deg", tinygltf::Value(light.angle_deg)}});
    } else {
      gl.type = "point";
      node.translation = gltf_vec3(light.position);
    }
    m_.lights.push_back(gl);
    tinygltf::Value::Object ref;
    ref["light"] = tinygltf::Value(static_cast<int>(m_.lights.size()) - 1);
    node.extensions["KHR_lights_punctual"] = tinygltf::Value(ref);
    add_node(node);
  }
}

SceneModel SceneModelBuilder::finish() {
  if (!m_.lights.empty()) m_.extensionsUsed.push_back("KHR_lights_punctual");
  for (tinygltf::Node& node : lod_nodes_) m_.nodes.push_back(std::move(node));
  if (options_.lods > 0) m_.extensionsUsed.push_back("MSFT_lod");
  m_.scenes.push_back(scene_);
  return {std::move(m_), fallback_bytes_, std::move(view_extensions_), std::move(images_)};
}

/// The scene as a tinygltf model with all binary data in buffer 0 (no URI; with Meshopt
/// compression, buffer 1 is the fallback) and the extensions of the encoded buffer views. With
/// `image_files` (texture_file_names(), one per texture), each used texture's image refers to
/// its file instead and the images are returned with their file names.
SceneModel scene_model(const SceneAssets& assets, const GltfSceneOptions& options,
                       const std::vector<std::string>* image_files = nullptr) {
  require_valid_assets(assets, kGltfRules, "scene assets");
  SceneModelBuilder builder(assets, options, image_files);
  builder.add_textures();
  builder.add_materials();
  builder.add_meshes();
  builder.add_instances();
  if (options.camera_and_lights) builder.add_camera_and_lights();
  return builder.finish();
}

/// A scene's glTF JSON (buffers without URIs), the bytes of buffer 0 and, with image files,
/// the images.
struct EncodedScene {
  nlohmann::json doc;
  std::vector<unsigned char> bin;
  std::vector<std::pair<std::string, std::string>> images;  ///< (file name, image bytes)
};

/// scene_model() serialised: buffer 0 holds `bin`; with Meshopt compression buffer 1 is the
/// EXT_meshopt_compression fallback, which holds no bytes.
EncodedScene encode_scene(const SceneAssets& assets, const GltfSceneOptions& options,
                          const std::vector<std::string>* image_files = nullptr) {
  SceneModel model = scene_model(assets, options, image_files);
  tinygltf::Model& m = model.model;
  EncodedScene scene;
  scene.bin.swap(m.buffers[0].data);
  scene.images = std::move(model.images);
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  writer.WriteGltfSceneToStream(&m, out, false, false);
  scene.doc = nlohmann::json::parse(out.str());
  scene.doc["buffers"][0] = {{"byteLength", scene.bin.size()}};
  if (options.compression == GltfCompression::Meshopt) {
    scene.doc["buffers"][1] = {{"byteLength", model.fallback_bytes},
                               {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}};
    for (const auto& [view, extensions] : model.view_extensions)
      scene.doc["bufferViews"][static_cast<size_t>(view)]["extensions"] = extensions;
  }
  for (const auto& [key, value] : options.scene_extras.items())
    scene.doc["scenes"][0]["extras"][key] = value;
  return scene;
}

/// Writes `bytes` to a fresh temporary file beside `target` (flushed) and returns its path.
std::filesystem::path stage_file(const std::filesystem::path& target, std::string_view bytes) {
  std::string tmp = target.string() + ".tmp-XXXXXX";
  const int fd = mkstemp(tmp.data());
  if (fd < 0) {
    throw EnvironmentError("cannot write " + target.string() + ": " + std::strerror(errno));
  }
  ::close(fd);
  try {
    write_file_atomically(tmp, bytes);
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
  return tmp;
}

void rename_or_throw(const std::filesystem::path& from, const std::filesystem::path& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0) {
    throw EnvironmentError("cannot write " + to.string() + ": " + std::strerror(errno));
  }
}

}  // namespace

std::string model_to_glb(const DsModel& model, const GltfModelOptions& options) {
  tinygltf::Model m = new_model();
  const int skin_mat = add_material(m, "skin", options.skin_alpha);
  const int inner_mat = add_material(m, "inner", options.inner_alpha);
  tinygltf::Scene scene;
  scene.name = model.name;
  for (const DsSurface& s : model.surfaces) {
    const DsMesh& mesh = s.mesh;
    std::vector<float> pos, front, back;
    for (auto vh : mesh.vertices()) {
      const auto& p = mesh.point(vh);
      const auto& d = mesh.data(vh);
      for (int k = 0; k < 3; ++k) {
        pos.push_back(static_cast<float>(p[k]));
        front.push_back(static_cast<float>(d.front[k]));
        back.push_back(static_cast<float>(d.back[k]));
      }
    }
    std::vector<float> normals, flipped;
    for (glm::dvec3 n : vertex_normals(mesh)) {
      if (n == glm::dvec3(0.0)) n = {0, 1, 0};  // glTF normals must be unit length
      for (int k = 0; k < 3; ++k) {
        normals.push_back(static_cast<float>(n[k]));
        flipped.push_back(static_cast<float>(-n[k]));
      }
    }
    std::vector<uint32_t> idx, rev;
    for (auto fh : mesh.faces()) {
      std::array<uint32_t, 3> v;
      int k = 0;
      for (auto vh : mesh.fv_range(fh)) v[k++] = static_cast<uint32_t>(vh.idx());
      idx.insert(idx.end(), {v[0], v[1], v[2]});
      rev.insert(rev.end(), {v[0], v[2], v[1]});
    }
    const int apos = add_vec3_accessor(m, pos, true);
    const int mat = s.role == SurfaceRole::Skin ? skin_mat : inner_mat;
    tinygltf::Mesh gm;
    gm.name = s.name;
    for (int side = 0; side < 2; ++side) {
      tinygltf::Primitive prim;
      prim.mode = TINYGLTF_MODE_TRIANGLES;
      prim.material = mat;
      prim.attributes["POSITION"] = apos;
      prim.attributes["NORMAL"] = add_vec3_accessor(m, side == 0 ? normals : flipped, false);
      prim.attributes["COLOR_0"] = add_vec3_accessor(m, side == 0 ? front : back, false);
      prim.indices = add_index_accessor(m, side == 0 ? idx : rev);
      gm.primitives.push_back(prim);
    }
    m.meshes.push_back(gm);
    tinygltf::Node node;
    node.name = s.name;
    node.mesh = static_cast<int>(m.meshes.size()) - 1;
    m.nodes.push_back(node);
    scene.nodes.push_back(static_cast<int>(m.nodes.size()) - 1);
  }
  m.scenes.push_back(scene);
  return to_glb(m);
}

GltfGeometryCounts count_glb_geometry(std::string_view glb) {
  const auto refuse = [](const std::string& why) {
    return EnvironmentError("not a binary glTF file: " + why);
  };
  const auto u32 = [&glb](size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, glb.data() + at, 4);
    return v;
  };
  if (glb.size() < 20 || glb.substr(0, 4) != "glTF") throw refuse("no glTF header");
  const size_t json_bytes = u32(12);
  if (u32(16) != 0x4E4F534Au || json_bytes > glb.size() - 20) throw refuse("no JSON chunk");
  const nlohmann::json doc =
      nlohmann::json::parse(glb.substr(20, json_bytes), nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) throw refuse("its JSON chunk does not parse");
  GltfGeometryCounts counts;
  try {
    const nlohmann::json& nodes = doc.at("nodes");
    std::vector<size_t> todo;
    for (const auto& n : doc.at("scenes").at(doc.value("scene", 0)).at("nodes"))
      todo.push_back(n.get<size_t>());
    while (!todo.empty()) {
      const nlohmann::json& node = nodes.at(todo.back());
      todo.pop_back();
      for (const auto& child : node.value("children", nlohmann::json::array()))
        todo.push_back(child.get<size_t>());
      // Collision hulls are not drawn.
      if (!node.contains("mesh") ||
          node.value("extras", nlohmann::json::object()).contains("collision"))
        continue;
      for (const auto& p : doc.at("meshes").at(node.at("mesh").get<size_t>()).at("primitives")) {
        counts.triangles +=
            doc.at("accessors").at(p.at("indices").get<size_t>()).at("count").get<size_t>() / 3;
        counts.vertices += doc.at("accessors")
                               .at(p.at("attributes").at("POSITION").get<size_t>())
                               .at("count")
                               .get<size_t>();
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw refuse(e.what());
  }
  return counts;
}

std::string section_to_glb(const CrossSection& section) {
  tinygltf::Model m = new_model();
  std::vector<float> pos, normal, colour;
  for (size_t i = 0; i < section.position.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      pos.push_back(static_cast<float>(section.position[i][k]));
      normal.push_back(static_cast<float>(section.plane.normal[k]));
      colour.push_back(static_cast<float>(section.colour[i][k]));
    }
  }
  std::vector<uint32_t> idx;
  for (const glm::uvec3& t : section.triangle) idx.insert(idx.end(), {t.x, t.y, t.z});
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = add_material(m, "cut face", 1.0, true);
  prim.attributes["POSITION"] = add_vec3_accessor(m, pos, true);
  prim.attributes["NORMAL"] = add_vec3_accessor(m, normal, false);
  prim.attributes["COLOR_0"] = add_vec3_accessor(m, colour, false);
  prim.indices = add_index_accessor(m, idx);
  tinygltf::Mesh mesh;
  mesh.name = "cross-section";
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = "cross-section";
  node.mesh = 0;
  m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  m.scenes.push_back(scene);
  return to_glb(m);
}

void write_model_glb(const std::filesystem::path& path, const DsModel& model,
                     const GltfModelOptions& options) {
  write_file_atomically(path, model_to_glb(model, options));
}

std::string scene_to_glb(const SceneAssets& assets, const GltfSceneOptions& options) {
  const EncodedScene scene = encode_scene(assets, options);
  // GLB (glTF 2.0 §4.4): a 12-byte header, the JSON chunk padded with spaces, the BIN chunk
  // padded with zeros, each length a multiple of 4, little-endian.
  std::string json = scene.doc.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const size_t bin_bytes = (scene.bin.size() + 3) / 4 * 4;
  std::string glb;
  glb.reserve(28 + json.size() + bin_bytes);
  auto u32 = [&glb](uint32_t v) {
    for (int k = 0; k < 4; ++k) glb += static_cast<char>((v >> (8 * k)) & 0xff);
  };
  glb += "glTF";
  u32(2);
  u32(static_cast<uint32_t>(12 + 8 + json.size() + (bin_bytes == 0 ? 0 : 8 + bin_bytes)));
  u32(static_cast<uint32_t>(json.size()));
  glb += "JSON";
  glb += json;
  if (bin_bytes > 0) {
    u32(static_cast<uint32_t>(bin_bytes));
    glb += std::string("BIN\0", 4);
    glb.append(reinterpret_cast<const char*>(scene.bin.data()), scene.bin.size());
    glb.resize(glb.size() + bin_bytes - scene.bin.size(), '\0');
  }
  return glb;
}

GltfCollision parse_gltf_collision(std::string_view name) {
  if (name == "none") return GltfCollision::None;
  if (name == "godot") return GltfCollision::Godot;
  if (name == "unreal") return GltfCollision::Unreal;
  if (name == "godot-rigid") return GltfCollision::GodotRigid;
  throw InternalError("unknown collision naming '" + std::string(name) +
                      "' (none, godot, unreal or godot-rigid)");
}

GltfCompression parse_gltf_compression(std::string_view name) {
  if (name == "none") return GltfCompression::None;
  if (name == "quantize") return GltfCompression::Quantize;
  if (name == "meshopt") return GltfCompression::Meshopt;
  throw InternalError("unknown glTF compression '" + std::string(name) +
                      "' (none, quantize or meshopt)");
}

void write_scene_gltf(const std::filesystem::path& path, const SceneAssets& assets,
                      const GltfSceneOptions& options) {
  namespace fs = std::filesystem;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".glb" && ext != ".gltf") {
    throw InternalError("scene export: unknown extension '" + path.extension().string() + "' of " +
                        path.string() + " (expected .glb or .gltf)");
  }
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw EnvironmentError("cannot write " + path.string() + ": no directory " + dir.string());
  }
  if (ext == ".glb") {
    write_file_atomically(path, scene_to_glb(assets, options));
    return;
  }
  // .gltf: the textures as image files beside it, written first (each atomically).
  const std::vector<std::string> image_files = texture_file_names(path, assets, options.textures);
  EncodedScene scene = encode_scene(assets, options, &image_files);
  for (const auto& [name, bytes] : scene.images) write_file_atomically(dir / name, bytes);
  // .gltf: buffer 0 is the .bin beside it.
  fs::path bin_path = path;
  bin_path.replace_extension(".bin");
  const std::vector<unsigned char>& bin = scene.bin;
  scene.doc["buffers"][0]["uri"] = uri_encode(bin_path.filename().string());
  const std::string json_text = scene.doc.dump(2) + "\n";

  const fs::path bin_tmp =
      stage_file(bin_path, std::string_view(reinterpret_cast<const char*>(bin.data()), bin.size()));
  fs::path json_tmp;
  try {
    json_tmp = stage_file(path, json_text);
    rename_or_throw(bin_tmp, bin_path);
  } catch (...) {
    ::unlink(bin_tmp.c_str());
    if (!json_tmp.empty()) ::unlink(json_tmp.c_str());
    throw;
  }
  try {
    rename_or_throw(json_tmp, path);
  } catch (...) {
    ::unlink(json_tmp.c_str());
    ::unlink(bin_path.c_str());
    throw;
  }
}

}  // namespace cutaway
