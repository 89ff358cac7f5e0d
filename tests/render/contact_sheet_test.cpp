// compose_grid (render/image/contact_sheet.h): sheet size, tile placement and centring, background,
// refusals.
#include <gtest/gtest.h>

#include <stdexcept>

#include "batch/variant_set.h"
#include "io/template_parser.h"
#include "render/image/contact_sheet.h"
#include "test_support.h"
#include "variation/variation.h"

namespace cutaway {
namespace {

Image solid(int w, int h, uint8_t grey) {
  Image im{w, h, std::vector<uint8_t>(static_cast<size_t>(w) * h * 4, grey)};
  for (size_t i = 3; i < im.rgba.size(); i += 4) im.rgba[i] = 255;
  return im;
}

uint8_t red_at(const Image& im, int x, int y) {
  return im.rgba[(static_cast<size_t>(y) * im.width + x) * 4];
}

TEST(ComposeGrid, SizesCellsByTheLargestTileAndCentresSmallerOnes) {
  GridOptions o;
  o.margin = 2;
  o.background_srgb = {1, 1, 1};
  // 3 tiles in 2 columns: 2 rows of cells 4 x 6 pixels.
  const Image sheet = compose_grid({solid(4, 6, 10), solid(2, 2, 20), solid(4, 4, 30)}, 2, o);
  EXPECT_EQ(sheet.width, 2 * 4 + 3 * 2);
  EXPECT_EQ(sheet.height, 2 * 6 + 3 * 2);
  ASSERT_EQ(sheet.rgba.size(), static_cast<size_t>(sheet.width) * sheet.height * 4);
  EXPECT_EQ(red_at(sheet, 0, 0), 255);  // margin
  EXPECT_EQ(red_at(sheet, 2, 2), 10);   // tile 0 fills cell (0, 0)
  EXPECT_EQ(red_at(sheet, 5, 7), 10);
  // Tile 1 (2 x 2) centred in cell (1, 0), which starts at x = 8, y = 2: pixels 9..10, 4..5.
  EXPECT_EQ(red_at(sheet, 8, 2), 255);
  EXPECT_EQ(red_at(sheet, 9, 4), 20);
  EXPECT_EQ(red_at(sheet, 10, 5), 20);
  EXPECT_EQ(red_at(sheet, 11, 5), 255);
  // Tile 2 (4 x 4) in cell (0, 1) at x = 2, y = 10, one row down: rows 11..14.
  EXPECT_EQ(red_at(sheet, 2, 10), 255);
  EXPECT_EQ(red_at(sheet, 2, 11), 30);
  EXPECT_EQ(red_at(sheet, 5, 14), 30);
  EXPECT_EQ(red_at(sheet, 9, 12), 255);  // the empty cell (1, 1) is background
  for (size_t i = 3; i < sheet.rgba.size(); i += 4) ASSERT_EQ(sheet.rgba[i], 255);
}

TEST(ComposeGrid, FewerTilesThanColumnsMakeOneRow) {
  const Image sheet = compose_grid({solid(3, 3, 0), solid(3, 3, 0)}, 5, GridOptions{1, {0, 0, 0}});
  EXPECT_EQ(sheet.width, 2 * 3 + 3);
  EXPECT_EQ(sheet.height, 3 + 2);
}

TEST(ComposeGrid, RefusesBadInput) {
  EXPECT_THROW(compose_grid({}, 1), InternalError);
  EXPECT_THROW(compose_grid({solid(2, 2, 0)}, 0), InternalError);
  Image broken = solid(2, 2, 0);
  broken.rgba.pop_back();
  EXPECT_THROW(compose_grid({broken}, 1), InternalError);
  EXPECT_THROW(compose_grid({solid(2, 2, 0)}, 1, GridOptions{-1, {1, 1, 1}}), InternalError);
  EXPECT_THROW(compose_grid({solid(9000, 10, 0), solid(9000, 10, 0)}, 2), InternalError);
}

// A missing section keeps its place as a tile of the background; the present ones are drawn
// as render_section_tiles draws them, in ceil(sqrt(n)) columns or the columns asked for.
TEST(SectionSheet, AMissingSectionLeavesABlankTileInItsPlace) {
  const Template kiwi = load_template(test::source_path("templates/kiwi.yaml").string());
  const DiffusionFactory cpu = [](const DsModel& model) {
    return make_cpu_diffusion(model, {4, 0});
  };
  Outcome<CrossSection> a = variant_section(make_variant(kiwi, 1), cpu);
  ASSERT_TRUE(a) << a.reason();
  SectionTileOptions o;
  o.tile_px = 32;
  std::vector<Outcome<CrossSection>> sections;
  sections.push_back(*a);
  sections.push_back(Outcome<CrossSection>::none("the plane misses"));
  sections.push_back(*a);
  const Image sheet = section_sheet(sections, o);
  const std::vector<Image> drawn = render_section_tiles({*a, *a}, o);
  Image blank = drawn[0];
  std::fill(blank.rgba.begin(), blank.rgba.end(), uint8_t{255});
  const Image expected = compose_grid({drawn[0], blank, drawn[1]}, 2);
  EXPECT_EQ(sheet.width, expected.width);
  EXPECT_EQ(sheet.height, expected.height);
  EXPECT_TRUE(sheet.rgba == expected.rgba);
  // Asked for a strip (the editor's variants): one row.
  const Image strip = section_sheet(sections, o, 3);
  EXPECT_TRUE(strip.rgba == compose_grid({drawn[0], blank, drawn[1]}, 3).rgba);
  EXPECT_GT(strip.width, 2 * strip.height);
  std::vector<Outcome<CrossSection>> none;
  none.push_back(Outcome<CrossSection>::none("the plane misses"));
  EXPECT_THROW(section_sheet(none, o), InternalError);
}

}  // namespace
}  // namespace cutaway
