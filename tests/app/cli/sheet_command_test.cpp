// `cutaway sheet` end to end: a two-template contact sheet is a PNG of the promised size with
// pictures and dark label text in it; --seed cuts seeded variants, deterministically; bad
// templates, cuts and views are refused with exit code 2 before anything is written.
#include <gtest/gtest.h>

#include <cstring>

#include <stb/stb_image.h>

#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

TEST(SheetCommand, TwoTemplatesMakeOneLabelledRow) {
  const fs::path dir = test::fresh_dir("sheet");
  const fs::path out = dir / "sheet.png";
  const test::RunResult r =
      test::run_cutaway({"sheet", "templates/avocado.yaml", "templates/apple.yaml:across", "--tile",
                         "128", "--cube", "4", "--backend", "cpu", "-q", "-o", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const test::PngInfo info = test::png_info(out);
  // Two tiles of 128 pixels in one row, margins of 4 pixels around and between them.
  EXPECT_EQ(info.width, 2 * 128 + 3 * 4);
  // A tile is 96 pixels of picture plus a label strip.
  EXPECT_GT(info.height, 96 + 2 * 4);
  EXPECT_LT(info.height, 96 + 2 * 4 + 40);
  // The cut objects cover a good share of the sheet, and the labels are there.
  EXPECT_GT(info.not_background, static_cast<size_t>(info.width * info.height / 10));
  EXPECT_GT(info.dark, 50u);
}

// --seed S cuts each template's variant of seed S: the same seed gives the same bytes, another
// seed (another shape, other grains, another turn of the stripes) other bytes, and so does the
// template itself.
TEST(SheetCommand, ASeedCutsEveryTemplatesVariantOfThatSeed) {
  const fs::path dir = test::fresh_dir("sheet-seed");
  auto sheet = [&](const std::string& name, const std::vector<std::string>& seed) {
    std::vector<std::string> args = {"sheet",
                                     "templates/watermelon.yaml:across",
                                     "templates/grape.yaml",
                                     "--tile",
                                     "128",
                                     "--cube",
                                     "4",
                                     "--backend",
                                     "cpu",
                                     "-q",
                                     "-o",
                                     (dir / name).string()};
    args.insert(args.end(), seed.begin(), seed.end());
    const test::RunResult r = test::run_cutaway(args);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return test::read_file(dir / name);
  };
  const std::string a = sheet("a.png", {"--seed", "3"}), b = sheet("b.png", {"--seed", "3"});
  const std::string c = sheet("c.png", {"--seed", "4"}), plain = sheet("plain.png", {});
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
  EXPECT_NE(a, plain);
}

TEST(SheetCommand, RefusesBadItemsBeforeWriting) {
  const fs::path dir = test::fresh_dir("sheet-bad");
  const fs::path out = dir / "sheet.png";
  const std::vector<std::vector<std::string>> bad = {
      {"templates/avocado.yaml", "templates/no_such_fruit.yaml"},
      {"templates/avocado.yaml", "templates/apple.yaml:slices:0"},
      {"templates/avocado.yaml", "templates/apple.yaml:julienne"},
      {"templates/avocado.yaml", "templates/apple.yaml@sideways"},
  };
  for (const auto& items : bad) {
    std::vector<std::string> args = {"sheet", "--cube", "4",  "--backend",
                                     "cpu",   "-q",     "-o", out.string()};
    args.insert(args.end(), items.begin(), items.end());
    const test::RunResult r = test::run_cutaway(args);
    EXPECT_EQ(r.exit_code, 2) << items[1] << ": " << r.err;
    EXPECT_FALSE(r.err.empty()) << items[1];
    EXPECT_FALSE(fs::exists(out)) << items[1];
  }
  const test::RunResult r = test::run_cutaway(
      {"sheet", "templates/avocado.yaml", "-q", "-o", (dir / "sheet.jpg").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
}

}  // namespace
}  // namespace cutaway
