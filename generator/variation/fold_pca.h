// PCA fold blending for N-fold templates (paper §4.2, after the morphable model of Blanz and
// Vetter 1999; doc/algorithms.md §5): every fold's horizontal curves form one feature vector,
// PCA over the N folds, new folds drawn as the mean plus random multiples of the principal
// vectors, N' folds rebuilt (N' may differ from N).
#pragma once

#include <vector>

#include "base/random.h"
#include "model/curves.h"
#include "model/template.h"

namespace cutaway {

/// Options of fold feature extraction and rebuilding.
struct FoldPcaOptions {
  int arc_samples = 41;   ///< points per Type I open curve (both fold lines included), >= 4
  int loop_samples = 48;  ///< points per Type II loop, >= 8
  int blend_points = 6;   ///< points on each side of a fold line over which Type I curves
                          ///< are blended to meet (< arc_samples / 2)
};

/// The folds of an N-fold template as feature vectors. Canonical space: a fold's angular span
/// [lo_k, hi_k] (fold_span) is mapped linearly onto the pie of angle W = 2 pi / N centred on
/// +x; a point at distance rho becomes (rho cos theta, rho sin theta), theta in [-W/2, W/2],
/// metres. Every curve of a fold contributes its canonical points (x, y pairs) in order.
struct FoldFeatures {
  int folds = 0;  ///< N
  /// Curves in feature order: index of the template surface, which of its sections (-1: its
  /// one `section`; k: `sections[k]`), and whether it is a Type I open curve (`around`
  /// section, split at the fold lines) or a Type II loop (`within` section).
  std::vector<int> surface;
  std::vector<int> section;
  std::vector<bool> open;
  std::vector<int> points;  ///< points of each curve
  /// N feature vectors (one per fold), each sum(points) * 2 long.
  std::vector<std::vector<double>> samples;
};

/// Principal components of the fold samples.
struct FoldPca {
  std::vector<double> mean;               ///< the mean fold
  std::vector<std::vector<double>> axes;  ///< unit principal vectors (sign: largest-magnitude
                                          ///< component positive), decreasing sigma
  std::vector<double> sigma;              ///< standard deviation along each axis (metres),
                                          ///< singular value / sqrt(N - 1); only > 1e-12 kept
};

/// Feature vectors of every fold: `around` surfaces with a drawn section (circles have no
/// folds and are left out) split at the N fold lines into open curves resampled uniformly by
/// arc length (end points exactly on the fold lines); `within` loops resampled uniformly,
/// counter-clockwise in canonical space, aligned with fold 0's loop by the cyclic shift with
/// the least sum of distances. A `within` section of one loop gives N equal samples. A surface
/// with `sections` at several heights gives one curve per section, so that all of them are
/// blended with the same fold vectors.
/// @pre tmpl.symmetry == NFold and tmpl passed check_template_curves
FoldFeatures fold_features(const Template& tmpl, const FoldPcaOptions& options);

/// PCA over the N samples (Eigen SVD of the centred N x D matrix).
FoldPca fold_pca(const FoldFeatures& features);

/// One new fold: mean + sum_p c_p sigma_p axis_p with c_p ~ N(0, amount^2) drawn from `rng`
/// in axis order.
std::vector<double> draw_fold(const FoldPca& pca, double amount, Rng& rng);

/// The curves of N' = fold_vectors.size() folds in the horizontal plane ([x, z], metres):
/// result[curve][fold]. Fold k is mapped from canonical space onto the span of
/// fold_angles_out[k] (half way to each neighbour). Type I open curves are first blended
/// across every fold line (the last/first options.blend_points points of both neighbours move
/// linearly towards the mean radius of the two end points), so fold k's last point equals fold
/// k + 1's first point (to rounding) and the joined loop is continuous.
/// @pre fold_vectors[k].size() == features.samples[0].size(); angles increasing, radians
std::vector<std::vector<Polyline2>> fold_curves_xz(
    const FoldFeatures& features, const std::vector<std::vector<double>>& fold_vectors,
    const std::vector<double>& fold_angles_out, const FoldPcaOptions& options);

/// `tmpl` with N' = fold_vectors.size() folds at `fold_angles_out` (radians, increasing,
/// spanning less than 2 pi; empty: the template's angles when N' == N, else fold_angles[0] +
/// k 2 pi / N'); every Type I section becomes the joined loop of its N' open
/// curves, every Type II section a list of N' loops (loop k inside fold k); so does each of a
/// surface's `sections` (`section` stays the first of them). Profiles, colours, blur, grains
/// and circle sections are kept.
/// @pre fold_angles_out empty or of N' angles
Template rebuild_folds(const Template& tmpl, const FoldFeatures& features,
                       const std::vector<std::vector<double>>& fold_vectors,
                       const FoldPcaOptions& options,
                       const std::vector<double>& fold_angles_out = {});

}  // namespace cutaway
