#include "scene/scene_assets.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/trigonometric.hpp>

#include "base/error.h"
#include "base/finite.h"

namespace cutaway {

std::string camera_defect(const AssetCamera& c, bool needs_up) {
  if (!all_finite(c.eye) || !all_finite(c.target) || !all_finite(c.up))
    return "eye, target and up must be finite";
  const glm::dvec3 forward = c.target - c.eye;
  if (!(glm::length(forward) > 0)) return "eye and target coincide";
  if (needs_up && (!(glm::length(c.up) > 0) ||
                   !(glm::length(glm::cross(glm::normalize(forward), c.up)) >
                     1e-9 * glm::length(c.up))))
    return "up is zero or parallel to the view direction";
  if (!(c.fov_y_deg > 0 && c.fov_y_deg < 180))
    return "fov_y_deg must be in (0, 180), not " + std::to_string(c.fov_y_deg);
  if (!(c.aspect > 0 && std::isfinite(c.aspect))) return "aspect must be positive and finite";
  if (!(c.znear > 0 && c.znear < c.zfar && std::isfinite(c.zfar)))
    return "need 0 < znear < zfar (finite), not " + std::to_string(c.znear) + ", " +
           std::to_string(c.zfar);
  return "";
}

glm::dvec3 stable_camera_up(const glm::dvec3& forward) {
  const glm::dvec3 f = glm::normalize(forward);
  return std::abs(f.y) > std::cos(glm::radians(0.5)) ? glm::dvec3(0, 0, -1) : glm::dvec3(0, 1, 0);
}

CameraFrame camera_frame(const AssetCamera& camera) {
  CameraFrame f;
  f.forward = glm::normalize(camera.target - camera.eye);
  f.right = glm::normalize(glm::cross(f.forward, camera.up));
  f.up = glm::cross(f.right, f.forward);
  return f;
}

glm::dmat4 view_from_scene(const AssetCamera& camera) {
  return glm::lookAt(camera.eye, camera.target, camera.up);
}

double focal_length_px(const AssetCamera& camera, int height_px) {
  return height_px / (2 * std::tan(glm::radians(camera.fov_y_deg) / 2));
}

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

namespace {

std::string texture_defect(const AssetTexture& t) {
  if (t.width < 1 || t.height < 1)
    return "is " + std::to_string(t.width) + "x" + std::to_string(t.height) +
           " (must be at least 1x1)";
  if (t.channels != 3 && t.channels != 4)
    return "has " + std::to_string(t.channels) + " channels (must be 3 or 4)";
  const size_t bytes = static_cast<size_t>(t.width) * static_cast<size_t>(t.height) *
                       static_cast<size_t>(t.channels);
  if (t.pixels.size() != bytes)
    return "has " + std::to_string(t.pixels.size()) +
           " bytes of pixels, not width * height * channels = " + std::to_string(bytes);
  return "";
}

std::string material_defect(const AssetMaterial& m, const std::vector<AssetTexture>& textures) {
  if (const std::string_view field = out_of_range_field(m.pbr); !field.empty())
    return "has " + std::string(field) + " outside its range";
  for (const auto& [field, texture] : {std::pair{"base_colour_texture", m.base_colour_texture},
                                       std::pair{"material_texture", m.material_texture}})
    if (texture < -1 || texture >= static_cast<int>(textures.size()))
      return "has " + std::string(field) + " " + std::to_string(texture) + ", neither -1 nor in 0.." +
             std::to_string(static_cast<long>(textures.size()) - 1);
  if (m.base_colour_texture >= 0 &&
      textures[static_cast<size_t>(m.base_colour_texture)].channels != 3)
    return "has a base colour texture that is not RGB (3 channels)";
  return "";
}

std::string mesh_defect(const AssetMesh& m, const std::vector<AssetMaterial>& materials,
                        const AssetRules& rules) {
  const size_t n = m.position.size();
  if (rules.meshes_need_triangles && (n == 0 || m.triangle.empty())) return "has no triangles";
  if (m.normal.size() != n || m.colour.size() != n)
    return "has " + std::to_string(n) + " positions, " + std::to_string(m.normal.size()) +
           " normals and " + std::to_string(m.colour.size()) + " colours (must be equal)";
  for (size_t v = 0; v < n; ++v)
    if (!all_finite(m.position[v]) || !all_finite(m.colour[v]) ||
        (!rules.normals_repaired && !all_finite(m.normal[v])))
      return "vertex " + std::to_string(v) + " has a non-finite position, normal or colour";
  if (!m.uv.empty() && m.uv.size() != n)
    return "has " + std::to_string(m.uv.size()) + " texture coordinates for " +
           std::to_string(n) + " positions (must be equal, or none)";
  for (size_t v = 0; v < m.uv.size(); ++v)
    if (!all_finite(m.uv[v]))
      return "vertex " + std::to_string(v) + " has non-finite texture coordinates";
  const auto out_of_range = [n](const std::vector<glm::uvec3>& triangles) {
    for (size_t t = 0; t < triangles.size(); ++t)
      for (int i = 0; i < 3; ++i)
        if (triangles[t][i] >= n) return true;
    return false;
  };
  if (out_of_range(m.triangle)) return "has a triangle vertex index not below " + std::to_string(n);
  if (std::string defect = primitives_defect(m, materials.size()); !defect.empty()) return defect;
  for (const AssetPrimitive& p : m.primitives) {
    if (out_of_range(p.coarse))
      return "has a coarse triangle vertex index not below " + std::to_string(n);
    if (rules.textures_need_uv && m.uv.empty() &&
        materials[static_cast<size_t>(p.material)].base_colour_texture >= 0)
      return "has no uv for its textured material " + std::to_string(p.material);
  }
  return "";
}

std::string light_defect(const AssetLight& l) {
  if (!all_finite(l.position) || !all_finite(l.direction) || !all_finite(l.colour) ||
      !std::isfinite(l.intensity))
    return "has a non-finite field";
  if (l.intensity < 0 || l.colour.r < 0 || l.colour.g < 0 || l.colour.b < 0)
    return "has a negative intensity or colour";
  if (l.type == LightType::Directional && !(glm::length(l.direction) > 0))
    return "is directional with a zero direction";
  return "";
}

/// "KIND INDEX 'NAME' DEFECT", or "" for no defect.
std::string named(const char* kind, size_t index, const std::string& name,
                  const std::string& defect) {
  return defect.empty() ? ""
                        : std::string(kind) + " " + std::to_string(index) + " '" + name + "' " +
                              defect;
}

}  // namespace

std::string assets_defect(const SceneAssets& a, const AssetRules& rules) {
  if (a.materials.empty()) return "no materials (material 0 is the plain one)";
  for (size_t i = 0; i < a.textures.size(); ++i)
    if (auto d = named("texture", i, a.textures[i].name, texture_defect(a.textures[i]));
        !d.empty())
      return d;
  for (size_t i = 0; i < a.materials.size(); ++i)
    if (auto d = named("material", i, a.materials[i].name,
                       material_defect(a.materials[i], a.textures));
        !d.empty())
      return d;
  for (size_t i = 0; i < a.meshes.size(); ++i)
    if (auto d = named("mesh", i, a.meshes[i].name, mesh_defect(a.meshes[i], a.materials, rules));
        !d.empty())
      return d;
  for (size_t i = 0; i < a.instances.size(); ++i) {
    const AssetInstance& inst = a.instances[i];
    const glm::dquat& q = inst.rotation;
    std::string defect;
    if (inst.mesh < 0 || static_cast<size_t>(inst.mesh) >= a.meshes.size())
      defect = "has mesh index " + std::to_string(inst.mesh) + ", not in 0.." +
               std::to_string(static_cast<long>(a.meshes.size()) - 1);
    else if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) ||
             !std::isfinite(q.z) || !(glm::length(q) > 0) || !all_finite(inst.translation))
      defect = "has a zero or non-finite rotation, or a non-finite translation";
    for (const AssetHull& hull : inst.collision) {
      bool bad = hull.position.size() < 4 || hull.triangle.size() < 4;
      for (const glm::dvec3& p : hull.position) bad = bad || !all_finite(p);
      for (const glm::uvec3& t : hull.triangle)
        bad = bad || std::max({t.x, t.y, t.z}) >= hull.position.size();
      if (bad && defect.empty())
        defect = "has a collision hull with under 4 corners or 4 triangles, a non-finite corner "
                 "or an index out of range";
    }
    if (auto d = named("instance", i, inst.name, defect); !d.empty()) return d;
  }
  if (const std::string d = camera_defect(a.camera, rules.camera_needs_up); !d.empty())
    return "camera: " + d;
  for (size_t i = 0; i < a.lights.size(); ++i)
    if (auto d = named("light", i, a.lights[i].name, light_defect(a.lights[i])); !d.empty())
      return d;
  if (!all_finite(a.background) || a.background.r < 0 || a.background.g < 0 || a.background.b < 0)
    return "the background must be finite and >= 0";
  return "";
}

void require_valid_assets(const SceneAssets& assets, const AssetRules& rules,
                          const std::string& who) {
  if (const std::string defect = assets_defect(assets, rules); !defect.empty())
    throw InternalError(who + ": " + defect);
}

}  // namespace cutaway
