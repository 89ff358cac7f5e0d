// Properties of built DS models over every shipped template (templates/) and the fixtures in
// tests/data/: closed, oriented, outward skins; closed outward `within` components inside their
// folds; N-fold rotational symmetry; surfaces of revolution; everything inside the skin (by an
// independent ray-parity test); DS attributes in range; bounds that match the profile.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <numeric>
#include <unordered_map>

#include <glm/geometric.hpp>

#include "base/constants.h"
#include "io/template_parser.h"
#include "model/curves.h"
#include "model/mesh_surface.h"
#include "model/model_builder.h"
#include "model/template_checks.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// A built template (test::built_template: shared with the sweep's other tests in this
/// process), with what these properties need besides.
struct Built {
  const Template& tmpl;
  const DsModel& model;
  /// The model in the sweep's frame: `model` itself, or for a template with a spine the model
  /// built without it (the fold and profile rules hold there; the bend keeps them).
  DsModel straight;
  /// model.surfaces[i] was made from tmpl.surfaces[spec_of[i]] (build_model: skin first).
  std::vector<int> spec_of;
};

const Built& built(const fs::path& file) {
  static std::map<std::string, std::unique_ptr<Built>> cache;
  auto& slot = cache[file.string()];
  if (!slot) {
    const test::BuiltTemplate& shared = test::built_template(file);
    Template straight = shared.tmpl;
    straight.spine = {};
    slot = std::make_unique<Built>(
        Built{shared.tmpl,
              shared.model,
              shared.tmpl.spine.points.empty() ? shared.model : build_model(straight),
              {}});
    slot->spec_of.push_back(slot->tmpl.skin);
    for (int i = 0; i < static_cast<int>(slot->tmpl.surfaces.size()); ++i)
      if (i != slot->tmpl.skin) slot->spec_of.push_back(i);
  }
  return *slot;
}

std::vector<std::array<glm::dvec3, 3>> triangles(const DsMesh& mesh) {
  std::vector<std::array<glm::dvec3, 3>> out;
  out.reserve(mesh.n_faces());
  for (auto fh : mesh.faces()) {
    std::array<glm::dvec3, 3> t;
    int k = 0;
    for (auto vh : mesh.fv_range(fh)) t[k++] = to_glm(mesh.point(vh));
    out.push_back(t);
  }
  return out;
}

double signed_volume(const std::vector<std::array<glm::dvec3, 3>>& tris) {
  double v = 0;
  for (const auto& t : tris) v += glm::dot(t[0], glm::cross(t[1], t[2])) / 6.0;
  return v;
}

/// Point-in-closed-mesh by ray parity (Moller-Trumbore), majority of three generic directions;
/// triangles binned by height so that nearly horizontal rays test few of them.
class InsideTest {
 public:
  explicit InsideTest(const DsMesh& mesh) : tris_(triangles(mesh)), stamp_(tris_.size(), 0) {
    lo_ = glm::dvec3(1e300);
    hi_ = glm::dvec3(-1e300);
    for (const auto& t : tris_)
      for (const auto& p : t) {
        lo_ = glm::min(lo_, p);
        hi_ = glm::max(hi_, p);
      }
    bins_.resize(kBins);
    for (size_t i = 0; i < tris_.size(); ++i) {
      const auto& t = tris_[i];
      const double y0 = std::min({t[0].y, t[1].y, t[2].y}), y1 = std::max({t[0].y, t[1].y, t[2].y});
      for (int b = bin(y0); b <= bin(y1); ++b) bins_[b].push_back(i);
    }
  }

  bool inside(const glm::dvec3& p) {
    if (glm::any(glm::lessThan(p, lo_)) || glm::any(glm::greaterThan(p, hi_))) return false;
    static const std::array<glm::dvec3, 3> dirs{
        glm::normalize(glm::dvec3(0.8017, 0.0131, 0.5977)),
        glm::normalize(glm::dvec3(-0.3109, -0.0173, 0.9504)),
        glm::normalize(glm::dvec3(-0.7331, 0.0157, -0.6801))};
    int votes = 0;
    for (const auto& d : dirs) votes += crossings(p, d) % 2;
    return votes >= 2;
  }

 private:
  static constexpr int kBins = 256;
  int bin(double y) const {
    const double h = hi_.y - lo_.y;
    return std::clamp(static_cast<int>((y - lo_.y) / (h > 0 ? h : 1) * kBins), 0, kBins - 1);
  }
  int crossings(const glm::dvec3& p, const glm::dvec3& d) {
    ++query_;
    const double reach = glm::distance(lo_, hi_);
    const double ya = p.y, yb = p.y + d.y * reach;
    int n = 0;
    for (int b = bin(std::min(ya, yb)); b <= bin(std::max(ya, yb)); ++b) {
      for (size_t i : bins_[b]) {
        if (stamp_[i] == query_) continue;
        stamp_[i] = query_;
        const auto& t = tris_[i];
        const glm::dvec3 e1 = t[1] - t[0], e2 = t[2] - t[0], q = glm::cross(d, e2);
        const double det = glm::dot(e1, q);
        if (std::abs(det) < 1e-300) continue;
        const glm::dvec3 s = p - t[0];
        const double u = glm::dot(s, q) / det;
        if (u < 0 || u > 1) continue;
        const glm::dvec3 r = glm::cross(s, e1);
        const double v = glm::dot(d, r) / det;
        if (v < 0 || u + v > 1) continue;
        if (glm::dot(e2, r) / det > 0) ++n;
      }
    }
    return n;
  }

  std::vector<std::array<glm::dvec3, 3>> tris_;
  std::vector<unsigned> stamp_;
  unsigned query_ = 0;
  glm::dvec3 lo_, hi_;
  std::vector<std::vector<size_t>> bins_;
};

/// Connected components of a mesh: for each component, its faces' vertex triples (indices),
/// ordered by their smallest vertex index.
std::vector<std::vector<int>> component_vertices(const DsMesh& mesh) {
  std::vector<int> parent(mesh.n_vertices());
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (auto eh : mesh.edges()) {
    const int a = find(mesh.from_vertex_handle(mesh.halfedge_handle(eh, 0)).idx());
    const int b = find(mesh.to_vertex_handle(mesh.halfedge_handle(eh, 0)).idx());
    parent[std::max(a, b)] = std::min(a, b);
  }
  std::map<int, std::vector<int>> groups;
  for (int v = 0; v < static_cast<int>(parent.size()); ++v) groups[find(v)].push_back(v);
  std::vector<std::vector<int>> out;
  for (auto& [root, vs] : groups) out.push_back(std::move(vs));
  return out;  // map keys are each component's smallest index: already in order
}

double wrap_angle(double a) {
  while (a > kPi) a -= 2 * kPi;
  while (a <= -kPi) a += 2 * kPi;
  return a;
}

/// Every template the properties are checked on: the shipped ones and the test fixtures.
std::vector<fs::path> property_templates() {
  std::vector<fs::path> out = test::shipped_templates();
  for (const auto& e : fs::directory_iterator(test::source_path("tests/data"))) {
    if (e.path().extension() == ".yaml") out.push_back(e.path());
  }
  std::sort(out.begin(), out.end());
  return out;
}

class ModelProperties : public ::testing::TestWithParam<fs::path> {};

TEST_P(ModelProperties, SkinIsAClosedOutwardOrientedManifold) {
  const Built& b = built(GetParam());
  ASSERT_FALSE(b.model.surfaces.empty());
  const DsSurface& skin = b.model.skin();
  EXPECT_EQ(skin.role, SurfaceRole::Skin);
  EXPECT_EQ(skin.name, b.tmpl.surfaces[b.tmpl.skin].name);
  const DsMesh& m = skin.mesh;
  for (auto h : m.halfedges()) ASSERT_FALSE(m.is_boundary(h)) << "boundary halfedge " << h.idx();
  for (auto e : m.edges()) {
    ASSERT_TRUE(m.face_handle(m.halfedge_handle(e, 0)).is_valid() &&
                m.face_handle(m.halfedge_handle(e, 1)).is_valid());
  }
  for (auto v : m.vertices()) ASSERT_TRUE(m.is_manifold(v)) << "non-manifold vertex " << v.idx();
  const auto tris = triangles(m);
  EXPECT_GT(signed_volume(tris), 0.0);

  // Just outside along a face normal is outside; just inside is inside.
  InsideTest inside(m);
  const double eps = 1e-3 * b.tmpl.edge_m;
  const size_t stride = std::max<size_t>(1, tris.size() / 150);
  int checked = 0;
  for (size_t i = 0; i < tris.size(); i += stride) {
    const auto& t = tris[i];
    const glm::dvec3 n = glm::cross(t[1] - t[0], t[2] - t[0]);
    if (glm::length(n) < 1e-6 * b.tmpl.edge_m * b.tmpl.edge_m) continue;  // sliver
    const glm::dvec3 c = (t[0] + t[1] + t[2]) / 3.0, u = glm::normalize(n);
    EXPECT_FALSE(inside.inside(c + eps * u)) << "face " << i << " points inwards";
    EXPECT_TRUE(inside.inside(c - eps * u)) << "face " << i << " points inwards";
    ++checked;
  }
  EXPECT_GT(checked, 0);
}

TEST_P(ModelProperties, WithinSurfacesAreClosedOutwardAndInsideTheirFolds) {
  const Built& b = built(GetParam());
  int within = 0;
  for (size_t s = 0; s < b.model.surfaces.size(); ++s) {
    const SurfaceSpec& spec = b.tmpl.surfaces[b.spec_of[s]];
    if (spec.kind != SurfaceKind::Within) continue;
    ++within;
    SCOPED_TRACE(spec.name);
    const DsMesh& m = b.straight.surfaces[s].mesh;
    for (auto h : m.halfedges()) ASSERT_FALSE(m.is_boundary(h));
    for (auto v : m.vertices()) ASSERT_TRUE(m.is_manifold(v));
    const auto comps = component_vertices(m);
    ASSERT_EQ(static_cast<int>(comps.size()), b.tmpl.folds);
    std::vector<int> comp_of(m.n_vertices());
    for (size_t k = 0; k < comps.size(); ++k)
      for (int v : comps[k]) comp_of[v] = static_cast<int>(k);
    std::vector<double> volume(comps.size(), 0.0);
    for (auto fh : m.faces()) {
      std::array<glm::dvec3, 3> t;
      int k = 0, c = -1;
      for (auto vh : m.fv_range(fh)) {
        t[k++] = to_glm(m.point(vh));
        c = comp_of[vh.idx()];
      }
      volume[c] += glm::dot(t[0], glm::cross(t[1], t[2])) / 6.0;
    }
    for (size_t k = 0; k < comps.size(); ++k) {
      EXPECT_GT(volume[k], 0.0) << "component " << k << " is inside out";
      const auto [lo, hi] = fold_span(b.tmpl, static_cast<int>(k));
      for (int v : comps[k]) {
        const glm::dvec3 p = to_glm(m.point(DsMesh::VertexHandle(v)));
        const double rel = wrap_angle(horizontal_angle({p.x, p.z}) - lo);
        ASSERT_GT(rel, 0.0) << "fold " << k << " vertex " << v;
        ASSERT_LT(rel, hi - lo) << "fold " << k << " vertex " << v;
      }
    }
  }
  if (within == 0) GTEST_SKIP() << "no 'within' surfaces";
}

TEST_P(ModelProperties, EverySurfaceLiesInsideTheSkin) {
  const Built& b = built(GetParam());
  InsideTest inside(b.model.skin().mesh);
  for (size_t s = 1; s < b.model.surfaces.size(); ++s) {
    const DsMesh& m = b.model.surfaces[s].mesh;
    const size_t stride = std::max<size_t>(1, m.n_vertices() / 4000);
    for (size_t i = 0; i < m.n_vertices(); i += stride) {
      const glm::dvec3 p = to_glm(m.point(DsMesh::VertexHandle(static_cast<int>(i))));
      ASSERT_TRUE(inside.inside(p)) << b.model.surfaces[s].name << " vertex " << i << " at (" << p.x
                                    << ", " << p.y << ", " << p.z << ")";
    }
  }
}

TEST_P(ModelProperties, DsAttributesAreInRange) {
  const Built& b = built(GetParam());
  for (const DsSurface& s : b.model.surfaces) {
    SCOPED_TRACE(s.name);
    const DsMesh& m = s.mesh;
    for (auto v : m.vertices()) {
      const auto& d = m.data(v);
      for (int k = 0; k < 3; ++k) {
        ASSERT_TRUE(std::isfinite(m.point(v)[k]));
        ASSERT_GE(d.front[k], 0.0);
        ASSERT_LE(d.front[k], 1.0);
        ASSERT_GE(d.back[k], 0.0);
        ASSERT_LE(d.back[k], 1.0);
      }
      ASSERT_GE(d.blur, 0.0);
      ASSERT_TRUE(std::isfinite(d.blur));
      for (int k = 0; k < 2; ++k) {
        ASSERT_GE(d.param[k], 0.0);
        ASSERT_LE(d.param[k], 1.0);
      }
    }
  }
  for (size_t s = 0; s < b.model.surfaces.size(); ++s) {
    const SurfaceSpec& spec = b.tmpl.surfaces[b.spec_of[s]];
    EXPECT_EQ(b.model.surfaces[s].name, spec.name);
    EXPECT_EQ(b.model.surfaces[s].visible_front, spec.visible_front);
    EXPECT_EQ(b.model.surfaces[s].visible_back, spec.visible_back);
  }
}

/// Radius (about the axis) of a fitted section loop where it crosses angle 0.
double radius_at_angle0(const Polyline2& loop) {
  for (size_t i = 0; i < loop.size(); ++i) {
    const glm::dvec2 a = loop[i], b = loop[(i + 1) % loop.size()];
    if ((a.y <= 0) != (b.y <= 0)) {
      const double s = a.y / (a.y - b.y);
      const double x = a.x + (b.x - a.x) * s;
      if (x > 0) return x;
    }
  }
  return 0;
}

TEST_P(ModelProperties, FaceCountAndBoundsMatchTheSkinProfile) {
  const Built& built_model = built(GetParam());
  // In the sweep's frame (a spine bends the model afterwards; its own test checks the bend).
  const Built b{built_model.tmpl, built_model.straight, built_model.straight, built_model.spec_of};
  EXPECT_GT(b.model.face_count(), 0u);
  size_t faces = 0;
  glm::dvec3 lo(1e300), hi(-1e300), skin_lo(1e300), skin_hi(-1e300);
  double skin_max_radius = 0;
  for (size_t s = 0; s < b.model.surfaces.size(); ++s) {
    const DsMesh& m = b.model.surfaces[s].mesh;
    EXPECT_GT(m.n_faces(), 0u) << b.model.surfaces[s].name;
    faces += m.n_faces();
    for (auto v : m.vertices()) {
      const glm::dvec3 p = to_glm(m.point(v));
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
      if (s == 0) {
        skin_lo = glm::min(skin_lo, p);
        skin_hi = glm::max(skin_hi, p);
        skin_max_radius = std::max(skin_max_radius, std::hypot(p.x, p.z));
      }
    }
  }
  EXPECT_EQ(b.model.face_count(), faces);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(b.model.bbox_min[k], lo[k]);
    EXPECT_EQ(b.model.bbox_max[k], hi[k]);
    // Everything is inside the skin, so the skin spans the model.
    EXPECT_EQ(skin_lo[k], lo[k]);
    EXPECT_EQ(skin_hi[k], hi[k]);
  }

  const SurfaceSpec& spec = b.tmpl.surfaces[b.tmpl.skin];
  const double tol = b.tmpl.edge_m;
  if (spec.kind == SurfaceKind::Mesh) {
    const MeshBounds mb = mesh_bounds(*spec.mesh, b.tmpl.metres_per_unit);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(skin_lo[k], mb.min[k], 1e-12);
      EXPECT_NEAR(skin_hi[k], mb.max[k], 1e-12);
    }
    return;
  }
  ASSERT_EQ(spec.kind, SurfaceKind::Around);
  // Heights: the profile's end points (on the axis) are the poles; the fitted curve between.
  const Polyline2 prof = fit_curve(spec.profile, false, spec.smooth);
  double y_lo = 1e300, y_hi = -1e300, r_max = 0;
  for (const auto& p : prof) {
    y_lo = std::min(y_lo, p.y);
    y_hi = std::max(y_hi, p.y);
    r_max = std::max(r_max, p.x);
  }
  EXPECT_NEAR(skin_lo.y, y_lo, tol);
  EXPECT_NEAR(skin_hi.y, y_hi, tol);
  EXPECT_GE(skin_lo.y, y_lo - 1e-12);
  EXPECT_LE(skin_hi.y, y_hi + 1e-12);
  // Widest radius: the profile's largest r times the section's largest radius over rho0. With
  // sections at several heights, at most the widest of them there (the profile's widest point
  // and the widest section may lie at different heights).
  std::vector<const SectionSpec*> sections{&spec.section};
  for (const HeightSection& h : spec.sections) sections.push_back(&h.section);
  double scale = 1;
  for (const SectionSpec* section : sections) {
    if (section->circle) continue;
    const Polyline2 loop = fit_curve(section->loops[0], true, spec.smooth);
    const double rho0 = radius_at_angle0(loop);
    ASSERT_GT(rho0, 0.0);
    double rho_max = 0;
    for (const auto& p : loop) rho_max = std::max(rho_max, glm::length(p));
    scale = std::max(scale, rho_max / rho0);
  }
  if (spec.sections.empty()) EXPECT_NEAR(skin_max_radius, r_max * scale, tol);
  EXPECT_LE(skin_max_radius, r_max * scale * (1 + 1e-9));
}

/// Whether a set of points maps onto itself under a rotation by `angle` about +Y.
::testing::AssertionResult rotation_invariant(const DsMesh& m, double angle, double tol) {
  const double cell = 1e-6;
  auto key = [&](const glm::dvec3& p) {
    return std::array<long long, 3>{std::llround(p.x / cell), std::llround(p.y / cell),
                                    std::llround(p.z / cell)};
  };
  struct Hash {
    size_t operator()(const std::array<long long, 3>& k) const {
      return static_cast<size_t>(k[0] * 73856093LL ^ k[1] * 19349663LL ^ k[2] * 83492791LL);
    }
  };
  std::unordered_map<std::array<long long, 3>, std::vector<glm::dvec3>, Hash> grid;
  for (auto v : m.vertices()) {
    const glm::dvec3 p = to_glm(m.point(v));
    grid[key(p)].push_back(p);
  }
  const double c = std::cos(angle), s = std::sin(angle);
  double worst = 0;
  for (auto v : m.vertices()) {
    const glm::dvec3 p = to_glm(m.point(v));
    // Angle grows from +X towards -Z.
    const glm::dvec3 q(p.x * c + p.z * s, p.y, p.z * c - p.x * s);
    const auto k = key(q);
    double best = 1e300;
    for (long long dx = -1; dx <= 1; ++dx)
      for (long long dy = -1; dy <= 1; ++dy)
        for (long long dz = -1; dz <= 1; ++dz) {
          auto it = grid.find({k[0] + dx, k[1] + dy, k[2] + dz});
          if (it == grid.end()) continue;
          for (const auto& r : it->second) best = std::min(best, glm::distance(q, r));
        }
    worst = std::max(worst, best);
    if (best > tol) {
      return ::testing::AssertionFailure()
             << "vertex " << v.idx() << " rotated has no counterpart (nearest " << best << " m)";
    }
  }
  return ::testing::AssertionSuccess() << "worst " << worst;
}

/// Whether a loop's points map onto themselves under a rotation by `angle`.
bool loop_symmetric(const Polyline2& loop, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  double size = 0;
  for (const auto& p : loop) size = std::max(size, glm::length(p));
  for (const auto& p : loop) {
    // [x, z] at angle a: (r cos a, -r sin a); turning by `angle`.
    const glm::dvec2 q(p.x * c + p.y * s, p.y * c - p.x * s);
    bool found = false;
    for (const auto& r : loop) found = found || glm::distance(q, r) < 1e-9 * size;
    if (!found) return false;
  }
  return true;
}

TEST_P(ModelProperties, NFoldModelWithIdenticalFoldsMapsOntoItself) {
  const Built& b = built(GetParam());
  const Template& t = b.tmpl;
  if (t.symmetry != Symmetry::NFold) GTEST_SKIP() << "not an N-fold template";
  const double step = 2 * kPi / t.folds;
  for (int k = 0; k < t.folds; ++k) {
    if (std::abs(wrap_angle(t.fold_angles[k] - (t.fold_angles[0] + k * step))) > 1e-12)
      GTEST_SKIP() << "fold angles are not uniform";
  }
  for (const auto& s : t.surfaces) {
    if (s.kind == SurfaceKind::Mesh) GTEST_SKIP() << "has a mesh surface";
    if (s.kind == SurfaceKind::Within && s.section.loops.size() != 1)
      GTEST_SKIP() << "folds have different loops";
    if (s.kind == SurfaceKind::Around && !s.section.circle &&
        !loop_symmetric(s.section.loops[0], step))
      GTEST_SKIP() << "section of '" << s.name << "' is not N-fold symmetric";
  }
  for (const DsSurface& s : b.straight.surfaces) {
    EXPECT_TRUE(rotation_invariant(s.mesh, step, 1e-9)) << s.name;
  }
}

TEST_P(ModelProperties, CircleSectionsGiveSurfacesOfRevolution) {
  const Built& b = built(GetParam());
  int circles = 0;
  for (size_t s = 0; s < b.model.surfaces.size(); ++s) {
    const SurfaceSpec& spec = b.tmpl.surfaces[b.spec_of[s]];
    if (spec.kind != SurfaceKind::Around || !spec.section.circle) continue;
    ++circles;
    std::map<double, std::vector<double>> rings;  // exact height -> radii
    const DsMesh& m = b.straight.surfaces[s].mesh;
    for (auto v : m.vertices()) {
      const auto& p = m.point(v);
      rings[p[1]].push_back(std::hypot(p[0], p[2]));
    }
    for (const auto& [y, radii] : rings) {
      const double mean = std::accumulate(radii.begin(), radii.end(), 0.0) / radii.size();
      for (double r : radii) ASSERT_NEAR(r, mean, 1e-9) << spec.name << " at y = " << y;
    }
    // Rings sit at the profile samples: far fewer rings than vertices.
    EXPECT_LT(rings.size() * 4, m.n_vertices()) << spec.name;
  }
  if (circles == 0) GTEST_SKIP() << "no circle sections";
}

// Named by the template's stem as the other sweeps are (tests/CMakeLists.txt runs each shipped
// template's sweep in one process); the test data's templates after "data_".
std::string property_test_name(const ::testing::TestParamInfo<fs::path>& info) {
  const bool shipped = info.param.parent_path().filename() == "templates";
  return (shipped ? "" : "data_") + test::template_test_name(info.param);
}

INSTANTIATE_TEST_SUITE_P(Templates, ModelProperties, ::testing::ValuesIn(property_templates()),
                         property_test_name);

}  // namespace
}  // namespace cutaway
