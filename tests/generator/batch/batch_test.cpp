// Asset batches (batch/): the batch format's rules, the plan (names, sample, fingerprints),
// manifest lines, resuming a run after a crash, merging shards and what merge reports, and
// the sbatch script.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <tiny_gltf.h>

#include "base/error.h"
#include "base/hash.h"
#include "batch/batch_manifest.h"
#include "batch/batch_runner.h"
#include "batch/slurm_job.h"
#include "diffusion/diffusion.h"
#include "export/texture_image.h"
#include "io/batch_parser.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;
using test::fresh_dir;
using test::read_file;
using test::source_path;

/// A batch file in a fresh folder beside a templates/ link, so that names resolve.
Batch parse_text(const std::string& text) {
  return parse_batch(text, source_path("batches/test.yaml").string());
}

std::string error_of(const std::string& text) {
  try {
    parse_text(text);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const char* kHeader = "format: cutaway-batch/1\nname: t\n";

TEST(BatchFormat, ReadsItemsCutsAndDefaults) {
  const Batch b =
      parse_text(std::string(kHeader) +
                 "seed: 5\nunits: cm\nitems:\n"
                 "  - template: tomato\n    count: 3\n"
                 "    cuts: [{type: slices, thickness: 1.2}, {type: wedges, count: 5}]\n"
                 "  - template: kiwi\n    seed: 90\n");
  ASSERT_EQ(b.items.size(), 2u);
  EXPECT_EQ(b.items[0].seed, 5u);
  EXPECT_EQ(b.items[0].count, 3);
  ASSERT_EQ(b.items[0].cuts.size(), 2u);
  EXPECT_NEAR(b.items[0].cuts[0].thickness_m, 0.012, 1e-12);
  EXPECT_EQ(b.items[0].cuts[1].count, 5);
  EXPECT_EQ(b.items[1].seed, 90u);
  ASSERT_EQ(b.items[1].cuts.size(), 1u);
  EXPECT_EQ(b.items[1].cuts[0].type, CutType::Halves);
  EXPECT_FALSE(b.outputs.model);
  EXPECT_EQ(b.outputs.sample, 12);
  EXPECT_EQ(b.export_options.cube, kDefaultCubeSize);                   // 12
  EXPECT_EQ(b.export_options.gltf.collision, GltfCollision::Godot);     // engine-ready by default
  EXPECT_EQ(b.export_options.gltf.compression, GltfCompression::None);  // every engine reads it
  EXPECT_FALSE(b.export_options.gltf.camera_and_lights);
  EXPECT_FALSE(b.export_options.power_of_two);
  EXPECT_TRUE(parse_text(std::string(kHeader) + "items:\n  - template: tomato\n" +
                         "export: {power_of_two: true}\n")
                  .export_options.power_of_two);
  // An engine profile sets what its engine needs; compress and collision given win over it.
  const GltfSceneOptions godot =
      parse_text(std::string(kHeader) + "items:\n  - template: tomato\nexport: {for: godot}\n")
          .export_options.gltf;
  EXPECT_EQ(godot.compression, GltfCompression::None);
  EXPECT_EQ(godot.collision, GltfCollision::GodotRigid);
  EXPECT_TRUE(godot.pivot_at_centre_of_mass);
  const GltfSceneOptions given =
      parse_text(std::string(kHeader) +
                 "items:\n  - template: tomato\nexport: {collision: none, for: godot, compress: "
                 "meshopt}\n")
          .export_options.gltf;
  EXPECT_EQ(given.compression, GltfCompression::Meshopt);
  EXPECT_EQ(given.collision, GltfCollision::None);
  EXPECT_TRUE(given.pivot_at_centre_of_mass);
}

TEST(BatchFormat, RefusesBrokenRulesAtTheField) {
  const std::string items = "items:\n  - template: tomato\n";
  EXPECT_NE(
      error_of("format: cutaway-batch/2\nname: t\n" + items).find(":1:9: format: unsupported"),
      std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + items + "    colour: red\n").find("items[0].colour"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + items + "    count: 0\n").find("items[0].count"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + items + "    cuts: []\n").find("at least one cut"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + items + "    seed: -1\n").find("items[0].seed"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + items + "outputs: {thumbnail_size: 9}\n")
                .find("outputs.thumbnail_size"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + items + "export: {compress: zip}\n")
                .find("export.compress: must be none, quantize or meshopt"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + items + "export: {collision: havok}\n")
                .find("export.collision: must be none, godot, unreal or godot-rigid"),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + items + "export: {for: maya}\n")
                .find("export.for: must be godot, unreal, unity, web or blender, not \"maya\""),
            std::string::npos);
  EXPECT_NE(error_of(std::string(kHeader) + "items: []\n").find("at least one item"),
            std::string::npos);
}

// Two items that would write the same asset file are refused once the names are known.
TEST(BatchFormat, RefusesTwoItemsMakingTheSameAsset) {
  const fs::path dir = fresh_dir("batch");
  const fs::path file = dir / "b.yaml";
  std::ofstream(file) << kHeader << "items:\n"
                      << "  - {template: " << source_path("templates/tomato.yaml").string()
                      << ", count: 4, seed: 10}\n"
                      << "  - {template: " << source_path("templates/tomato.yaml").string()
                      << ", count: 2, seed: 13}\n";
  try {
    load_batch(file.string());
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("items[1].seed: makes the assets of items[0] again"),
              std::string::npos)
        << e.what();
  }
}

Batch two_item_batch() {
  Batch b =
      parse_text(std::string(kHeader) + "items:\n  - template: tomato\n    count: 3\n"
                                        "    cuts: [{type: halves}, {type: wedges, count: 6}]\n"
                                        "  - template: kiwi\n    seed: 50\n    count: 2\n"
                                        "outputs: {sample: 4}\n");
  b.items[0].template_name = "tomato";
  b.items[1].template_name = "kiwi";
  for (BatchItem& item : b.items) {
    auto tmpl = std::make_shared<Template>();
    tmpl->name = item.template_name;
    tmpl->source_hash = fnv1a64(item.template_name);
    item.tmpl = tmpl;
  }
  return b;
}

TEST(BatchPlan, NamesEveryAssetInBatchOrderWithAnEvenSample) {
  const BatchPlan plan = plan_batch(two_item_batch(), "");
  ASSERT_EQ(plan.units.size(), 5u);
  ASSERT_EQ(plan.assets.size(), 8u);
  EXPECT_EQ(plan.assets[0].stem, "tomato-0-halves");
  EXPECT_EQ(plan.assets[1].stem, "tomato-0-wedges-6");
  EXPECT_EQ(plan.assets[7].stem, "kiwi-51-halves");
  EXPECT_EQ(plan.units[3].first_asset, 6u);
  std::vector<size_t> sample;
  for (size_t a = 0; a < plan.assets.size(); ++a)
    if (plan.assets[a].sample) sample.push_back(a);
  EXPECT_EQ(sample, (std::vector<size_t>{0, 2, 4, 6}));
  std::set<uint64_t> inputs;
  for (const BatchAsset& a : plan.assets) inputs.insert(a.inputs);
  EXPECT_EQ(inputs.size(), plan.assets.size());
  // The fingerprint follows what changes the bytes, and nothing else.
  EXPECT_EQ(plan_batch(two_item_batch(), "").assets[3].inputs, plan.assets[3].inputs);
  EXPECT_NE(plan_batch(two_item_batch(), "backend=gl").assets[3].inputs, plan.assets[3].inputs);
  Batch other = two_item_batch();
  other.export_options.perlin = 0.5;
  EXPECT_NE(plan_batch(other, "").assets[3].inputs, plan.assets[3].inputs);
  // Another template file, or the same file with other meshes (Template::source_hash).
  other = two_item_batch();
  auto edited = std::make_shared<Template>(*other.items[0].tmpl);
  edited->source_hash += 1;
  other.items[0].tmpl = edited;
  EXPECT_NE(plan_batch(other, "").assets[3].inputs, plan.assets[3].inputs);
}

TEST(BatchManifest, LinesRoundTripAndRefuseDamage) {
  AssetRecord r;
  r.file = "tomato-3-halves.glb";
  r.template_name = "tomato";
  r.seed = 3;
  r.cut = "halves";
  r.pieces = 2;
  r.triangles = 1234;
  r.vertices = 777;
  r.volume_m3 = 1.25e-4;
  r.hash = 0x0123456789abcdefULL;
  r.thumbnail = "tomato-3-halves.png";
  r.thumbnail_hash = 42;
  r.inputs = 7;
  const std::string line = manifest_line(r);
  EXPECT_EQ(line.back(), '\n');
  EXPECT_EQ(line.find("seconds"), std::string::npos);
  EXPECT_EQ(line.find("model"), std::string::npos);
  const Outcome<AssetRecord> back = parse_manifest_line(line);
  ASSERT_TRUE(back) << back.reason();
  EXPECT_EQ(*back, r);
  EXPECT_FALSE(parse_manifest_line(line.substr(0, line.size() / 2)));
  std::string escaping = line;
  escaping.replace(escaping.find("tomato-3-halves.glb"), 19, "../../etc/passwd.glb");
  EXPECT_FALSE(parse_manifest_line(escaping));
  // The pieces that hold a whole stone: listed in increasing order, each a piece of the file.
  r.stone_pieces = {1};
  const std::string stoned = manifest_line(r);
  EXPECT_NE(stoned.find(R"("fnv1a64":"0123456789abcdef","stone_pieces":[1],)"), std::string::npos)
      << stoned;
  ASSERT_TRUE(parse_manifest_line(stoned));
  EXPECT_EQ(*parse_manifest_line(stoned), r);
  for (const char* bad : {"[2]", "[1,1]", "[-1]", "\"1\""}) {
    std::string wrong = stoned;
    wrong.replace(wrong.find("[1]"), 3, bad);
    EXPECT_FALSE(parse_manifest_line(wrong)) << wrong;
  }
  EXPECT_EQ(manifest_name(std::nullopt), "manifest.jsonl");
  EXPECT_EQ(manifest_name(Shard{2, 4}), "manifest-2-of-4.jsonl");
}

/// A real batch of two variants, one cut each, with cheap diffusion.
struct SmallBatch {
  Batch batch;
  BatchPlan plan;
  BatchRunOptions options;
};
SmallBatch small_batch() {
  SmallBatch s;
  s.batch = load_batch(source_path("tests/data/batches/four-variants.yaml").string());
  s.batch.items.resize(1);  // persimmon: two variants, cut two ways
  s.batch.outputs.thumbnails = false;
  s.batch.outputs.sample = 0;
  s.plan = plan_batch(s.batch, "test");
  s.options.build.diffusion = [](const DsModel& m) { return make_cpu_diffusion(m, {4, 0}); };
  return s;
}

TEST(BatchRun, ResumesWhereACrashLeftOffAndShardsMergeToTheSameManifest) {
  SmallBatch s = small_batch();
  const fs::path whole = fresh_dir("whole");
  const BatchRunResult first = run_batch(s.batch, s.plan, whole, s.options);
  EXPECT_EQ(first.built, 4u);
  const std::string manifest = read_file(whole / "manifest.jsonl");
  EXPECT_EQ(std::count(manifest.begin(), manifest.end(), '\n'), 4);

  // A second run builds nothing; a changed file and a torn manifest line are rebuilt.
  EXPECT_EQ(run_batch(s.batch, s.plan, whole, s.options).built, 0u);
  std::ofstream(whole / "persimmon-8-halves.glb", std::ios::app) << "x";
  std::ofstream(whole / "manifest.jsonl", std::ios::app) << "{\"file\":\"persim";
  const BatchRunResult again = run_batch(s.batch, s.plan, whole, s.options);
  EXPECT_EQ(again.built, 2u);  // the variant of the changed asset, both its cuts
  EXPECT_EQ(again.skipped, 2u);
  EXPECT_EQ(read_file(whole / "manifest.jsonl"), manifest);

  const fs::path sharded = fresh_dir("sharded");
  for (int k = 1; k <= 2; ++k) {
    s.options.shard = Shard{k, 2};
    run_batch(s.batch, s.plan, sharded, s.options);
  }
  // More shards than variants: shard 3 of 4 has none, and lists none.
  s.options.shard = Shard{3, 4};
  const BatchRunResult empty = run_batch(s.batch, s.plan, sharded, s.options);
  EXPECT_EQ(empty.units, 0u);
  EXPECT_EQ(empty.built + empty.skipped, 0u);
  EXPECT_EQ(read_file(sharded / "manifest-3-of-4.jsonl"), "");
  fs::remove(sharded / "manifest-3-of-4.jsonl");
  const Outcome<BatchIndex> index = read_batch_index(sharded);
  ASSERT_TRUE(index) << index.reason();
  MergeReport report = merge_manifests(*index, sharded);
  EXPECT_TRUE(report.complete());
  EXPECT_EQ(report.manifests.size(), 2u);
  std::string merged;
  for (const AssetRecord& r : report.records) merged += manifest_line(r);
  EXPECT_EQ(merged, manifest);

  // What merge reports: a missing shard, a damaged file.
  fs::remove(sharded / "manifest-2-of-2.jsonl");
  report = merge_manifests(*index, sharded);
  EXPECT_FALSE(report.complete());
  EXPECT_EQ(report.missing,
            (std::vector<std::string>{"persimmon-8-wedges-4", "persimmon-8-halves"}));
  std::ofstream(sharded / "persimmon-7-halves.glb", std::ios::app) << "x";
  report = merge_manifests(*index, sharded);
  EXPECT_EQ(report.damaged, (std::vector<std::string>{"persimmon-7-halves"}));
}

/// A .glb read with tinygltf.
tinygltf::Model load_glb(const fs::path& file) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, file.string())) << err << warn;
  return m;
}

/// Triangles and vertices a viewer draws of a glTF model: the meshes of the
/// default scene's nodes and their children (MSFT_lod's coarser levels are not in the scene),
/// but not the collision hulls (nodes whose extras say "collision"), which engines do not draw.
std::pair<size_t, size_t> drawn_geometry(const tinygltf::Model& m) {
  size_t triangles = 0, vertices = 0;
  std::vector<int> todo = m.scenes.at(static_cast<size_t>(std::max(m.defaultScene, 0))).nodes;
  while (!todo.empty()) {
    const tinygltf::Node& node = m.nodes.at(static_cast<size_t>(todo.back()));
    todo.pop_back();
    todo.insert(todo.end(), node.children.begin(), node.children.end());
    if (node.mesh < 0 || (node.extras.IsObject() && node.extras.Has("collision"))) continue;
    for (const tinygltf::Primitive& p : m.meshes.at(static_cast<size_t>(node.mesh)).primitives) {
      triangles += m.accessors.at(static_cast<size_t>(p.indices)).count / 3;
      vertices += m.accessors.at(static_cast<size_t>(p.attributes.at("POSITION"))).count;
    }
  }
  return {triangles, vertices};
}

// The manifest's counts are the files' (with textures, whose caps are coarse meshes, with
// levels of detail, which are not drawn at once, and with collision hulls, which are not
// drawn): read back with another glTF reader.
TEST(BatchRun, ManifestCountsAreWhatTheFilesDraw) {
  SmallBatch s = small_batch();
  s.batch.items.at(0).count = 1;
  s.batch.outputs.model = false;
  s.batch.export_options.gltf.textures = TextureFormat::Jpeg;
  s.batch.export_options.gltf.lods = 2;
  s.plan = plan_batch(s.batch, "test");
  const fs::path dir = fresh_dir("counts");
  run_batch(s.batch, s.plan, dir, s.options);
  const Outcome<BatchIndex> index = read_batch_index(dir);
  ASSERT_TRUE(index) << index.reason();
  const MergeReport report = merge_manifests(*index, dir);
  ASSERT_EQ(report.records.size(), 2u);
  for (const AssetRecord& r : report.records) {
    const tinygltf::Model m = load_glb(dir / r.file);
    const auto [triangles, vertices] = drawn_geometry(m);
    EXPECT_EQ(r.triangles, triangles) << r.file;
    EXPECT_EQ(r.vertices, vertices) << r.file;
    EXPECT_GT(triangles, 1000u) << r.file;
    // The hulls are there (batches write them for Godot by default).
    EXPECT_TRUE(std::any_of(m.nodes.begin(), m.nodes.end(), [](const tinygltf::Node& n) {
      return n.name.size() > 12 && n.name.substr(n.name.size() - 12) == "-convcolonly";
    })) << r.file;
  }
}

TEST(SlurmJob, WritesAnArrayScriptAndRefusesUnquotablePaths) {
  SlurmJob job{"/opt/cutaway", "/data/b.yaml", "/data/out dir", "fruit", 4, 2, "", "", {}};
  EXPECT_NE(check_slurm_job(job).reason().find("white space"), std::string::npos);
  job.dir = "/data/out";
  job.partition = "cpu";
  job.time = "1:00:00";
  job.extra_args = {"--backend", "cpu"};
  ASSERT_TRUE(check_slurm_job(job));
  const std::string script = sbatch_script(job);
  EXPECT_NE(script.find("#SBATCH --array=1-4\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --partition=cpu\n"), std::string::npos);
  EXPECT_NE(script.find("#SBATCH --output=/data/out/slurm/%A_%a.out\n"), std::string::npos);
  EXPECT_NE(script.find("exec '/opt/cutaway' batch '/data/b.yaml' -o '/data/out' --shard "
                        "\"${SLURM_ARRAY_TASK_ID}/4\" --threads 2 '--backend' 'cpu'\n"),
            std::string::npos)
      << script;
  job.partition = "a;rm";
  EXPECT_FALSE(check_slurm_job(job));
}

// sbatch splits #SBATCH lines on every white-space byte, vertical tab and form feed included:
// "out\f--chdir=/srv" would become an option of its own. Each separator, control character,
// quote, pattern character and a byte that is not UTF-8 is refused, in each of the three paths.
TEST(SlurmJob, RefusesEveryByteSbatchSplitsOnOrCannotPrint) {
  std::vector<std::string> bad = {" ", "\t", "\n",   "\v",       "\f",       "\r",   "'",   "\"",
                                  "%", "\\", "\x7f", "\xc2\x85", "\xc2\xa0", "\xff", "\xc3"};
  for (int c = 1; c < 0x20; ++c) bad.push_back(std::string(1, static_cast<char>(c)));
  for (const std::string& b : bad) {
    for (int which = 0; which < 3; ++which) {
      SlurmJob job{"/opt/cutaway", "/data/b.yaml", "/data/out", "fruit", 4, 2, "", "", {}};
      std::string& path = which == 0 ? job.cutaway : which == 1 ? job.batch_file : job.dir;
      path += b + "--chdir=/srv";
      EXPECT_NE(check_slurm_job(job).reason().find("sbatch splits"), std::string::npos)
          << "byte " << static_cast<int>(static_cast<unsigned char>(b[0])) << " in path " << which;
    }
  }
  // Printable UTF-8 beyond ASCII is kept.
  SlurmJob job{"/opt/cutaway", "/data/b.yaml", "/data/frühstück-ø", "fruit", 4, 2, "", "", {}};
  EXPECT_TRUE(check_slurm_job(job));
}

}  // namespace
}  // namespace cutaway
