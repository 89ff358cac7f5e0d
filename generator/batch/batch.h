// A batch of cut assets (doc/batch-format.md): which templates, how many seeded variants of
// each, which cuts of every variant, and what is written per asset. Parsed and validated by
// io/batch_parser.h; built by batch/batch_runner.h, one shard at a time.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "base/error.h"
#include "diffusion/diffusion.h"
#include "export/gltf_export.h"
#include "model/template.h"
#include "pieces/cut_spec.h"
#include "volume/interior_volume.h"

namespace cutaway {

/// One `items` entry: `count` variants of one template, seeds seed .. seed + count - 1, each
/// cut in every way of `cuts` (one asset per variant and cut).
struct BatchItem {
  std::string template_name;  ///< the template's own name (its `name` field)
  std::string template_path;  ///< the resolved template file
  /// The parsed template (load_batch reads each file once; items naming it share it), null
  /// after parse_batch alone
  std::shared_ptr<const Template> tmpl;
  int count = 1;              ///< variants, 1..100000
  uint64_t seed = 0;          ///< the first variant's seed
  double variation = 1.0;     ///< scales the template's variation amount, 0..10
  std::vector<CutSpec> cuts;  ///< at least one, lengths in metres
  FileLoc loc;                ///< where the item is written
  std::string path;           ///< its field path, e.g. "items[2]"
};

/// What is written per asset besides the pieces' .glb.
struct BatchOutputs {
  bool model = false;       ///< the variant's DS model, STEM.model.glb (see-through surfaces)
  bool thumbnails = false;  ///< a PNG of every asset's pieces, STEM.png
  int thumbnail_px = 256;   ///< thumbnail width in pixels (height 3/4 of it), 64..1024
  /// Assets of the contact sheet `batch merge` writes, spread evenly over the batch (0..64);
  /// their thumbnails are written even without `thumbnails`.
  int sample = 12;
  /// Each variant's interior volume (doc/interior-volume.md): TEMPLATE-SEED.volume.json with
  /// its flipbooks and TEMPLATE-SEED.volume.vdb, `volume_voxels` along the skin's longest edge.
  bool volume = false;
  int volume_voxels = kDefaultVoxelsAcross;  ///< 8..200
};

/// A batch's glTF defaults: float32 vertex data (every engine reads it at its size; Godot 3
/// reads KHR_mesh_quantization's integers as raw positions, doc/engines.md), no camera or
/// lights, Godot's collision naming.
inline GltfSceneOptions batch_gltf_defaults() {
  GltfSceneOptions gltf;
  gltf.compression = GltfCompression::None;
  gltf.camera_and_lights = false;
  gltf.collision = GltfCollision::Godot;
  return gltf;
}

/// How the assets are exported.
struct BatchExport {
  /// compression, levels of detail, texture format; camera and lights off unless asked
  /// (batch_gltf_defaults)
  GltfSceneOptions gltf = batch_gltf_defaults();
  double texels_per_mm = 8.6;   ///< baked cut-face texture density, 0.1..100
  double perlin = 1.0;          ///< Perlin colour modulation strength, 0..10
  int cube = kDefaultCubeSize;  ///< PMVC cube-map texels per face edge, 2..256
  bool power_of_two = false;    ///< baked textures' sides powers of two, not multiples of 4
};

/// The most assets (items' count x cuts, over all items) one batch may make: its plan holds
/// every asset's name and inputs (about 130 bytes each) before the first is built.
inline constexpr long long kMaxBatchAssets = 1'000'000;

/// A whole parsed, validated batch.
struct Batch {
  std::string name;  ///< [a-z0-9_-]+
  std::string file;  ///< path it was read from
  std::vector<BatchItem> items;
  BatchOutputs outputs;
  BatchExport export_options;
};

}  // namespace cutaway
