#include "model/mesh_import.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <vector>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <glm/common.hpp>

#include "base/colour.h"
#include "base/file_read.h"
#include "io/ply_guard.h"
#include "model/sweep.h"

namespace cutaway {

static_assert(kMaxMeshVertices == kMaxModelVertices,
              "a mesh file may declare the model's whole vertex budget, no more");

namespace {

/// The mesh type OpenMesh reads PLY into (custom properties are attached by name).
using PlyMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;


/// The bytes of a mesh file, refused when it is not a .ply path, not a regular file or larger
/// than kMaxMeshFileBytes (read_regular_file: nothing is read from a FIFO or device).
std::string read_mesh_file(const std::string& file, const FileLoc& loc, const std::string& field) {
  if (std::filesystem::path(file).extension() != ".ply") {
    throw InputError(loc, field, "a mesh surface's file must be a PLY file (.ply)");
  }
  try {
    return read_regular_file(file, kMaxMeshFileBytes);
  } catch (const FileReadError& e) {
    throw InputError(loc, field, "the mesh file " + quoted(file) + " " + e.rule());
  }
}

/// The mesh of a PLY file that passed check_ply and declares at most `max_vertices` vertices.
PlyMesh read_ply(const std::string& file, const FileLoc& loc, const std::string& field,
                 size_t max_vertices = kMaxMeshVertices) {
  std::string bytes = read_mesh_file(file, loc, field);
  const PlyCheck check = check_ply(bytes, loc, field);
  if (check.vertices > max_vertices) {
    throw InputError(loc, field,
                     "the mesh has " + std::to_string(check.vertices) +
                         " vertices, and the model may have at most " +
                         std::to_string(kMaxModelVertices) + " over all surfaces (" +
                         std::to_string(kMaxModelVertices - max_vertices) +
                         " taken by the surfaces before it)");
  }
  std::istringstream ply(prepare_ply(std::move(bytes), check.binary, check.header_end));
  PlyMesh mesh;
  OpenMesh::IO::Options opt = OpenMesh::IO::Options::Custom;
  if (!OpenMesh::IO::read_mesh(mesh, ply, "ply", opt) || mesh.n_faces() == 0) {
    throw InputError(loc, field, "cannot read " + quoted(file) + " as a triangle mesh (PLY)");
  }
  // OpenMesh adds vertices of its own when it has to split faces that break the 2-manifold.
  if (mesh.n_vertices() != check.vertices) {
    throw InputError(loc, field,
                     "the mesh is not an oriented 2-manifold: some faces make a complex edge or "
                     "vertex, or flip orientation");
  }
  if (mesh.n_faces() != check.triangles) {
    throw InputError(loc, field,
                     "OpenMesh read " + std::to_string(mesh.n_faces()) + " of the " +
                         std::to_string(check.triangles) + " triangles the file's faces make");
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

/// Property `name` as doubles (empty if absent); `is_integer` tells whether it had an integer
/// type (colours 0..255) rather than a floating-point one (colours 0..1).
std::vector<double> vertex_property(const PlyMesh& mesh, const char* name, bool& is_integer) {
  std::vector<double> v;
  is_integer = read_property<unsigned char>(mesh, name, v) ||
               read_property<signed char>(mesh, name, v) || read_property<short>(mesh, name, v) ||
               read_property<unsigned short>(mesh, name, v) || read_property<int>(mesh, name, v) ||
               read_property<unsigned int>(mesh, name, v);
  if (!is_integer && !read_property<float>(mesh, name, v)) read_property<double>(mesh, name, v);
  return v;
}

/// Per-vertex colour (linear) from the three named properties, or empty when absent.
std::vector<glm::dvec3> vertex_colours(const PlyMesh& mesh, const char* r, const char* g,
                                       const char* b) {
  bool int_r, int_g, int_b;
  const auto vr = vertex_property(mesh, r, int_r), vg = vertex_property(mesh, g, int_g),
             vb = vertex_property(mesh, b, int_b);
  if (vr.empty() || vg.empty() || vb.empty()) return {};
  // Each component by its own type: integers are 0..255, floating point 0..1.
  const glm::dvec3 scale(int_r ? 1 / 255.0 : 1.0, int_g ? 1 / 255.0 : 1.0, int_b ? 1 / 255.0 : 1.0);
  std::vector<glm::dvec3> out(vr.size());
  for (size_t i = 0; i < vr.size(); ++i) {
    const glm::dvec3 c = glm::dvec3(vr[i], vg[i], vb[i]) * scale;
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

DsSurface import_mesh_surface(const SurfaceSpec& spec, const Template& tmpl,
                              size_t max_vertices) {
  const std::string field = spec.path + ".file";
  PlyMesh ply = read_ply(spec.mesh_file, spec.mesh_loc, field, max_vertices);
  const auto front = vertex_colours(ply, "front_red", "front_green", "front_blue");
  const auto back = vertex_colours(ply, "back_red", "back_green", "back_blue");
  bool blur_integer;
  const auto blur = vertex_property(ply, "blur", blur_integer);

  DsSurface s;
  s.name = spec.name;
  s.role = spec.is_skin ? SurfaceRole::Skin : SurfaceRole::Structure;
  s.visible_front = spec.visible_front;
  s.visible_back = spec.visible_back;
  // A closed mesh's front is its outside (doc/template-format.md, Surfaces: Front and back):
  // wound inwards, it is turned.
  bool closed = true;
  for (auto h : ply.halfedges()) closed = closed && !ply.is_boundary(h);
  double volume = 0;
  for (auto f : ply.faces()) {
    std::array<OpenMesh::Vec3d, 3> p;
    int k = 0;
    for (auto v : ply.fv_range(f)) p[k++] = ply.point(v);
    volume += OpenMesh::dot(p[0], OpenMesh::cross(p[1], p[2]));
  }
  const bool turn = closed && volume < 0;

  // Vertices no face uses have no normal and no meaning in a DS: they are left out.
  std::vector<DsMesh::VertexHandle> vh(ply.n_vertices());
  for (auto v : ply.vertices()) {
    if (ply.is_isolated(v)) continue;
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
    vh[i] = h;
  }
  for (auto f : ply.faces()) {
    std::vector<DsMesh::VertexHandle> corners;
    for (auto v : ply.fv_range(f)) corners.push_back(vh[v.idx()]);
    if (turn) std::reverse(corners.begin(), corners.end());
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
