// Scene layout (doc/algorithms.md §4) checked independently of the height field that makes
// it: no two placed pieces intersect (CGAL's surface and bounded-side tests on the welded piece
// meshes), no piece cuts into the container, and every piece rests on something (moved 4 mm
// down, and at most one and a half height-field cells sideways, it would hit the container or
// another piece).
#include <map>
#include <tuple>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/intersection.h>
#include <CGAL/Surface_mesh.h>
#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "diffusion/diffusion.h"
#include "scene_builder.h"
#include "scene_parser.h"
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

TEST(SceneLayout, PiecesRestWithoutInterpenetrating) {
  const Scene scene = load_scene(test::source_path("tests/data/scenes/tiny.yaml").string());
  SceneBuildOptions options;
  options.diffusion = [](const DsModel& model) { return make_cpu_diffusion(model, {4, 0}); };
  SceneStats stats;
  const SceneAssets assets = build_scene(scene, scene.seed, options, &stats);
  EXPECT_EQ(stats.placed, stats.pieces);
  ASSERT_GE(stats.placed, 7);
  ASSERT_EQ(assets.instances.front().name, "bowl");

  const Mesh bowl = placed_mesh(assets, assets.instances.front());
  std::vector<Mesh> pieces;
  for (size_t k = 1; k < assets.instances.size(); ++k) {
    pieces.push_back(placed_mesh(assets, assets.instances[k]));
    ASSERT_TRUE(CGAL::is_closed(pieces.back())) << assets.instances[k].name;
  }
  for (size_t a = 0; a < pieces.size(); ++a) {
    EXPECT_FALSE(PMP::do_intersect(pieces[a], bowl)) << assets.instances[a + 1].name;
    for (size_t b = a + 1; b < pieces.size(); ++b) {
      EXPECT_FALSE(PMP::do_intersect(pieces[a], pieces[b],
                                     CGAL::parameters::do_overlap_test_of_bounded_sides(true),
                                     CGAL::parameters::do_overlap_test_of_bounded_sides(true)))
          << assets.instances[a + 1].name << " and " << assets.instances[b + 1].name;
    }
  }
  // Resting: 4 mm lower, each piece would hit the bowl or a piece. The pile is a height field
  // of 1 mm cells, so a piece may rest on a neighbour up to a cell away sideways: the drop
  // also tries 1.5 mm shifts in x and z.
  const double cell = LayoutOptions{}.cell_m * 1.5;
  for (size_t a = 0; a < pieces.size(); ++a) {
    bool hits = false;
    for (const glm::dvec3 side : {glm::dvec3(0, 0, 0), glm::dvec3(cell, 0, 0),
                                  glm::dvec3(-cell, 0, 0), glm::dvec3(0, 0, cell),
                                  glm::dvec3(0, 0, -cell)}) {
      const Mesh dropped =
          placed_mesh(assets, assets.instances[a + 1], side - glm::dvec3(0, 0.004, 0));
      hits = hits || PMP::do_intersect(dropped, bowl);
      for (size_t b = 0; b < pieces.size() && !hits; ++b)
        hits = b != a &&
               PMP::do_intersect(dropped, pieces[b],
                                 CGAL::parameters::do_overlap_test_of_bounded_sides(true),
                                 CGAL::parameters::do_overlap_test_of_bounded_sides(true));
    }
    EXPECT_TRUE(hits) << assets.instances[a + 1].name << " floats";
  }
}

}  // namespace
}  // namespace cutaway
