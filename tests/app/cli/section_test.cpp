// `cutaway section` end to end: glb (Khronos validator), PLY and PNG output, --stats (with the
// output hashes), bad planes and planes that miss or only touch the object (exit 2, nothing
// written), and byte-identical output across runs and thread counts, with either --sampling.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "batch/variant_batch.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

const std::string kSpheres = "templates/spheres.yaml";

TEST(SectionCommand, WritesAValidGlb) {
  for (const char* tmpl : {"templates/tomato.yaml", "templates/onion.yaml"}) {
    const fs::path dir = test::fresh_dir("cli_section_glb");
    const test::RunResult r = test::run_cutaway({"section", tmpl, "--plane", "4,20,1/0.2,1,0.1",
                                                 "--cube", "8", "-o", (dir / "x.glb").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(test::files_in(dir), std::vector<std::string>{"x.glb"});
    EXPECT_EQ(test::read_file(dir / "x.glb").substr(0, 4), "glTF");
    const test::GltfReport v = test::validate_gltf(dir / "x.glb");
    EXPECT_EQ(v.errors, 0) << tmpl << ": " << v.output;
  }
}

TEST(SectionCommand, WritesABinaryPlyWithColours) {
  const fs::path dir = test::fresh_dir("cli_section_ply");
  const test::RunResult r = test::run_cutaway(
      {"section", kSpheres, "--plane", "y=10", "--cube", "8", "-o", (dir / "x.ply").string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string ply = test::read_file(dir / "x.ply");
  const size_t end = ply.find("end_header\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = ply.substr(0, end);
  EXPECT_EQ(header.substr(0, 4), "ply\n");
  EXPECT_NE(header.find("format binary_little_endian 1.0"), std::string::npos) << header;
  EXPECT_NE(header.find("property uchar red"), std::string::npos) << header;
  EXPECT_NE(header.find("property uchar green"), std::string::npos) << header;
  EXPECT_NE(header.find("property uchar blue"), std::string::npos) << header;
  EXPECT_NE(header.find("element face"), std::string::npos) << header;
  EXPECT_GT(ply.size(), end + 11 + 1000) << "too little binary data";
}

TEST(SectionCommand, WritesAPngAndStats) {
  const fs::path dir = test::fresh_dir("cli_section_png");
  const test::RunResult r =
      test::run_cutaway({"section", kSpheres, "--plane", "z=0", "--cube", "8", "--png",
                         (dir / "x.png").string(), "--size", "96", "--stats"});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  // --png alone writes only the PNG.
  ASSERT_EQ(test::files_in(dir), std::vector<std::string>{"x.png"});
  const std::string png = test::read_file(dir / "x.png");
  ASSERT_GT(png.size(), 24u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  // Exactly one JSON line on stderr (with -q nothing else is printed; here logging may be).
  std::istringstream lines(r.err);
  std::string line;
  int json_lines = 0;
  while (std::getline(lines, line)) {
    if (line.empty() || line.front() != '{') continue;
    ++json_lines;
    const nlohmann::json j = nlohmann::json::parse(line);
    EXPECT_GT(j.at("vertices").get<long>(), 0);
    EXPECT_GT(j.at("interior_vertices").get<long>(), 0);
    EXPECT_LT(j.at("interior_vertices").get<long>(), j.at("vertices").get<long>());
    ASSERT_TRUE(j.at("seconds").is_object());
    for (const auto& [key, value] : j.at("seconds").items()) {
      EXPECT_TRUE(value.is_number()) << key;
      EXPECT_GE(value.get<double>(), 0) << key;
    }
  }
  EXPECT_EQ(json_lines, 1) << r.err;

  const test::RunResult quiet =
      test::run_cutaway({"section", kSpheres, "--plane", "z=0", "--cube", "4", "-q", "--stats",
                         "-o", (dir / "q.glb").string()});
  ASSERT_EQ(quiet.exit_code, 0) << quiet.err;
  EXPECT_EQ(std::count(quiet.err.begin(), quiet.err.end(), '\n'), 1) << quiet.err;
  ASSERT_TRUE(nlohmann::json::accept(quiet.err)) << quiet.err;
  // The same line ends with the written file's content hash.
  const nlohmann::json hashes = nlohmann::json::parse(quiet.err).at("outputs_fnv1a64");
  ASSERT_EQ(hashes.size(), 1u) << quiet.err;
  EXPECT_EQ(fs::path(hashes.begin().key()).filename(), "q.glb") << quiet.err;
  // Run from a folder beside the file, the file is named by its absolute path, not "../q.glb".
  fs::create_directories(dir / "elsewhere");
  const test::RunResult outside = test::run_program(
      "sh", {"-c", "cd '" + (dir / "elsewhere").string() + "' && '" + CUTAWAY_BINARY +
                       "' section '" + fs::absolute(kSpheres).string() +
                       "' --plane z=0 --cube 4 -q --stats -o ../q.glb"});
  ASSERT_EQ(outside.exit_code, 0) << outside.err;
  const nlohmann::json named = nlohmann::json::parse(outside.err).at("outputs_fnv1a64");
  ASSERT_EQ(named.size(), 1u) << outside.err;
  EXPECT_EQ(named.begin().key(), fs::absolute(dir / "q.glb").lexically_normal().string());
  EXPECT_EQ(hashes.begin().value(), hex64(fnv1a64(test::read_file(dir / "q.glb"))));
}

TEST(SectionCommand, BadPlanesExitTwoAndWriteNothing) {
  for (const std::string plane : {"y=abc", "1,2/0,0,0", "0,0,0/0,0,0", "w=3", "", "y=", "1,2,3"}) {
    const fs::path dir = test::fresh_dir("cli_section_bad");
    const test::RunResult r =
        test::run_cutaway({"section", kSpheres, "--plane", plane, "-o", (dir / "x.glb").string(),
                           "--png", (dir / "x.png").string()});
    EXPECT_EQ(r.exit_code, 2) << "--plane '" << plane << "': " << r.err;
    EXPECT_NE(r.err.find("plane"), std::string::npos) << r.err;
    EXPECT_TRUE(test::files_in(dir).empty()) << "--plane '" << plane << "'";
  }
}

TEST(SectionCommand, PlaneMissingOrTouchingTheObjectExitsTwo) {
  for (const std::string plane : {"y=100", "y=40", "y=-40", "100,0,0/1,0.5,0"}) {
    const fs::path dir = test::fresh_dir("cli_section_miss");
    const test::RunResult r =
        test::run_cutaway({"section", kSpheres, "--plane", plane, "-o", (dir / "x.glb").string()});
    EXPECT_EQ(r.exit_code, 2) << "--plane " << plane << ": " << r.err;
    EXPECT_TRUE(r.err.find("misses") != std::string::npos ||
                r.err.find("touches") != std::string::npos)
        << r.err;
    EXPECT_TRUE(test::files_in(dir).empty()) << "--plane " << plane;
  }
  // Just inside the pole: a valid tiny section or the same clear refusal, never a crash.
  const fs::path dir = test::fresh_dir("cli_section_pole");
  const test::RunResult r = test::run_cutaway(
      {"section", kSpheres, "--plane", "y=39.999", "--cube", "4", "-o", (dir / "x.glb").string()});
  if (r.exit_code == 0) {
    const test::GltfReport v = test::validate_gltf(dir / "x.glb");
    EXPECT_EQ(v.errors, 0) << v.output;
  } else {
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_TRUE(test::files_in(dir).empty());
  }
}

// A calyx with sharp sepal tips (tests/data/sharp_calyx.yaml): the skin folds back at the
// tips, and a face of the cap's triangulation lies a hair off a skin cut segment there. Every
// plane through the axis or near it keeps its cap: a valid file with the whole berry's cut.
TEST(SectionCommand, SharpTipsKeepTheCap) {
  for (const std::string plane : {"z=0", "z=2", "z=-2", "x=3", "x=0"}) {
    const fs::path dir = test::fresh_dir("cli_section_calyx");
    const test::RunResult r =
        test::run_cutaway({"section", "tests/data/sharp_calyx.yaml", "--plane", plane, "--cube",
                           "4", "-q", "--stats", "-o", (dir / "x.glb").string()});
    ASSERT_EQ(r.exit_code, 0) << "--plane " << plane << ": " << r.err;
    const nlohmann::json stats = nlohmann::json::parse(r.err);
    EXPECT_GT(stats.at("vertices").get<int>(), 1000) << "--plane " << plane;
    const test::GltfReport v = test::validate_gltf(dir / "x.glb");
    EXPECT_EQ(v.errors, 0) << v.output;
  }
}

TEST(SectionCommand, ByteIdenticalAcrossRunsAndThreadCounts) {
  std::string glb[7];
  const std::vector<std::vector<std::string>> extra = {{"--sampling", "dense"},
                                                       {"--sampling", "dense", "--threads", "1"},
                                                       {"--sampling", "dense", "--threads", "2"},
                                                       {"--threads", "1"},  // adaptive, the default
                                                       {"--threads", "2"},
                                                       {"--directions", "every", "--threads", "1"},
                                                       {"--directions", "every", "--threads", "2"}};
  for (int run = 0; run < 7; ++run) {
    const fs::path dir = test::fresh_dir("cli_section_det_" + std::to_string(run));
    std::vector<std::string> args = {"section", "templates/tomato.yaml",
                                     "--plane", "3,25,-2/0.3,0.2,1",
                                     "--cube",  "8",
                                     "-o",      (dir / "x.glb").string()};
    args.insert(args.end(), extra[run].begin(), extra[run].end());
    const test::RunResult r = test::run_cutaway(args);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    glb[run] = test::read_file(dir / "x.glb");
  }
  ASSERT_FALSE(glb[0].empty());
  EXPECT_TRUE(glb[0] == glb[1]) << "the glb differs between two runs";
  EXPECT_TRUE(glb[1] == glb[2]) << "the glb differs between --threads 1 and 2";
  EXPECT_TRUE(glb[3] == glb[4]) << "adaptive sampling: the glb differs between --threads 1 and 2";
  EXPECT_FALSE(glb[0] == glb[3]) << "--sampling dense changed nothing";
  EXPECT_TRUE(glb[5] == glb[6]) << "every texel: the glb differs between --threads 1 and 2";
  EXPECT_FALSE(glb[3] == glb[5]) << "--directions every changed nothing";
}

TEST(SectionCommand, AdaptiveDirectionsCastFewerRaysThanEveryTexel) {
  long rays[2] = {0, 0}, points[2] = {0, 0};
  const char* directions[2] = {"every", "adaptive"};
  for (int d = 0; d < 2; ++d) {
    const fs::path dir = test::fresh_dir(std::string("cli_section_directions_") + directions[d]);
    const test::RunResult r = test::run_cutaway(
        {"--sampling", "dense", "--directions", directions[d], "section", "templates/tomato.yaml",
         "--plane", "y=30", "--cube", "8", "-q", "--stats", "-o", (dir / "x.glb").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.err);
    rays[d] = j.at("rays").get<long>();
    points[d] = j.at("diffused_points").get<long>();
  }
  EXPECT_EQ(points[0], points[1]);  // dense: the same mesh, every vertex
  EXPECT_EQ(rays[0], points[0] * 6 * 8 * 8);
  EXPECT_LT(rays[1], rays[0] * 3 / 4);
  EXPECT_GE(rays[1], points[1] * 6 * 4 * 4);
}

TEST(SectionCommand, AdaptiveSamplingDiffusesFewerPointsOnTheSameMesh) {
  long points[2] = {0, 0}, vertices[2] = {0, 0};
  const char* modes[2] = {"dense", "adaptive"};
  for (int m = 0; m < 2; ++m) {
    const fs::path dir = test::fresh_dir(std::string("cli_section_sampling_") + modes[m]);
    const test::RunResult r =
        test::run_cutaway({"--sampling", modes[m], "section", "templates/tomato.yaml", "--plane",
                           "y=30", "--cube", "8", "-q", "--stats", "-o", (dir / "x.glb").string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const nlohmann::json j = nlohmann::json::parse(r.err);
    points[m] = j.at("diffused_points").get<long>();
    vertices[m] = j.at("vertices").get<long>();
  }
  EXPECT_EQ(vertices[0], vertices[1]);
  EXPECT_GT(points[0], 2 * points[1]);
}

}  // namespace
}  // namespace cutaway
