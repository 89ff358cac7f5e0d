// Variants of the shipped templates (generator/variation/variation.h): every variant builds (closed
// skin, nothing crosses the skin, `within` loops inside their folds: build_model runs check_model),
// variants differ from each other, and the same seed gives the same variant.
#include "variation/variation.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstdio>
#include <vector>

#include "base/colour.h"
#include "base/constants.h"
#include "io/template_parser.h"
#include "model/template_checks.h"
#include "test_support.h"

namespace cutaway {
namespace {

bool same_sections(const Template& a, const Template& b) {
  if (a.folds != b.folds || a.surfaces.size() != b.surfaces.size()) return false;
  for (size_t i = 0; i < a.surfaces.size(); ++i)
    if (a.surfaces[i].section.loops != b.surfaces[i].section.loops) return false;
  return true;
}

// 40 seeds per shipped template (CUTAWAY_VARIANT_SEEDS; `make fuzz` draws 200), one test per
// template (the template's sweep). For speed the meshes are built at twice the template's edge
// length (the curves, and so the rules they must keep, are the same at any resolution).
class ShippedVariation : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(ShippedVariation, EveryVariantBuilds) {
  const std::filesystem::path& path = GetParam();
  Template t = test::built_template(path).tmpl;
  t.edge_m *= 2;
  const char* env = std::getenv("CUTAWAY_VARIANT_SEEDS");
  const int seeds = env && *env ? std::atoi(env) : 40;
  int distinct = 0, redraws = 0, halved = 0;
  Template first;
  for (uint64_t seed = 0; seed < static_cast<uint64_t>(seeds); ++seed) {
    const Variant v = make_variant(t, seed);
    if (seed == 0) first = v.tmpl;
    redraws += v.draws - 1;
    halved += v.amount < t.variation_amount;
    EXPECT_NO_THROW(check_template_curves(v.tmpl)) << t.name << " seed " << seed;
    EXPECT_GE(v.model.surfaces.size(), t.surfaces.size());
    distinct += seed > 0 && !same_sections(v.tmpl, first);
    EXPECT_EQ(v.tmpl.grains.size(), t.grains.size());
    for (size_t i = 0; i < t.surfaces.size(); ++i)
      EXPECT_EQ(v.tmpl.surfaces[i].profile, t.surfaces[i].profile);
  }
  std::printf("%s: %d variants, %d differ from seed 0's, %d redraws, %d with a halved amount\n",
              t.name.c_str(), seeds, distinct, redraws, halved);
  // Cylindrical: drawn loops vary. N-fold: a fold-count range or unequal folds vary (the
  // shipped cucumber has three equal folds and a fixed count: all its variants agree).
  bool varies = false;
  if (t.symmetry == Symmetry::Cylindrical) {
    for (const auto& sf : t.surfaces)
      varies |= sf.kind == SurfaceKind::Around && !sf.section.circle;
  } else if (t.symmetry == Symmetry::NFold) {
    varies = t.variation_folds_max > t.variation_folds_min ||
             !fold_pca(fold_features(t, {})).axes.empty();
  }
  if (varies) {
    EXPECT_GE(distinct, seeds / 2) << t.name;
  }
}

INSTANTIATE_TEST_SUITE_P(Templates, ShippedVariation,
                         ::testing::ValuesIn(test::shipped_templates()),
                         [](const auto& info) { return test::template_test_name(info.param); });

TEST(Variation, SameSeedSameVariant) {
  for (const char* name : {"templates/onion.yaml", "templates/tomato.yaml"}) {
    const Template t = load_template(test::source_path(name).string());
    const Template a = vary(t, 17), b = vary(t, 17);
    EXPECT_TRUE(same_sections(a, b));
    bool other = false;  // the tomato's folds are equal: only its fold count (4..6) varies
    for (uint64_t seed = 18; seed < 30 && !other; ++seed) other = !same_sections(a, vary(t, seed));
    EXPECT_TRUE(other);
  }
}

// The onion skin's radius changes by a visible but small fraction.
TEST(Variation, OnionSkinVariesModestly) {
  const Template t = load_template(test::source_path("templates/onion.yaml").string());
  const PolarLoop p0 = polar_resample(t.surfaces[t.skin].section.loops[0], true, 128);
  double change = 0;
  for (uint64_t seed = 0; seed < 10; ++seed) {
    const Template v = draw_variant(t, seed, 0, 1.0);
    const PolarLoop p = polar_resample(v.surfaces[t.skin].section.loops[0], true, 128);
    for (int i = 0; i < 128; ++i) change += std::abs(p.rho[i] - p0.rho[i]) / p0.rho[i] / 1280;
  }
  std::printf("onion skin: mean relative radius change %.4f\n", change);
  EXPECT_GT(change, 0.002);
  EXPECT_LT(change, 0.05);
}

TEST(Variation, AmountZeroKeepsTheTemplate) {
  Template t = load_template(test::source_path("templates/onion.yaml").string());
  t.variation_amount = 0;
  EXPECT_TRUE(same_sections(vary(t, 5), t));
}

// Colour variation per variant (`variation.ripeness`, gradients `along: ripeness`): each seed
// draws a ripeness in the range from a stream of its own, so the skin's colour changes between
// the two stops while the shapes a seed draws stay those of the template without ripeness.
TEST(Variation, RipenessGivesEachSeedItsColourBetweenTheStopsAndKeepsTheShapes) {
  const std::string path = test::source_path("templates/onion.yaml").string();
  std::string text = test::read_file(path);
  const std::string plain = text;
  text.replace(text.find("variation: {amount: 1.0}"), 24,
               "variation: {amount: 1.0, ripeness: [0.2, 0.8]}");
  const std::string skin_front = "front: \"#b0702e\"";
  text.replace(text.find(skin_front), skin_front.size(),
               "front: {along: ripeness, stops: [[0, \"#40a040\"], [1, \"#e0d040\"]]}");
  const std::string dir = test::source_path("templates").string();
  const Template t = parse_template(text, path, dir);
  const Template t_plain = parse_template(plain, path, dir);
  EXPECT_DOUBLE_EQ(t.ripeness, 0.5);
  const glm::dvec3 green = srgb_to_linear({0x40 / 255.0, 0xa0 / 255.0, 0x40 / 255.0});
  const glm::dvec3 yellow = srgb_to_linear({0xe0 / 255.0, 0xd0 / 255.0, 0x40 / 255.0});
  double lo = 1, hi = 0;
  for (uint64_t seed = 0; seed < 40; ++seed) {
    const double r = draw_ripeness(t, seed);
    EXPECT_GE(r, 0.2);
    EXPECT_LE(r, 0.8);
    lo = std::min(lo, r);
    hi = std::max(hi, r);
    EXPECT_EQ(r, draw_ripeness(t, seed));
  }
  EXPECT_LT(lo, 0.3);
  EXPECT_GT(hi, 0.7);
  for (uint64_t seed : {3u, 11u}) {
    const Variant v = make_variant(t, seed);
    EXPECT_EQ(v.tmpl.ripeness, draw_ripeness(t, seed));
    EXPECT_TRUE(same_sections(v.tmpl, vary(t_plain, seed)));
    const glm::dvec3 expected = green + (yellow - green) * v.tmpl.ripeness;
    const auto& skin = v.model.surfaces[static_cast<size_t>(t.skin)].mesh;
    for (auto vh : skin.vertices()) {
      const auto& f = skin.data(vh).front;
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(f[c], expected[c], 1e-6);
    }
  }
  // Amount 0: every variant at the middle of the range.
  Template still = t;
  still.variation_amount = 0;
  EXPECT_EQ(draw_ripeness(still, 7), 0.5);
}

// A stop along ripeness may hold a field along the profile: the skin keeps its profile gradient
// at every ripeness and moves between the two stop fields point by point.
TEST(Variation, ARipenessStopMayBeAFieldAlongTheProfile) {
  const std::string path = test::source_path("templates/onion.yaml").string();
  std::string text = test::read_file(path);
  const std::string skin_front = "front: \"#b0702e\"";
  const std::string nested =
      "front: {along: ripeness, stops: [[0, {along: profile, stops: [[0, [0, 0, 0]], "
      "[1, [0, 1, 0]]]}], [1, {along: profile, stops: [[0, [1, 0, 0]], [1, [1, 1, 1]]]}]]}";
  text.replace(text.find(skin_front), skin_front.size(), nested);
  const std::string dir = test::source_path("templates").string();
  const ColourField f = parse_template(text, path, dir).surfaces[0].front;
  ASSERT_EQ(f.along, GradientAxis::Ripeness);
  EXPECT_NEAR(f.at(0, 0, 0).r, 0.0, 1e-12);    // bottom, unripe: black
  EXPECT_NEAR(f.at(1, 0, 0).g, 1.0, 1e-12);    // top, unripe: green
  EXPECT_NEAR(f.at(0, 0, 1).r, 1.0, 1e-12);    // bottom, ripe: red
  EXPECT_NEAR(f.at(1, 0, 0.5).r, 0.5, 1e-12);  // top, half ripe: between green and white
  EXPECT_NEAR(f.at(1, 0, 0.5).g, 1.0, 1e-12);
  // Nested along ripeness again: refused where it is written.
  std::string twice = test::read_file(path);
  twice.replace(
      twice.find(skin_front), skin_front.size(),
      "front: {along: ripeness, stops: [[0, {along: ripeness, stops: [[0, [0, 0, 0]]]}]]}");
  try {
    parse_template(twice, path, dir);
    ADD_FAILURE() << "a ripeness gradient inside a ripeness gradient was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not along ripeness again"), std::string::npos)
        << e.what();
  }
}

/// The message the onion template is refused with when its `variation` is `variation` (a
/// failure, and an empty message, where it is accepted: `what` says what was accepted).
std::string onion_refusal(const std::string& variation, const std::string& what) {
  const std::string path = test::source_path("templates/onion.yaml").string();
  std::string text = test::read_file(path);
  text.replace(text.find("variation: {amount: 1.0}"), 24, variation);
  try {
    parse_template(text, path, test::source_path("templates").string());
    ADD_FAILURE() << what << " was accepted";
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(Variation, RipenessRangeIsCheckedWhereItIsWritten) {
  const std::string e =
      onion_refusal("variation: {amount: 1.0, ripeness: [0.9, 0.1]}", "a reversed ripeness range");
  EXPECT_NE(e.find("variation.ripeness: needs min <= max"), std::string::npos) << e;
}

// Fold widths (`variation.fold_widths`): the drawn centres fill the turn once, fold 0 stays
// where the template put it, every fold's span (half way to each neighbour) lies within the
// spread of the mean, and the same seed draws the same centres.
TEST(Variation, FoldWidthsAreDrawnWithinTheSpreadAndFillTheTurn) {
  for (int folds : {2, 9, 14}) {
    for (uint64_t seed : {1ull, 2ull, 3ull}) {
      const std::vector<double> a = draw_fold_angles(0.3, folds, 0.25, seed);
      ASSERT_EQ(a.size(), static_cast<size_t>(folds));
      EXPECT_EQ(a, draw_fold_angles(0.3, folds, 0.25, seed));
      EXPECT_DOUBLE_EQ(a[0], 0.3);
      const double mean = 2 * kPi / folds;
      for (int k = 0; k < folds; ++k) {
        const double next = k + 1 < folds ? a[k + 1] : a[0] + 2 * kPi;
        const double prev = k > 0 ? a[k - 1] : a[folds - 1] - 2 * kPi;
        const double span = 0.5 * (next - a[k]) + 0.5 * (a[k] - prev);
        // Widths 1 +- 0.25 scaled to fill the turn: each within 0.75 / 1.25 .. 1.25 / 0.75.
        EXPECT_GT(span, mean * 0.75 / 1.25) << folds << " " << seed << " " << k;
        EXPECT_LT(span, mean * 1.25 / 0.75) << folds << " " << seed << " " << k;
      }
      EXPECT_LT(a.back(), a[0] + 2 * kPi);
    }
  }
  // Spread 0: even.
  const std::vector<double> even = draw_fold_angles(0.0, 8, 0.0, 5);
  for (int k = 0; k < 8; ++k) EXPECT_NEAR(even[k], k * 2 * kPi / 8, 1e-12);
}

// The lime's variants (fold_widths 0.25) have folds of unequal widths: the widest fold's span
// exceeds the narrowest's by at least a tenth in each of five seeds; its template keeps them
// even. `fold_widths` is only for nfold templates and lies in 0..0.5.
TEST(Variation, ALimesSegmentsDifferInWidth) {
  const Template lime = load_template(test::source_path("templates/lime.yaml").string());
  ASSERT_GT(lime.variation_fold_widths, 0);
  for (uint64_t seed = 1; seed <= 5; ++seed) {
    const Template v = draw_variant(lime, seed, 0, 1.0);
    const int n = v.folds;
    double lo = 1e9, hi = 0;
    for (int k = 0; k < n; ++k) {
      const double next = k + 1 < n ? v.fold_angles[k + 1] : v.fold_angles[0] + 2 * kPi;
      const double prev = k > 0 ? v.fold_angles[k - 1] : v.fold_angles[n - 1] - 2 * kPi;
      const double span = 0.5 * (next - prev);
      lo = std::min(lo, span);
      hi = std::max(hi, span);
    }
    EXPECT_GT(hi / lo, 1.1) << seed;
  }
  // A large amount takes the spread to at most 0.9: every fold keeps some width.
  Template wild = lime;
  wild.variation_amount = 4;
  wild.variation_fold_widths = 0.5;
  for (uint64_t seed = 1; seed <= 3; ++seed) {
    const Template v = draw_variant(wild, seed, 0, 1.0);
    for (int k = 0; k + 1 < v.folds; ++k) EXPECT_GT(v.fold_angles[k + 1], v.fold_angles[k]);
  }
  const std::string e = onion_refusal("variation: {amount: 1.0, fold_widths: 0.2}",
                                      "fold_widths on a cylindrical template");
  EXPECT_NE(e.find("variation.fold_widths: variation.fold_widths is only for symmetry nfold"),
            std::string::npos)
      << e;
}

}  // namespace
}  // namespace cutaway
