// Embree pieces shared by the CPU backend (pmvc_cpu.cpp) and the benchmark of raw Embree
// throughput: the sheets as scene geometry, and packets of 16 rays from one point along a run of
// cube-map directions.
#pragma once

#include <algorithm>
#include <limits>
#include <span>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include "diffusion/cube_directions.h"
#include "diffusion/diffusion_sheets.h"

namespace cutaway {

/// Adds every sheet to `scene` as triangle geometry whose geometry ID is the sheet's index
/// (positions in metres), then commits the scene.
inline void commit_sheet_scene(RTCDevice device, RTCScene scene,
                               const std::vector<DiffusionSheet>& sheets) {
  for (size_t i = 0; i < sheets.size(); ++i) {
    const DiffusionSheet& s = sheets[i];
    RTCGeometry g = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), s.position.size()));
    for (size_t v = 0; v < s.position.size(); ++v)
      for (int k = 0; k < 3; ++k) vb[3 * v + k] = s.position[v][k];
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), s.triangle.size()));
    for (size_t t = 0; t < s.triangle.size(); ++t)
      for (int k = 0; k < 3; ++k) ib[3 * t + k] = s.triangle[t][k];
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(scene, g, static_cast<unsigned>(i));
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(scene);
}

/// Sets `rh` to the rays from `origin` (metres) along directions[base .. base + 16) (fewer at
/// the end: the unused lanes repeat the last direction and are invalid) and `valid` to the
/// Embree mask. Returns the number of valid lanes.
inline int fill_ray_packet(std::span<const glm::vec3> directions, size_t base,
                           const glm::dvec3& origin, RTCRayHit16& rh, int (&valid)[16]) {
  const int lanes = static_cast<int>(std::min<size_t>(16, directions.size() - base));
  for (int l = 0; l < 16; ++l) {
    valid[l] = l < lanes ? -1 : 0;
    const glm::vec3 d = directions[base + std::min(l, lanes - 1)];
    rh.ray.org_x[l] = static_cast<float>(origin.x);
    rh.ray.org_y[l] = static_cast<float>(origin.y);
    rh.ray.org_z[l] = static_cast<float>(origin.z);
    rh.ray.dir_x[l] = d.x;
    rh.ray.dir_y[l] = d.y;
    rh.ray.dir_z[l] = d.z;
    rh.ray.tnear[l] = 0.0f;
    rh.ray.tfar[l] = std::numeric_limits<float>::infinity();
    rh.ray.mask[l] = 0xFFFFFFFFu;
    rh.ray.time[l] = 0.0f;
    rh.ray.flags[l] = 0;
    rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
  }
  return lanes;
}

}  // namespace cutaway
