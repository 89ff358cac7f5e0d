// Whether a small mesh (a grain) touches or crosses any of a set of DS surfaces: CGAL's AABB
// tree over the surfaces' triangles, queried triangle by triangle with exact predicates.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "model/ds_model.h"

namespace cutaway {

/// Crossing tests against a fixed set of surfaces, their tree built once.
class CrossingTest {
 public:
  /// @param surfaces  the meshes to test against (their triangles are copied); crossed()
  ///                  answers with an index into this list
  explicit CrossingTest(const std::vector<const DsMesh*>& surfaces);
  ~CrossingTest();
  CrossingTest(const CrossingTest&) = delete;
  CrossingTest& operator=(const CrossingTest&) = delete;

  /// The index of a surface that one of `triangles` (metres, the surfaces' frame) touches or
  /// crosses (exact triangle-triangle predicates, CGAL Epick), or -1 where none does. A mesh
  /// wholly inside or outside every surface crosses none.
  int crossed(const std::vector<std::array<glm::dvec3, 3>>& triangles) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cutaway
