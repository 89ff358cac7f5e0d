// Multiresolution texture synthesis (De Bonet 1997) on cyclic 1D multi-channel signals, and its
// use for the horizontal curves of cylindrical templates (paper §4.2, doc/algorithms.md §5):
// a star-shaped section loop becomes a cyclic array of (radius, angle to the next point), a 1D
// texture sample; a synthesised array becomes a new loop.
#pragma once

#include <vector>

#include "base/random.h"
#include "model/curves.h"

namespace cutaway {

/// A cyclic signal: `length` samples of `channels` values each, sample-major
/// (v[i * channels + c]); sample length - 1 is followed by sample 0.
struct CyclicSignal {
  int length = 0;
  int channels = 0;
  std::vector<double> v;

  CyclicSignal() = default;
  CyclicSignal(int n, int c) : length(n), channels(c), v(static_cast<size_t>(n) * c, 0.0) {}
  double& at(int i, int c) { return v[static_cast<size_t>(i) * channels + c]; }
  double at(int i, int c) const { return v[static_cast<size_t>(i) * channels + c]; }
};

/// Options of debonet_synthesize.
struct DeBonetOptions {
  /// Scales every level's threshold; 0 reproduces the input exactly (paper: variation.amount).
  double amount = 1.0;
  /// Threshold at amount 1, as a fraction of each parent component's range over the input
  /// (max-norm over the parent feature vector).
  double threshold = 0.15;
  /// Coarsest pyramid level length: levels are halved while the result keeps >= min_length
  /// samples and the length is even.
  int min_length = 8;
  /// Also compare the parents' forward differences (De Bonet's derivative features).
  bool derivatives = true;
};

/// Laplacian pyramid with wrap-around filtering: 5-tap binomial [1 4 6 4 1]/16, decimation by
/// 2. Element 0 is the finest band (input length), the last element the coarsest Gaussian
/// level itself. collapse_pyramid inverts it (to rounding, |error| < 1e-12 relative).
/// @pre signal.length >= 1
std::vector<CyclicSignal> laplacian_pyramid(const CyclicSignal& signal, int min_length = 8);

/// Sum of the bands, coarse to fine (upsampling with the same cyclic filter).
CyclicSignal collapse_pyramid(const std::vector<CyclicSignal>& bands);

/// De Bonet 1997 synthesis of new bands from the input's bands, coarse to fine. The coarsest
/// level is kept. At each finer level and output position i, the candidates are the input
/// positions j whose parent feature vector (band values, and their forward differences when
/// options.derivatives, of all coarser levels at the ancestors j >> d, every channel, each
/// component divided by its range over the input) lies within amount * threshold of the
/// output's in the max norm; one candidate is picked uniformly with `rng` (the nearest when
/// none; with a zero threshold the nearest, preferring j = i) and its band value (all
/// channels) copied. Every output band value is therefore one of the input's.
/// @return bands of the same shapes as `bands`
std::vector<CyclicSignal> synthesize_bands(const std::vector<CyclicSignal>& bands,
                                           const DeBonetOptions& options, Rng& rng);

/// laplacian_pyramid, synthesize_bands, collapse_pyramid. amount 0 returns the input (to
/// rounding, < 1e-12 relative).
CyclicSignal debonet_synthesize(const CyclicSignal& signal, const DeBonetOptions& options,
                                Rng& rng);

/// A star-shaped section loop in polar form: `count` points spaced uniformly by arc length,
/// from the loop's crossing of angle 0, counter-clockwise seen from +Y (doc/template-format.md,
/// Frame and units). rho: distance from the axis (metres); dphi: angle to the next point
/// (radians, > 0, summing to 2 pi).
struct PolarLoop {
  std::vector<double> rho, dphi;
};

/// Fits (spline when `smooth`, else polyline) and resamples a closed [x, z] loop (metres) into
/// polar form.
/// @pre the loop surrounds the axis and is star-shaped about it (check_template_curves)
PolarLoop polar_resample(const Polyline2& loop_xz, bool smooth, int count);

/// The [x, z] loop of a polar form: the first point at angle 0, angles accumulated from dphi
/// after clamping it to >= 1e-3 of its mean and normalising its sum to 2 pi; rho clamped to
/// >= 1e-3 of its mean.
Polyline2 loop_from_polar(const PolarLoop& polar);

/// Joint De Bonet synthesis of nested section loops (paper §4.2): every loop is resampled to
/// `count` points (polar_resample), the loops become one signal with channels (rho_0, dphi_0,
/// rho_1, dphi_1, ...), so one choice of source position moves every loop alike and inner
/// loops tend to stay inside outer ones (not guaranteed: callers check). Rebuilt with
/// loop_from_polar.
/// @param loops_xz  closed [x, z] loops (metres); smooth[i] as in the template
/// @pre count is a multiple of options.min_length times a power of two for a deep pyramid
std::vector<Polyline2> synthesize_loops(const std::vector<Polyline2>& loops_xz,
                                        const std::vector<bool>& smooth, int count,
                                        const DeBonetOptions& options, Rng& rng);

}  // namespace cutaway
