#include "model/model_checks.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/intersection.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

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
}

}  // namespace cutaway
