// Silhouette-adaptive directions (diffusion/adaptive_directions.h): the two levels tile the
// sphere, the neighbour pairs reach across cube edges, refinement follows the changes of what
// is seen, and PMVC with them is as accurate as casting every texel, with far fewer rays.
#include <algorithm>
#include <cstdio>
#include <set>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "base/colour.h"
#include "base/error.h"
#include "diffusion/adaptive_directions.h"
#include "diffusion/diffusion.h"
#include "section/cross_section.h"
#include "test_support.h"

namespace cutaway {
namespace {

TEST(AdaptiveDirections, FineTexelsTileEachCoarseTexelOnce) {
  for (int n : {2, 4, 16}) {
    const AdaptiveDirections d = make_adaptive_directions(n);
    ASSERT_EQ(d.coarse.n, n / 2);
    std::set<unsigned> covered;
    for (unsigned k = 0; k < d.coarse.direction.size(); ++k) {
      double sum = 0;
      for (unsigned f : d.children(k)) {
        ASSERT_LT(f, d.fine.direction.size());
        EXPECT_TRUE(covered.insert(f).second) << "fine texel " << f << " twice";
        sum += d.fine.solid_angle[f];
        // The fine texel's centre is nearer its own coarse texel's centre than any other's.
        float best = -2;
        unsigned nearest = 0;
        for (unsigned j = 0; j < d.coarse.direction.size(); ++j) {
          const float c = glm::dot(d.fine.direction[f], d.coarse.direction[j]);
          if (c > best) {
            best = c;
            nearest = j;
          }
        }
        EXPECT_EQ(nearest, k) << "n " << n << " fine " << f;
      }
      EXPECT_NEAR(sum, d.coarse.solid_angle[k], 1e-12) << "n " << n << " coarse " << k;
    }
    EXPECT_EQ(covered.size(), d.fine.direction.size());
  }
  EXPECT_THROW(make_adaptive_directions(15), InternalError);
  EXPECT_THROW(make_adaptive_directions(0), InternalError);
}

TEST(AdaptiveDirections, NeighbourPairsJoinNearTexelsAlsoAcrossCubeEdges) {
  const AdaptiveDirections d = make_adaptive_directions(16);
  const size_t count = d.coarse.direction.size();
  std::vector<int> degree(count, 0);
  int across_faces = 0;
  const unsigned per_face = static_cast<unsigned>(d.coarse.n * d.coarse.n);
  for (size_t i = 0; i < d.pairs.size(); ++i) {
    const glm::uvec2 p = d.pairs[i];
    ASSERT_LT(p.x, p.y);
    ASSERT_LT(p.y, count);
    if (i > 0) {
      EXPECT_TRUE(d.pairs[i - 1].x < p.x || d.pairs[i - 1].y < p.y) << "sorted, unique";
    }
    ++degree[p.x];
    ++degree[p.y];
    across_faces += p.x / per_face != p.y / per_face;
    // Neighbours: at most a texel apart (a coarse texel spans at most 90/8 degrees).
    EXPECT_GT(glm::dot(d.coarse.direction[p.x], d.coarse.direction[p.y]), std::cos(0.3f));
  }
  for (size_t k = 0; k < count; ++k) EXPECT_GE(degree[k], 4) << "texel " << k;
  // Each of the 12 cube edges has 8 texels on either side.
  EXPECT_GE(across_faces, 12 * 8);
}

TEST(AdaptiveDirections, TexelsAreRefinedWhereWhatIsSeenChanges) {
  const AdaptiveDirections d = make_adaptive_directions(16);
  const size_t count = d.coarse.direction.size();
  std::vector<int> seen(count, 4);
  std::vector<unsigned char> refine(count, 1);
  mark_refined_texels(d, seen, refine);
  EXPECT_EQ(std::count(refine.begin(), refine.end(), 1), 0) << "one sheet everywhere";
  // Two sheets meeting on a tilted great circle: only texels next to it are refined, and all
  // of them.
  const glm::vec3 normal = glm::normalize(glm::vec3(0.3f, 1.0f, 0.2f));
  for (size_t k = 0; k < count; ++k) seen[k] = glm::dot(d.coarse.direction[k], normal) > 0 ? 2 : 7;
  mark_refined_texels(d, seen, refine);
  int refined = 0;
  for (size_t k = 0; k < count; ++k) {
    const float height = std::abs(glm::dot(d.coarse.direction[k], normal));
    if (refine[k]) {
      ++refined;
      EXPECT_LT(height, 0.45f) << "texel " << k << " far from the circle";
    } else {
      EXPECT_GT(height, 0.02f) << "texel " << k << " on the circle";
    }
  }
  EXPECT_GE(refined, 2 * 4 * 8);  // a ring at least two texels wide round the sphere
  EXPECT_LT(refined, static_cast<int>(count) / 2);
}

TEST(AdaptiveDirections, PmvcAsAccurateAsEveryTexelWithAboutHalfTheRays) {
  // The kiwi's mid-height cut: 24 narrow locules with seeds, many silhouettes to refine.
  const test::MidHeightCut cut = test::mid_height_cut(test::source_path("templates/kiwi.yaml"));
  const auto every_texel = make_cpu_diffusion(cut.model, DiffusionOptions{16, 0, true, false});
  CrossSectionOptions options{cut.tmpl.edge_m};
  options.sampling = CapSampling::Dense;
  const CrossSection cs = *make_cross_section(cut.model, cut.plane, *every_texel, options);
  const std::vector<size_t> picked = test::interior_vertices(cs, 300);
  std::vector<glm::dvec3> points;
  for (size_t v : picked) points.push_back(cs.position[v]);
  ASSERT_GT(points.size(), 100u);
  const auto adaptive = make_cpu_diffusion(cut.model, DiffusionOptions{16, 0});
  const auto reference = make_cpu_diffusion(cut.model, DiffusionOptions{32, 0, true, false});
  const std::vector<glm::dvec3> with_every = every_texel->diffuse(points);
  const size_t before = adaptive->rays_cast();
  const std::vector<glm::dvec3> with_adaptive = adaptive->diffuse(points);
  const double rays = static_cast<double>(adaptive->rays_cast() - before) / points.size();
  const std::vector<glm::dvec3> truth = reference->diffuse(points);
  double every_sum = 0, adaptive_sum = 0, adaptive_max = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    every_sum += visible_difference(with_every[i], glm::dvec2(0), truth[i], glm::dvec2(0));
    const double e = visible_difference(with_adaptive[i], glm::dvec2(0), truth[i], glm::dvec2(0));
    adaptive_sum += e;
    adaptive_max = std::max(adaptive_max, e);
  }
  const double n = static_cast<double>(points.size());
  std::printf("kiwi cut, %zu points against cube 32: every texel mean %.3f, adaptive mean %.3f "
              "max %.2f (of 255); adaptive %.0f rays a point of %d\n",
              points.size(), every_sum / n, adaptive_sum / n, adaptive_max, rays, 6 * 16 * 16);
  EXPECT_LE(adaptive_sum / n, every_sum / n + 0.05);
  EXPECT_LE(adaptive_max, 1.0);
  EXPECT_LT(rays, 0.7 * 6 * 16 * 16);
  EXPECT_GE(rays, 6 * 8 * 8);
}

}  // namespace
}  // namespace cutaway
