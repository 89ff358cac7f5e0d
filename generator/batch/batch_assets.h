// The assets of a batch (doc/batch-format.md, Assets): the plan (every variant to build and
// every asset it makes, named and fingerprinted before any work) and the building of one
// variant's assets as file bytes and manifest records.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "batch/batch.h"
#include "batch/variant_batch.h"
#include "scene/scene_builder.h"

namespace cutaway {

/// One variant of a batch: item `item`'s template with seed `seed`; it makes one asset per cut
/// of the item. Shards of a batch are contiguous runs of units (Shard over the unit count).
struct BatchUnit {
  size_t item = 0;
  uint64_t seed = 0;
  size_t first_asset = 0;  ///< its assets are first_asset .. first_asset + cuts - 1
};

/// One asset: the pieces of one variant cut one way.
struct BatchAsset {
  size_t unit = 0, item = 0, cut = 0;  ///< indices into the plan's units, the batch's items
                                       ///< and the item's cuts
  uint64_t seed = 0;
  std::string stem;        ///< TEMPLATE-SEED-CUT, e.g. "tomato-100-wedges-6"; files STEM.glb,
                           ///< STEM.png, and TEMPLATE-SEED.model.glb for the variant
  uint64_t inputs = 0;     ///< fingerprint of everything the asset's bytes depend on
  bool thumbnail = false;  ///< STEM.png is written (outputs.thumbnails, or in the sample)
  bool sample = false;     ///< on the contact sheet of `batch merge`
};

/// Every unit and asset of a batch, in batch order: items in order, seeds ascending, cuts in
/// order.
struct BatchPlan {
  std::vector<BatchUnit> units;
  std::vector<BatchAsset> assets;
};

/// The variants and assets of shard `shard` of `plan` (none: the whole plan): units
/// [first_unit, last_unit) and assets [first_asset, last_asset), contiguous (Shard over the
/// unit count; a shard of no variants, when there are more shards than variants, has no assets).
struct ShardRange {
  size_t first_unit = 0, last_unit = 0, first_asset = 0, last_asset = 0;
};
ShardRange shard_range(const BatchPlan& plan, const std::optional<Shard>& shard);

/// A cut as it appears in asset names: cut_label() with ':' turned into '-', e.g. "halves",
/// "wedges-6", "slices-8mm", "dice-12.5mm".
std::string cut_file_label(const CutSpec& cut);

/// The plan of `batch`. Each asset's fingerprint is fnv1a64 of a text holding this program's
/// version, the template's source_hash (its file and meshes), the seed, the variation, the
/// cut, the outputs and export options and `settings` (what else changes the bytes: the
/// diffusion backend and sampling chosen on the command line). The sample is
/// min(outputs.sample, assets) assets spread evenly: asset floor(k * assets / sample) for
/// k = 0 .. sample - 1.
/// @pre every item's tmpl is set (load_batch)
BatchPlan plan_batch(const Batch& batch, const std::string& settings);

/// One written file of an asset: its name in the output folder, and its bytes.
struct BatchFile {
  std::string name;
  std::string bytes;
};

/// One asset's line of the manifest (batch_manifest.h). Files are named relative to the
/// output folder; hashes are fnv1a64 of their bytes.
struct AssetRecord {
  std::string file;  ///< STEM.glb
  std::string template_name;
  uint64_t seed = 0;
  std::string cut;  ///< cut_label()
  size_t pieces = 0;
  size_t triangles = 0, vertices = 0;  ///< in `file`, as count_glb_geometry reads them
  double volume_m3 = 0;                ///< the pieces' volumes summed, cubic metres
  /// The pieces (0-based, in the file's node order) that hold a whole stone (a rigid surface,
  /// doc/template-format.md), in increasing order; empty without stones.
  std::vector<size_t> stone_pieces;
  uint64_t hash = 0;  ///< of `file`
  std::string model;  ///< TEMPLATE-SEED.model.glb, or empty
  uint64_t model_hash = 0;
  std::string thumbnail;  ///< STEM.png, or empty
  uint64_t thumbnail_hash = 0;
  /// The variant's interior volume files (TEMPLATE-SEED.volume.json first, then its flipbooks
  /// and .vdb) with their hashes, or none.
  std::vector<std::pair<std::string, uint64_t>> volume;
  uint64_t inputs = 0;  ///< BatchAsset::inputs
  friend bool operator==(const AssetRecord&, const AssetRecord&) = default;
};

/// Wall seconds of building assets, by stage.
struct UnitTimings {
  double variant = 0, cut = 0, bake = 0, export_glb = 0, thumbnail = 0;
};

/// One built asset: its record and its files (the model file with the unit's first asset only).
struct BuiltAsset {
  AssetRecord record;
  std::vector<BatchFile> files;
  UnitTimings seconds;  ///< what this asset took (the variant's time shared evenly by its cuts)
};

/// Renders a SceneAssets (a few pieces on the ground, grid_piece_assets) to PNG bytes.
using ThumbnailRenderer = std::function<std::string(const SceneAssets&)>;

/// How build_batch_unit works.
struct BatchBuildOptions {
  DiffusionFactory diffusion;  ///< required
  /// What of the diffusion backend changes colours (SceneBuildOptions::diffusion_settings);
  /// required with `cache`.
  std::string diffusion_settings;
  CutCache* cache = nullptr;  ///< the cut cache (cut_cache.h), or null: every asset is cut
  CapSampling sampling = CapSampling::Adaptive;
  ThumbnailRenderer thumbnail;  ///< required when the unit has an asset with a thumbnail
};

/// Builds unit `unit` of `plan`: the variant (make_variant with the item's variation), then
/// per cut its pieces (cut_scene_object: every piece kept, caps and skins baked into textures,
/// Perlin modulation seeded by the variant's seed) as one glTF binary, the pieces in place in
/// the object frame (metres, +Y up) with the template's materials, a camera framing them and
/// the studio lights; a thumbnail of the pieces laid cut face up when the asset has one; the DS
/// model when outputs.model. Deterministic: the same batch, plan and options give the same
/// bytes, whatever the thread count.
/// @throws InputError when the template cannot be read; InternalError when
///         options.diffusion is empty, or a thumbnail is due and options.thumbnail is empty
std::vector<BuiltAsset> build_batch_unit(const Batch& batch, const BatchPlan& plan, size_t unit,
                                         const BatchBuildOptions& options,
                                         UnitTimings* timings = nullptr);

}  // namespace cutaway
