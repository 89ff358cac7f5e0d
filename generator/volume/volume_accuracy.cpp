#include "volume/volume_accuracy.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>

#include "base/colour.h"
#include "base/random.h"
#include "volume/volume_lookup.h"

namespace cutaway {

namespace {

/// The most lattice points one plane contributes: the spacing grows beyond voxel_m / 2 when
/// a cap would have more.
constexpr double kPointsPerPlane = 3000;

/// Mean and 99th percentile of `errors` (sorted in place); zeros when empty.
std::pair<double, double> mean_and_p99(std::vector<double>& errors) {
  if (errors.empty()) return {0, 0};
  std::sort(errors.begin(), errors.end());
  double sum = 0;
  for (double e : errors) sum += e;
  return {sum / static_cast<double>(errors.size()),
          errors[static_cast<size_t>(0.99 * static_cast<double>(errors.size() - 1))]};
}

}  // namespace

std::vector<Plane> random_cap_planes(const DsModel& model, int count, uint64_t seed) {
  const auto [lo, hi] = skin_bounds(model);
  Rng rng(derive_seed(seed, {0x766f6c756d65ull}));  // "volume"
  std::vector<Plane> planes;
  for (int i = 0; i < count; ++i) {
    Plane plane;
    for (int a = 0; a < 3; ++a)
      plane.point[a] = rng.uniform(0.75 * lo[a] + 0.25 * hi[a], 0.25 * lo[a] + 0.75 * hi[a]);
    plane.normal = random_direction(rng);
    planes.push_back(plane);
  }
  return planes;
}

VolumeErrors volume_errors(const DsModel& model, const DiffusionBackend& diffusion,
                           const InteriorVolume& volume, const std::vector<Plane>& planes,
                           int threads) {
  const glm::dvec3 lo = volume.origin;
  const glm::dvec3 hi = volume.origin + volume.voxel_m * glm::dvec3(volume.size - 1);
  std::vector<glm::dvec3> points;
  for (const Plane& plane : planes) {
    const glm::dvec3 n = glm::normalize(plane.normal);
    const glm::dvec3 helper = std::abs(n.x) < 0.6 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 u = glm::normalize(glm::cross(n, helper)), v = glm::cross(n, u);
    // The plane's reach within the grid's box, along u and v.
    double u0 = 1e300, u1 = -1e300, v0 = 1e300, v1 = -1e300;
    for (int c = 0; c < 8; ++c) {
      const glm::dvec3 corner(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
      u0 = std::min(u0, glm::dot(corner - plane.point, u));
      u1 = std::max(u1, glm::dot(corner - plane.point, u));
      v0 = std::min(v0, glm::dot(corner - plane.point, v));
      v1 = std::max(v1, glm::dot(corner - plane.point, v));
    }
    const double h =
        std::max(0.5 * volume.voxel_m, std::sqrt((u1 - u0) * (v1 - v0) / kPointsPerPlane));
    const double shift = 0.6180339887498949 * h;  // the golden ratio's fraction
    for (double a = u0 + shift; a <= u1; a += h) {
      for (double b = v0 + 0.5 * shift; b <= v1; b += h) {
        const glm::dvec3 p = plane.point + a * u + b * v;
        if (glm::all(glm::greaterThanEqual(p, lo)) && glm::all(glm::lessThanEqual(p, hi)))
          points.push_back(p);
      }
    }
  }
  const std::vector<PointClass> classes = classify_points(model, points, volume.voxel_m, threads);
  std::vector<glm::dvec3> solid;
  std::vector<bool> near;
  std::vector<VolumeSample> samples;
  size_t either = 0, wrong = 0;
  for (size_t p = 0; p < points.size(); ++p) {
    const VolumeSample sample = sample_volume(volume, points[p]);
    const bool volume_solid = sample.region != kEmptyRegion;
    if (classes[p].solid || volume_solid) ++either;
    if (classes[p].solid != volume_solid) ++wrong;
    if (!classes[p].solid || !volume_solid) continue;
    solid.push_back(points[p]);
    near.push_back(classes[p].near_sheet);
    samples.push_back(sample);
  }
  const std::vector<glm::dvec3> reference = diffusion.diffuse(solid);
  std::vector<double> far_errors, near_errors;
  for (size_t p = 0; p < solid.size(); ++p) {
    const double e = colour_difference(glm::dvec3(samples[p].colour), reference[p]);
    (near[p] ? near_errors : far_errors).push_back(e);
  }
  VolumeErrors errors;
  errors.points = solid.size();
  errors.near_points = near_errors.size();
  std::tie(errors.mean_far, errors.p99_far) = mean_and_p99(far_errors);
  std::tie(errors.mean_near, errors.p99_near) = mean_and_p99(near_errors);
  errors.wrong_side = either > 0 ? static_cast<double>(wrong) / static_cast<double>(either) : 0;
  return errors;
}

}  // namespace cutaway
