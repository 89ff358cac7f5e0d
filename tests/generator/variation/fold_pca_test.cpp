// PCA fold blending (generator/variation/fold_pca.h) on the tomato and on a tomato whose folds
// differ.
#include "base/constants.h"
#include "variation/fold_pca.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

#include "io/template_parser.h"
#include "model/model_builder.h"
#include "model/template_checks.h"
#include "test_support.h"

namespace cutaway {
namespace {

/// The shipped tomato with equal folds: its chambers' per-fold loops replaced by fold 0's loop,
/// repeated in every fold (its skin's lobes are already 5-fold symmetric).
Template tomato() {
  Template t = load_template(test::source_path("templates/tomato.yaml").string());
  for (auto& s : t.surfaces) {
    if (s.kind == SurfaceKind::Within) s.section.loops.resize(1);
  }
  return t;
}

glm::dvec2 polar_xz(double rho, double phi) { return {rho * std::cos(phi), -rho * std::sin(phi)}; }

/// The tomato with unequal folds: Type I loops scaled by 1 + 0.02 sin(angle), each chamber
/// loop k narrowed or widened across its fold.
Template uneven_tomato() {
  Template t = tomato();
  for (auto& s : t.surfaces) {
    if (s.kind == SurfaceKind::Around && !s.section.circle) {
      for (auto& p : s.section.loops[0]) {
        const double phi = horizontal_angle(p);
        p *= 1 + 0.02 * std::sin(phi);
      }
    }
    if (s.kind == SurfaceKind::Within) {
      const Polyline2 base = s.section.loops[0];
      s.section.loops.clear();
      for (int k = 0; k < t.folds; ++k) {
        Polyline2 loop;
        for (const auto& p : base) {
          const double rel = horizontal_angle(p) - t.fold_angles[0];
          const double scale = 0.8 + 0.1 * (k % 3);
          loop.push_back(polar_xz(glm::length(p), t.fold_angles[k] + rel * scale));
        }
        s.section.loops.push_back(loop);
      }
    }
  }
  check_template_curves(t);
  return t;
}

int components(const DsMesh& m) {
  std::vector<int> parent(m.n_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (auto e : m.edges()) {
    const int a = find(m.from_vertex_handle(m.halfedge_handle(e, 0)).idx());
    const int b = find(m.to_vertex_handle(m.halfedge_handle(e, 0)).idx());
    parent[a] = b;
  }
  int n = 0;
  for (int i = 0; i < static_cast<int>(parent.size()); ++i) n += find(i) == i;
  return n;
}

TEST(FoldPca, EqualFoldsHaveNoVariance) {
  const Template t = tomato();
  const FoldFeatures f = fold_features(t, {});
  EXPECT_EQ(f.folds, 5);
  EXPECT_EQ(f.surface.size(), 3u);  // skin, flesh wall (Type I), chambers (Type II)
  const FoldPca pca = fold_pca(f);
  EXPECT_TRUE(pca.axes.empty());
  for (int k = 0; k < 5; ++k)
    for (size_t d = 0; d < pca.mean.size(); ++d) EXPECT_NEAR(f.samples[k][d], pca.mean[d], 1e-9);
}

TEST(FoldPca, ZeroCoefficientsGiveTheMeanFold) {
  const Template t = uneven_tomato();
  const FoldFeatures f = fold_features(t, {});
  const FoldPca pca = fold_pca(f);
  ASSERT_GE(pca.axes.size(), 2u);
  ASSERT_LE(pca.axes.size(), 4u);  // N - 1 at most
  for (size_t d = 0; d < pca.mean.size(); ++d) {
    double m = 0;
    for (const auto& s : f.samples) m += s[d] / f.samples.size();
    EXPECT_NEAR(pca.mean[d], m, 1e-12);
  }
  Rng rng(derive_seed(3, {}));
  const auto v = draw_fold(pca, 0.0, rng);
  for (size_t d = 0; d < v.size(); ++d) EXPECT_EQ(v[d], pca.mean[d]);
  // Each sample is the mean plus its projections on the axes (the axes span the samples).
  for (const auto& s : f.samples) {
    std::vector<double> r = pca.mean;
    for (const auto& a : pca.axes) {
      double c = 0;
      for (size_t d = 0; d < s.size(); ++d) c += (s[d] - pca.mean[d]) * a[d];
      for (size_t d = 0; d < s.size(); ++d) r[d] += c * a[d];
    }
    for (size_t d = 0; d < s.size(); ++d) EXPECT_NEAR(r[d], s[d], 1e-9);
  }
}

TEST(FoldPca, TypeOneCurvesAreContinuousAcrossFoldLines) {
  const Template t = uneven_tomato();
  const FoldFeatures f = fold_features(t, {});
  const FoldPca pca = fold_pca(f);
  for (int np : {4, 5, 6}) {
    Rng rng(derive_seed(11, {static_cast<uint64_t>(np)}));
    std::vector<std::vector<double>> vs;
    std::vector<double> angles;
    for (int k = 0; k < np; ++k) {
      vs.push_back(draw_fold(pca, 1.5, rng));
      angles.push_back(k * 2 * kPi / np);
    }
    const auto curves = fold_curves_xz(f, vs, angles, {});
    for (size_t ci = 0; ci < curves.size(); ++ci) {
      ASSERT_EQ(static_cast<int>(curves[ci].size()), np);
      if (!f.open[ci]) continue;
      for (int k = 0; k < np; ++k) {
        const double gap = glm::distance(curves[ci][k].back(), curves[ci][(k + 1) % np].front());
        EXPECT_LT(gap, 1e-9) << "curve " << ci << " fold line " << k;
      }
    }
  }
}

TEST(FoldPca, VariantWithNFoldsHasNChambers) {
  const Template t = uneven_tomato();
  const FoldFeatures f = fold_features(t, {});
  const FoldPca pca = fold_pca(f);
  for (int np : {4, 6}) {
    Rng rng(derive_seed(21, {static_cast<uint64_t>(np)}));
    std::vector<std::vector<double>> vs;
    for (int k = 0; k < np; ++k) vs.push_back(draw_fold(pca, 1.0, rng));
    Template v = rebuild_folds(t, f, vs, {});
    v.edge_m *= 2;
    EXPECT_EQ(v.folds, np);
    check_template_curves(v);
    const DsModel m = build_model(v);
    for (const auto& s : m.surfaces) {
      if (s.name == "chambers") {
        EXPECT_EQ(components(s.mesh), np);
      }
      if (s.name == "skin") {
        EXPECT_EQ(components(s.mesh), 1);
      }
    }
  }
}

/// The widest angle a loop spans about the axis, radians.
double angular_width(const Polyline2& loop) {
  double lo = 1e9, hi = -1e9;
  const double centre = horizontal_angle(loop[0]);
  for (const auto& p : loop) {
    const double a = wrap_angle(horizontal_angle(p) - centre);
    lo = std::min(lo, a);
    hi = std::max(hi, a);
  }
  return hi - lo;
}

// A surface with sections at several heights has every section blended with the same fold
// vectors: the rebuilt object keeps both heights' loops, each in N' folds, the upper ones
// still narrower than the lower ones.
TEST(FoldPca, EverySectionAtAHeightIsRebuiltInTheNewFolds) {
  Template t = uneven_tomato();
  size_t chambers = 0;
  for (size_t i = 0; i < t.surfaces.size(); ++i) {
    SurfaceSpec& s = t.surfaces[i];
    if (s.name != "chambers") continue;
    chambers = i;
    SectionSpec narrow = s.section;
    for (size_t k = 0; k < narrow.loops.size(); ++k) {
      for (auto& p : narrow.loops[k]) {
        const double rel = wrap_angle(horizontal_angle(p) - t.fold_angles[k]);
        p = polar_xz(glm::length(p), t.fold_angles[k] + 0.7 * rel);
      }
    }
    s.sections = {{0.2, s.section}, {0.8, narrow}};
  }
  ASSERT_GT(chambers, 0u);
  check_template_curves(t);
  const FoldFeatures f = fold_features(t, {});
  int of_chambers = 0;
  for (size_t c = 0; c < f.surface.size(); ++c) {
    if (f.surface[c] != static_cast<int>(chambers)) continue;
    EXPECT_EQ(f.section[c], of_chambers);
    ++of_chambers;
  }
  EXPECT_EQ(of_chambers, 2);
  const FoldPca pca = fold_pca(f);
  Rng rng(derive_seed(22, {6}));
  std::vector<std::vector<double>> vs;
  for (int k = 0; k < 6; ++k) vs.push_back(draw_fold(pca, 1.0, rng));
  Template v = rebuild_folds(t, f, vs, {});
  v.edge_m *= 2;
  const SurfaceSpec& s = v.surfaces[chambers];
  ASSERT_EQ(s.sections.size(), 2u);
  for (const HeightSection& h : s.sections) EXPECT_EQ(h.section.loops.size(), 6u);
  EXPECT_EQ(s.section.loops, s.sections[0].section.loops);
  for (size_t k = 0; k < 6; ++k) {
    EXPECT_LT(angular_width(s.sections[1].section.loops[k]),
              0.8 * angular_width(s.sections[0].section.loops[k]))
        << "fold " << k;
  }
  check_template_curves(v);
  const DsModel m = build_model(v);
  for (const auto& surface : m.surfaces) {
    if (surface.name == "chambers") {
      EXPECT_EQ(components(surface.mesh), 6);
    }
  }
}

TEST(FoldPca, MeanOfEqualFoldsRebuildsTheTemplate) {
  const Template t = tomato();
  const FoldFeatures f = fold_features(t, {});
  const Template v = rebuild_folds(t, f, f.samples, {});
  // The rebuilt skin loop follows the original: radii at the same angles agree closely.
  const Polyline2 orig = fit_curve(t.surfaces[t.skin].section.loops[0], true, true);
  const Polyline2& loop = v.surfaces[t.skin].section.loops[0];
  for (const auto& p : loop) {
    const double phi = horizontal_angle(p);
    double best = 1e9, rho = 0;
    for (const auto& q : orig) {
      const double d = std::abs(std::remainder(horizontal_angle(q) - phi, 2 * kPi));
      if (d < best) {
        best = d;
        rho = glm::length(q);
      }
    }
    EXPECT_NEAR(glm::length(p), rho, 2e-4);
  }
}

}  // namespace
}  // namespace cutaway
