#include "pieces/seam_stitch.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <set>
#include <unordered_map>

#include <glm/geometric.hpp>

namespace cutaway {

namespace {

/// Boundary edges of a part: directed (a, b) as they appear in their triangle, with it.
struct BoundaryEdge {
  unsigned a, b;
  size_t triangle;
  int corner;  // the triangle's corner where the edge starts
};

std::vector<BoundaryEdge> boundary_edges(const ShadedMesh& mesh) {
  std::map<std::pair<unsigned, unsigned>, int> uses;
  for (const glm::uvec3& t : mesh.triangle)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(t[k], t[(k + 1) % 3])];
  std::vector<BoundaryEdge> out;
  for (size_t f = 0; f < mesh.triangle.size(); ++f) {
    const glm::uvec3& t = mesh.triangle[f];
    for (int k = 0; k < 3; ++k)
      if (uses[std::minmax(t[k], t[(k + 1) % 3])] == 1) out.push_back({t[k], t[(k + 1) % 3], f, k});
  }
  return out;
}

/// A uniform grid hash of points.
class PointGrid {
 public:
  explicit PointGrid(double cell) : cell_(cell) {}
  void add(const glm::dvec3& p, size_t id) { cells_[key(cell_of(p))].push_back(id); }
  /// Ids in the cells overlapping the box [lo, hi].
  template <class F>
  void for_box(const glm::dvec3& lo, const glm::dvec3& hi, F f) const {
    const glm::i64vec3 a = cell_of(lo), b = cell_of(hi);
    for (int64_t x = a.x; x <= b.x; ++x)
      for (int64_t y = a.y; y <= b.y; ++y)
        for (int64_t z = a.z; z <= b.z; ++z) {
          auto it = cells_.find(key({x, y, z}));
          if (it != cells_.end())
            for (size_t id : it->second) f(id);
        }
  }

 private:
  glm::i64vec3 cell_of(const glm::dvec3& p) const {
    return {static_cast<int64_t>(std::floor(p.x / cell_)),
            static_cast<int64_t>(std::floor(p.y / cell_)),
            static_cast<int64_t>(std::floor(p.z / cell_))};
  }
  static uint64_t key(const glm::i64vec3& c) {
    return (static_cast<uint64_t>(c.x) * 73856093u) ^ (static_cast<uint64_t>(c.y) * 19349663u) ^
           (static_cast<uint64_t>(c.z) * 83492791u);
  }
  double cell_;
  std::unordered_map<uint64_t, std::vector<size_t>> cells_;
};

struct BoundaryVertex {
  size_t part;
  unsigned vertex;
};

/// The boundary edges of every part and their vertices, sorted by part and vertex, and a grid
/// cell as large as the longest boundary edge (at least the tolerance): an edge query then
/// visits a few cells.
struct Boundaries {
  std::vector<std::vector<BoundaryEdge>> edges;  // per part
  std::vector<BoundaryVertex> all;
  double cell = 0;
};

Boundaries collect_boundaries(const std::vector<ShadedMesh*>& parts, double tolerance_m) {
  Boundaries b;
  b.edges.resize(parts.size());
  b.cell = tolerance_m;
  for (size_t p = 0; p < parts.size(); ++p) {
    std::set<unsigned> seen;
    b.edges[p] = boundary_edges(*parts[p]);
    for (const BoundaryEdge& e : b.edges[p]) {
      b.cell = std::max(b.cell, glm::distance(parts[p]->position[e.a], parts[p]->position[e.b]));
      for (unsigned v : {e.a, e.b})
        if (seen.insert(v).second) b.all.push_back({p, v});
    }
  }
  std::sort(b.all.begin(), b.all.end(), [](const BoundaryVertex& x, const BoundaryVertex& y) {
    return x.part != y.part ? x.part < y.part : x.vertex < y.vertex;
  });
  return b;
}

/// Step 1: snaps boundary vertices onto earlier parts' boundary vertices within the tolerance.
/// A vertex only snaps onto a target that has no nearer boundary vertex in the snapping
/// vertex's own part (mutual nearest, positions before snapping; vertices that share a
/// position tie), so that of two vertices of one part closer than the tolerance (a Steiner
/// point beside a corner) only the one that matches moves, and the other is inserted into the
/// seam in step 2. Each target takes one vertex per part.
void snap_boundary_vertices(std::vector<ShadedMesh*>& parts, double tolerance_m,
                            const Boundaries& b, StitchStats& stats) {
  const std::vector<BoundaryVertex>& all = b.all;
  std::vector<glm::dvec3> original(all.size());
  PointGrid originals(b.cell);
  for (size_t i = 0; i < all.size(); ++i) {
    original[i] = parts[all[i].part]->position[all[i].vertex];
    originals.add(original[i], i);
  }
  const glm::dvec3 r(tolerance_m);
  // The distance from q to the nearest boundary vertex of `part` (before snapping).
  auto nearest_in_part = [&](const glm::dvec3& q, size_t part) {
    double best_d = 2 * tolerance_m;
    originals.for_box(q - 2.0 * r, q + 2.0 * r, [&](size_t k) {
      if (all[k].part == part) best_d = std::min(best_d, glm::distance(original[k], q));
    });
    return best_d;
  };
  PointGrid grid(b.cell);
  std::set<std::pair<size_t, size_t>> taken;  // (target, part): one vertex per part each
  for (size_t i = 0; i < all.size(); ++i) {
    glm::dvec3& p = parts[all[i].part]->position[all[i].vertex];
    size_t best = all.size();
    double best_d = tolerance_m;
    grid.for_box(p - r, p + r, [&](size_t j) {
      if (all[j].part == all[i].part || taken.count({j, all[i].part})) return;
      const double d = glm::distance(parts[all[j].part]->position[all[j].vertex], p);
      if (d < best_d || (d == best_d && j < best)) {
        best_d = d;
        best = j;
      }
    });
    if (best < all.size() &&
        glm::distance(original[i], original[best]) > nearest_in_part(original[best], all[i].part))
      best = all.size();
    if (best < all.size()) {
      taken.insert({best, all[i].part});
      const glm::dvec3 q = parts[all[best].part]->position[all[best].vertex];
      if (q != p) ++stats.snapped;
      p = q;
    }
    grid.add(p, i);
  }
}

/// Points to insert on each edge of a triangle (the edge starting at corner k), by parameter.
using EdgeInserts = std::array<std::vector<std::pair<double, glm::dvec3>>, 3>;

/// Replaces triangle f of `mesh` by triangles over its outline with the vertices of `edges`
/// inserted (each exactly at its point): a fan from the opposite corner when one edge is
/// split, else a fan from a new vertex inside the triangle.
void split_triangle(ShadedMesh& mesh, size_t f, const EdgeInserts& edges, StitchStats& stats) {
  const glm::uvec3 t = mesh.triangle[f];
  // The triangle's outline with the inserted vertices, counter-clockwise.
  std::vector<unsigned> outline;
  int split_edges = 0, only = -1;
  for (int k = 0; k < 3; ++k) {
    outline.push_back(t[k]);
    if (!edges[k].empty()) {
      ++split_edges;
      only = k;
    }
    for (const auto& [s, q] : edges[k]) {
      const unsigned v = add_interpolated_vertex(mesh, t[k], t[(k + 1) % 3], s);
      mesh.position[v] = q;  // exactly the other part's vertex
      outline.push_back(v);
      ++stats.inserted;
    }
  }
  std::vector<glm::uvec3> fan;
  if (split_edges == 1) {
    // Fan from the corner opposite the split edge, which starts at outline index `apex`.
    const unsigned apex_vertex = t[(only + 2) % 3];
    size_t apex = 0;
    while (outline[apex] != apex_vertex) ++apex;
    for (size_t k = 1; k + 1 < outline.size(); ++k)
      fan.push_back({apex_vertex, outline[(apex + k) % outline.size()],
                     outline[(apex + k + 1) % outline.size()]});
  } else {
    const unsigned c0 = add_interpolated_vertex(mesh, t[0], t[1], 0.5);
    const unsigned c = add_interpolated_vertex(mesh, c0, t[2], 1.0 / 3);
    for (size_t k = 0; k < outline.size(); ++k)
      fan.push_back({c, outline[k], outline[(k + 1) % outline.size()]});
  }
  mesh.triangle[f] = fan.front();
  mesh.triangle.insert(mesh.triangle.end(), fan.begin() + 1, fan.end());
}

/// Step 2: inserts other parts' boundary vertices into the boundary edges they lie on (within
/// the tolerance, strictly inside the edge), splitting those edges' triangles.
void insert_seam_vertices(std::vector<ShadedMesh*>& parts, double tolerance_m, const Boundaries& b,
                          StitchStats& stats) {
  const std::vector<BoundaryVertex>& all = b.all;
  PointGrid grid(b.cell);
  for (size_t i = 0; i < all.size(); ++i) grid.add(parts[all[i].part]->position[all[i].vertex], i);
  for (size_t p = 0; p < parts.size(); ++p) {
    ShadedMesh& mesh = *parts[p];
    std::map<size_t, EdgeInserts> inserts;  // per triangle
    for (const BoundaryEdge& e : b.edges[p]) {
      const glm::dvec3 a = mesh.position[e.a], bq = mesh.position[e.b], ab = bq - a;
      const double len2 = glm::dot(ab, ab);
      if (len2 == 0) continue;
      const glm::dvec3 r(tolerance_m);
      std::vector<std::pair<double, glm::dvec3>> found;
      grid.for_box(glm::min(a, bq) - r, glm::max(a, bq) + r, [&](size_t j) {
        if (all[j].part == p) return;
        const glm::dvec3 q = parts[all[j].part]->position[all[j].vertex];
        if (q == a || q == bq) return;
        const double t = glm::dot(q - a, ab) / len2;
        if (t <= 0 || t >= 1) return;
        if (glm::distance(a + ab * t, q) > tolerance_m) return;
        found.emplace_back(t, q);
      });
      if (found.empty()) continue;
      std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) {
        return x.first != y.first ? x.first < y.first
                                  : std::tie(x.second.x, x.second.y, x.second.z) <
                                        std::tie(y.second.x, y.second.y, y.second.z);
      });
      // The same point may be found twice (two parts share it): keep one.
      std::vector<std::pair<double, glm::dvec3>> unique;
      for (const auto& f : found)
        if (unique.empty() || unique.back().second != f.second) unique.push_back(f);
      inserts[e.triangle][e.corner] = std::move(unique);
    }
    for (const auto& [f, edges] : inserts) split_triangle(mesh, f, edges, stats);
    if (!inserts.empty()) remove_unused_vertices(mesh);
  }
}

}  // namespace

StitchStats stitch_seams(std::vector<ShadedMesh*>& parts, double tolerance_m) {
  StitchStats stats;
  // Boundary edges per part: snapping moves vertices but keeps every part's triangles, so they
  // serve step 2 too.
  const Boundaries boundaries = collect_boundaries(parts, tolerance_m);
  snap_boundary_vertices(parts, tolerance_m, boundaries, stats);
  insert_seam_vertices(parts, tolerance_m, boundaries, stats);
  return stats;
}

}  // namespace cutaway
