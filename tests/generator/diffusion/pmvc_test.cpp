// PMVC colour diffusion against the reference checks of doc/algorithms.md §2.
#include <chrono>
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "base/colour.h"
#include "base/constants.h"
#include "diffusion/cube_directions.h"
#include "diffusion/diffusion.h"
#include "generator/diffusion/analytic_spheres.h"
#include "generator/diffusion/material_channels.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

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
  DiffusionOptions aligned;
  aligned.rotate_cubes = false;
  const test::TwoSphereErrors a =
      test::two_sphere_errors(*make_cpu_diffusion(model, aligned), t.edge_m);
  std::printf("pmvc cpu, cubes not turned: mean error %.5f, max %.5f\n", a.mean, a.max);
  RecordProperty("mean_error", std::to_string(e.mean));
  std::printf("pmvc cpu: %zu points, mean error %.5f, max %.5f, %.3f s\n", e.points, e.mean, e.max,
              e.seconds);
  EXPECT_LE(e.mean, 0.005);
  EXPECT_LE(e.max, 0.03);
}

TEST(PmvcCpu, TurnedCubesCancelTheTexelErrorsOnTheAxisOfAFourFoldObject) {
  // On the axis of a 4-fold object the cube's texel grid lines up with the symmetry and the
  // texel errors add up; a cube turned per point (cube_rotation) lets them cancel.
  const Template t = load_template(test::source_path("templates/pepper.yaml").string());
  const DsModel model = build_model(t);
  std::vector<glm::dvec3> axis;
  const double lo = model.bbox_min.y, hi = model.bbox_max.y;
  for (int i = 1; i <= 24; ++i) axis.push_back({0, lo + (hi - lo) * (0.2 + 0.6 * i / 25.0), 0});
  DiffusionOptions reference{64, 0};
  reference.rotate_cubes = false;
  const std::vector<glm::dvec3> want = make_cpu_diffusion(model, reference)->diffuse(axis);
  auto errors = [&](bool rotate) {
    DiffusionOptions o{16, 0};
    o.rotate_cubes = rotate;
    const std::vector<glm::dvec3> got = make_cpu_diffusion(model, o)->diffuse(axis);
    double sum = 0, max = 0;
    for (size_t i = 0; i < axis.size(); ++i)
      for (int k = 0; k < 3; ++k) {
        const double e = std::fabs(got[i][k] - want[i][k]);
        sum += e;
        max = std::max(max, e);
      }
    return std::pair<double, double>(sum / (3.0 * axis.size()), max);
  };
  const auto [aligned_mean, aligned_max] = errors(false);
  const auto [turned_mean, turned_max] = errors(true);
  std::printf("pepper axis, cube 16 vs 64 (linear): aligned mean %.5f max %.5f, turned mean "
              "%.5f max %.5f\n",
              aligned_mean, aligned_max, turned_mean, turned_max);
  EXPECT_LT(turned_max, aligned_max);
  EXPECT_LT(turned_mean, aligned_mean);
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
  const std::vector<glm::dvec3> pts = {
      {0.001, 0.005, 0}, {0.015, 0.02, 0.003}, {0, 0.04, 0.001}, {0.002, 0.02, 0.002}};
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

TEST(PmvcCpu, MaterialChannelsAreDiffusedFromTheSameRaysAsColours) {
  const DsModel model =
      build_model(load_template(test::source_path("templates/tomato.yaml").string()));
  std::vector<glm::dvec3> pts;
  for (int i = 0; i < 64; ++i) pts.push_back({0.001 * (i % 8) * 3, 0.01 + 0.004 * (i / 8), 0.002});
  const test::MaterialChannelErrors e =
      test::material_channel_errors(model, pts, [](const DsModel& m) {
        return make_cpu_diffusion(m, DiffusionOptions{16, 2});
      });
  EXPECT_GT(e.distinct_values, 0.05);  // the channels vary: the check means something
  EXPECT_LT(e.material_vs_colour, 1e-6);
  EXPECT_EQ(e.colour_change, 0.0);  // colours do not depend on whether materials are asked for
}

TEST(PmvcCpu, TemplateMaterialChannelsReachTheCutFace) {
  // Roughness 0.2 on the core's outside, 0.8 everywhere else; translucency from the cut
  // material (0.4) except 0.9 on the skin's inside.
  const std::string text = R"(format: cutaway-template/1
name: channels
symmetry: {type: cylindrical}
resolution: {edge: 3}
materials: {cut: {roughness: 0.8, translucency: 0.4}}
surfaces:
  - {name: skin, kind: around, role: skin, profile: [[0, 0], [20, 10], [25, 30], [0, 50]], translucency: {back: 0.9}}
  - {name: core, kind: around, profile: [[0, 10], [8, 20], [0, 35]], roughness: {front: 0.2}}
)";
  const DsModel model = build_model(parse_template(text, "channels.yaml", "."));
  const auto backend = make_cpu_diffusion(model, DiffusionOptions{8, 1});
  // Inside the core it sees only the core's back (0.8, 0.4); between, a blend.
  const std::vector<glm::dvec3> pts = {{0, 0.02, 0.001}, {0.015, 0.02, 0.003}};
  std::vector<glm::dvec3> colour(pts.size());
  std::vector<glm::dvec2> material(pts.size());
  backend->diffuse_channels(pts, colour, material);
  EXPECT_NEAR(material[0].x, 0.8, 1e-6);
  EXPECT_NEAR(material[0].y, 0.4, 1e-6);
  EXPECT_GT(material[1].x, 0.2);
  EXPECT_LT(material[1].x, 0.8);
  EXPECT_GT(material[1].y, 0.4);
  EXPECT_LT(material[1].y, 0.9);
  std::vector<glm::dvec2> short_material(1);
  EXPECT_THROW(backend->diffuse_channels(pts, colour, short_material), InternalError);
}

}  // namespace
}  // namespace cutaway
