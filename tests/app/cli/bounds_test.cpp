// Inputs within every documented rule that used to cost gigabytes, never end or fail with exit
// code 1, each run with 2 GiB of address space and 60 s of CPU time (a guard against a hang):
// each must end in exit 0 or 2, within bounds on memory and bytes read, with a message that
// names the field of the total it passes. The inputs are in tests/data/bounds/ (copies of
// shipped templates and scenes with one value pushed to the edge); the large ones (a
// 128,000-object scene, a 32-million-asset batch) are generated here.
#include <sys/stat.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace cutaway {
namespace {

/// A container large enough for any heap the other totals allow (scene-format.md, Totals).
const char* const kLargeBoard =
    "container: {type: board, width: 20000, depth: 20000, height: 20}\n";

namespace fs = std::filesystem;

const std::string kDir = "tests/data/bounds/";

/// run_cutaway_limited with 2 GiB of address space and 60 s of CPU time.
test::LimitedRun run_bounded(const std::vector<std::string>& args) {
  return test::run_cutaway_limited(args, uint64_t{2} << 30, 60);
}

/// Expects exit code 2 with `rule` in the message, and at most 2 GB of memory.
void expect_refused(const test::LimitedRun& r, const std::string& rule) {
  EXPECT_EQ(r.signal, 0) << r.err;
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(rule), std::string::npos) << "'" << rule << "' missing in\n" << r.err;
  EXPECT_LT(r.peak_rss_bytes, uint64_t{2000} << 20);
}

/// Expects exit code 0 and at most 2 GB of memory.
void expect_made(const test::LimitedRun& r) {
  EXPECT_EQ(r.signal, 0) << r.err;
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_LT(r.peak_rss_bytes, uint64_t{2000} << 20);
}

TEST(Bounds, CamerasLookingStraightDownOrFromBelowMakeTheirScene) {
  const fs::path dir = test::fresh_dir("bounds");
  const test::LimitedRun down =
      run_bounded({"scene", kDir + "camera_top_down.yaml", "-o", (dir / "down.glb").string(), "-o",
                   (dir / "down.pov").string()});
  expect_made(down);
  EXPECT_TRUE(fs::exists(dir / "down.glb") && fs::exists(dir / "down.pov"));
  // From below the container, the pile is placed as from its side: every piece.
  const test::LimitedRun below =
      run_bounded({"scene", kDir + "camera_below.yaml", "-o", (dir / "below.glb").string()});
  expect_made(below);
  EXPECT_NE(below.err.find("2 pieces placed"), std::string::npos) << below.err;
  EXPECT_EQ(below.err.find("did not fit"), std::string::npos) << below.err;
}

TEST(Bounds, ContainersOfAnyAcceptedSizeCostTheSame) {
  const fs::path dir = test::fresh_dir("bounds");
  for (const char* name : {"bowl_20m", "bowl_100m"}) {
    const test::LimitedRun r = run_bounded(
        {"scene", kDir + name + ".yaml", "-o", (dir / (std::string(name) + ".glb")).string()});
    expect_made(r);
    EXPECT_LT(r.peak_rss_bytes, uint64_t{600} << 20) << name;
    EXPECT_NE(r.err.find("2 pieces placed"), std::string::npos) << r.err;
  }
}

TEST(Bounds, TemplateTotalsAreCheckedBeforeTheWork) {
  // Three concentric spheres of 1.87 M vertices each: the first passes the model's total.
  expect_refused(run_bounded({"check", kDir + "three_spheres.yaml"}),
                 "resolution.edge: the edge length is too small: surface \"s0\" would get at "
                 "least 1872112 vertices, and the model may have at most 1000000");
  // Ten grain sets of 18,943 grains each: the first passes the total.
  expect_refused(run_bounded({"check", kDir + "tomato_ten_grain_sets.yaml"}),
                 "grains[0].spacing: the spacing is too small for the region: up to 18943");
  const fs::path dir = test::fresh_dir("bounds");
  expect_refused(run_bounded({"model", kDir + "tomato_ten_grain_sets.yaml", "--seed", "1", "-o",
                              (dir / "g.glb").string()}),
                 "grains[0].spacing");
  EXPECT_FALSE(fs::exists(dir / "g.glb"));
  // Achenes 0.7 mm apart, under the total but closer than their largest semi-axis (0.9 mm):
  // pieces of wedges and dice were open.
  expect_refused(run_bounded({"check", kDir + "strawberry_achenes_0_7.yaml"}),
                 "strawberry_achenes_0_7.yaml:44:14: grains[0].spacing: the spacing (0.7 mm) is "
                 "smaller than the grain's largest semi-axis (0.9 mm)");
  // An edge longer than an eighth of the skin's height: the pieces would not close.
  expect_refused(run_bounded({"check", kDir + "avocado_edge_too_long.yaml"}),
                 "resolution.edge: the edge length must be at most 1/8");
}

TEST(Bounds, ABlurAsWideAsTheGapToTheNextLayerStillGivesClosedPieces) {
  // The shipped volcano with one layer blurred by 10 mm: its ladder points fell exactly on the
  // next layer's cut segment.
  const fs::path dir = test::fresh_dir("bounds");
  const test::LimitedRun r = run_bounded(
      {"piece", kDir + "volcano_blur_10.yaml", "--cut", "halves", "-o", (dir / "v.glb").string()});
  expect_made(r);
  EXPECT_EQ(r.err.find("not closed"), std::string::npos) << r.err;
}

TEST(Bounds, SceneAndBatchTotalsAreChecked) {
  const fs::path dir = test::fresh_dir("bounds");
  // 2,000 items of 64 okra diced: 128,000 objects and millions of pieces.
  {
    std::ofstream f(dir / "many.yaml");
    f << "format: cutaway-scene/1\nname: many\nitems:\n";
    for (int i = 0; i < 2000; ++i)
      f << "  - {template: okra, count: 64, cut: {type: dice, size: 5}}\n";
  }
  // Its first item alone: 64 okra diced at 5 mm make more pieces than a scene may hold.
  const test::LimitedRun many = run_bounded({"check", (dir / "many.yaml").string()});
  expect_refused(many, "items[0].count: the items up to here make about");
  {
    std::ofstream f(dir / "objects.yaml");
    // On a 20 m board, which holds their heap: the object total is what refuses them.
    f << "format: cutaway-scene/1\nname: objects\n" << kLargeBoard << "items:\n";
    for (int i = 0; i < 17; ++i) f << "  - {template: tomato, count: 64}\n";
  }
  expect_refused(run_bounded({"check", (dir / "objects.yaml").string()}),
                 "items[16].count: the items up to here make 1088 objects (at most 1024");
  // 256 whole tomatoes of about 16,600 model vertices each: the third item passes 3 M.
  {
    std::ofstream f(dir / "vertices.yaml");
    f << "format: cutaway-scene/1\nname: vertices\n" << kLargeBoard << "items:\n";
    for (int i = 0; i < 4; ++i) f << "  - {template: tomato, count: 64}\n";
  }
  expect_refused(run_bounded({"check", (dir / "vertices.yaml").string()}),
                 "items[2].count: the objects up to here have");
  expect_refused(run_bounded({"scene", (dir / "vertices.yaml").string(), "-o",
                              (dir / "vertices.glb").string()}),
                 "DS-model vertices (at most 3000000 in a scene)");
  EXPECT_FALSE(fs::exists(dir / "vertices.glb"));
  {
    std::ofstream f(dir / "texels.yaml");
    f << "format: cutaway-scene/1\nname: texels\nitems:\n"
         "  - {template: tomato, count: 8, cut: {type: slices, thickness: 5}}\n"
         "render: {texels_per_mm: 100}\n";
  }
  expect_refused(run_bounded({"check", (dir / "texels.yaml").string()}),
                 "render.texels_per_mm: at 100 texels per mm the cut faces would need about");
  {
    std::ofstream f(dir / "pixels.yaml");
    f << "format: cutaway-scene/1\nname: pixels\nitems:\n  - {template: tomato}\n"
         "render: {width: 8192, height: 8192}\n";
  }
  expect_refused(run_bounded({"check", (dir / "pixels.yaml").string()}),
                 "render: width x height is 67108864 pixels");
  // One asset bakes its own caps: 1 mm slices of a tomato at 100 texels per mm.
  {
    std::ofstream f(dir / "dense.yaml");
    f << "format: cutaway-batch/1\nname: dense\nitems:\n"
         "  - {template: tomato, cuts: [{type: slices, thickness: 1}]}\n"
         "export: {texels_per_mm: 100}\n";
  }
  expect_refused(run_bounded({"check", (dir / "dense.yaml").string()}),
                 "items[0].cuts[0]: at 100 texels per mm the cut faces would need about");
  // 20 items of 100,000 strawberries with 16 cuts each: 32 M assets.
  {
    std::ofstream f(dir / "batch.yaml");
    f << "format: cutaway-batch/1\nname: big\nitems:\n";
    for (int i = 0; i < 20; ++i) {
      f << "  - template: strawberry\n    count: 100000\n    seed: " << i * 100000
        << "\n    cuts:\n";
      for (int w = 2; w < 18; ++w) f << "      - {type: wedges, count: " << w << "}\n";
    }
  }
  expect_refused(run_bounded({"check", (dir / "batch.yaml").string()}),
                 "items[0].count: the items up to here make 1600000 assets (at most 1000000");
  expect_refused(run_bounded({"batch", (dir / "batch.yaml").string(), "-o", (dir / "out").string(),
                              "--shard", "1/100000"}),
                 "1600000 assets");
}

TEST(Bounds, FilesThatAreNotRegularOrTooLargeAreNotRead) {
  const fs::path dir = test::fresh_dir("bounds");
  ASSERT_EQ(::mkfifo((dir / "fifo.yaml").c_str(), 0600), 0);
  { std::ofstream(dir / "big.yaml"); }
  fs::resize_file(dir / "big.yaml", uint64_t{1} << 30);
  // Not a byte of the file is read: each run reads what the program reads before any input
  // (measured: exactly that), where /dev/zero would give bytes without end and a 16 MiB limit
  // read up to it. 4 KiB of slack, below one page of the file. (Opening the FIFO for a read
  // would block: CTest's timeout ends such a hang.)
  const uint64_t start = test::cutaway_start().read_bytes;
  for (const std::string& file : {std::string("/dev/zero"), (dir / "fifo.yaml").string()}) {
    const test::LimitedRun r = run_bounded({"check", file});
    expect_refused(r, file + ":1:1: (file): the file is not a regular file");
    EXPECT_LT(r.read_bytes, start + 4096) << "bytes read of " << file;
  }
  const test::LimitedRun big = run_bounded({"check", (dir / "big.yaml").string()});
  expect_refused(big, "(file): the file is larger than 16 MiB");
  EXPECT_LT(big.read_bytes, start + 4096) << "bytes read";
  EXPECT_LT(big.peak_rss_bytes, uint64_t{200} << 20);
}

TEST(Bounds, SmallerHolesAreClosed) {
  // A second YAML document is refused, not ignored.
  const fs::path dir = test::fresh_dir("bounds");
  {
    std::ofstream f(dir / "two.yaml");
    f << test::read_file(test::source_path("templates/tomato.yaml")) << "---\nname: other\n";
  }
  expect_refused(run_bounded({"check", (dir / "two.yaml").string()}),
                 "(file): a second YAML document");
  expect_refused(run_bounded({"check", kDir + "tomato_second_document.yaml"}), "(file): ");
  // The last variant's seed must be one --seed accepts.
  expect_refused(run_bounded({"variants", "templates/strawberry.yaml", "--seed",
                              "9223372036854775806", "--count", "3", "-o", (dir / "v").string()}),
                 "give --seed at most 9223372036854775805");
  EXPECT_FALSE(fs::exists(dir / "v"));
  // Contact sheets are held to a render's pixels before any variant or tile is made.
  expect_refused(run_bounded({"variants", "templates/tomato.yaml", "--count", "256", "--sheet",
                              "256", "--tile", "4096", "-o", (dir / "sheet").string()}),
                 "makes a contact sheet of up to 4294967296 pixels (at most 8294400)");
  expect_refused(run_bounded({"sheet", "templates/tomato.yaml", "templates/kiwi.yaml",
                              "templates/okra.yaml", "templates/onion.yaml", "templates/apple.yaml",
                              "--tile", "2048", "-o", (dir / "sheet.png").string()}),
                 "makes a sheet of up to 20971520 pixels");
  EXPECT_FALSE(fs::exists(dir / "sheet") || fs::exists(dir / "sheet.png"));
  // An empty --shard is refused, not read as the whole batch.
  expect_refused(run_bounded({"batch", "batches/fruit-assets.yaml", "-o", (dir / "b").string(),
                              "--shard", ""}),
                 "--shard");
  EXPECT_FALSE(fs::exists(dir / "b"));
  // A value just over a range is shown as written.
  {
    std::ofstream f(dir / "variation.yaml");
    f << "format: cutaway-scene/1\nname: v\nitems:\n  - {template: tomato, variation: 10.000001}\n";
  }
  expect_refused(run_bounded({"check", (dir / "variation.yaml").string()}),
                 "must be between 0 and 10, not 10.000001");
}

}  // namespace
}  // namespace cutaway
