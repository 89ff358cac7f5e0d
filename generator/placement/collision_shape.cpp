#include "placement/collision_shape.h"

#include <algorithm>
#include <array>
#include <limits>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>
#include <HACD/hacdHACD.h>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <meshoptimizer.h>
#include <oneapi/tbb/parallel_for.h>

#include "base/error.h"
#include "base/timer.h"

namespace cutaway {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using HullMesh = CGAL::Surface_mesh<Kernel::Point_3>;

/// The mesh with its vertices welded by exact position and degenerate triangles dropped.
struct Welded {
  std::vector<glm::dvec3> point;
  std::vector<std::array<unsigned, 3>> triangle;
};

Welded weld(const ShadedMesh& mesh) {
  Welded w;
  std::map<std::tuple<double, double, double>, unsigned> index;
  std::vector<unsigned> id(mesh.position.size());
  for (size_t i = 0; i < mesh.position.size(); ++i) {
    const glm::dvec3& p = mesh.position[i];
    auto [it, added] = index.emplace(std::make_tuple(p.x, p.y, p.z), w.point.size());
    if (added) w.point.push_back(p);
    id[i] = it->second;
  }
  for (const glm::uvec3& t : mesh.triangle) {
    const std::array<unsigned, 3> u{id[t[0]], id[t[1]], id[t[2]]};
    if (u[0] != u[1] && u[1] != u[2] && u[0] != u[2]) w.triangle.push_back(u);
  }
  return w;
}

/// A convex hull in a form that does not depend on the run: CGAL's hull is the same polytope
/// every run, but the order of its vertices and faces, and how it triangulates a planar facet
/// (a cut face's corners), vary with memory addresses, and the last bits of every normal
/// computed from its triangles with them. Here the corners are sorted, and each facet (the
/// triangles coplanar by CGAL's exact predicate, merged) takes its plane from canonical
/// corners and its outline in order around it: the same numbers every run.
struct Facets {
  std::vector<glm::dvec3> corners;  ///< sorted (x, then y, then z)
  struct Facet {
    std::vector<unsigned> loop;  ///< corners, counter-clockwise seen from outside
    glm::dvec3 normal{0.0};      ///< unit, outward
    double offset = 0;           ///< normal . x = offset on the plane (metres)
  };
  std::vector<Facet> facets;  ///< sorted by their corners
};

bool lexicographic(const glm::dvec3& a, const glm::dvec3& b) {
  return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
}

Facets hull_facets(const std::vector<glm::dvec3>& points) {
  std::vector<Kernel::Point_3> in;
  in.reserve(points.size());
  for (const glm::dvec3& p : points) in.emplace_back(p.x, p.y, p.z);
  HullMesh hull;
  CGAL::convex_hull_3(in.begin(), in.end(), hull);
  Facets out;
  for (const auto v : hull.vertices())
    out.corners.emplace_back(hull.point(v).x(), hull.point(v).y(), hull.point(v).z());
  std::sort(out.corners.begin(), out.corners.end(), lexicographic);
  const auto index = [&](HullMesh::Vertex_index v) {
    const glm::dvec3 p(hull.point(v).x(), hull.point(v).y(), hull.point(v).z());
    return static_cast<unsigned>(
        std::lower_bound(out.corners.begin(), out.corners.end(), p, lexicographic) -
        out.corners.begin());
  };
  // Coplanar neighbouring triangles join one facet (union-find over the faces).
  std::vector<size_t> root(hull.number_of_faces());
  for (size_t f = 0; f < root.size(); ++f) root[f] = f;
  const auto find = [&](size_t f) {
    while (root[f] != f) f = root[f] = root[root[f]];
    return f;
  };
  for (const auto h : hull.halfedges()) {
    if (hull.is_border(h) || hull.is_border(hull.opposite(h))) continue;
    const auto o = hull.opposite(h);
    if (CGAL::coplanar(hull.point(hull.source(h)), hull.point(hull.target(h)),
                       hull.point(hull.target(hull.next(h))),
                       hull.point(hull.target(hull.next(o)))))
      root[find(hull.face(h))] = find(hull.face(o));
  }
  std::map<size_t, std::vector<unsigned>> groups;  // facet root -> its corners
  for (const auto f : hull.faces())
    for (const auto v : CGAL::vertices_around_face(hull.halfedge(f), hull))
      groups[find(f)].push_back(index(v));
  std::vector<std::vector<unsigned>> sets;
  for (auto& [r, g] : groups) {
    std::sort(g.begin(), g.end());
    g.erase(std::unique(g.begin(), g.end()), g.end());
    sets.push_back(std::move(g));
  }
  std::sort(sets.begin(), sets.end());
  glm::dvec3 inside(0.0);
  for (const glm::dvec3& c : out.corners) inside += c;
  inside /= static_cast<double>(out.corners.size());
  const auto point = [&](unsigned k) {
    return Kernel::Point_3(out.corners[k].x, out.corners[k].y, out.corners[k].z);
  };
  for (const std::vector<unsigned>& g : sets) {
    // The plane through a well-shaped triangle of canonical corners: the facet's first corner
    // a, the corner b farthest from it and the corner farthest from the line ab (the first
    // of equals). The first three corners in order can be in line to 1e-15 without being
    // collinear (a cut face's outline), and their cross product then points anywhere.
    const glm::dvec3 a = out.corners[g[0]];
    size_t second = 1, third = 0;
    double farthest = glm::distance(out.corners[g[1]], a);
    for (size_t k = 2; k < g.size(); ++k) {
      const double distance = glm::distance(out.corners[g[k]], a);
      if (distance > farthest) {
        farthest = distance;
        second = k;
      }
    }
    const glm::dvec3 u = out.corners[g[second]] - a;
    double widest = 0;
    for (size_t k = 1; k < g.size(); ++k) {
      const double width = glm::length(glm::cross(u, out.corners[g[k]] - a));
      if (width > widest) {
        widest = width;
        third = k;
      }
    }
    if (third == 0 || CGAL::collinear(point(g[0]), point(g[second]), point(g[third])))
      continue;  // degenerate
    glm::dvec3 n = glm::normalize(glm::cross(u, out.corners[g[third]] - a));
    if (glm::dot(n, inside - a) > 0) n = -n;
    Facets::Facet facet{g, n, glm::dot(n, a)};
    // The outline: by angle about the facet's mean, counter-clockwise about the normal,
    // starting at its first corner.
    glm::dvec3 mean(0.0);
    for (unsigned k : g) mean += out.corners[k];
    mean /= static_cast<double>(g.size());
    const glm::dvec3 e1 = glm::normalize(u), e2 = glm::cross(n, e1);
    std::vector<std::pair<double, unsigned>> around;
    for (unsigned k : g) {
      const glm::dvec3 d = out.corners[k] - mean;
      around.emplace_back(std::atan2(glm::dot(d, e2), glm::dot(d, e1)), k);
    }
    std::sort(around.begin(), around.end());
    facet.loop.clear();
    for (const auto& [angle, k] : around) facet.loop.push_back(k);
    std::rotate(facet.loop.begin(), std::find(facet.loop.begin(), facet.loop.end(), g[0]),
                facet.loop.end());
    out.facets.push_back(std::move(facet));
  }
  return out;
}

/// The corners of the convex hull of `points` (sorted) and the hull's volume (cubic metres).
std::pair<std::vector<glm::dvec3>, double> convex_hull(const std::vector<glm::dvec3>& points) {
  const Facets h = hull_facets(points);
  double volume = 0;
  for (const Facets::Facet& f : h.facets) {
    for (size_t k = 1; k + 1 < f.loop.size(); ++k)
      volume += glm::dot(h.corners[f.loop[0]],
                         glm::cross(h.corners[f.loop[k]], h.corners[f.loop[k + 1]])) /
                6;
  }
  return {h.corners, volume};
}

/// The planes of the convex hull of `corners`: unit outward normal and offset (n . x = d on
/// the plane), and the hull's triangles (each facet's fan) for exact distances: those of
/// plane k are triangle[first[k]] up to triangle[first[k + 1]].
struct HullPlanes {
  std::vector<std::pair<glm::dvec3, double>> plane;
  std::vector<Kernel::Triangle_3> triangle;
  std::vector<size_t> first;  ///< #planes + 1
};

HullPlanes hull_planes(const std::vector<glm::dvec3>& corners) {
  const Facets h = hull_facets(corners);
  HullPlanes out;
  const auto point = [&](unsigned k) {
    return Kernel::Point_3(h.corners[k].x, h.corners[k].y, h.corners[k].z);
  };
  for (const Facets::Facet& f : h.facets) {
    out.plane.emplace_back(f.normal, f.offset);
    out.first.push_back(out.triangle.size());
    for (size_t k = 1; k + 1 < f.loop.size(); ++k)
      out.triangle.emplace_back(point(f.loop[0]), point(f.loop[k]), point(f.loop[k + 1]));
  }
  out.first.push_back(out.triangle.size());
  return out;
}

/// The largest distance of any of `points` outside the convex hull of `corners` (0 if none
/// is outside), metres, rounded up to 0.1 um. A point is outside where CGAL's exact
/// orientation puts it on the outer side of a hull triangle, and its distance is the least
/// of CGAL's distances to the triangles. Shortcuts give the same result faster: a point more
/// than kSure inside every facet's plane (the planes in doubles are off by far less) is
/// inside, and one more than kSure outside a facet's plane outside, without exact tests; a
/// triangle whose plane lies farther than the nearest triangle found so far (by more than
/// rounding) cannot be the nearest, so its distance is not computed.
double outside_distance(const std::vector<glm::dvec3>& points,
                        const std::vector<glm::dvec3>& corners) {
  constexpr double kSure = 1e-9;  // metres
  const HullPlanes h = hull_planes(corners);
  double outside = 0;
  std::vector<double> above(h.plane.size());  // the point's height over each plane
  for (const glm::dvec3& p : points) {
    size_t highest = 0;
    for (size_t f = 0; f < h.plane.size(); ++f) {
      above[f] = glm::dot(h.plane[f].first, p) - h.plane[f].second;
      if (above[f] > above[highest]) highest = f;
    }
    if (h.plane.empty() || above[highest] < -kSure) continue;
    const Kernel::Point_3 q(p.x, p.y, p.z);
    bool out = above[highest] > kSure;  // on the outer side of that facet's triangles
    for (const Kernel::Triangle_3& t : h.triangle)
      out = out || CGAL::orientation(t[0], t[1], t[2], q) == CGAL::POSITIVE;
    if (!out) continue;
    // The facet the point stands highest over first: its triangles are nearly always nearest.
    double d2 = std::numeric_limits<double>::max();
    const auto facet = [&](size_t f) {
      for (size_t k = h.first[f]; k < h.first[f + 1]; ++k)
        d2 = std::min(d2, CGAL::to_double(CGAL::squared_distance(q, h.triangle[k])));
    };
    facet(highest);
    for (size_t f = 0; f < h.plane.size(); ++f) {
      const double bound = std::abs(above[f]) - kSure;
      if (f == highest || (bound > 0 && bound * bound > d2 * (1 + 1e-12))) continue;
      facet(f);
    }
    outside = std::max(outside, std::sqrt(d2));
  }
  return std::ceil(outside * 1e7) / 1e7;
}

/// The corners of a convex hull moved outward so that every face's plane moves out by at
/// least `distance` (metres): each corner along the mean normal of its faces, by distance over
/// the smallest cosine between that mean and a face's normal (at most 3 x distance). A point
/// within `distance` outside the hull is then (nearly always) inside the grown one; the caller
/// measures what is left.
std::vector<glm::dvec3> inflate(const std::vector<glm::dvec3>& corners, double distance) {
  const Facets h = hull_facets(corners);
  std::vector<std::vector<glm::dvec3>> normals(h.corners.size());  // per corner, its facets'
  for (const Facets::Facet& f : h.facets)
    for (unsigned k : f.loop) normals[k].push_back(f.normal);
  std::vector<glm::dvec3> out;
  for (size_t v = 0; v < h.corners.size(); ++v) {
    const glm::dvec3& p = h.corners[v];
    glm::dvec3 mean(0.0);
    for (const glm::dvec3& n : normals[v]) mean += n;
    if (glm::length(mean) == 0) {
      out.push_back(p);
      continue;
    }
    mean = glm::normalize(mean);
    double cosine = 1;
    for (const glm::dvec3& n : normals[v]) cosine = std::min(cosine, glm::dot(mean, n));
    out.push_back(p + mean * (distance / std::max(cosine, 1.0 / 3)));
  }
  std::sort(out.begin(), out.end(), lexicographic);
  return out;
}

/// The part standing for `points` (the corners of a convex hull), by greedy refinement in the
/// manner of Quickhull (Barber, Dobkin and Huhdanpaa 1996): start from `seed_corners` corners
/// picked by farthest-point sampling, then, round after round, add the points farthest outside
/// the hull of those kept (at most one per neighbourhood of a twentieth of the extent, so a
/// round adds corners all over the hull) until none lies more than `corner_tolerance_m` outside
/// or `max_corners` are kept. The kept hull is then grown by the largest distance of a point
/// outside it (inflate), so that it encloses them all: Bullet's polyhedral contacts touch the
/// hull itself, not the hull grown by its collision margin. `outside_m` is what is left outside.
ConvexPart reduce(const std::vector<glm::dvec3>& points, const CollisionShapeOptions& o) {
  ConvexPart part;
  if (static_cast<int>(points.size()) <= o.max_corners) {
    part.corners = points;
    return part;
  }
  glm::dvec3 mean(0.0), lo(points[0]), hi(points[0]);
  for (const glm::dvec3& p : points) {
    mean += p;
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  mean /= static_cast<double>(points.size());
  const double spacing = glm::length(hi - lo) / 20;
  std::vector<bool> kept(points.size(), false);
  std::vector<size_t> chosen;
  std::vector<double> gap(points.size());
  for (size_t k = 0; k < points.size(); ++k) gap[k] = glm::length(points[k] - mean);
  while (static_cast<int>(chosen.size()) < std::min(o.seed_corners, o.max_corners)) {
    const size_t far = static_cast<size_t>(std::max_element(gap.begin(), gap.end()) - gap.begin());
    chosen.push_back(far);
    kept[far] = true;
    for (size_t k = 0; k < points.size(); ++k)
      gap[k] = std::min(gap[k], glm::length(points[k] - points[far]));
  }
  for (;;) {
    std::vector<glm::dvec3> corners;
    for (size_t k : chosen) corners.push_back(points[k]);
    const HullPlanes h = hull_planes(corners);
    // Each point's distance outside (largest over the hull's planes).
    std::vector<std::pair<double, size_t>> candidate;
    for (size_t k = 0; k < points.size(); ++k) {
      if (kept[k]) continue;
      double d = 0;
      for (const auto& [n, offset] : h.plane) d = std::max(d, glm::dot(n, points[k]) - offset);
      if (d > o.corner_tolerance_m) candidate.emplace_back(-d, k);
    }
    if (candidate.empty() || static_cast<int>(chosen.size()) >= o.max_corners) break;
    std::sort(candidate.begin(), candidate.end());
    std::vector<size_t> added;
    for (const auto& [minus_d, k] : candidate) {
      if (static_cast<int>(chosen.size() + added.size()) >= o.max_corners) break;
      bool near = false;
      for (size_t a : added) near = near || glm::length(points[a] - points[k]) < spacing;
      if (!near) added.push_back(k);
    }
    for (size_t k : added) {
      chosen.push_back(k);
      kept[k] = true;
    }
  }
  const std::vector<glm::dvec3> corners = convex_hull([&] {
                                            std::vector<glm::dvec3> c;
                                            for (size_t k : chosen) c.push_back(points[k]);
                                            return c;
                                          }())
                                              .first;
  const double outside = outside_distance(points, corners);
  part.corners = outside > 0 ? inflate(corners, outside) : corners;
  part.outside_m = outside > 0 ? outside_distance(points, part.corners) : 0;
  return part;
}

/// The decomposition's parts: HACD clusters the triangles of the simplified piece; every
/// vertex of the piece joins the clusters of the nearest simplified vertex, so the parts'
/// hulls cover the piece's vertices, not only the simplified ones. Empty if HACD fails.
std::vector<ConvexPart> decompose(const Welded& w, const CollisionShapeOptions& o) {
  std::vector<float> xyz;
  for (const glm::dvec3& p : w.point) {
    xyz.push_back(static_cast<float>(p.x));
    xyz.push_back(static_cast<float>(p.y));
    xyz.push_back(static_cast<float>(p.z));
  }
  std::vector<unsigned> indices;
  for (const auto& t : w.triangle) indices.insert(indices.end(), t.begin(), t.end());
  std::vector<unsigned> simple(indices.size());
  const size_t target =
      std::min(indices.size(), static_cast<size_t>(3 * o.decomposition_triangles));
  simple.resize(meshopt_simplify(simple.data(), indices.data(), indices.size(), xyz.data(),
                                 w.point.size(), 3 * sizeof(float), target, 0.02f, 0, nullptr));
  if (simple.size() < 12) return {};

  // HACD numbers the simplified mesh's vertices densely.
  std::vector<long> dense(w.point.size(), -1);
  std::vector<HACD::Vec3<HACD::Real>> points;
  std::vector<unsigned> used;
  std::vector<HACD::Vec3<long>> triangles;
  std::vector<std::array<long, 3>> corners;  // the same triangles, readable
  for (size_t i = 0; i < simple.size(); i += 3) {
    long t[3];
    for (int k = 0; k < 3; ++k) {
      const unsigned v = simple[i + k];
      if (dense[v] < 0) {
        dense[v] = static_cast<long>(points.size());
        points.emplace_back(w.point[v].x, w.point[v].y, w.point[v].z);
        used.push_back(v);
      }
      t[k] = dense[v];
    }
    triangles.emplace_back(t[0], t[1], t[2]);
    corners.push_back({t[0], t[1], t[2]});
  }
  glm::dvec3 lo(w.point[0]), hi(w.point[0]);
  for (const glm::dvec3& p : w.point) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  HACD::HACD hacd;
  hacd.SetPoints(points.data());
  hacd.SetNPoints(points.size());
  hacd.SetTriangles(triangles.data());
  hacd.SetNTriangles(triangles.size());
  hacd.SetCompacityWeight(0.1);
  hacd.SetVolumeWeight(0.0);
  hacd.SetNClusters(1);
  hacd.SetNVerticesPerCH(64);
  hacd.SetScaleFactor(1000);  // HACD rescales the mesh so its largest extent is this
  hacd.SetConcavity(1000 * o.concavity);
  hacd.SetConnectDist(30);  // joins pieces of the surface closer than 3 % of the extent
  hacd.SetAddExtraDistPoints(false);
  hacd.SetAddNeighboursDistPoints(false);
  hacd.SetAddFacesPoints(false);
  if (!hacd.Compute() || hacd.GetNClusters() == 0 || extent <= 0) return {};
  const long* partition = hacd.GetPartition();
  const size_t clusters = hacd.GetNClusters();

  // Clusters of each simplified vertex, then of each vertex of the piece.
  std::vector<std::vector<size_t>> of_vertex(used.size());
  for (size_t t = 0; t < triangles.size(); ++t) {
    const long c = partition[t];
    if (c < 0 || static_cast<size_t>(c) >= clusters) return {};
    for (int k = 0; k < 3; ++k) {
      std::vector<size_t>& list = of_vertex[static_cast<size_t>(corners[t][k])];
      if (std::find(list.begin(), list.end(), static_cast<size_t>(c)) == list.end())
        list.push_back(static_cast<size_t>(c));
    }
  }
  std::vector<std::vector<glm::dvec3>> members(clusters);
  for (const glm::dvec3& p : w.point) {
    size_t nearest = 0;
    double best = std::numeric_limits<double>::max();
    for (size_t k = 0; k < used.size(); ++k) {
      const glm::dvec3 d = w.point[used[k]] - p;
      const double d2 = glm::dot(d, d);
      if (d2 < best) {
        best = d2;
        nearest = k;
      }
    }
    for (size_t c : of_vertex[nearest]) members[c].push_back(p);
  }
  std::vector<ConvexPart> parts;
  for (const auto& m : members) {
    if (m.size() >= 4) parts.push_back(reduce(convex_hull(m).first, o));
  }
  if (parts.empty() || static_cast<int>(parts.size()) > o.max_parts) return {};
  return parts;
}

}  // namespace

CollisionShape collision_shape(const ShadedMesh& mesh, const CollisionShapeOptions& options) {
  const Welded w = weld(mesh);
  CUTAWAY_CHECK(w.point.size() >= 4 && !w.triangle.empty());
  CollisionShape s;
  glm::dvec3 moment(0.0);
  for (const auto& t : w.triangle) {
    const glm::dvec3 &a = w.point[t[0]], &b = w.point[t[1]], &c = w.point[t[2]];
    const double v = glm::dot(a, glm::cross(b, c)) / 6;  // the tetrahedron (0, a, b, c)
    s.volume_m3 += v;
    moment += v * (a + b + c) / 4.0;
  }
  auto [hull, hull_volume] = convex_hull(w.point);
  CUTAWAY_CHECK(hull_volume > 0);
  if (s.volume_m3 > 0) {
    s.centroid = moment / s.volume_m3;
    s.convexity = std::min(1.0, s.volume_m3 / hull_volume);
  } else {  // not a closed outward surface: collide as the hull, centred on its corners
    for (const glm::dvec3& p : hull) s.centroid += p;
    s.centroid /= static_cast<double>(hull.size());
    s.volume_m3 = hull_volume;
  }
  if (s.convexity < options.min_convexity) {
    s.parts = decompose(w, options);
    s.decomposed = !s.parts.empty();
  }
  if (s.parts.empty()) s.parts.push_back(reduce(hull, options));
  return s;
}

std::vector<AssetHull> collision_hulls(const CollisionShape& shape) {
  std::vector<AssetHull> hulls;
  for (const ConvexPart& part : shape.parts) {
    const Facets h = hull_facets(part.corners);
    AssetHull hull;
    hull.position = h.corners;
    for (const Facets::Facet& f : h.facets)
      for (size_t k = 1; k + 1 < f.loop.size(); ++k)
        hull.triangle.emplace_back(f.loop[0], f.loop[k], f.loop[k + 1]);
    hulls.push_back(std::move(hull));
  }
  return hulls;
}

std::vector<CollisionShape> collision_shapes(const std::vector<ShadedMesh>& meshes,
                                             const CollisionShapeOptions& options,
                                             double* processor_seconds) {
  std::vector<CollisionShape> shapes(meshes.size());
  std::vector<double> seconds(meshes.size(), 0.0);
  // One piece a task: a decomposed piece takes a hundred times as long as a convex one.
  oneapi::tbb::parallel_for(
      oneapi::tbb::blocked_range<size_t>(0, meshes.size(), 1),
      [&](const oneapi::tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k != r.end(); ++k) {
          const double t0 = thread_processor_seconds();
          shapes[k] = collision_shape(meshes[k], options);
          seconds[k] = thread_processor_seconds() - t0;
        }
      },
      oneapi::tbb::simple_partitioner());
  if (processor_seconds) *processor_seconds = std::accumulate(seconds.begin(), seconds.end(), 0.0);
  return shapes;
}

}  // namespace cutaway
