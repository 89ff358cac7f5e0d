#include "assets/scene_assets.h"

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/trigonometric.hpp>

#include "base/error.h"
#include "base/finite.h"

namespace cutaway {

Check check_camera(const AssetCamera& c, bool needs_up) {
  if (!all_finite(c.eye) || !all_finite(c.target) || !all_finite(c.up))
    return Check::none("eye, target and up must be finite");
  const glm::dvec3 forward = c.target - c.eye;
  if (!(glm::length(forward) > 0)) return Check::none("eye and target coincide");
  if (needs_up &&
      (!(glm::length(c.up) > 0) ||
       !(glm::length(glm::cross(glm::normalize(forward), c.up)) > 1e-9 * glm::length(c.up))))
    return Check::none("up is zero or parallel to the view direction");
  if (!(c.fov_y_deg > 0 && c.fov_y_deg < 180))
    return Check::none("fov_y_deg must be in (0, 180), not " + std::to_string(c.fov_y_deg));
  if (!(c.aspect > 0 && std::isfinite(c.aspect)))
    return Check::none("aspect must be positive and finite");
  if (!(c.znear > 0 && c.znear < c.zfar && std::isfinite(c.zfar)))
    return Check::none("need 0 < znear < zfar (finite), not " + std::to_string(c.znear) + ", " +
                       std::to_string(c.zfar));
  return {};
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

glm::dvec3 volume_centroid(const ColouredMesh& mesh) {
  double volume6 = 0;  // six times the volume
  glm::dvec3 moment(0.0);
  for (const glm::uvec3& t : mesh.triangle) {
    const glm::dvec3 &a = mesh.position[t.x], &b = mesh.position[t.y], &c = mesh.position[t.z];
    const double v6 = glm::dot(a, glm::cross(b, c));
    volume6 += v6;
    moment += v6 * (a + b + c);  // the tetrahedron's centroid is (a + b + c) / 4
  }
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const glm::dvec3& p : mesh.position) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  if (mesh.position.empty()) return glm::dvec3(0.0);
  // Enclosing no volume against its extent (cubed): the box centre.
  const double extent = glm::length(hi - lo);
  if (!(std::fabs(volume6) > 1e-9 * extent * extent * extent)) return 0.5 * (lo + hi);
  return moment / (4 * volume6);
}

size_t drawn_triangles(const SceneAssets& assets) {
  size_t count = 0;
  for (const AssetInstance& inst : assets.instances) {
    const AssetMesh& mesh = assets.meshes[static_cast<size_t>(inst.mesh)];
    if (mesh.primitives.empty()) {
      count += mesh.triangle.size();
      continue;
    }
    for (const AssetPrimitive& p : mesh.primitives) {
      const bool textured =
          !mesh.uv.empty() &&
          assets.materials[static_cast<size_t>(p.material)].base_colour_texture >= 0;
      count += primitive_triangles(mesh, p, textured).size();
    }
  }
  return count;
}

Check check_primitives(const AssetMesh& mesh, size_t materials) {
  if (mesh.primitives.empty() && materials == 0) return Check::none("material index out of range");
  size_t next = 0;
  for (const AssetPrimitive& p : mesh.primitives) {
    if (p.first != next || p.count == 0)
      return Check::none("primitives must cover the triangles in order");
    if (p.material < 0 || static_cast<size_t>(p.material) >= materials)
      return Check::none("material index out of range");
    next += p.count;
  }
  if (!mesh.primitives.empty() && next != mesh.triangle.size())
    return Check::none("primitives must cover the triangles in order");
  return {};
}

namespace {

Check check_texture(const AssetTexture& t) {
  if (t.width < 1 || t.height < 1)
    return Check::none("is " + std::to_string(t.width) + "x" + std::to_string(t.height) +
                       " (must be at least 1x1)");
  if (t.channels != 1 && t.channels != 3 && t.channels != 4)
    return Check::none("has " + std::to_string(t.channels) + " channels (must be 1, 3 or 4)");
  const size_t bytes = static_cast<size_t>(t.width) * static_cast<size_t>(t.height) *
                       static_cast<size_t>(t.channels);
  if (t.pixels.size() != bytes)
    return Check::none(
        "has " + std::to_string(t.pixels.size()) +
        " bytes of pixels, not width * height * channels = " + std::to_string(bytes));
  return {};
}

Check check_material(const AssetMaterial& m, const std::vector<AssetTexture>& textures) {
  if (const std::string_view field = out_of_range_field(m.pbr); !field.empty())
    return Check::none("has " + std::string(field) + " outside its range");
  for (const auto& [field, texture] : {std::pair{"base_colour_texture", m.base_colour_texture},
                                       std::pair{"material_texture", m.material_texture},
                                       std::pair{"normal_texture", m.normal_texture},
                                       std::pair{"height_texture", m.height_texture}})
    if (texture < -1 || texture >= static_cast<int>(textures.size()))
      return Check::none("has " + std::string(field) + " " + std::to_string(texture) +
                         ", neither -1 nor in 0.." +
                         std::to_string(static_cast<long>(textures.size()) - 1));
  if (m.base_colour_texture >= 0 &&
      textures[static_cast<size_t>(m.base_colour_texture)].channels != 3)
    return Check::none("has a base colour texture that is not RGB (3 channels)");
  if (m.normal_texture >= 0 && textures[static_cast<size_t>(m.normal_texture)].channels != 3)
    return Check::none("has a normal texture that is not RGB (3 channels)");
  if (m.height_texture >= 0 && textures[static_cast<size_t>(m.height_texture)].channels != 1)
    return Check::none("has a height texture that is not grey (1 channel)");
  if (m.height_texture >= 0 && !(m.height_bump >= 0 && std::isfinite(m.height_bump)))
    return Check::none("has a height_bump that is not finite and at least 0");
  return {};
}

Check check_mesh(const AssetMesh& m, const std::vector<AssetMaterial>& materials,
                 const AssetRules& rules) {
  const size_t n = m.position.size();
  if (rules.meshes_need_triangles && (n == 0 || m.triangle.empty()))
    return Check::none("has no triangles");
  if (m.normal.size() != n || m.colour.size() != n)
    return Check::none("has " + std::to_string(n) + " positions, " +
                       std::to_string(m.normal.size()) + " normals and " +
                       std::to_string(m.colour.size()) + " colours (must be equal)");
  for (size_t v = 0; v < n; ++v)
    if (!all_finite(m.position[v]) || !all_finite(m.colour[v]) ||
        (!rules.normals_repaired && !all_finite(m.normal[v])))
      return Check::none("vertex " + std::to_string(v) +
                         " has a non-finite position, normal or colour");
  if (!m.uv.empty() && m.uv.size() != n)
    return Check::none("has " + std::to_string(m.uv.size()) + " texture coordinates for " +
                       std::to_string(n) + " positions (must be equal, or none)");
  for (size_t v = 0; v < m.uv.size(); ++v)
    if (!all_finite(m.uv[v]))
      return Check::none("vertex " + std::to_string(v) + " has non-finite texture coordinates");
  const auto out_of_range = [n](const std::vector<glm::uvec3>& triangles) {
    for (size_t t = 0; t < triangles.size(); ++t)
      for (int i = 0; i < 3; ++i)
        if (triangles[t][i] >= n) return true;
    return false;
  };
  if (out_of_range(m.triangle))
    return Check::none("has a triangle vertex index not below " + std::to_string(n));
  if (Check primitives = check_primitives(m, materials.size()); !primitives) return primitives;
  for (const AssetPrimitive& p : m.primitives) {
    if (out_of_range(p.coarse))
      return Check::none("has a coarse triangle vertex index not below " + std::to_string(n));
    if (rules.textures_need_uv && m.uv.empty() &&
        materials[static_cast<size_t>(p.material)].base_colour_texture >= 0)
      return Check::none("has no uv for its textured material " + std::to_string(p.material));
  }
  return {};
}

Check check_light(const AssetLight& l) {
  if (!all_finite(l.position) || !all_finite(l.direction) || !all_finite(l.colour) ||
      !std::isfinite(l.intensity))
    return Check::none("has a non-finite field");
  if (l.intensity < 0 || l.colour.r < 0 || l.colour.g < 0 || l.colour.b < 0)
    return Check::none("has a negative intensity or colour");
  if (l.type == LightType::Directional && !(glm::length(l.direction) > 0))
    return Check::none("is directional with a zero direction");
  if (!(l.angle_deg >= 0 && l.angle_deg <= 180))
    return Check::none("has an angle outside 0..180 degrees");
  return {};
}

/// `check`, failing as "KIND INDEX 'NAME' REASON".
Check named(const char* kind, size_t index, const std::string& name, const Check& check) {
  if (check) return check;
  return Check::none(std::string(kind) + " " + std::to_string(index) + " '" + name + "' " +
                     check.reason());
}

}  // namespace

BoundingSphere shadow_casters_bounds(const SceneAssets& a) {
  glm::dvec3 lo(HUGE_VAL), hi(-HUGE_VAL);
  std::vector<glm::dvec3> placed;
  for (const AssetInstance& inst : a.instances) {
    if (inst.backdrop) continue;
    const glm::dmat3 r = glm::mat3_cast(glm::normalize(inst.rotation));
    for (const glm::dvec3& p : a.meshes[static_cast<size_t>(inst.mesh)].position) {
      placed.push_back(inst.translation + r * p);
      lo = glm::min(lo, placed.back());
      hi = glm::max(hi, placed.back());
    }
  }
  BoundingSphere b;
  if (placed.empty()) return b;
  b.centre = 0.5 * (lo + hi);
  for (const glm::dvec3& p : placed) b.radius = std::max(b.radius, glm::length(p - b.centre));
  return b;
}

int shadow_casting_light(const SceneAssets& a) {
  int caster = a.lights.empty() ? -1 : 0;
  for (size_t i = 1; i < a.lights.size(); ++i)
    if (a.lights[i].intensity > a.lights[static_cast<size_t>(caster)].intensity)
      caster = static_cast<int>(i);
  return caster;
}

Check check_assets(const SceneAssets& a, const AssetRules& rules) {
  if (a.materials.empty()) return Check::none("no materials (material 0 is the plain one)");
  for (size_t i = 0; i < a.textures.size(); ++i)
    if (Check c = named("texture", i, a.textures[i].name, check_texture(a.textures[i])); !c)
      return c;
  for (size_t i = 0; i < a.materials.size(); ++i)
    if (Check c =
            named("material", i, a.materials[i].name, check_material(a.materials[i], a.textures));
        !c)
      return c;
  for (size_t i = 0; i < a.meshes.size(); ++i)
    if (Check c = named("mesh", i, a.meshes[i].name, check_mesh(a.meshes[i], a.materials, rules));
        !c)
      return c;
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
    if (!defect.empty()) return named("instance", i, inst.name, Check::none(defect));
  }
  if (const Check camera = check_camera(a.camera, rules.camera_needs_up); !camera)
    return Check::none("camera: " + camera.reason());
  for (size_t i = 0; i < a.lights.size(); ++i)
    if (Check c = named("light", i, a.lights[i].name, check_light(a.lights[i])); !c) return c;
  if (!all_finite(a.background) || a.background.r < 0 || a.background.g < 0 || a.background.b < 0)
    return Check::none("the background must be finite and >= 0");
  return {};
}

void require_valid_assets(const SceneAssets& assets, const AssetRules& rules,
                          const std::string& who) {
  if (const Check check = check_assets(assets, rules); !check)
    throw InternalError(who + ": " + check.reason());
}

}  // namespace cutaway
