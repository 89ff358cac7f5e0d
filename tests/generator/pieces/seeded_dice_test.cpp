// Closed pieces whatever the seed: every shipped template, as a seeded variant (grains
// included), diced into 12 mm cubes (larger for large objects: about 150 pieces at most; many
// planes, many caps, planes that graze surfaces), must
// give pieces that are closed, consistently oriented 2-manifolds with no two distinct vertices
// closer than 10 nm (near-duplicates that only close after a weld) and no triangle of zero area,
// whether or not cut_pieces had to nudge its planes. A template with grains is also cut in
// halves and in 4 wedges, planes through the axis, which are never nudged: a grain that
// reaches into a hollow or out of the skin lies on them as on any other plane.
//
// `make test` cuts one seed per template; CUTAWAY_DICE_SEEDS=N (set by `make fuzz`) cuts N.
// Besides: the papaya, whose seeds hang into its hollow, cut in halves and in wedges for the
// seeds that once gave open pieces, and a strawberry with achenes as dense as `cutaway check`
// accepts (they overlap), cut in halves and in wedges.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "base/error.h"
#include "diffusion/diffusion.h"
#include "io/cut_notation.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "pieces/cut_spec.h"
#include "pieces/manifold_check.h"
#include "pieces/pieces.h"
#include "test_support.h"
#include "variation/grains.h"
#include "variation/variation.h"

namespace cutaway {
namespace {

/// Cuts `variant` with the cut written `notation` (doc/command-line.md, lengths in
/// millimetres): at least two pieces, none defective, each a closed 2-manifold without
/// slivers.
void expect_closed_pieces(const Variant& variant, const DiffusionBackend& diffusion,
                          const std::string& notation) {
  SCOPED_TRACE(notation);
  CutSpec cut = *parse_cut_spec(notation, 1e-3);
  // Dice of 12 mm cubes, or larger ones for large objects: at most about 150 pieces.
  if (cut.type == CutType::Dice)
    while (estimate_piece_count(cut, template_extents(variant.tmpl)) > 150) cut.size_m *= 1.25;
  PieceOptions options;
  options.section.edge_m = variant.tmpl.edge_m;
  const PieceSet set = *cut_pieces(variant.model, cut, diffusion, options);
  EXPECT_GE(set.pieces.size(), 2u);
  EXPECT_EQ(set.defective_pieces, 0u);
  for (const Piece& piece : set.pieces)
    EXPECT_TRUE(check_manifold(merge_parts(piece), kMinVertexSeparation_m))
        << "piece of cell " << piece.cell;
}

class SeededDice : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(SeededDice, PiecesAreClosedWithoutSlivers) {
  const char* env = std::getenv("CUTAWAY_DICE_SEEDS");
  const int seeds = env && *env ? std::atoi(env) : 1;
  const Template& tmpl = test::built_template(GetParam()).tmpl;
  for (int s = 0; s < seeds; ++s) {
    const uint64_t seed = 100 + static_cast<uint64_t>(s);
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Variant v = make_variant(tmpl, seed);
    const auto diffusion = make_cpu_diffusion(v.model, {4, 0});
    expect_closed_pieces(v, *diffusion, "dice:12");
    if (tmpl.grains.empty()) continue;
    for (const char* through_axis : {"halves", "wedges:4"})
      expect_closed_pieces(v, *diffusion, through_axis);
  }
}

INSTANTIATE_TEST_SUITE_P(Templates, SeededDice, ::testing::ValuesIn(test::shipped_templates()),
                         [](const auto& info) { return test::template_test_name(info.param); });

// The papaya's seeds reach into its hollow: where a plane cut one wholly inside the hollow, the
// cap had an island and both halves were open, for every seed 1 to 20.
TEST(SeededCuts, PapayaHalvesAndWedgesAreClosed) {
  const Template tmpl = load_template(test::source_path("templates/papaya.yaml").string());
  for (const uint64_t seed : {10, 39, 42}) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Variant v = make_variant(tmpl, seed);
    const auto diffusion = make_cpu_diffusion(v.model, {4, 0});
    for (const char* cut : {"halves", "wedges:4"}) expect_closed_pieces(v, *diffusion, cut);
  }
}

// Achenes as dense as the grain limits allow: 0.9 mm apart, their largest semi-axis (the
// 0.9 x 0.6 x 0.5 mm grains overlap each other and reach out of the skin), cut closed in halves
// and in 4 wedges; 0.7 mm apart (under the grain total), refused.
TEST(SeededCuts, OverlappingGrainsThatCheckAcceptsCutClosed) {
  Template tmpl = load_template(test::source_path("templates/strawberry.yaml").string());
  ASSERT_GE(tmpl.grains.size(), 1u);
  ASSERT_EQ(tmpl.grains[0].name, "achenes");
  tmpl.grains.resize(1);  // the achenes alone (not the strands through the rim)
  tmpl.grains[0].spacing = 0.7e-3;
  EXPECT_THROW(check_grain_limits(tmpl, build_model(tmpl)), InputError);
  tmpl.grains[0].spacing = tmpl.grains[0].semi_axes.x;  // 0.9 mm, the largest
  EXPECT_NO_THROW(check_grain_limits(tmpl, build_model(tmpl)));
  const Variant v = make_variant(tmpl, 2);
  const auto diffusion = make_cpu_diffusion(v.model, {4, 0});
  for (const char* cut : {"halves", "wedges:4"}) expect_closed_pieces(v, *diffusion, cut);
}

}  // namespace
}  // namespace cutaway
