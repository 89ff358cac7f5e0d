// `cutaway scene` and `cutaway piece` end to end: every export passes the Khronos validator and
// loads in three.js, the POV-Ray file renders, the previews are pictures of the right size; the
// same scene and seed give byte-identical files across runs and thread counts, another seed
// another layout; bad arguments are refused with exit code 2 and leave nothing behind.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>
#include <map>
#include <set>
#include <sstream>

#include <stb/stb_image.h>
#include <tiny_gltf.h>

#include "export/engine_profile.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

const char* kTiny = "tests/data/scenes/tiny.yaml";

std::vector<std::string> scene_args(const fs::path& dir, const std::string& stem,
                                    std::vector<std::string> extra = {}) {
  std::vector<std::string> args = {"scene",
                                   kTiny,
                                   "--backend",
                                   "cpu",
                                   "--cube",
                                   "4",
                                   "-q",
                                   "-o",
                                   (dir / (stem + ".glb")).string(),
                                   "-o",
                                   (dir / (stem + ".pov")).string()};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

TEST(SceneCommand, ExportsValidGltfAndPovRayAndPictures) {
  const fs::path dir = test::fresh_dir("scene");
  auto args =
      scene_args(dir, "tiny",
                 {"-o", (dir / "tiny.gltf").string(), "--png", (dir / "preview.png").string(),
                  "--render", (dir / "povray.png").string()});
  args.insert(args.begin(), "--stats");
  const test::RunResult r = test::run_cutaway(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json stats = nlohmann::json::parse(r.err.substr(r.err.rfind("\n{") + 1));
  for (const char* f : {"tiny.glb", "tiny.gltf"}) {
    const test::GltfReport report = test::validate_gltf(dir / f);
    EXPECT_EQ(report.errors, 0) << f << ": " << report.output;
  }
  EXPECT_TRUE(fs::exists(dir / "tiny.bin"));
  const test::ThreeLoadReport three = test::load_gltf_three(dir / "tiny.glb");
  ASSERT_TRUE(three.ok) << three.error << "\n" << three.output;
  EXPECT_EQ(three.cameras, 1);
  EXPECT_EQ(three.lights, 3);
  EXPECT_GE(three.meshes, 8);  // the bowl and at least 7 pieces (4 wedges, 2 halves, slices)
  EXPECT_GT(three.triangles, 10000);
  // The triangles the run reports are those the file draws (textured cut faces coarse).
  EXPECT_EQ(stats["triangles"].get<long long>(), three.triangles);
  for (const char* f : {"preview.png", "povray.png"}) {
    const test::PngInfo png = test::png_info(dir / f);
    EXPECT_EQ(png.width, 160) << f;
    EXPECT_EQ(png.height, 120) << f;
    EXPECT_GT(png.not_background, 160u * 120u / 8) << f << ": (nearly) empty";
  }
  const std::string pov = test::read_file(dir / "tiny.pov");
  EXPECT_NE(pov.find("assumed_gamma 1.0"), std::string::npos);
  EXPECT_NE(pov.find("mesh2"), std::string::npos);
  // Every piece's node says what it is; the bowl's has no extras.
  const auto gltf = nlohmann::json::parse(test::read_file(dir / "tiny.gltf"));
  int pieces = 0, backdrops = 0;
  // The scene's root holds one node per instance; each holds its mesh in one child.
  const auto& root = gltf["nodes"][gltf["scenes"][0]["nodes"][0].get<size_t>()];
  EXPECT_EQ(root["name"], gltf["scenes"][0]["name"]);
  for (const auto& index : root["children"]) {
    const auto& node = gltf["nodes"][index.get<size_t>()];
    ASSERT_EQ(node["children"].size(), 1u) << node.dump();
    EXPECT_TRUE(gltf["nodes"][node["children"][0].get<size_t>()].contains("mesh")) << node.dump();
    if (!node.contains("extras")) {
      EXPECT_EQ(node["name"], "bowl");
      continue;
    }
    if (node["extras"].contains("backdrop")) {
      EXPECT_EQ(node["name"], "backdrop");
      EXPECT_EQ(node["extras"]["backdrop"], true);
      ++backdrops;
      continue;
    }
    ++pieces;
    const auto& x = node["extras"];
    EXPECT_TRUE(x["template"] == "tomato" || x["template"] == "onion" ||
                x["template"] == "cucumber")
        << x.dump();
    EXPECT_TRUE(x["seed"].is_string());
    EXPECT_TRUE(x["cut"].is_string());
    EXPECT_GE(x["piece"].get<int>(), 0);
    EXPECT_EQ(x["parts"][0], "skin");
    EXPECT_GT(x["volume_m3"].get<double>(), 1e-7);
    EXPECT_LT(x["volume_m3"].get<double>(), 1e-3);
  }
  EXPECT_GE(pieces, 7);
  EXPECT_EQ(backdrops, 1);
  // The .pov's textures beside it (cut faces and skins, one each per object, JPEG by
  // default), named in it.
  EXPECT_EQ(pov.find("image_map { jpeg \"tiny_i0_tomato_0_skin.jpg\""), pov.find("image_map"));
  EXPECT_NE(pov.find("image_map { jpeg \"tiny_i0_tomato_0_cut.jpg\""), std::string::npos);
  // The .gltf refers to the same files (no image bytes in its buffer); the cut faces of the
  // tomato and the cucumber, whose material channels vary, have material maps read by both
  // the roughness and the translucency; the onion's do not vary.
  std::set<std::string> uris;
  for (const auto& image : gltf["images"]) {
    EXPECT_FALSE(image.contains("bufferView")) << image.dump();
    uris.insert(image["uri"].get<std::string>());
  }
  // Base colours as JPEG, material maps (linear, with alpha) as PNG.
  const std::set<std::string> textures = {"tiny_i0_tomato_0_cut.jpg",
                                          "tiny_i0_tomato_0_cut_material.png",
                                          "tiny_i0_tomato_0_skin.jpg",
                                          "tiny_i1_onion_0_cut.jpg",
                                          "tiny_i1_onion_0_skin.jpg",
                                          "tiny_i2_cucumber_0_cut.jpg",
                                          "tiny_i2_cucumber_0_cut_material.png",
                                          "tiny_i2_cucumber_0_skin.jpg"};
  EXPECT_EQ(uris, textures);
  int material_maps = 0;
  for (const auto& material : gltf["materials"]) {
    const auto& pbr = material["pbrMetallicRoughness"];
    if (!pbr.contains("metallicRoughnessTexture")) continue;
    ++material_maps;
    EXPECT_EQ(pbr.value("roughnessFactor", 1.0), 1.0) << material.dump();  // glTF default 1
    EXPECT_EQ(material["extensions"]["KHR_materials_diffuse_transmission"]
                      ["diffuseTransmissionTexture"]["index"],
              pbr["metallicRoughnessTexture"]["index"])
        << material.dump();
  }
  EXPECT_EQ(material_maps, 2);
  // Nothing but the outputs is left in the folder.
  std::set<std::string> outputs = textures;
  outputs.insert({"povray.png", "preview.png", "tiny.bin", "tiny.glb", "tiny.gltf", "tiny.pov"});
  const std::vector<std::string> files = test::files_in(dir);
  EXPECT_EQ(std::set<std::string>(files.begin(), files.end()), outputs);
}

TEST(SceneCommand, SameSeedSameBytesWhateverTheThreadsAnotherSeedAnotherLayout) {
  // One folder per run, the same file names (a .pov names its texture files by its stem).
  // Each run cuts and settles everything itself (its own empty cache, checked by its stats).
  const fs::path dir = test::fresh_dir("scene-determinism");
  for (const auto& [run, extra] : std::vector<std::pair<std::string, std::vector<std::string>>>{
           {"a", {"--threads", "1", "--stats"}},
           {"b", {"--threads", "2", "--stats"}},
           {"c", {"--seed", "12", "--stats"}}}) {
    fs::create_directories(dir / run);
    const test::RunResult r = test::run_cutaway(scene_args(dir / run, "s", extra));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_TRUE(test::made_afresh(r)) << run;
  }
  for (const char* file : {"s.glb", "s.pov", "s_i0_tomato_0_cut.jpg"}) {
    const std::string a = test::read_file(dir / "a" / file);
    ASSERT_FALSE(a.empty()) << file;
    EXPECT_TRUE(a == test::read_file(dir / "b" / file)) << file;
    EXPECT_FALSE(a == test::read_file(dir / "c" / file)) << file;
  }
  EXPECT_EQ(test::files_in(dir / "a"), test::files_in(dir / "b"));
}

// What keeps the byte comparisons honest: a run whose cut objects and placements were read back
// from a cache is told from one that made them (test::made_afresh), by its --stats.
TEST(SceneCommand, ARunReadFromTheCutCacheIsToldFromOneThatCutEverything) {
  const fs::path dir = test::fresh_dir("scene-afresh");
  const std::vector<std::string> cache = {"--cache", (dir / "cache").string(), "--stats"};
  const test::RunResult first = test::run_cutaway(scene_args(dir, "first", cache));
  ASSERT_EQ(first.exit_code, 0) << first.err;
  EXPECT_TRUE(test::made_afresh(first));
  const test::RunResult again = test::run_cutaway(scene_args(dir, "again", cache));
  ASSERT_EQ(again.exit_code, 0) << again.err;
  const ::testing::AssertionResult read_back = test::made_afresh(again);
  EXPECT_FALSE(read_back);
  EXPECT_NE(std::string(read_back.message()).find("read from the cut cache"), std::string::npos)
      << read_back.message();
  EXPECT_EQ(test::read_file(dir / "again.glb"), test::read_file(dir / "first.glb"));
}

/// The cut_cache object of a run's --stats line (null when there is none).
nlohmann::json cut_cache_stats(const test::RunResult& run) {
  std::istringstream lines(run.err);
  nlohmann::json found;
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("{", 0) == 0) {
      const nlohmann::json j = nlohmann::json::parse(line, nullptr, false);
      if (j.is_object() && j.contains("cut_cache")) found = j["cut_cache"];
    }
  return found;
}

// KTX2 textures are kept in the cut cache beside the cut objects (entries a JPEG run does not
// make) and read back by the next run, the same bytes as a run that encodes every texture
// afresh.
TEST(SceneCommand, Ktx2TexturesAreKeptInTheCutCacheAsTheBytesAFreshRunWrites) {
  const fs::path dir = test::fresh_dir("scene-ktx2-cache");
  const std::string cache = (dir / "cache").string();
  auto run = [&](const std::string& stem, std::vector<std::string> more) {
    std::vector<std::string> args = scene_args(dir, stem, {"--stats"});
    args.insert(args.end(), more.begin(), more.end());
    const test::RunResult r = test::run_cutaway(args);
    EXPECT_EQ(r.exit_code, 0) << stem << ": " << r.err;
    return r;
  };
  const nlohmann::json jpeg =
      cut_cache_stats(run("jpeg", {"--cache", (dir / "jpeg-cache").string()}));
  const nlohmann::json first =
      cut_cache_stats(run("first", {"--textures", "ktx2", "--cache", cache}));
  ASSERT_TRUE(jpeg.is_object() && first.is_object());
  EXPECT_GT(first["stored"].get<int>(), jpeg["stored"].get<int>());  // the textures' entries
  const nlohmann::json again =
      cut_cache_stats(run("again", {"--textures", "ktx2", "--cache", cache}));
  EXPECT_EQ(again["hits"], first["stored"]);
  EXPECT_EQ(again["stored"], 0);
  EXPECT_EQ(test::read_file(dir / "again.glb"), test::read_file(dir / "first.glb"));
  const test::RunResult fresh = run("fresh", {"--textures", "ktx2", "--no-cache"});
  EXPECT_TRUE(test::made_afresh(fresh));
  EXPECT_EQ(test::read_file(dir / "fresh.glb"), test::read_file(dir / "first.glb"));
}

TEST(SceneCommand, RefusesBadArgumentsAndLeavesNothing) {
  const fs::path dir = test::fresh_dir("scene-bad");
  const std::vector<std::vector<std::string>> bad = {
      {"scene", kTiny, "-o", (dir / "x.obj").string()},
      {"scene", kTiny, "-o", (dir / "x.glb").string(), "--png", (dir / "x.jpg").string()},
      {"scene", "tests/data/scenes/missing.yaml", "-o", (dir / "x.glb").string()},
      {"scene", kTiny, "-o", (dir / "x.glb").string(), "--compress", "zip"},
      {"scene", kTiny, "-o", (dir / "x.pov").string(), "--textures", "gif"},
      {"scene", "tests/data/scenes/bad/unknown_field.yaml", "-o", (dir / "x.glb").string()},
      {"piece", "templates/tomato.yaml", "--cut", "slices:0", "-o", (dir / "x.glb").string()},
      {"piece", "templates/tomato.yaml", "--cut", "dice:0.5", "-o", (dir / "x.glb").string()},
      {"piece", "templates/tomato.yaml", "--cut", "plane:y=500", "-o", (dir / "x.glb").string()},
  };
  for (const auto& args : bad) {
    const test::RunResult r = test::run_cutaway(args);
    EXPECT_EQ(r.exit_code, 2) << args[1] << " " << args[2] << ": " << r.err;
    EXPECT_FALSE(r.err.empty());
  }
  EXPECT_TRUE(test::files_in(dir).empty());
}

/// The JSON chunk of a .glb file.
nlohmann::json glb_json(const fs::path& file) {
  const std::string glb = test::read_file(file);
  uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.substr(20, length));
}

TEST(PieceCommand, HalvesGiveTwoValidMeshesAndAPicture) {
  const fs::path dir = test::fresh_dir("piece");
  const test::RunResult r =
      test::run_cutaway({"piece", "templates/tomato.yaml", "--cut", "halves", "--backend", "cpu",
                         "--cube", "4", "-q", "--colours", "vertex", "-o",
                         (dir / "halves.glb").string(), "--png", (dir / "halves.png").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::GltfReport report = test::validate_gltf(dir / "halves.glb");
  EXPECT_EQ(report.errors, 0) << report.output;
  const test::PngInfo png = test::png_info(dir / "halves.png");
  EXPECT_EQ(png.width, 800);
  EXPECT_GT(png.not_background, 800u * 600u / 20);
  // The same halves meshopt-compressed: valid, smaller (in vertex colours, the file is its
  // geometry), the same triangles in three.js.
  const test::RunResult m = test::run_cutaway(
      {"piece", "templates/tomato.yaml", "--cut", "halves", "--backend", "cpu", "--cube", "4", "-q",
       "--colours", "vertex", "-o", (dir / "meshopt.glb").string(), "--compress", "meshopt"});
  ASSERT_EQ(m.exit_code, 0) << m.err;
  EXPECT_EQ(test::validate_gltf(dir / "meshopt.glb").errors, 0);
  EXPECT_LT(fs::file_size(dir / "meshopt.glb"), fs::file_size(dir / "halves.glb") / 2);
  const test::ThreeLoadReport plain = test::load_gltf_three(dir / "halves.glb");
  const test::ThreeLoadReport packed = test::load_gltf_three(dir / "meshopt.glb");
  ASSERT_TRUE(packed.ok) << packed.error << "\n" << packed.output;
  EXPECT_EQ(packed.triangles, plain.triangles);
  EXPECT_GT(plain.triangles, 10000);
  // By default the cut faces and the skin are baked into textures, as in scenes: a cantaloupe
  // wedge's skin carries its netting's colour and relief (base colour and normal map).
  const test::RunResult t =
      test::run_cutaway({"piece", "templates/cantaloupe.yaml", "--cut", "wedges:6", "--backend",
                         "cpu", "--cube", "4", "-q", "-o", (dir / "cantaloupe.glb").string()});
  ASSERT_EQ(t.exit_code, 0) << t.err;
  const test::GltfReport textured = test::validate_gltf(dir / "cantaloupe.glb");
  EXPECT_EQ(textured.errors, 0) << textured.output;
  size_t normal_mapped = 0;
  const nlohmann::json gltf = glb_json(dir / "cantaloupe.glb");
  for (const auto& material : gltf["materials"])
    normal_mapped += material.contains("normalTexture") &&
                     material["pbrMetallicRoughness"].contains("baseColorTexture");
  EXPECT_EQ(normal_mapped, 1u);
}

// The style decides the ink strokes: realistic (the default) draws none, illustration draws the
// silhouettes and the outlines inside the cut faces; --silhouettes wins over --style.
TEST(PieceCommand, TheStyleDecidesTheInkStrokes) {
  const fs::path dir = test::fresh_dir("piece_style");
  const auto strokes = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {
        "--stats", "piece", "templates/tomato.yaml", "--cut", "halves", "--cube", "4", "--colours",
        "vertex",  "--png", (dir / "p.png").string()};
    args.insert(args.end(), extra.begin(), extra.end());
    const test::RunResult r = test::run_cutaway(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    const std::string json = r.err.substr(r.err.rfind("\n{") + 1);
    return nlohmann::json::parse(json)["strokes"].get<int>();
  };
  EXPECT_EQ(strokes({}), 0);
  EXPECT_EQ(strokes({"--style", "realistic"}), 0);
  const int drawn = strokes({"--style", "illustration"});
  EXPECT_GT(drawn, 0);
  EXPECT_EQ(strokes({"--style", "illustration", "--silhouettes", "0"}), 0);
  EXPECT_EQ(strokes({"--silhouettes", "1"}), drawn);
  const test::RunResult bad =
      test::run_cutaway({"piece", "templates/tomato.yaml", "--cut", "halves", "--style", "photo",
                         "--png", (dir / "q.png").string()});
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--style"), std::string::npos) << bad.err;
}

// A piece asset drops into another scene: one root named after it at the origin, no camera,
// no lights unless asked; its pieces' nodes placed alike whatever the compression (the
// quantization's scale and offset sit on the mesh nodes below them).
TEST(PieceCommand, AssetsHaveOneRootNoCameraOrLightsAndTheSameTransformsWhateverTheCompression) {
  const fs::path dir = test::fresh_dir("piece-engine");
  std::map<std::string, nlohmann::json> files;
  for (const char* compress : {"none", "quantize", "meshopt"}) {
    const fs::path file = dir / (std::string(compress) + ".glb");
    const test::RunResult r = test::run_cutaway(
        {"piece", "templates/tomato.yaml", "--cut", "wedges:3", "--backend", "cpu", "--cube", "4",
         "-q", "-o", file.string(), "--compress", compress});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_EQ(test::validate_gltf(file).errors, 0) << compress;
    files[compress] = glb_json(file);
  }
  for (const auto& [compress, j] : files) {
    EXPECT_FALSE(j.contains("cameras")) << compress;
    EXPECT_FALSE(j.contains("extensions") && j["extensions"].contains("KHR_lights_punctual"))
        << compress;
    ASSERT_EQ(j.at("scenes").at(0).at("nodes").size(), 1u) << compress;
    const auto& root = j["nodes"][j.at("scenes").at(0).at("nodes").at(0).get<size_t>()];
    EXPECT_EQ(root["name"], j.at("scenes").at(0).at("name")) << compress;
    EXPECT_FALSE(root.contains("translation") || root.contains("rotation") ||
                 root.contains("scale"));
    ASSERT_EQ(root["children"].size(), 3u) << compress;
    for (size_t k = 0; k < 3; ++k) {
      const auto& piece = j["nodes"][root["children"][k].get<size_t>()];
      const auto& reference = files["none"]["nodes"][root["children"][k].get<size_t>()];
      EXPECT_EQ(piece.value("translation", nlohmann::json()),
                reference.value("translation", nlohmann::json()));
      EXPECT_EQ(piece.value("rotation", nlohmann::json()),
                reference.value("rotation", nlohmann::json()));
      EXPECT_FALSE(piece.contains("scale")) << compress;
      EXPECT_EQ(piece["extras"]["piece"], static_cast<int>(k)) << compress;
      // Below the piece: its mesh node, then its convex collision hulls, named for Godot.
      ASSERT_GE(piece["children"].size(), 2u) << compress;
      for (size_t c = 1; c < piece["children"].size(); ++c) {
        const auto& hull = j["nodes"][piece["children"][c].get<size_t>()];
        EXPECT_EQ(hull["name"].get<std::string>(), piece["name"].get<std::string>() + "_collision" +
                                                       std::to_string(c - 1) + "-convcolonly");
        EXPECT_EQ(hull["extras"]["collision"], "convex");
      }
    }
  }
  // Unreal's naming: UCX_ and the render mesh's name; none: no hulls.
  for (const char* naming : {"unreal", "none"}) {
    const fs::path file = dir / (std::string(naming) + "-hulls.glb");
    const test::RunResult r =
        test::run_cutaway({"piece", "templates/tomato.yaml", "--cut", "halves", "--backend", "cpu",
                           "--cube", "4", "-q", "-o", file.string(), "--collision", naming});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = glb_json(file);
    size_t hulls = 0;
    for (const auto& node : j["nodes"])
      if (node.contains("extras") && node["extras"].contains("collision")) {
        ++hulls;
        EXPECT_EQ(node["name"].get<std::string>().rfind("UCX_", 0), 0u) << node["name"];
      }
    EXPECT_EQ(hulls > 0, std::string(naming) == "unreal") << naming;
  }
  // Asked for, the preview's camera and lights come along.
  const test::RunResult r = test::run_cutaway({"piece", "templates/tomato.yaml", "--cut", "halves",
                                               "--backend", "cpu", "--cube", "4", "-q", "-o",
                                               (dir / "lit.glb").string(), "--camera-and-lights"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const nlohmann::json lit = glb_json(dir / "lit.glb");
  EXPECT_EQ(lit["cameras"].size(), 1u);
  EXPECT_EQ(lit["extensions"]["KHR_lights_punctual"]["lights"].size(), 3u);
}

// Each engine profile writes what its consumer reads: a valid file (no validator warnings), its
// vertex encoding, its collision naming (Godot's -rigid mesh nodes, Unreal's UCX_ hulls, none
// for the others) and, for the game engines, each piece's mesh node at its centre of mass
// rather than at its box's centre (the blender file's); three.js draws every one alike.
TEST(PieceCommand, EachEngineProfileWritesWhatItsConsumerReads) {
  const fs::path dir = test::fresh_dir("piece-profiles");
  struct Expected {
    std::set<std::string> encoding;  // the vertex encoding's extensions (none: float32)
    const char* hull_prefix;
    bool rigid, pivots;
  };
  const std::map<std::string, Expected> expected = {
      {"godot", {{}, nullptr, true, true}},
      {"unreal", {{}, "UCX_", false, true}},
      {"unity", {{"KHR_mesh_quantization"}, nullptr, false, true}},
      {"web", {{"KHR_mesh_quantization", "EXT_meshopt_compression"}, nullptr, false, false}},
      {"blender", {{"KHR_mesh_quantization"}, nullptr, false, false}}};
  std::map<std::string, nlohmann::json> files;
  std::map<std::string, long> drawn;  // triangles three.js draws
  for (const std::string_view name : kEngineProfiles) {
    const std::string profile(name);
    ASSERT_TRUE(expected.count(profile)) << profile << ": a profile this test does not know";
    const Expected& e = expected.at(profile);
    const fs::path file = dir / (profile + ".glb");
    const test::RunResult r = test::run_cutaway(
        {"piece", "templates/tomato.yaml", "--cut", "wedges:3", "--backend", "cpu", "--cube", "4",
         "-q", "--apart", "0", "-o", file.string(), "--for", profile});
    ASSERT_EQ(r.exit_code, 0) << profile << ": " << r.err;
    const test::GltfReport report = test::validate_gltf(file);
    EXPECT_EQ(report.errors, 0) << profile << ": " << report.output;
    EXPECT_EQ(nlohmann::json::parse(report.output).value("warnings", -1), 0)
        << profile << ": " << report.output;
    const nlohmann::json j = glb_json(file);
    files[profile] = j;
    std::set<std::string> encoding;
    for (const std::string extension : j.value("extensionsUsed", nlohmann::json::array()))
      if (extension == "KHR_mesh_quantization" || extension == "EXT_meshopt_compression")
        encoding.insert(extension);
    EXPECT_EQ(encoding, e.encoding) << profile;
    size_t hulls = 0, rigid = 0, meshes = 0;
    for (const auto& node : j["nodes"]) {
      const std::string node_name = node.value("name", "");
      if (node.contains("extras") && node["extras"].contains("collision")) {
        ++hulls;
        EXPECT_TRUE(e.hull_prefix && node_name.rfind(e.hull_prefix, 0) == 0) << profile << node;
      }
      if (node.contains("mesh")) {
        ++meshes;
        rigid += node_name.size() > 6 && node_name.substr(node_name.size() - 6) == "-rigid";
      }
    }
    EXPECT_EQ(hulls > 0, e.hull_prefix != nullptr) << profile;
    EXPECT_EQ(rigid, e.rigid ? 3u : 0u) << profile;
    EXPECT_EQ(meshes, 3u + hulls) << profile;
    if (profile != "godot") {  // Godot reads it itself (tests/godot/)
      const test::ThreeLoadReport three = test::load_gltf_three(file);
      ASSERT_TRUE(three.ok) << profile << ": " << three.error;
      drawn[profile] = three.triangles;
    }
  }
  // three.js draws the same pieces from each; Unreal's hulls are meshes it draws as well.
  for (const auto& [profile, triangles] : drawn)
    if (expected.at(profile).hull_prefix) EXPECT_GT(triangles, drawn.at("blender")) << profile;
    else EXPECT_EQ(triangles, drawn.at("blender")) << profile;
  // Pivots: where the first piece's mesh node sits in its piece (metres): at the centre of mass
  // for the game engines, alike in each of them; at the centre of its box (quantize's frame)
  // for blender.
  auto mesh_offset = [&](const std::string& profile) {
    const nlohmann::json& j = files.at(profile);
    const auto& root = j["nodes"][j["scenes"][0]["nodes"][0].get<size_t>()];
    const auto& piece = j["nodes"][root["children"][0].get<size_t>()];
    const auto& mesh = j["nodes"][piece["children"][0].get<size_t>()];
    return mesh.value("translation", std::vector<double>{0, 0, 0});
  };
  const std::vector<double> centre_of_mass = mesh_offset("godot");
  for (const auto& [profile, e] : expected) {
    const std::vector<double> offset = mesh_offset(profile);
    double gap = 0;
    for (int k = 0; k < 3; ++k) gap = std::max(gap, std::abs(offset[k] - centre_of_mass[k]));
    if (e.pivots) EXPECT_LT(gap, 1e-6) << profile;
    else if (profile == "blender") EXPECT_GT(gap, 1e-4) << profile;
  }
}

TEST(PieceCommand, LevelsOfDetailHalveTheTrianglesAndLeaveNoHoles) {
  const fs::path dir = test::fresh_dir("piece-lods");
  const test::RunResult r =
      test::run_cutaway({"piece", "templates/tomato.yaml", "--cut", "wedges:4", "--backend", "cpu",
                         "--cube", "4", "-q", "-o", (dir / "lods.glb").string(), "--lods", "2",
                         "--compress", "none", "--collision", "none"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::GltfReport report = test::validate_gltf(dir / "lods.glb");
  EXPECT_EQ(report.errors, 0) << report.output;
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, (dir / "lods.glb").string())) << err;
  ASSERT_EQ(m.meshes.size(), 12u);  // 4 pieces, 3 levels each
  auto triangles = [&](const tinygltf::Mesh& mesh) {
    size_t n = 0;
    for (const auto& prim : mesh.primitives) n += m.accessors.at(prim.indices).count / 3;
    return static_cast<double>(n);
  };
  for (size_t piece = 0; piece < 4; ++piece) {
    const tinygltf::Mesh& full = m.meshes[3 * piece];
    const tinygltf::Mesh& lod1 = m.meshes[3 * piece + 1];
    const tinygltf::Mesh& lod2 = m.meshes[3 * piece + 2];
    EXPECT_EQ(lod1.name, full.name + "_LOD1");
    EXPECT_EQ(lod2.name, full.name + "_LOD2");
    EXPECT_TRUE(test::watertight(m, full)) << full.name;
    EXPECT_TRUE(test::watertight(m, lod1)) << lod1.name;
    EXPECT_TRUE(test::watertight(m, lod2)) << lod2.name;
    EXPECT_NEAR(triangles(lod1) / triangles(full), 0.5, 0.1) << lod1.name;
    EXPECT_NEAR(triangles(lod2) / triangles(full), 0.25, 0.1) << lod2.name;
    // The full node names its levels' nodes, which draw the level meshes where it stands.
    const tinygltf::Node& piece_node = m.nodes[1 + 2 * piece];
    const tinygltf::Node& node = m.nodes.at(static_cast<size_t>(piece_node.children.at(0)));
    ASSERT_TRUE(node.extensions.count("MSFT_lod")) << node.name;
    const tinygltf::Value& ids = node.extensions.at("MSFT_lod").Get("ids");
    ASSERT_EQ(ids.ArrayLen(), 2u);
    for (int l = 0; l < 2; ++l) {
      const tinygltf::Node& level = m.nodes.at(static_cast<size_t>(ids.Get(l).GetNumberAsInt()));
      EXPECT_EQ(level.name, piece_node.name + "_LOD" + std::to_string(l + 1));
      EXPECT_EQ(level.mesh, 3 * static_cast<int>(piece) + 1 + l);
      EXPECT_EQ(level.translation, node.translation);
      EXPECT_EQ(level.scale, node.scale);
      EXPECT_EQ(level.rotation, node.rotation);
    }
  }
}

}  // namespace
}  // namespace cutaway
