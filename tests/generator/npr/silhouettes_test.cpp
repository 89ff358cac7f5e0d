// extract_strokes (generator/npr/silhouettes.h): silhouettes of a cube seen from a corner, hidden
// edges removed, the crease threshold, linking of collinear edges into one stroke, tapering,
// and the POV-Ray sphere_sweep export of strokes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>

#include "export/pov_export.h"
#include "npr/silhouettes.h"

namespace cutaway {
namespace {

/// An axis-aligned box at `centre` with half-extents `half`, 4 vertices per face (so the faces
/// share no vertex: extraction must weld them by position), outward, counter-clockwise.
AssetMesh box(const std::string& name, const glm::dvec3& half,
              const glm::dvec3& centre = glm::dvec3(0.0)) {
  AssetMesh m;
  m.name = name;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      glm::dvec3 n(0.0), u(0.0), v(0.0);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1;
      v[(axis + 2) % 3] = 1;
      if (sign < 0) std::swap(u, v);
      const auto base = static_cast<unsigned>(m.position.size());
      for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        m.position.push_back(centre + half * (n + double(a) * u + double(b) * v));
        m.normal.push_back(n);
        m.colour.push_back({0.5, 0.4, 0.3});
      }
      m.triangle.push_back({base, base + 1, base + 2});
      m.triangle.push_back({base, base + 2, base + 3});
    }
  }
  return m;
}

SceneAssets scene_of(std::vector<AssetMesh> meshes, const glm::dvec3& eye, double fov_deg = 40) {
  SceneAssets a;
  a.name = "test";
  a.meshes = std::move(meshes);
  for (size_t i = 0; i < a.meshes.size(); ++i) {
    AssetInstance inst;
    inst.name = "i" + std::to_string(i);
    inst.mesh = static_cast<int>(i);
    a.instances.push_back(inst);
  }
  a.camera.eye = eye;
  a.camera.target = glm::dvec3(0.0);
  a.camera.up = {0, 1, 0};
  a.camera.fov_y_deg = fov_deg;
  a.width = 200;
  a.height = 200;
  return a;
}

StrokeOptions exact() {
  StrokeOptions o;
  o.smoothing = 0;  // points stay on the mesh's vertices
  return o;
}

// The cube is seen along its diagonal from afar (nearly orthographic): its outline is a
// regular hexagon, turning 60 degrees at each corner.
TEST(Silhouettes, CubeFromACornerGivesItsHexagonAsOneClosedStroke) {
  const SceneAssets a = scene_of({box("cube", glm::dvec3(0.05))}, glm::dvec3(2.0, 2.0, 2.0), 4);
  StrokeOptions o = exact();
  o.crease_deg = 100;  // cube edges are 90-degree creases: silhouettes only
  const std::vector<Stroke> strokes = extract_strokes(a, o);
  ASSERT_EQ(strokes.size(), 1u);
  const Stroke& s = strokes[0];
  EXPECT_TRUE(s.closed);
  ASSERT_EQ(s.points.size(), 6u);
  ASSERT_EQ(s.width_px.size(), 6u);
  for (const glm::dvec3& p : s.points)
    for (int i = 0; i < 3; ++i) EXPECT_DOUBLE_EQ(std::abs(p[i]), 0.05);
  // Neither the corner nearest the eye nor the one farthest away is on the silhouette.
  for (const glm::dvec3& p : s.points) {
    EXPECT_FALSE(p.x > 0 && p.y > 0 && p.z > 0);
    EXPECT_FALSE(p.x < 0 && p.y < 0 && p.z < 0);
  }
  for (double w : s.width_px) EXPECT_GT(w, 0);
  EXPECT_LT(glm::length(s.colour), glm::length(glm::dvec3(0.5, 0.4, 0.3)));  // darkened
}

TEST(Silhouettes, CubeCreasesFacingTheEyeAreStrokesOfTheirOwn) {
  const SceneAssets a = scene_of({box("cube", glm::dvec3(0.05))}, glm::dvec3(2.0, 2.0, 2.0), 4);
  const std::vector<Stroke> strokes = extract_strokes(a, exact());
  // The hexagon, and the three edges of the near corner, which meet at 120 degrees (a turn of
  // 60: two of them link) and turn 120 degrees into the hexagon (never linked); the three
  // edges of the far corner face away and are hidden.
  ASSERT_EQ(strokes.size(), 3u);
  int closed = 0;
  size_t open_edges = 0;
  const glm::dvec3 near_corner(0.05);
  for (const Stroke& s : strokes) {
    if (s.closed) {
      ++closed;
      EXPECT_EQ(s.points.size(), 6u);
    } else {
      open_edges += s.points.size() - 1;
      EXPECT_NE(std::find(s.points.begin(), s.points.end(), near_corner), s.points.end());
    }
  }
  EXPECT_EQ(open_edges, 3u);
  EXPECT_EQ(closed, 1);
}

TEST(Silhouettes, HiddenEdgesAreRemoved) {
  // A small box far behind a big one, seen along -z: the big one hides it completely.
  AssetMesh big = box("big", {0.1, 0.1, 0.01}, {0, 0, 0.05});
  AssetMesh small = box("small", glm::dvec3(0.02), {0, 0, -0.2});
  const glm::dvec3 eye(0.01, 0.02, 0.6);
  const std::vector<Stroke> both = extract_strokes(scene_of({big, small}, eye), exact());
  ASSERT_FALSE(both.empty());
  for (const Stroke& s : both)
    for (const glm::dvec3& p : s.points) EXPECT_GT(p.z, 0.0) << "an edge of the hidden box";
  // Alone, the small box has strokes.
  const std::vector<Stroke> alone = extract_strokes(scene_of({small}, eye), exact());
  EXPECT_FALSE(alone.empty());
}

TEST(Silhouettes, ALongEdgePartlyHiddenIsDrawnOnlyWhereInSight) {
  // A wide, flat box far behind a narrow pillar that hides the middle of it (seen along -z):
  // its long outline edges are drawn on both sides of the pillar, never across it.
  AssetMesh wide = box("wide", {0.2, 0.02, 0.01}, {0, 0, -0.2});
  AssetMesh pillar = box("pillar", {0.03, 0.2, 0.01}, {0, 0, 0.1});
  const glm::dvec3 eye(0.0, 0.01, 0.8);
  const std::vector<Stroke> strokes = extract_strokes(scene_of({wide, pillar}, eye, 50), exact());
  bool left = false, right = false;
  for (const Stroke& s : strokes) {
    for (size_t k = 0; k + 1 < s.points.size(); ++k) {
      const glm::dvec3 &a = s.points[k], &b = s.points[k + 1];
      if (a.z > -0.1 || b.z > -0.1) continue;  // the pillar's own strokes
      EXPECT_FALSE(std::min(a.x, b.x) < 0 && std::max(a.x, b.x) > 0)
          << "a stroke of the wide box across the pillar: " << a.x << " .. " << b.x;
      left = left || std::min(a.x, b.x) < -0.1;
      right = right || std::max(a.x, b.x) > 0.1;
    }
  }
  EXPECT_TRUE(left);
  EXPECT_TRUE(right);
}

/// Two quads meeting at a ridge along z (x = 0), each sloping down by `slope_deg`: an open
/// mesh whose ridge is a crease of dihedral angle 2 * slope_deg; its outline is boundary.
AssetMesh roof(double slope_deg) {
  AssetMesh m;
  m.name = "roof";
  const double s = glm::radians(slope_deg);
  const double w = 0.05, d = 0.05;
  const glm::dvec3 left(-w * std::cos(s), -w * std::sin(s), 0);
  const glm::dvec3 right(w * std::cos(s), -w * std::sin(s), 0);
  m.position = {{0, 0, -d},
                {0, 0, d},
                left + glm::dvec3(0, 0, d),
                left + glm::dvec3(0, 0, -d),
                right + glm::dvec3(0, 0, -d),
                right + glm::dvec3(0, 0, d)};
  m.triangle = {{0, 3, 2}, {0, 2, 1}, {0, 1, 5}, {0, 5, 4}};
  m.normal.assign(m.position.size(), {0, 1, 0});
  m.colour.assign(m.position.size(), {0.2, 0.6, 0.2});
  return m;
}

bool has_ridge_stroke(const std::vector<Stroke>& strokes) {
  for (const Stroke& s : strokes)
    if (std::all_of(s.points.begin(), s.points.end(),
                    [](const glm::dvec3& p) { return p.x == 0 && p.y == 0; }))
      return true;
  return false;
}

TEST(Silhouettes, CreaseThreshold) {
  const glm::dvec3 eye(0.02, 0.4, 0.15);
  const SceneAssets a = scene_of({roof(20)}, eye);  // normals 40 degrees apart
  StrokeOptions o = exact();
  o.crease_deg = 60;
  EXPECT_FALSE(has_ridge_stroke(extract_strokes(a, o)));
  o.crease_deg = 30;
  EXPECT_TRUE(has_ridge_stroke(extract_strokes(a, o)));
  // The boundary is there either way.
  o.crease_deg = 60;
  EXPECT_GE(extract_strokes(a, o).size(), 3u);
}

TEST(Silhouettes, CollinearEdgesLinkIntoOneTaperedStroke) {
  // A flat strip of 10 quads in the xz plane seen from above: its long sides are 10 edges each.
  AssetMesh strip;
  strip.name = "strip";
  for (int i = 0; i <= 10; ++i)
    for (const double z : {-0.01, 0.01}) strip.position.push_back({-0.1 + 0.02 * i, 0, z});
  for (unsigned i = 0; i < 10; ++i) {
    const unsigned a = 2 * i;
    strip.triangle.push_back({a, a + 1, a + 3});
    strip.triangle.push_back({a, a + 3, a + 2});
  }
  strip.normal.assign(strip.position.size(), {0, 1, 0});
  strip.colour.assign(strip.position.size(), {0.9, 0.1, 0.1});
  SceneAssets a = scene_of({strip}, {0.0, 0.35, 0.05});
  const std::vector<Stroke> strokes = extract_strokes(a, exact());
  ASSERT_EQ(strokes.size(), 4u);  // the corners turn 90 degrees: four sides
  int long_sides = 0;
  for (const Stroke& s : strokes) {
    EXPECT_FALSE(s.closed);
    if (s.points.size() != 11) continue;
    ++long_sides;
    EXPECT_LT(s.width_px.front(), 0.5 * s.width_px[5]);  // thin at both ends
    EXPECT_LT(s.width_px.back(), 0.5 * s.width_px[5]);
    EXPECT_EQ(*std::max_element(s.width_px.begin(), s.width_px.end()), s.width_px[5]);
  }
  EXPECT_EQ(long_sides, 2);
}

TEST(Silhouettes, SeamsInsideAFlatFaceAreThinnerStructureLines) {
  // The strip of CollinearEdgesLinkIntoOneTaperedStroke, with its middle cross edge (x = 0)
  // split: the two halves use their own copies of its vertices, as a cross-section's two sides
  // of a cut segment do.
  AssetMesh strip;
  strip.name = "strip";
  for (int i = 0; i <= 10; ++i)
    for (const double z : {-0.01, 0.01}) strip.position.push_back({-0.1 + 0.02 * i, 0, z});
  strip.position.push_back(strip.position[10]);  // copies of the x = 0 vertices: 22, 23
  strip.position.push_back(strip.position[11]);
  for (unsigned i = 0; i < 10; ++i) {
    unsigned a = 2 * i, b = a + 1, c = a + 3, d = a + 2;
    if (i == 5) a = 22, b = 23;  // the right half starts on the copies
    strip.triangle.push_back({a, b, c});
    strip.triangle.push_back({a, c, d});
  }
  strip.normal.assign(strip.position.size(), {0, 1, 0});
  strip.colour.assign(strip.position.size(), {0.9, 0.1, 0.1});
  const SceneAssets a = scene_of({strip}, {0.0, 0.35, 0.05});
  StrokeOptions o = exact();
  o.min_length_px = 1;
  const std::vector<Stroke> with = extract_strokes(a, o);
  o.structure_width = 0;
  const std::vector<Stroke> without = extract_strokes(a, o);
  ASSERT_EQ(with.size(), without.size() + 1);
  // The extra stroke runs along x = 0, thinner than an outline of the same length would be.
  const Stroke* seam = nullptr;
  for (const Stroke& s : with)
    if (s.points.size() == 2 && s.points[0].x == 0 && s.points[1].x == 0) seam = &s;
  ASSERT_NE(seam, nullptr);
  double outline_max = 0;
  for (const Stroke& s : without)
    outline_max = std::max(outline_max, *std::max_element(s.width_px.begin(), s.width_px.end()));
  EXPECT_LT(*std::max_element(seam->width_px.begin(), seam->width_px.end()), outline_max);
}

TEST(Silhouettes, CopiesMadeOnlyForTextureCoordinatesAreNoSeam) {
  // The same split strip, textured: where the copies differ from their originals only in
  // their texture coordinates (a skin texture's seam), there is no structure line; where they
  // also differ in colour (the two sides of a cut segment), there is.
  AssetMesh strip;
  strip.name = "strip";
  for (int i = 0; i <= 10; ++i)
    for (const double z : {-0.01, 0.01}) strip.position.push_back({-0.1 + 0.02 * i, 0, z});
  strip.position.push_back(strip.position[10]);
  strip.position.push_back(strip.position[11]);
  for (unsigned i = 0; i < 10; ++i) {
    unsigned a = 2 * i, b = a + 1, c = a + 3, d = a + 2;
    if (i == 5) a = 22, b = 23;
    strip.triangle.push_back({a, b, c});
    strip.triangle.push_back({a, c, d});
  }
  strip.normal.assign(strip.position.size(), {0, 1, 0});
  strip.colour.assign(strip.position.size(), {0.9, 0.1, 0.1});
  for (const glm::dvec3& p : strip.position) strip.uv.push_back({p.x + 0.1, p.z});
  strip.uv[22].x += 1;  // the copies: u + 1, as across t_section = 0
  strip.uv[23].x += 1;
  StrokeOptions o = exact();
  o.min_length_px = 1;
  const std::vector<Stroke> textured = extract_strokes(scene_of({strip}, {0.0, 0.35, 0.05}), o);
  o.structure_width = 0;
  const std::vector<Stroke> outlines = extract_strokes(scene_of({strip}, {0.0, 0.35, 0.05}), o);
  EXPECT_EQ(textured.size(), outlines.size());
  strip.colour[22] = strip.colour[23] = {0.1, 0.9, 0.1};
  o.structure_width = StrokeOptions{}.structure_width;
  EXPECT_EQ(extract_strokes(scene_of({strip}, {0.0, 0.35, 0.05}), o).size(), outlines.size() + 1);
}

/// The largest distance, in pixels at its depth, of a stroke point of `strokes` from the
/// surface of the box of half extents `half` at the origin (exact on its faces, a lower bound
/// off them).
double largest_offset_px(const std::vector<Stroke>& strokes, const glm::dvec3& half,
                         const SceneAssets& a) {
  const double metres_per_px_at_1m = 2 * std::tan(glm::radians(a.camera.fov_y_deg) / 2) / a.height;
  double worst = 0;
  for (const Stroke& s : strokes)
    for (const glm::dvec3& p : s.points) {
      const glm::dvec3 d = glm::abs(p) - half;
      const double off = std::fabs(std::max({d.x, d.y, d.z}));
      worst = std::max(worst, off / (glm::distance(p, a.camera.eye) * metres_per_px_at_1m));
    }
  return worst;
}

TEST(Silhouettes, SmoothingKeepsTheCornersOfLongEdges) {
  // A box's outline is a few long edges: smoothing (default options) moves a corner by at most
  // smoothing_shift_px per pass, not by a quarter of its edges (which pulled a board's outline
  // 50 pixels into the board, drawn over the pieces on it).
  const glm::dvec3 half(0.1, 0.02, 0.08);
  const SceneAssets a = scene_of({box("box", half)}, {0.05, 0.3, 0.25});
  StrokeOptions o;
  const std::vector<Stroke> strokes = extract_strokes(a, o);
  ASSERT_FALSE(strokes.empty());
  EXPECT_LE(largest_offset_px(strokes, half, a), o.smoothing * o.smoothing_shift_px + 0.5);
  // Unlimited, as before: the corners move far off the box.
  o.smoothing_shift_px = 1e9;
  EXPECT_GT(largest_offset_px(extract_strokes(a, o), half, a), 6.0);
}

TEST(Silhouettes, StrengthZeroGivesNothingAndResultsAreDeterministic) {
  const SceneAssets a = scene_of({box("cube", glm::dvec3(0.05))}, glm::dvec3(2.0, 2.0, 2.0), 4);
  StrokeOptions o;
  o.strength = 0;
  EXPECT_TRUE(extract_strokes(a, o).empty());
  o.strength = 1;
  const auto s1 = extract_strokes(a, o), s2 = extract_strokes(a, o);
  ASSERT_EQ(s1.size(), s2.size());
  for (size_t i = 0; i < s1.size(); ++i) {
    EXPECT_EQ(s1[i].points, s2[i].points);
    EXPECT_EQ(s1[i].width_px, s2[i].width_px);
  }
  o.strength = 2;
  const auto thick = extract_strokes(a, o);
  ASSERT_EQ(thick.size(), s1.size());
  EXPECT_DOUBLE_EQ(thick[0].width_px[0], 2 * s1[0].width_px[0]);
}

TEST(Silhouettes, PovExportWritesOneTubePerStroke) {
  const SceneAssets a = scene_of({box("cube", glm::dvec3(0.05))}, glm::dvec3(2.0, 2.0, 2.0), 4);
  const std::vector<Stroke> strokes = extract_strokes(a);
  const std::string pov = scene_to_pov(a, &strokes);
  size_t count = 0;
  for (size_t at = pov.find("union {"); at != std::string::npos; at = pov.find("union {", at + 1))
    ++count;
  EXPECT_EQ(count, strokes.size());
  size_t cones = 0;
  for (size_t at = pov.find("cone {"); at != std::string::npos; at = pov.find("cone {", at + 1))
    ++cones;
  EXPECT_GE(cones, 6u);  // the hexagon, closed: six cones
  EXPECT_NE(pov.find("no_shadow"), std::string::npos);
  EXPECT_EQ(scene_to_pov(a).find("cone {"), std::string::npos);
}

}  // namespace
}  // namespace cutaway
