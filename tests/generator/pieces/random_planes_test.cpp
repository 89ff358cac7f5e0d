// Random cuts of every shipped template, as a batch of seeded variants meets them: planes through
// the bounding box at random, planes through a vertex of each surface with a random normal
// (nearly tangent to it), planes at the extremes of each surface's bounding box (touching its
// poles and tips), and the same on a seeded variant, grains included. Every cut must end in a
// cross-section whose boundary is closed and runs along the skin and the hollows' walls only
// (never round a grain) and whose colours are finite, or in the clean "misses" / "only
// touches" error; never a crash, a hang or another error.
//
// `make test` cuts kPlanesPerTemplate planes per template. CUTAWAY_RANDOM_PLANES=N (set by
// `make fuzz`) cuts N per template instead, with a seed offset CUTAWAY_RANDOM_PLANES_SEED.
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <exception>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "base/random.h"
#include "diffusion/diffusion.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "section/cross_section.h"
#include "section/cut_segments.h"
#include "test_support.h"
#include "variation/variation.h"

namespace cutaway {
namespace {

constexpr int kPlanesPerTemplate = 24;

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::atoi(v) : fallback;
}

/// The i-th plane of the stream: cycles through the kinds of cut.
Plane random_plane(const DsModel& model, Rng& rng, int i) {
  Plane p;
  const int kind = i % 4;
  const DsSurface& surface =
      model.surfaces[rng.below(static_cast<uint32_t>(model.surfaces.size()))];
  const DsMesh& mesh = surface.mesh;
  if (kind == 0) {  // anywhere through the bounding box
    for (int k = 0; k < 3; ++k) p.point[k] = rng.uniform(model.bbox_min[k], model.bbox_max[k]);
    p.normal = random_direction(rng);
  } else if (kind == 1) {  // through a vertex of a surface: nearly tangent to it there
    const auto vh =
        mesh.vertex_handle(static_cast<int>(rng.below(static_cast<uint32_t>(mesh.n_vertices()))));
    const auto& q = mesh.point(vh);
    p.point = {q[0], q[1], q[2]};
    p.normal = random_direction(rng);
  } else {  // at an extreme of the surface's bounding box along an axis, or just inside it
    const int axis = static_cast<int>(rng.below(static_cast<uint32_t>(3)));
    double lo = INFINITY, hi = -INFINITY;
    for (auto vh : mesh.vertices()) {
      lo = std::min(lo, mesh.point(vh)[axis]);
      hi = std::max(hi, mesh.point(vh)[axis]);
    }
    const double inset[] = {0.0, 1e-12, 1e-9, 1e-6, 1e-4};
    const double d = inset[rng.below(static_cast<uint32_t>(5))];
    p.point = glm::dvec3(0.0);
    p.point[axis] = kind == 2 ? hi - d : lo + d;
    p.normal = glm::dvec3(0.0);
    p.normal[axis] = 1;
    if (rng.uniform() < 0.5) {  // tilted a hair
      p.normal += 1e-7 * random_direction(rng);
      p.normal = glm::normalize(p.normal);
    }
  }
  return p;
}

/// Boundary edges (used by one triangle) welded by exact position: every welded vertex must
/// have as many boundary edges leaving it as entering it, so the boundary is closed loops.
::testing::AssertionResult closed_boundary(const CrossSection& cs) {
  std::map<std::tuple<double, double, double>, int> id;
  auto weld = [&](unsigned v) {
    const glm::dvec3& p = cs.position[v];
    return id.emplace(std::make_tuple(p.x, p.y, p.z), static_cast<int>(id.size())).first->second;
  };
  std::map<std::pair<int, int>, int> directed;
  for (const glm::uvec3& t : cs.triangle)
    for (int k = 0; k < 3; ++k) ++directed[{weld(t[k]), weld(t[(k + 1) % 3])}];
  std::map<int, int> balance;
  for (const auto& [e, n] : directed) {
    const auto twin = directed.find({e.second, e.first});
    const int open = n - (twin == directed.end() ? 0 : twin->second);
    if (open > 0) {
      balance[e.first] += open;
      balance[e.second] -= open;
    }
  }
  for (const auto& [v, b] : balance)
    if (b != 0) return ::testing::AssertionFailure() << "boundary vertex " << v << " is open";
  return ::testing::AssertionSuccess();
}

/// Whether a surface bounds the cut face: the skin and the walls of hollows (a side hidden).
bool bounds_face(const DsSurface& surface) {
  return surface.role == SurfaceRole::Skin || !surface.visible_front || !surface.visible_back;
}

/// Every boundary edge of the cut face (used by one triangle, welded by exact position) has
/// both ends within a thousandth of an edge (`edge_m`) of a cut segment of the skin or of a
/// hollow's wall, merged as make_cross_section merges them: a grain, seen on both sides,
/// colours the face but never bounds it, so that no loop of a grain in a hollow or outside
/// the skin is left as an island that no clipped skin or wall meets.
::testing::AssertionResult bounded_by_skin_and_walls(const DsModel& model, const CrossSection& cs,
                                                     double edge_m) {
  std::vector<CutSegment> cut;
  for (const CutSegment& s : cut_segments(model, cs.plane))
    if (bounds_face(model.surfaces[static_cast<size_t>(s.surface)])) cut.push_back(s);
  const CrossSectionOptions options{edge_m};
  const std::vector<CutSegment> bounding =
      merge_collinear_segments(cut, options.merge_tolerance * edge_m, edge_m);
  auto on_bounding = [&](const glm::dvec3& p) {
    for (const CutSegment& s : bounding) {
      const glm::dvec3 d = s.b - s.a;
      const double t = std::clamp(glm::dot(p - s.a, d) / glm::dot(d, d), 0.0, 1.0);
      if (glm::distance(p, s.a + t * d) <= 1e-3 * edge_m) return true;
    }
    return false;
  };
  using Point = std::tuple<double, double, double>;
  auto point = [&](unsigned v) {
    const glm::dvec3& p = cs.position[v];
    return Point(p.x, p.y, p.z);
  };
  std::map<std::pair<Point, Point>, int> uses;  // undirected edges, welded
  for (const glm::uvec3& t : cs.triangle)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(point(t[k]), point(t[(k + 1) % 3]))];
  size_t off = 0;
  for (const auto& [edge, n] : uses) {
    if (n != 1) continue;
    for (const Point& p : {edge.first, edge.second})
      off += !on_bounding({std::get<0>(p), std::get<1>(p), std::get<2>(p)});
  }
  if (off > 0)
    return ::testing::AssertionFailure()
           << off << " ends of boundary edges lie on no segment of the skin or a wall";
  return ::testing::AssertionSuccess();
}

/// Cuts `model` with `count` planes of the stream `seed`; returns how many gave sections.
int cut_many(const DsModel& model, double edge_m, const std::string& what, uint64_t seed,
             int count) {
  const auto diffusion = make_cpu_diffusion(model, DiffusionOptions{4, 0});
  Rng rng(seed);
  int sections = 0;
  for (int i = 0; i < count; ++i) {
    const Plane plane = random_plane(model, rng, i);
    SCOPED_TRACE(what + " plane " + std::to_string(i) + ": point (" +
                 std::to_string(plane.point.x) + ", " + std::to_string(plane.point.y) + ", " +
                 std::to_string(plane.point.z) + ") normal (" + std::to_string(plane.normal.x) +
                 ", " + std::to_string(plane.normal.y) + ", " + std::to_string(plane.normal.z) +
                 ")");
    Outcome<CrossSection> made = Outcome<CrossSection>::none("not made");
    try {
      made = make_cross_section(model, plane, *diffusion, {edge_m});
    } catch (const std::exception& e) {
      ADD_FAILURE() << "unexpected error: " << e.what();
      continue;
    }
    if (!made) {
      EXPECT_TRUE(made.reason() == kPlaneMisses || made.reason() == kPlaneOnlyTouches)
          << made.reason();
      continue;
    }
    const CrossSection& cs = *made;
    ++sections;
    EXPECT_FALSE(cs.triangle.empty());
    for (const glm::dvec3& c : cs.colour)
      EXPECT_TRUE(std::isfinite(c.x) && std::isfinite(c.y) && std::isfinite(c.z));
    for (const glm::dvec3& p : cs.position)
      EXPECT_TRUE(std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z));
    EXPECT_TRUE(closed_boundary(cs));
    EXPECT_TRUE(bounded_by_skin_and_walls(model, cs, edge_m));
  }
  return sections;
}

class RandomPlanes : public ::testing::TestWithParam<std::filesystem::path> {};

TEST_P(RandomPlanes, CutOrMissCleanly) {
  const int count = env_int("CUTAWAY_RANDOM_PLANES", kPlanesPerTemplate);
  const uint64_t offset = static_cast<uint64_t>(env_int("CUTAWAY_RANDOM_PLANES_SEED", 0));
  const test::BuiltTemplate& built = test::built_template(GetParam());
  const Template& t = built.tmpl;
  const DsModel& model = built.model;
  const int a =
      cut_many(model, t.edge_m, t.name, derive_seed(offset, {1, model.face_count()}), count);
  // A seeded variant, grains included, as a batch of variants makes them.
  const Variant v = make_variant(t, 1000 + offset);
  const int b =
      cut_many(v.model, v.tmpl.edge_m, t.name + " variant", derive_seed(offset, {2}), count / 2);
  // Random planes are no use if most of them miss: at least a quarter must cut.
  EXPECT_GE(a + b, (count + count / 2) / 4) << "sections: " << a << " + " << b;
}

INSTANTIATE_TEST_SUITE_P(Templates, RandomPlanes, ::testing::ValuesIn(test::shipped_templates()),
                         [](const auto& info) { return test::template_test_name(info.param); });

}  // namespace
}  // namespace cutaway
