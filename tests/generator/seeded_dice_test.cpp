// Closed pieces whatever the seed: every shipped template, as a seeded variant (grains
// included), diced into 12 mm cubes (larger for large objects: about 150 pieces at most; many planes, many caps, planes that graze surfaces), must
// give pieces that are closed, consistently oriented 2-manifolds with no two distinct vertices
// closer than 10 nm (near-duplicates that only close after a weld) and no triangle of zero area.
//
// `make test` cuts one seed per template; CUTAWAY_DICE_SEEDS=N (set by `make fuzz`) cuts N.
#include <cmath>
#include <cstdlib>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "cut_spec.h"
#include "diffusion/diffusion.h"
#include "pieces.h"
#include "template_parser.h"
#include "test_support.h"
#include "variation.h"

namespace cutaway {
namespace {

constexpr double kNearDuplicate_m = 1e-8;

/// No two distinct positions closer than kNearDuplicate_m, no zero-area triangle.
::testing::AssertionResult no_slivers(const ShadedMesh& mesh) {
  std::map<std::tuple<long long, long long, long long>, std::vector<glm::dvec3>> grid;
  auto cell = [](const glm::dvec3& p) {
    return std::make_tuple(static_cast<long long>(std::floor(p.x / kNearDuplicate_m)),
                           static_cast<long long>(std::floor(p.y / kNearDuplicate_m)),
                           static_cast<long long>(std::floor(p.z / kNearDuplicate_m)));
  };
  for (const glm::dvec3& p : mesh.position) {
    auto& here = grid[cell(p)];
    bool seen = false;
    for (const glm::dvec3& q : here) seen = seen || q == p;
    if (!seen) here.push_back(p);
  }
  for (const auto& [c, points] : grid) {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto it = grid.find({std::get<0>(c) + dx, std::get<1>(c) + dy,
                                     std::get<2>(c) + dz});
          if (it == grid.end()) continue;
          for (const glm::dvec3& p : points)
            for (const glm::dvec3& q : it->second)
              if (p != q && glm::distance(p, q) < kNearDuplicate_m)
                return ::testing::AssertionFailure()
                       << "two vertices " << glm::distance(p, q) << " m apart";
        }
  }
  for (const glm::uvec3& t : mesh.triangle) {
    const glm::dvec3 a = mesh.position[t.x], b = mesh.position[t.y], c = mesh.position[t.z];
    if (!(glm::length(glm::cross(b - a, c - a)) > 0))
      return ::testing::AssertionFailure() << "a triangle of zero area";
  }
  return ::testing::AssertionSuccess();
}

class SeededDice : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(SeededDice, PiecesAreClosedWithoutSlivers) {
  const char* env = std::getenv("CUTAWAY_DICE_SEEDS");
  const int seeds = env && *env ? std::atoi(env) : 1;
  const Template tmpl = load_template(GetParam().string());
  // 12 mm cubes, or larger ones for large objects: at most about 150 pieces.
  CutSpec dice = parse_cut_spec("dice:12", 1e-3);
  while (estimate_piece_count(dice, template_extents(tmpl)) > 150) dice.size_m *= 1.25;
  for (int s = 0; s < seeds; ++s) {
    const uint64_t seed = 100 + static_cast<uint64_t>(s);
    SCOPED_TRACE("seed " + std::to_string(seed));
    const Variant v = make_variant(tmpl, seed);
    const auto diffusion = make_cpu_diffusion(v.model, {4, 0});
    PieceOptions options;
    options.section.edge_m = v.tmpl.edge_m;
    const PieceSet set =
        cut_pieces(v.model, dice, *diffusion, options);
    EXPECT_GE(set.pieces.size(), 2u);
    for (const Piece& piece : set.pieces) {
      const ShadedMesh mesh = merge_parts(piece);
      EXPECT_TRUE(test::closed_and_oriented(mesh)) << "piece of cell " << piece.cell;
      EXPECT_TRUE(no_slivers(mesh)) << "piece of cell " << piece.cell;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Templates, SeededDice, ::testing::ValuesIn(test::shipped_templates()),
                         [](const auto& info) { return info.param.stem().string(); });

}  // namespace
}  // namespace cutaway
