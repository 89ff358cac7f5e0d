#include "model/model_checks.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/intersection.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include "model/inside_test.h"

#include <cstdio>
#include <exception>
#include <iterator>
#include <string>
#include <vector>

namespace cutaway {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

SurfaceMesh to_cgal(const DsMesh& mesh) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> v;
  v.reserve(mesh.n_vertices());
  for (auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    v.push_back(sm.add_vertex(Kernel::Point_3(p[0], p[1], p[2])));
  }
  for (auto fh : mesh.faces()) {
    std::array<SurfaceMesh::Vertex_index, 3> f;
    int k = 0;
    for (auto vh : mesh.fv_range(fh)) f[k++] = v[vh.idx()];
    sm.add_face(f[0], f[1], f[2]);
  }
  return sm;
}

/// " near (x, y, z)" in template units: a point where `a` and `b` cross (the first point of
/// their intersection polylines, CGAL's corefinement); empty where it finds none (surfaces that
/// only touch, or faces it cannot intersect).
std::string crossing_point(const SurfaceMesh& a, const SurfaceMesh& b, double metres_per_unit) {
  std::vector<std::vector<Kernel::Point_3>> lines;
  try {
    PMP::surface_intersection(a, b, std::back_inserter(lines));
  } catch (const std::exception&) {
    return "";
  }
  for (const auto& line : lines) {
    if (line.empty()) continue;
    const Kernel::Point_3& p = line.front();
    char buf[96];
    std::snprintf(buf, sizeof buf, " near (%.1f, %.1f, %.1f)", p.x() / metres_per_unit,
                  p.y() / metres_per_unit, p.z() / metres_per_unit);
    return buf;
  }
  return "";
}

}  // namespace

void check_model(const Template& t, const DsModel& model, const std::vector<int>& specs) {
  const SurfaceSpec& skin_spec = t.surfaces[specs[0]];
  const DsMesh& skin = model.surfaces[0].mesh;
  for (auto h : skin.halfedges()) {
    if (skin.is_boundary(h)) {
      throw InputError(skin_spec.loc, skin_spec.path,
                       "the skin must be a closed surface (it has a hole)");
    }
  }
  const SurfaceMesh skin_sm = to_cgal(skin);
  const CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel> side(skin_sm);
  for (size_t i = 1; i < model.surfaces.size(); ++i) {
    const SurfaceSpec& spec = t.surfaces[specs[i]];
    const DsMesh& mesh = model.surfaces[i].mesh;
    const SurfaceMesh sm = to_cgal(mesh);
    if (PMP::do_intersect(skin_sm, sm)) {
      throw InputError(spec.loc, spec.path,
                       "surface " + quoted(spec.name) + " touches or crosses the skin " +
                           quoted(skin_spec.name) +
                           ": every other surface must lie inside the skin");
    }
    for (auto vh : mesh.vertices()) {
      const auto& p = mesh.point(vh);
      if (side(Kernel::Point_3(p[0], p[1], p[2])) != CGAL::ON_BOUNDED_SIDE) {
        throw InputError(spec.loc, spec.path,
                         "surface " + quoted(spec.name) + " lies outside the skin " +
                             quoted(skin_spec.name) +
                             ": every other surface must lie inside the skin");
      }
    }
  }
  // A rigid surface is closed, and no other surface crosses or touches it: each lies wholly
  // inside it (kept whole with it) or wholly outside (cut as flesh).
  for (size_t i = 1; i < model.surfaces.size(); ++i) {
    if (!model.surfaces[i].rigid) continue;
    const SurfaceSpec& spec = t.surfaces[specs[i]];
    if (!closed_surface(model.surfaces[i].mesh)) {
      throw InputError(spec.loc, spec.path,
                       "rigid: the rigid surface " + quoted(spec.name) +
                           " must be closed (it has a hole), since a cut keeps what it "
                           "encloses whole");
    }
  }
  // No two surfaces cross or touch: each lies inside, outside or beside each other one (a
  // crossing gives cut faces whose regions are not nested, and colours smeared across them).
  std::vector<SurfaceMesh> inner;
  for (size_t i = 1; i < model.surfaces.size(); ++i)
    inner.push_back(to_cgal(model.surfaces[i].mesh));
  for (size_t j = 1; j < model.surfaces.size(); ++j) {
    for (size_t i = 1; i < j; ++i) {
      if (!PMP::do_intersect(inner[i - 1], inner[j - 1])) continue;
      const SurfaceSpec& a = t.surfaces[specs[i]];
      const SurfaceSpec& b = t.surfaces[specs[j]];
      const bool rigid = model.surfaces[i].rigid || model.surfaces[j].rigid;
      throw InputError(b.loc, b.path,
                       "surface " + quoted(b.name) + " touches or crosses " +
                           (rigid ? "the rigid surface " : "surface ") + quoted(a.name) +
                           crossing_point(inner[i - 1], inner[j - 1], t.metres_per_unit) +
                           (rigid ? ": a surface lies wholly inside a rigid one or wholly "
                                    "outside it"
                                  : ": surfaces may nest inside each other but not cross"));
    }
  }
}

}  // namespace cutaway
