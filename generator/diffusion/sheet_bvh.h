// A bounding volume hierarchy over the triangles of the diffusion sheets, flat and in the
// layout a GPU traversal reads (render/gl/pmvc_gl.cpp, shaders/pmvc_trace.comp): the ray-casting
// acceleration structure of the gl PMVC backend, where Embree serves the cpu backend.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "diffusion/diffusion_sheets.h"

namespace cutaway {

/// One triangle of one sheet.
struct SheetTriangleRef {
  uint32_t sheet = 0;     ///< index into the sheets
  uint32_t triangle = 0;  ///< index into that sheet's triangles
};

/// A binary BVH over every sheet triangle, nodes in one array (node 0 the root). 32 bytes a
/// node, as a std430 `struct { vec3 lo; int first; vec3 hi; int count; }`.
struct SheetBvh {
  struct Node {
    glm::vec3 lo;       ///< box minimum, metres
    int32_t first = 0;  ///< inner node: index of its first child (the second is first + 1);
                        ///< leaf: index of its first triangle in `triangles`
    glm::vec3 hi;       ///< box maximum, metres
    int32_t count = 0;  ///< leaf: its number of triangles (>= 1); inner node: 0
  };
  std::vector<Node> nodes;
  std::vector<SheetTriangleRef> triangles;  ///< every sheet triangle once, in leaf order
  int depth = 0;  ///< nodes on the longest path from the root to a leaf (0: no nodes)
};

/// Builds the BVH top down with the surface area heuristic over 16 bins of triangle centroids
/// per axis (Wald 2007, "On fast construction of SAH-based bounding volume hierarchies"): a
/// node becomes a leaf when it holds at most 4 triangles or no split is cheaper than the leaf
/// (traversal step cost 1, intersection cost 1). Where every centroid of a node coincides on
/// all three axes, it is split in the middle of its triangles in sheet order. Deterministic:
/// the result depends only on the sheets.
/// @returns a BVH with no nodes when the sheets have no triangles
SheetBvh build_sheet_bvh(const std::vector<DiffusionSheet>& sheets);

}  // namespace cutaway
