// The CPU PMVC backend (doc/algorithms.md §2, Backends: cpu).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "diffusion/adaptive_directions.h"
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
        directions_(uses_adaptive_directions(options) ? CubeDirections{}
                                                      : make_cube_directions(options.cube_size)),
        sheets_(make_diffusion_sheets(model)) {
    const std::string config = "threads=" + std::to_string(std::max(options.threads, 0));
    device_ = rtcNewDevice(config.c_str());
    if (!device_) throw std::runtime_error("cannot initialise Embree (rtcNewDevice failed)");
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    commit_sheet_scene(device_, scene_, sheets_);
    if (uses_adaptive_directions(options)) adaptive_ = make_adaptive_directions(options.cube_size);
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
      size_t rays = 0;
      for (size_t i = range.begin(); i != range.end(); ++i)
        rays += diffuse_point(points[i], colour[i], with_material ? &material[i] : nullptr);
      rays_ += rays;
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

  size_t rays_cast() const override { return rays_; }
  int threads() const override { return options_.threads; }

 private:
  /// A ray's nearest hit, as the sums need it.
  struct Hit {
    int seen = -1;  ///< 2 sheet + (1 on the back side), -1: no hit
    double distance = 0;
    glm::vec3 colour{0.0f};
    glm::vec2 material{0.0f};
  };

  /// Casts rays from x along `rays` (#R unit directions) in packets of 16 and writes their
  /// hits (#R).
  void cast(const glm::dvec3& x, std::span<const glm::vec3> rays, std::span<Hit> hits) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    alignas(64) RTCRayHit16 rh;
    alignas(64) int valid[16];
    for (size_t base = 0; base < rays.size(); base += 16) {
      const int lanes = fill_ray_packet(rays, base, x, rh, valid);
      rtcIntersect16(valid, scene_, &context, &rh);
      for (int l = 0; l < lanes; ++l) {
        Hit& hit = hits[base + static_cast<size_t>(l)];
        hit = Hit{};
        if (rh.hit.geomID[l] == RTC_INVALID_GEOMETRY_ID) continue;
        const DiffusionSheet& s = sheets_[rh.hit.geomID[l]];
        const unsigned prim = rh.hit.primID[l];
        const glm::uvec3 t = s.triangle[prim];
        const float u = rh.hit.u[l], v = rh.hit.v[l], w0 = 1.0f - u - v;
        const bool front =
            !s.two_faced || glm::dot(rays[base + static_cast<size_t>(l)], s.face_normal[prim]) < 0;
        const auto& c = front ? s.colour_front : s.colour_back;
        const auto& m = front ? s.material_front : s.material_back;
        hit.seen = 2 * static_cast<int>(rh.hit.geomID[l]) + (front ? 0 : 1);
        hit.distance = std::max(static_cast<double>(rh.ray.tfar[l]), 1e-9);
        hit.colour = w0 * c[t[0]] + u * c[t[1]] + v * c[t[2]];
        hit.material = w0 * m[t[0]] + u * m[t[1]] + v * m[t[2]];
      }
    }
  }

  /// Sums of one point: colour, material channels and weight, each hit weighted by
  /// solid angle / distance.
  struct Sums {
    glm::dvec3 colour{0.0};
    glm::dvec2 material{0.0};
    double weight = 0;
    void add(const Hit& hit, double solid_angle) {
      if (hit.seen < 0) return;
      const double w = solid_angle / hit.distance;
      colour += glm::dvec3(hit.colour) * w;
      material += glm::dvec2(hit.material) * w;
      weight += w;
    }
  };

  /// One point, summed in a fixed order (texel order; a refined texel's four fine texels in
  /// their order): every texel of the cube, or, with adaptive directions, the coarse texels
  /// and the fine ones of the refined texels. @returns the rays cast
  size_t diffuse_point(const glm::dvec3& x, glm::dvec3& colour_out, glm::dvec2* material) const {
    // The cube turned by the point's rotation (or not).
    const glm::mat3 turn = options_.rotate_cubes ? glm::mat3(cube_rotation(x)) : glm::mat3(1.0f);
    thread_local std::vector<glm::vec3> rays, fine_rays;
    thread_local std::vector<Hit> hits, fine_hits;
    thread_local std::vector<int> seen;
    thread_local std::vector<unsigned char> refine;
    const CubeDirections& first = adaptive_ ? adaptive_->coarse : directions_;
    const size_t count = first.direction.size();
    rays.resize(count);
    hits.resize(count);
    for (size_t k = 0; k < count; ++k) rays[k] = turn * first.direction[k];
    cast(x, rays, hits);
    Sums sums;
    size_t cast_rays = count;
    if (!adaptive_) {
      for (size_t k = 0; k < count; ++k) sums.add(hits[k], first.solid_angle[k]);
    } else {
      seen.resize(count);
      refine.resize(count);
      for (size_t k = 0; k < count; ++k) seen[k] = hits[k].seen;
      mark_refined_texels(*adaptive_, seen, refine);
      fine_rays.clear();
      for (size_t k = 0; k < count; ++k)
        if (refine[k])
          for (unsigned f : adaptive_->children(static_cast<unsigned>(k)))
            fine_rays.push_back(turn * adaptive_->fine.direction[f]);
      fine_hits.resize(fine_rays.size());
      cast(x, fine_rays, fine_hits);
      cast_rays += fine_rays.size();
      size_t next = 0;
      for (size_t k = 0; k < count; ++k) {
        if (!refine[k]) {
          sums.add(hits[k], first.solid_angle[k]);
          continue;
        }
        for (unsigned f : adaptive_->children(static_cast<unsigned>(k)))
          sums.add(fine_hits[next++], adaptive_->fine.solid_angle[f]);
      }
    }
    colour_out = sums.weight > 0 ? sums.colour / sums.weight : glm::dvec3(0.0);
    if (material) *material = sums.weight > 0 ? sums.material / sums.weight : glm::dvec2(0.0);
    return cast_rays;
  }

  DiffusionOptions options_;
  CubeDirections directions_;  ///< every texel of the cube; empty with adaptive directions
  /// With adaptive directions (an even cube size): the coarse and fine levels.
  std::optional<AdaptiveDirections> adaptive_;
  mutable std::atomic<size_t> rays_{0};
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
