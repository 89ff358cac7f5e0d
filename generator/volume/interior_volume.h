// A variant's interior as a volume: the PMVC colour and material channels sampled on a regular
// grid, with what keeps sheets crisp between the samples (doc/algorithms.md §8): each voxel's
// region (the solid cell between sheets it lies in, or empty) and its distances to the nearest
// sheet and to the outline, so a sampler (volume_lookup.h, the cutting page's shader) can colour a
// cut anywhere without running PMVC again.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/outcome.h"
#include "diffusion/diffusion.h"
#include "material/colour_modulation.h"
#include "model/ds_model.h"

namespace cutaway {

/// Region id of empty voxels: outside the skin, or on a hollow side (a cavity).
inline constexpr uint32_t kEmptyRegion = 0;

/// The most voxels one volume may have (about 1.5 GB of samples and two minutes of PMVC per
/// million solid voxels on two cores): a finer grid is refused before any work.
inline constexpr size_t kMaxVolumeVoxels = 16'000'000;

/// A rigid surface (a stone, doc/template-format.md) as a triangle mesh beside the voxels, so
/// that a cut of the volume can keep it whole in one half and its imprint in the other, as
/// `cutaway piece` does (the cutting page; doc/interior-volume.md, Stones).
struct VolumeStone {
  std::string surface;                ///< the rigid surface's name
  std::vector<glm::dvec3> points;     ///< #V points, metres, object frame
  std::vector<glm::uvec3> triangles;  ///< #F by 3 indices into points, wound outwards
  /// #V linear RGB colours: the stone's own (its inside side) and the flesh's against it (its
  /// outside side).
  std::vector<glm::dvec3> stone, flesh;
};

/// A regular grid of samples over an object's skin, object frame, metres. Voxel (i, j, k) is
/// the cube of edge `voxel_m` centred on origin + voxel_m (i, j, k); arrays are indexed
/// i + size.x (j + size.y k) (x fastest, then y, then z). The grid reaches one voxel beyond the
/// skin's bounding box on every side, so every border voxel is empty.
struct InteriorVolume {
  glm::ivec3 size{0};      ///< voxels along x, y, z
  glm::dvec3 origin{0.0};  ///< centre of voxel (0, 0, 0), metres
  double voxel_m = 0;      ///< edge length, metres
  /// Linear RGB per voxel: PMVC at the voxel's centre where it is solid (at a point inside a
  /// grain where a grain passes through it but misses its centre: thin_grains.h; in the middle
  /// of a layer its grid line misses: thin_layers.h); where it is empty, the mean of its solid face
  /// neighbours (0 with none), so that plain trilinear filtering by a tool that ignores `region`
  /// does not darken the skin's outline.
  std::vector<glm::vec3> colour;
  std::vector<glm::vec2> material;  ///< roughness, translucency (0..1), as `colour`
  /// Per voxel: kEmptyRegion, or 1 + the index of the solid region its centre lies in. Two
  /// face neighbours share a region when the segment between their centres crosses no sharp
  /// surface (one blurred by less than half a voxel there); regions are numbered in voxel
  /// order of their first voxel.
  std::vector<uint32_t> region;
  /// Per voxel, metres: the distance from its centre to the plane of the nearest crossing on
  /// its six face-neighbour segments of a sharp surface, or of any surface between solid and
  /// empty, at most voxel_m (voxel_m: none within one voxel). A sampler reads it as an
  /// unsigned distance to its region's border.
  std::vector<float> sheet_distance;
  /// Per voxel, metres: the distance from its centre to the plane of the nearest crossing of a
  /// wall (the skin, or a surface with a hollow side) on its face-neighbour segments that run
  /// between solid and empty, at most voxel_m. A sampler reads it as an unsigned distance to
  /// the outline, solid against empty, whatever surfaces lie between.
  std::vector<float> outline_distance;
  std::vector<VolumeStone> stones;  ///< the model's rigid surfaces; none without
  uint32_t regions = 0;             ///< solid regions (the largest region id)
  size_t solid = 0;                 ///< voxels whose region is not empty (the PMVC points)
  size_t grain_samples = 0;     ///< of them, those sampled inside a grain that misses their centre
  size_t layer_samples = 0;     ///< and those sampled inside a layer their grid line misses
  double seconds_classify = 0;  ///< ray casts for the regions and the distances
  double seconds_diffuse = 0;   ///< PMVC at the solid voxels

  size_t voxels() const { return static_cast<size_t>(size.x) * size.y * size.z; }
  size_t index(int i, int j, int k) const {
    return static_cast<size_t>(i) +
           static_cast<size_t>(size.x) * (j + static_cast<size_t>(size.y) * k);
  }
  /// The voxel (i, j, k) of array index `v` (the inverse of index()).
  glm::ivec3 voxel(size_t v) const {
    return {static_cast<int>(v % size.x), static_cast<int>(v / size.x % size.y),
            static_cast<int>(v / (static_cast<size_t>(size.x) * size.y))};
  }
  /// The centre of voxel (i, j, k), metres.
  glm::dvec3 centre(int i, int j, int k) const { return origin + voxel_m * glm::dvec3(i, j, k); }
  glm::dvec3 centre(const glm::ivec3& ijk) const { return centre(ijk.x, ijk.y, ijk.z); }
};

/// How many voxels the longest edge of the skin's bounding box gets when no voxel length is
/// given (doc/algorithms.md §8, Voxel size: chosen from the accuracy table).
inline constexpr int kDefaultVoxelsAcross = 96;

/// The voxel edge that puts `across` voxels along the longest edge of `model`'s skin's
/// bounding box, metres. @pre the skin has vertices, across > 0
double voxel_length_across(const DsModel& model, int across);

/// The default voxel edge for `model`: voxel_length_across(model, kDefaultVoxelsAcross).
inline double default_voxel_length(const DsModel& model) {
  return voxel_length_across(model, kDefaultVoxelsAcross);
}

/// The grid over `model`'s skin with voxel edge `voxel_m` (metres): size and origin set, no
/// samples; or none, with the reason, when voxel_m is not positive and finite, is longer than
/// half the skin's longest bounding-box edge, or makes more than kMaxVolumeVoxels voxels.
Outcome<InteriorVolume> volume_grid(const DsModel& model, double voxel_m);

/// Samples `model`'s interior on `grid` (volume_grid's, for this model): each voxel
/// classified solid or empty by the side votes (classify_points), regions joined along
/// face-neighbour segments that cross no sharp surface (one ray each), sheet distances from
/// those crossings, outline distances from a second cast against the walls alone (the skin
/// and the surfaces with a hollow side), and `diffusion` (PMVC over the model's diffusion sheets,
/// the same backend and settings as cut faces) at every solid voxel's centre (or inside a grain
/// that passes through it but misses its centre, thin_grain_samples, or in a layer its grid
/// line misses, thin_layer_samples), then, with `modulation`, the
/// object's Perlin colour modulation of that strength at the same points (as cut faces get it:
/// material/colour_modulation.h). The model's rigid surfaces go beside the voxels
/// as VolumeStones. Ray casts run on `threads` threads (0: all cores); the result does not
/// depend on it.
InteriorVolume sample_interior_volume(const DsModel& model, const DiffusionBackend& diffusion,
                                      InteriorVolume grid, int threads = 0,
                                      const ColourModulation* modulation = nullptr,
                                      double strength = 1.0);

/// The number of directions whose first hits vote on whether a point is solid (odd: no ties).
inline constexpr int kSideVotes = 9;

/// What classify_points says of one point.
struct PointClass {
  bool solid = false;       ///< inside the object and not in a cavity
  bool near_sheet = false;  ///< a surface lies within the given reach along some axis
};

/// Per point (#P, metres, object frame): whether it is solid, and whether a surface crosses
/// one of the six axis-parallel segments of length `reach_m` from it. A point is solid when
/// the surface side a ray from it meets first is solid in most of kSideVotes fixed directions;
/// a side is empty when it is the skin's front (outside) or a hollow side
/// (DsSurface::visible_front/back false), and a ray that meets nothing counts as empty. The
/// same test as sample_interior_volume's, for checking a volume at points of one's choosing.
std::vector<PointClass> classify_points(const DsModel& model, const std::vector<glm::dvec3>& points,
                                        double reach_m, int threads = 0);

}  // namespace cutaway
