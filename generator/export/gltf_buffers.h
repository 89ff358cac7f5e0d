// glTF buffers: buffer views and accessors appended to a glTF model, and a scene's vertex
// attributes and indices written as its compression asks (float32, KHR_mesh_quantization or
// EXT_meshopt_compression through meshoptimizer). A part of the glTF export (gltf_export.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "assets/scene_assets.h"
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
/// stored value as a reader takes it (normalized SHORT: -1..1; meshopt's UNSIGNED_SHORT grid
/// steps: the integers themselves). Identity for float positions.
struct MeshFrame {
  glm::dvec3 offset{0.0};
  double scale = 1.0;
};

/// The grids a meshopt scene is quantized on, each the same for all its meshes (gltfpack's
/// rule, -vp 14 -vt 12: the steps follow the scene, not each mesh, so a piece carries no more
/// precision than the scene can show, and the codec's deltas stay small).
struct MeshoptGrid {
  /// Metres between position steps: the largest side of the box that holds every written
  /// mesh in its own frame, over 16383 (14 bits); 0: each mesh over its own 14-bit cube.
  double position_step = 0;
  /// Steps per unit of texture coordinate: twice the largest side (texels) of the scene's
  /// textures, so a coordinate lands at most a quarter texel off; 0: 16 bits over 0..1 (or
  /// float), without a texture transform.
  double uv_steps = 0;
  /// The texture coordinate of step 0: the whole numbers below the smallest coordinate.
  glm::dvec2 uv_origin{0.0};
};

/// The grid of meshopt_grid() for `meshes` (those written) and the scene's `textures`. The uv
/// grid is left out (uv_steps 0) where no texture is given or where the coordinates span more
/// than 65535 steps from the origin in u or v (they do not fit UNSIGNED_SHORT). Source:
/// gltfpack's quantization (meshoptimizer, gltf/stream.cpp), steps chosen for the textures.
MeshoptGrid meshopt_grid(const std::vector<const AssetMesh*>& meshes,
                         const std::vector<AssetTexture>& textures);

/// Writes a scene's vertex attributes and indices as the compression mode asks:
/// - None: float32 attributes, one tightly packed buffer view each, in buffer 0;
/// - Quantize (KHR_mesh_quantization): POSITION as normalized SHORT over the mesh's bounding
///   cube (MeshFrame, stride 8), NORMAL as normalized BYTE (stride 4), COLOR_0 as normalized
///   UNSIGNED_SHORT (stride 8), TEXCOORD_0 as normalized UNSIGNED_SHORT when every coordinate
///   lies in 0..1 (else float); still one plain buffer view each, in buffer 0;
/// - Meshopt: the Quantize data on the scene's MeshoptGrid (positions as UNSIGNED_SHORT steps
///   from the corner of the mesh's box, grid_positions(), or as SHORT about a pivot;
///   texture coordinates as normalized UNSIGNED_SHORT steps, which a KHR_texture_transform of
///   uv_transform() on every texture maps back; normals and tangents through the OCTAHEDRAL
///   filter), encoded by meshoptimizer's vertex or index codec: the vertex attributes of every
///   mesh in one view per element size and filter (finish(); one block of JSON and one codec
///   tail each, as gltfpack writes them), the indices of every primitive in one view per index
///   size (index codec version 1, which the extension requires: a primitive counting from 0
///   again costs a few bytes),
///   into buffer 0 (EXT_meshopt_compression); the views themselves lie in buffer 1, a fallback
///   that holds no bytes (its byteLength is fallback_bytes()).
/// Indices are UNSIGNED_SHORT when the mesh has at most 65535 vertices (65535 is the primitive
/// restart value, never an index), else UNSIGNED_INT. In every mode an accessor whose data
/// equals one written before is not written again: the earlier one is returned.
class SceneBuffers {
 public:
  /// `grid`: the scene's grid, used with Meshopt only.
  SceneBuffers(tinygltf::Model& m, GltfCompression compression, const MeshoptGrid& grid = {})
      : m_(m), compression_(compression), grid_(grid) {}

  tinygltf::Model& model() { return m_; }
  /// Writes what is held back (with Meshopt: the shared vertex and index views) and points the
  /// accessors at it; run once, after the last mesh.
  void finish();
  GltfCompression compression() const { return compression_; }
  /// Whether texture coordinates are written on the grid's uv steps: every texture then needs
  /// the KHR_texture_transform of uv_transform() (offset, scale per axis).
  bool uvs_on_grid() const {
    return compression_ == GltfCompression::Meshopt && grid_.uv_steps > 0;
  }
  std::pair<glm::dvec2, glm::dvec2> uv_transform() const {
    return {grid_.uv_origin, glm::dvec2(65535.0 / grid_.uv_steps)};
  }
  size_t fallback_bytes() const { return fallback_; }
  /// (buffer view, its "extensions" object) of each encoded view: tinygltf does not write
  /// extensions of buffer views, so they are added to the serialised JSON.
  const std::vector<std::pair<int, nlohmann::json>>& view_extensions() const {
    return view_extensions_;
  }

  /// #V x 3 positions (metres); returns the accessor and sets `frame`, decided by `extent_of`
  /// (#W x 3 positions that hold `xyz`: those of the whole mesh, so that the accessors of its
  /// primitives share one frame). With a `pivot` (metres), the frame's offset is the pivot:
  /// float positions are stored relative to it, and quantized ones over the cube about it that
  /// holds `extent_of`.
  int positions(const std::vector<float>& xyz, const std::vector<float>& extent_of,
                MeshFrame& frame, const glm::dvec3* pivot);

  /// #V x 3 unit normals: normalized BYTE; with meshopt through the codec's octahedral filter
  /// (8-bit X/Y of the octahedral map, Z 1: the constant bytes cost nearly nothing and the
  /// directions are spread more evenly than on the cube of three BYTEs).
  int normals(const std::vector<float>& xyz);

  /// #V x 4 tangents (unit xyz, w +-1): float without compression, else normalized BYTE (with
  /// meshopt through the octahedral filter, w kept).
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

  /// Meshopt positions without a pivot, as gltfpack writes them: UNSIGNED_SHORT steps of the
  /// scene grid from the corner `lo` of the box (lo, hi) that holds the mesh (frame: offset
  /// lo, scale one step), so the codec never sees a sign flip between neighbours.
  int grid_positions(const std::vector<float>& xyz, const glm::dvec3& lo, const glm::dvec3& hi,
                     MeshFrame& frame);

  /// positions() about `pivot`.
  int positions_about(const std::vector<float>& xyz, const std::vector<float>& extent_of,
                      const glm::dvec3& pivot, MeshFrame& frame);

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

  /// Meshopt vertex attributes held back for one shared view: elements of `stride` bytes
  /// through `filter` (empty: none), and each accessor's index in the model.
  struct SharedStream {
    size_t stride = 0;
    std::string filter;
    std::vector<unsigned char> bytes;
    std::vector<int> accessors;
  };

  /// Meshopt triangle lists held back for one shared view: indices of `size` bytes (2 or 4),
  /// each primitive's counting from 0, over at most `vertices` vertices, and each accessor's
  /// index in the model.
  struct SharedIndices {
    size_t size = 0;
    std::vector<uint32_t> idx;
    size_t vertices = 0;
    std::vector<int> accessors;
  };

  /// Where the bytes of a written accessor are kept until the file is written: in buffer 0,
  /// in held-back stream `stream` of shared_, or (as uint32 values) of shared_indices_.
  struct Held {
    int accessor = -1;
    enum { Buffer, Attributes, Indices } where = Buffer;
    size_t stream = 0;
    size_t offset = 0;  ///< bytes into its buffer or stream
    size_t bytes = 0;
  };

  /// The content key of an accessor: fnv1a64 of its `description` (what a reader makes of
  /// the bytes) and its `bytes`.
  static uint64_t content_key(const std::string& description, std::span<const unsigned char> bytes);

  /// The accessor written before with content key `key` whose bytes equal `bytes`, or -1.
  int written_before(uint64_t key, std::span<const unsigned char> bytes) const;

  tinygltf::Model& m_;
  GltfCompression compression_;
  /// Every accessor written, by content key: identical data (the skins of a variant's copies
  /// that differ only in their cut-face material, a piece repeated) is written once and its
  /// accessor shared, as gltfpack shares it.
  std::unordered_multimap<uint64_t, Held> written_;
  std::vector<SharedStream> shared_;
  std::vector<SharedIndices> shared_indices_;
  MeshoptGrid grid_;
  size_t fallback_ = 0;
  std::vector<std::pair<int, nlohmann::json>> view_extensions_;
};

}  // namespace cutaway::gltf
