#include "mesh_import.h"

#include <algorithm>
#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <glm/common.hpp>

#include "colour.h"

namespace cutaway {

namespace {

/// The mesh type OpenMesh reads PLY into (custom properties are attached by name).
using PlyMesh = OpenMesh::TriMesh_ArrayKernelT<OpenMesh::DefaultTraitsDouble>;

/// A PLY file's bytes prepared for OpenMesh, and the vertex count its header declares.
struct PlyText {
  std::string bytes;
  long vertex_count = -1;  ///< -1: not declared
};

/// OpenMesh 9's ASCII PLY reader reads a custom 8-bit property (char, uchar, int8, uint8) as one
/// character instead of a number, which corrupts that value and everything after it (binary
/// files are read correctly). In an ASCII file such a property's text is also a valid `int`, so
/// its declaration is widened to `int` before OpenMesh reads it; colours stored as integers are
/// 0..255 either way. Other bytes are unchanged. Also notes `element vertex N`: OpenMesh adds
/// vertices of its own when it has to split faces that break the 2-manifold.
PlyText prepare_ply(std::string ply) {
  PlyText out;
  const size_t header_end = ply.find("end_header");
  if (header_end == std::string::npos) {
    out.bytes = std::move(ply);
    return out;
  }
  std::istringstream header(ply.substr(0, header_end));
  std::string text, line;
  bool ascii = false;
  while (std::getline(header, line)) {
    std::istringstream words(line);
    std::vector<std::string> w;
    for (std::string x; words >> x;) w.push_back(x);
    if (w.size() >= 2 && w[0] == "format") ascii = w[1] == "ascii";
    if (w.size() == 3 && w[0] == "element" && w[1] == "vertex") {
      out.vertex_count = std::strtol(w[2].c_str(), nullptr, 10);
    }
    if (w.size() == 3 && w[0] == "property" &&
        (w[1] == "char" || w[1] == "uchar" || w[1] == "int8" || w[1] == "uint8")) {
      line = "property int " + w[2] + (line.ends_with('\r') ? "\r" : "");
    }
    text += line + '\n';
  }
  out.bytes = ascii ? text + ply.substr(header_end) : std::move(ply);
  return out;
}

PlyMesh read_ply(const std::string& file, const FileLoc& loc, const std::string& field) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw InputError(loc, field, "the mesh file '" + file + "' does not exist");
  }
  if (std::filesystem::path(file).extension() != ".ply") {
    throw InputError(loc, field, "a mesh surface's file must be a PLY file (.ply)");
  }
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  const PlyText prepared = prepare_ply(text.str());
  std::istringstream ply(prepared.bytes);
  PlyMesh mesh;
  OpenMesh::IO::Options opt = OpenMesh::IO::Options::Custom;
  if (!in || !OpenMesh::IO::read_mesh(mesh, ply, "ply", opt) || mesh.n_faces() == 0) {
    throw InputError(loc, field, "cannot read '" + file + "' as a triangle mesh (PLY)");
  }
  if (prepared.vertex_count >= 0 &&
      static_cast<long>(mesh.n_vertices()) != prepared.vertex_count) {
    throw InputError(loc, field,
                     "the mesh is not an oriented 2-manifold: some faces make a complex edge or "
                     "vertex, or flip orientation");
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

DsSurface import_mesh_surface(const SurfaceSpec& spec, const Template& tmpl) {
  const std::string field = spec.path + ".file";
  PlyMesh ply = read_ply(spec.mesh_file, spec.mesh_loc, field);
  const auto front = vertex_colours(ply, "front_red", "front_green", "front_blue");
  const auto back = vertex_colours(ply, "back_red", "back_green", "back_blue");
  bool blur_integer;
  const auto blur = vertex_property(ply, "blur", blur_integer);

  DsSurface s;
  s.name = spec.name;
  s.role = spec.is_skin ? SurfaceRole::Skin : SurfaceRole::Structure;
  s.visible_front = spec.visible_front;
  s.visible_back = spec.visible_back;
  // A closed mesh's front is its outside (spec: Front and back): wound inwards, it is turned.
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
