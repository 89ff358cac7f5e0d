// The CPU PMVC backend (doc/algorithms.md §2, Backends: cpu).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>

#include "base/parallel_chunks.h"
#include "diffusion/adaptive_directions.h"
#include "diffusion/cube_directions.h"
#include "diffusion/diffusion.h"
#include "diffusion/diffusion_sheets.h"
#include "diffusion/sheet_rays.h"

namespace cutaway {

namespace {

class CpuDiffusion final : public DiffusionBackend {
 public:
  CpuDiffusion(const DsModel& model, const DiffusionOptions& options)
      : options_(options),
        directions_(uses_adaptive_directions(options) ? CubeDirections{}
                                                      : make_cube_directions(options.cube_size)),
        sheets_(make_diffusion_sheets(model)),
        caster_(sheets_, options.threads, sheet_hits_from_environment()) {
    if (uses_adaptive_directions(options)) adaptive_ = make_adaptive_directions(options.cube_size);
  }

  std::string name() const override { return "cpu"; }

  void diffuse_channels(std::span<const glm::dvec3> points, std::span<glm::dvec3> colour,
                        std::span<glm::dvec2> material) const override {
    check_channel_sizes(points.size(), colour.size(), material.size());
    const bool with_material = !material.empty();
    parallel_chunks(points.size(), 4, options_.threads, [&](size_t begin, size_t end) {
      size_t rays = 0;
      for (size_t i = begin; i != end; ++i)
        rays += diffuse_point(points[i], colour[i], with_material ? &material[i] : nullptr);
      rays_ += rays;
    });
  }

  size_t rays_cast() const override { return rays_; }
  int threads() const override { return options_.threads; }

 private:
  /// A ray's nearest hit, as the sums need it.
  struct Hit {
    int seen = -1;  ///< 2 sheet + (1 on the back side), -1: no hit
    double distance = 0;
    glm::dvec3 colour{0.0};
    glm::dvec2 material{0.0};
  };

  /// Casts rays from x along `rays` (#R unit directions) and writes their hits (#R), colours
  /// interpolated in double precision from the crossing's barycentric weights.
  void cast(const glm::dvec3& x, std::span<const glm::vec3> rays, std::span<Hit> hits) const {
    thread_local std::vector<SheetHit> first;
    first.resize(rays.size());
    caster_.cast(x, rays, first);
    for (size_t r = 0; r < rays.size(); ++r) {
      Hit& hit = hits[r];
      hit = Hit{};
      const SheetHit& h = first[r];
      if (h.sheet < 0) continue;
      const DiffusionSheet& s = sheets_[static_cast<size_t>(h.sheet)];
      const glm::uvec3 t = s.triangle[h.triangle];
      const double u = h.at.u, v = h.at.v, w0 = 1.0 - u - v;
      const bool front =
          !s.two_faced || glm::dot(glm::dvec3(rays[r]), glm::dvec3(s.face_normal[h.triangle])) < 0;
      const auto& c = front ? s.colour_front : s.colour_back;
      const auto& m = front ? s.material_front : s.material_back;
      hit.seen = 2 * h.sheet + (front ? 0 : 1);
      hit.distance = std::max(h.at.t, 1e-9);
      hit.colour = w0 * glm::dvec3(c[t[0]]) + u * glm::dvec3(c[t[1]]) + v * glm::dvec3(c[t[2]]);
      hit.material = w0 * glm::dvec2(m[t[0]]) + u * glm::dvec2(m[t[1]]) + v * glm::dvec2(m[t[2]]);
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
      colour += hit.colour * w;
      material += hit.material * w;
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
  SheetRayCaster caster_;  ///< over sheets_
};

}  // namespace

std::unique_ptr<DiffusionBackend> make_cpu_diffusion(const DsModel& model,
                                                     const DiffusionOptions& options) {
  return std::make_unique<CpuDiffusion>(model, options);
}

}  // namespace cutaway
