// Grains (generator/variation/grains.h) on the tomato's and the pepper's surfaces, and
// grains through a region between two surfaces.
#include "variation/grains.h"

#include <functional>

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include "base/colour.h"
#include "base/constants.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

struct Built {
  Template t;
  DsModel m;
};

Built build(const char* name) {
  Built b{load_template(test::source_path(name).string()), {}};
  b.m = build_model(b.t);
  return b;
}

const DsSurface& named(const DsModel& m, const std::string& name) {
  for (const auto& s : m.surfaces)
    if (s.name == name) return s;
  throw std::runtime_error("no surface " + name);
}

TEST(Grains, PoissonDiscSpacingHolds) {
  for (const char* name : {"templates/tomato.yaml", "templates/pepper.yaml"}) {
    const Built b = build(name);
    const GrainSpec& g = b.t.grains.at(0);
    Rng rng(derive_seed(1, {}));
    const auto grains = place_grains(g, named(b.m, g.on), rng);
    EXPECT_GT(grains.size(), 20u) << name;
    double min_d = 1e9;
    for (size_t i = 0; i < grains.size(); ++i)
      for (size_t j = i + 1; j < grains.size(); ++j)
        min_d = std::min(min_d, glm::distance(grains[i].centre, grains[j].centre));
    EXPECT_GE(min_d, g.spacing) << name;
    EXPECT_LT(min_d, 1.5 * g.spacing) << name;  // the region is filled, not sparse
    for (const auto& p : grains) {
      EXPECT_NEAR(glm::distance(p.surface_point, p.centre), g.depth, 1e-9);
      EXPECT_NEAR(glm::dot(p.axis_profile, p.axis_normal), 0, 1e-9);
      EXPECT_NEAR(glm::length(p.axis_section), 1, 1e-9);
      for (int k = 0; k < 3; ++k) {
        EXPECT_GE(p.semi_axes[k], g.semi_axes[k] * (1 - g.jitter) - 1e-12);
        EXPECT_LE(p.semi_axes[k], g.semi_axes[k] * (1 + g.jitter) + 1e-12);
      }
    }
    std::printf("%s: %zu grains, minimum centre distance %.3f mm (spacing %.3f mm)\n", name,
                grains.size(), min_d * 1e3, g.spacing * 1e3);
  }
}

TEST(Grains, ScatterAddsClosedOutwardEllipsoids) {
  Built b = build("templates/tomato.yaml");
  const size_t before = b.m.surfaces.size();
  scatter_grains(b.t, b.m, 7);
  ASSERT_EQ(b.m.surfaces.size(), before + 1);
  const DsSurface& s = b.m.surfaces.back();
  EXPECT_EQ(s.role, SurfaceRole::Grain);
  EXPECT_EQ(s.name, "seeds");
  const GrainOptions opt;
  const size_t per = 2 + (opt.rings - 1) * opt.segments;
  ASSERT_EQ(s.mesh.n_vertices() % per, 0u);
  for (auto h : s.mesh.halfedges()) ASSERT_FALSE(s.mesh.is_boundary(h));
  EXPECT_GT(signed_volume(s.mesh), 0);  // normals point out of every grain
  const auto f = s.mesh.data(*s.mesh.vertices_begin()).front;
  EXPECT_NEAR(f[0], b.t.grains[0].front.x, 1e-12);
  // Same seed, same grains; another seed, other grains.
  Built c = build("templates/tomato.yaml");
  scatter_grains(c.t, c.m, 7);
  Built d = build("templates/tomato.yaml");
  scatter_grains(d.t, d.m, 8);
  const auto& pc = c.m.surfaces.back().mesh;
  ASSERT_EQ(pc.n_vertices(), s.mesh.n_vertices());
  for (auto vh : s.mesh.vertices()) ASSERT_EQ(s.mesh.point(vh), pc.point(vh));
  EXPECT_TRUE(d.m.surfaces.back().mesh.n_vertices() != s.mesh.n_vertices() ||
              d.m.surfaces.back().mesh.point(d.m.surfaces.back().mesh.vertex_handle(0)) !=
                  s.mesh.point(s.mesh.vertex_handle(0)));
}

/// The profile of a ball of radius r (mm): 13 points on a half circle, bottom to top.
std::string half_circle(double r) {
  std::string out = "[";
  for (int k = 0; k <= 12; ++k) {
    const double a = kPi * (k / 12.0 - 0.5);
    out += (k ? ", [" : "[") + std::to_string(k == 0 || k == 12 ? 0.0 : r * std::cos(a)) + ", " +
           std::to_string(r * std::sin(a)) + "]";
  }
  return out + "]";
}

/// A ball of radius 20 mm holding a ball `core` of radius `core_r` whose centre lies
/// `core_x` mm along +X, and seeds on the skin's back side, 4 mm deep, 2 mm across.
Template seeded_ball(double core_x, double core_r) {
  return parse_template(
      "format: cutaway-template/1\nname: ball\nunits: mm\nsymmetry: {type: cylindrical}\n"
      "resolution: {edge: 1.2}\nsurfaces:\n"
      "  - {name: skin, kind: around, role: skin, profile: " +
          half_circle(20) + "}\n  - {name: core, kind: around, offset: [" + std::to_string(core_x) +
          ", 0, 0], profile: " + half_circle(core_r) +
          "}\n"
          "grains:\n"
          "  - {name: seeds, on: skin, spacing: 5, depth: 4, shape: {ellipsoid: [2, 2, 2]}, front: "
          "\"#201810\", back: \"#201810\"}\n",
      "ball.yaml", ".");
}

// Grains may cross the surface they sit on, but no other: a core off the axis reaches within
// 5 mm of the skin on its side, where 4 mm deep seeds 2 mm across would cross it; none is
// placed across it, while the same cone on the far side gets grains.
TEST(Grains, NoGrainCrossesASurfaceItDoesNotSitOn) {
  const Template t = seeded_ball(7, 8);
  DsModel m = build_model(t);
  scatter_grains(t, m, 3);
  const DsSurface& seeds = m.surfaces.back();
  ASSERT_EQ(seeds.name, "seeds");
  const GrainOptions opt;
  const size_t per = 2 + (opt.rings - 1) * opt.segments;
  size_t near_side = 0, far_side = 0;
  double closest = 1e9;  // from a grain vertex to the core's centre, mm
  for (size_t g = 0; g < seeds.mesh.n_vertices() / per; ++g) {
    glm::dvec3 centre(0.0);
    for (size_t k = 0; k < per; ++k) {
      const glm::dvec3 p =
          to_glm(seeds.mesh.point(DsMesh::VertexHandle(static_cast<int>(g * per + k))));
      centre += p / static_cast<double>(per);
      closest = std::min(closest, glm::distance(p, glm::dvec3(7e-3, 0, 0)) * 1e3);
    }
    // Within 20 degrees of +X a grain 16 mm out would come within 7.7 mm of the core's centre.
    const double along = centre.x / glm::length(centre);
    near_side += along > std::cos(20 * kPi / 180);
    far_side += -along > std::cos(20 * kPi / 180);
  }
  EXPECT_GT(closest, 8.0);  // the core's mesh lies within its 8 mm ball
  EXPECT_EQ(near_side, 0u);
  EXPECT_GT(far_side, 0u);
  std::printf("%zu grains beside the core, %zu on the far side; closest grain point %.2f mm from "
              "its centre\n",
              near_side, far_side, closest);
}

TEST(Grains, ASetThatCrossesASurfaceWhereverItIsPlacedIsRefused) {
  const Template t = seeded_ball(0, 15);  // seeds reach 14 mm from the centre
  DsModel m = build_model(t);
  try {
    scatter_grains(t, m, 3);
    FAIL() << "grains that cross the core everywhere were placed";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "grains[0]");
    EXPECT_NE(std::string(e.what()).find("grains \"seeds\" touch or cross surface \"core\" "
                                         "wherever they are placed"),
              std::string::npos)
        << e.what();
  }
}

/// Expects `work` to throw an InputError at `field` whose rule contains `rule` (`what` names
/// the case in the failure message).
void expect_refused(const std::function<void()>& work, const std::string& field,
                    const std::string& rule, const std::string& what) {
  try {
    work();
    ADD_FAILURE() << "accepted: " << what;
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), field) << e.what();
    EXPECT_NE(std::string(e.rule()).find(rule), std::string::npos) << e.what();
  }
}

/// A ball of radius 20 mm holding `flesh` (radius 14 mm, blur 1 mm) around a `core` (radius 6
/// mm), with the grain set `grain` (a YAML flow map without its braces).
Template ball_with_region(const std::string& grain) {
  return parse_template(
      "format: cutaway-template/1\nname: ball\nunits: mm\nsymmetry: {type: cylindrical}\n"
      "resolution: {edge: 1.2}\nsurfaces:\n"
      "  - {name: skin, kind: around, role: skin, profile: " +
          half_circle(20) + "}\n  - {name: flesh, kind: around, blur: 1, profile: " +
          half_circle(14) + "}\n  - {name: core, kind: around, profile: " + half_circle(6) +
          "}\ngrains:\n  - {" + grain + "}\n",
      "ball.yaml", ".");
}

TEST(Grains, GrainsThroughARegionFillItAndKeepClearOfEverySurfaceAndBlurSheet) {
  const Template t = ball_with_region(
      "name: seeds, inside: flesh, outside: core, spacing: 2.5, shape: {ellipsoid: [0.9, 0.6, "
      "0.5]}, front: \"#201810\", back: \"#201810\", jitter: 0.2");
  DsModel m = build_model(t);
  scatter_grains(t, m, 5);
  const DsSurface& seeds = m.surfaces.back();
  ASSERT_EQ(seeds.name, "seeds");
  const GrainOptions opt;
  const size_t per = 2 + (opt.rings - 1) * opt.segments;
  const size_t count = seeds.mesh.n_vertices() / per;
  double nearest = 1e9, farthest = 0;  // grain vertices' distances from the centre, mm
  std::vector<glm::dvec3> centres;
  for (size_t g = 0; g < count; ++g) {
    glm::dvec3 centre(0.0);
    for (size_t k = 0; k < per; ++k) {
      const glm::dvec3 p =
          to_glm(seeds.mesh.point(DsMesh::VertexHandle(static_cast<int>(g * per + k))));
      centre += p / static_cast<double>(per);
      nearest = std::min(nearest, glm::length(p) * 1e3);
      farthest = std::max(farthest, glm::length(p) * 1e3);
    }
    centres.push_back(centre);
  }
  // The shell between 6 and 14 mm holds about 10,600 mm^3; at 2.5 mm spacing dart throwing
  // fills it with several hundred grains.
  EXPECT_GT(count, 300u);
  EXPECT_GT(nearest, 5.9);    // outside the core (its chords come 0.05 mm inside its 6 mm ball)
  EXPECT_LT(farthest, 13.0);  // inside the flesh's back sheet, 1 mm in from its 14 mm
  double closest_pair = 1e9;
  for (size_t i = 0; i < centres.size(); ++i)
    for (size_t j = i + 1; j < centres.size(); ++j)
      closest_pair = std::min(closest_pair, glm::distance(centres[i], centres[j]) * 1e3);
  EXPECT_GE(closest_pair, 2.5 - 1e-9);
  std::printf("%zu grains between 6 and 14 mm: vertices %.2f to %.2f mm from the centre, centres "
              "at least %.2f mm apart\n",
              count, nearest, farthest, closest_pair);
}

TEST(Grains, GrainsThroughARegionAreRefusedWithTheirLocation) {
  struct Case {
    std::string grain, field, rule;
  };
  const std::string shape =
      "spacing: 2.5, shape: {ellipsoid: [1, 1, 1]}, front: \"#000000\", back: \"#000000\"";
  const Case cases[] = {
      {"name: s, on: skin, inside: flesh, " + shape, "grains[0].on", "either on a surface"},
      {"name: s, outside: core, on: skin, " + shape, "grains[0].outside", "needs an inside"},
      {"name: s, inside: flesh, outside: flesh, " + shape, "grains[0].outside", "another surface"},
      {"name: s, inside: pulp, " + shape, "grains[0].inside", "no surface is named \"pulp\""},
      {"name: s, inside: flesh, depth: 1, " + shape, "grains[0].depth", "only grains `on`"},
      {"name: s, inside: flesh, region: {profile: [0, 1]}, " + shape, "grains[0].region",
       "only grains `on`"},
  };
  for (const Case& c : cases) {
    expect_refused([&] { ball_with_region(c.grain); }, c.field, c.rule, c.grain);
  }
  // Far too many for the volume: 4/3 pi 14^3 mm^3 at 0.3 mm spacing.
  const Template dense = ball_with_region(
      "name: s, inside: flesh, spacing: 0.3, shape: {ellipsoid: [0.1, 0.1, 0.1]}, front: "
      "\"#000000\", back: \"#000000\"");
  DsModel m = build_model(dense);
  expect_refused([&] { scatter_grains(dense, m, 1); }, "grains[0].spacing", "",
                 "a spacing far too small for the volume");
}

// A set with a core gets a second surface, "<name>-core": one smaller ellipsoid inside each
// grain, the same centre and frame, its semi-axes times the scale, its own colours. The
// budget counts each core as a grain.
TEST(Grains, ACoreIsASmallerGrainInsideEachGrain) {
  const std::string grain =
      "name: arils, inside: flesh, outside: core, spacing: 2.5, shape: {ellipsoid: [0.9, 0.6, "
      "0.5]}, front: \"#c81434\", back: \"#d42444\", jitter: 0.2, core: {scale: 0.4, front: "
      "\"#d42444\", back: \"#f2e2d6\", translucency: 0.1}";
  const Template t = ball_with_region(grain);
  ASSERT_TRUE(t.grains[0].core.has_value());
  DsModel m = build_model(t);
  scatter_grains(t, m, 5);
  ASSERT_GE(m.surfaces.size(), 2u);
  const DsSurface& arils = m.surfaces[m.surfaces.size() - 2];
  const DsSurface& cores = m.surfaces.back();
  ASSERT_EQ(arils.name, "arils");
  ASSERT_EQ(cores.name, "arils-core");
  EXPECT_EQ(cores.role, SurfaceRole::Grain);
  ASSERT_EQ(cores.mesh.n_vertices(), arils.mesh.n_vertices());
  ASSERT_GT(arils.mesh.n_vertices(), 0u);
  const GrainOptions opt;
  const size_t per = 2 + (opt.rings - 1) * opt.segments;
  for (size_t g = 0; g < arils.mesh.n_vertices() / per; ++g) {
    glm::dvec3 centre(0.0);
    for (size_t k = 0; k < per; ++k)
      centre += to_glm(arils.mesh.point(DsMesh::VertexHandle(static_cast<int>(g * per + k)))) /
                static_cast<double>(per);
    for (size_t k = 0; k < per; ++k) {  // each core vertex is its grain's, drawn in by 0.4
      const int v = static_cast<int>(g * per + k);
      const glm::dvec3 a = to_glm(arils.mesh.point(DsMesh::VertexHandle(v)));
      const glm::dvec3 c = to_glm(cores.mesh.point(DsMesh::VertexHandle(v)));
      EXPECT_NEAR(glm::distance(c, centre + 0.4 * (a - centre)), 0.0, 1e-12);
    }
  }
  const auto& d = cores.mesh.data(DsMesh::VertexHandle(0));
  EXPECT_NEAR(d.back[0], srgb_to_linear(0xf2 / 255.0), 1e-9);
  EXPECT_NEAR(d.material_back[1], 0.1, 1e-12);
  EXPECT_EQ(d.blur, 0.0);

  // The budget counts the cores: a spacing whose grains alone fit the 10,000 but not with
  // as many cores is refused, saying so.
  const Template crowded = ball_with_region(
      "name: s, inside: flesh, spacing: 0.8, shape: {ellipsoid: [0.3, 0.3, 0.3]}, front: "
      "\"#000000\", back: \"#000000\", core: {scale: 0.5, front: \"#000000\", back: "
      "\"#ffffff\"}");
  DsModel cm = build_model(crowded);
  expect_refused([&] { scatter_grains(crowded, cm, 1); }, "grains[0].spacing", "grains and cores",
                 "cores beyond the grain budget");
}

TEST(Grains, ABadCoreIsRefusedWithItsLocation) {
  struct Case {
    std::string core, field, rule;
  };
  const Case cases[] = {
      {"{scale: 1, front: \"#000000\", back: \"#000000\"}", "grains[0].core.scale",
       "strictly between 0 and 1"},
      {"{scale: 0, front: \"#000000\", back: \"#000000\"}", "grains[0].core.scale",
       "strictly between 0 and 1"},
      {"{scale: 0.5, back: \"#000000\"}", "grains[0].core", "front"},
      {"{scale: 0.5, front: \"#000000\", back: \"#000000\", blur: 1}", "grains[0].core.blur", ""},
  };
  for (const Case& c : cases) {
    expect_refused(
        [&] {
          ball_with_region(
              "name: s, inside: flesh, spacing: 2.5, shape: {ellipsoid: [1, 1, 1]}, front: "
              "\"#000000\", back: \"#000000\", core: " +
              c.core);
        },
        c.field, c.rule, c.core);
  }
}

}  // namespace
}  // namespace cutaway
