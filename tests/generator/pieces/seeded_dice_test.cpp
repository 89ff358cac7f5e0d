// Closed pieces whatever the seed: every shipped template, as a seeded variant (grains
// included), diced into 12 mm cubes (larger for large objects: about 150 pieces at most; many
// planes, many caps, planes that graze surfaces), must
// give pieces that are closed, consistently oriented 2-manifolds with no two distinct vertices
// closer than 10 nm (near-duplicates that only close after a weld) and no triangle of zero area,
// whether or not cut_pieces had to nudge its planes.
//
// `make test` cuts one seed per template; CUTAWAY_DICE_SEEDS=N (set by `make fuzz`) cuts N.
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

#include "diffusion/diffusion.h"
#include "io/cut_notation.h"
#include "io/template_parser.h"
#include "pieces/cut_spec.h"
#include "pieces/manifold_check.h"
#include "pieces/pieces.h"
#include "test_support.h"
#include "variation/variation.h"

namespace cutaway {
namespace {

class SeededDice : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(SeededDice, PiecesAreClosedWithoutSlivers) {
  const char* env = std::getenv("CUTAWAY_DICE_SEEDS");
  const int seeds = env && *env ? std::atoi(env) : 1;
  const Template tmpl = load_template(GetParam().string());
  // 12 mm cubes, or larger ones for large objects: at most about 150 pieces.
  CutSpec dice = *parse_cut_spec("dice:12", 1e-3);
  while (estimate_piece_count(dice, template_extents(tmpl)) > 150) dice.size_m *= 1.25;
  for (int s = 0; s < seeds; ++s) {
    const uint64_t seed = 100 + static_cast<uint64_t>(s);
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Variant v = make_variant(tmpl, seed);
    const auto diffusion = make_cpu_diffusion(v.model, {4, 0});
    PieceOptions options;
    options.section.edge_m = v.tmpl.edge_m;
    const PieceSet set =
        *cut_pieces(v.model, dice, *diffusion, options);
    EXPECT_GE(set.pieces.size(), 2u);
    EXPECT_EQ(set.defective_pieces, 0u);
    for (const Piece& piece : set.pieces) {
      const ShadedMesh mesh = merge_parts(piece);
      EXPECT_TRUE(check_manifold(mesh, kMinVertexSeparation_m))
          << "piece of cell " << piece.cell;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Templates, SeededDice, ::testing::ValuesIn(test::shipped_templates()),
                         [](const auto& info) { return info.param.stem().string(); });

}  // namespace
}  // namespace cutaway
