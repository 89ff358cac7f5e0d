#include "pieces/clip_mesh.h"

#include <cmath>
#include <map>

#include <glm/geometric.hpp>

namespace cutaway {

ShadedMesh clip_to_half_space(const ShadedMesh& mesh, const Plane& plane, bool keep_positive) {
  const size_t n = mesh.position.size();
  std::vector<double> d(n);
  std::vector<bool> positive(n);
  for (size_t i = 0; i < n; ++i) {
    d[i] = glm::dot(mesh.position[i] - plane.point, plane.normal);
    if (std::fabs(d[i]) <= kOnPlane_m) d[i] = 0;
    positive[i] = d[i] >= 0;
  }
  auto kept = [&](unsigned i) { return positive[i] == keep_positive; };

  ShadedMesh out;
  std::vector<unsigned> copied(n, ~0u);
  auto vertex = [&](unsigned i) {
    if (copied[i] == ~0u) copied[i] = copy_vertex(mesh, i, out);
    return copied[i];
  };
  // Crossings: by edge, or by the positive vertex itself when it lies on the plane.
  std::map<std::pair<unsigned, unsigned>, unsigned> crossing;
  auto cross = [&](unsigned a, unsigned b) {
    const unsigned p = positive[a] ? a : b, q = positive[a] ? b : a;
    if (d[p] == 0) return vertex(p);
    const auto key = std::make_pair(p, q);
    auto it = crossing.find(key);
    if (it != crossing.end()) return it->second;
    const unsigned vp = vertex(p), vq = vertex(q);
    const double t = d[p] / (d[p] - d[q]);
    const unsigned id = add_interpolated_vertex(out, vp, vq, t);
    crossing.emplace(key, id);
    return id;
  };

  for (const glm::uvec3& t : mesh.triangle) {
    const int inside = kept(t[0]) + kept(t[1]) + kept(t[2]);
    if (inside == 0) continue;
    if (inside == 3) {
      out.triangle.push_back({vertex(t[0]), vertex(t[1]), vertex(t[2])});
      continue;
    }
    // Sutherland-Hodgman on one triangle, then a fan over the polygon without repeats.
    std::vector<unsigned> poly;
    for (int k = 0; k < 3; ++k) {
      const unsigned a = t[k], b = t[(k + 1) % 3];
      if (kept(a)) poly.push_back(vertex(a));
      if (kept(a) != kept(b)) poly.push_back(cross(a, b));
    }
    std::vector<unsigned> unique;
    for (unsigned v : poly)
      if (unique.empty() || unique.back() != v) unique.push_back(v);
    while (unique.size() > 1 && unique.back() == unique.front()) unique.pop_back();
    for (size_t k = 1; k + 1 < unique.size(); ++k)
      out.triangle.push_back({unique[0], unique[k], unique[k + 1]});
  }
  remove_unused_vertices(out);
  return out;
}

}  // namespace cutaway
