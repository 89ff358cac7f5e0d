// The template editor's page in headless Chromium (tests/tools/edit_in_chromium.mjs), used as a
// person would: a new fruit sketched over a photo and saved, and every shipped template opened,
// its curves rewritten by the page with the values they have, and saved.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <iostream>
#include <string>

#include "io/template_parser.h"
#include "model/model_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

TEST(EditPage, SketchANewFruitOverAPhotoAndSaveIt) {
  const fs::path dir = test::fresh_dir("edit-page");
  // The photo: a picture of cut tomato halves (a golden image) stands in for a camera's.
  fs::copy_file(test::source_path("tests/golden/pieces-tomato-halves.png"), dir / "photo.png");
  const test::NodeToolRun run =
      test::run_node_tool("edit_in_chromium.mjs", {CUTAWAY_BINARY, "sketch", dir.string()});
  ASSERT_TRUE(run.report.is_object()) << run.output;
  const nlohmann::json& r = run.report;
  EXPECT_EQ(run.exit_code, 0) << run.output;
  ASSERT_TRUE(r.value("ok", false)) << run.output;
  EXPECT_TRUE(r["warnings"].empty()) << r["warnings"].dump();
  // After the first stroke, every step leaves a template that builds, except the profile drawn
  // crossing itself, which is refused with the rule at the curve.
  for (const auto& s : r["steps"]) {
    const bool refused = s["what"] == "opened an empty template" ||
                         s["what"] == "drew a profile that crosses itself" ||
                         s["what"] == "typed text that is not YAML" ||
                         s["what"] == "typed YAML of the wrong shape";
    EXPECT_EQ(s["verdict"].get<std::string>().substr(0, 2) == "ok", !refused) << s.dump();
  }
  EXPECT_NE(r.value("error_at_curve", "").find("intersects itself"), std::string::npos);
  EXPECT_NEAR(r.value("dragged_to", 0.0) - r.value("dragged_from", 0.0), 4.0, 0.5);
  // A cut that waited behind a slow one while text that does not build was typed: a picture
  // of the last checked text, not a refusal (which would also be a console error above).
  EXPECT_TRUE(r.value("cut_while_typing", false)) << run.output;
  // The eyedropper took the photo's red, not the default skin colour.
  const std::string picked = r.value("picked", "");
  ASSERT_EQ(picked.size(), 7u);
  EXPECT_NE(picked, "#c03020");
  EXPECT_GT(std::stoi(picked.substr(1, 2), nullptr, 16), 150);  // a red photo gives a red skin

  // The photo's scale line: 60 units drawn, said to be 70, keeping the line's middle (0, 30) in
  // place; then the photo moved 5 units to the right, and turned.
  const nlohmann::json& photo = r["photo"];
  ASSERT_TRUE(photo.is_object()) << run.output;
  const double before = photo["before"]["unitsPerPixel"], after = photo["after"]["unitsPerPixel"];
  EXPECT_NEAR(after / before, 70.0 / 60.0, 0.01);
  const double cx = photo["before"]["centre"][0], cy = photo["before"]["centre"][1];
  EXPECT_NEAR(photo["after"]["centre"][0].get<double>(), cx * 70 / 60 + 5, 0.5);
  EXPECT_NEAR(photo["after"]["centre"][1].get<double>(), 30 + (cy - 30) * 70 / 60, 0.5);
  // Turned a quarter turn by a drag round its centre, and back.
  EXPECT_NEAR(photo["turned"].get<double>(), M_PI / 2, 0.05);
  EXPECT_NEAR(photo["after"]["angle"].get<double>(), 0.0, 0.05);

  // The saved file passes `cutaway check` and builds a 5-fold model with chambers.
  const fs::path saved = dir / "new-fruit.yaml";
  const test::RunResult check = test::run_cutaway({"check", saved.string()});
  EXPECT_EQ(check.exit_code, 0) << check.out << check.err;
  const Template t = load_template(saved.string());
  EXPECT_EQ(t.symmetry, Symmetry::NFold);
  EXPECT_EQ(t.folds, 5);
  ASSERT_EQ(t.surfaces.size(), 2u);
  EXPECT_EQ(t.surfaces[1].kind, SurfaceKind::Within);
  EXPECT_FALSE(build_model(t).surfaces.empty());

  for (const char* shot : {"editor-sketched.png", "editor-error.png", "editor-saved.png"}) {
    const test::PngInfo png = test::png_info(dir / shot);
    EXPECT_GT(png.width, 1000) << shot;
    EXPECT_GT(png.not_background, 100000u) << shot;
  }
  std::cout << "screenshots: " << (dir / "editor-sketched.png").string() << ", "
            << (dir / "editor-saved.png").string() << "; cut " << r.value("cut_seconds", -1.0)
            << " s, coarse cut " << r.value("coarse_cut_seconds", -1.0) << " s\n";
}

TEST(EditPage, TheOutsideIsLitAsScenesAre) {
  // The cantaloupe's netted skin in the editor's 3D view with "outside" checked, seen from the
  // file's camera, against the same glTF rendered as doc/lighting.md tells a three.js user to
  // (a newer three.js, the file's lights, sky and exposure): the same colours. With the editor's
  // own diagram lights (no exposure, linear output) it was 120, 116, 64 against 132, 128, 99: more
  // saturated, 35 steps short in blue.
  const fs::path dir = test::fresh_dir("edit-outside-page");
  fs::copy_file(test::source_path("templates/cantaloupe.yaml"), dir / "cantaloupe.yaml");
  const test::NodeToolRun run = test::run_node_tool(
      "edit_in_chromium.mjs",
      {CUTAWAY_BINARY, "outside", (dir / "cantaloupe.yaml").string(), dir.string()});
  ASSERT_TRUE(run.report.is_object()) << run.output;
  ASSERT_TRUE(run.report.value("ok", false)) << run.output;
  EXPECT_TRUE(run.report["warnings"].empty()) << run.report["warnings"].dump();
  const test::PngInfo editor = test::png_info(dir / "editor-outside.png");
  ASSERT_GT(editor.width, 100);
  const test::ThreeLoadReport three = test::load_gltf_three(
      dir / "skin.glb", dir / "three-outside.png", editor.width, editor.height);
  ASSERT_TRUE(three.ok) << three.error;
  const test::PngInfo reference = test::png_info(dir / "three-outside.png");
  EXPECT_GT(editor.not_background, static_cast<size_t>(editor.width * editor.height / 20));
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(editor.mean_colour[c], reference.mean_colour[c], 8.0) << "channel " << c;
  std::cout << "outside: editor " << editor.mean_colour.r << " " << editor.mean_colour.g << " "
            << editor.mean_colour.b << ", three.js " << reference.mean_colour.r << " "
            << reference.mean_colour.g << " " << reference.mean_colour.b << " (sRGB, of 255)\n";
}

TEST(EditPage, EveryShippedTemplateKeepsItsBytesThroughThePage) {
  const fs::path dir = test::fresh_dir("edit-page");
  std::vector<std::string> args = {CUTAWAY_BINARY, "rewrite"};
  std::vector<fs::path> copies;
  for (const auto& e : fs::directory_iterator(test::source_path("templates"))) {
    fs::copy_file(e.path(), dir / e.path().filename());
    if (e.path().extension() == ".yaml") {
      copies.push_back(dir / e.path().filename());
      args.push_back(copies.back().string());
    }
  }
  ASSERT_GE(copies.size(), 13u);
  const test::NodeToolRun run = test::run_node_tool("edit_in_chromium.mjs", args);
  ASSERT_TRUE(run.report.is_object()) << run.output;
  EXPECT_EQ(run.exit_code, 0) << run.output;
  EXPECT_TRUE(run.report.value("ok", false)) << run.output;
  EXPECT_EQ(run.report["steps"].size(), 2u) << run.output;  // the first file, opened and rewritten
  EXPECT_TRUE(run.report["changed"].empty()) << run.output;
  // Setting every curve to the value it has changes no byte of any shipped template, so each
  // builds the same model.
  for (const fs::path& copy : copies) {
    EXPECT_EQ(test::read_file(copy),
              test::read_file(test::source_path("templates/" + copy.filename().string())))
        << copy.filename();
  }
}

}  // namespace
}  // namespace cutaway
