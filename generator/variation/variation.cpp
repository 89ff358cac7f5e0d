#include "variation/variation.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <glm/geometric.hpp>

#include "base/constants.h"
#include "model/model_builder.h"
#include "model/template_checks.h"
#include "variation/grains.h"
#include "variation/knife_wobble.h"
#include "variation/organic_deformation.h"

namespace cutaway {

namespace {

/// Purpose tag of the variation streams in derive_seed paths.
constexpr uint64_t kPurposeVariation = 0x7661726961;  // "varia"
/// Purpose tag of the ripeness stream.
constexpr uint64_t kPurposeRipeness = 0x726970656e;  // "ripen"
/// The most a fold's width may differ from the mean (a fraction of it) whatever the amount: a
/// fold keeps at least a tenth of the mean width.
constexpr double kMostFoldSpread = 0.9;
/// Purpose tag of the fold widths' stream.
constexpr uint64_t kPurposeFoldWidths = 0x666f6c6477;  // "foldw"
/// Purpose tag of the parts' wander streams (one per surface and draw).
constexpr uint64_t kPurposeWander = 0x77616e646572;  // "wander"

/// `out` with every surface that may wander moved by a seeded offset, uniform in the ball of
/// radius amount * wander_m (rejection sampling), on top of its own offset.
Template wandered(Template out, uint64_t seed, uint64_t draw, double amount) {
  for (size_t i = 0; i < out.surfaces.size(); ++i) {
    SurfaceSpec& s = out.surfaces[i];
    if (!(s.wander_m > 0)) continue;
    Rng rng(derive_seed(seed, {kPurposeWander, draw, static_cast<uint64_t>(i)}));
    glm::dvec3 d;
    do {
      d = {rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1)};
    } while (glm::dot(d, d) > 1);
    s.offset_m += amount * s.wander_m * d;
  }
  return out;
}

}  // namespace

Template draw_variant(const Template& t, uint64_t seed, uint64_t draw, double amount_scale,
                      const VariationOptions& opt) {
  const double amount = t.variation_amount * amount_scale;
  if (t.symmetry == Symmetry::None || !(amount > 0)) return t;
  Rng rng(derive_seed(seed, {kPurposeVariation, draw}));
  Template out = t;
  if (t.symmetry == Symmetry::Cylindrical) {
    std::vector<int> which;
    std::vector<Polyline2> loops;
    std::vector<bool> smooth;
    for (int i = 0; i < static_cast<int>(t.surfaces.size()); ++i) {
      const SurfaceSpec& s = t.surfaces[i];
      // Sections at several heights keep their shapes (the organic deformation still moves
      // them); De Bonet varies one loop per surface.
      if (s.kind != SurfaceKind::Around || s.section.circle || !s.sections.empty()) continue;
      which.push_back(i);
      loops.push_back(s.section.loops[0]);
      smooth.push_back(s.smooth);
    }
    if (which.empty()) return wandered(out, seed, draw, amount);
    DeBonetOptions d = opt.debonet;
    d.amount = amount;
    const auto varied = synthesize_loops(loops, smooth, opt.loop_samples, d, rng);
    for (size_t k = 0; k < which.size(); ++k) out.surfaces[which[k]].section.loops = {varied[k]};
    return wandered(out, seed, draw, amount);
  }
  // N-fold.
  const FoldFeatures f = fold_features(t, opt.folds);
  const FoldPca pca = fold_pca(f);
  const int lo = std::max(1, t.variation_folds_min), hi = std::max(lo, t.variation_folds_max);
  const int np = lo + static_cast<int>(rng.below(static_cast<uint32_t>(hi - lo + 1)));
  std::vector<std::vector<double>> vectors;
  for (int k = 0; k < np; ++k) vectors.push_back(draw_fold(pca, amount, rng));
  const std::vector<double> angles =
      t.variation_fold_widths > 0
          ? draw_fold_angles(t.fold_angles[0], np,
                             std::min(amount * t.variation_fold_widths, kMostFoldSpread),
                             derive_seed(seed, {kPurposeFoldWidths, draw}))
          : std::vector<double>{};
  return wandered(rebuild_folds(t, f, vectors, opt.folds, angles), seed, draw, amount);
}

std::vector<double> draw_fold_angles(double first_rad, int folds, double spread, uint64_t seed) {
  CUTAWAY_CHECK(folds >= 1 && spread >= 0 && spread < 1);
  Rng rng(seed);
  std::vector<double> width(static_cast<size_t>(folds));
  double total = 0;
  for (double& w : width) total += w = 1 + spread * rng.uniform(-1, 1);
  std::vector<double> angles{first_rad};
  for (size_t k = 1; k < width.size(); ++k)
    angles.push_back(angles.back() + kPi * (width[k - 1] + width[k]) / total);
  return angles;
}

double draw_ripeness(const Template& t, uint64_t seed) {
  const double mid = 0.5 * (t.ripeness_range.x + t.ripeness_range.y);
  const double spread =
      (t.ripeness_range.y - t.ripeness_range.x) * std::clamp(t.variation_amount, 0.0, 1.0);
  if (!(spread > 0)) return mid;
  Rng rng(derive_seed(seed, {kPurposeRipeness}));
  return std::clamp(mid + spread * (rng.uniform() - 0.5), t.ripeness_range.x, t.ripeness_range.y);
}

Variant make_variant(const Template& tmpl, uint64_t seed, const VariationOptions& opt) {
  Template t = tmpl;
  t.ripeness = draw_ripeness(tmpl, seed);
  uint64_t draw = 0;
  double scale = 1.0;
  for (int h = 0; h <= opt.halvings; ++h, scale *= 0.5) {
    for (int a = 0; a < opt.attempts; ++a) {
      Template v = draw_variant(t, seed, draw++, scale, opt);
      std::optional<DsModel> m;
      try {
        check_template_curves(v);
        m = build_model(v);
      } catch (const InputError&) {
        // A draw broke a rule (a loop left its fold, a surface crossed the skin): draw again.
      }
      if (m) {
        // Outside the retry: a grain set over its limits is the template's fault, not the draw's.
        scatter_grains(v, *m, seed);
        deform_model(draw_organic(t, *m, seed), *m);
        m->knife = draw_knife_wobble(*m, seed);
        return {std::move(v), std::move(*m), static_cast<int>(draw), t.variation_amount * scale};
      }
      if (t.symmetry == Symmetry::None || !(t.variation_amount > 0)) break;
    }
    if (t.symmetry == Symmetry::None || !(t.variation_amount > 0)) break;
  }
  DsModel m = build_model(t);
  scatter_grains(t, m, seed);
  deform_model(draw_organic(t, m, seed), m);
  m.knife = draw_knife_wobble(m, seed);
  return {t, std::move(m), static_cast<int>(draw), 0.0};
}

Template vary(const Template& t, uint64_t seed) { return make_variant(t, seed).tmpl; }

}  // namespace cutaway
