// `cutaway sheet` end to end: a two-template contact sheet is a PNG of the promised size with
// pictures and dark label text in it; bad templates, cuts and views are refused with exit code 2
// before anything is written.
#include <gtest/gtest.h>

#include <cstring>

#include <stb/stb_image.h>

#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// Width and height of a PNG, how many pixels differ from its top-left pixel and how many are
/// near black (label text; the renders have no black).
struct PngInfo {
  int width = 0, height = 0;
  size_t not_background = 0, dark = 0;
};

PngInfo png_info(const fs::path& file) {
  const std::string png = test::read_file(file);
  PngInfo info;
  int channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                            static_cast<int>(png.size()), &info.width, &info.height, &channels, 4);
  if (!pixels) return info;
  for (int i = 0; i < info.width * info.height; ++i) {
    const unsigned char* p = pixels + 4 * i;
    info.not_background += std::memcmp(p, pixels, 3) != 0;
    info.dark += p[0] < 8 && p[1] < 8 && p[2] < 8;
  }
  stbi_image_free(pixels);
  return info;
}

TEST(SheetCommand, TwoTemplatesMakeOneLabelledRow) {
  const fs::path dir = test::fresh_dir("sheet");
  const fs::path out = dir / "sheet.png";
  const test::RunResult r = test::run_cutaway(
      {"sheet", "templates/avocado.yaml", "templates/apple.yaml:across", "--tile", "128",
       "--cube", "4", "--backend", "cpu", "-q", "-o", out.string()});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const PngInfo info = png_info(out);
  // Two tiles of 128 pixels in one row, margins of 4 pixels around and between them.
  EXPECT_EQ(info.width, 2 * 128 + 3 * 4);
  // A tile is 96 pixels of picture plus a label strip.
  EXPECT_GT(info.height, 96 + 2 * 4);
  EXPECT_LT(info.height, 96 + 2 * 4 + 40);
  // The cut objects cover a good share of the sheet, and the labels are there.
  EXPECT_GT(info.not_background, static_cast<size_t>(info.width * info.height / 10));
  EXPECT_GT(info.dark, 50u);
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
    std::vector<std::string> args = {"sheet", "--cube", "4", "--backend", "cpu", "-q",
                                     "-o", out.string()};
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
