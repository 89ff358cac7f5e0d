#include "export/ply_export.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include "base/colour.h"
#include "base/error.h"

namespace cutaway {

std::string section_to_ply(const CrossSection& section) {
  using Mesh = OpenMesh::TriMesh_ArrayKernelT<>;
  Mesh mesh;
  mesh.request_vertex_colors();
  std::vector<Mesh::VertexHandle> vh;
  for (size_t i = 0; i < section.position.size(); ++i) {
    const glm::dvec3& p = section.position[i];
    const auto h = mesh.add_vertex(
        Mesh::Point(static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)));
    const glm::dvec3 c = linear_to_srgb(section.colour[i]);
    mesh.set_color(h, Mesh::Color(static_cast<unsigned char>(std::lround(c.x * 255)),
                                  static_cast<unsigned char>(std::lround(c.y * 255)),
                                  static_cast<unsigned char>(std::lround(c.z * 255))));
    vh.push_back(h);
  }
  for (const glm::uvec3& t : section.triangle) {
    if (!mesh.add_face(vh[t.x], vh[t.y], vh[t.z]).is_valid()) {
      throw InternalError("the cross-section is not a manifold triangle mesh");
    }
  }
  std::ostringstream out;
  const OpenMesh::IO::Options options =
      OpenMesh::IO::Options::Binary | OpenMesh::IO::Options::VertexColor;
  if (!OpenMesh::IO::write_mesh(mesh, out, ".ply", options)) {
    throw EnvironmentError("cannot encode the cross-section as PLY");
  }
  return out.str();
}

}  // namespace cutaway
