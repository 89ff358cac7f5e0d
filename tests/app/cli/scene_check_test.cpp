// `cutaway check` on scene files (doc/scene-format.md): a bad scene exits with code 2 and one
// line "FILE:LINE:COL: field.path: rule" on stderr that points at the offending node. Fixtures
// are in tests/data/scenes/bad/ (each a copy of valid_bowl.yaml with one defect); every scene
// shipped in scenes/ passes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

const std::string kDir = "tests/data/scenes/bad/";

struct BadSceneCase {
  std::string name;   ///< the fixture kDir/NAME.yaml
  int line = 0;       ///< expected 1-based line of the offending node
  int column = 0;     ///< expected 1-based column
  std::string field;  ///< expected field path
  std::string rule;   ///< a fragment the rule must contain
  std::string file;   ///< the file the message names, when not the fixture (a bad template)
};

std::ostream& operator<<(std::ostream& os, const BadSceneCase& c) { return os << c.name; }

/// A fixture kDir/NAME.yaml whose message names `file` (default: the fixture itself).
BadSceneCase bad(std::string name, int line, int column, std::string field, std::string rule,
                 std::string file = "") {
  return BadSceneCase{std::move(name), line,           column, std::move(field),
                      std::move(rule), std::move(file)};
}

std::vector<BadSceneCase> bad_scenes() {
  return {
      // The file and its top-level fields.
      bad("unknown_field", 6, 1, "colour", "unknown field \"colour\""),
      bad("duplicate_field", 5, 1, "seed", "field \"seed\" is given twice"),
      bad("wrong_format", 2, 9, "format", "unsupported format \"cutaway-scene/2\""),
      bad("bad_name", 3, 7, "name", "a name uses only a-z, 0-9, '_' and '-', not \"Summer Salad\""),
      bad("negative_seed", 4, 7, "seed", "must not be negative"),
      bad("bad_units", 5, 8, "units", "must be mm, cm or m, not \"in\""),
      // Container.
      bad("container_type", 6, 19, "container.type",
          "must be bowl, plate, board or none, not \"pot\""),
      bad("negative_diameter", 6, 35, "container.diameter", "must be positive"),
      bad("container_field_of_other_type", 6, 32, "container.width",
          "a \"bowl\" container has no width"),
      bad("container_colour", 6, 59, "container.color", "not \"#f3efgg\""),
      // Items and their templates.
      bad("no_items", 7, 8, "items", "a scene needs at least one item"),
      bad("item_without_template", 11, 5, "items[1]", "missing required field 'template'"),
      bad("missing_template", 8, 15, "items[0].template", "no template named \"yuzu\" (looked for"),
      bad("missing_template_file", 11, 15, "items[1].template",
          "the template file \"tests/data/scenes/kiwi.yaml\" does not exist"),
      bad("bad_template_name", 8, 15, "items[0].template", "not \"Tomato\""),
      bad("broken_template", 5, 32, "symmetry.folds", "folds >= 2",
          "tests/bad_input/folds_one.yaml"),
      bad("template_model_invalid", 15, 5, "surfaces[1]", "crosses the skin",
          "tests/bad_input/nested_crosses_skin.yaml"),
      bad("count_zero", 9, 12, "items[0].count", "must be a whole number from 1 to 64, not 0"),
      bad("count_fractional", 9, 12, "items[0].count", "must be a whole number, not \"2.5\""),
      bad("variation_too_large", 13, 16, "items[1].variation", "must be between 0 and 10, not 12"),
      bad("keep_zero", 13, 11, "items[1].keep", "must be more than 0 and at most 1"),
      bad("heap_too_large", 9, 12, "items[0].count",
          "make a heap of about 11.4 litres (the objects' volume over 0.74 packing) and the bowl "
          "holds about 3.46 litres heaped"),
      // Cuts.
      bad("cut_type", 10, 17, "items[0].cut.type",
          "must be whole, halves, slices, wedges or dice, not \"quarters\""),
      bad("wedges_count_one", 10, 32, "items[0].cut.count",
          "must be a whole number from 2 to 64, not 1"),
      bad("cut_field_of_other_type", 10, 36, "items[0].cut.thickness",
          "a \"halves\" cut has no thickness"),
      bad("slices_thickness_zero", 12, 36, "items[1].cut.thickness", "must be positive"),
      bad("slices_thinner_than_minimum", 12, 36, "items[1].cut.thickness", "at least 0.5 mm"),
      bad("slices_missing_thickness", 12, 10, "items[1].cut", "missing required field 'thickness'"),
      bad("dice_too_many_pieces", 12, 29, "items[1].cut.size",
          "too small: would make 25920 pieces of template \"cucumber\" (at most 512 per object)"),
      // Camera and render settings.
      bad("camera_eye_is_target", 14, 38, "camera.target", "must differ from its eye"),
      bad("camera_missing_eye", 14, 9, "camera", "missing required field 'eye'"),
      bad("camera_fov", 14, 55, "camera.fov", "must be between 1 and 170, not 180"),
      bad("camera_point_two_coordinates", 14, 38, "camera.target", "a point must be [x, y, z]"),
      bad("render_width_small", 15, 17, "render.width",
          "must be a whole number from 16 to 8192, not 8"),
      bad("render_perlin_negative", 15, 44, "render.perlin", "must be between 0 and 10, not -1"),
  };
}

class SceneBadInput : public ::testing::TestWithParam<BadSceneCase> {};

TEST_P(SceneBadInput, CheckRefusesWithLocation) {
  const BadSceneCase& c = GetParam();
  const std::string input = kDir + c.name + ".yaml";
  const auto r = test::run_cutaway({"check", input});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  const std::string prefix = (c.file.empty() ? input : c.file) + ":" + std::to_string(c.line) +
                             ":" + std::to_string(c.column) + ": " + c.field + ": ";
  EXPECT_EQ(r.err.rfind(prefix, 0), 0u)
      << "expected a message starting with\n  " << prefix << "\ngot\n  " << r.err;
  EXPECT_NE(r.err.find(c.rule), std::string::npos)
      << "rule '" << c.rule << "' missing in\n  " << r.err;
  EXPECT_EQ(r.err.find('\n'), r.err.size() - 1) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
}

INSTANTIATE_TEST_SUITE_P(SceneCheck, SceneBadInput, ::testing::ValuesIn(bad_scenes()),
                         [](const ::testing::TestParamInfo<BadSceneCase>& info) {
                           return info.param.name;
                         });

/// Every fixture in the folder is a case above, or one of the valid bases.
TEST(SceneCheck, EveryFixtureIsTested) {
  std::vector<std::string> named;
  for (const auto& c : bad_scenes()) named.push_back(c.name + ".yaml");
  for (const auto& f : test::files_in(test::source_path(kDir))) {
    if (f.rfind("valid_", 0) == 0) continue;
    EXPECT_NE(std::find(named.begin(), named.end(), f), named.end()) << f << " has no case";
  }
}

/// The bases the fixtures are derived from are valid: each fixture's defect is its only one.
TEST(SceneCheck, BasesAreValid) {
  const auto r = test::run_cutaway({"check", kDir + "valid_bowl.yaml", kDir + "valid_board.yaml",
                                    "tests/data/scenes/small.yaml"});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
  EXPECT_NE(r.out.find(kDir + "valid_bowl.yaml: ok (scene 'fixture', 2 items, 3 objects, "),
            std::string::npos)
      << r.out;
}

/// Every scene shipped in scenes/ passes `cutaway check`.
TEST(SceneCheck, ShippedScenesAreValid) {
  std::vector<std::string> args{"check"};
  for (const auto& f : test::files_in(test::source_path("scenes"))) {
    if (fs::path(f).extension() == ".yaml") args.push_back("scenes/" + f);
  }
  if (args.size() == 1) GTEST_SKIP() << "no scenes in scenes/ yet";
  const auto r = test::run_cutaway(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(r.err.empty()) << r.err;
}

/// Scenes and templates mix on one command line; every bad file is reported.
TEST(SceneCheck, MixedWithTemplatesReportsEveryBadFile) {
  const auto r = test::run_cutaway({"check", kDir + "keep_zero.yaml", "templates/spheres.yaml",
                                    kDir + "valid_bowl.yaml", "tests/bad_input/folds_one.yaml"});
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(kDir + "keep_zero.yaml:13:11: items[1].keep: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("tests/bad_input/folds_one.yaml:5:32: symmetry.folds: "), std::string::npos)
      << r.err;
  EXPECT_NE(r.out.find("templates/spheres.yaml: ok (template"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(kDir + "valid_bowl.yaml: ok (scene"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace cutaway
