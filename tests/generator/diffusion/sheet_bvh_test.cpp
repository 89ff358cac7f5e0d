// The BVH of the gl PMVC backend (generator/diffusion/sheet_bvh.h): every triangle in exactly
// one leaf, boxes that hold what is below them, a depth the GPU traversal can walk, and the same
// tree from the same sheets.
#include <algorithm>
#include <set>
#include <utility>

#include <gtest/gtest.h>

#include "diffusion/diffusion_sheets.h"
#include "diffusion/sheet_bvh.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

bool contains(const SheetBvh::Node& outer, const glm::vec3& lo, const glm::vec3& hi) {
  return glm::all(glm::lessThanEqual(outer.lo, lo)) && glm::all(glm::lessThanEqual(hi, outer.hi));
}

/// Walks the tree: every node reached once, leaves cover `triangles` exactly once, every box
/// holds its children's boxes or its triangles' vertices.
void check_structure(const SheetBvh& bvh, const std::vector<DiffusionSheet>& sheets) {
  size_t total = 0;
  for (const DiffusionSheet& s : sheets) total += s.triangle.size();
  ASSERT_EQ(bvh.triangles.size(), total);
  std::set<std::pair<uint32_t, uint32_t>> refs;
  for (const SheetTriangleRef& r : bvh.triangles) refs.insert({r.sheet, r.triangle});
  EXPECT_EQ(refs.size(), total) << "a triangle is in the BVH twice";
  std::vector<int> covered(bvh.triangles.size(), 0), reached(bvh.nodes.size(), 0);
  std::vector<std::pair<int, int>> stack{{0, 1}};  // node, depth
  int depth = 0;
  while (!stack.empty()) {
    const auto [i, d] = stack.back();
    stack.pop_back();
    ++reached[i];
    depth = std::max(depth, d);
    const SheetBvh::Node& n = bvh.nodes[i];
    if (n.count > 0) {
      for (int k = n.first; k < n.first + n.count; ++k) {
        ++covered[k];
        const SheetTriangleRef r = bvh.triangles[k];
        for (int c = 0; c < 3; ++c) {
          const glm::vec3 p = sheets[r.sheet].position[sheets[r.sheet].triangle[r.triangle][c]];
          ASSERT_TRUE(contains(n, p, p)) << "leaf " << i << " misses a vertex";
        }
      }
    } else {
      ASSERT_GT(n.first, i);
      ASSERT_LT(n.first + 1, static_cast<int>(bvh.nodes.size()));
      for (int c = n.first; c <= n.first + 1; ++c) {
        ASSERT_TRUE(contains(n, bvh.nodes[c].lo, bvh.nodes[c].hi)) << "node " << i;
        stack.push_back({c, d + 1});
      }
    }
  }
  EXPECT_TRUE(std::all_of(covered.begin(), covered.end(), [](int c) { return c == 1; }));
  EXPECT_TRUE(std::all_of(reached.begin(), reached.end(), [](int c) { return c == 1; }));
  EXPECT_EQ(depth, bvh.depth);
}

TEST(SheetBvh, CoversEveryTomatoTriangleOnceInNestedBoxes) {
  const DsModel model =
      build_model(load_template(test::source_path("templates/tomato.yaml").string()));
  const std::vector<DiffusionSheet> sheets = make_diffusion_sheets(model);
  const SheetBvh bvh = build_sheet_bvh(sheets);
  check_structure(bvh, sheets);
  // SAH trees of ~60k triangles: far shallower than the shader's stack of 64, with small leaves.
  EXPECT_LE(bvh.depth, 40);
  size_t leaves = 0;
  for (const SheetBvh::Node& n : bvh.nodes) leaves += n.count > 0;
  EXPECT_LE(static_cast<double>(bvh.triangles.size()) / leaves, 4.0);
  // The same sheets give the same tree.
  const SheetBvh again = build_sheet_bvh(sheets);
  ASSERT_EQ(again.nodes.size(), bvh.nodes.size());
  for (size_t i = 0; i < bvh.nodes.size(); ++i) {
    EXPECT_EQ(again.nodes[i].first, bvh.nodes[i].first);
    EXPECT_EQ(again.nodes[i].count, bvh.nodes[i].count);
  }
}

TEST(SheetBvh, CoincidentTrianglesAndNoTrianglesAreHandled) {
  DiffusionSheet s;
  s.position = {{0, 0, 0}, {1e-3f, 0, 0}, {0, 1e-3f, 0}};
  s.triangle.assign(37, glm::uvec3(0, 1, 2));  // 37 copies: one centroid, no SAH split
  s.face_normal.assign(37, glm::vec3(0, 0, 1));
  const std::vector<DiffusionSheet> sheets{s};
  const SheetBvh bvh = build_sheet_bvh(sheets);
  check_structure(bvh, sheets);
  for (const SheetBvh::Node& n : bvh.nodes) EXPECT_LE(n.count, 4);
  EXPECT_TRUE(build_sheet_bvh({}).nodes.empty());
  EXPECT_EQ(build_sheet_bvh({}).depth, 0);
}

}  // namespace
}  // namespace cutaway
