// PMVC colour diffusion against the reference checks of design/algorithms.md §2.
#include <chrono>
#include <cmath>
#include <numbers>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "colour.h"
#include "diffusion/cube_directions.h"
#include "diffusion/diffusion.h"
#include "generator/diffusion/analytic_spheres.h"
#include "model_builder.h"
#include "template_parser.h"
#include "test_support.h"

namespace cutaway {
namespace {

constexpr double kPi = std::numbers::pi;

using test::inner_share;

TEST(CubeDirections, SolidAnglesSumToTheSphere) {
  for (int n : {1, 4, 32}) {
    const CubeDirections d = make_cube_directions(n);
    ASSERT_EQ(d.direction.size(), static_cast<size_t>(6 * n * n));
    double sum = 0;
    for (double s : d.solid_angle) sum += s;
    EXPECT_NEAR(sum, 4 * kPi, 1e-9) << "n = " << n;
    for (const auto& v : d.direction) EXPECT_NEAR(glm::length(v), 1.0f, 1e-6f);
  }
}

TEST(PmvcCpu, ConcentricSpheresMatchTheAnalyticIntegral) {
  const Template t = load_template(test::source_path("templates/spheres.yaml").string());
  const DsModel model = build_model(t);
  const auto backend = make_cpu_diffusion(model, DiffusionOptions{});
  const double a = 0.020, b = 0.040, edge = t.edge_m;
  std::vector<glm::dvec3> points;
  std::vector<double> expected;
  // Rays from the centre in several directions, off the axes and on them.
  const glm::dvec3 dirs[] = {{1, 0, 0}, {0, 1, 0}, glm::normalize(glm::dvec3(1, 0.7, -0.4)),
                             glm::normalize(glm::dvec3(-0.3, -0.8, 0.5))};
  for (const auto& d : dirs) {
    for (double r = a + edge; r <= b - edge + 1e-12; r += (b - a - 2 * edge) / 24) {
      points.push_back(d * r);
      expected.push_back(inner_share(a, b, r));
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<glm::dvec3> colours = backend->diffuse(points);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  double sum_err = 0, max_err = 0;
  for (size_t i = 0; i < points.size(); ++i) {
    // Inner sphere: green (0, 1, 0); outer sphere's inside: red (1, 0, 0); linear RGB.
    const glm::dvec3 want(1 - expected[i], expected[i], 0);
    const double err = glm::length(colours[i] - want) / std::sqrt(2.0);
    sum_err += err;
    max_err = std::max(max_err, err);
  }
  const double mean_err = sum_err / points.size();
  RecordProperty("mean_error", std::to_string(mean_err));
  std::printf("pmvc cpu: %zu points, mean error %.5f, max %.5f, %.0f rays/s\n", points.size(),
              mean_err, max_err, points.size() * 6.0 * 32 * 32 / seconds);
  EXPECT_LE(mean_err, 0.005);
  EXPECT_LE(max_err, 0.03);
}

TEST(PmvcCpu, OneColourEverywhereGivesThatColour) {
  const std::string text = R"(format: cutaway-template/1
name: one-colour
symmetry: {type: cylindrical}
resolution: {edge: 3}
surfaces:
  - {name: skin, kind: around, role: skin, profile: [[0, 0], [20, 10], [25, 30], [0, 50]], front: "#336699", back: "#336699", blur: 2}
  - {name: core, kind: around, profile: [[0, 10], [8, 20], [0, 35]], front: "#336699", back: "#336699"}
)";
  const DsModel model = build_model(parse_template(text, "one-colour.yaml", "."));
  const auto backend = make_cpu_diffusion(model, DiffusionOptions{8, 1});
  const std::vector<glm::dvec3> pts = {{0.001, 0.005, 0}, {0.015, 0.02, 0.003}, {0, 0.04, 0.001},
                                       {0.002, 0.02, 0.002}};
  const glm::dvec3 want = srgb_to_linear(glm::dvec3(0x33, 0x66, 0x99) / 255.0);
  for (const auto& c : backend->diffuse(pts)) {
    EXPECT_NEAR(c.x, want.x, 1e-6);
    EXPECT_NEAR(c.y, want.y, 1e-6);
    EXPECT_NEAR(c.z, want.z, 1e-6);
  }
}

TEST(PmvcCpu, ResultDoesNotDependOnThreadCount) {
  const Template t = load_template(test::source_path("templates/tomato.yaml").string());
  const DsModel model = build_model(t);
  std::vector<glm::dvec3> pts;
  for (int i = 0; i < 64; ++i) pts.push_back({0.001 * (i % 8) * 3, 0.01 + 0.004 * (i / 8), 0.002});
  const auto one = make_cpu_diffusion(model, DiffusionOptions{16, 1})->diffuse(pts);
  const auto two = make_cpu_diffusion(model, DiffusionOptions{16, 2})->diffuse(pts);
  ASSERT_EQ(one.size(), two.size());
  for (size_t i = 0; i < one.size(); ++i) EXPECT_EQ(one[i], two[i]) << "point " << i;
}

}  // namespace
}  // namespace cutaway
