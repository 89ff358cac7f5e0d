// Grains (paper §4 step 2, doc/algorithms.md §5): small closed ellipsoid DSs scattered over a
// surface region by dart throwing with a Poisson-disc radius (kiwi and tomato seeds).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "base/random.h"
#include "model/crossing_test.h"
#include "model/ds_model.h"
#include "model/inside_test.h"
#include "model/template.h"

namespace cutaway {

/// Where one grain sits, metres, object frame.
struct GrainPlacement {
  glm::dvec3 surface_point{0.0};  ///< the dart's point on the `on` surface
  glm::dvec3 centre{0.0};         ///< surface_point + depth along the normal towards the side
  glm::dvec3 axis_profile{0.0};   ///< unit axes of the ellipsoid: along the profile tangent
  glm::dvec3 axis_section{0.0};   ///<   along the section tangent (turned by the jitter)
  glm::dvec3 axis_normal{0.0};    ///<   along the surface normal (front side)
  glm::dvec3 semi_axes{0.0};      ///< semi-axes along those axes, jittered
};

/// Options of the dart throwing.
struct GrainOptions {
  /// Stop after this many consecutive rejected darts (the region is then nearly saturated).
  int max_consecutive_failures = 2000;
  size_t max_grains = 100000;    ///< hard cap per grain set
  int rings = 6, segments = 10;  ///< ellipsoid mesh resolution (UV sphere)
  /// Grains through a region: the most darts thrown into the region's bounding box in all
  /// (those outside the region count here, not as failures).
  size_t max_region_darts = 1000000;
};

/// Dart throwing (Cook 1986; the paper's "dart throwing while respecting a Poisson disc
/// radius") on the triangles of `on` whose three vertices' params (t_profile, t_section) lie
/// in spec.region_*: a dart is a point uniform by area (triangle by cumulative area, then
/// barycentric coordinates); its grain centre lies spec.depth along the interpolated vertex
/// normal towards spec.on_front's side; it is accepted when every accepted centre is at least
/// spec.spacing away (3D, metres; a uniform hash grid). Frame: profile axis = gradient of
/// t_profile over the triangle, projected off the normal (any perpendicular where it
/// vanishes), then turned about the normal by jitter * 90 degrees * U(-1, 1); semi-axes scaled
/// by 1 + jitter * U(-1, 1). Deterministic for a given rng state.
/// A dart whose grain `obstacles` says it touches or crosses is rejected like one too close to
/// another (it counts as a failure); `crossings[k]`, when given, counts the darts rejected for
/// obstacle k (resized to fit).
/// Note: darts instead of Bridson's (2007) active list: the region is a set of triangles, on
/// several components (one per fold), where a parameter-domain grid is not one-to-one.
std::vector<GrainPlacement> place_grains(const GrainSpec& spec, const DsSurface& on, Rng& rng,
                                         const GrainOptions& options = {},
                                         const CrossingTest* obstacles = nullptr,
                                         std::vector<size_t>* crossings = nullptr);

/// The cells of a grid over a closed surface's bounding box that may hold points inside it:
/// those its triangles' bounding boxes reach and those whose centre lies inside. Equal cubes,
/// so a point uniform in a cell drawn uniformly is uniform over their union, which holds the
/// whole inside.
struct RegionCells {
  std::vector<glm::dvec3> corners;  ///< each cell's lowest corner, metres
  /// Per cell, 1 when no triangle's bounding box reaches it and its centre lies inside: the
  /// whole cell is inside, so a dart there needs no inside test.
  std::vector<uint8_t> interior;
  double size = 0;  ///< the cells' edge, metres
};

/// The RegionCells of `mesh` (closed; `inside` its test), cells `spacing` across or, for a
/// large box, 1/128 of its longest side.
RegionCells region_cells(const DsMesh& mesh, const InsideTest& inside, double spacing);

/// Dart throwing through a region (grains `inside` a closed surface, doc/template-format.md,
/// Grains): a dart is a point uniform in a cell of `cells` drawn uniformly (RegionCells of the
/// `inside` surface: so uniform over a set that holds the region, far tighter than its bounding
/// box for a ring of thin locules); one outside
/// `inside` or inside `outside` (when given) is thrown away without counting as a failure; one
/// within spec.spacing of an accepted centre, or whose ellipsoid `obstacles` says touches or
/// crosses a surface, is a failure. Frame: the normal axis points away from the object's axis
/// (y) horizontally, the profile axis up, turned about the normal by jitter * 90 degrees *
/// U(-1, 1); semi-axes scaled by 1 + jitter * U(-1, 1). Stops after
/// options.max_consecutive_failures failures in a row, options.max_grains grains or
/// options.max_region_darts darts. surface_point = centre. Deterministic for a given rng state.
/// @param inside, outside point-in-surface tests of closed surfaces
std::vector<GrainPlacement> place_grains_inside(const GrainSpec& spec, const InsideTest& inside,
                                                const InsideTest* outside, const RegionCells& cells,
                                                Rng& rng, const GrainOptions& options = {},
                                                const CrossingTest* obstacles = nullptr,
                                                std::vector<size_t>* crossings = nullptr);

/// Appends one closed ellipsoid (UV sphere of options.rings x options.segments, poles on the
/// normal axis, outward normals) per placement to `mesh`, with DS attributes front, back (linear
/// RGB) and blur (metres).
void add_ellipsoids(const std::vector<GrainPlacement>& grains, const glm::dvec3& front,
                    const glm::dvec3& back, double blur, const GrainOptions& options, DsMesh& mesh);

/// The most grains a template's grain sets may ask for together, each set counted as its
/// region's area over the area a grain's Poisson disc claims in the densest packing
/// (sqrt(3)/2 spacing^2). Each grain is a mesh of 50 vertices, so this bounds the grains of a
/// variant at 500,000 vertices.
inline constexpr double kMaxGrains = 10000;

/// Refuses grain sets of `tmpl` that would take unbounded work or make no sense on `model`
/// (built from tmpl), before any dart is thrown: more than kMaxGrains grains for the regions'
/// areas (volumes, for grains through a region: the volume inside `inside` over spacing^3 /
/// sqrt(2)) over all sets (a spacing far too small), an ellipsoid semi-axis or a depth larger than
/// the skin's bounding box, or a spacing below the largest semi-axis (grains so dense that one
/// can hold the centres of others: their loops on a cut face cross each other and the skin
/// nanometres apart, and pieces of wedges and dice were found open). A region with no area is
/// allowed (it gets no grains).
/// @throws InputError at the grain's `spacing`, `shape` or item, naming the rule
void check_grain_limits(const Template& tmpl, const DsModel& model);

/// The cores of grain set `spec` (GrainSpec::core, which it must have) placed as `grains`: one
/// closed ellipsoid inside each grain, same centre and frame, semi-axes times core.scale,
/// core colours and material channels, no blur; a Grain surface named grain_core_name(spec).
/// @throws InternalError when spec has no core
DsSurface grain_cores(const GrainSpec& spec, const std::vector<GrainPlacement>& grains,
                      const GrainOptions& options = {});

/// Scatters every grain set of `tmpl` over its `on` surface of `model` (or through its region:
/// place_grains_inside, crossing no surface at all) and appends one
/// DsSurface per set that got grains (role Grain, name of the set, many components; a set whose
/// region gets none adds no surface), followed by its cores' (grain_cores) when it has them;
/// bounds updated. Grain set i uses the stream
/// derive_seed(seed, {grains purpose, i}). A grain may cross the surface it sits on (a pip in
/// its carpel wall, an eye in the skin) but no other surface and no grain of an earlier set:
/// such darts are rejected (doc/template-format.md, Grains).
/// @pre model was built from tmpl (build_model); every grain's `on` names one of its surfaces
/// @throws InputError from check_grain_limits, at the grain set's item when its region has
///         room for grains but every dart crossed another surface (naming the one crossed
///         most), or at its `inside` or `outside` when that surface is not closed
void scatter_grains(const Template& tmpl, DsModel& model, uint64_t seed,
                    const GrainOptions& options = {});

}  // namespace cutaway
