#include "io/batch_parser.h"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string>

#include <glm/vec3.hpp>

#include "export/engine_profile.h"
#include "io/format_fields.h"
#include "io/text_rules.h"
#include "io/yaml_reader.h"
#include "pieces/cut_spec.h"
#include "volume/interior_volume.h"
#include "volume/volume_cost.h"

namespace cutaway {

namespace {

/// The largest seed a batch may name: integers above 2^53 do not survive a JSON reader that
/// keeps numbers as doubles, and the manifest lists every seed.
constexpr int64_t kMaxBatchSeed = int64_t{1} << 53;

/// A seed: a whole number from 0 up (integer() refuses more than 9e15, below kMaxBatchSeed).
uint64_t parse_seed(const YamlField& f) {
  const int64_t v = f.integer();
  if (v < 0) f.fail("must not be negative");
  return static_cast<uint64_t>(v);
}

/// outputs.volume_voxels' range: voxels along the skin's longest edge (the cost may bound it
/// lower for a template: check_volume_cost).
constexpr int kMinBatchVolumeVoxels = 8, kMaxBatchVolumeVoxels = 200;

/// The cut fields of every item, kept for the checks load_batch makes once templates are read.
struct ParsedItem {
  YamlField item;                                       ///< the item's mapping
  std::vector<std::optional<YamlField>> length_fields;  ///< per cut
  std::vector<YamlField> cut_fields;                    ///< per cut
  std::optional<YamlField> seed_field;
};

/// The fields load_batch checks once templates are read.
struct ParsedBatch {
  std::vector<ParsedItem> items;
  /// Where a volume's cost is refused: outputs.volume_voxels, else outputs.volume (none when
  /// no volume is asked for).
  std::optional<YamlField> volume;
};

/// Fails at `field` when the volume of template `name` (within `extents`) that `b` asks for
/// would cost more than any volume may (check_volume_rays, its grid estimated from the extents
/// as volume_grid lays it over the skin), naming the most voxels across that fit.
void check_volume_cost(const Batch& b, const ObjectExtents& extents, const std::string& name,
                       const YamlField& field) {
  const glm::dvec3 box(2 * extents.radius_m, extents.height_m, 2 * extents.radius_m);
  const glm::dvec3 n = grid_voxels(box, std::max(box.x, box.y) / b.outputs.volume_voxels);
  const int cube = b.export_options.cube;
  const Check cost = check_volume_rays(n.x * n.y * n.z, cube);
  if (cost) return;
  const int most = most_voxels_across(box, cube);
  field.fail("template " + quoted(name) + ": " + cost.reason() + "; " +
             (most >= kMinBatchVolumeVoxels
                  ? "give volume_voxels " + std::to_string(most) + " or fewer"
                  : std::string("give a smaller export.cube")));
}

Batch parse(std::string_view text, const std::string& file, ParsedBatch* parsed) {
  const YamlField root = parse_yaml(text, file);
  Batch b;
  b.file = file;
  require_format(root, "cutaway-batch/1");
  root.allow_only({"format", "name", "seed", "units", "items", "outputs", "export"});
  b.name = parse_name(root);
  uint64_t seed = 0;
  if (auto x = root.get("seed")) seed = parse_seed(*x);
  double m = 1e-3;
  if (auto u = root.get("units")) m = parse_units(*u);
  std::filesystem::path dir = std::filesystem::path(file).parent_path();
  if (dir.empty()) dir = ".";
  const YamlField items = root.require("items");
  if (items.size() == 0) items.fail("a batch needs at least one item");
  long long assets = 0;  // count x cuts of the items so far
  for (size_t i = 0; i < items.size(); ++i) {
    const YamlField f = items[i];
    f.allow_only({"template", "count", "seed", "variation", "cuts"});
    BatchItem item;
    ParsedItem p{f, {}, {}, {}};
    item.loc = f.loc();
    item.path = f.path();
    const YamlField tmpl = f.require("template");
    item.template_name = tmpl.string();
    item.template_path = resolve_template(tmpl, dir, "batch");
    if (auto x = f.get("count")) item.count = parse_int_in(*x, 1, 100000);
    item.seed = seed;
    if (auto x = f.get("seed")) {
      item.seed = parse_seed(*x);
      p.seed_field = *x;
    }
    if (item.seed + static_cast<uint64_t>(item.count) - 1 > static_cast<uint64_t>(kMaxBatchSeed))
      (p.seed_field ? *p.seed_field : f)
          .fail("the item's last seed (seed + count - 1) must be at most 2^53");
    if (auto x = f.get("variation")) item.variation = x->number_in(0, 10);
    if (auto x = f.get("cuts")) {
      if (x->size() == 0) x->fail("an item needs at least one cut (or no cuts field: halves)");
      if (x->size() > 16) x->fail("at most 16 cuts per item");
      for (size_t c = 0; c < x->size(); ++c) {
        std::optional<YamlField> length;
        item.cuts.push_back(parse_cut((*x)[c], m, length));
        p.length_fields.push_back(length);
        p.cut_fields.push_back((*x)[c]);
      }
    } else {
      CutSpec halves;
      halves.type = CutType::Halves;
      item.cuts.push_back(halves);
      p.length_fields.emplace_back();
      p.cut_fields.push_back(f);
    }
    assets += static_cast<long long>(item.count) * static_cast<long long>(item.cuts.size());
    if (assets > kMaxBatchAssets)
      f.get("count").value_or(f).fail("the items up to here make " + std::to_string(assets) +
                                      " assets (at most " + std::to_string(kMaxBatchAssets) +
                                      " in a batch: split it into several batches)");
    b.items.push_back(std::move(item));
    if (parsed) parsed->items.push_back(std::move(p));
  }
  if (auto o = root.get("outputs")) {
    o->allow_only({"model", "thumbnails", "thumbnail_size", "sample", "volume", "volume_voxels"});
    if (auto x = o->get("model")) b.outputs.model = x->boolean();
    if (auto x = o->get("thumbnails")) b.outputs.thumbnails = x->boolean();
    if (auto x = o->get("thumbnail_size")) b.outputs.thumbnail_px = parse_int_in(*x, 64, 1024);
    if (auto x = o->get("sample")) b.outputs.sample = parse_int_in(*x, 0, 64);
    if (auto x = o->get("volume")) b.outputs.volume = x->boolean();
    if (auto x = o->get("volume_voxels"))
      b.outputs.volume_voxels = parse_int_in(*x, kMinBatchVolumeVoxels, kMaxBatchVolumeVoxels);
    if (parsed && b.outputs.volume)
      parsed->volume = o->get("volume_voxels").value_or(o->require("volume"));
  }
  if (auto e = root.get("export")) {
    e->allow_only({"for", "compress", "lods", "textures", "texture_fallback", "camera_and_lights",
                   "collision", "texels_per_mm", "perlin", "cube", "power_of_two"});
    // The profile first: compress and collision, when given, are written over it.
    if (auto x = e->get("for")) {
      const std::string v = x->string();
      if (std::find(std::begin(kEngineProfiles), std::end(kEngineProfiles), v) ==
          std::end(kEngineProfiles))
        x->fail("must be godot, unreal, unity, web or blender, not " + quoted(v));
      apply_engine_profile(v, b.export_options.gltf);
    }
    if (auto x = e->get("compress")) {
      const std::string v = x->string();
      if (v != "none" && v != "quantize" && v != "meshopt")
        x->fail("must be none, quantize or meshopt, not " + quoted(v));
      b.export_options.gltf.compression = parse_gltf_compression(v);
    }
    if (auto x = e->get("lods")) b.export_options.gltf.lods = parse_int_in(*x, 0, 4);
    if (auto x = e->get("textures")) {
      const std::string v = x->string();
      if (v != "jpeg" && v != "png" && v != "ktx2")
        x->fail("must be jpeg, png or ktx2, not " + quoted(v));
      b.export_options.gltf.textures = parse_texture_format(v);
    }
    if (auto x = e->get("texture_fallback")) {
      b.export_options.gltf.texture_fallback = x->boolean();
      if (b.export_options.gltf.texture_fallback &&
          b.export_options.gltf.textures != TextureFormat::Ktx2)
        x->fail("only with textures: ktx2 (it adds JPEG or PNG beside the KTX2 images)");
    }
    if (auto x = e->get("camera_and_lights"))
      b.export_options.gltf.camera_and_lights = x->boolean();
    if (auto x = e->get("collision")) {
      const std::string v = x->string();
      if (v != "none" && v != "godot" && v != "unreal" && v != "godot-rigid")
        x->fail("must be none, godot, unreal or godot-rigid, not " + quoted(v));
      b.export_options.gltf.collision = parse_gltf_collision(v);
    }
    if (auto x = e->get("texels_per_mm")) b.export_options.texels_per_mm = x->number_in(0.1, 100);
    if (auto x = e->get("perlin")) b.export_options.perlin = x->number_in(0, 10);
    if (auto x = e->get("cube")) b.export_options.cube = parse_int_in(*x, 2, 256);
    if (auto x = e->get("power_of_two")) b.export_options.power_of_two = x->boolean();
  }
  return b;
}

}  // namespace

Batch parse_batch(std::string_view text, const std::string& file) {
  return parse(text, file, nullptr);
}

Batch load_batch(const std::string& path) {
  const std::string text = read_input_file(path);
  ParsedBatch parsed_batch;
  Batch b = parse(text, path, &parsed_batch);
  std::vector<ParsedItem>& parsed = parsed_batch.items;
  TemplateCheck templates;
  // An asset is named by its template, seed and cut (batch_assets.h): no two may agree.
  for (size_t i = 0; i < b.items.size(); ++i) {
    BatchItem& item = b.items[i];
    for (size_t c = 0; c < item.cuts.size(); ++c) {
      const LoadedTemplate& loaded =
          templates.check(item.template_path, item.cuts[c], parsed[i].length_fields[c]);
      item.tmpl = loaded.tmpl;
      item.template_name = loaded.tmpl->name;
      if (c == 0) check_item_variation(parsed[i].item, *item.tmpl, item.variation);
      // Each asset bakes its own caps: one object's cut faces at the batch's density.
      const double area = estimate_cut_area(item.cuts[c], loaded.extents);
      if (const Check texels = check_cap_texels(area, b.export_options.texels_per_mm); !texels)
        parsed[i].cut_fields[c].fail(texels.reason());
      if (c == 0 && parsed_batch.volume)
        check_volume_cost(b, loaded.extents, item.template_name, *parsed_batch.volume);
    }
    for (size_t c = 0; c < item.cuts.size(); ++c)
      for (size_t d = 0; d < c; ++d)
        if (cut_label(item.cuts[c]) == cut_label(item.cuts[d]))
          parsed[i].cut_fields[c].fail("the same cut as cuts[" + std::to_string(d) + "] (" +
                                       cut_label(item.cuts[c]) + ")");
    for (size_t j = 0; j < i; ++j) {
      const BatchItem& other = b.items[j];
      if (other.template_name != item.template_name) continue;
      const uint64_t lo = std::max(item.seed, other.seed);
      const uint64_t hi = std::min(item.seed + item.count, other.seed + other.count);
      if (lo >= hi) continue;
      for (const CutSpec& cut : item.cuts)
        for (const CutSpec& theirs : other.cuts)
          if (cut_label(cut) == cut_label(theirs)) {
            const std::string rule = "makes the assets of " + other.path + " again (template " +
                                     quoted(item.template_name) + ", seed " + std::to_string(lo) +
                                     ", cut " + cut_label(cut) + "): give it other seeds";
            (parsed[i].seed_field ? *parsed[i].seed_field : parsed[i].item).fail(rule);
          }
    }
  }
  return b;
}

}  // namespace cutaway
