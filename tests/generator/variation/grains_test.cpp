// Grains (generator/variation/grains.h) on the tomato's and the cucumber's chambers.
#include "variation/grains.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

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
  for (const char* name : {"templates/tomato.yaml", "templates/cucumber.yaml"}) {
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

}  // namespace
}  // namespace cutaway
