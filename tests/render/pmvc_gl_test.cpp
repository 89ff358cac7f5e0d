// The GL PMVC backend (render/gl/pmvc_gl.h) against the analytic reference of
// doc/algorithms.md §2(b), the CPU backend, and itself (determinism across batches).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "base/colour.h"
#include "base/constants.h"
#include "base/timer.h"
#include "diffusion/diffusion.h"
#include "diffusion/diffusion_sheets.h"
#include "generator/diffusion/analytic_spheres.h"
#include "generator/diffusion/material_channels.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "render/gl/pmvc_gl.h"
#include "test_support.h"

namespace cutaway {
namespace {

/// ~200 points inside the tomato's skin: polar rings r < 25 mm on horizontal planes at
/// 10..42 mm (the fruit's axis is y).
std::vector<glm::dvec3> tomato_points() {
  std::vector<glm::dvec3> points;
  for (double y : {10.5, 18.5, 26.0, 34.0, 41.5}) {
    for (double r : {0.7, 6.3, 12.1, 17.9, 24.2}) {
      for (int k = 0; k < 8; ++k) {
        const double angle = 2 * kPi * (k + 0.37 * r / 25) / 8;
        points.push_back(1e-3 * glm::dvec3(r * std::cos(angle), y, r * std::sin(angle)));
      }
    }
  }
  return points;
}

const DsModel& tomato_model() {
  static const DsModel model =
      build_model(load_template(test::source_path("templates/tomato.yaml").string()));
  return model;
}

TEST(PmvcGl, ConcentricSpheresMatchTheAnalyticIntegral) {
  const Template t = load_template(test::source_path("templates/spheres.yaml").string());
  const DsModel model = build_model(t);
  const auto backend = make_gl_diffusion(model, DiffusionOptions{32, 0});
  EXPECT_EQ(backend->name(), "gl");
  const test::TwoSphereErrors e = test::two_sphere_errors(*backend, t.edge_m);
  RecordProperty("mean_error", std::to_string(e.mean));
  std::printf("pmvc gl: %zu points, mean error %.5f, max %.5f, %.3f s\n", e.points, e.mean, e.max,
              e.seconds);
  EXPECT_LE(e.mean, 0.005);
  EXPECT_LE(e.max, 0.03);
}

// A two-faced (unblurred) sheet shows its front colour where the ray meets its front face: the
// cube faces are mirrored projections, so this checks the winding convention of the renderer.
TEST(PmvcGl, TwoFacedSheetsShowTheFaceTheRayMeets) {
  const std::string text = R"(format: cutaway-template/1
name: faces
symmetry: {type: cylindrical}
resolution: {edge: 3}
surfaces:
  - {name: skin, kind: around, role: skin, section: circle, profile: [[0, -30], [21.2, -21.2], [30, 0], [21.2, 21.2], [0, 30]], front: "#0000ff", back: "#336699"}
  - {name: core, kind: around, section: circle, profile: [[0, -12], [8.5, -8.5], [12, 0], [8.5, 8.5], [0, 12]], front: "#336699", back: "#ffffff"}
)";
  const DsModel model = build_model(parse_template(text, "faces.yaml", "."));
  const auto backend = make_gl_diffusion(model, DiffusionOptions{16, 0});
  // Inside the core: only the core's back face. Between: the skin's back and the core's front.
  const std::vector<glm::dvec3> points = {
      {0.001, 0.002, -0.003}, {-0.004, 0, 0.002}, {0.018, 0.003, 0.001}, {0, -0.02, 0.004}};
  const std::vector<glm::dvec3> colours = backend->diffuse(points);
  const glm::dvec3 blue_grey = srgb_to_linear(glm::dvec3(0x33, 0x66, 0x99) / 255.0);
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 want = i < 2 ? glm::dvec3(1.0) : blue_grey;
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(colours[i][c], want[c], 1e-6) << "point " << i;
  }
}

TEST(PmvcGl, MaterialChannelsAreDiffusedFromTheSameRaysAsColours) {
  const test::MaterialChannelErrors e =
      test::material_channel_errors(tomato_model(), tomato_points(), [](const DsModel& m) {
        return make_gl_diffusion(m, DiffusionOptions{16, 0});
      });
  EXPECT_GT(e.distinct_values, 0.05);
  EXPECT_LT(e.material_vs_colour, 1e-6);
  EXPECT_EQ(e.colour_change, 0.0);
}

TEST(PmvcGl, AgreesWithTheCpuBackendInsideTheTomato) {
  // With adaptive directions (the default) and with every texel cast: the same colours, and
  // adaptively the same texels refined (the same number of rays, up to float rounding deciding
  // a hit differently).
  const std::vector<glm::dvec3> points = tomato_points();
  const int n = 16;
  for (const bool adaptive : {true, false}) {
    const DiffusionOptions options{n, 0, true, adaptive};
    const auto gl = make_gl_diffusion(tomato_model(), options);
    const auto cpu = make_cpu_diffusion(tomato_model(), options);
    auto start = std::chrono::steady_clock::now();
    const std::vector<glm::dvec3> a = gl->diffuse(points);
    const double gl_s = seconds_since(start);
    start = std::chrono::steady_clock::now();
    const std::vector<glm::dvec3> b = cpu->diffuse(points);
    const double cpu_s = seconds_since(start);
    double sum = 0, max = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      for (int c = 0; c < 3; ++c) {
        const double d = std::abs(a[i][c] - b[i][c]);
        sum += d;
        max = std::max(max, d);
      }
    }
    const double mean = sum / (3.0 * points.size());
    const double rays = static_cast<double>(cpu->rays_cast());
    std::printf(
        "pmvc gl vs cpu, tomato, cube %d%s, %zu points: mean |difference| %.2e, max %.2e per "
        "channel (linear RGB); %.0f rays a point (gl %.0f); gl %.0f points/s (%.2e rays/s), "
        "cpu %.0f points/s (%.2e rays/s)\n",
        n, adaptive ? " adaptive" : "", points.size(), mean, max, rays / points.size(),
        static_cast<double>(gl->rays_cast()) / points.size(), points.size() / gl_s, rays / gl_s,
        points.size() / cpu_s, rays / cpu_s);
    RecordProperty(adaptive ? "mean_difference_adaptive" : "mean_difference", std::to_string(mean));
    EXPECT_LE(mean, 0.005);  // doc/algorithms.md §2: backends agree to 0.005 per channel on average
    EXPECT_LE(max, 0.05);
    EXPECT_NEAR(static_cast<double>(gl->rays_cast()), rays, 0.01 * rays);
    if (!adaptive) {
      EXPECT_EQ(cpu->rays_cast(), points.size() * 6 * n * n);
    }
  }
}

TEST(PmvcGl, ResultsAreBitIdenticalAcrossRunsAndBatches) {
  const std::vector<glm::dvec3> tomato_all = tomato_points();
  const std::vector<glm::dvec3> all(tomato_all.begin(), tomato_all.begin() + 60);
  const auto backend = make_gl_diffusion(tomato_model(), DiffusionOptions{16, 0});
  const std::vector<glm::dvec3> first = backend->diffuse(all);
  const std::vector<glm::dvec3> second = backend->diffuse(all);
  ASSERT_EQ(first, second);
  // Seven of them alone, and all in reverse order: other batches, other batch positions.
  const size_t picks[] = {0, 9, 17, 26, 38, 44, all.size() - 1};
  std::vector<glm::dvec3> some;
  for (size_t i : picks) some.push_back(all[i]);
  const std::vector<glm::dvec3> alone = backend->diffuse(some);
  for (size_t k = 0; k < some.size(); ++k)
    EXPECT_EQ(alone[k], first[picks[k]]) << "point " << picks[k];
  const std::vector<glm::dvec3> reversed_order = [&] {
    std::vector<glm::dvec3> r(all.rbegin(), all.rend());
    return backend->diffuse(r);
  }();
  for (size_t i = 0; i < all.size(); ++i)
    EXPECT_EQ(reversed_order[all.size() - 1 - i], first[i]) << "point " << i;
}

TEST(PmvcGl, OutsidePointsAreBlackAndBadCubeSizesAreRefused) {
  const auto backend = make_gl_diffusion(tomato_model(), DiffusionOptions{8, 0});
  const std::vector<glm::dvec3> outside = backend->diffuse(std::vector<glm::dvec3>{{1, 1, 1}});
  EXPECT_EQ(outside[0], glm::dvec3(0.0));
  EXPECT_TRUE(backend->diffuse({}).empty());
  EXPECT_THROW(make_gl_diffusion(tomato_model(), DiffusionOptions{0, 0}), InternalError);
}

/// Throughput on templates/tomato.yaml, both backends, cube 32 and 16 (not part of the suite:
/// run with --gtest_also_run_disabled_tests --gtest_filter='*Throughput*').
TEST(PmvcGl, DISABLED_Throughput) {
  size_t vertices = 0, triangles = 0;
  for (const DiffusionSheet& s : make_diffusion_sheets(tomato_model())) {
    vertices += s.position.size();
    triangles += s.triangle.size();
  }
  std::printf("tomato sheets: %zu vertices, %zu triangles\n", vertices, triangles);
  std::vector<glm::dvec3> points;
  for (int i = 0; i < 4; ++i)
    for (const glm::dvec3& p : tomato_points()) points.push_back(p + glm::dvec3(0, 1e-4 * i, 0));
  for (int n : {32, 16}) {
    for (bool use_gl : {true, false}) {
      const auto backend = use_gl ? make_gl_diffusion(tomato_model(), DiffusionOptions{n, 0})
                                  : make_cpu_diffusion(tomato_model(), DiffusionOptions{n, 0});
      const auto start = std::chrono::steady_clock::now();
      backend->diffuse(points);
      const double s = seconds_since(start);
      std::printf("%s cube %d: %zu points in %.2f s: %.0f points/s, %.3e rays/s\n",
                  backend->name().c_str(), n, points.size(), s, points.size() / s,
                  points.size() * 6.0 * n * n / s);
    }
  }
}

}  // namespace
}  // namespace cutaway
