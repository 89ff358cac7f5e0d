// parse_scene and load_scene (generator/io/scene_parser.h): every field with its default, units to
// metres, sRGB to linear, template resolution (scene folder, $CUTAWAY_TEMPLATES, the project's
// templates/), and the InputError raised for bad input (file, line, column, field path, rule).
#include "io/scene_parser.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include <gtest/gtest.h>

#include "base/colour.h"
#include "base/error.h"
#include "pieces/cut_spec.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// A scene file name in the source tree's tests/data/scenes (templates resolve from there).
std::string scene_file(const std::string& name = "t.yaml") {
  return test::source_path("tests/data/scenes/" + name).string();
}

Scene parse_scene_text(const std::string& text) { return parse_scene(text, scene_file()); }

/// The InputError parse_scene_text() raises on `text` (fails the test when it parses).
InputError scene_error_of(const std::string& text) {
  try {
    parse_scene_text(text);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError for:\n" << text;
  return InputError(FileLoc{}, "", "");
}

/// The InputError load_scene raises on `path`.
InputError load_error_of(const std::string& path) {
  try {
    load_scene(path);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError for " << path;
  return InputError(FileLoc{}, "", "");
}

const std::string kHead = "format: cutaway-scene/1\nname: t\n";
const std::string kItem = "items: [{template: spheres}]\n";

bool same_file(const std::string& a, const std::string& b) {
  std::error_code ec;
  return fs::equivalent(a, b, ec);
}

void expect_vec(const glm::dvec3& v, double x, double y, double z) {
  EXPECT_NEAR(v.x, x, 1e-12);
  EXPECT_NEAR(v.y, y, 1e-12);
  EXPECT_NEAR(v.z, z, 1e-12);
}

TEST(SceneParser, SmallSceneValues) {
  const std::string file = scene_file("small.yaml");
  const Scene s = parse_scene(test::read_file(file), file);
  EXPECT_EQ(s.name, "small");
  EXPECT_EQ(s.file, file);
  EXPECT_EQ(s.seed, 3u);
  EXPECT_DOUBLE_EQ(s.metres_per_unit, 1e-3);

  EXPECT_EQ(s.container.type, ContainerType::Plate);
  EXPECT_DOUBLE_EQ(s.container.diameter_m, 0.280);
  EXPECT_DOUBLE_EQ(s.container.height_m, 0.018);
  const glm::dvec3 plate = srgb_to_linear(glm::dvec3(0xf0, 0xf0, 0xea) / 255.0);
  expect_vec(s.container.colour, plate.x, plate.y, plate.z);

  ASSERT_EQ(s.items.size(), 2u);
  const SceneItem& tomato = s.items[0];
  EXPECT_EQ(tomato.template_name, "tomato");
  EXPECT_TRUE(same_file(tomato.template_path, test::source_path("templates/tomato.yaml")))
      << tomato.template_path;
  EXPECT_EQ(tomato.count, 2);
  EXPECT_EQ(tomato.cut.type, CutType::Halves);
  EXPECT_DOUBLE_EQ(tomato.keep, 1.0);
  EXPECT_DOUBLE_EQ(tomato.variation, 1.0);
  EXPECT_EQ(tomato.path, "items[0]");
  EXPECT_EQ(tomato.loc.file, file);
  EXPECT_EQ(tomato.loc.line, 9);
  EXPECT_EQ(tomato.loc.column, 5);

  const SceneItem& cucumber = s.items[1];
  EXPECT_EQ(cucumber.template_name, "cucumber");
  EXPECT_TRUE(same_file(cucumber.template_path, test::source_path("templates/cucumber.yaml")));
  EXPECT_EQ(cucumber.count, 1);
  EXPECT_EQ(cucumber.cut.type, CutType::Slices);
  EXPECT_DOUBLE_EQ(cucumber.cut.thickness_m, 0.006);
  EXPECT_DOUBLE_EQ(cucumber.keep, 0.5);
  EXPECT_DOUBLE_EQ(cucumber.variation, 0.5);
  EXPECT_EQ(cucumber.path, "items[1]");

  ASSERT_TRUE(s.camera.has_value());
  expect_vec(s.camera->eye, 0, 0.300, 0.250);
  expect_vec(s.camera->target, 0, 0.020, 0);
  EXPECT_DOUBLE_EQ(s.camera->fov_deg, 35);
  EXPECT_EQ(s.render.width, 640);
  EXPECT_EQ(s.render.height, 480);
  EXPECT_DOUBLE_EQ(s.render.perlin, 0.5);
  EXPECT_DOUBLE_EQ(s.render.silhouettes, 1.5);
  EXPECT_DOUBLE_EQ(s.render.texels_per_mm, 4);
}

TEST(SceneParser, Defaults) {
  const Scene s = parse_scene_text(kHead + kItem);
  EXPECT_EQ(s.seed, 0u);
  EXPECT_DOUBLE_EQ(s.metres_per_unit, 1e-3);
  EXPECT_EQ(s.container.type, ContainerType::None);
  ASSERT_EQ(s.items.size(), 1u);
  EXPECT_EQ(s.items[0].count, 1);
  EXPECT_EQ(s.items[0].cut.type, CutType::Whole);
  EXPECT_DOUBLE_EQ(s.items[0].keep, 1.0);
  EXPECT_DOUBLE_EQ(s.items[0].variation, 1.0);
  EXPECT_FALSE(s.camera.has_value());
  EXPECT_EQ(s.render.width, 1280);
  EXPECT_EQ(s.render.height, 960);
  EXPECT_DOUBLE_EQ(s.render.perlin, 1.0);
  EXPECT_EQ(s.render.style, RenderStyle::Realistic);
  EXPECT_DOUBLE_EQ(s.render.silhouettes, 0.0);  // realistic: no ink strokes
  EXPECT_FALSE(s.render.silhouettes_given);
  EXPECT_DOUBLE_EQ(s.render.texels_per_mm, 8.6);
}

TEST(SceneParser, TheStyleSetsTheStrokesUnlessTheyAreGiven) {
  const Scene illustration = parse_scene_text(kHead + "render: {style: illustration}\n" + kItem);
  EXPECT_EQ(illustration.render.style, RenderStyle::Illustration);
  EXPECT_DOUBLE_EQ(illustration.render.silhouettes, 1.0);
  const Scene given =
      parse_scene_text(kHead + "render: {style: illustration, silhouettes: 0.5}\n" + kItem);
  EXPECT_DOUBLE_EQ(given.render.silhouettes, 0.5);
  EXPECT_TRUE(given.render.silhouettes_given);
  const Scene realistic =
      parse_scene_text(kHead + "render: {style: realistic, silhouettes: 2}\n" + kItem);
  EXPECT_EQ(realistic.render.style, RenderStyle::Realistic);
  EXPECT_DOUBLE_EQ(realistic.render.silhouettes, 2.0);
}

TEST(SceneParser, TheBackdropFollowsTheStyleUnlessItIsGiven) {
  const Scene realistic = parse_scene_text(kHead + kItem);
  EXPECT_TRUE(realistic.backdrop.sweep);
  const glm::dvec3 linen = srgb_to_linear(glm::dvec3(0xb0, 0xa8, 0x9e) / 255.0);
  expect_vec(realistic.backdrop.colour, linen.x, linen.y, linen.z);
  EXPECT_FALSE(parse_scene_text(kHead + "render: {style: illustration}\n" + kItem).backdrop.sweep);
  const Scene given = parse_scene_text(
      kHead + "render: {style: illustration}\nbackdrop: {type: sweep, color: \"#ffffff\"}\n" +
      kItem);
  EXPECT_TRUE(given.backdrop.sweep);
  expect_vec(given.backdrop.colour, 1, 1, 1);
  EXPECT_FALSE(parse_scene_text(kHead + "backdrop: {type: none}\n" + kItem).backdrop.sweep);
}

TEST(SceneParser, ContainerDefaultsPerType) {
  const auto container = [](const std::string& type) {
    return parse_scene_text(kHead + "container: {type: " + type + "}\n" + kItem).container;
  };
  const Container bowl = container("bowl");
  EXPECT_EQ(bowl.type, ContainerType::Bowl);
  EXPECT_DOUBLE_EQ(bowl.diameter_m, 0.240);
  EXPECT_DOUBLE_EQ(bowl.height_m, 0.080);
  const glm::dvec3 bowl_c = srgb_to_linear(glm::dvec3(0xf3, 0xef, 0xe6) / 255.0);
  expect_vec(bowl.colour, bowl_c.x, bowl_c.y, bowl_c.z);

  const Container plate = container("plate");
  EXPECT_EQ(plate.type, ContainerType::Plate);
  EXPECT_DOUBLE_EQ(plate.diameter_m, 0.260);
  EXPECT_DOUBLE_EQ(plate.height_m, 0.020);
  const glm::dvec3 plate_c = srgb_to_linear(glm::dvec3(0xfa, 0xfa, 0xfa) / 255.0);
  expect_vec(plate.colour, plate_c.x, plate_c.y, plate_c.z);

  const Container board = container("board");
  EXPECT_EQ(board.type, ContainerType::Board);
  EXPECT_DOUBLE_EQ(board.width_m, 0.360);
  EXPECT_DOUBLE_EQ(board.depth_m, 0.240);
  EXPECT_DOUBLE_EQ(board.height_m, 0.020);
  EXPECT_DOUBLE_EQ(board.diameter_m, 0.0);
  const glm::dvec3 board_c = srgb_to_linear(glm::dvec3(0xc4, 0x9a, 0x6c) / 255.0);
  expect_vec(board.colour, board_c.x, board_c.y, board_c.z);

  EXPECT_EQ(container("none").type, ContainerType::None);
}

TEST(SceneParser, UnitsBecomeMetres) {
  const Scene cm = parse_scene_text(kHead + R"(units: cm
container: {type: board, width: 40, depth: 30, height: 2, color: [1, 0, 0.5]}
items:
  - template: cucumber
    cut: {type: slices, thickness: 0.5}
  - template: tomato
    cut: {type: dice, size: 1.2}
camera: {eye: [0, 30, 25], target: [0, 2, 0]}
)");
  EXPECT_DOUBLE_EQ(cm.metres_per_unit, 1e-2);
  EXPECT_DOUBLE_EQ(cm.container.width_m, 0.40);
  EXPECT_DOUBLE_EQ(cm.container.depth_m, 0.30);
  EXPECT_DOUBLE_EQ(cm.container.height_m, 0.02);
  expect_vec(cm.container.colour, 1.0, 0.0, srgb_to_linear(0.5));
  EXPECT_DOUBLE_EQ(cm.items[0].cut.thickness_m, 0.005);
  EXPECT_DOUBLE_EQ(cm.items[1].cut.size_m, 0.012);
  expect_vec(cm.camera->eye, 0, 0.30, 0.25);
  EXPECT_DOUBLE_EQ(cm.camera->fov_deg, 40);

  const Scene m = parse_scene_text(kHead + R"(units: m
container: {type: bowl, diameter: 0.3, height: 0.1}
items: [{template: tomato, count: 64, cut: {type: wedges, count: 8}, keep: 0.25, variation: 0}]
seed: 123456789012
)");
  EXPECT_DOUBLE_EQ(m.container.diameter_m, 0.3);
  EXPECT_DOUBLE_EQ(m.container.height_m, 0.1);
  EXPECT_EQ(m.items[0].count, 64);
  EXPECT_EQ(m.items[0].cut.count, 8);
  EXPECT_DOUBLE_EQ(m.items[0].keep, 0.25);
  EXPECT_DOUBLE_EQ(m.items[0].variation, 0.0);
  EXPECT_EQ(m.seed, 123456789012u);
}

TEST(SceneParser, JsonIsAccepted) {
  const Scene s = parse_scene_text(R"({"format": "cutaway-scene/1", "name": "j", "units": "cm",
    "container": {"type": "plate", "diameter": 30},
    "items": [{"template": "onion", "cut": {"type": "halves"}}]})");
  EXPECT_EQ(s.name, "j");
  EXPECT_DOUBLE_EQ(s.container.diameter_m, 0.30);
  EXPECT_DOUBLE_EQ(s.container.height_m, 0.020);
  EXPECT_EQ(s.items[0].cut.type, CutType::Halves);
}

TEST(SceneParser, TemplatePathRelativeToTheScene) {
  const Scene s = parse_scene_text(kHead + "items: [{template: ../mesh_octahedra.yaml}, "
                                           "{template: ../../../templates/onion.yaml}]\n");
  EXPECT_TRUE(
      same_file(s.items[0].template_path, test::source_path("tests/data/mesh_octahedra.yaml")));
  EXPECT_EQ(s.items[0].template_name, "../mesh_octahedra.yaml");
  EXPECT_TRUE(same_file(s.items[1].template_path, test::source_path("templates/onion.yaml")));
}

TEST(SceneParser, TemplateNameLookupOrder) {
  // <scene dir>/../templates first, then $CUTAWAY_TEMPLATES, then the project's templates/.
  const fs::path root = test::fresh_dir("scene_lookup");
  fs::create_directories(root / "project/scenes");
  fs::create_directories(root / "project/templates");
  fs::create_directories(root / "env");
  fs::copy_file(test::source_path("templates/tomato.yaml"), root / "project/templates/tomato.yaml");
  fs::copy_file(test::source_path("templates/onion.yaml"), root / "env/onion.yaml");
  fs::copy_file(test::source_path("templates/onion.yaml"), root / "env/yuzu.yaml");
  const std::string text =
      kHead +
      "items: [{template: tomato}, {template: onion}, {template: yuzu}, {template: cucumber}]\n";
  const std::string file = (root / "project/scenes/s.yaml").string();

  ::setenv("CUTAWAY_TEMPLATES", (root / "env").c_str(), 1);
  const Scene s = parse_scene(text, file);
  ::unsetenv("CUTAWAY_TEMPLATES");
  EXPECT_TRUE(
      same_file(s.items[0].template_path, (root / "project/templates/tomato.yaml").string()));
  EXPECT_TRUE(same_file(s.items[1].template_path, (root / "env/onion.yaml").string()));
  EXPECT_TRUE(same_file(s.items[2].template_path, (root / "env/yuzu.yaml").string()));
  EXPECT_TRUE(same_file(s.items[3].template_path, test::source_path("templates/cucumber.yaml")));

  // Without the environment folder, 'yuzu' is found nowhere: the message names where it looked.
  try {
    parse_scene(text, file);
    ADD_FAILURE() << "'yuzu' was found";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "items[2].template");
    EXPECT_EQ(e.loc().line, 3);
    EXPECT_EQ(e.loc().column, 59);
    EXPECT_NE(e.rule().find("no template named \"yuzu\""), std::string::npos) << e.rule();
    EXPECT_NE(e.rule().find((root / "project/templates").string()), std::string::npos) << e.rule();
  }
}

TEST(SceneParser, ErrorUnknownItemField) {
  const InputError e = scene_error_of(kHead + R"(items:
  - template: tomato
    cut: {type: halves}
    colour: red
)");
  EXPECT_EQ(e.loc().file, scene_file());
  EXPECT_EQ(e.loc().line, 6);
  EXPECT_EQ(e.loc().column, 5);
  EXPECT_EQ(e.field(), "items[0].colour");
  EXPECT_NE(e.rule().find("unknown field \"colour\""), std::string::npos) << e.rule();
  EXPECT_EQ(std::string(e.what()).rfind(scene_file() + ":6:5: items[0].colour: unknown field", 0),
            0u)
      << e.what();
}

TEST(SceneParser, ArrangementsAreReadByName) {
  const Scene s = parse_scene_text(kHead + "container: {type: board}\narrange: together\n" +
                                   "items:\n  - {template: tomato}\n" +
                                   "  - {template: tomato, arrange: scatter}\n");
  EXPECT_EQ(s.items[0].arrange, Arrangement::Together);  // the scene's
  EXPECT_EQ(s.items[1].arrange, Arrangement::Scatter);   // the item's own
}

TEST(SceneParser, ErrorsOfTypeAndRange) {
  struct Case {
    std::string text, field, rule;
  };
  const Case cases[] = {
      {kHead + "items: {template: tomato}\n", "items", "must be a list"},
      {kHead + "backdrop: {type: wall}\n" + kItem, "backdrop.type", "must be sweep or none"},
      {kHead + "backdrop: {type: sweep, size: 2}\n" + kItem, "backdrop.size",
       "unknown field \"size\""},
      {kHead + "backdrop: {color: red}\n" + kItem, "backdrop.color", "a colour must be"},
      {kHead + "items: [tomato]\n", "items[0]", "must be a mapping"},
      {kHead + "items: [{template: tomato, count: many}]\n", "items[0].count",
       "must be a number, not \"many\""},
      {kHead + "items: [{template: tomato, count: 65}]\n", "items[0].count", "from 1 to 64"},
      {kHead + "items: [{template: tomato, keep: 1.5}]\n", "items[0].keep", "at most 1"},
      {kHead + "items: [{template: tomato, arrange: heap}]\n", "items[0].arrange",
       "must be pile, fan, scatter or together, not \"heap\""},
      {kHead + "items: [{template: tomato, variation: -1}]\n", "items[0].variation",
       "between 0 and 10"},
      {kHead + "items: [{template: tomato, cut: halves}]\n", "items[0].cut", "must be a mapping"},
      {kHead + "items: [{template: tomato, cut: {type: wedges, count: 65}}]\n",
       "items[0].cut.count", "from 2 to 64"},
      {kHead + "items: [{template: tomato, cut: {type: dice, size: 0.4}}]\n", "items[0].cut.size",
       "at least 0.5 mm"},
      {kHead + "items: [{template: tomato, cut: {type: whole, size: 4}}]\n", "items[0].cut.size",
       "a \"whole\" cut has no size"},
      {kHead + "items: [{template: tomato, cut: {type: slices, thickness: 3, spacing: 2}}]\n",
       "items[0].cut.spacing", "unknown field \"spacing\""},
      {kHead + "items: [{template: \"\"}]\n", "items[0].template", "must not be empty"},
      {kHead + "container: {type: none, height: 3}\n" + kItem, "container.height",
       "a \"none\" container has no height"},
      {kHead + "container: {type: board, diameter: 3}\n" + kItem, "container.diameter",
       "a \"board\" container has no diameter"},
      {kHead + "container: {type: board, depth: 0}\n" + kItem, "container.depth",
       "must be positive"},
      {kHead + "container: {diameter: 3}\n" + kItem, "container", "missing required field 'type'"},
      {kHead + "container: {type: bowl, diameter: 2e9}\n" + kItem, "container.diameter",
       "at most 1 km"},
      {kHead + "seed: 1.5\n" + kItem, "seed", "must be a whole number"},
      {kHead + "camera: {eye: [0, 1, 1], target: [0, 0, 0], fov: 0}\n" + kItem, "camera.fov",
       "between 1 and 170"},
      {kHead + "camera: {eye: [0, 1, .nan], target: [0, 0, 0]}\n" + kItem, "camera.eye[2]",
       "must be a finite number"},
      {kHead + "camera: {eye: [0, 1, 1]}\n" + kItem, "camera", "missing required field 'target'"},
      {kHead + "render: {height: 9000}\n" + kItem, "render.height", "from 16 to 8192"},
      {kHead + "render: {silhouettes: 11}\n" + kItem, "render.silhouettes", "between 0 and 10"},
      {kHead + "render: {style: photo}\n" + kItem, "render.style",
       "must be realistic or illustration, not \"photo\""},
      {kHead + "render: {texels_per_mm: 0}\n" + kItem, "render.texels_per_mm",
       "between 0.1 and 100"},
      {kHead + "render: {dpi: 300}\n" + kItem, "render.dpi", "unknown field \"dpi\""},
      {"format: cutaway-template/1\nname: t\n" + kItem, "format", "unsupported format"},
      {"name: t\n" + kItem, "(root)", "missing required field 'format'"},
      {"format: cutaway-scene/1\n" + kItem, "(root)", "missing required field 'name'"},
      {kHead, "(root)", "missing required field 'items'"},
  };
  for (const auto& c : cases) {
    const InputError e = scene_error_of(c.text);
    EXPECT_EQ(e.field(), c.field) << c.text << e.what();
    EXPECT_NE(e.rule().find(c.rule), std::string::npos) << c.text << e.what();
    EXPECT_GE(e.loc().line, 1) << c.text;
    EXPECT_GE(e.loc().column, 1) << c.text;
  }
}

// A scene whose cut faces would pass the texel budget at the default density is baked at the
// density that fits, a tenth of a texel per mm below which it would not, and says so; the same
// scene with the density written is refused there.
TEST(SceneParser, ABigSceneGetsTheTexelDensityThatFitsUnlessItIsWritten) {
  const fs::path dir = test::fresh_dir("scene_texel_fit");
  const std::string items =
      "items:\n  - {template: " + test::source_path("templates/tomato.yaml").string() +
      ", count: 14, cut: {type: slices, thickness: 4}}\n";
  std::ofstream(dir / "big.yaml") << kHead + items;
  const Scene s = load_scene((dir / "big.yaml").string());
  const double area = scene_cut_area(s);
  EXPECT_FALSE(check_cap_texels(area, 8.6));
  EXPECT_EQ(s.render.fitted_from_texels_per_mm, 8.6);
  EXPECT_LT(s.render.texels_per_mm, 8.6);
  EXPECT_TRUE(check_cap_texels(area, s.render.texels_per_mm));
  EXPECT_FALSE(check_cap_texels(area, s.render.texels_per_mm + 0.1));
  char used[64];
  std::snprintf(used, sizeof used, "baked at %g texels per mm", s.render.texels_per_mm);
  EXPECT_NE(texel_fit_note(s).find(used), std::string::npos) << texel_fit_note(s);

  std::ofstream(dir / "given.yaml") << kHead + items + "render: {texels_per_mm: 8.6}\n";
  const InputError e = load_error_of((dir / "given.yaml").string());
  EXPECT_EQ(e.field(), "render.texels_per_mm");
  EXPECT_NE(e.rule().find("would need about"), std::string::npos) << e.what();

  // A scene that fits keeps its density and has nothing to say.
  const Scene small = load_scene(scene_file("small.yaml"));
  EXPECT_EQ(small.render.fitted_from_texels_per_mm, 0);
  EXPECT_EQ(texel_fit_note(small), "");
}

TEST(SceneParser, LoadSceneChecksTheTemplates) {
  const std::string file = scene_file("small.yaml");
  const Scene s = load_scene(file);
  EXPECT_EQ(s.name, "small");
  EXPECT_EQ(s.items.size(), 2u);
  EXPECT_EQ(s.file, file);

  // parse_scene does not read the templates; load_scene does, and reports the template's error.
  const fs::path dir = test::fresh_dir("scene_broken_template");
  const std::string text =
      kHead + "items: [{template: " + test::source_path("tests/bad_input/folds_one.yaml").string() +
      "}]\n";
  std::ofstream(dir / "s.yaml") << text;
  EXPECT_NO_THROW(parse_scene(text, (dir / "s.yaml").string()));
  const InputError e = load_error_of((dir / "s.yaml").string());
  EXPECT_TRUE(same_file(e.loc().file, test::source_path("tests/bad_input/folds_one.yaml")));
  EXPECT_EQ(e.field(), "symmetry.folds");
}

TEST(SceneParser, LoadSceneRefusesTooManyPieces) {
  // A sphere of radius 400 mm (spheres.yaml in centimetres): 1 mm slices make 801 pieces.
  const fs::path dir = test::fresh_dir("scene_pieces");
  std::string big = test::read_file(test::source_path("templates/spheres.yaml"));
  big = std::regex_replace(big, std::regex("units: mm"), "units: cm");
  std::ofstream(dir / "big.yaml") << big;
  std::ofstream(dir / "s.yaml") << kHead + R"(items:
  - template: big.yaml
    cut: {type: slices, thickness: 1}
)";
  const InputError e = load_error_of((dir / "s.yaml").string());
  EXPECT_EQ(e.field(), "items[0].cut.thickness");
  EXPECT_EQ(e.loc().line, 5);
  EXPECT_EQ(e.loc().column, 36);
  EXPECT_NE(e.rule().find("too small: would make 801 pieces of template \"spheres\" (at most 512"),
            std::string::npos)
      << e.rule();

  // 2 mm slices make 401: fine (at a texel density that keeps their caps within the total, on
  // a board large enough to hold their heap).
  std::ofstream(dir / "ok.yaml")
      << kHead + R"(container: {type: board, width: 4000, depth: 4000, height: 20}
items:
  - template: big.yaml
    cut: {type: slices, thickness: 2}
render: {texels_per_mm: 0.1}
)";
  EXPECT_NO_THROW(load_scene((dir / "ok.yaml").string()));
}

TEST(SceneParser, LoadSceneRefusesMorePiecesThanTheContainerHolds) {
  // 40 tomatoes heap to about 7 litres (0.18 litre each: their volume over 0.74 packing); a
  // 26 cm plate holds a cone of about 2.3 litres, a 60 x 40 cm board a heap of about 19 litres.
  const fs::path dir = test::fresh_dir("scene_heap");
  const std::string items = R"(items:
  - template: tomato
    count: 40
    cut: {type: halves}
)";
  std::ofstream(dir / "plate.yaml") << kHead + "container: {type: plate}\n" + items;
  const InputError e = load_error_of((dir / "plate.yaml").string());
  EXPECT_EQ(e.field(), "items[0].count");
  EXPECT_NE(e.rule().find("and the plate holds about"), std::string::npos) << e.rule();
  std::ofstream(dir / "board.yaml")
      << kHead + "container: {type: board, width: 600, depth: 400, height: 20}\n" + items;
  EXPECT_NO_THROW(load_scene((dir / "board.yaml").string()));
}

TEST(SceneParser, LoadSceneMissingFile) {
  const InputError e = load_error_of("tests/data/scenes/no_such_scene.yaml");
  EXPECT_EQ(e.field(), "(file)");
  EXPECT_NE(e.rule().find("does not exist"), std::string::npos) << e.rule();
}

}  // namespace
}  // namespace cutaway
