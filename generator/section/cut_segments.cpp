#include "section/cut_segments.h"

#include <cmath>
#include <map>

#include <glm/geometric.hpp>

namespace cutaway {

namespace {

DsAttributes attributes_of(const DsMesh::VertexData& d) {
  return {to_glm(d.front),
          to_glm(d.back),
          {d.material_front[0], d.material_front[1]},
          {d.material_back[0], d.material_back[1]},
          d.blur};
}

/// A point where the plane crosses a mesh edge, with the DS attributes there.
struct Crossing {
  glm::dvec3 p;
  DsAttributes at;
};

}  // namespace

DsAttributes lerp(const DsAttributes& a, const DsAttributes& b, double t) {
  return {a.front + (b.front - a.front) * t, a.back + (b.back - a.back) * t,
          a.material_front + (b.material_front - a.material_front) * t,
          a.material_back + (b.material_back - a.material_back) * t,
          a.blur + (b.blur - a.blur) * t};
}

std::vector<CutSegment> cut_segments(const DsModel& model, const Plane& plane) {
  std::vector<CutSegment> out;
  for (size_t si = 0; si < model.surfaces.size(); ++si) {
    const DsMesh& mesh = model.surfaces[si].mesh;
    std::vector<double> dist(mesh.n_vertices());
    for (auto vh : mesh.vertices()) {
      const double d = glm::dot(to_glm(mesh.point(vh)) - plane.point, plane.normal);
      dist[vh.idx()] = std::fabs(d) <= kOnPlane_m ? 0.0 : d;
    }
    auto positive = [&](int v) { return dist[v] >= 0; };  // symbolic perturbation: 0 is +
    auto crossing = [&](DsMesh::VertexHandle a, DsMesh::VertexHandle b) {
      // Interpolate from the positive end; a positive end at distance 0 is the crossing itself.
      if (!positive(a.idx())) std::swap(a, b);
      const double da = dist[a.idx()], db = dist[b.idx()];
      const double t = da == 0 ? 0.0 : da / (da - db);
      Crossing c;
      c.p = to_glm(mesh.point(a)) + (to_glm(mesh.point(b)) - to_glm(mesh.point(a))) * t;
      c.at = lerp(attributes_of(mesh.data(a)), attributes_of(mesh.data(b)), t);
      return c;
    };
    for (auto fh : mesh.faces()) {
      std::array<DsMesh::VertexHandle, 3> v;
      int k = 0;
      for (auto vh : mesh.fv_range(fh)) v[k++] = vh;
      const int npos = positive(v[0].idx()) + positive(v[1].idx()) + positive(v[2].idx());
      if (npos == 0 || npos == 3) continue;
      // The lone vertex (the one whose side differs), then the two edges from it in winding
      // order; the segment runs so that the front side is consistently to one side.
      int lone = 0;
      for (int i = 0; i < 3; ++i) {
        const bool pi = positive(v[i].idx());
        if ((npos == 1 && pi) || (npos == 2 && !pi)) lone = i;
      }
      const auto l = v[lone], n1 = v[(lone + 1) % 3], n2 = v[(lone + 2) % 3];
      // A lone vertex on the negative side mirrors the picture: swap the ends so that the
      // front side stays on the same hand of every segment.
      Crossing c1 = crossing(l, n1), c2 = crossing(l, n2);
      if (npos == 2) std::swap(c1, c2);
      if (glm::distance(c1.p, c2.p) <= 0) continue;
      const glm::dvec3 p0 = to_glm(mesh.point(v[0])), p1 = to_glm(mesh.point(v[1])),
                       p2 = to_glm(mesh.point(v[2]));
      const glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
      const double len = glm::length(n);
      if (len == 0) continue;
      CutSegment s;
      s.surface = static_cast<int>(si);
      s.a = c1.p;
      s.b = c2.p;
      s.front_normal = n / len;
      s.at_a = c1.at;
      s.at_b = c2.at;
      out.push_back(s);
    }
  }
  return out;
}

std::vector<CutSegment> merge_collinear_segments(const std::vector<CutSegment>& segments,
                                                 double tolerance_m, double max_length_m,
                                                 const std::vector<Plane>& split_planes) {
  using Key = std::array<double, 3>;
  auto key = [](const glm::dvec3& p) { return Key{p.x, p.y, p.z}; };
  std::vector<CutSegment> segs = segments;
  std::vector<bool> alive(segs.size(), true);
  std::map<Key, std::vector<size_t>> incident;  // end point -> segments ending there
  std::vector<Key> order;                       // end points in order of first appearance
  for (size_t i = 0; i < segs.size(); ++i) {
    for (const glm::dvec3& p : {segs[i].a, segs[i].b}) {
      auto& list = incident[key(p)];
      if (list.empty()) order.push_back(key(p));
      list.push_back(i);
    }
  }
  for (const Key& k : order) {
    auto& list = incident[k];
    if (list.size() != 2 || list[0] == list[1]) continue;
    const size_t i = list[0], j = list[1];
    CutSegment& s = segs[i];
    const CutSegment& t = segs[j];
    if (!alive[i] || !alive[j] || s.surface != t.surface) continue;
    const glm::dvec3 p(k[0], k[1], k[2]);
    // Orient both away from p: s runs q -> p, t runs p -> r.
    const bool s_ends_at_p = key(s.b) == k, t_starts_at_p = key(t.a) == k;
    const glm::dvec3 q = s_ends_at_p ? s.a : s.b, r = t_starts_at_p ? t.b : t.a;
    const double chord = glm::distance(q, r);
    if (chord > max_length_m || chord == 0) continue;
    const double off = glm::length(glm::cross(p - q, r - q)) / chord;
    if (off > tolerance_m) continue;
    bool straddles = false;
    for (const Plane& split : split_planes) {
      const double dq = glm::dot(q - split.point, split.normal);
      const double dp = glm::dot(p - split.point, split.normal);
      const double dr = glm::dot(r - split.point, split.normal);
      straddles = straddles || !((dq > 0 && dp > 0 && dr > 0) || (dq < 0 && dp < 0 && dr < 0));
    }
    if (straddles) continue;
    // A loop smaller than the tolerance must keep three segments: merging q-p-r where a
    // segment r-q exists would leave a two-segment loop of no area.
    bool closes_loop = false;
    for (size_t x : incident[key(q)]) {
      if (x == i || x == j || !alive[x]) continue;
      const CutSegment& u = segs[x];
      closes_loop = closes_loop || key(u.a) == key(r) || key(u.b) == key(r);
    }
    if (closes_loop) continue;
    CutSegment merged = s;
    merged.a = q;
    merged.at_a = s_ends_at_p ? s.at_a : s.at_b;
    merged.b = r;
    merged.at_b = t_starts_at_p ? t.at_b : t.at_a;
    if (!s_ends_at_p) {  // the loop runs r -> p -> q: keep its direction
      std::swap(merged.a, merged.b);
      std::swap(merged.at_a, merged.at_b);
    }
    s = merged;
    alive[j] = false;
    list.clear();
    for (size_t& x : incident[key(r)])
      if (x == j) x = i;
  }
  std::vector<CutSegment> out;
  for (size_t i = 0; i < segs.size(); ++i)
    if (alive[i]) out.push_back(segs[i]);
  return out;
}

}  // namespace cutaway
