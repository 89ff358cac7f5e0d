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
  /// @param with_blur_sheets also test against the two sheets a blurred surface shows the
  ///                  diffusion (diffusion_sheets.h: each vertex moved by its blur along the
  ///                  vertex normal, both ways), answered as the surface's index: a closed
  ///                  grain that one of them passes through is coloured by it from inside
  explicit CrossingTest(const std::vector<const DsMesh*>& surfaces, bool with_blur_sheets = false);
  ~CrossingTest();
  CrossingTest(const CrossingTest&) = delete;
  CrossingTest& operator=(const CrossingTest&) = delete;

  /// The index of a surface that one of `triangles` (metres, the surfaces' frame) touches or
  /// crosses (exact triangle-triangle predicates, CGAL Epick), or -1 where none does. A mesh
  /// wholly inside or outside every surface crosses none.
  int crossed(const std::vector<std::array<glm::dvec3, 3>>& triangles) const;

  /// The distance (metres) from `p` to the nearest triangle (a surface's or, with
  /// with_blur_sheets, one of its sheets') and that surface's index; {infinity, -1} when there
  /// are none. A mesh all of whose points lie closer to p than that touches no triangle (the
  /// grains' quick accept, before crossed()).
  struct Nearest {
    double distance;
    int surface;
  };
  Nearest nearest(const glm::dvec3& p) const;

  /// With with_blur_sheets: whether `p` (metres) lies closer to a blurred surface than that
  /// surface's blur (the largest of the nearby triangle's corners'), i.e. between its two
  /// sheets, where a grain wholly inside would cross none of them and still be coloured by
  /// the blur's sheets from inside. Always false without with_blur_sheets.
  bool within_blur(const glm::dvec3& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace cutaway
