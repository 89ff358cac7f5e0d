// Binned SAH BVH over the diffusion sheets (sheet_bvh.h).
#include "diffusion/sheet_bvh.h"

#include <algorithm>
#include <array>
#include <limits>

#include <glm/common.hpp>

namespace cutaway {
namespace {

constexpr int kBins = 16;
constexpr size_t kLeafSize = 4;

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::max()};
  glm::vec3 hi{-std::numeric_limits<float>::max()};
  void grow(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  void grow(const Box& b) {
    lo = glm::min(lo, b.lo);
    hi = glm::max(hi, b.hi);
  }
  bool empty() const { return lo.x > hi.x; }
  /// Half the surface area (enough for the heuristic's ratios); 0 for an empty box.
  float area() const {
    if (empty()) return 0;
    const glm::vec3 e = hi - lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

/// A triangle while building: its box and centroid.
struct Item {
  SheetTriangleRef ref;
  Box box;
  glm::vec3 centroid;
};

/// The best binned SAH split of items[begin, end): axis and bin boundary (items with bin <
/// `bin` go left), or axis -1 when no split beats a leaf.
struct Split {
  int axis = -1;
  int bin = 0;
};

Split best_split(const std::vector<Item>& items, size_t begin, size_t end, const Box& centroids,
                 const Box& bounds) {
  Split best;
  const auto count = static_cast<float>(end - begin);
  float best_cost = count;  // the leaf: one intersection per triangle
  for (int axis = 0; axis < 3; ++axis) {
    const float lo = centroids.lo[axis], extent = centroids.hi[axis] - lo;
    if (!(extent > 0)) continue;
    std::array<Box, kBins> bin_box;
    std::array<size_t, kBins> bin_count{};
    for (size_t i = begin; i < end; ++i) {
      const int b =
          std::min(kBins - 1, static_cast<int>(kBins * (items[i].centroid[axis] - lo) / extent));
      bin_box[b].grow(items[i].box);
      ++bin_count[b];
    }
    // Right-to-left sweep of areas and counts, then left to right.
    std::array<float, kBins> right_area{};
    std::array<size_t, kBins> right_count{};
    Box right;
    size_t n = 0;
    for (int b = kBins - 1; b > 0; --b) {
      right.grow(bin_box[b]);
      n += bin_count[b];
      right_area[b] = right.area();
      right_count[b] = n;
    }
    Box left;
    size_t m = 0;
    for (int b = 1; b < kBins; ++b) {
      left.grow(bin_box[b - 1]);
      m += bin_count[b - 1];
      if (m == 0 || right_count[b] == 0) continue;
      const float cost = 1.0f + (left.area() * static_cast<float>(m) +
                                 right_area[b] * static_cast<float>(right_count[b])) /
                                    bounds.area();
      if (cost < best_cost) {
        best_cost = cost;
        best = {axis, b};
      }
    }
  }
  return best;
}

}  // namespace

SheetBvh build_sheet_bvh(const std::vector<DiffusionSheet>& sheets) {
  std::vector<Item> items;
  for (size_t s = 0; s < sheets.size(); ++s) {
    for (size_t t = 0; t < sheets[s].triangle.size(); ++t) {
      Item item{{static_cast<uint32_t>(s), static_cast<uint32_t>(t)}, {}, {}};
      for (int k = 0; k < 3; ++k) item.box.grow(sheets[s].position[sheets[s].triangle[t][k]]);
      item.centroid = 0.5f * (item.box.lo + item.box.hi);
      items.push_back(item);
    }
  }
  SheetBvh bvh;
  if (items.empty()) return bvh;
  struct Task {
    int node;
    size_t begin, end;
    int depth;  // of the node: the root is 1
  };
  bvh.nodes.emplace_back();
  std::vector<Task> tasks{{0, 0, items.size(), 1}};
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    bvh.depth = std::max(bvh.depth, task.depth);
    Box bounds, centroids;
    for (size_t i = task.begin; i < task.end; ++i) {
      bounds.grow(items[i].box);
      centroids.grow(items[i].centroid);
    }
    bvh.nodes[task.node].lo = bounds.lo;
    bvh.nodes[task.node].hi = bounds.hi;
    const size_t count = task.end - task.begin;
    size_t middle = task.begin;
    if (count > kLeafSize) {
      const Split split = best_split(items, task.begin, task.end, centroids, bounds);
      if (split.axis >= 0) {
        const float lo = centroids.lo[split.axis];
        const float extent = centroids.hi[split.axis] - lo;
        middle = static_cast<size_t>(
            std::stable_partition(items.begin() + static_cast<std::ptrdiff_t>(task.begin),
                                  items.begin() + static_cast<std::ptrdiff_t>(task.end),
                                  [&](const Item& item) {
                                    return std::min(kBins - 1,
                                                    static_cast<int>(
                                                        kBins * (item.centroid[split.axis] - lo) /
                                                        extent)) < split.bin;
                                  }) -
            items.begin());
      } else if (centroids.lo == centroids.hi) {
        middle = task.begin + count / 2;  // coincident centroids: split by order
      }
    }
    if (middle == task.begin || middle == task.end) {  // a leaf
      bvh.nodes[task.node].first = static_cast<int32_t>(task.begin);
      bvh.nodes[task.node].count = static_cast<int32_t>(count);
      continue;
    }
    const auto child = static_cast<int32_t>(bvh.nodes.size());
    bvh.nodes[task.node].first = child;
    bvh.nodes[task.node].count = 0;
    bvh.nodes.emplace_back();
    bvh.nodes.emplace_back();
    tasks.push_back({child + 1, middle, task.end, task.depth + 1});
    tasks.push_back({child, task.begin, middle, task.depth + 1});
  }
  bvh.triangles.reserve(items.size());
  for (const Item& item : items) bvh.triangles.push_back(item.ref);
  return bvh;
}

}  // namespace cutaway
