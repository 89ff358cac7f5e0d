// `cutaway volume` as a user runs it: every form from one stem, each referring to the others,
// the glTF valid, the same bytes for the same seed, bad outputs refused before any work, and
// the .vdb imported by Blender (headless).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// `cutaway volume` on the hollow-spheres fixture at 3 mm voxels (about 7,000 voxels).
test::RunResult volume(const std::vector<std::string>& extra) {
  std::vector<std::string> args = {"volume", "tests/data/section_hollow.yaml", "--voxel", "3"};
  args.insert(args.end(), extra.begin(), extra.end());
  return test::run_cutaway(args);
}

TEST(InteriorVolumeCommand, AStemWritesEveryFormEachReferringToTheOthers) {
  const fs::path dir = test::fresh_dir("volume-stem");
  const test::RunResult run = volume({"-o", (dir / "hollow").string()});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(test::files_in(dir), (std::vector<std::string>{"hollow.colour.png", "hollow.glb",
                                                           "hollow.json", "hollow.material.png",
                                                           "hollow.structure.png", "hollow.vdb"}));
  const nlohmann::json sidecar = nlohmann::json::parse(test::read_file(dir / "hollow.json"));
  EXPECT_EQ(sidecar["template"], "section-hollow");
  EXPECT_TRUE(sidecar["seed"].is_null());
  EXPECT_EQ(sidecar["images"]["colour"], "hollow.colour.png");
  EXPECT_EQ(sidecar["vdb"], "hollow.vdb");
  EXPECT_DOUBLE_EQ(sidecar["grid"]["voxel_m"].get<double>(), 0.003);
  EXPECT_EQ(sidecar["regions"], 1);
  const test::PngInfo png = test::png_info(dir / "hollow.colour.png");
  EXPECT_EQ(png.width,
            sidecar["tiling"]["columns"].get<int>() * sidecar["tiling"]["tile_width"].get<int>());
  EXPECT_EQ(test::read_file(dir / "hollow.vdb").substr(0, 4), std::string(" BDV"));
  // The glTF is valid and names the volume's files in its scene's extras.
  const test::GltfReport report = test::validate_gltf(dir / "hollow.glb");
  EXPECT_EQ(report.errors, 0) << report.output;
  const std::string glb = test::read_file(dir / "hollow.glb");
  const uint32_t json_length = *reinterpret_cast<const uint32_t*>(glb.data() + 12);
  const nlohmann::json gltf = nlohmann::json::parse(glb.substr(20, json_length));
  const nlohmann::json& ref = gltf["scenes"][0]["extras"]["interior_volume"];
  EXPECT_EQ(ref["sidecar"], "hollow.json");
  EXPECT_EQ(ref["vdb"], "hollow.vdb");
  EXPECT_EQ(ref["size"], sidecar["grid"]["size"]);
  EXPECT_FALSE(gltf.contains("cameras"));  // an asset, not a scene to render
}

TEST(InteriorVolumeCommand, TheSameSeedGivesTheSameBytesAnotherSeedOthers) {
  const fs::path dir = test::fresh_dir("volume-seed");
  for (const char* name : {"a", "b"})
    ASSERT_EQ(test::run_cutaway({"volume", "templates/kiwi.yaml", "--voxel", "3", "--seed", "5",
                                 "-o", (dir / name).string() + ".json", "-o",
                                 (dir / name).string() + ".vdb"})
                  .exit_code,
              0);
  ASSERT_EQ(test::run_cutaway({"volume", "templates/kiwi.yaml", "--voxel", "3", "--seed", "6", "-o",
                               (dir / "c.json").string()})
                .exit_code,
            0);
  EXPECT_EQ(test::read_file(dir / "a.vdb"), test::read_file(dir / "b.vdb"));
  EXPECT_EQ(test::read_file(dir / "a.colour.png"), test::read_file(dir / "b.colour.png"));
  EXPECT_EQ(test::read_file(dir / "a.structure.png"), test::read_file(dir / "b.structure.png"));
  EXPECT_NE(test::read_file(dir / "a.colour.png"), test::read_file(dir / "c.colour.png"));
  const nlohmann::json a = nlohmann::json::parse(test::read_file(dir / "a.json"));
  EXPECT_EQ(a["seed"], 5);
  EXPECT_EQ(a["vdb"], "a.vdb");
}

TEST(InteriorVolumeCommand, BadOutputsAndVoxelsAreRefusedBeforeAnyWork) {
  const fs::path dir = test::fresh_dir("volume-bad");
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"-o", (dir / "x.txt").string()}, "must end in .vdb, .json"},
      {{"-o", (dir / "x.glb").string()}, "also give a .json or .vdb"},
      {{"-o", (dir / "x").string(), "-o", (dir / "y.vdb").string()}, "a second .vdb output"},
  };
  for (const Case& c : cases) {
    const test::RunResult run = volume(c.args);
    EXPECT_EQ(run.exit_code, 2) << run.err;
    EXPECT_NE(run.err.find(c.message), std::string::npos) << run.err;
  }
  const test::RunResult fine =
      test::run_cutaway({"volume", "tests/data/section_hollow.yaml", "--voxel", "0.001", "-o",
                         (dir / "fine").string()});
  EXPECT_EQ(fine.exit_code, 2);
  EXPECT_NE(fine.err.find("--voxel: "), std::string::npos) << fine.err;
  EXPECT_NE(fine.err.find("give a longer voxel length"), std::string::npos) << fine.err;
  // A voxel that is not a plain positive decimal, or longer than half the object.
  const std::string positive = "--voxel: must be a number above 0, not ";
  const std::vector<std::pair<std::string, std::string>> voxels = {
      {"nan", positive + "\"nan\""},
      {"inf", positive + "\"inf\""},
      {"abc", positive + "\"abc\""},
      {"1e400", positive + "\"1e400\""},
      {"-1", positive + "\"-1\""},
      {"0", positive + "\"0\""},
      {"1e308", "at least two voxels across"}};
  for (const auto& [voxel, message] : voxels) {
    const test::RunResult run = test::run_cutaway(
        {"volume", "tests/data/section_hollow.yaml", "--voxel", voxel, "-o", (dir / "v").string()});
    EXPECT_EQ(run.exit_code, 2) << voxel << ": " << run.err;
    EXPECT_NE(run.err.find(message), std::string::npos) << voxel << ": " << run.err;
  }
  EXPECT_TRUE(test::files_in(dir).empty());  // nothing written, not even a part
}

TEST(InteriorVolumeCommand, BlenderImportsTheVdbWithEveryGridWhereTheGltfPutsTheObject) {
  const fs::path dir = test::fresh_dir("volume-blender");
  ASSERT_EQ(volume({"-o", (dir / "hollow.vdb").string()}).exit_code, 0);
  const test::RunResult run = test::run_program(
      "blender", {"-b", "--factory-startup", "--python-exit-code", "1", "--python",
                  "tests/blender/volume_import.py", "--", (dir / "hollow.vdb").string(), "--render",
                  (dir / "blender.png").string()});
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  const size_t at = run.out.find("VOLUME_REPORT ");
  ASSERT_NE(at, std::string::npos) << run.out;
  const nlohmann::json report =
      nlohmann::json::parse(run.out.substr(at + 14, run.out.find('\n', at) - at - 14));
  EXPECT_EQ(report["volumes"], 1);
  EXPECT_EQ(report["load_error"], "");
  EXPECT_EQ(report["grids"], (nlohmann::json{{"density", "FLOAT"},
                                             {"color", "VECTOR_FLOAT"},
                                             {"roughness", "FLOAT"},
                                             {"translucency", "FLOAT"},
                                             {"region", "INT"},
                                             {"sheet_distance", "FLOAT"},
                                             {"outline_distance", "FLOAT"}}));
  // The sphere of radius 30 mm centred on (0, 0, 0), in Blender's +Z-up axes as the glTF
  // importer puts the object. Blender's box runs from the first stored voxel's index to one
  // past the last, and the stored voxels include the one-voxel ring of colour outside the
  // skin: so within two voxels (6 mm) of +-30 mm, and never inside the sphere.
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(report["bounds"][0][a].get<double>(), -0.030, 0.0061) << report.dump();
    EXPECT_NEAR(report["bounds"][1][a].get<double>(), 0.030, 0.0061) << report.dump();
    EXPECT_LT(report["bounds"][0][a].get<double>(), -0.029) << report.dump();
    EXPECT_GT(report["bounds"][1][a].get<double>(), 0.029) << report.dump();
  }
  EXPECT_GT(test::png_info(dir / "blender.png").not_background, 5000u);  // a sphere drawn
}

}  // namespace
}  // namespace cutaway

namespace cutaway::test {
namespace {

// `outputs: {volume: true}`: each variant's interior volume beside its assets, listed with
// hashes on every one of its assets' manifest lines, and checked by `batch merge`.
TEST(InteriorVolumeBatch, EachVariantGetsItsVolumeListedAndCheckedByMerge) {
  const fs::path dir = fresh_dir("volume-batch");
  const fs::path file = dir / "kiwis.yaml";
  std::ofstream(file) << "format: cutaway-batch/1\nname: kiwis\nseed: 4\nitems:\n"
                         "  - template: kiwi\n    count: 2\n"
                         "    cuts: [{type: halves}, {type: whole}]\n"
                         "outputs: {volume: true, volume_voxels: 24, sample: 0}\n";
  RunResult r = run_cutaway({"-q", "batch", file.string(), "-o", (dir / "out").string(), "--shard",
                             "1/1", "--backend", "cpu"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* seed : {"4", "5"})
    for (const char* ext : {".json", ".colour.png", ".structure.png", ".material.png", ".vdb"})
      EXPECT_TRUE(fs::exists(dir / "out" / (std::string("kiwi-") + seed + ".volume" + ext)))
          << seed << ext;
  const nlohmann::json sidecar =
      nlohmann::json::parse(read_file(dir / "out" / "kiwi-5.volume.json"));
  EXPECT_EQ(sidecar["seed"], 5);
  EXPECT_EQ(sidecar["vdb"], "kiwi-5.volume.vdb");
  const auto& size = sidecar["grid"]["size"];  // 24 across the longest edge, one voxel beyond
  EXPECT_EQ(std::max({size[0].get<int>(), size[1].get<int>(), size[2].get<int>()}), 27);
  // The same variant's volume as `cutaway volume --seed` makes it (the batch's Perlin strength
  // and cube are the command's defaults).
  const fs::path own = dir / "own.json";
  char voxel_mm[32];
  std::snprintf(voxel_mm, sizeof voxel_mm, "%.17g",
                sidecar["grid"]["voxel_m"].get<double>() * 1000);
  r = run_cutaway(
      {"volume", "templates/kiwi.yaml", "--seed", "5", "--voxel", voxel_mm, "-o", own.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(read_file(dir / "own.colour.png") ==
              read_file(dir / "out" / "kiwi-5.volume.colour.png"));
  // Both assets of a variant list its five files; merge checks them.
  const std::string manifest = read_file(dir / "out" / "manifest-1-of-1.jsonl");
  size_t lines = 0;
  for (size_t at = 0; (at = manifest.find("\"volume\":[", at)) != std::string::npos; ++at) ++lines;
  EXPECT_EQ(lines, 4u) << manifest;
  r = run_cutaway({"batch", "merge", (dir / "out").string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  // A damaged volume file is found by merge (it is not intact, so the asset is due again).
  std::ofstream(dir / "out" / "kiwi-4.volume.structure.png") << "damaged";
  r = run_cutaway({"batch", "merge", (dir / "out").string()});
  EXPECT_NE(r.exit_code, 0) << r.err;
}

}  // namespace
}  // namespace cutaway::test
