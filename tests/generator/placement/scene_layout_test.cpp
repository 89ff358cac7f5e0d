// Settled scenes (doc/algorithms.md §4) checked independently of the physics that makes them:
// no piece cuts into another or into the container deeper than the stated tolerance (CGAL:
// surface intersection, then the depth of each vertex of one inside the other), every piece
// rests on something (moved 4 mm straight down it would hit the container or another piece),
// a bowl of 60 pieces forms a pile that stays put when simulated again, a board with more
// pieces than free ground heaps them instead of leaving any out, and the pieces of one object
// arranged together lie side by side.
#include <cmath>
#include <limits>
#include <map>
#include <tuple>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/intersection.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "io/scene_parser.h"
#include "placement/container_mesh.h"
#include "placement/scene_layout.h"
#include "scene/scene_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

/// The instance's mesh in the scene frame, vertices welded by exact position, moved by `shift`.
Mesh placed_mesh(const SceneAssets& assets, const AssetInstance& inst,
                 glm::dvec3 shift = glm::dvec3(0.0)) {
  const AssetMesh& m = assets.meshes[inst.mesh];
  Mesh out;
  std::map<std::tuple<double, double, double>, Mesh::Vertex_index> welded;
  std::vector<Mesh::Vertex_index> id(m.position.size());
  for (size_t i = 0; i < m.position.size(); ++i) {
    const glm::dvec3 p = inst.translation + inst.rotation * m.position[i] + shift;
    auto [it, added] = welded.emplace(std::make_tuple(p.x, p.y, p.z), Mesh::Vertex_index());
    if (added) it->second = out.add_vertex(K::Point_3(p.x, p.y, p.z));
    id[i] = it->second;
  }
  for (const glm::uvec3& t : m.triangle) {
    if (id[t[0]] == id[t[1]] || id[t[1]] == id[t[2]] || id[t[0]] == id[t[2]]) continue;
    out.add_face(id[t[0]], id[t[1]], id[t[2]]);
  }
  return out;
}

/// Pieces may touch within this: Bullet keeps bodies apart up to its solver's slop, and a
/// collision hull encloses its piece only to within its margin (physics_settle.h).
constexpr double kPenetrationTolerance_m = 0.0005;

/// How deep `a` reaches into the closed mesh `b`: the largest distance to b's surface of a
/// vertex of a inside b (0 if none). Metres.
double depth_inside(const Mesh& a, const Mesh& b) {
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
  Tree tree(faces(b).first, faces(b).second, b);
  tree.accelerate_distance_queries();
  const CGAL::Side_of_triangle_mesh<Mesh, K> side(tree);
  double deepest = 0;
  for (const auto v : a.vertices()) {
    if (side(a.point(v)) != CGAL::ON_BOUNDED_SIDE) continue;
    deepest = std::max(deepest, std::sqrt(CGAL::to_double(tree.squared_distance(a.point(v)))));
  }
  return deepest;
}

/// Whether piece `a` (pieces[a], instance a + 1 of `assets`), moved by `offset` (metres),
/// intersects the container or another piece.
bool touches(const SceneAssets& assets, size_t a, const glm::dvec3& offset, const Mesh& container,
             const std::vector<Mesh>& pieces) {
  const Mesh moved = placed_mesh(assets, assets.instances[a + 1], offset);
  if (PMP::do_intersect(moved, container)) return true;
  for (size_t b = 0; b < pieces.size(); ++b)
    if (b != a && PMP::do_intersect(moved, pieces[b],
                                    CGAL::parameters::do_overlap_test_of_bounded_sides(true),
                                    CGAL::parameters::do_overlap_test_of_bounded_sides(true)))
      return true;
  return false;
}

/// The unit direction from piece `a`'s vertex nearest to another piece or the container to
/// that nearest point, when it points down (zero otherwise, or when nothing is near).
glm::dvec3 nearest_support_below(const std::vector<Mesh>& pieces, size_t a, const Mesh& container) {
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
  double nearest = std::numeric_limits<double>::infinity();
  glm::dvec3 direction(0.0);
  for (size_t b = 0; b <= pieces.size(); ++b) {
    if (b == a) continue;
    const Mesh& other = b < pieces.size() ? pieces[b] : container;
    Tree tree(faces(other).first, faces(other).second, other);
    tree.accelerate_distance_queries();
    for (const auto v : pieces[a].vertices()) {
      const K::Point_3 p = pieces[a].point(v), q = tree.closest_point(p);
      const double d = std::sqrt(CGAL::to_double(CGAL::squared_distance(p, q)));
      if (d < nearest && d > 0) {
        nearest = d;
        direction = glm::dvec3(CGAL::to_double(q.x() - p.x()), CGAL::to_double(q.y() - p.y()),
                               CGAL::to_double(q.z() - p.z())) /
                    d;
      }
    }
  }
  return direction.y < 0 ? direction : glm::dvec3(0.0);
}

/// The placed pieces of `assets` (its first instance the container; the backdrop skipped),
/// checked: closed; no
/// two pieces, and no piece and the container, overlap deeper than kPenetrationTolerance_m;
/// each piece, 4 mm lower, would hit the container or another piece.
std::vector<Mesh> check_resting_pieces(const SceneAssets& assets) {
  const Mesh container = placed_mesh(assets, assets.instances.front());
  std::vector<Mesh> pieces;
  for (size_t k = 1; k < assets.instances.size(); ++k) {
    if (assets.instances[k].backdrop) continue;
    pieces.push_back(placed_mesh(assets, assets.instances[k]));
    EXPECT_TRUE(CGAL::is_closed(pieces.back())) << assets.instances[k].name;
  }
  for (size_t a = 0; a < pieces.size(); ++a) {
    const std::string& name_a = assets.instances[a + 1].name;
    if (PMP::do_intersect(pieces[a], container)) {
      EXPECT_LE(depth_inside(pieces[a], container), kPenetrationTolerance_m)
          << name_a << " cuts into the container";
    }
    for (size_t b = a + 1; b < pieces.size(); ++b) {
      if (!PMP::do_intersect(pieces[a], pieces[b],
                             CGAL::parameters::do_overlap_test_of_bounded_sides(true),
                             CGAL::parameters::do_overlap_test_of_bounded_sides(true)))
        continue;
      EXPECT_LE(std::max(depth_inside(pieces[a], pieces[b]), depth_inside(pieces[b], pieces[a])),
                kPenetrationTolerance_m)
          << name_a << " and " << assets.instances[b + 1].name;
    }
  }
  for (size_t a = 0; a < pieces.size(); ++a) {
    // Resting: 4 mm lower it would hit the container or another piece; or, leaning on a
    // slope (where a vertical drop slides past the hull standing proud of the mesh), 4 mm
    // towards the nearest point of what lies below it.
    bool hits = touches(assets, a, glm::dvec3(0, -0.004, 0), container, pieces);
    if (!hits) {
      const glm::dvec3 towards = nearest_support_below(pieces, a, container);
      hits = glm::length(towards) > 0 && touches(assets, a, 0.004 * towards, container, pieces);
    }
    EXPECT_TRUE(hits) << assets.instances[a + 1].name << " floats";
  }
  return pieces;
}

TEST(SceneLayout, TheOverhangIsTheDistanceBeyondTheRestingArea) {
  const Container board{ContainerType::Board, 0, 0.4, 0.2, 0.02};
  EXPECT_EQ(resting_overhang(board, 0.19, -0.09, 0), 0.0);
  EXPECT_DOUBLE_EQ(resting_overhang(board, 0.25, 0.0, 0), 0.05);
  EXPECT_DOUBLE_EQ(resting_overhang(board, -0.25, 0.15, 0), std::hypot(0.05, 0.05));
  const Container plate{ContainerType::Plate, 0.3, 0, 0, 0.02};
  EXPECT_EQ(resting_overhang(plate, 0.1, 0.1, 0), 0.0);
  EXPECT_DOUBLE_EQ(resting_overhang(plate, 0.0, -0.2, 0), 0.05);
  // A bowl's resting area ends at its inner rim: the wall (3 % of the diameter) inside the rim.
  const Container bowl{ContainerType::Bowl, 0.3, 0, 0, 0.1};
  EXPECT_NEAR(resting_overhang(bowl, 0.15, 0.0, 0), 0.009, 1e-12);
  const Container none{};
  EXPECT_NEAR(resting_overhang(none, 0.0, 0.3, 0.2), 0.1, 1e-12);
  // Over the area exactly where rest_height gives a height.
  for (const Container& c : {board, plate, bowl}) {
    for (double x = -0.3; x <= 0.3; x += 0.0137) {
      EXPECT_EQ(resting_overhang(c, x, 0.05, 0) == 0, rest_height(c, x, 0.05, 0).has_value())
          << static_cast<int>(c.type) << " " << x;
    }
  }
}

TEST(SceneLayout, PiecesRestWithoutInterpenetrating) {
  const Scene scene = load_scene(test::source_path("tests/data/scenes/tiny.yaml").string());
  SceneStats stats;
  const SceneAssets assets = test::build_settled_scene(scene, CapColours::Texture, &stats);
  ASSERT_GE(stats.placed, 7);
  ASSERT_EQ(assets.instances.front().name, "bowl");
  check_resting_pieces(assets);
}

TEST(SceneLayout, SixtyPiecesInABowlFormAStablePile) {
  // 4 cucumbers in 10 mm slices: 64 pieces, each 10 mm thick, in a 200 mm bowl.
  const Scene scene = parse_scene_and_templates(R"(format: cutaway-scene/1
name: pile
seed: 3
container: {type: bowl, diameter: 200, height: 70}
items:
  - template: cucumber
    count: 4
    cut: {type: slices, thickness: 10}
)",
                                                test::source_path("scenes/pile.yaml").string());
  // Every piece placed, none lost, and the stability check: re-simulated for 1 s in a new
  // world, no corner moves 1 mm.
  SceneStats stats;
  const SceneAssets assets = test::build_settled_scene(scene, CapColours::Vertex, &stats);
  ASSERT_GE(stats.pieces, 60);
  const std::vector<Mesh> pieces = check_resting_pieces(assets);
  // Resting on others: the lowest point well above the bowl's surface under it. The pile: its
  // top at least two slice thicknesses above the bowl's floor.
  const double floor = *rest_height(scene.container, 0, 0, 0);
  int on_others = 0;
  double top = floor;
  for (const Mesh& m : pieces) {
    K::Point_3 low = m.point(*m.vertices().begin());
    for (const auto v : m.vertices()) {
      if (m.point(v).y() < low.y()) low = m.point(v);
      top = std::max(top, m.point(v).y());
    }
    const auto under = rest_height(scene.container, low.x(), low.z(), 0);
    if (under && low.y() > *under + 0.003) ++on_others;
  }
  EXPECT_GE(on_others, 10);
  EXPECT_GE(top - floor, 2 * 0.010);
}

/// A closed box of `size` (metres) centred on the origin, as a piece's mesh.
ShadedMesh box(const glm::dvec3& size) {
  ShadedMesh m;
  for (int k = 0; k < 8; ++k) {
    m.position.push_back(0.5 * size * glm::dvec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1));
    m.normal.push_back(glm::normalize(m.position.back()));
    m.colour.push_back(glm::dvec3(0.5));
  }
  m.triangle = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
  return m;
}

TEST(SceneLayout, ACrowdedBoardHeapsEveryPieceInsteadOfLeavingOut) {
  // 60 blocks of 30 x 20 x 30 mm, scattered and fanned, on a board of 120 x 120 mm: about 16
  // fit side by side; the others must heap on them, none left out.
  const ShadedMesh block = box({0.03, 0.02, 0.03});
  std::vector<LayoutPiece> pieces(60);
  for (size_t p = 0; p < pieces.size(); ++p) {
    pieces[p].mesh = &block;
    pieces[p].cap_normal = {0, 1, 0};
    pieces[p].arrange = p % 3 == 0 ? Arrangement::Fan : Arrangement::Scatter;
    pieces[p].group = static_cast<int>(p % 2);
    pieces[p].rank = static_cast<int>(p);
  }
  Container board;
  board.type = ContainerType::Board;
  board.width_m = board.depth_m = 0.12;
  board.height_m = 0.02;
  const std::vector<Placement> out = layout_pieces(pieces, board, LayoutOptions{}, 7);
  int heaped = 0;
  for (const Placement& p : out) {
    ASSERT_TRUE(p.placed);
    if (p.translation.y > board.height_m + 0.025) ++heaped;  // over another block
  }
  EXPECT_GE(heaped, 20);
}

// Six objects cut in two (blocks of 40 x 20 x 30 mm), their pieces interleaved as the scene's
// seeded order mixes them, arranged `together` on a board of 600 x 450 mm: each piece's nearest
// neighbour is the other piece of its own object. Scattered instead, fewer than half of them
// have it nearest.
TEST(SceneLayout, TogetherLaysThePiecesOfAnObjectSideBySide) {
  const ShadedMesh block = box({0.04, 0.02, 0.03});
  const LayoutOptions options;
  Container board;
  board.type = ContainerType::Board;
  board.width_m = 0.6;
  board.depth_m = 0.45;
  board.height_m = 0.02;
  const auto mates_nearest = [&](bool grouped) {
    std::vector<LayoutPiece> pieces(12);
    for (size_t p = 0; p < pieces.size(); ++p) {
      pieces[p].mesh = &block;
      pieces[p].cap_normal = {0, 1, 0};
      pieces[p].arrange = grouped ? Arrangement::Together : Arrangement::Scatter;
      pieces[p].group = static_cast<int>(p % 6);  // object p % 6
    }
    const std::vector<Placement> out = layout_pieces(pieces, board, options, 21);
    std::vector<glm::dvec3> centre;
    for (const Placement& p : out) {
      EXPECT_TRUE(p.placed);
      glm::dvec3 c(0.0);
      for (const glm::dvec3& v : block.position) c += p.translation + p.rotation * v;
      centre.push_back(c / static_cast<double>(block.position.size()));
    }
    int count = 0;
    for (size_t p = 0; p < centre.size(); ++p) {
      size_t nearest = p;
      for (size_t q = 0; q < centre.size(); ++q) {
        if (q != p && (nearest == p || glm::distance(centre[p], centre[q]) <
                                           glm::distance(centre[p], centre[nearest])))
          nearest = q;
      }
      count += nearest % 6 == p % 6;
    }
    return count;
  };
  EXPECT_EQ(mates_nearest(true), 12);
  EXPECT_LT(mates_nearest(false), 6);
}

}  // namespace
}  // namespace cutaway
