// The rules that keep the seams of a piece exact where the geometry is nearly degenerate:
// merging of cut segments across split planes, split lines through nearby cut vertices,
// mutual-nearest snapping of seam vertices, and the manifold check that decides a recut.
#include <vector>

#include <gtest/gtest.h>

#include "pieces/manifold_check.h"
#include "pieces/seam_stitch.h"
#include "section/split_lines.h"

namespace cutaway {
namespace {

CutSegment segment(const glm::dvec3& a, const glm::dvec3& b) {
  CutSegment s;
  s.surface = 1;
  s.a = a;
  s.b = b;
  s.front_normal = {0, 0, 1};
  return s;
}

TEST(Seams, NearlyCollinearSegmentsAreNotMergedAcrossASplitPlane) {
  // q -> p -> r bends by 1 um, within the 10 um tolerance.
  const std::vector<CutSegment> segs = {segment({0, 0, 0}, {1e-3, 1e-6, 0}),
                                        segment({1e-3, 1e-6, 0}, {2e-3, 0, 0})};
  EXPECT_EQ(merge_collinear_segments(segs, 1e-5, 1e-2).size(), 1u);
  // A plane x = 0.5 mm between q and p: the merged chord would cross it 0.5 um from where the
  // surface does.
  const Plane split{{0.5e-3, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(merge_collinear_segments(segs, 1e-5, 1e-2, {split}).size(), 2u);
  // A plane beyond all three points does not stop the merge.
  const Plane beyond{{5e-3, 0, 0}, {1, 0, 0}};
  EXPECT_EQ(merge_collinear_segments(segs, 1e-5, 1e-2, {beyond}).size(), 1u);
}

TEST(Seams, ASplitLinePassesThroughACutVertexWithinTheSnapDistance) {
  // A segment whose end point lies 3 nm from the line y = 0, the other end far below it.
  const glm::dvec2 a(1e-3, 3e-9), b(2e-3, -1e-3);
  const Line2 line{{0, 1}, 0};
  const auto constraints =
      arrange_split_lines({{a, b}}, {line}, glm::dvec2(-1e-2), glm::dvec2(1e-2), 1e-8);
  // The segment stays whole and the line is split at a: no crossing 3 nm from the vertex.
  int segments = 0, line_pieces = 0;
  for (const Constraint2& c : constraints) {
    if (c.segment == 0) {
      ++segments;
      EXPECT_EQ(c.a, a);
      EXPECT_EQ(c.b, b);
    } else {
      ++line_pieces;
      EXPECT_TRUE(c.a == a || c.b == a);
    }
  }
  EXPECT_EQ(segments, 1);
  EXPECT_EQ(line_pieces, 2);
  // 30 nm away it is an ordinary crossing: the segment is split.
  const glm::dvec2 far(1e-3, 3e-8);
  int split = 0;
  for (const Constraint2& c :
       arrange_split_lines({{far, b}}, {line}, glm::dvec2(-1e-2), glm::dvec2(1e-2), 1e-8))
    split += c.segment == 0;
  EXPECT_EQ(split, 2);
}

/// One triangle (a, b, c) as a mesh.
ShadedMesh triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
  ShadedMesh m;
  m.position = {a, b, c};
  m.normal.assign(3, glm::dvec3(0, 0, 1));
  m.colour.assign(3, glm::dvec3(0.5));
  m.material.assign(3, glm::dvec2(0.5, 0));
  m.triangle = {{0, 1, 2}};
  return m;
}

TEST(Seams, OnlyTheNearestVertexOfAPartSnapsOntoASeamVertex) {
  // Part A: a triangle with a corner at the origin. Part B: a fan of two triangles whose
  // boundary has a vertex 3 nm from that corner (listed first) and one exactly on it.
  ShadedMesh a = triangle({0, 0, 0}, {-1e-3, -1e-3, 0}, {-1e-3, 1e-3, 0});
  ShadedMesh b;
  b.position = {{3e-9, 0, 0}, {0, 0, 0}, {1e-3, 1e-3, 0}, {1e-3, -1e-3, 0}};
  b.normal.assign(4, glm::dvec3(0, 0, 1));
  b.colour.assign(4, glm::dvec3(0.5));
  b.material.assign(4, glm::dvec2(0.5, 0));
  b.triangle = {{0, 3, 2}, {1, 0, 2}};
  std::vector<ShadedMesh*> parts = {&a, &b};
  stitch_seams(parts, 2e-8);
  // The vertex at the corner stays where it is, the other is not moved onto it.
  EXPECT_EQ(b.position[0], glm::dvec3(3e-9, 0, 0));
  EXPECT_EQ(b.position[1], glm::dvec3(0, 0, 0));
}

/// A closed tetrahedron, wound outwards.
ShadedMesh tetrahedron() {
  ShadedMesh m;
  m.position = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  m.normal.assign(4, glm::dvec3(0, 0, 1));
  m.colour.assign(4, glm::dvec3(0.5));
  m.material.assign(4, glm::dvec2(0.5, 0));
  m.triangle = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return m;
}

TEST(ManifoldCheck, FindsOpenFlippedDegenerateAndNearDuplicateMeshes) {
  EXPECT_TRUE(check_manifold(tetrahedron(), 1e-9));
  ShadedMesh open = tetrahedron();
  open.triangle.pop_back();
  EXPECT_EQ(check_manifold(open, 0).reason(), "an open edge");
  ShadedMesh flipped = tetrahedron();
  std::swap(flipped.triangle[3][1], flipped.triangle[3][2]);
  EXPECT_FALSE(check_manifold(flipped, 0));
  ShadedMesh pinched = tetrahedron();
  pinched.triangle[3] = {1, 1, 3};
  EXPECT_EQ(check_manifold(pinched, 0).reason(), "a triangle with two corners at one point");
  // Duplicated vertices at one position are welded; 0.1 nm apart they are a near-duplicate.
  ShadedMesh split = tetrahedron();
  split.position.push_back(split.position[3]);
  split.normal.push_back(split.normal[3]);
  split.colour.push_back(split.colour[3]);
  split.material.push_back(split.material[3]);
  split.triangle[3][2] = 4;
  EXPECT_TRUE(check_manifold(split, 1e-9));
  split.position[4].x += 1e-10;
  EXPECT_FALSE(check_manifold(split, 1e-9));
  // Two tetrahedra touching at one vertex (the second mirrored through it): two fans there.
  ShadedMesh bow = tetrahedron();
  for (unsigned v = 0; v < 4; ++v) {
    bow.position.push_back(-bow.position[v]);
    bow.normal.push_back(-bow.normal[v]);
    bow.colour.push_back(bow.colour[v]);
    bow.material.push_back(bow.material[v]);
  }
  for (glm::uvec3 t : tetrahedron().triangle) bow.triangle.push_back({t.x + 4, t.z + 4, t.y + 4});
  EXPECT_EQ(check_manifold(bow, 0).reason(), "a vertex with more than one fan of triangles");
}

}  // namespace
}  // namespace cutaway
