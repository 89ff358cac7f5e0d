#include "pieces/coarse_cap.h"

#include <algorithm>
#include <exception>
#include <list>
#include <map>
#include <set>
#include <tuple>
#include <utility>
#include <vector>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_face_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <glm/geometric.hpp>

namespace cutaway {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Triangulation_vertex_base_with_info_2<unsigned, K>;
using Fbi = CGAL::Triangulation_face_base_with_info_2<int, K>;  // nesting level, -1: unknown
using Fb = CGAL::Constrained_triangulation_face_base_2<K, Fbi>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
// No intersection tag: crossing constraints throw, and the cap is kept as it is.
using Cdt =
    CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::No_constraint_intersection_tag>;

/// Nesting levels by flooding from the infinite face across constrained edges (level + 1).
void mark_nesting(Cdt& cdt) {
  for (auto f = cdt.all_faces_begin(); f != cdt.all_faces_end(); ++f) f->info() = -1;
  std::list<std::pair<Cdt::Face_handle, int>> border{{cdt.infinite_face(), 0}};
  while (!border.empty()) {
    auto [start, level] = border.front();
    border.pop_front();
    if (start->info() != -1) continue;
    std::list<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
      Cdt::Face_handle f = queue.front();
      queue.pop_front();
      if (f->info() != -1) continue;
      f->info() = level;
      for (int i = 0; i < 3; ++i) {
        Cdt::Face_handle n = f->neighbor(i);
        if (n->info() != -1) continue;
        if (cdt.is_constrained({f, i})) border.push_back({n, level + 1});
        else queue.push_back(n);
      }
    }
  }
}

}  // namespace

std::vector<glm::uvec3> coarse_cap_triangles(const ShadedMesh& cap, const glm::dvec3& u,
                                             const glm::dvec3& v) {
  // Vertices at one position (a cut vertex has one copy per colour side) are one: the first.
  std::map<std::tuple<double, double, double>, unsigned> first_at;
  std::vector<unsigned> same(cap.position.size());
  for (unsigned i = 0; i < cap.position.size(); ++i) {
    const glm::dvec3& p = cap.position[i];
    same[i] = first_at.emplace(std::make_tuple(p.x, p.y, p.z), i).first->second;
  }
  std::map<std::pair<unsigned, unsigned>, int> uses;
  for (const glm::uvec3& t : cap.triangle)
    for (int k = 0; k < 3; ++k) ++uses[std::minmax(same[t[k]], same[t[(k + 1) % 3]])];
  std::vector<std::pair<unsigned, unsigned>> outline;
  for (const auto& [e, n] : uses)
    if (n == 1) outline.push_back(e);
  if (outline.empty()) return cap.triangle;
  // Which way the cap's triangles turn in (u, v): the sign of their summed area.
  double area = 0;
  auto plane = [&](unsigned i) {
    return K::Point_2(glm::dot(cap.position[i], u), glm::dot(cap.position[i], v));
  };
  for (const glm::uvec3& t : cap.triangle) area += CGAL::area(plane(t.x), plane(t.y), plane(t.z));
  // Two outline vertices at one point of the plane would become one vertex of the
  // triangulation, which then has no triangles of the outline's own: keep the cap as it is.
  std::set<unsigned> corners;
  for (const auto& [a, b] : outline) corners.insert({a, b});
  std::vector<K::Point_2> points;
  for (unsigned i : corners) points.push_back(plane(i));
  std::sort(points.begin(), points.end());
  if (std::adjacent_find(points.begin(), points.end()) != points.end()) return cap.triangle;
  try {
    Cdt cdt;
    std::map<unsigned, Cdt::Vertex_handle> handle;
    auto insert = [&](unsigned i) {
      if (auto it = handle.find(i); it != handle.end()) return it->second;
      Cdt::Vertex_handle h = cdt.insert(plane(i));
      h->info() = i;
      handle.emplace(i, h);
      return h;
    };
    for (const auto& [a, b] : outline) cdt.insert_constraint(insert(a), insert(b));
    if (cdt.number_of_vertices() != handle.size()) return cap.triangle;
    mark_nesting(cdt);
    std::vector<glm::uvec3> out;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
      if (f->info() % 2 != 1) continue;
      glm::uvec3 t(f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info());
      if ((area < 0) != (CGAL::area(plane(t.x), plane(t.y), plane(t.z)) < 0)) std::swap(t.y, t.z);
      out.push_back(t);
    }
    return out.empty() ? cap.triangle : out;
  } catch (const std::exception&) {
    // CGAL's way of saying that the outline's edges cross (its constraints intersect).
    return cap.triangle;
  }
}

}  // namespace cutaway
