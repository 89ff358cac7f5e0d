#include "scene/scene_assets.h"

namespace cutaway {

std::span<const glm::uvec3> primitive_triangles(const AssetMesh& mesh, const AssetPrimitive& p,
                                                bool textured) {
  if (textured && !p.coarse.empty()) return p.coarse;
  return std::span<const glm::uvec3>(mesh.triangle).subspan(p.first, p.count);
}

std::string primitives_defect(const AssetMesh& mesh, size_t materials) {
  if (mesh.primitives.empty() && materials == 0) return "material index out of range";
  size_t next = 0;
  for (const AssetPrimitive& p : mesh.primitives) {
    if (p.first != next || p.count == 0) return "primitives must cover the triangles in order";
    if (p.material < 0 || static_cast<size_t>(p.material) >= materials)
      return "material index out of range";
    next += p.count;
  }
  if (!mesh.primitives.empty() && next != mesh.triangle.size())
    return "primitives must cover the triangles in order";
  return "";
}

}  // namespace cutaway
