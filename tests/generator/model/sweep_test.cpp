// Type I and Type II sweeps (generator/model/sweep.h, doc/algorithms.md §1) on tiny hand-made
// templates whose answers are known exactly: polyline profiles (smooth: false) with straight
// rails, square and diamond sections.
#include "base/constants.h"
#include "model/sweep.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include <glm/geometric.hpp>

#include "base/colour.h"
#include "io/template_parser.h"
#include "model/template_checks.h"

namespace cutaway {
namespace {

Template parse(const std::string& text) { return parse_template(text, "sweep_test.yaml", "."); }

const SurfaceSpec& surface(const Template& t, const std::string& name) {
  for (const auto& s : t.surfaces)
    if (s.name == name) return s;
  throw std::runtime_error("no surface " + name);
}

glm::dvec3 point(const DsMesh& m, DsMesh::VertexHandle v) {
  const auto& p = m.point(v);
  return {p[0], p[1], p[2]};
}

int boundary_halfedges(const DsMesh& m) {
  int n = 0;
  for (auto h : m.halfedges()) n += m.is_boundary(h);
  return n;
}

/// A cylinder of radius 10 mm and height 20 mm with flat caps: profile length 40 mm, so the
/// normalised profile parameter t maps to r and y exactly.
std::string cylinder(const std::string& symmetry, const std::string& edge,
                     const std::string& section = "circle", const std::string& extra = "") {
  return "format: cutaway-template/1\nname: cyl\nunits: mm\nsymmetry: " + symmetry +
         "\nresolution: {edge: " + edge +
         "}\nsurfaces:\n"
         "  - name: skin\n    kind: around\n    role: skin\n    smooth: false\n"
         "    profile: [[0, 0], [10, 0], [10, 20], [0, 20]]\n    section: " +
         section + "\n" + extra;
}

/// (r, y) in metres of the cylinder profile at normalised arc length t.
glm::dvec2 cylinder_profile(double t) {
  const double s = 40 * t;
  if (s <= 10) return {s * 1e-3, 0};
  if (s <= 30) return {10e-3, (s - 10) * 1e-3};
  return {(40 - s) * 1e-3, 20e-3};
}

TEST(SweepAround, VertexCountsFollowTheEdgeLength) {
  for (double edge : {0.9, 1.7, 2.4}) {
    const std::string e = std::to_string(edge);
    const Template t = parse(cylinder("{type: cylindrical}", e));
    const DsSurface s = sweep_around(t.surfaces[0], t);
    const int n = static_cast<int>(std::ceil(40 / edge));
    const int m = std::max(8, static_cast<int>(std::ceil(10 * 2 * kPi / edge)));
    EXPECT_EQ(s.mesh.n_vertices(), static_cast<size_t>((n - 1) * m + 2)) << "edge " << edge;
    EXPECT_EQ(s.mesh.n_faces(), static_cast<size_t>(2 * m * (n - 1))) << "edge " << edge;
    // N-fold: the section count is rounded up to a multiple of N.
    const Template t5 = parse(cylinder("{type: nfold, folds: 5}", e));
    const DsSurface s5 = sweep_around(t5.surfaces[0], t5);
    const int m5 = (m + 4) / 5 * 5;
    EXPECT_EQ(s5.mesh.n_vertices(), static_cast<size_t>((n - 1) * m5 + 2)) << "edge " << edge;
  }
  // 2.5 mm is the coarsest edge, an eighth of the 20 mm height; a coarser one is refused (its
  // meshes would no longer follow the curves closely enough to cut).
  EXPECT_THROW(parse(cylinder("{type: cylindrical}", "2.51")), InputError);
}

TEST(SweepAround, PolesMakeWatertightFans) {
  const Template t = parse(cylinder("{type: cylindrical}", "1.7"));
  const DsSurface s = sweep_around(t.surfaces[0], t);
  const DsMesh& m = s.mesh;
  EXPECT_EQ(boundary_halfedges(m), 0);
  for (auto v : m.vertices()) ASSERT_TRUE(m.is_manifold(v));
  EXPECT_EQ(static_cast<long>(m.n_vertices()) - static_cast<long>(m.n_edges()) +
                static_cast<long>(m.n_faces()),
            2);  // a sphere
  const int ring = static_cast<int>(std::ceil(10 * 2 * kPi / 1.7));
  int poles = 0;
  for (auto v : m.vertices()) {
    const glm::dvec3 p = point(m, v);
    if (std::hypot(p.x, p.z) == 0) {
      ++poles;
      EXPECT_EQ(static_cast<int>(m.valence(v)), ring);
      // Outward: the fan's normals point down at the bottom pole, up at the top one.
      for (auto f : m.vf_range(v)) {
        const auto n = m.calc_face_normal(f);
        EXPECT_GT(n[1] * (p.y > 0.01 ? 1 : -1), 0.99);
      }
    }
  }
  EXPECT_EQ(poles, 2);
}

TEST(SweepAround, OpenProfilesLeaveRingsOpenAndNormalsPointAwayFromTheAxis) {
  const std::string extra = "  - name: shell\n    kind: around\n    smooth: false\n"
                            "    profile: [[4, 2], [8, 10], [4, 18]]\n"
                            "  - name: cup\n    kind: around\n    smooth: false\n"
                            "    profile: [[0, 3], [5, 5], [6, 9]]\n";
  const Template t = parse(cylinder("{type: cylindrical}", "0.8", "circle", extra));
  const DsSurface shell = sweep_around(surface(t, "shell"), t);
  const DsSurface cup = sweep_around(surface(t, "cup"), t);
  auto ring_size = [](const DsSurface& s) {
    int n = 0;
    for (auto v : s.mesh.vertices()) n += s.mesh.data(v).param[0] == 1.0;
    return n;
  };
  EXPECT_GE(ring_size(shell), 8);
  EXPECT_EQ(boundary_halfedges(shell.mesh), 2 * ring_size(shell));  // two open rings
  EXPECT_EQ(boundary_halfedges(cup.mesh), ring_size(cup));          // one pole, one open ring
  for (auto v : cup.mesh.vertices()) EXPECT_TRUE(cup.mesh.is_manifold(v));
  for (const DsSurface* s : {&shell, &cup}) {
    for (auto f : s->mesh.faces()) {
      const auto n = s->mesh.calc_face_normal(f);
      const auto c = s->mesh.calc_face_centroid(f);
      EXPECT_GT(n[0] * c[0] + n[2] * c[2], 0) << s->name << " face " << f.idx();
    }
  }
}

// A leaf that covers a third of the way round: every vertex lies in its span, the two side
// edges and the two end rings are its only boundary, its normals point away from the axis, and
// the section parameter runs 0..1 across the span. A pole closes one end as a fan.
TEST(SweepAround, ASpanCoversPartOfTheWayRound) {
  const std::string extra = "  - name: leaf\n    kind: around\n    smooth: false\n"
                            "    span: [30, 150]\n    section: {polar: [[0, 1], [90, 1.2], "
                            "[180, 1], [270, 1.2]]}\n"
                            "    profile: [[4, 2], [8, 10], [4, 18]]\n"
                            "  - name: cup\n    kind: around\n    smooth: false\n"
                            "    span: [-60, 60]\n    profile: [[0, 3], [5, 5], [6, 9]]\n";
  const Template t = parse(cylinder("{type: nfold, folds: 4}", "0.8", "circle", extra));
  check_template_curves(t);
  const DsSurface leaf = sweep_around(surface(t, "leaf"), t);
  const DsSurface cup = sweep_around(surface(t, "cup"), t);
  int rows = 0, cols = 0;
  for (auto v : leaf.mesh.vertices()) {
    const glm::dvec3 p = point(leaf.mesh, v);
    const double deg = horizontal_angle({p.x, p.z}) * 180 / kPi;
    const double ts = leaf.mesh.data(v).param[1];
    ASSERT_NEAR(deg, 30 + 120 * ts, 1e-9);
    rows += ts == 0;
    cols += leaf.mesh.data(v).param[0] == 0;
  }
  EXPECT_GE(cols, 5);
  EXPECT_EQ(boundary_halfedges(leaf.mesh), 2 * (rows - 1) + 2 * (cols - 1));
  for (const DsSurface* s : {&leaf, &cup}) {
    for (auto v : s->mesh.vertices()) ASSERT_TRUE(s->mesh.is_manifold(v)) << s->name;
    for (auto f : s->mesh.faces()) {
      const auto n = s->mesh.calc_face_normal(f);
      const auto c = s->mesh.calc_face_centroid(f);
      EXPECT_GT(n[0] * c[0] + n[2] * c[2], 0) << s->name << " face " << f.idx();
    }
  }
  int cup_rows = 0, cup_cols = 0;
  for (auto v : cup.mesh.vertices()) {
    const auto& d = cup.mesh.data(v);
    cup_rows += d.param[1] == 0;
    cup_cols += d.param[0] == 1;
  }
  // The pole, the rings' two sides and the open top ring.
  EXPECT_EQ(boundary_halfedges(cup.mesh), 2 * (cup_rows - 1) + (cup_cols - 1));
}

TEST(SweepAround, ASpanFollowsItsRules) {
  auto error = [](const std::string& extra) -> std::string {
    try {
      parse(cylinder("{type: cylindrical}", "1", "circle", extra));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  const std::string inner =
      "  - name: leaf\n    kind: around\n    profile: [[4, 2], [8, 10], [4, 18]]\n";
  EXPECT_NE(error(inner + "    span: [150, 30]\n").find("span: 'to' must lie above 'from'"),
            std::string::npos);
  EXPECT_NE(error(inner + "    span: [0, 360]\n").find("less than a whole turn"),
            std::string::npos);
  EXPECT_NE(error(inner + "    span: [0, 90]\n    rigid: true\n")
                .find("rigid: a rigid surface is closed"),
            std::string::npos);
  std::string skin = cylinder("{type: cylindrical}", "1", "circle");
  skin.replace(skin.find("    section: circle"), 0, "    span: [0, 90]\n");
  try {
    parse(skin);
    ADD_FAILURE() << "a skin with a span was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("span: the skin is closed"), std::string::npos)
        << e.what();
  }
}

TEST(SweepAround, SectionRadiusAtAngleZeroEqualsTheProfileRadius) {
  // A rhombus-like polar loop: radius 2 at angle 0 (the loop's scale does not matter).
  const Template t = parse(
      cylinder("{type: cylindrical}", "0.7", "{polar: [[0, 2], [90, 3], [180, 2], [270, 3]]}"));
  const DsSurface s = sweep_around(t.surfaces[0], t);
  int rows = 0;
  for (auto v : s.mesh.vertices()) {
    const auto& d = s.mesh.data(v);
    if (d.param[1] != 0) continue;
    ++rows;
    const glm::dvec3 p = point(s.mesh, v);
    const glm::dvec2 rp = cylinder_profile(d.param[0]);
    EXPECT_NEAR(p.x, rp.x, 1e-12) << "t = " << d.param[0];
    EXPECT_NEAR(p.y, rp.y, 1e-12) << "t = " << d.param[0];
    EXPECT_NEAR(p.z, 0, 1e-12);
  }
  EXPECT_EQ(rows, static_cast<int>(std::ceil(40 / 0.7)) + 1);
}

TEST(SweepAround, APolarSquareKeepsItsShape) {
  // Corners at 45, 135, ... degrees, radius sqrt(2): a square of half side 1; its radius at
  // angle 0 is 1, so at the cylinder's side every ring is a square of half side 10 mm.
  const std::string sq = "{polar: [[45, 1.4142135623730951], [135, 1.4142135623730951], "
                         "[225, 1.4142135623730951], [315, 1.4142135623730951]]}";
  const Template t = parse(cylinder("{type: nfold, folds: 4}", "1.3", sq));
  const DsSurface s = sweep_around(t.surfaces[0], t);
  int side = 0, corners = 0;
  for (auto v : s.mesh.vertices()) {
    const glm::dvec3 p = point(s.mesh, v);
    const double r = cylinder_profile(s.mesh.data(v).param[0]).x;
    ASSERT_NEAR(std::max(std::abs(p.x), std::abs(p.z)), r, 1e-12);
    if (p.y > 0 && p.y < 20e-3) {
      ++side;
      corners += std::abs(std::abs(p.x) - 10e-3) < 1e-12 && std::abs(std::abs(p.z) - 10e-3) < 1e-12;
    }
  }
  EXPECT_GT(side, 0);
  EXPECT_EQ(corners % 4, 0);
  EXPECT_GT(corners, 0);  // 4-fold: the section count is a multiple of 4, so corners are samples
}

/// The cylinder with `sections` (a YAML flow list) instead of one section.
std::string cylinder_with_sections(const std::string& symmetry, const std::string& sections) {
  std::string text = cylinder(symmetry, "1.3");
  text.replace(text.find("    section: circle\n"), 20, "    sections: " + sections + "\n");
  return text;
}

// Sections at two heights: a circle up to a quarter of the profile, a square from three
// quarters, and between them every ring lies between the two (blended radius by radius).
TEST(SweepAround, SectionsAtSeveralHeightsBlendFromOneToTheNext) {
  const std::string sq = "{polar: [[45, 1.4142135623730951], [135, 1.4142135623730951], "
                         "[225, 1.4142135623730951], [315, 1.4142135623730951]]}";
  const Template t = parse(cylinder_with_sections(
      "{type: cylindrical}", "[{at: 0.25, section: circle}, {at: 0.75, section: " + sq + "}]"));
  ASSERT_EQ(t.surfaces[0].sections.size(), 2u);
  const DsSurface s = sweep_around(t.surfaces[0], t);
  int circles = 0, squares = 0, between = 0;
  for (auto v : s.mesh.vertices()) {
    const glm::dvec3 p = point(s.mesh, v);
    const double tp = s.mesh.data(v).param[0];
    const double r = cylinder_profile(tp).x;
    if (r == 0) continue;
    const double round = std::hypot(p.x, p.z), square = std::max(std::abs(p.x), std::abs(p.z));
    if (tp <= 0.25) {
      ASSERT_NEAR(round, r, 1e-9) << tp;
      ++circles;
    } else if (tp >= 0.75) {
      ASSERT_NEAR(square, r, 1e-9) << tp;
      ++squares;
    } else {
      ASSERT_LE(square, r + 1e-9) << tp;
      ASSERT_GE(round, r - 1e-9) << tp;
      ++between;
    }
  }
  EXPECT_GT(circles, 0);
  EXPECT_GT(squares, 0);
  EXPECT_GT(between, 0);
}

// In an N-fold template too: the rings keep a multiple of N samples, so the blended surface
// maps onto itself under a turn by one fold.
TEST(SweepAround, SectionsAtSeveralHeightsInAnNFoldTemplateKeepItsFolds) {
  const std::string sq = "{polar: [[45, 1.4142135623730951], [135, 1.4142135623730951], "
                         "[225, 1.4142135623730951], [315, 1.4142135623730951]]}";
  const Template t = parse(cylinder_with_sections(
      "{type: nfold, folds: 4}", "[{at: 0.25, section: circle}, {at: 0.75, section: " + sq + "}]"));
  check_template_curves(t);
  const DsSurface s = sweep_around(t.surfaces[0], t);
  std::vector<glm::dvec3> points;
  for (auto v : s.mesh.vertices()) points.push_back(point(s.mesh, v));
  auto key = [](const glm::dvec3& p) {
    return std::tuple<long, long, long>(std::lround(p.x * 1e8), std::lround(p.y * 1e8),
                                        std::lround(p.z * 1e8));
  };
  std::set<std::tuple<long, long, long>> keys;
  for (const auto& p : points) keys.insert(key(p));
  int squares = 0;
  for (const auto& p : points) {
    // A turn by 90 degrees about +Y: (x, z) -> (z, -x).
    ASSERT_TRUE(keys.count(key({p.z, p.y, -p.x}))) << p.x << " " << p.y << " " << p.z;
    squares += p.y > 0.016 && p.y < 0.02 &&
               std::abs(std::max(std::abs(p.x), std::abs(p.z)) - 10e-3) < 1e-9;
  }
  EXPECT_GT(squares, 0);
}

TEST(SweepAround, SectionsAtHeightsFollowTheirRules) {
  auto error = [](const std::string& text) -> std::string {
    try {
      check_template_curves(parse(text));
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(error(cylinder_with_sections("{type: cylindrical}",
                                         "[{at: 0.5, section: circle}, {at: 0.5, section: "
                                         "circle}]"))
                .find("sections[1].at: the heights 'at' must increase"),
            std::string::npos);
  EXPECT_NE(error(cylinder_with_sections("{type: nfold, folds: 4}",
                                         "[{at: 0, section: circle}, {at: 1, section: "
                                         "[[1, 0], [0, 1], [-1, 0], [0, -1]]}, {at: 0.5, "
                                         "section: circle}]"))
                .find("sections[2].at: the heights 'at' must increase"),
            std::string::npos);
  EXPECT_NE(error(cylinder_with_sections("{type: cylindrical}", "[{at: 0, section: circle}]"))
                .find("at least two"),
            std::string::npos);
  // Each loop is held to the rules of a single section, at its own field.
  EXPECT_NE(error(cylinder_with_sections(
                      "{type: cylindrical}",
                      "[{at: 0, section: circle}, {at: 1, section: [[1, 1], [2, 1], [2, 2]]}]"))
                .find("sections[1].section: an 'around' section loop must surround the axis"),
            std::string::npos);
}

TEST(SweepAround, GradientsFollowTheSweepParameters) {
  const std::string extra =
      "    front: {along: profile, stops: [[0, \"#000000\"], [1, \"#ffffff\"]]}\n"
      "    back: {along: section, stops: [[0, [0, 0, 0]], [0.5, [1, 0, 0]], [1, [0, 0, 0]]]}\n"
      "    blur: {along: profile, stops: [[0, 0], [0.5, 2], [1, 0]]}\n"
      "    visible: {front: false}\n";
  const Template t = parse(cylinder("{type: cylindrical}", "1.1", "circle", extra));
  const DsSurface s = sweep_around(t.surfaces[0], t);
  EXPECT_FALSE(s.visible_front);
  EXPECT_TRUE(s.visible_back);
  EXPECT_EQ(s.role, SurfaceRole::Skin);
  EXPECT_EQ(s.name, "skin");
  for (auto v : s.mesh.vertices()) {
    const auto& d = s.mesh.data(v);
    const double tp = d.param[0], ts = d.param[1];
    const glm::dvec3 p = point(s.mesh, v);
    // The parameters are normalised arc length: tp from the position along the profile ...
    const glm::dvec2 rp = cylinder_profile(tp);
    ASSERT_NEAR(std::hypot(p.x, p.z), rp.x, 1e-12);
    ASSERT_NEAR(p.y, rp.y, 1e-12);
    // ... and ts from the angle (counter-clockwise seen from +Y, from angle 0).
    if (rp.x > 0) {
      double a = horizontal_angle({p.x, p.z});
      if (a < -1e-12) a += 2 * kPi;
      ASSERT_NEAR(ts, a / (2 * kPi), 1e-12);
    }
    // Linear RGB, interpolated linearly: black to white is t itself.
    for (int k = 0; k < 3; ++k) ASSERT_NEAR(d.front[k], tp, 1e-12);
    ASSERT_NEAR(d.back[0], 1 - std::abs(2 * ts - 1), 1e-12);
    ASSERT_EQ(d.back[1], 0.0);
    ASSERT_NEAR(d.blur, 2e-3 * (1 - std::abs(2 * tp - 1)), 1e-15);
  }
}

TEST(SweepAround, UnitsBecomeMetres) {
  std::string text = cylinder("{type: cylindrical}", "0.25");
  text.replace(text.find("units: mm"), 9, "units: cm");
  const Template t = parse(text);
  const DsSurface s = sweep_around(t.surfaces[0], t);
  double r = 0, y = 0;
  for (auto v : s.mesh.vertices()) {
    const glm::dvec3 p = point(s.mesh, v);
    r = std::max(r, std::hypot(p.x, p.z));
    y = std::max(y, p.y);
  }
  EXPECT_NEAR(r, 0.10, 1e-12);
  EXPECT_NEAR(y, 0.20, 1e-12);
}

TEST(SweepAround, TheVertexBudgetGuardRefusesATinyEdge) {
  // 0.005 mm passes the parser's bound (height / 4096) but gives ~1e8 vertices.
  Template t = parse(cylinder("{type: cylindrical}", "0.005"));
  for (double edge : {t.edge_m, 1e-9}) {
    t.edge_m = edge;
    try {
      sweep_around(t.surfaces[0], t);
      FAIL() << "a tiny edge was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "resolution.edge");
      EXPECT_NE(e.rule().find("too small"), std::string::npos) << e.what();
    }
  }
}

/// A 4-fold template with a hexagonal `within` profile whose rails are known:
/// r_in(y) = 15 - y, 10, y - 5 and r_out(y) = 15 + y, 20, 35 - y (mm) on [0,5], [5,15], [15,20];
/// and a diamond loop from u = 12 to u = 18 in fold 0.
std::string hexagon_within(const std::string& edge, const std::string& extra = "") {
  return "format: cutaway-template/1\nname: hex\nunits: mm\nsymmetry: {type: nfold, folds: 4}\n"
         "resolution: {edge: " +
         edge +
         "}\nsurfaces:\n"
         "  - name: skin\n    kind: around\n    role: skin\n    smooth: false\n"
         "    profile: [[0, -2], [30, -2], [30, 22], [0, 22]]\n"
         "  - name: cell\n    kind: within\n    smooth: false\n"
         "    profile: [[15, 0], [20, 5], [20, 15], [15, 20], [10, 15], [10, 5]]\n"
         "    section: [[12, 0], [15, -1.5], [18, 0], [15, 1.5]]\n" +
         extra;
}

double rail_in(double y_mm) { return y_mm <= 5 ? 15 - y_mm : (y_mm <= 15 ? 10 : y_mm - 5); }
double rail_out(double y_mm) { return y_mm <= 5 ? 15 + y_mm : (y_mm <= 15 ? 20 : 35 - y_mm); }

TEST(SweepWithin, ExtremePointsAlongTheFoldCentreTouchTheRails) {
  const Template t = parse(hexagon_within("2"));
  const SurfaceSpec& spec = surface(t, "cell");
  const DsSurface s = sweep_within(spec, t);
  ASSERT_EQ(s.mesh.n_vertices() % 4, 0u);
  const size_t per_fold = s.mesh.n_vertices() / 4;
  for (int fold = 0; fold < 4; ++fold) {
    const double a = t.fold_angles[fold];
    const glm::dvec2 centre(std::cos(a), -std::sin(a));  // [x, z] of the fold's centre line
    std::map<double, std::pair<double, double>> extent;  // y -> (min u, max u)
    for (size_t i = fold * per_fold; i < (fold + 1) * per_fold; ++i) {
      const glm::dvec3 p = point(s.mesh, DsMesh::VertexHandle(static_cast<int>(i)));
      const double u = glm::dot(glm::dvec2(p.x, p.z), centre);
      auto [it, fresh] = extent.try_emplace(p.y, u, u);
      it->second.first = std::min(it->second.first, u);
      it->second.second = std::max(it->second.second, u);
    }
    EXPECT_GT(extent.size(), 5u);
    for (const auto& [y, uu] : extent) {
      EXPECT_NEAR(uu.first, rail_in(y * 1e3) * 1e-3, 1e-12) << "fold " << fold << " y " << y;
      EXPECT_NEAR(uu.second, rail_out(y * 1e3) * 1e-3, 1e-12) << "fold " << fold << " y " << y;
    }
    EXPECT_NEAR(extent.begin()->first, 0.0, 1e-15);
    EXPECT_NEAR(extent.rbegin()->first, 20e-3, 1e-15);
  }
  EXPECT_EQ(boundary_halfedges(s.mesh), 0);
}

TEST(SweepWithin, SectionParameterStartsAtTheOutermostPoint) {
  const Template t = parse(hexagon_within(
      "2", "    front: {along: section, stops: [[0, \"#ffffff\"], [1, \"#000000\"]]}\n"
           "    visible: {back: false}\n"));
  const DsSurface s = sweep_within(surface(t, "cell"), t);
  EXPECT_TRUE(s.visible_front);
  EXPECT_FALSE(s.visible_back);
  EXPECT_EQ(s.role, SurfaceRole::Structure);
  for (auto v : s.mesh.vertices()) {
    const auto& d = s.mesh.data(v);
    ASSERT_NEAR(d.front[0], 1 - d.param[1], 1e-12);
    if (d.param[1] == 0) {
      // t_section = 0 is the loop's outermost point: on the outer rail, on the fold centre.
      const glm::dvec3 p = point(s.mesh, v);
      const double r = std::hypot(p.x, p.z);
      ASSERT_NEAR(r, rail_out(p.y * 1e3) * 1e-3, 1e-12);
    }
  }
}

/// The hexagon's cell with `sections` (a YAML flow list) instead of its one section.
std::string hexagon_with_sections(const std::string& sections) {
  std::string text = hexagon_within("1");
  const std::string one = "    section: [[12, 0], [15, -1.5], [18, 0], [15, 1.5]]\n";
  text.replace(text.find(one), one.size(), "    sections: " + sections + "\n");
  return text;
}

// A loop that widens with height: a diamond half as wide as long up to 0.3 of the rails, one
// as wide as long from 0.7; each ring still reaches from rail to rail, and between the two
// heights its width grows steadily.
TEST(SweepWithin, SectionsAtSeveralHeightsBlendTheLoop) {
  const Template t =
      parse(hexagon_with_sections("[{at: 0.3, section: [[12, 0], [15, -1.5], [18, 0], [15, 1.5]]}, "
                                  "{at: 0.7, section: [[12, 0], [15, -3], [18, 0], [15, 3]]}]"));
  check_template_curves(t);
  const DsSurface s = sweep_within(surface(t, "cell"), t);
  EXPECT_EQ(boundary_halfedges(s.mesh), 0);
  const size_t per_fold = s.mesh.n_vertices() / 4;
  for (int fold = 0; fold < 4; ++fold) {
    const double a = t.fold_angles[fold];
    const glm::dvec2 centre(std::cos(a), -std::sin(a)), across(-std::sin(a), -std::cos(a));
    std::map<double, glm::dvec3> ring;  // y -> (min u, max u, max |w|)
    for (size_t i = fold * per_fold; i < (fold + 1) * per_fold; ++i) {
      const glm::dvec3 p = point(s.mesh, DsMesh::VertexHandle(static_cast<int>(i)));
      const double u = glm::dot(glm::dvec2(p.x, p.z), centre);
      const double w = std::abs(glm::dot(glm::dvec2(p.x, p.z), across));
      auto [it, fresh] = ring.try_emplace(p.y, u, u, w);
      it->second = {std::min(it->second.x, u), std::max(it->second.y, u),
                    std::max(it->second.z, w)};
    }
    ring.erase(ring.begin());  // the poles
    ring.erase(std::prev(ring.end()));
    double last = 0;
    int narrow = 0, wide = 0;
    for (const auto& [y, r] : ring) {
      EXPECT_NEAR(r.x, rail_in(y * 1e3) * 1e-3, 1e-12) << y;
      EXPECT_NEAR(r.y, rail_out(y * 1e3) * 1e-3, 1e-12) << y;
      const double ratio = r.z / (r.y - r.x);  // half width over length
      EXPECT_GE(ratio, last - 1e-12) << y;
      EXPECT_GE(ratio, 0.25 - 1e-9) << y;
      EXPECT_LE(ratio, 0.5 + 1e-9) << y;
      narrow += std::abs(ratio - 0.25) < 1e-9;
      wide += std::abs(ratio - 0.5) < 1e-9;
      last = ratio;
    }
    EXPECT_GT(narrow, 2) << "fold " << fold;
    EXPECT_GT(wide, 2) << "fold " << fold;
  }
}

TEST(SweepWithin, SectionsAtHeightsFollowTheirRules) {
  auto error = [](const std::string& text) -> std::string {
    try {
      const Template t = parse(text);
      check_template_curves(t);
      for (const SurfaceSpec& s : t.surfaces)
        if (s.kind == SurfaceKind::Within) sweep_within(s, t);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  // Each section's loops follow the rules of a single section, at its own field.
  EXPECT_NE(error(hexagon_with_sections("[{at: 0, section: [[12, 0], [15, -1.5], [18, 0]]}, "
                                        "{at: 1, section: [[12, 0], [15, 20], [18, 0]]}]"))
                .find("sections[1].section: a 'within' loop must lie inside fold 0"),
            std::string::npos);
  EXPECT_NE(error(hexagon_with_sections("[{at: 0, section: circle}, "
                                        "{at: 1, section: [[12, 0], [15, 1], [18, 0]]}]"))
                .find("sections[0].section: a 'within' section is a loop"),
            std::string::npos);
  // A C opening one way blended into a C opening the other way crosses itself half way.
  EXPECT_NE(error(hexagon_with_sections(
                      "[{at: 0.2, section: [[12, -1], [18, -1], [18, 0], [13, 0], [13, 0.5], "
                      "[18, 0.5], [18, 1.5], [12, 1.5]]}, "
                      "{at: 0.8, section: [[12, -1], [18, -1], [18, 1.5], [12, 1.5], [12, 0.5], "
                      "[17, 0.5], [17, 0], [12, 0]]}]"))
                .find("the blend of two sections crosses itself"),
            std::string::npos);
}

TEST(SweepWithin, TheVertexBudgetGuardRefusesATinyEdge) {
  Template t = parse(hexagon_within("0.006"));
  for (double edge : {t.edge_m, 1e-9}) {
    t.edge_m = edge;
    try {
      sweep_within(surface(t, "cell"), t);
      FAIL() << "a tiny edge was accepted";
    } catch (const InputError& e) {
      EXPECT_EQ(e.field(), "resolution.edge");
    }
  }
}

}  // namespace
}  // namespace cutaway
