#include "assets/asset_camera.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "base/constants.h"

namespace cutaway {

AssetCamera frame_box(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& to_camera,
                      double fov_deg, double aspect) {
  AssetCamera cam;
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const glm::dvec3 back = glm::normalize(to_camera);
  glm::dvec3 right = glm::cross(-back, cam.up);
  right = glm::length(right) > 1e-9 ? glm::normalize(right) : glm::dvec3(1, 0, 0);
  const glm::dvec3 up = glm::cross(right, -back);
  const double tan_v = std::tan(0.5 * glm::radians(fov_deg)), tan_h = aspect * tan_v;
  // The distance from the centre at which every corner of the box is in view, with 4 % margin.
  double distance = 1e-3;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c((k & 1 ? hi.x : lo.x) - centre.x, (k & 2 ? hi.y : lo.y) - centre.y,
                       (k & 4 ? hi.z : lo.z) - centre.z);
    const double towards = glm::dot(c, back);
    distance = std::max({distance, towards + std::fabs(glm::dot(c, right)) / tan_h,
                         towards + std::fabs(glm::dot(c, up)) / tan_v});
  }
  distance *= 1.04;
  const double radius = std::max(1e-3, 0.5 * glm::distance(lo, hi));
  cam.target = centre;
  cam.eye = centre + back * distance;
  cam.fov_y_deg = fov_deg;
  cam.aspect = aspect;
  cam.znear = std::max(1e-3, 0.25 * (distance - radius));
  cam.zfar = distance + 4 * radius;
  return cam;
}

void light_like_studio(SceneAssets& assets) {
  const AssetCamera& camera = assets.camera;
  const glm::dvec3 f = glm::normalize(camera.target - camera.eye);
  glm::dvec3 r = glm::cross(f, camera.up);
  r = glm::length(r) > 1e-9 ? glm::normalize(r) : glm::dvec3(1, 0, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(r, f));
  // Directions towards each light; the light travels the other way.
  // Strengths in W/m^2 as Blender shows them, times lumens per watt: lux.
  // Angles: the sources' apparent sizes, a softbox's for the key (soft-edged shadows) and a
  // broad bounce for the fill.
  auto light = [&](const char* name, glm::dvec3 towards, double watts, glm::dvec3 colour,
                   double angle_deg) {
    AssetLight l;
    l.name = name;
    l.type = LightType::Directional;
    l.direction = -glm::normalize(towards);
    l.intensity = watts * kLumensPerWatt;
    l.colour = colour;
    l.angle_deg = angle_deg;
    return l;
  };
  assets.lights = {light("key", -0.5 * r + 1.0 * u - 0.6 * f, 2.4, {1.0, 0.97, 0.92}, 24),
                   light("fill", 0.8 * r + 0.3 * u - 0.5 * f, 0.96, {0.92, 0.95, 1.0}, 30),
                   light("rim", 0.2 * r + 0.8 * u + 0.9 * f, 0.8, {1.0, 1.0, 1.0}, 12)};
  // A sky of radiance 0.12 W/m^2/sr: pi * 0.12 W/m^2 on an open face.
  assets.ambient_lux = 0.12 * kPi * kLumensPerWatt;
}

}  // namespace cutaway
