// glTF buffers: buffer views and accessors appended to a glTF model, and a scene's vertex
// attributes and indices written as its compression asks (float32, KHR_mesh_quantization or
// EXT_meshopt_compression through meshoptimizer). A part of the glTF export (gltf_export.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "export/gltf_export.h"

namespace cutaway::gltf {

/// Appends `bytes` bytes at `data` to buffer 0 of `m` as a new buffer view (4-byte aligned,
/// of `target`); returns the view's index.
int add_view(tinygltf::Model& m, const void* data, size_t bytes, int target);

/// Appends #V x 3 float32 `xyz` as a VEC3 FLOAT accessor in its own view; `with_bounds`: with
/// min and max (POSITION needs them). Returns the accessor's index.
int add_vec3_accessor(tinygltf::Model& m, const std::vector<float>& xyz, bool with_bounds);

/// Appends a triangle list as an UNSIGNED_INT SCALAR accessor in its own view; returns its
/// index.
int add_index_accessor(tinygltf::Model& m, const std::vector<uint32_t>& idx);

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
  int positions(const std::vector<float>& xyz, MeshFrame& frame, const glm::dvec3* pivot);

  /// #V x 3 unit normals: normalized BYTE; with meshopt through the codec's octahedral filter
  /// (8-bit X/Y of the octahedral map, Z 1: the constant bytes cost nearly nothing and the
  /// directions are spread more evenly than on the cube of three BYTEs).
  int normals(const std::vector<float>& xyz);

  /// #V x 4 tangents (unit xyz, w +-1): float without compression, else normalized BYTE (the
  /// codec alone with meshopt).
  int tangents(const std::vector<float>& xyzw);

  /// #V x 3 linear RGB colours in 0..1: normalized UNSIGNED_SHORT.
  int colours(const std::vector<float>& rgb);

  /// #V x 2 texture coordinates.
  int uvs(const std::vector<float>& xy);

  /// A triangle list over `vertices` vertices.
  int indices(const std::vector<uint32_t>& idx, size_t vertices);

 private:
  /// The positions quantized over the cube of half size frame.scale about frame.offset (a
  /// scale of 0 taken as 1); frame.scale then maps the stored integers back to metres.
  int quantized_positions(const std::vector<float>& xyz, MeshFrame& frame);

  /// positions() about `pivot`.
  int positions_about(const std::vector<float>& xyz, const glm::dvec3& pivot, MeshFrame& frame);

  /// A VEC3 accessor of `xyz` (each in lo..1): float without compression, else normalized
  /// components of T (BYTE or UNSIGNED_SHORT, glTF type `component`), each element padded to
  /// 4 of them so that it is 4-byte aligned.
  template <typename T>
  int vec3(const std::vector<float>& xyz, std::vector<T> q, int component, float lo);

  /// An accessor over `count` elements `stride` bytes apart (the element itself first); with
  /// meshopt, `filter` names the EXT_meshopt_compression filter `data` was encoded with.
  int accessor(const void* data, size_t count, size_t stride, int component, int type,
               bool normalized, std::vector<double> lo = {}, std::vector<double> hi = {},
               const char* filter = nullptr);

  /// A view of `count` elements of `size` bytes in the fallback buffer (byteStride
  /// `view_stride`, 0 for none) whose bytes are `packed`, meshoptimizer's encoding in `mode`
  /// (with `filter`, when not null).
  int encoded_view(const std::vector<unsigned char>& packed, size_t count, size_t size,
                   size_t view_stride, const char* mode, int target, const char* filter = nullptr);

  tinygltf::Model& m_;
  GltfCompression compression_;
  size_t fallback_ = 0;
  std::vector<std::pair<int, nlohmann::json>> view_extensions_;
};

}  // namespace cutaway::gltf
