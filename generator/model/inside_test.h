// Which side of a closed DS surface a point lies on, and which surfaces a closed surface
// encloses (CGAL's Side_of_triangle_mesh: exact predicates over an AABB tree).
#pragma once

#include <cstddef>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>

#include "model/ds_model.h"

namespace cutaway {

/// Point-in-surface tests against one closed DS surface, its tree built once.
class InsideTest {
 public:
  /// @param mesh  closed (no boundary edge); its triangles are copied
  explicit InsideTest(const DsMesh& mesh);
  ~InsideTest();
  InsideTest(const InsideTest&) = delete;
  InsideTest& operator=(const InsideTest&) = delete;

  /// Whether `p` (metres, the mesh's frame) lies strictly inside the surface (a point on it
  /// does not).
  bool inside(const glm::dvec3& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Whether the DS surface has no boundary edge (every edge has a triangle on both sides).
bool closed_surface(const DsMesh& mesh);

/// The surfaces of `model` other than `s` whose first vertex lies inside surface s (those it
/// encloses, when no surface crosses it: check_model), in surface order; none when s is not
/// closed.
std::vector<size_t> surfaces_inside(const DsModel& model, size_t s);

/// The same with surface s's InsideTest already built (`test`), for a caller that tests more
/// points against it. @pre s is closed
std::vector<size_t> surfaces_inside(const DsModel& model, size_t s, const InsideTest& test);

}  // namespace cutaway
