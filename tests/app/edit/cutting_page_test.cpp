// The cutting page (app/edit/web/cut.html) in headless Chromium (tests/tools/cut_in_chromium.mjs)
// on `cutaway edit`, used as a person would: a tomato and a kiwi cut live from their interior
// volumes, the cut face against the reading rule, the plane dragged, knife strokes drawn, frame
// times measured.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>
#include <string>

#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

// One test per fruit (each its own editor and browser), so that they run side by side.
class CuttingPage : public ::testing::TestWithParam<std::string> {};

TEST_P(CuttingPage, CutsLiveFromItsVolume) {
  const std::string fruit = GetParam();
  const fs::path dir = test::fresh_dir("cutting-page-" + fruit);
  // A copy: the editor may write the file it serves (it does not here).
  fs::copy_file(test::source_path("templates") / (fruit + ".yaml"), dir / (fruit + ".yaml"));
  const test::NodeToolRun run = test::run_node_tool(
      "cut_in_chromium.mjs", {"--cutaway", CUTAWAY_BINARY, (dir / (fruit + ".yaml")).string(),
                              "--out", dir.string(), "--volume-voxels", "48"});
  ASSERT_TRUE(run.report.is_object()) << run.output;
  const nlohmann::json& r = run.report;
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(r.value("ok", false)) << r.dump();
  EXPECT_TRUE(r["warnings"].empty()) << r["warnings"].dump();
  ASSERT_EQ(r["pages"].size(), 1u) << r.dump();
  const nlohmann::json& page = r["pages"][0];
  // The page decoded the flipbooks to the byte, and its cut face shows the volume as the
  // reading rule reads it (8-bit rounding apart), nothing where the volume is empty.
  EXPECT_TRUE(page.value("bytes_ok", false));
  EXPECT_GE(page.value("cap_points", 0), 200);
  EXPECT_LE(page.value("max_diff", 255), 2);
  EXPECT_LE(page.value("mean_diff", 255.0), 1.0);
  EXPECT_EQ(page.value("empty_mismatches", -1), 0);
  EXPECT_TRUE(page.value("drag_ok", false));
  EXPECT_TRUE(page.value("flip_ok", false));
  EXPECT_TRUE(page.value("knife_ok", false));
  EXPECT_GE(page.value("frames", 0), 25);
  std::cout << page["name"] << ": frame " << page["frame_ms_mean"] << " ms mean, "
            << page["frame_ms_p95"] << " ms p95 (software WebGL)\n";
  EXPECT_TRUE(fs::exists(dir / ("cut-" + fruit + "-knife-shift.png")));
  // The kiwi's sharp surfaces (locule walls, seeds) bound regions: the page chose between them.
  if (fruit == "kiwi") {
    EXPECT_GT(page.value("regions_compared", 0), 1);
  }
}

INSTANTIATE_TEST_SUITE_P(Fruits, CuttingPage, ::testing::Values("tomato", "kiwi"));

// An avocado cut through its pit on the page, both ways: the half that holds the pit shows it
// whole, the other a smooth cavity in the flesh's colour, as `cutaway piece` cuts it.
TEST(CuttingPageStones, APitStaysWholeInTheHalfThatHoldsIt) {
  const fs::path dir = test::fresh_dir("cutting-page-avocado");
  fs::copy_file(test::source_path("templates/avocado.yaml"), dir / "avocado.yaml");
  const test::NodeToolRun run = test::run_node_tool(
      "cut_in_chromium.mjs", {"--cutaway", CUTAWAY_BINARY, (dir / "avocado.yaml").string(), "--out",
                              dir.string(), "--volume-voxels", "48", "--stones"});
  ASSERT_TRUE(run.report.is_object()) << run.output;
  const nlohmann::json& r = run.report;
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(r.value("ok", false)) << r.dump();
  ASSERT_EQ(r["pages"].size(), 1u) << r.dump();
  const nlohmann::json& page = r["pages"][0];
  EXPECT_TRUE(page.value("bytes_ok", false));
  EXPECT_TRUE(page.value("stones_ok", false)) << page.dump();
  ASSERT_EQ(page["stones"].size(), 1u);
  std::cout << page["stones"][0].dump() << "\n";
}

}  // namespace
}  // namespace cutaway
