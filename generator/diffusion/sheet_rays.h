// First hits of rays on the diffusion sheets, the same bits on every CPU (doc/algorithms.md
// §2, Hits that do not depend on the CPU).
//
// Embree picks SSE, AVX, AVX2 or AVX-512 kernels at run time, and their floating-point
// rounding differs: a ray that grazes a sheet's edge hits it with one kernel and misses it with
// another, and two sheets a hair apart swap places. Here Embree only proposes: it traces a copy
// of the sheets whose triangles are grown by a margin well above its rounding error, from an
// origin moved back along the ray by another margin, and hands every triangle it meets to a
// filter; so are the triangles next to the ray's origin, where a grazing ray's t may come out
// with the wrong sign. The filter decides in double precision, by one fixed formula
// (cross_triangle), on the original triangle: whether the ray crosses it, where, and whether that
// is nearer than the best crossing so far (ties go to the lower sheet, then triangle, index). Every
// triangle the exact test would accept is among the proposals whatever the kernel, so the answer is
// the exact test's alone.
#pragma once

#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "diffusion/diffusion_sheets.h"

namespace cutaway {

/// Where a ray crosses a triangle: o + t d = (1 - u - v) a + u b + v c.
struct TriangleCrossing {
  double t = 0;  ///< along the ray, in units of |d|
  double u = 0;  ///< weight of the second corner
  double v = 0;  ///< weight of the third corner
};

/// The crossing of the ray o + t d (t > 0) with triangle (a, b, c), edges and corners
/// included, or none (also for a degenerate triangle or a ray in its plane). Möller and
/// Trumbore's test (1997) in double precision; the same inputs give the same bits on every
/// CPU (no FMA: the build sets -ffp-contract=off).
std::optional<TriangleCrossing> cross_triangle(const glm::dvec3& o, const glm::dvec3& d,
                                               const glm::dvec3& a, const glm::dvec3& b,
                                               const glm::dvec3& c);

/// A ray's first hit on the sheets.
struct SheetHit {
  int sheet = -1;         ///< index into the sheets; -1: the ray hits nothing
  unsigned triangle = 0;  ///< index into that sheet's triangles
  TriangleCrossing at;    ///< where (t in metres for a unit direction)
};

/// How a SheetRayCaster finds hits.
enum class SheetHits {
  /// Decided in double precision on every triangle Embree proposes (the same bits on every
  /// CPU): what cutaway uses.
  Decided,
  /// Embree's own single-precision hits on the sheets as they are (cutaway 0.1's way): about
  /// a third cheaper, but which triangle a grazing ray hits, and the last bits of t, u and v,
  /// depend on the kernel Embree picked for the CPU. Kept to measure what Decided costs.
  EmbreeFloat,
};

/// The hits the environment asks for: SheetHits::EmbreeFloat when CUTAWAY_PMVC_HITS is
/// "embree", else Decided. Meant for benchmarks (tests/bench/bench_portability.cpp).
SheetHits sheet_hits_from_environment();

/// Casts rays against a fixed set of sheets (positions in metres). Thread-safe: cast may run
/// on many threads at once.
class SheetRayCaster {
 public:
  /// Builds Embree's BVH over `sheets` (the grown copy for SheetHits::Decided), which must
  /// outlive the caster. `threads`: Embree's build threads (0: all cores). The environment
  /// variable CUTAWAY_EMBREE_ISA (sse2, sse4.2, avx, avx2, avx512), meant for tests, makes
  /// Embree use that instruction set's kernels instead of the best the CPU has; decided hits
  /// do not change.
  /// @throws EnvironmentError when Embree cannot be initialised
  SheetRayCaster(const std::vector<DiffusionSheet>& sheets, int threads,
                 SheetHits hits = SheetHits::Decided);
  ~SheetRayCaster();
  SheetRayCaster(const SheetRayCaster&) = delete;
  SheetRayCaster& operator=(const SheetRayCaster&) = delete;

  /// The first hit (t > 0) of the ray from `origin` along each of `directions` (#R, unit
  /// vectors) into `hits` (#R): the nearest crossing of cross_triangle over every triangle of
  /// every sheet, ties to the lower (sheet, triangle) (with SheetHits::EmbreeFloat: Embree's
  /// nearest hit). Rays go in packets of 16.
  void cast(const glm::dvec3& origin, std::span<const glm::vec3> directions,
            std::span<SheetHit> hits) const;

  const std::vector<DiffusionSheet>& sheets() const { return sheets_; }

  /// How far each triangle's edges are moved out in the copy Embree traces (metres): 1e-6
  /// of the sheets' bounding-box diagonal, at least 1e-9 m, over ten times the float rounding
  /// of the positions. Embree's ray starts 100 margins behind the origin, and the triangles
  /// within 10,000 margins (1 % of the diagonal) of the origin whose plane passes within 1 %
  /// of that of it (where a grazing ray may cross them, and every triangle within rounding
  /// distance of the origin) are tested for every ray (doc/algorithms.md §2).
  double margin() const { return margin_; }

  /// One cast's data, for Embree's filter and point query (sheet_rays.cpp).
  struct Query;

 private:
  struct Embree;
  const std::vector<DiffusionSheet>& sheets_;
  /// SheetHits::Decided: per sheet, Embree's vertex buffer, kVertexFloats floats per corner
  /// of each triangle (3 t + k): the grown corner Embree traces, then the sheet's own.
  std::vector<const float*> corners_;
  SheetHits mode_;
  double margin_ = 0;
  double back_ = 0;  ///< metres Embree's ray origin lies behind the true one
  /// Triangles this near the origin whose plane passes within kGrazingSine of this of it are
  /// tested for every ray.
  double grazing_radius_ = 0;
  Embree* embree_ = nullptr;
};

}  // namespace cutaway
