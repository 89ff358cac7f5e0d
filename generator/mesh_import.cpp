#include "mesh_import.h"

#include <filesystem>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <glm/common.hpp>

#include "colour.h"

namespace cutaway {

namespace {

/// The mesh type OpenMesh reads PLY into (custom properties are attached by name).
using PlyMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;

PlyMesh read_ply(const std::string& file, const FileLoc& loc, const std::string& field) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(loc, field, "the mesh file '" + file + "' does not exist");
  }
  if (std::filesystem::path(file).extension() != ".ply") {
    throw InputError(loc, field, "a mesh surface's file must be a PLY file (.ply)");
  }
  PlyMesh mesh;
  OpenMesh::IO::Options opt = OpenMesh::IO::Options::Custom;
  if (!OpenMesh::IO::read_mesh(mesh, file, opt) || mesh.n_faces() == 0) {
    throw InputError(loc, field, "cannot read '" + file + "' as a triangle mesh (PLY)");
  }
  return mesh;
}

/// Reads a named custom vertex property as double, whatever its PLY scalar type.
template <class T>
bool read_property(const PlyMesh& mesh, const char* name, std::vector<double>& out) {
  OpenMesh::VPropHandleT<T> h;
  if (!mesh.get_property_handle(h, name)) return false;
  out.resize(mesh.n_vertices());
  for (auto vh : mesh.vertices()) out[vh.idx()] = static_cast<double>(mesh.property(h, vh));
  return true;
}

/// Property `name` as doubles (empty if absent); `is_byte` tells whether it was uchar.
std::vector<double> vertex_property(const PlyMesh& mesh, const char* name, bool& is_byte) {
  std::vector<double> v;
  is_byte = read_property<unsigned char>(mesh, name, v);
  if (!is_byte && !read_property<float>(mesh, name, v)) read_property<double>(mesh, name, v);
  return v;
}

/// Per-vertex colour (linear) from the three named properties, or empty when absent.
std::vector<glm::dvec3> vertex_colours(const PlyMesh& mesh, const char* r, const char* g,
                                       const char* b) {
  bool byte_r, byte_g, byte_b;
  const auto vr = vertex_property(mesh, r, byte_r), vg = vertex_property(mesh, g, byte_g),
             vb = vertex_property(mesh, b, byte_b);
  if (vr.empty() || vg.empty() || vb.empty()) return {};
  std::vector<glm::dvec3> out(vr.size());
  for (size_t i = 0; i < vr.size(); ++i) {
    glm::dvec3 c(vr[i], vg[i], vb[i]);
    if (byte_r) c /= 255.0;
    out[i] = srgb_to_linear(glm::clamp(c, 0.0, 1.0));
  }
  return out;
}

}  // namespace

MeshBounds read_mesh_bounds(const std::string& file, double metres_per_unit, const FileLoc& loc,
                            const std::string& field) {
  const PlyMesh mesh = read_ply(file, loc, field);
  MeshBounds b;
  bool first = true;
  for (auto vh : mesh.vertices()) {
    const auto p = mesh.point(vh) * metres_per_unit;
    const glm::dvec3 q(p[0], p[1], p[2]);
    b.min = first ? q : glm::min(b.min, q);
    b.max = first ? q : glm::max(b.max, q);
    first = false;
  }
  return b;
}

DsSurface import_mesh_surface(const SurfaceSpec& spec, const Template& tmpl) {
  const std::string field = spec.path + ".file";
  PlyMesh ply = read_ply(spec.mesh_file, spec.mesh_loc, field);
  const auto front = vertex_colours(ply, "front_red", "front_green", "front_blue");
  const auto back = vertex_colours(ply, "back_red", "back_green", "back_blue");
  bool blur_byte;
  const auto blur = vertex_property(ply, "blur", blur_byte);

  DsSurface s;
  s.name = spec.name;
  s.role = spec.is_skin ? SurfaceRole::Skin : SurfaceRole::Structure;
  s.visible_front = spec.visible_front;
  s.visible_back = spec.visible_back;
  std::vector<DsMesh::VertexHandle> vh;
  for (auto v : ply.vertices()) {
    const auto p = ply.point(v) * tmpl.metres_per_unit;
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
      throw InputError(spec.mesh_loc, field, "the mesh has a vertex that is not a finite number");
    }
    auto h = s.mesh.add_vertex(DsMesh::Point(p[0], p[1], p[2]));
    auto& d = s.mesh.data(h);
    const size_t i = static_cast<size_t>(v.idx());
    const glm::dvec3 f = front.empty() ? spec.front.at(0, 0) : front[i];
    const glm::dvec3 b = back.empty() ? spec.back.at(0, 0) : back[i];
    d.front = {f.x, f.y, f.z};
    d.back = {b.x, b.y, b.z};
    d.blur = blur.empty() ? spec.blur.at(0, 0) : std::max(0.0, blur[i] * tmpl.metres_per_unit);
    vh.push_back(h);
  }
  for (auto f : ply.faces()) {
    std::vector<DsMesh::VertexHandle> corners;
    for (auto v : ply.fv_range(f)) corners.push_back(vh[v.idx()]);
    if (!s.mesh.add_face(corners).is_valid()) {
      throw InputError(spec.mesh_loc, field,
                       "the mesh is not an oriented 2-manifold (face " + std::to_string(f.idx()) +
                           " makes a complex edge or flips orientation)");
    }
  }
  if (spec.is_skin) {
    for (auto h : s.mesh.halfedges()) {
      if (s.mesh.is_boundary(h)) {
        throw InputError(spec.mesh_loc, field, "the skin must be a closed mesh (it has a hole)");
      }
    }
  }
  return s;
}

}  // namespace cutaway
