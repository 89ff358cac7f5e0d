// parse_template (generator/io/template_parser.h) on in-memory text: the values it produces (units
// to metres, sRGB to linear, polar sections, gradients, defaults) and the InputError it raises
// (file, line, column, field path, rule).
#include "base/constants.h"
#include "io/template_parser.h"

#include <cmath>
#include <string>
#include <tuple>

#include <gtest/gtest.h>

#include "base/colour.h"
#include "base/error.h"
#include "model/model_builder.h"

namespace cutaway {
namespace {

const char* const kTemplate = R"(format: cutaway-template/1
name: test-fruit_1
description: "a test"
units: cm
symmetry: {type: nfold, folds: 4}
surfaces:
  - name: skin
    kind: around
    role: skin
    profile: [[0, 0], [2, 1], [2.5, 2], [2, 3], [0, 4]]
    section: {polar: [[0, 2], [90, 2], [180, 2], [270, 2]]}
    front: "#ff0000"
    back: [0.5, 0.5, 0.5]
    blur: {along: profile, stops: [[0, 0.1], [1, 0.2]]}
  - name: core
    kind: within
    smooth: false
    profile: [[0.6, 1], [1.4, 2], [0.6, 3]]
    section: [[0.8, 0], [1.2, -0.2], [1.6, 0], [1.2, 0.2]]
    front: {along: section, stops: [[0, "#000000"], [0.5, "#ffffff"]]}
    visible: {back: false}
grains:
  - name: seeds
    on: core
    spacing: 0.25
    shape: {ellipsoid: [0.1, 0.05, 0.02]}
    front: "#2a1a0e"
    back: "#3b2a1a"
)";

Template parse(const std::string& text, const std::string& file = "t.yaml") {
  return parse_template(text, file, ".");
}

/// The InputError parse() raises on `text` (fails the test when it parses).
InputError error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const InputError& e) {
    return e;
  }
  ADD_FAILURE() << "expected an InputError for:\n" << text;
  return InputError(FileLoc{}, "", "");
}

TEST(TemplateParser, ValidTemplateValues) {
  const Template t = parse(kTemplate);
  EXPECT_EQ(t.name, "test-fruit_1");
  EXPECT_EQ(t.description, "a test");
  EXPECT_EQ(t.file, "t.yaml");
  EXPECT_DOUBLE_EQ(t.metres_per_unit, 0.01);
  EXPECT_EQ(t.symmetry, Symmetry::NFold);
  EXPECT_EQ(t.folds, 4);
  // Default fold angles: k * 360 / N, in radians.
  ASSERT_EQ(t.fold_angles.size(), 4u);
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(t.fold_angles[k], k * kPi / 2, 1e-12);
  EXPECT_EQ(t.variation_folds_min, 4);
  EXPECT_EQ(t.variation_folds_max, 4);
  EXPECT_DOUBLE_EQ(t.variation_amount, 1.0);

  ASSERT_EQ(t.surfaces.size(), 2u);
  EXPECT_EQ(t.skin, 0);
  const SurfaceSpec& skin = t.surfaces[0];
  EXPECT_EQ(skin.kind, SurfaceKind::Around);
  EXPECT_TRUE(skin.is_skin);
  EXPECT_TRUE(skin.smooth);
  EXPECT_EQ(skin.path, "surfaces[0]");
  // Units: cm -> m.
  ASSERT_EQ(skin.profile.size(), 5u);
  EXPECT_NEAR(skin.profile[1].x, 0.02, 1e-15);
  EXPECT_NEAR(skin.profile[1].y, 0.01, 1e-15);
  EXPECT_NEAR(skin.profile[4].y, 0.04, 1e-15);
  // Polar section: [deg, radius], angle from +X towards -Z.
  ASSERT_FALSE(skin.section.circle);
  ASSERT_EQ(skin.section.loops.size(), 1u);
  const auto& loop = skin.section.loops[0];
  ASSERT_EQ(loop.size(), 4u);
  EXPECT_NEAR(loop[0].x, 0.02, 1e-12);
  EXPECT_NEAR(loop[0].y, 0.0, 1e-12);
  EXPECT_NEAR(loop[1].x, 0.0, 1e-12);
  EXPECT_NEAR(loop[1].y, -0.02, 1e-12);
  EXPECT_NEAR(loop[2].x, -0.02, 1e-12);
  // Colours: sRGB -> linear.
  EXPECT_EQ(skin.front.along, GradientAxis::Constant);
  EXPECT_NEAR(skin.front.at(0, 0, 0.5).r, 1.0, 1e-12);
  EXPECT_NEAR(skin.front.at(0, 0, 0.5).g, 0.0, 1e-12);
  EXPECT_NEAR(skin.back.at(0, 0, 0.5).r, srgb_to_linear(0.5), 1e-12);
  EXPECT_NEAR(skin.back.at(0, 0, 0.5).r, 0.2140, 1e-4);
  // A LENGTH gradient in metres.
  EXPECT_EQ(skin.blur.along, GradientAxis::Profile);
  ASSERT_EQ(skin.blur.stops.size(), 2u);
  EXPECT_NEAR(skin.blur.stops[0].second, 0.001, 1e-15);
  EXPECT_NEAR(skin.blur.at(0.5, 0, 0.5), 0.0015, 1e-15);

  const SurfaceSpec& core = t.surfaces[1];
  EXPECT_EQ(core.kind, SurfaceKind::Within);
  EXPECT_FALSE(core.is_skin);
  EXPECT_FALSE(core.smooth);
  EXPECT_EQ(core.profile.size(), 3u);
  EXPECT_TRUE(core.visible_front);
  EXPECT_FALSE(core.visible_back);
  // A colour gradient along the section, interpolated in linear RGB.
  EXPECT_EQ(core.front.along, GradientAxis::Section);
  ASSERT_EQ(core.front.stops.size(), 2u);
  EXPECT_NEAR(core.front.at(0, 0.25, 0.5).g, 0.5, 1e-12);
  EXPECT_NEAR(core.front.at(0, 0.9, 0.5).b, 1.0, 1e-12);
  // Unset colours and blur keep their defaults.
  EXPECT_NEAR(core.back.at(0, 0, 0.5).r, 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(core.blur.at(0, 0, 0.5), 0.0);

  ASSERT_EQ(t.grains.size(), 1u);
  const GrainSpec& g = t.grains[0];
  EXPECT_EQ(g.on, "core");
  EXPECT_NEAR(g.spacing, 0.0025, 1e-15);
  EXPECT_NEAR(g.semi_axes.x, 0.001, 1e-15);
  EXPECT_FALSE(g.on_front);
  EXPECT_NEAR(g.front.r, srgb_to_linear(0x2a / 255.0), 1e-12);

  // Default edge: the skin's height / 64.
  EXPECT_NEAR(t.edge_m, 0.04 / 64, 1e-15);
}

TEST(TemplateParser, MillimetresByDefaultAndExplicitEdge) {
  const Template t = parse(R"(format: cutaway-template/1
name: m
symmetry: {type: cylindrical}
resolution: {edge: 1.5}
surfaces:
  - {name: skin, kind: around, role: skin, profile: [[0, 0], [20, 20], [0, 40]]}
)");
  EXPECT_DOUBLE_EQ(t.metres_per_unit, 1e-3);
  EXPECT_NEAR(t.edge_m, 0.0015, 1e-15);
  EXPECT_NEAR(t.surfaces[0].profile[1].x, 0.02, 1e-15);
  EXPECT_TRUE(t.surfaces[0].section.circle);  // section defaults to circle
  EXPECT_EQ(t.folds, 1);
  EXPECT_TRUE(t.fold_angles.empty());
}

TEST(TemplateParser, ExplicitFoldAnglesInRadians) {
  const Template t = parse(R"(format: cutaway-template/1
name: f
units: m
symmetry: {type: nfold, folds: 3, fold_angles: [10, 130, 250]}
variation: {amount: 0.5, folds: [3, 5]}
surfaces:
  - {name: skin, kind: around, role: skin, profile: [[0, 0], [1, 1], [0, 2]]}
)");
  ASSERT_EQ(t.fold_angles.size(), 3u);
  EXPECT_NEAR(t.fold_angles[0], 10 * kPi / 180, 1e-12);
  EXPECT_NEAR(t.fold_angles[2], 250 * kPi / 180, 1e-12);
  EXPECT_DOUBLE_EQ(t.variation_amount, 0.5);
  EXPECT_EQ(t.variation_folds_min, 3);
  EXPECT_EQ(t.variation_folds_max, 5);
  EXPECT_NEAR(t.edge_m, 2.0 / 64, 1e-12);
}

TEST(TemplateParser, JsonIsAccepted) {
  const Template t = parse(R"({
  "format": "cutaway-template/1",
  "name": "json",
  "units": "mm",
  "symmetry": {"type": "cylindrical"},
  "surfaces": [
    {"name": "skin", "kind": "around", "role": "skin",
     "profile": [[0, 0], [20, 20], [0, 40]], "section": "circle",
     "front": "#808080", "back": [1, 1, 1], "blur": 0.5}
  ]
})",
                           "t.json");
  EXPECT_EQ(t.name, "json");
  ASSERT_EQ(t.surfaces.size(), 1u);
  EXPECT_NEAR(t.surfaces[0].back.at(0, 0, 0.5).g, 1.0, 1e-12);
  EXPECT_NEAR(t.surfaces[0].blur.at(0, 0, 0.5), 0.0005, 1e-15);
  EXPECT_NEAR(t.edge_m, 0.04 / 64, 1e-15);
}

TEST(TemplateParser, MaterialsOfSkinAndCut) {
  // Absent: the plain default for both.
  const Template plain = parse(kTemplate);
  EXPECT_EQ(plain.skin_material, PbrMaterial{});
  EXPECT_EQ(plain.cut_material, PbrMaterial{});
  const Template t = parse(std::string(kTemplate) + R"(materials:
  skin: {roughness: 0.3, clearcoat: 0.6, clearcoat_roughness: 0.1, sheen: "#ffffff",
         sheen_roughness: 0.5}
  cut: {translucency: 0.4}
)");
  EXPECT_DOUBLE_EQ(t.skin_material.roughness, 0.3);
  EXPECT_DOUBLE_EQ(t.skin_material.clearcoat, 0.6);
  EXPECT_DOUBLE_EQ(t.skin_material.clearcoat_roughness, 0.1);
  EXPECT_EQ(t.skin_material.sheen, glm::dvec3(1.0));  // sRGB white is linear white
  EXPECT_DOUBLE_EQ(t.skin_material.sheen_roughness, 0.5);
  EXPECT_DOUBLE_EQ(t.skin_material.translucency, 0.0);
  // Unwritten values keep their defaults.
  EXPECT_DOUBLE_EQ(t.cut_material.translucency, 0.4);
  EXPECT_DOUBLE_EQ(t.cut_material.roughness, PbrMaterial{}.roughness);
  EXPECT_DOUBLE_EQ(t.cut_material.clearcoat, 0.0);
}

TEST(TemplateParser, ErrorsInMaterials) {
  struct Case {
    const char* yaml;
    int line, column;
    const char* field;
    const char* rule;
  };
  const int base = 29;  // the first line after kTemplate
  for (const Case& c : std::initializer_list<Case>{
           {"materials:\n  skin: {roughness: 1.5}\n", base + 1, 21, "materials.skin.roughness",
            "between 0 and 1"},
           {"materials:\n  cut: {translucency: -0.1}\n", base + 1, 23, "materials.cut.translucency",
            "between 0 and 1"},
           {"materials:\n  cut: {shine: 1}\n", base + 1, 9, "materials.cut.shine",
            "unknown field \"shine\""},
           {"materials:\n  flesh: {roughness: 0.2}\n", base + 1, 3, "materials.flesh",
            "unknown field \"flesh\""},
           {"materials:\n  skin: {clearcoat_roughness: 0.2}\n", base + 1, 31,
            "materials.skin.clearcoat_roughness", "needs a clearcoat"},
           {"materials:\n  skin: {sheen_roughness: 0.2}\n", base + 1, 27,
            "materials.skin.sheen_roughness", "needs a sheen colour"},
           {"materials:\n  skin: {sheen: 3}\n", base + 1, 17, "materials.skin.sheen", ""},
       }) {
    const InputError e = error_of(std::string(kTemplate) + c.yaml);
    EXPECT_EQ(e.field(), c.field) << c.yaml;
    EXPECT_EQ(e.loc().line, c.line) << c.yaml;
    EXPECT_EQ(e.loc().column, c.column) << c.yaml;
    EXPECT_NE(e.rule().find(c.rule), std::string::npos) << c.yaml << ": " << e.rule();
  }
}

// `halves`: along (the default) or across; anything else is refused at its value.
TEST(TemplateParser, HalvesAlongOrAcross) {
  EXPECT_FALSE(parse(kTemplate).halves_across);
  EXPECT_FALSE(parse(std::string(kTemplate) + "halves: along\n").halves_across);
  EXPECT_TRUE(parse(std::string(kTemplate) + "halves: across\n").halves_across);
  EXPECT_TRUE(build_model(parse(std::string(kTemplate) + "halves: across\n")).halves_across);
  const InputError e = error_of(std::string(kTemplate) + "halves: sideways\n");
  EXPECT_EQ(e.field(), "halves");
  EXPECT_EQ(e.loc().line, 29);
  EXPECT_EQ(e.loc().column, 9);
  EXPECT_NE(e.rule().find("'along' or 'across'"), std::string::npos) << e.rule();
}

TEST(TemplateParser, SurfaceMaterialChannelsDefaultToTheCutMaterial) {
  const std::string head = R"(format: cutaway-template/1
name: x
symmetry: {type: cylindrical}
materials: {cut: {roughness: 0.8, translucency: 0.4}}
surfaces:
)";
  const Template t = parse(
      head +
      R"(  - {name: skin, kind: around, role: skin, profile: [[0, 0], [20, 10], [0, 40]], roughness: 0.2}
  - {name: core, kind: around, profile: [[0, 10], [8, 20], [0, 30]], translucency: {back: 0.9}}
)");
  EXPECT_EQ(t.surfaces[0].material_front, glm::dvec2(0.2, 0.4));
  EXPECT_EQ(t.surfaces[0].material_back, glm::dvec2(0.2, 0.4));
  EXPECT_EQ(t.surfaces[1].material_front, glm::dvec2(0.8, 0.4));
  EXPECT_EQ(t.surfaces[1].material_back, glm::dvec2(0.8, 0.9));
  const std::string skin =
      "  - {name: skin, kind: around, role: skin, profile: [[0, 0], [20, 10], [0, 40]], ";
  for (const auto& [yaml, field, rule] :
       std::initializer_list<std::tuple<std::string, std::string, std::string>>{
           {"roughness: 1.5}\n", "surfaces[0].roughness", "between 0 and 1"},
           {"translucency: {back: -1}}\n", "surfaces[0].translucency.back", "between 0 and 1"},
           {"translucency: {inside: 1}}\n", "surfaces[0].translucency.inside",
            "unknown field \"inside\""},
           {"roughness: shiny}\n", "surfaces[0].roughness", ""}}) {
    const InputError e = error_of(head + skin + yaml);
    EXPECT_EQ(e.field(), field) << yaml;
    EXPECT_EQ(e.loc().line, 6) << yaml;
    EXPECT_NE(e.rule().find(rule), std::string::npos) << yaml << ": " << e.rule();
  }
}

TEST(TemplateParser, ErrorUnknownField) {
  const InputError e = error_of(R"(format: cutaway-template/1
name: x
symmetry: {type: cylindrical}
surfaces:
  - name: skin
    kind: around
    role: skin
    profile: [[0, 0], [20, 20], [0, 40]]
    colour: "#ffffff"
)");
  EXPECT_EQ(e.loc().file, "t.yaml");
  EXPECT_EQ(e.loc().line, 9);
  EXPECT_EQ(e.loc().column, 5);
  EXPECT_EQ(e.field(), "surfaces[0].colour");
  EXPECT_NE(e.rule().find("unknown field \"colour\""), std::string::npos) << e.rule();
  EXPECT_EQ(std::string(e.what()).rfind("t.yaml:9:5: surfaces[0].colour: unknown field", 0), 0u)
      << e.what();
}

TEST(TemplateParser, ErrorEmptyValueIsAtItsKey) {
  // yaml-cpp marks an empty value at the next token; the error names the key's position.
  const InputError e = error_of(R"(format: cutaway-template/1
name: x
symmetry: {type: cylindrical}
resolution:
  edge:
surfaces:
  - {name: skin, kind: around, role: skin, profile: [[0, 0], [20, 20], [0, 40]]}
)");
  EXPECT_EQ(e.loc().line, 5);
  EXPECT_EQ(e.loc().column, 3);
  EXPECT_EQ(e.field(), "resolution.edge");
  EXPECT_NE(e.rule().find("must be a number"), std::string::npos) << e.rule();
}

TEST(TemplateParser, ErrorEmptyListItemIsAtItsDash) {
  const InputError e = error_of(R"(format: cutaway-template/1
name: x
symmetry: {type: cylindrical}
surfaces:
  - {name: skin, kind: around, role: skin, profile: [[0, 0], [20, 20], [0, 40]]}
  -   # nothing here

grains: []
)");
  EXPECT_EQ(e.loc().line, 6);
  EXPECT_EQ(e.loc().column, 3);
  EXPECT_EQ(e.field(), "surfaces[1]");
}

TEST(TemplateParser, ErrorGeometricRuleAtTheCurve) {
  const InputError e = error_of(R"(format: cutaway-template/1
name: x
symmetry: {type: nfold, folds: 4}
surfaces:
  - name: skin
    kind: around
    role: skin
    profile: [[0, 0], [20, 5], [25, 20], [20, 35], [0, 40]]
  - name: core
    kind: within
    smooth: false
    profile: [[6, 10], [14, 20], [6, 30]]
    section: [[-8, 0], [-12, -2], [-16, 0], [-12, 2]]
)");
  EXPECT_EQ(e.loc().line, 13);
  EXPECT_EQ(e.loc().column, 14);
  EXPECT_EQ(e.field(), "surfaces[1].section");
  EXPECT_NE(e.rule().find("must lie inside fold 0"), std::string::npos) << e.rule();
}

TEST(TemplateParser, ErrorNotFiniteAndWrongType) {
  const InputError nan = error_of(
      "format: cutaway-template/1\nname: x\nsymmetry: {type: cylindrical}\n"
      "resolution: {edge: .NaN}\n"
      "surfaces: [{name: skin, kind: around, role: skin, profile: [[0, 0], [2, 2], [0, 4]]}]\n");
  EXPECT_EQ(nan.loc().line, 4);
  EXPECT_EQ(nan.loc().column, 20);
  EXPECT_EQ(nan.field(), "resolution.edge");
  EXPECT_NE(nan.rule().find("finite"), std::string::npos) << nan.rule();

  const InputError folds =
      error_of("format: cutaway-template/1\nname: x\nsymmetry: {type: nfold, folds: five}\n");
  EXPECT_EQ(folds.loc().line, 3);
  EXPECT_EQ(folds.loc().column, 32);
  EXPECT_EQ(folds.field(), "symmetry.folds");
  EXPECT_NE(folds.rule().find("must be a number"), std::string::npos) << folds.rule();
}

TEST(TemplateParser, HugeFoldAnglesDoNotHang) {
  // Angles are wrapped with std::remainder: 1e15 degrees must not loop for ever.
  const InputError e = error_of(R"(format: cutaway-template/1
name: x
symmetry: {type: nfold, folds: 2, fold_angles: [1e15, 1.0000000000001e15]}
surfaces:
  - {name: skin, kind: around, role: skin, profile: [[0, 0], [20, 5], [25, 20], [0, 40]]}
  - {name: core, kind: within, smooth: false, profile: [[6, 10], [14, 20], [6, 30]],
     section: [[8, 0], [12, -2], [16, 0], [12, 2]]}
)");
  EXPECT_EQ(e.field(), "surfaces[1].section");
}

TEST(TemplateParser, ErrorWholeFile) {
  const InputError empty = error_of("# only a comment\n");
  EXPECT_EQ(empty.loc().line, 1);
  EXPECT_EQ(empty.loc().column, 1);
  EXPECT_EQ(empty.field(), "(root)");
  const InputError list = error_of("- 1\n- 2\n");
  EXPECT_EQ(list.field(), "(root)");
  EXPECT_NE(list.rule().find("must be a mapping"), std::string::npos) << list.rule();
  const InputError syntax = error_of("format: [\n");
  EXPECT_EQ(syntax.field(), "(file)");
  EXPECT_NE(syntax.rule().find("YAML syntax error"), std::string::npos) << syntax.rule();
}

}  // namespace
}  // namespace cutaway
