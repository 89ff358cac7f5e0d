// Cross-sections (paper §3.2, Fig. 3; doc/algorithms.md §3): the cut face of a DS model on a
// plane, triangulated by conforming constrained Delaunay refinement with the cut segments as
// constraints, split along them, and coloured by PMVC diffusion (colour and material channels).
#pragma once

#include <cstddef>
#include <functional>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/outcome.h"
#include "diffusion/diffusion.h"
#include "model/ds_model.h"
#include "section/cut_segments.h"

namespace cutaway {

/// Which points of a cap are diffused.
enum class CapSampling {
  /// Every vertex of a mesh refined to `interior_edge` everywhere (paper §3.2).
  Dense,
  /// The same mesh; its blur bands' lines sampled sparsely along their length
  /// (band_sampling.h) except where a band is not a strip along one line, its other interior
  /// vertices sparsely by Poisson-disc and harmonic interpolation (harmonic_sampling.h), both
  /// refined where a test point's diffused colour or material channels differ visibly from the
  /// interpolation (by more than `tolerance` or `material_tolerance`, colour.h); every point
  /// near a grain is diffused (grain_neighbourhood.h). The default: on the default salad it
  /// diffuses 1.6x fewer points, in 2.6x less PMVC time with adaptive directions, and its cap
  /// vertices differ from dense sampling's by 0.20/255 on average.
  Adaptive,
};

/// How a cross-section is meshed.
struct CrossSectionOptions {
  double edge_m = 0.002;       ///< the template's edge length, metres
  double interior_edge = 3.0;  ///< largest triangle edge, in edge_m: the cut segments are
                               ///< finer, and refinement grades from them into the interior
  CapSampling sampling = CapSampling::Adaptive;
  double tolerance = 2.0;           ///< adaptive: largest colour interpolation error left at a test
                                    ///< point, in steps of 1/255 (colour_difference: sRGB)
  double material_tolerance = 4.0;  ///< adaptive: the same for the material channels
                                    ///< (material_difference: 8-bit roughness, translucency)
  double harmonic_spacing = 6.0;    ///< adaptive: Poisson-disc radius of the first interior
                                    ///< samples, in edge_m (harmonic_sampling.h)
  double harmonic_min_spacing = 0.25;  ///< adaptive: the interior's test radius is halved down
                                       ///< to this, in edge_m (harmonic_sampling.h)
  double band_spacing = 16.0;          ///< adaptive: largest arc length between the first samples
                                       ///< along a blur band's lines, in edge_m (band_sampling.h)
  double merge_tolerance = 0.01;       ///< nearly collinear cut segments are merged up to edge_m
                                       ///< long where they deviate less than this, in edge_m
  /// Whether the skin's and the hollow walls' segments (the domain's boundary) are merged too.
  /// Pieces turn it off, so that the caps' boundaries run through exactly the crossings where
  /// the clipped skin ends.
  bool merge_boundary = true;
  double shape_bound = 0.125;  ///< Delaunay_mesh_size_criteria_2 shape bound B = 1/(4 sin^2 a):
                               ///< 0.125 is a minimum angle a of about 20.7 degrees
};

/// Restricts a cross-section to the faces of convex cells (doc/algorithms.md §4): the lines
/// where other cutting planes meet this one become extra constraints of the triangulation, so
/// that every triangle lies on one side of each, and only the triangles whose centroid `keep`
/// accepts are coloured and returned.
struct CapRestriction {
  std::vector<Plane> split_planes;  ///< planes whose lines on this plane are constraints;
                                    ///< planes parallel to this one are ignored
  std::function<bool(const glm::dvec3&)> keep;  ///< centroid (metres) -> keep; empty: all
};

/// PMVC evaluations of cross-sections, added up over caps, pieces and objects with +=.
struct DiffusedPoints {
  size_t all = 0;          ///< interior vertices and the locations of blurred cut vertices
                           ///< (their duplicates share one); adaptive sampling: the samples and
                           ///< test points only
  size_t on_bands = 0;     ///< adaptive: of `all`, those on blur bands' lines (band_sampling.h;
                           ///< the rest are interior)
  size_t near_grains = 0;  ///< of `all`, those near a grain (within kNearGrainRadii of one,
                           ///< grain_neighbourhood.h), which adaptive sampling diffuses all

  DiffusedPoints& operator+=(const DiffusedPoints& other) {
    all += other.all;
    on_bands += other.on_bands;
    near_grains += other.near_grains;
    return *this;
  }
};

/// The triangulated, coloured cut face on one plane.
struct CrossSection {
  Plane plane;
  glm::dvec3 u_axis{1, 0, 0}, v_axis{0, 1, 0};  ///< in-plane frame: cross(u, v) = normal
  std::vector<glm::dvec3> position;             ///< #V, metres, object frame
  std::vector<glm::uvec3> triangle;  ///< #F, counter-clockwise seen from the normal's side
  std::vector<glm::dvec3> colour;    ///< #V, linear RGB
  std::vector<glm::dvec2> material;  ///< #V, material channels (roughness, translucency)
  /// #V: the surface a vertex lies on (a cut vertex, one duplicate per side), or -1 for an
  /// interior vertex.
  std::vector<int> cut_surface;
  size_t interior_vertices = 0;    ///< vertices off the cut segments
  DiffusedPoints diffused;         ///< PMVC evaluations
  size_t cut_segments = 0;         ///< input cut segments
  bool refinement_capped = false;  ///< Delaunay refinement ran out of its step budget or
                                   ///< failed CGAL's checks (rounding near a degenerate input),
                                   ///< so the cap is the unrefined constrained Delaunay
                                   ///< triangulation
  double seconds_triangulate = 0;  ///< wall time: cut segments, triangulation, splitting
  double seconds_diffuse = 0;      ///< wall time: PMVC colours
};

/// Why make_cross_section gives no cross-section (Outcome::reason).
inline constexpr const char* kPlaneMisses = "the plane misses the object";
inline constexpr const char* kPlaneOnlyTouches = "the plane only touches the object";

/// The in-plane frame of a plane: u along the world axis least aligned with the normal,
/// projected; v = cross(normal, u).
void plane_frame(const Plane& plane, glm::dvec3& u, glm::dvec3& v);

/// Cuts `model` with `plane` (cut_segments), triangulates the domain inside the skin's cut
/// loops minus hollow sides (CGAL Constrained_Delaunay_triangulation_2 refined by
/// Delaunay_mesher_2, conforming), splits every vertex on a cut segment into one duplicate per
/// side (Fig. 3c) coloured with that side's DS colour where the blur is 0, and colours every
/// other vertex with `diffusion` (PMVC).
/// A region of the plane is in the domain when it is bounded (not connected to infinity), is
/// not on the skin's front (outer) side, and is not on a hollow side (visible_front/back false)
/// of any surface bounding it. Only the skin and the walls of hollows bound regions: the loops
/// of grains and other surfaces seen on both sides lie in the region around them (a grain in
/// a hollow or outside the skin is no part of the cut face).
/// With a `restriction`, its split planes' lines are constraints that do not bound the domain
/// (vertices on them are split like cut vertices and diffused), and triangles whose centroid it
/// does not keep are left out before diffusion.
/// @returns the cross-section, or none, an expected outcome the caller reports as bad input or
///          skips (no cap), with the reason kPlaneMisses when no cut segment lies on the skin,
///          kPlaneOnlyTouches when the cut face has no area or the restriction keeps nothing
Outcome<CrossSection> make_cross_section(const DsModel& model, const Plane& plane,
                                         const DiffusionBackend& diffusion,
                                         const CrossSectionOptions& options,
                                         const CapRestriction& restriction = {});

/// A cross-section triangulated and refined but not yet split or coloured: make_cross_section
/// stopped before its first PMVC evaluation, so that a caller can see where its triangles lie
/// and leave out those it does not need (the caps of pieces a scene does not keep) before
/// paying for their colours. Move-only; holds copies of what it was made from, except `model`,
/// which must outlive it.
class MeshedSection {
 public:
  struct Stages;  ///< the meshing state (cross_section.cpp)
  explicit MeshedSection(std::unique_ptr<Stages> stages);
  MeshedSection(MeshedSection&&) noexcept;
  MeshedSection& operator=(MeshedSection&&) noexcept;
  ~MeshedSection();

  /// The centroids (metres, object frame) of the triangles in the cut face, one per triangle,
  /// in the triangulation's order: the points a CapRestriction's `keep` is asked about.
  std::vector<glm::dvec3> triangle_centroids() const;
  /// Leaves out the triangles whose centroid `keep` rejects, as a restriction's `keep` would
  /// have (refinement came before either, so the triangles kept are the same).
  void restrict_to(const std::function<bool(const glm::dvec3&)>& keep);

 private:
  friend Outcome<CrossSection> colour_cross_section(MeshedSection section,
                                                    const DiffusionBackend& diffusion);
  std::unique_ptr<Stages> stages_;
};

/// make_cross_section's meshing: its steps up to the refinement and the restriction's cells.
/// @returns the meshed section, or none for the reasons make_cross_section gives
Outcome<MeshedSection> mesh_cross_section(const DsModel& model, const Plane& plane,
                                          const CrossSectionOptions& options,
                                          const CapRestriction& restriction = {});

/// make_cross_section's colouring of a meshed section: the blur bands, the split of the cut
/// vertices and PMVC diffusion with `diffusion`. mesh_cross_section followed by this gives
/// what make_cross_section gives.
/// @returns the cross-section, or none (kPlaneOnlyTouches) when no triangle is left
Outcome<CrossSection> colour_cross_section(MeshedSection section,
                                           const DiffusionBackend& diffusion);

}  // namespace cutaway
