// Blur-band sampling (adaptive cap sampling, cross_section.h): the points that mesh a blurred
// cut segment's band (paper §3.1, Fig. 2) lie on three lines along the cut, the traces of its
// two sheets and the cut itself. Across the band the PMVC colour changes fast, along it slowly,
// so each line is diffused sparsely by arc length and interpolated linearly along its length,
// and refined where a point halfway between two samples disagrees with their interpolation.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "base/colour.h"
#include "diffusion/diffusion.h"

namespace cutaway {

/// Where each segment lies on its chain: a polyline of segments of one group joined end to end.
struct SegmentChains {
  std::vector<int> chain;      ///< per segment: chain index, or -1 for a segment not chained
  std::vector<double> offset;  ///< per segment: arc length of its start on the chain (metres)
  std::vector<bool> forward;   ///< per segment: whether the chain runs from its a to its b
  std::vector<double> length;  ///< per chain: arc length (metres)
  std::vector<bool> closed;    ///< per chain: whether it is a closed loop
  int chains = 0;

  /// Arc length on its chain of the point at parameter t (0 at a, 1 at b) of segment i.
  double arc_length(size_t i, double t, double length) const {
    return offset[i] + (forward[i] ? t : 1 - t) * length;
  }
};

/// Joins `segments` (#S, end points in plane coordinates, metres) of equal `group` (#S; -1:
/// left out) into chains: two segments of a group are joined where they share an end point
/// exactly and no other segment of the group ends there. A closed loop is cut open at the end
/// of its first segment (in segment order). Deterministic (segment order).
SegmentChains chain_segments(std::span<const std::array<glm::dvec2, 2>> segments,
                             std::span<const int> group);

/// The lines of chain `chain`'s band: its front sheet's trace (side +1), the cut (0), its back
/// sheet's trace (-1).
inline int band_line(int chain, int side) { return 3 * chain + 1 - side; }

/// A point to colour on one line of a band.
struct BandPoint {
  int line = 0;              ///< which line (band_line): points of one line are interpolated
                             ///< together
  double arc_length = 0;     ///< along the line (its chain's arc length), metres
  glm::dvec3 position{0.0};  ///< object frame, metres
  double width = 0;          ///< the band's half width there (the blur), metres
  bool exact = false;        ///< always diffused, and a sample (mark_irregular_band_points)
};

/// Sets `exact` on the band points (#P) where the band is not a strip along one line, so that
/// interpolation along a line cannot be trusted: within two widths (arc length) of an open end
/// of its chain (the band turns round the end), and where a point of another line, or of the
/// same line further than 1.5 times their distance plus a width away along it, lies within 0.9
/// of the point's width (a narrow loop's inner trace meets its cut or crosses itself, or another
/// band runs into this one). A line of another chain that runs alongside (within 25 degrees,
/// at least half the point's width away, and not near its own chain's open end) does not count:
/// two strips side by side, such as a sheet just under the skin, interpolate along their lines.
void mark_irregular_band_points(std::span<BandPoint> points, const SegmentChains& chains);

/// How sparsely the lines are sampled.
struct BandSamplingOptions {
  double spacing_m = 0;        ///< largest arc length between the first samples of a line (its
                               ///< two ends are always samples)
  VisibleTolerance tolerance;  ///< largest accepted differences (colour.h) between a test
                               ///< point's diffused and interpolated values
};

/// Counts of one band sampling.
struct BandSamplingCounts {
  size_t points = 0;    ///< band points coloured
  size_t diffused = 0;  ///< of which diffused (first samples and test points)
  size_t failed = 0;    ///< test points whose interpolation was off (their gaps were split)
};

/// Colours every band point (`colour`, `material`: #P, linear RGB and material channels) with
/// few PMVC evaluations: per line, points sorted by arc length; the two ends and points at most
/// `spacing_m` apart are diffused; then, round by round, for every gap between consecutive
/// samples with points in it, the point nearest its middle is diffused and becomes a sample,
/// and where it differs from the linear interpolation (by arc length) of the gap's ends by
/// more than `tolerance` both halves are tested again. All other points get the linear
/// interpolation of the samples around them. Deterministic; each round is one diffusion batch.
/// @throws InternalError when colour or material is not #P long, or spacing_m <= 0
BandSamplingCounts sample_bands(std::span<const BandPoint> points,
                                const DiffusionBackend& diffusion,
                                const BandSamplingOptions& options, std::span<glm::dvec3> colour,
                                std::span<glm::dvec2> material);

}  // namespace cutaway
