#include "batch/batch_assets.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>

#include <glm/trigonometric.hpp>
#include <nlohmann/json.hpp>

#include "assets/asset_camera.h"
#include "base/error.h"
#include "base/source_fingerprint.h"
#include "base/timer.h"
#include "batch/variant_batch.h"
#include "cache/cached_cut.h"
#include "cut/piece_views.h"
#include "export/gltf_export.h"
#include "export/volume_files.h"
#include "material/colour_modulation.h"
#include "placement/collision_shape.h"
#include "variation/variation.h"

namespace cutaway {

namespace {

using Clock = std::chrono::steady_clock;

/// The text an asset's fingerprint hashes: everything its bytes depend on.
std::string fingerprint_text(const Batch& b, const BatchItem& item, uint64_t seed,
                             const CutSpec& cut, bool thumbnail, const std::string& settings) {
  const nlohmann::ordered_json j = {
      {"cutaway", CUTAWAY_VERSION},
      {"sources", source_fingerprint()},
      {"template", hex64(item.tmpl->source_hash)},
      {"seed", seed},
      {"variation", item.variation},
      {"cut", cut_exact_text(cut)},
      {"model", b.outputs.model},
      {"volume", b.outputs.volume ? b.outputs.volume_voxels : 0},
      {"thumbnail", thumbnail ? b.outputs.thumbnail_px : 0},
      {"compress", static_cast<int>(b.export_options.gltf.compression)},
      {"lods", b.export_options.gltf.lods},
      {"textures", static_cast<int>(b.export_options.gltf.textures)},
      {"camera_and_lights", b.export_options.gltf.camera_and_lights},
      {"collision", static_cast<int>(b.export_options.gltf.collision)},
      {"pivot_at_centre_of_mass", b.export_options.gltf.pivot_at_centre_of_mass},
      {"texture_fallback", b.export_options.gltf.texture_fallback},
      {"texels_per_mm", b.export_options.texels_per_mm},
      {"perlin", b.export_options.perlin},
      {"cube", b.export_options.cube},
      {"power_of_two", b.export_options.power_of_two},
      {"settings", settings}};
  return j.dump();
}

/// The direction the asset camera looks from: front right, 35 degrees up.
glm::dvec3 asset_view_direction() {
  const double up = glm::radians(35.0), around = glm::radians(30.0);
  return {std::cos(up) * std::sin(around), std::sin(up), std::cos(up) * std::cos(around)};
}

}  // namespace

std::string cut_file_label(const CutSpec& cut) {
  std::string label = cut_label(cut);
  for (char& c : label)
    if (c == ':') c = '-';
  return label;
}

ShardRange shard_range(const BatchPlan& plan, const std::optional<Shard>& shard) {
  const Shard s = shard.value_or(Shard{});
  const int units = static_cast<int>(plan.units.size());
  ShardRange r;
  r.first_unit = static_cast<size_t>(s.begin(units));
  r.last_unit = static_cast<size_t>(s.end(units));
  const auto first_asset_of = [&](size_t u) {
    return u < plan.units.size() ? plan.units[u].first_asset : plan.assets.size();
  };
  r.first_asset = first_asset_of(r.first_unit);
  r.last_asset = first_asset_of(r.last_unit);
  return r;
}

BatchPlan plan_batch(const Batch& batch, const std::string& settings) {
  BatchPlan plan;
  for (size_t i = 0; i < batch.items.size(); ++i) {
    const BatchItem& item = batch.items[i];
    for (int v = 0; v < item.count; ++v) {
      const uint64_t seed = item.seed + static_cast<uint64_t>(v);
      plan.units.push_back({i, seed, plan.assets.size()});
      for (size_t c = 0; c < item.cuts.size(); ++c) {
        BatchAsset a;
        a.unit = plan.units.size() - 1;
        a.item = i;
        a.cut = c;
        a.seed = seed;
        a.stem =
            item.template_name + "-" + std::to_string(seed) + "-" + cut_file_label(item.cuts[c]);
        plan.assets.push_back(std::move(a));
      }
    }
  }
  const size_t n = plan.assets.size();
  const size_t sample = std::min(n, static_cast<size_t>(batch.outputs.sample));
  for (size_t k = 0; k < sample; ++k) plan.assets[k * n / sample].sample = true;
  for (BatchAsset& a : plan.assets) {
    a.thumbnail = batch.outputs.thumbnails || a.sample;
    const BatchItem& item = batch.items[a.item];
    CUTAWAY_CHECK(item.tmpl);  // load_batch read it
    a.inputs =
        fnv1a64(fingerprint_text(batch, item, a.seed, item.cuts[a.cut], a.thumbnail, settings));
  }
  return plan;
}

namespace {

/// The variant of a batch unit and its diffusion backend, made when first asked for (a unit
/// whose cuts are all in the cut cache and that writes no DS model needs neither).
class LazyVariant {
 public:
  LazyVariant(const Template& tmpl, uint64_t seed, const BatchBuildOptions& options)
      : tmpl_(tmpl), seed_(seed), options_(options) {}
  const Variant& variant() {
    if (!variant_) {
      const auto t0 = Clock::now();
      variant_ = make_variant(tmpl_, seed_);
      seconds_ += seconds_since(t0);
    }
    return *variant_;
  }
  /// One backend (its BVH) serves every cut of the variant.
  const DiffusionBackend& diffusion() {
    if (!diffusion_) {
      const Variant& v = variant();
      const auto t0 = Clock::now();
      diffusion_ = options_.diffusion(v.model);
      seconds_ += seconds_since(t0);
    }
    return *diffusion_;
  }
  /// Wall seconds spent making the variant and its backend so far.
  double seconds() const { return seconds_; }

 private:
  const Template& tmpl_;
  uint64_t seed_;
  const BatchBuildOptions& options_;
  std::optional<Variant> variant_;
  std::unique_ptr<DiffusionBackend> diffusion_;
  double seconds_ = 0;
};

/// One asset's pieces: the unit's variant cut by `cut_spec` into a new SceneAssets named
/// `stem` (its materials and baked textures), every piece kept, Perlin modulation seeded by
/// `seed`, with collision shapes when the batch exports them; through the cut cache.
CachedCut cut_asset(SceneAssets& assets, const Batch& batch, const Template& tmpl,
                    LazyVariant& variant, uint64_t seed, const CutSpec& cut_spec,
                    const std::string& stem, const BatchBuildOptions& options, ObjectCutStats& st) {
  assets.name = stem;
  assets.background = {1, 1, 1};
  const PieceMaterials materials =
      add_piece_materials(assets, tmpl.name, tmpl.skin_material, tmpl.cut_material);
  ObjectCutOptions cut;
  cut.cut = cut_spec;
  cut.modulation_seed = seed;
  cut.perlin = batch.export_options.perlin;
  cut.atlas.texels_per_m = 1000 * batch.export_options.texels_per_mm;
  cut.atlas.power_of_two = cut.skin.power_of_two = batch.export_options.power_of_two;
  cut.sampling = options.sampling;
  const CollisionShapeOptions hulls;
  const CollisionShapeOptions* collision =
      writes_hull_nodes(batch.export_options.gltf.collision) ? &hulls : nullptr;
  const std::string object = asset_name(stem);
  const std::string key = cut_cache_key({tmpl.source_hash, tmpl.variation_amount, seed, object,
                                         options.diffusion_settings, &cut, collision});
  const CutEntry entry = make_cut_entry(
      options.cache, key, tmpl, collision, [&](SceneAssets& own, const PieceMaterials& given) {
        return CutPieces(std::move(*cut_object(own, variant.variant(), seed, given, object,
                                               variant.diffusion(), cut, st)));
      });
  return add_cut_entry(entry, assets, materials);
}

/// The asset's glTF binary: `object`'s pieces placed in `assets` as they lie in the object frame
/// (with their collision hulls when the batch exports them), a camera framing them and the
/// studio lights; KTX2 textures kept in `cache` (may be null). Fills the record's pieces,
/// volume, hash and geometry counts.
std::string asset_glb(SceneAssets& assets, CachedCut& cut, const Batch& batch, CutCache* cache,
                      AssetRecord& r) {
  CutPieces& object = cut.pieces;
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (size_t q = 0; q < object.meshes.size(); ++q) {
    for (const glm::dvec3& p : object.shapes[q].position) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    r.volume_m3 += object.infos[q].volume_m3;
    const std::vector<std::string>& parts = object.infos[q].parts;
    if (std::find(parts.begin(), parts.end(), "stone") != parts.end()) r.stone_pieces.push_back(q);
    assets.instances.push_back({object.meshes[q].name,
                                static_cast<int>(assets.meshes.size()),
                                {1, 0, 0, 0},
                                {0, 0, 0},
                                object.infos[q]});
    if (!cut.collision.empty())
      assets.instances.back().collision = collision_hulls(cut.collision[q]);
    assets.meshes.push_back(std::move(object.meshes[q]));
  }
  r.pieces = object.meshes.size();
  assets.camera = frame_box(lo, hi, asset_view_direction(), 40, 4.0 / 3);
  light_like_studio(assets);
  GltfSceneOptions gltf = batch.export_options.gltf;
  if (cache) gltf.texture_store = cache->blob_store();
  std::string glb = scene_to_glb(assets, gltf);
  r.hash = fnv1a64(glb);
  const GltfGeometryCounts counts = count_glb_geometry(glb);
  r.triangles = counts.triangles;
  r.vertices = counts.vertices;
  return glb;
}

}  // namespace

std::vector<BuiltAsset> build_batch_unit(const Batch& batch, const BatchPlan& plan, size_t unit,
                                         const BatchBuildOptions& options, UnitTimings* timings) {
  if (!options.diffusion) throw InternalError("build_batch_unit: no diffusion backend");
  UnitTimings local;
  UnitTimings& t = timings ? *timings : local;
  t = UnitTimings{};
  const BatchUnit& u = plan.units.at(unit);
  const BatchItem& item = batch.items[u.item];
  auto t0 = Clock::now();
  CUTAWAY_CHECK(item.tmpl);  // load_batch read it
  Template tmpl = *item.tmpl;
  tmpl.variation_amount *= item.variation;
  LazyVariant variant(tmpl, u.seed, options);
  // The DS model is one file per variant, shared by its cuts' records: encoded once (its time
  // counts as the variant's, as do the variant's and its backend's when a cut first needs them).
  const std::string model_file = item.template_name + "-" + std::to_string(u.seed) + ".model.glb";
  std::string model =
      batch.outputs.model ? model_to_glb(variant.variant().model, GltfModelOptions{}) : "";
  const uint64_t model_hash = fnv1a64(model);
  // The interior volume likewise: one set of files per variant, its time the variant's.
  std::vector<NamedFile> volume;
  if (batch.outputs.volume) {
    const DsModel& ds = variant.variant().model;
    Outcome<InteriorVolume> grid =
        volume_grid(ds, voxel_length_across(ds, batch.outputs.volume_voxels));
    CUTAWAY_CHECK(grid.has_value());  // 200 voxels across stay below kMaxVolumeVoxels
    const ColourModulation modulation(tmpl.npr, u.seed);
    const DiffusionBackend& diffusion = variant.diffusion();
    Outcome<std::vector<NamedFile>> files =
        volume_files(sample_interior_volume(ds, diffusion, std::move(*grid), diffusion.threads(),
                                            &modulation, batch.export_options.perlin),
                     item.template_name + "-" + std::to_string(u.seed) + ".volume", tmpl.name,
                     static_cast<int64_t>(u.seed), true);
    if (!files) throw InputError({batch.file, 0, 0}, "outputs.volume_voxels", files.reason());
    volume = std::move(*files);
  }
  std::vector<std::pair<std::string, uint64_t>> volume_record;
  for (const auto& [name, bytes] : volume) volume_record.emplace_back(name, fnv1a64(bytes));
  t.variant = seconds_since(t0);

  std::vector<BuiltAsset> out;
  for (size_t c = 0; c < item.cuts.size(); ++c) {
    const BatchAsset& a = plan.assets[u.first_asset + c];
    t0 = Clock::now();
    SceneAssets assets;
    ObjectCutStats st;
    const double before = variant.seconds();
    CachedCut object =
        cut_asset(assets, batch, tmpl, variant, u.seed, item.cuts[c], a.stem, options, st);
    const double made_variant = variant.seconds() - before;
    t.variant += made_variant;
    BuiltAsset built;
    UnitTimings& own = built.seconds;
    own.cut = seconds_since(t0) - st.seconds_bake - made_variant;
    own.bake = st.seconds_bake;

    // The thumbnail first: it shows the meshes that the glTF scene then takes over.
    std::string thumbnail;
    if (a.thumbnail) {
      if (!options.thumbnail)
        throw InternalError("build_batch_unit: a thumbnail is due and no renderer given");
      t0 = Clock::now();
      const int w = batch.outputs.thumbnail_px;
      thumbnail =
          options.thumbnail(grid_piece_assets(assets, object.pieces, PieceView::Up, w, w * 3 / 4));
      own.thumbnail = seconds_since(t0);
    }

    t0 = Clock::now();
    AssetRecord& r = built.record;
    r.file = a.stem + ".glb";
    r.template_name = item.template_name;
    r.seed = u.seed;
    r.cut = cut_label(item.cuts[c]);
    r.inputs = a.inputs;
    std::string glb = asset_glb(assets, object, batch, options.cache, r);
    built.files.push_back({r.file, std::move(glb)});
    if (batch.outputs.model) {
      r.model = model_file;
      r.model_hash = model_hash;
      if (c == 0) built.files.push_back({r.model, std::move(model)});
    }
    r.volume = volume_record;
    if (c == 0)
      for (auto& [name, bytes] : volume) built.files.push_back({name, std::move(bytes)});
    own.export_glb = seconds_since(t0);

    if (!thumbnail.empty()) {
      r.thumbnail = a.stem + ".png";
      r.thumbnail_hash = fnv1a64(thumbnail);
      built.files.push_back({r.thumbnail, std::move(thumbnail)});
    }
    t.cut += own.cut;
    t.bake += own.bake;
    t.export_glb += own.export_glb;
    t.thumbnail += own.thumbnail;
    out.push_back(std::move(built));
  }
  for (BuiltAsset& built : out) built.seconds.variant = t.variant / static_cast<double>(out.size());
  return out;
}

}  // namespace cutaway
