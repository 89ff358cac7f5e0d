// Skin patterns (generator/material/skin_pattern.h, doc/template-format.md Skin patterns):
// stripes come `count` times around the section, cover `width` of each period and wrap across
// the section's seam; speckles cover spots of about their size, the same for the same seed and
// elsewhere for another; a net draws thin lines between cells; layers are laid in order; the
// rules are checked where they are written.
#include "material/skin_pattern.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "base/colour.h"
#include "base/constants.h"
#include "io/template_parser.h"
#include "model/ds_model.h"
#include "test_support.h"

namespace cutaway {
namespace {

SkinPatternLayer stripes(int count, double width, double wobble) {
  SkinPatternLayer s;
  s.kind = SkinPatternLayer::Kind::Stripes;
  s.count = count;
  s.width = width;
  s.wobble = wobble;
  s.softness = 0.1;
  s.colour = {0, 0.2, 0};
  return s;
}

SkinPatternLayer speckles(double spacing, double size) {
  SkinPatternLayer s;
  s.kind = SkinPatternLayer::Kind::Speckles;
  s.spacing_m = spacing;
  s.size_m = size;
  s.softness = 0.1;
  s.colour = {1, 1, 1};
  return s;
}

TEST(SkinPattern, StripesComeCountTimesAroundCoverTheirWidthAndWrapAcrossTheSeam) {
  const SkinPatterns p({stripes(12, 0.4, 0.0)}, 7);
  for (double tp : {0.2, 0.5, 0.8}) {
    int rises = 0;
    double covered = 0;
    const int n = 4800;
    double before = p.coverage(0, {tp, 1.0 - 1.0 / n}, {});
    for (int i = 0; i < n; ++i) {
      const double c = p.coverage(0, {tp, (i + 0.5) / n}, {});
      rises += before < 0.5 && c >= 0.5;
      covered += c / n;
      before = c;
    }
    EXPECT_EQ(rises, 12) << tp;
    EXPECT_NEAR(covered, 0.4, 0.01) << tp;
  }
  // With wobble the stripes still wrap: t_section 0 and 1 are the same point.
  const SkinPatterns w({stripes(9, 0.5, 0.6)}, 3);
  for (double tp : {0.1, 0.37, 0.9})
    EXPECT_NEAR(w.coverage(0, {tp, 0.0}, {}), w.coverage(0, {tp, 1.0}, {}), 1e-9);
  // Another seed turns them.
  const SkinPatterns turned({stripes(12, 0.4, 0.0)}, 8);
  double differ = 0;
  for (int i = 0; i < 100; ++i)
    differ +=
        std::fabs(p.coverage(0, {0.5, i / 100.0}, {}) - turned.coverage(0, {0.5, i / 100.0}, {}));
  EXPECT_GT(differ, 1.0);
}

TEST(SkinPattern, SpecklesCoverSpotsOfTheirSizeAndMoveWithTheSeed) {
  // Points on a sphere of 40 mm radius; speckles of 1.5 mm radius on a 4 mm lattice.
  const SkinPatterns a({speckles(4e-3, 1.5e-3)}, 1), same({speckles(4e-3, 1.5e-3)}, 1);
  const SkinPatterns b({speckles(4e-3, 1.5e-3)}, 2);
  int covered = 0, moved = 0;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    // a Fibonacci sphere
    const double z = 1 - (i + 0.5) * 2.0 / n, r = std::sqrt(1 - z * z);
    const double phi = i * kPi * (3 - std::sqrt(5.0));
    const glm::dvec3 p = 0.04 * glm::dvec3(r * std::cos(phi), z, r * std::sin(phi));
    const double ca = a.coverage(0, {}, p);
    EXPECT_GE(ca, 0.0);
    EXPECT_LE(ca, 1.0);
    EXPECT_EQ(ca, same.coverage(0, {}, p));
    covered += ca > 0.5;
    moved += (ca > 0.5) != (b.coverage(0, {}, p) > 0.5);
  }
  // A surface crosses the spheres as a plane would: it is covered where space is, 4/3 pi
  // 1.5^3 / 4^3 = 22 % (less where spheres overlap and inside the soft edge).
  EXPECT_GT(covered, n / 10);
  EXPECT_LT(covered, n * 35 / 100);
  EXPECT_GT(moved, covered / 2);
}

// A net: lines on the walls between lattice cells. Along a straight line through many cells
// the coverage rises once per wall crossed, and a point at a lattice point (the middle of its
// cell) is never on a line.
TEST(SkinPattern, ANetDrawsThinLinesOnTheWallsBetweenCells) {
  SkinPatternLayer net = speckles(8e-3, 1e-3);
  net.kind = SkinPatternLayer::Kind::Net;
  const SkinPatterns p({net}, 4);
  int rises = 0;
  double covered = 0;
  const int n = 20000;
  double before = 0;
  for (int i = 0; i < n; ++i) {
    const double c = p.coverage(0, {}, {0.4 * i / n, 0.0123, 0.0311});  // 400 mm, 50 cells
    rises += before < 0.5 && c >= 0.5;
    covered += c / n;
    before = c;
  }
  // About one wall per cell crossed (a line meets between 1 and 2 walls per cell length).
  EXPECT_GT(rises, 30);
  EXPECT_LT(rises, 110);
  // Lines 1 mm wide (in F2 - F1, about half that to each side of a wall) over 8 mm cells,
  // crossed at all angles (an oblique crossing is longer): measured 36 %.
  EXPECT_GT(covered, 0.1);
  EXPECT_LT(covered, 0.45);
}

TEST(SkinPattern, LayersAreLaidInOrderWithTheirOpacity) {
  SkinPatternLayer all = stripes(1, 0.999, 0.0);
  all.softness = 0;
  all.colour = {1, 0, 0};
  all.opacity = 0.5;
  const SkinPatterns p({all}, 0);
  const glm::dvec3 c = p({0.5, 0.5}, {}, {0, 0, 1});
  EXPECT_NEAR(c.r, 0.5, 1e-12);
  EXPECT_NEAR(c.b, 0.5, 1e-12);
}

TEST(SkinPattern, TheReliefIsTheSumOfEachLayersReliefTimesItsCoverage) {
  SkinPatternLayer ridge = stripes(1, 0.999, 0.0);
  ridge.softness = 0;
  ridge.relief_m = 4e-4;
  SkinPatternLayer pores = speckles(0.01, 0.002);
  pores.relief_m = -2e-4;
  const SkinPatterns flat({stripes(4, 0.5, 0.0)}, 1);
  EXPECT_FALSE(flat.has_relief());
  EXPECT_EQ(flat.shade({0.5, 0.3}, {0.01, 0.02, 0.03}, {}).height, 0.0);
  const SkinPatterns p({ridge, pores}, 2);
  EXPECT_TRUE(p.has_relief());
  for (const glm::dvec3 at : {glm::dvec3(0.011, 0.02, 0.003), glm::dvec3(-0.03, 0.05, 0.01),
                              glm::dvec3(0.0, 0.001, -0.02)}) {
    const glm::dvec2 param(0.5, 0.5);
    EXPECT_NEAR(p.shade(param, at, {}).height,
                4e-4 * p.coverage(0, param, at) - 2e-4 * p.coverage(1, param, at), 1e-15);
  }
}

TEST(SkinPattern, GrainSpotsCoverTheSkinOverTheirGrainsOnly) {
  SkinPatternLayer spots;
  spots.kind = SkinPatternLayer::Kind::Grains;
  spots.grain_set = "achenes";
  spots.size_m = 0.001;
  spots.softness = 0.5;
  spots.relief_m = -3e-4;
  DsModel model;
  DsSurface grains;
  grains.name = "achenes";
  grains.role = SurfaceRole::Grain;
  grains.grain_sites = {{0.01, 0.02, 0.0}, {0.01, 0.0235, 0.0}, {-0.02, 0.0, 0.005}};
  model.surfaces.push_back(grains);
  const SkinPatterns p({spots}, 4, &model);
  for (const glm::dvec3& site : model.surfaces[0].grain_sites) {
    EXPECT_DOUBLE_EQ(p.coverage(0, {}, site), 1.0);
    EXPECT_DOUBLE_EQ(p.coverage(0, {}, site + glm::dvec3(0.0003, 0.0, 0.0)), 1.0);  // inner half
    EXPECT_DOUBLE_EQ(p.coverage(0, {}, site + glm::dvec3(0.0, 0.0, 0.0011)), 0.0);  // outside
    EXPECT_DOUBLE_EQ(p.shade({}, site, {}).height, -3e-4);
  }
  const glm::dvec3 edge(0.01, 0.02, 0.00075);  // halfway through the blended edge
  EXPECT_NEAR(p.coverage(0, {}, edge), 0.5, 1e-9);
  EXPECT_DOUBLE_EQ(p.coverage(0, {}, {0.0, 0.0, 0.0}), 0.0);
  // Without the model (or without that set) the layer covers nothing.
  const SkinPatterns alone({spots}, 4);
  EXPECT_DOUBLE_EQ(alone.coverage(0, {}, model.surfaces[0].grain_sites[0]), 0.0);
}

std::string refusal(const std::string& find, const std::string& replace) {
  const std::string path = test::source_path("templates/onion.yaml").string();
  std::string text = test::read_file(path);
  text.replace(text.find(find), find.size(), replace);
  try {
    parse_template(text, path, test::source_path("templates").string());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SkinPattern, RulesAreCheckedWhereTheyAreWritten) {
  const std::string skin_blur = "    blur: 0.3\n  - name: ring-1";
  EXPECT_NE(refusal(skin_blur, "    blur: 0.3\n    patterns: [{speckles: {spacing: 1, size: 0.8, "
                               "jitter: 0.5, colour: \"#ffffff\"}}]\n  - name: ring-1")
                .find("patterns[0].speckles.spacing: must be at least size x (1 + jitter)"),
            std::string::npos);
  EXPECT_NE(refusal(skin_blur, "    blur: 0.3\n    patterns: [{stripes: {count: 300, "
                               "colour: \"#ffffff\"}}]\n  - name: ring-1")
                .find("stripes.count: must be a whole number 1 to 256"),
            std::string::npos);
  EXPECT_NE(refusal("    blur: 0.25\n  - name: ring-2",
                    "    blur: 0.25\n    patterns: [{stripes: {count: 3, colour: \"#ffffff\"}}]\n"
                    "  - name: ring-2")
                .find("only the skin (role: skin) has patterns"),
            std::string::npos);
  EXPECT_EQ(refusal(skin_blur, "    blur: 0.3\n    patterns: [{stripes: {count: 16, width: 0.3, "
                               "wobble: 0.2, colour: \"#204010\"}}]\n  - name: ring-1"),
            "");
  // Relief: signed, at most 2 mm either way; a layer of opacity 0 needs no colour but a relief.
  EXPECT_NE(refusal(skin_blur, "    blur: 0.3\n    patterns: [{net: {spacing: 6, width: 1, "
                               "colour: \"#ffffff\", relief: 2.5}}]\n  - name: ring-1")
                .find("patterns[0].net.relief: must be between -2 and 2, not 2.5"),
            std::string::npos);
  EXPECT_NE(refusal(skin_blur, "    blur: 0.3\n    patterns: [{speckles: {spacing: 2, size: 0.5, "
                               "opacity: 0}}]\n  - name: ring-1")
                .find("a layer of opacity 0 without a relief changes nothing"),
            std::string::npos);
  EXPECT_NE(refusal(skin_blur, "    blur: 0.3\n    patterns: [{speckles: {spacing: 2, size: 0.5, "
                               "relief: -0.2}}]\n  - name: ring-1")
                .find("patterns[0].speckles: "),
            std::string::npos);  // opacity 1 (the default) still needs its colour
  EXPECT_EQ(refusal(skin_blur, "    blur: 0.3\n    patterns: [{speckles: {spacing: 2, size: 0.5, "
                               "opacity: 0, relief: -0.2}}]\n  - name: ring-1"),
            "");
}

TEST(SkinPattern, AGrainsLayerNamesAGrainSetOnTheSkin) {
  const std::string path = test::source_path("templates/strawberry.yaml").string();
  const std::string text = test::read_file(path);
  auto refused = [&](const std::string& find, const std::string& replace) -> std::string {
    std::string t = text;
    const size_t at = t.find(find);
    EXPECT_NE(at, std::string::npos) << find;
    if (at == std::string::npos) return "";
    t.replace(at, find.size(), replace);
    try {
      parse_template(t, path, test::source_path("templates").string());
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(refused("set: achenes", "set: achenes"), "");
  EXPECT_NE(refused("set: achenes", "set: pips")
                .find("patterns[0].grains.set: no grain set is named \"pips\""),
            std::string::npos);
  EXPECT_NE(refused("    on: skin", "    on: rim")
                .find("grain set \"achenes\" lies on \"rim\", not on the skin \"skin\""),
            std::string::npos);
}

}  // namespace
}  // namespace cutaway
