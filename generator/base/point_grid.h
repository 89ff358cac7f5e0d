// Points bucketed in a uniform grid of cubes, for "which points lie within one cell of here"
// (the Poisson-disc test of grain placement, the grain spots of skin patterns).
#pragma once

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

namespace cutaway {

/// Point ids in cubes `cell` metres wide. Queries visit the 27 cubes around a point, so every
/// point closer than `cell` to it is visited (and some farther ones). Deterministic: ids are
/// visited cube by cube in a fixed order and, within a cube, in the order they were added.
struct PointGrid {
  double cell = 1.0;  ///< cube side, metres; > 0
  std::unordered_map<uint64_t, std::vector<size_t>> cells;

  /// Adds point `p` (metres) under `id`.
  void add(const glm::dvec3& p, size_t id) { cells[key(index(p))].push_back(id); }

  /// Calls visit(id) for every id added in the 27 cubes around `p`; stops early when visit
  /// returns false.
  template <class Visit>
  void visit_near(const glm::dvec3& p, Visit visit) const {
    const Index c = index(p);
    for (int64_t dx = -1; dx <= 1; ++dx)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dz = -1; dz <= 1; ++dz) {
          const auto it = cells.find(key({c.x + dx, c.y + dy, c.z + dz}));
          if (it == cells.end()) continue;
          for (const size_t id : it->second)
            if (!visit(id)) return;
        }
  }

 private:
  struct Index {
    int64_t x, y, z;
  };
  Index index(const glm::dvec3& p) const {
    return {static_cast<int64_t>(std::floor(p.x / cell)),
            static_cast<int64_t>(std::floor(p.y / cell)),
            static_cast<int64_t>(std::floor(p.z / cell))};
  }
  static uint64_t key(const Index& i) {
    return (static_cast<uint64_t>(i.x) * 73856093ULL) ^ (static_cast<uint64_t>(i.y) * 19349663ULL) ^
           (static_cast<uint64_t>(i.z) * 83492791ULL);
  }
};

}  // namespace cutaway
