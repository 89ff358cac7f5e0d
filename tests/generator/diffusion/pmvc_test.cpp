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
  const test::TwoSphereErrors e = test::two_sphere_errors(*backend, t.edge_m);
  RecordProperty("mean_error", std::to_string(e.mean));
  std::printf("pmvc cpu: %zu points, mean error %.5f, max %.5f, %.3f s\n", e.points, e.mean,
              e.max, e.seconds);
  EXPECT_LE(e.mean, 0.005);
  EXPECT_LE(e.max, 0.03);
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
