#include "model/inside_test.h"

#include <array>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

namespace cutaway {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<Kernel::Point_3>;

}  // namespace

struct InsideTest::Impl {
  SurfaceMesh mesh;
  std::unique_ptr<CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel>> side;
};

InsideTest::InsideTest(const DsMesh& mesh) : impl_(new Impl) {
  std::vector<SurfaceMesh::Vertex_index> v;
  v.reserve(mesh.n_vertices());
  for (auto vh : mesh.vertices()) {
    const auto& p = mesh.point(vh);
    v.push_back(impl_->mesh.add_vertex(Kernel::Point_3(p[0], p[1], p[2])));
  }
  for (auto fh : mesh.faces()) {
    std::array<SurfaceMesh::Vertex_index, 3> f;
    int k = 0;
    for (auto vh : mesh.fv_range(fh)) f[k++] = v[vh.idx()];
    impl_->mesh.add_face(f[0], f[1], f[2]);
  }
  impl_->side.reset(new CGAL::Side_of_triangle_mesh<SurfaceMesh, Kernel>(impl_->mesh));
}

InsideTest::~InsideTest() = default;

bool InsideTest::inside(const glm::dvec3& p) const {
  return (*impl_->side)(Kernel::Point_3(p.x, p.y, p.z)) == CGAL::ON_BOUNDED_SIDE;
}

bool closed_surface(const DsMesh& mesh) {
  if (mesh.n_faces() == 0) return false;
  for (auto h : mesh.halfedges())
    if (mesh.is_boundary(h)) return false;
  return true;
}

std::vector<size_t> surfaces_inside(const DsModel& model, size_t s) {
  std::vector<size_t> out;
  if (!closed_surface(model.surfaces[s].mesh)) return out;
  return surfaces_inside(model, s, InsideTest(model.surfaces[s].mesh));
}

std::vector<size_t> surfaces_inside(const DsModel& model, size_t s, const InsideTest& test) {
  std::vector<size_t> out;
  for (size_t j = 0; j < model.surfaces.size(); ++j) {
    const DsMesh& mesh = model.surfaces[j].mesh;
    if (j == s || mesh.n_vertices() == 0) continue;
    if (test.inside(to_glm(mesh.point(*mesh.vertices_begin())))) out.push_back(j);
  }
  return out;
}

}  // namespace cutaway
