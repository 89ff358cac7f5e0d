// The CPU PMVC backend (doc/algorithms.md §2, Backends: cpu).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "diffusion/cube_directions.h"
#include "diffusion/diffusion.h"
#include "diffusion/diffusion_sheets.h"
#include "diffusion/embree_sheets.h"

namespace cutaway {

namespace {

class CpuDiffusion final : public DiffusionBackend {
 public:
  CpuDiffusion(const DsModel& model, const DiffusionOptions& options)
      : options_(options),
        directions_(make_cube_directions(options.cube_size)),
        sheets_(make_diffusion_sheets(model)) {
    const std::string config = "threads=" + std::to_string(std::max(options.threads, 0));
    device_ = rtcNewDevice(config.c_str());
    if (!device_) throw std::runtime_error("cannot initialise Embree (rtcNewDevice failed)");
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    commit_sheet_scene(device_, scene_, sheets_);
  }

  ~CpuDiffusion() override {
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
  }

  std::string name() const override { return "cpu"; }

  void diffuse_channels(std::span<const glm::dvec3> points, std::span<glm::dvec3> colour,
                        std::span<glm::dvec2> material) const override {
    check_channel_sizes(points.size(), colour.size(), material.size());
    const bool with_material = !material.empty();
    auto body = [&](const oneapi::tbb::blocked_range<size_t>& range) {
      for (size_t i = range.begin(); i != range.end(); ++i)
        diffuse_point(points[i], colour[i], with_material ? &material[i] : nullptr);
    };
    if (options_.threads > 0) {
      oneapi::tbb::task_arena arena(options_.threads);
      arena.execute([&] {
        oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<size_t>(0, points.size(), 4), body);
      });
    } else {
      oneapi::tbb::parallel_for(oneapi::tbb::blocked_range<size_t>(0, points.size(), 4), body);
    }
  }

 private:
  /// One point: all cube-map directions in packets of 16, summed in direction order; the
  /// material channels from the same hits when `material` is not null.
  void diffuse_point(const glm::dvec3& x, glm::dvec3& colour_out, glm::dvec2* material) const {
    const size_t count = directions_.direction.size();
    // The cube turned by the point's rotation (or not): each packet's ray directions R d.
    const glm::mat3 turn = options_.rotate_cubes ? glm::mat3(cube_rotation(x)) : glm::mat3(1.0f);
    std::array<glm::vec3, 16> rays;
    glm::dvec3 sum_colour(0.0);
    glm::dvec2 sum_material(0.0);
    double sum_weight = 0;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    for (size_t base = 0; base < count; base += 16) {
      const size_t packet = std::min<size_t>(16, count - base);
      for (size_t l = 0; l < packet; ++l) rays[l] = turn * directions_.direction[base + l];
      const int lanes = fill_ray_packet(std::span<const glm::vec3>(rays.data(), packet), 0, x, rh,
                                        valid);
      rtcIntersect16(valid, scene_, &context, &rh);
      for (int l = 0; l < lanes; ++l) {
        if (rh.hit.geomID[l] == RTC_INVALID_GEOMETRY_ID) continue;
        const DiffusionSheet& s = sheets_[rh.hit.geomID[l]];
        const unsigned prim = rh.hit.primID[l];
        const glm::uvec3 t = s.triangle[prim];
        const float u = rh.hit.u[l], v = rh.hit.v[l], w0 = 1.0f - u - v;
        const glm::vec3 d = rays[static_cast<size_t>(l)];
        const bool front = !s.two_faced || glm::dot(d, s.face_normal[prim]) < 0;
        const auto& c = front ? s.colour_front : s.colour_back;
        const glm::vec3 colour = w0 * c[t[0]] + u * c[t[1]] + v * c[t[2]];
        const double r = std::max(static_cast<double>(rh.ray.tfar[l]), 1e-9);
        const double weight = directions_.solid_angle[base + l] / r;
        sum_colour += glm::dvec3(colour) * weight;
        sum_weight += weight;
        if (material) {
          const auto& m = front ? s.material_front : s.material_back;
          sum_material += glm::dvec2(w0 * m[t[0]] + u * m[t[1]] + v * m[t[2]]) * weight;
        }
      }
    }
    colour_out = sum_weight > 0 ? sum_colour / sum_weight : glm::dvec3(0.0);
    if (material) *material = sum_weight > 0 ? sum_material / sum_weight : glm::dvec2(0.0);
  }

  DiffusionOptions options_;
  CubeDirections directions_;
  std::vector<DiffusionSheet> sheets_;
  RTCDevice device_ = nullptr;
  RTCScene scene_ = nullptr;
};

}  // namespace

std::unique_ptr<DiffusionBackend> make_cpu_diffusion(const DsModel& model,
                                                     const DiffusionOptions& options) {
  return std::make_unique<CpuDiffusion>(model, options);
}

}  // namespace cutaway
