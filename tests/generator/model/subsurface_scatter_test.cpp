// The subsurface radius a template's materials carry (model/subsurface_scatter.h): it follows
// the translucency, the skin's size and the dark grains, and the glTF material carries it.
#include <gtest/gtest.h>

#include <string>

#include "io/template_parser.h"
#include "model/subsurface_scatter.h"
#include "test_support.h"

namespace cutaway {
namespace {

/// A ball `diameter_mm` across whose cut faces have `translucency`, with `grains` (a YAML list
/// item, or "") inside its flesh.
Template ball(double diameter_mm, double translucency, const std::string& grains = "") {
  const double r = diameter_mm / 2, f = 0.7 * r;
  auto circle = [](double radius) {
    return "[[0, " + std::to_string(-radius) + "], [" + std::to_string(0.7071 * radius) + ", " +
           std::to_string(-0.7071 * radius) + "], [" + std::to_string(radius) + ", 0], [" +
           std::to_string(0.7071 * radius) + ", " + std::to_string(0.7071 * radius) + "], [0, " +
           std::to_string(radius) + "]]";
  };
  return parse_template(
      "format: cutaway-template/1\nname: ball\nunits: mm\nsymmetry: {type: cylindrical}\n"
      "surfaces:\n  - {name: skin, kind: around, role: skin, profile: " +
          circle(r) + "}\n  - {name: flesh, kind: around, profile: " + circle(f) + "}\n" +
          (grains.empty() ? "" : "grains:\n  - " + grains + "\n") +
          "materials:\n  cut: {translucency: " + std::to_string(translucency) + "}\n",
      "ball.yaml", ".");
}

TEST(SubsurfaceScatter, FollowsTheTranslucencyTheSizeAndTheDarkSeeds) {
  // No translucency: no scattering; the skin (translucency 0 by default) neither.
  EXPECT_EQ(ball(80, 0).cut_material.scatter_m, 0.0);
  EXPECT_EQ(ball(80, 0.3).skin_material.scatter_m, 0.0);
  // The translucency: 10 mm per unit, at most 4 mm.
  EXPECT_DOUBLE_EQ(ball(80, 0.25).cut_material.scatter_m, 0.0025);
  EXPECT_DOUBLE_EQ(ball(80, 0.9).cut_material.scatter_m, kMaxScatter_m);
  // The size: a tenth of a 22 mm ball.
  EXPECT_NEAR(ball(22, 0.35).cut_material.scatter_m, 0.0022, 1e-9);
  // Dark seeds 1 mm thick bound it; pale ones of the same size do not.
  const std::string seeds = "{name: seeds, inside: flesh, spacing: 3, shape: {ellipsoid: [1.0, "
                            "0.5, 0.8]}, back: \"#2c2014\", front: \"#1a120a\"}";
  EXPECT_DOUBLE_EQ(ball(80, 0.4, seeds).cut_material.scatter_m, 0.001);
  std::string pale = seeds;
  pale.replace(pale.find("#2c2014"), 7, "#e8d8a0");
  EXPECT_DOUBLE_EQ(ball(80, 0.4, pale).cut_material.scatter_m, 0.004);
}

TEST(SubsurfaceScatter, TheShippedKiwiKeepsItsSeedsDark) {
  const Template kiwi = load_template(test::source_path("templates/kiwi.yaml").string());
  // Its seeds are 1 mm thick (semi-axes 1.0, 0.5, 0.8 mm): light travels no farther.
  EXPECT_NEAR(kiwi.cut_material.scatter_m, 0.001, 1e-9);
}

}  // namespace
}  // namespace cutaway
