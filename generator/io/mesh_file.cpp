#include "io/mesh_file.h"

#include <cstdint>
#include <filesystem>
#include <sstream>
#include <vector>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <glm/common.hpp>

#include "base/colour.h"
#include "base/file_read.h"
#include "io/ply_guard.h"
#include "model/ds_model.h"

namespace cutaway {

static_assert(kMaxMeshVertices == kMaxModelVertices,
              "a mesh file may declare the model's whole vertex budget, no more");

namespace {

/// The mesh type OpenMesh reads PLY into (custom properties are attached by name).
using PlyMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;

/// The bytes of a mesh file, refused when it is not a .ply path, not a regular file or larger
/// than kMaxMeshFileBytes (read_regular_file: nothing is read from a FIFO or device).
std::string mesh_file_bytes(const std::string& file, const FileLoc& loc, const std::string& field) {
  if (std::filesystem::path(file).extension() != ".ply") {
    throw InputError(loc, field, "a mesh surface's file must be a PLY file (.ply)");
  }
  try {
    return read_regular_file(file, kMaxMeshFileBytes);
  } catch (const FileReadError& e) {
    throw InputError(loc, field, "the mesh file " + quoted(file) + " " + e.rule());
  }
}

/// The mesh of a PLY file that passed check_ply, read by OpenMesh as its header declares.
PlyMesh read_ply(const std::string& file, const FileLoc& loc, const std::string& field) {
  std::string bytes = mesh_file_bytes(file, loc, field);
  const PlyCheck check = check_ply(bytes, loc, field);
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

MeshData read_mesh_file(const std::string& file, const FileLoc& loc, const std::string& field) {
  const PlyMesh ply = read_ply(file, loc, field);
  MeshData m;
  m.points.reserve(ply.n_vertices());
  for (auto v : ply.vertices()) {
    const auto& p = ply.point(v);
    m.points.emplace_back(p[0], p[1], p[2]);
  }
  m.triangles.reserve(ply.n_faces());
  for (auto f : ply.faces()) {
    std::array<int, 3> t{};
    std::array<OpenMesh::Vec3d, 3> p;
    int k = 0;
    for (auto v : ply.fv_range(f)) {
      t[k] = v.idx();
      p[k++] = ply.point(v);
    }
    m.triangles.push_back(t);
    m.signed_volume6 += OpenMesh::dot(p[0], OpenMesh::cross(p[1], p[2]));
  }
  m.closed = true;
  for (auto h : ply.halfedges()) m.closed = m.closed && !ply.is_boundary(h);
  m.front = vertex_colours(ply, "front_red", "front_green", "front_blue");
  m.back = vertex_colours(ply, "back_red", "back_green", "back_blue");
  bool blur_integer;
  m.blur = vertex_property(ply, "blur", blur_integer);
  return m;
}

}  // namespace cutaway
