// Settling with Bullet (doc/algorithms.md §4, Settling): collision shapes that enclose their
// pieces, a decomposition for a hollow piece, deterministic settling, pieces that fall out of
// the container dropped again, a piece at rest staying put, and the arrangements of a scene:
// scatter on a board (none on another) and fan on a plate (each slice on the one before, the
// rows of several objects side by side).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/gtx/quaternion.hpp>
#include <glm/trigonometric.hpp>
#include <gtest/gtest.h>
#include <oneapi/tbb/global_control.h>

#include "diffusion/diffusion.h"
#include "io/cut_notation.h"
#include "io/scene_parser.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "pieces/pieces.h"
#include "placement/collision_shape.h"
#include "placement/container_mesh.h"
#include "placement/physics_settle.h"
#include "placement/scene_layout.h"
#include "scene/scene_builder.h"
#include "test_support.h"
#include "variation/variation.h"

namespace cutaway {
namespace {

/// The pieces of `name` cut by `cut`, merged (as the scene builder places them).
std::vector<ShadedMesh> pieces_of(const std::string& name, const std::string& cut) {
  const Template tmpl = load_template(test::source_path("templates/" + name + ".yaml").string());
  const DsModel model = build_model(tmpl);
  const auto diffusion = make_cpu_diffusion(model, {4, 0});
  PieceOptions options;
  options.section.edge_m = tmpl.edge_m;
  const PieceSet set = *cut_pieces(model, *parse_cut_spec(cut, 1e-3), *diffusion, options);
  std::vector<ShadedMesh> out;
  for (const Piece& p : set.pieces) out.push_back(merge_parts(p));
  return out;
}

/// How far p lies outside the convex hull of `corners` (0 inside), by the hull's support
/// planes in 64 x 32 directions: a lower bound of the distance, exact enough to test coverage.
double outside(const std::vector<glm::dvec3>& corners, const glm::dvec3& p) {
  double worst = -1;
  for (int i = 0; i < 64; ++i) {
    for (int j = 1; j < 32; ++j) {
      const double a = 2 * 3.14159265358979 * i / 64, b = 3.14159265358979 * j / 32;
      const glm::dvec3 d(std::sin(b) * std::cos(a), std::cos(b), std::sin(b) * std::sin(a));
      double support = -1e9;
      for (const glm::dvec3& c : corners) support = std::max(support, glm::dot(c, d));
      worst = std::max(worst, glm::dot(p, d) - support);
    }
  }
  return std::max(0.0, worst);
}

TEST(CollisionShape, AConvexPieceIsItsHullAndTheHullEnclosesEveryVertex) {
  const std::vector<ShadedMesh> halves = pieces_of("tomato", "halves");
  ASSERT_EQ(halves.size(), 2u);
  const CollisionShape s = collision_shape(halves[0]);
  EXPECT_FALSE(s.decomposed);
  ASSERT_EQ(s.parts.size(), 1u);
  EXPECT_GT(s.convexity, 0.8);
  EXPECT_LE(s.convexity, 1.0);
  EXPECT_NEAR(s.volume_m3, signed_volume(halves[0]), 1e-12);
  EXPECT_LE(static_cast<int>(s.parts[0].corners.size()), CollisionShapeOptions{}.max_corners);
  EXPECT_LT(s.parts[0].outside_m, 0.0015);
  for (size_t v = 0; v < halves[0].position.size(); v += 7)
    EXPECT_LE(outside(s.parts[0].corners, halves[0].position[v]), s.parts[0].outside_m + 1e-9);
}

TEST(CollisionShape, AHollowPepperHalfIsDecomposedAndItsPartsCoverIt) {
  const std::vector<ShadedMesh> halves = pieces_of("pepper", "halves");
  ASSERT_FALSE(halves.empty());
  const CollisionShape s = collision_shape(halves[0]);
  EXPECT_LT(s.convexity, 0.8);
  ASSERT_TRUE(s.decomposed);
  EXPECT_GE(s.parts.size(), 2u);
  // Every vertex of the piece is inside (or within the margin of) some part.
  for (size_t v = 0; v < halves[0].position.size(); v += 5) {
    double best = 1e9;
    for (const ConvexPart& part : s.parts)
      best = std::min(best, outside(part.corners, halves[0].position[v]) - part.outside_m);
    EXPECT_LE(best, 1e-9) << "vertex " << v;
  }
  // Same input, same shape.
  const CollisionShape again = collision_shape(halves[0]);
  ASSERT_EQ(again.parts.size(), s.parts.size());
  for (size_t k = 0; k < s.parts.size(); ++k) EXPECT_EQ(again.parts[k].corners, s.parts[k].corners);
}

// The hulls written for engines (collision_hulls): one closed, outward-wound convex mesh per
// part, over the part's own corners, holding every vertex of the piece between them.
TEST(CollisionShape, ExportedHullsAreClosedConvexMeshesWoundOutward) {
  const std::vector<ShadedMesh> halves = pieces_of("pepper", "halves");
  ASSERT_FALSE(halves.empty());
  const CollisionShape shape = collision_shape(halves[0]);
  const std::vector<AssetHull> hulls = collision_hulls(collision_shape(halves[0]));
  ASSERT_EQ(hulls.size(), shape.parts.size());
  ASSERT_GE(hulls.size(), 2u);
  for (size_t k = 0; k < hulls.size(); ++k) {
    const AssetHull& h = hulls[k];
    ASSERT_GE(h.triangle.size(), 4u) << "hull " << k;
    // Closed and consistently wound: each directed edge once, its reverse once.
    std::map<std::pair<unsigned, unsigned>, int> edges;
    for (const glm::uvec3& t : h.triangle)
      for (int e = 0; e < 3; ++e) ++edges[{t[e], t[(e + 1) % 3]}];
    for (const auto& [edge, n] : edges) {
      EXPECT_EQ(n, 1) << "hull " << k;
      EXPECT_EQ(edges.count({edge.second, edge.first}), 1u) << "hull " << k;
    }
    // Outward and convex: every corner on or behind every triangle's plane, and a positive
    // volume (the divergence theorem over the triangles).
    double volume = 0;
    for (const glm::uvec3& t : h.triangle) {
      const glm::dvec3 a = h.position[t.x], b = h.position[t.y], c = h.position[t.z];
      const glm::dvec3 n = glm::cross(b - a, c - a);
      volume += glm::dot(a, glm::cross(b, c)) / 6;
      for (const glm::dvec3& p : h.position)
        EXPECT_LE(glm::dot(p - a, n) / glm::length(n), 1e-9) << "hull " << k;  // metres
    }
    EXPECT_GT(volume, 0) << "hull " << k;
    // The part's corners, no others.
    std::set<std::tuple<double, double, double>> corners, used;
    for (const glm::dvec3& c : shape.parts[k].corners) corners.insert({c.x, c.y, c.z});
    for (const glm::dvec3& p : h.position) used.insert({p.x, p.y, p.z});
    EXPECT_TRUE(std::includes(corners.begin(), corners.end(), used.begin(), used.end()))
        << "hull " << k;
  }
}

/// A bowl, a piece dropped into it from `drop` and settled.
// A cut face's outline has corners in line to the last bit (crossings computed along one
// edge), and the hull keeps those that bulge out by a rounding error. When they were a facet's
// first corners, the facet's plane came from them, in a random direction or none (NaN), and
// the hull's volume came out negative: the plate scene with seed 548067 stopped on an internal
// error. Its tomato's slices, cut as the scene cuts them:
TEST(CollisionShape, SlicesWhoseFacetsStartWithCornersInLineHaveTheirHullVolume) {
  Template tmpl = load_template(test::source_path("templates/tomato.yaml").string());
  const Variant variant = make_variant(tmpl, object_seed(548067, 1, 0, 1));
  const auto diffusion = make_cpu_diffusion(variant.model, {2, 0});
  PieceOptions options;
  options.section.edge_m = tmpl.edge_m;
  const PieceSet set =
      *cut_pieces(variant.model, *parse_cut_spec("slices:9", 1e-3), *diffusion, options);
  ASSERT_EQ(set.pieces.size(), 5u);
  for (const Piece& p : set.pieces) {
    CollisionShape s;
    ASSERT_NO_THROW(s = collision_shape(merge_parts(p))) << "piece " << p.cell;
    EXPECT_GT(s.convexity, 0.9) << "piece " << p.cell;
    EXPECT_LE(s.convexity, 1.0) << "piece " << p.cell;
  }
}

SettleResult settle_one(const CollisionShape& shape, const Container& bowl, Placement drop) {
  return settle_pieces({{&shape, 1000, drop}}, bowl, SettleOptions{});
}

TEST(CollisionShape, IsTheSameEveryRun) {
  // CGAL's hull varies with memory addresses in the order of its faces and how it
  // triangulates a planar facet; the shape must not (it once did, by a micrometre, for one
  // slice in a hundred, and moved a piece of the market scene). Repeated with the heap in
  // other states.
  for (const auto& [name, cut] : {std::pair<std::string, std::string>{"cucumber", "slices:10"},
                                  {"kiwi", "slices:10"},
                                  {"tomato", "slices:10"},
                                  {"pepper", "halves"}}) {
    int differ = 0;
    for (const ShadedMesh& piece : pieces_of(name, cut)) {
      const CollisionShape a = collision_shape(piece);
      for (int r = 1; r <= 4; ++r) {
        const std::vector<std::vector<int>> other_heap(static_cast<size_t>(100 * r),
                                                       std::vector<int>(static_cast<size_t>(r)));
        const CollisionShape b = collision_shape(piece);
        bool same = a.parts.size() == b.parts.size() && a.volume_m3 == b.volume_m3;
        for (size_t k = 0; same && k < a.parts.size(); ++k)
          same = a.parts[k].corners == b.parts[k].corners &&
                 a.parts[k].outside_m == b.parts[k].outside_m;
        differ += !same;
      }
    }
    EXPECT_EQ(differ, 0) << name << " " << cut;
  }
}

TEST(PhysicsSettle, APieceFallsToTheFloorOfTheBowlAndStaysThere) {
  const std::vector<ShadedMesh> halves = pieces_of("tomato", "halves");
  const CollisionShape shape = collision_shape(halves[0]);
  Container bowl{ContainerType::Bowl, 0.2, 0, 0, 0.07};
  const Placement drop{true, glm::dquat(1, 0, 0, 0), glm::dvec3(0.01, 0.12, 0.0)};
  const SettleResult r = settle_one(shape, bowl, drop);
  ASSERT_TRUE(r.placements[0].placed);
  EXPECT_TRUE(r.all_asleep);
  EXPECT_EQ(r.lost, 0);
  // It fell: its lowest point is now near the floor of the bowl (0.08 x height).
  double low = 1;
  for (const glm::dvec3& p : halves[0].position)
    low = std::min(low, (r.placements[0].translation + r.placements[0].rotation * p).y);
  EXPECT_LT(low, 0.08 * 0.07 + 0.004);
  EXPECT_GT(low, 0.08 * 0.07 - 0.001);
  // At rest: simulated again for 1 s in a new world it moves less than 1 mm, found by the
  // first check.
  EXPECT_TRUE(r.stable);
  EXPECT_LT(r.stability_motion_m, 0.001);
  EXPECT_EQ(r.verify_rounds, 1);
  // Deterministic.
  const SettleResult again = settle_one(shape, bowl, drop);
  EXPECT_EQ(again.placements[0].translation, r.placements[0].translation);
  EXPECT_EQ(again.placements[0].rotation, r.placements[0].rotation);
}

TEST(PhysicsSettle, APieceThatFallsOffTheBoardIsDroppedAgainOrCounted) {
  const std::vector<ShadedMesh> halves = pieces_of("tomato", "halves");
  const CollisionShape shape = collision_shape(halves[0]);
  Container board{ContainerType::Board, 0, 0.3, 0.2, 0.02};
  // Dropped far beside the board: it lands on the table, outside, and is dropped again a
  // quarter of the way nearer the axis each time (1.5, 1, 0.5 m), still beside it: lost.
  const Placement far{true, glm::dquat(1, 0, 0, 0), glm::dvec3(2.0, 0.1, 0.0)};
  const SettleResult r = settle_one(shape, board, far);
  EXPECT_EQ(r.redrops, SettleOptions{}.max_redrops);
  EXPECT_EQ(r.lost, 1);
  EXPECT_FALSE(r.placements[0].placed);
  // Just beside it: dropped again nearer the axis, it ends on the board.
  const Placement beside{true, glm::dquat(1, 0, 0, 0), glm::dvec3(0.3, 0.1, 0.0)};
  const SettleResult b = settle_one(shape, board, beside);
  EXPECT_GE(b.redrops, 1);
  EXPECT_EQ(b.lost, 0);
  EXPECT_TRUE(b.placements[0].placed);
  // Dropped over the edge (its centre on the board): it is dropped again nearer the
  // axis, and ends on the board hanging over its edge by at most max_overhang of its size.
  const Placement edge{true, glm::dquat(1, 0, 0, 0), glm::dvec3(0.13, 0.06, 0.0)};
  const auto overhang_share = [&](const Placement& pose) {
    glm::dvec3 low(1e9), high(-1e9);
    double over = 0;
    for (const glm::dvec3& v : halves[0].position) {
      const glm::dvec3 p = pose.translation + pose.rotation * v;
      low = glm::min(low, p);
      high = glm::max(high, p);
      over = std::max(over, resting_overhang(board, p.x, p.z, 0.2));
    }
    const glm::dvec3 size = high - low;
    return over / std::max({size.x, size.y, size.z});
  };
  ASSERT_GT(overhang_share(edge), 0.2);  // over the fifth a reviewer accepts
  const SettleResult e = settle_one(shape, board, edge);
  EXPECT_EQ(e.lost, 0);
  EXPECT_GE(e.redrops, 1);
  ASSERT_TRUE(e.placements[0].placed);
  const glm::dvec3 c = e.placements[0].translation + e.placements[0].rotation * shape.centroid;
  EXPECT_LT(std::fabs(c.x), 0.15);
  EXPECT_GT(c.y, 0.02);
  // The hull stands up to 1.5 mm proud of the mesh: a little under the limit on the mesh.
  EXPECT_LE(overhang_share(e.placements[0]), SettleOptions{}.max_overhang);
}

/// The outward normal of the largest flat side of `piece` among +-X and +-Z (its triangles'
/// areas summed by the axis they face within 1 degree): a half's cut face.
glm::dvec3 flat_side(const ShadedMesh& piece) {
  const glm::dvec3 axes[] = {{1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {0, 0, -1}};
  double area[4] = {0, 0, 0, 0};
  for (const glm::uvec3& t : piece.triangle) {
    const glm::dvec3 c = glm::cross(piece.position[t.y] - piece.position[t.x],
                                    piece.position[t.z] - piece.position[t.x]);
    const double a = glm::length(c);
    for (int k = 0; k < 4; ++k)
      if (a > 0 && glm::dot(c / a, axes[k]) > std::cos(glm::radians(1.0))) area[k] += a;
  }
  return axes[std::max_element(area, area + 4) - area];
}

/// `shape` turned by `turn` and held with its lowest corner 5 mm over a board 20 mm high, its
/// origin over (x, z).
Placement over_the_board(const CollisionShape& shape, const glm::dquat& turn, double x = 0,
                         double z = 0) {
  double low = 0;
  for (const auto& part : shape.parts)
    for (const glm::dvec3& p : part.corners) low = std::min(low, (turn * p).y);
  return {true, turn, glm::dvec3(x, 0.025 - low, z)};
}

TEST(PhysicsSettle, AHalfLyingOnItsCutFaceIsDroppedAgainFaceUp) {
  const std::vector<ShadedMesh> halves = pieces_of("tomato", "halves");
  const CollisionShape shape = collision_shape(halves[0]);
  const glm::dvec3 face = flat_side(halves[0]);
  Container board{ContainerType::Board, 0, 0.3, 0.2, 0.02};
  // Dropped face down just over the middle of the board: it lands on its cut face.
  const glm::dquat down = glm::rotation(face, glm::dvec3(0, -1, 0));
  const Placement drop = over_the_board(shape, down);
  const auto face_up = [&](const SettleResult& r) { return (r.placements[0].rotation * face).y; };
  SettleOptions ignore;
  ignore.min_cut_face_up = -2;
  const SettleResult as_it_fell = settle_pieces({{&shape, 1000, drop, face}}, board, ignore);
  EXPECT_LT(face_up(as_it_fell), -0.9);
  EXPECT_EQ(as_it_fell.redrops, 0);
  const SettleResult r = settle_pieces({{&shape, 1000, drop, face}}, board, SettleOptions{});
  EXPECT_GE(r.redrops, 1);
  EXPECT_EQ(r.lost, 0);
  ASSERT_TRUE(r.placements[0].placed);
  EXPECT_GT(face_up(r), 0.9) << "dropped again with its cut face straight up, it lies on its back";
  // A piece without a face to show (a slice) lies as it fell.
  const SettleResult slice = settle_pieces({{&shape, 1000, drop}}, board, SettleOptions{});
  EXPECT_EQ(slice.redrops, 0);
  EXPECT_LT(face_up(slice), -0.9);
}

// A piece that rests with its cut face up but leaning away from the camera is spun about the
// vertical, where it lies, until the face leans towards the camera. A tomato's eighth lying on
// one of its sides shows the other leaning 45 degrees: with the camera on the side the face
// leans to, it is left as it lies.
TEST(PhysicsSettle, AFaceLeaningAwayFromTheCameraIsSpunTowardsIt) {
  const std::vector<ShadedMesh> wedges = pieces_of("tomato", "wedges:8");
  const CollisionShape shape = collision_shape(wedges[0]);
  // The eighth between 0 and 45 degrees: one side faces +Z, the other (-1, 0, -1) / sqrt 2.
  const glm::dvec3 side = flat_side(wedges[0]), face = glm::normalize(glm::dvec3(-1, 0, -1));
  ASSERT_EQ(side, glm::dvec3(0, 0, 1));
  Container board{ContainerType::Board, 0, 0.4, 0.4, 0.02};
  const glm::dquat on_side = glm::rotation(side, glm::dvec3(0, -1, 0));
  const Placement drop = over_the_board(shape, on_side);
  const auto normal = [&](const SettleResult& r) { return r.placements[0].rotation * face; };
  const SettleResult free = settle_pieces({{&shape, 1000, drop, face}}, board, SettleOptions{});
  const glm::dvec3 lean = normal(free);
  EXPECT_NEAR(lean.y, std::sqrt(0.5), 0.05);
  const glm::dvec2 away = -glm::normalize(glm::dvec2(lean.x, lean.z));
  const double up50 = std::sin(glm::radians(50.0)), out50 = std::cos(glm::radians(50.0));
  SettleOptions facing;  // a camera 50 degrees up on the side away from the lean
  facing.to_camera = glm::dvec3(away.x * out50, up50, away.y * out50);
  ASSERT_LT(glm::dot(lean, facing.to_camera), facing.min_cut_face_seen);
  const SettleResult r = settle_pieces({{&shape, 1000, drop, face}}, board, facing);
  EXPECT_GE(r.redrops, 1);
  EXPECT_EQ(r.lost, 0);
  EXPECT_GT(glm::dot(normal(r), facing.to_camera), 0.9);
  SettleOptions behind = facing;  // the camera on the side it leans to: nothing to do
  behind.to_camera = glm::dvec3(-away.x * out50, up50, -away.y * out50);
  const SettleResult b = settle_pieces({{&shape, 1000, drop, face}}, board, behind);
  EXPECT_EQ(b.redrops, 0);
  EXPECT_NEAR(glm::length(normal(b) - lean), 0.0, 1e-9);
}

// A piece resting over the board but hanging over its edge is moved, as it lies, to the
// freest ground where it does not: beside a neighbour, not onto it.
TEST(PhysicsSettle, APieceHangingOverTheEdgeMovesToFreeGround) {
  const std::vector<ShadedMesh> halves = pieces_of("tomato", "halves");
  const CollisionShape shape = collision_shape(halves[0]);
  const glm::dvec3 face = flat_side(halves[0]);
  Container board{ContainerType::Board, 0, 0.3, 0.2, 0.02};
  const glm::dquat up = glm::rotation(face, glm::dvec3(0, 1, 0));
  // One half where the other, face up with its centre just inside the right edge, would land
  // when dropped again a quarter of the way nearer the axis (the drop again of a piece that
  // left the board).
  const Placement middle = over_the_board(shape, up, 0.1), edge = over_the_board(shape, up, 0.14);
  const SettleResult r = settle_pieces({{&shape, 1000, middle, face}, {&shape, 1000, edge, face}},
                                       board, SettleOptions{});
  EXPECT_GE(r.redrops, 1);
  EXPECT_EQ(r.lost, 0);
  const auto centre = [&](size_t k) {
    return r.placements[k].translation + r.placements[k].rotation * shape.centroid;
  };
  const glm::dvec3 a = centre(0), b = centre(1);
  EXPECT_LT(std::fabs(b.x), 0.15);
  // Both rest on the board, neither on the other: their centres at the same height, apart.
  EXPECT_NEAR(a.y, b.y, 0.003);
  EXPECT_GT(glm::length(glm::dvec2(a.x - b.x, a.z - b.z)), 0.05);
}

/// The scene file's pieces, as placed: per instance (not the container, first, nor the
/// backdrop) its mesh in the scene frame.
std::vector<std::vector<glm::dvec3>> placed_points(const SceneAssets& assets) {
  std::vector<std::vector<glm::dvec3>> out;
  for (size_t k = 1; k < assets.instances.size(); ++k) {
    const AssetInstance& inst = assets.instances[k];
    if (inst.backdrop) continue;
    out.emplace_back();
    for (const glm::dvec3& p : assets.meshes[inst.mesh].position)
      out.back().push_back(inst.translation + inst.rotation * p);
  }
  return out;
}

TEST(PhysicsSettle, ScatterOnABoardPutsEveryPieceOnTheBoardApart) {
  const Scene scene = parse_scene_and_templates(R"(format: cutaway-scene/1
name: scatter
seed: 5
container: {type: board, width: 360, depth: 240, height: 20}
items:
  - template: tomato
    cut: {type: halves}
  - template: cucumber
    cut: {type: slices, thickness: 20}
    keep: 0.5
)",
                                                test::source_path("scenes/scatter.yaml").string());
  ASSERT_EQ(scene.items[0].arrange, Arrangement::Scatter);  // the board's default
  SceneStats stats;
  const SceneAssets assets = test::build_settled_scene(scene, CapColours::Vertex, &stats);
  const auto pieces = placed_points(assets);
  for (size_t k = 0; k < pieces.size(); ++k) {
    double low = 1;
    for (const glm::dvec3& q : pieces[k]) low = std::min(low, q.y);
    // On the board's top, not on another piece (which would lift it by 10 mm or more). A piece
    // rests on its collision hull, reduced to at most 128 corners and grown to enclose it: on
    // a tomato half's rounded skin the hull stands up to 1.5 mm proud of the mesh.
    EXPECT_NEAR(low, 0.02, 0.002) << assets.instances[k + 1].name;
  }
}

TEST(PhysicsSettle, FanOnAPlateLaysEachSliceOverThePreviousOne) {
  const Scene scene = parse_scene_and_templates(R"(format: cutaway-scene/1
name: fan
seed: 2
container: {type: plate, diameter: 280, height: 20}
arrange: fan
items:
  - template: cucumber
    cut: {type: slices, thickness: 10}
    keep: 0.5
)",
                                                test::source_path("scenes/fan.yaml").string());
  SceneStats stats;
  const SceneAssets assets = test::build_settled_scene(scene, CapColours::Vertex, &stats);
  ASSERT_GE(stats.placed, 4);
  // The row's direction: from one end of the row to the other (the two centres farthest
  // apart); the slices in row order, by their centres along it.
  const auto points = placed_points(assets);
  std::vector<glm::dvec3> centre;
  for (const auto& p : points) {
    glm::dvec3 c(0.0);
    for (const glm::dvec3& q : p) c += q;
    centre.push_back(c / static_cast<double>(p.size()));
  }
  glm::dvec3 row(1, 0, 0);
  double longest = 0;
  for (const glm::dvec3& a : centre)
    for (const glm::dvec3& b : centre)
      if (glm::length(b - a) > longest && glm::dot(b - a, glm::dvec3(1, 0, 1)) > 0) {
        longest = glm::length(b - a);
        row = glm::normalize(b - a);
      }
  std::map<double, std::vector<glm::dvec3>> by_position;  // by the centre along the row
  for (size_t k = 0; k < points.size(); ++k) by_position[glm::dot(centre[k], row)] = points[k];
  std::vector<std::pair<double, double>> extent;  // along the row
  std::vector<double> top;
  for (const auto& [position, p] : by_position) {
    double lo = 1e9, hi = -1e9, y = -1;
    for (const glm::dvec3& q : p) {
      lo = std::min(lo, glm::dot(q, row));
      hi = std::max(hi, glm::dot(q, row));
      y = std::max(y, q.y);
    }
    extent.emplace_back(lo, hi);
    top.push_back(y);
  }
  for (size_t k = 1; k < extent.size(); ++k) {
    // Consecutive slices overlap along the row, and each lies higher than the plate alone
    // would hold it: part of it rests on the one before. The row's last piece may be the
    // cucumber's rounded end, laid flat on its skin at the row's end, where it can roll off
    // the slice before it (seed 2 does since the portable libm changed Bullet's last bits):
    // it only has to lie beyond that slice.
    EXPECT_GT(extent[k].second, extent[k - 1].second) << "slice " << k;
    if (k + 1 < extent.size()) {
      EXPECT_LT(extent[k].first, extent[k - 1].second) << "slice " << k;
    }
  }
  // Not all flat on the plate: the slices resting on others stand higher than the lowest.
  EXPECT_GT(*std::max_element(top.begin(), top.end()),
            *std::min_element(top.begin(), top.end()) + 0.002);
}

/// The points of a 2 mm lattice in x and z that lie under the placed piece `points` (under one
/// of its triangles `triangles`, projected straight down).
std::set<std::pair<int, int>> lattice_under(const std::vector<glm::dvec3>& points,
                                            const std::vector<glm::uvec3>& triangles) {
  constexpr double step = 0.002;
  std::set<std::pair<int, int>> out;
  for (const glm::uvec3& t : triangles) {
    const glm::dvec2 a(points[t[0]].x, points[t[0]].z), b(points[t[1]].x, points[t[1]].z),
        c(points[t[2]].x, points[t[2]].z);
    const double det = (b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y);
    if (det == 0) continue;
    for (int i = static_cast<int>(std::ceil(std::min({a.x, b.x, c.x}) / step));
         i * step <= std::max({a.x, b.x, c.x}); ++i) {
      for (int j = static_cast<int>(std::ceil(std::min({a.y, b.y, c.y}) / step));
           j * step <= std::max({a.y, b.y, c.y}); ++j) {
        const glm::dvec2 q(i * step, j * step);
        const double u = ((b.x - q.x) * (c.y - q.y) - (c.x - q.x) * (b.y - q.y)) / det;
        const double v = ((c.x - q.x) * (a.y - q.y) - (a.x - q.x) * (c.y - q.y)) / det;
        if (u >= 0 && v >= 0 && u + v <= 1) out.insert({i, j});
      }
    }
  }
  return out;
}

TEST(PhysicsSettle, FanRowsOfSeveralObjectsLieSideBySideWithoutCrossing) {
  // Cucumber, tomato and kiwi slices fanned on a plate of 300 mm.
  const Scene scene = load_scene(test::source_path("scenes/plate.yaml").string());
  SceneStats stats;
  const SceneAssets assets = test::build_settled_scene(scene, CapColours::Vertex, &stats);
  // No point of the plate lies under pieces of two objects: every row keeps to its own ground.
  std::map<std::pair<int, int>, std::string> owner;  // lattice point -> object
  std::set<std::string> objects;
  int shared = 0;
  std::string example;
  const auto points = placed_points(assets);
  for (size_t k = 0; k < points.size(); ++k) {
    const std::string& name = assets.instances[k + 1].name;
    const std::string object = name.substr(0, name.find("_piece"));
    objects.insert(object);
    const AssetMesh& mesh = assets.meshes[assets.instances[k + 1].mesh];
    for (const auto& q : lattice_under(points[k], mesh.triangle)) {
      const auto [it, added] = owner.try_emplace(q, object);
      if (added || it->second == object) continue;
      ++shared;
      example = name + " over " + it->second;
    }
  }
  EXPECT_EQ(objects.size(), 3u);
  EXPECT_EQ(shared, 0) << example;
}

/// Pieces laid out on `container` as `arrange` asks (layout seed `seed`), each with its
/// collision shape: the bodies to settle (density 1000 kg/m^3; they point into `shapes`).
struct LaidOut {
  std::vector<CollisionShape> shapes;
  std::vector<SettleBody> bodies;
};
LaidOut laid_out(const std::vector<ShadedMesh>& pieces, Arrangement arrange,
                 const Container& container, uint64_t seed) {
  LaidOut out;
  std::vector<LayoutPiece> layout;
  for (const ShadedMesh& m : pieces) {
    out.shapes.push_back(collision_shape(m));
    layout.push_back({&m, {0, 1, 0}, arrange});
  }
  const std::vector<Placement> drops = layout_pieces(layout, container, LayoutOptions{}, seed);
  for (size_t k = 0; k < layout.size(); ++k) out.bodies.push_back({&out.shapes[k], 1000, drops[k]});
  return out;
}

// Pieces that have come to rest are frozen while the others settle on: with kiwi slices
// lying apart on a board and a tomato half dropped from 1.5 m in a corner, the slices are
// frozen while it falls and rolls, so the work (bodies simulated per step, summed) follows the
// moving piece; every piece ends placed, and at rest in the stability check, which frees every
// body again.
TEST(PhysicsSettle, RestedPiecesAreFrozenSoTheWorkFollowsTheMovingOnes) {
  const std::vector<ShadedMesh> slices = pieces_of("kiwi", "slices:10");
  const std::vector<ShadedMesh> halves = pieces_of("tomato", "halves");
  const CollisionShape half = collision_shape(halves[0]);
  Container board{ContainerType::Board, 0, 0.8, 0.8, 0.02};
  LaidOut laid = laid_out(slices, Arrangement::Scatter, board, 3);
  std::vector<SettleBody>& bodies = laid.bodies;
  bodies.push_back({&half, 1000, {true, glm::dquat(1, 0, 0, 0), glm::dvec3(0.3, 1.5, 0.3)}});
  SettleOptions whole;
  whole.freeze_after_s = 0;
  const SettleResult frozen = settle_pieces(bodies, board, SettleOptions{});
  const SettleResult free = settle_pieces(bodies, board, whole);
  for (const SettleResult* r : {&frozen, &free}) {
    EXPECT_EQ(r->lost, 0);
    EXPECT_TRUE(r->stable) << (r == &frozen ? "frozen " : "free ") << r->stability_motion_m;
    for (const Placement& p : r->placements) EXPECT_TRUE(p.placed);
  }
  std::printf("%zu pieces: %lld body steps with freezing, %lld without\n", bodies.size(),
              frozen.body_steps, free.body_steps);
  EXPECT_LT(static_cast<double>(frozen.body_steps), 0.67 * static_cast<double>(free.body_steps));
}

// When the last stability check does not pass, the layout of the check that moved least
// within the limit is kept (a later round of settling can unsettle a piece that rested), and the
// motion reported is that layout's own: checked again from the kept placements, with no
// settling first, it moves exactly as much. The rounds end early at a check that moved more
// than the kept one.
TEST(PhysicsSettle, TheKeptLayoutIsTheOneItsReportedCheckMeasured) {
  const std::vector<ShadedMesh> slices = pieces_of("kiwi", "slices:10");
  Container board{ContainerType::Board, 0, 0.3, 0.3, 0.02};
  LaidOut laid = laid_out(slices, Arrangement::Pile, board, 5);
  std::vector<SettleBody>& bodies = laid.bodies;
  SettleOptions options;
  options.check_motion_m = 0;  // no check passes
  options.max_verify_rounds = 6;
  const SettleResult r = settle_pieces(bodies, board, options);
  // Ended before the last round allowed, at a check that moved more than the kept one (the
  // kept layout's motion is checked again below).
  EXPECT_LT(r.verify_rounds, options.max_verify_rounds);
  EXPECT_GE(r.kept_round, 1);
  EXPECT_LT(r.kept_round, r.verify_rounds);
  ASSERT_TRUE(r.stable) << r.stability_motion_m;
  for (size_t k = 0; k < bodies.size(); ++k) bodies[k].drop = r.placements[k];
  SettleOptions check_only = options;
  check_only.max_seconds = 0;
  check_only.max_verify_rounds = 1;
  const SettleResult again = settle_pieces(bodies, board, check_only);
  EXPECT_EQ(again.kept_round, 1);
  EXPECT_EQ(again.stability_motion_m, r.stability_motion_m);
  std::printf("kept check %d of %d: %.3f mm\n", r.kept_round, r.verify_rounds,
              1000 * r.stability_motion_m);
}

// After a failed stability check only the pieces that moved in it, and their neighbours, settle
// on; the others stay where the check left them. Kiwi slices rest apart on a board and a
// tomato half falls from 40 cm in a corner; settling stops after a quarter second, while it
// still falls, so the first check fails. In the round of settling that follows only the tomato half
// moves: the work (bodies simulated per step) is its alone, and every slice ends within the
// pass mark of the layout the first check started from. With a gap that reaches every piece, every
// piece settles on. (The corner is the one farthest from the slices.)
TEST(PhysicsSettle, AfterAFailedCheckOnlyThePiecesNearTheMotionSettleOn) {
  const std::vector<ShadedMesh> slices = pieces_of("kiwi", "slices:10");
  const CollisionShape half = collision_shape(pieces_of("tomato", "halves")[0]);
  Container board{ContainerType::Board, 0, 0.8, 0.8, 0.02};
  LaidOut laid = laid_out(slices, Arrangement::Scatter, board, 3);
  std::vector<SettleBody>& bodies = laid.bodies;
  const size_t apart = bodies.size();
  const SettleResult rested = settle_pieces(bodies, board, SettleOptions{});
  for (size_t k = 0; k < apart; ++k) bodies[k].drop = rested.placements[k];
  // The corner farthest from the slices' centres (seen from above).
  std::vector<glm::dvec3> centres;
  for (size_t k = 0; k < apart; ++k) {
    glm::dvec3 centre(0.0);
    for (const glm::dvec3& p : slices[k].position) centre += p;
    centre /= static_cast<double>(slices[k].position.size());
    const Placement& at = rested.placements[k];
    centres.push_back(at.translation + at.rotation * centre);
  }
  glm::dvec3 corner(0.0);
  double farthest = -1;
  for (const glm::dvec3 c : {glm::dvec3(0.3, 0.4, 0.3), glm::dvec3(-0.3, 0.4, 0.3),
                             glm::dvec3(0.3, 0.4, -0.3), glm::dvec3(-0.3, 0.4, -0.3)}) {
    double nearest = 1e9;
    for (const glm::dvec3& centre : centres)
      nearest = std::min(nearest, std::hypot(centre.x - c.x, centre.z - c.z));
    if (nearest > farthest) std::tie(farthest, corner) = std::make_pair(nearest, c);
  }
  bodies.push_back({&half, 1000, {true, glm::dquat(1, 0, 0, 0), corner}});
  SettleOptions options;
  options.max_seconds = 0.25;   // the tomato half still falls when the first check starts
  options.stable_motion_m = 0;  // the last round's layout is returned
  options.max_verify_rounds = 1;
  const SettleResult first = settle_pieces(bodies, board, options);
  options.max_verify_rounds = 2;
  const SettleResult second = settle_pieces(bodies, board, options);
  SettleOptions everywhere = options;
  everywhere.resettle_gap_m = 10;
  const SettleResult all = settle_pieces(bodies, board, everywhere);
  ASSERT_EQ(second.verify_rounds, 2);
  const long long round_work = second.body_steps - first.body_steps;
  const long long round_work_everywhere = all.body_steps - first.body_steps;
  std::printf("%zu pieces: %lld body steps settling after the check, %lld with every piece\n",
              bodies.size(), round_work, round_work_everywhere);
  // At most one body a step (the steps counted also hold the second check's).
  EXPECT_LE(round_work, second.steps - first.steps);
  EXPECT_GT(round_work_everywhere, 2 * round_work);
  for (size_t k = 0; k < apart; ++k) {
    const double moved =
        glm::distance(second.placements[k].translation, first.placements[k].translation);
    EXPECT_LE(moved, options.check_motion_m) << "slice " << k;
  }
  EXPECT_GT(glm::distance(second.placements[apart].translation,
                          first.placements[apart].translation),
            0.01);
}

// The contacts of a step are computed on several threads (ordered_dispatcher.h) with the serial
// dispatcher's results: a pile of kiwi slices and tomato wedges in a bowl (tens of overlapping
// pairs a step, a compound bowl) settles to the same placements, to the bit, with one thread
// and with four.
TEST(PhysicsSettle, ContactsOnSeveralThreadsGiveTheSerialPlacements) {
  std::vector<ShadedMesh> pieces = pieces_of("kiwi", "slices:10");
  for (ShadedMesh& m : pieces_of("tomato", "wedges:6")) pieces.push_back(std::move(m));
  Container bowl{ContainerType::Bowl, 0.2, 0, 0, 0.07};
  const LaidOut laid = laid_out(pieces, Arrangement::Pile, bowl, 7);
  SettleOptions options;
  options.max_verify_rounds = 1;
  const auto settle_on = [&](int threads) {
    const oneapi::tbb::global_control limit(oneapi::tbb::global_control::max_allowed_parallelism,
                                            static_cast<size_t>(threads));
    return settle_pieces(laid.bodies, bowl, options);
  };
  const SettleResult serial = settle_on(1), parallel = settle_on(4);
  EXPECT_EQ(serial.steps, parallel.steps);
  EXPECT_EQ(serial.body_steps, parallel.body_steps);
  EXPECT_EQ(serial.stability_motion_m, parallel.stability_motion_m);
  ASSERT_EQ(serial.placements.size(), parallel.placements.size());
  for (size_t k = 0; k < serial.placements.size(); ++k) {
    const Placement &a = serial.placements[k], &b = parallel.placements[k];
    EXPECT_EQ(a.placed, b.placed) << k;
    for (int i = 0; i < 3; ++i) EXPECT_EQ(a.translation[i], b.translation[i]) << k;
    for (int i = 0; i < 4; ++i) EXPECT_EQ(a.rotation[i], b.rotation[i]) << k;
  }
}

}  // namespace
}  // namespace cutaway
