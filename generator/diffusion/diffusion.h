// Colour diffusion with positive mean value coordinates (PMVC; paper §3.2, Lipman et al. 2007;
// doc/algorithms.md §2): the colour at a point inside the object is the average of the
// colours of the DS sheets it sees first in every direction, weighted by solid angle / distance.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/error.h"
#include "model/ds_model.h"

namespace cutaway {

/// The cube size every command and batch uses unless told otherwise (`--cube N`): texels per
/// cube-map face edge, 6 n^2 directions per point. 12 (doc/algorithms.md §2, Cube size 12):
/// with adaptive directions the cut faces' vertices differ from a cube-32 diffusion by
/// 0.188/255 on average against 0.174 at cube 16, with the same largest error, for about a
/// quarter less PMVC time; the default salad's first run is 1.17x rather than 1.37x that of the
/// version before the anatomy work.
inline constexpr int kDefaultCubeSize = 12;

/// Settings shared by every diffusion backend.
struct DiffusionOptions {
  /// Texels per cube-map face edge (6 n^2 directions per point).
  int cube_size = kDefaultCubeSize;
  int threads = 0;  ///< worker threads; 0 = all cores. Results do not depend on it.
  /// Each point's cube map turned by its own seeded rotation (cube_rotation): texel errors
  /// cancel instead of adding up where the cube's grid lines up with an object's symmetry.
  bool rotate_cubes = true;
  /// Silhouette-adaptive directions (adaptive_directions.h): each point's cube is cast at
  /// half the resolution first, and only the texels where the sheet seen changes between
  /// neighbours are cast again at full resolution. On the shipped templates' mid-height cuts
  /// about 650 rays a point instead of 1,536 at cube 16, with the same error against cube 32
  /// (doc/algorithms.md §2). Needs an even cube size up to 32 (the GPU keeps a work group's
  /// coarse texels in shared memory); other sizes cast every texel.
  bool adaptive_directions = true;
};

/// Whether a backend with these options casts adaptive directions: requested, and an even
/// cube size from 2 to 32.
inline bool uses_adaptive_directions(const DiffusionOptions& options) {
  return options.adaptive_directions && options.cube_size >= 2 && options.cube_size <= 32 &&
         options.cube_size % 2 == 0;
}

/// colour(x) = sum_w c(w) dOmega(w) / r(w)  /  sum_w dOmega(w) / r(w) over the cube-map texel
/// directions w that hit a sheet (with adaptive directions: the coarse texels where the sheet
/// seen does not change and the fine texels of the others); r(w) is the Euclidean distance to the
/// first hit and c(w) the colour the hit sheet shows there (make_diffusion_sheets). The material
/// channels (roughness, translucency) are diffused the same way, from the same rays (paper §6:
/// material information on DSs besides colours).
class DiffusionBackend {
 public:
  virtual ~DiffusionBackend() = default;
  /// Linear RGB colours (`colour`, #P) and, when `material` is not empty (#P), material
  /// channels (roughness, translucency; 0..1) at `points` (#P, metres, object frame), in one
  /// ray cast per direction. A point that sees no sheet in any direction (outside the object)
  /// gets zeros. Each point is summed in a fixed order: the result does not depend on the
  /// thread count.
  /// @throws InternalError when colour (or a non-empty material) is not #P long
  virtual void diffuse_channels(std::span<const glm::dvec3> points, std::span<glm::dvec3> colour,
                                std::span<glm::dvec2> material) const = 0;
  /// Colours only (#P).
  std::vector<glm::dvec3> diffuse(std::span<const glm::dvec3> points) const {
    std::vector<glm::dvec3> colour(points.size());
    diffuse_channels(points, colour, {});
    return colour;
  }
  /// Diffuses `where` (#K, as diffuse_channels) in one batch and writes point k's colour and
  /// material channels to entry which[k] (#K) of `colour` and `material`: for samplers that
  /// diffuse a subset of their points.
  void diffuse_into(std::span<const glm::dvec3> where, std::span<const size_t> which,
                    std::span<glm::dvec3> colour, std::span<glm::dvec2> material) const {
    std::vector<glm::dvec3> c(where.size());
    std::vector<glm::dvec2> m(where.size());
    diffuse_channels(where, c, m);
    for (size_t k = 0; k < which.size(); ++k) {
      colour[which[k]] = c[k];
      material[which[k]] = m[k];
    }
  }
  /// "cpu" or "gl".
  virtual std::string name() const = 0;
  /// Rays cast so far by this backend, over all calls (0 for a backend that casts none).
  virtual size_t rays_cast() const { return 0; }
  /// The worker threads it was made with (DiffusionOptions::threads; 0: all cores). Work
  /// around it honours the same budget: cut_pieces makes that many caps at once (one at a
  /// time when it is 1).
  virtual int threads() const { return 0; }
};

/// The sizes diffuse_channels needs: throws InternalError unless colour has one entry
/// per point and material none or one per point.
inline void check_channel_sizes(size_t points, size_t colour, size_t material) {
  if (colour != points || (material != 0 && material != points))
    throw InternalError("diffusion: " + std::to_string(points) + " points but " +
                        std::to_string(colour) + " colours and " + std::to_string(material) +
                        " material channels");
}

/// The CPU backend: Embree 3 ray casting, packets of 16 directions of one point, TBB over
/// points. Builds the BVH of all sheets once.
/// @throws EnvironmentError when Embree cannot be initialised
std::unique_ptr<DiffusionBackend> make_cpu_diffusion(const DsModel& model,
                                                     const DiffusionOptions& options);

}  // namespace cutaway
