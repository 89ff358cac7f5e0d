// Random variants of a template (paper §4.2, doc/algorithms.md §5): only the horizontal
// curves change; profiles, colours, blur and grains are kept, so attributes carry over.
// Cylindrical templates: De Bonet synthesis of the section loops (debonet.h); N-fold templates:
// PCA fold blending (fold_pca.h); symmetry none: unchanged.
#pragma once

#include <cstdint>
#include <vector>

#include "model/ds_model.h"
#include "model/template.h"
#include "variation/debonet.h"
#include "variation/fold_pca.h"

namespace cutaway {

/// Options of vary / make_variant.
struct VariationOptions {
  int loop_samples = 128;  ///< De Bonet: samples per section loop (a multiple of 8 x 2^k)
  int attempts = 6;        ///< draws per amount before the amount is halved
  int halvings = 3;        ///< amount halvings before giving up (the template unchanged)
  DeBonetOptions debonet;  ///< its `amount` is replaced by the template's
  FoldPcaOptions folds;
};

/// The centres (radians) of `folds` folds of drawn widths: fold k is 1 + spread U(-1, 1) times
/// as wide as the others' mean, the widths scaled to fill the turn, fold 0 centred on
/// `first_rad`, each next one half its width and half the next's further on (a fold spans half
/// way to each neighbour: fold_pca.h). Real citrus segments and locules differ this way
/// (`variation.fold_widths`, times the amount). Deterministic in `seed`.
/// @pre folds >= 1, 0 <= spread < 1
std::vector<double> draw_fold_angles(double first_rad, int folds, double spread, uint64_t seed);

/// A variant and its DS model (grains scattered).
struct Variant {
  Template tmpl;
  DsModel model;
  int draws = 0;        ///< draws made (1 when the first one passed)
  double amount = 0.0;  ///< the variation amount that passed (template's, or halved; 0: none)
};

/// One variant of `tmpl`, unchecked: cylindrical -> the drawn section loops (`around`, not
/// `circle`) synthesised jointly by De Bonet with amount tmpl.variation_amount * amount_scale;
/// N-fold -> N' folds (uniform in [variation_folds_min, max]) drawn by PCA fold blending with
/// coefficients ~ N(0, amount^2), at centres of drawn widths where the template has
/// variation_fold_widths (draw_fold_angles, spread amount x fold_widths up to 0.9, a stream of
/// its own); none or amount 0 -> tmpl. Deterministic in (seed, draw).
/// Circle sections stay circles (nothing to vary; their radius channel would be constant).
/// Besides, each surface with a `wander` (SurfaceSpec::wander_m) gets a seeded offset uniform
/// in the ball of radius amount * wander_m, from a stream of its own per surface and draw
/// (part_placement.h moves it; a draw that makes it cross another surface is drawn again).
Template draw_variant(const Template& tmpl, uint64_t seed, uint64_t draw, double amount_scale,
                      const VariationOptions& options = {});

/// The ripeness of the variant of `seed` (doc/template-format.md, `variation.ripeness`):
/// uniform about the middle of tmpl.ripeness_range, over the whole range at variation amount
/// 1 or more and over amount times it below (amount 0: the middle). From a pcg32 stream of
/// its own, so the shapes a seed draws do not depend on it.
double draw_ripeness(const Template& tmpl, uint64_t seed);

/// A variant that passes check_template_curves and build_model (closed skin, nothing crosses
/// the skin, `within` loops inside their folds): draws with the template's amount until one
/// passes (options.attempts draws), then with the amount halved (options.halvings times); if
/// none passes, the template itself (amount 0). Its colours are taken at draw_ripeness(tmpl,
/// seed) in every case. The model then gets its grains (scatter_grains with the same seed), and
/// then the whole model its organic deformation (draw_organic with the same seed and the
/// template's full amount; none where the template asks for none), and last the knife's wobble
/// for a halves cut (draw_knife_wobble with the same seed, whatever the amount: it is the cut's,
/// not the fruit's).
/// Same seed -> identical result.
/// @pre tmpl was returned by parse_template / load_template
/// @throws InputError only when tmpl itself does not build
Variant make_variant(const Template& tmpl, uint64_t seed, const VariationOptions& options = {});

/// make_variant(tmpl, seed).tmpl: the varied template (builds the model once to check it).
Template vary(const Template& tmpl, uint64_t seed);

}  // namespace cutaway
