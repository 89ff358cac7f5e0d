// The knife's small wobble (doc/algorithms.md §5, Knife wobble): a hand cuts a fruit in halves
// neither exactly through its axis nor exactly upright, so the two halves of one object are not
// mirror copies of each other. A variant draws how far the halves' plane leans and how far off
// the axis it runs; make_cut_cells applies it.
#pragma once

#include <cstdint>

#include "model/ds_model.h"

namespace cutaway {

/// The largest lean of the halves' plane, radians (4 degrees).
inline constexpr double kMaxKnifeLeanRad = 0.06981317007977318;
/// The largest distance of the halves' plane from the axis, as a share of the model's
/// horizontal reach (half the larger side of its bounding box across the axis): 5 %, halves of
/// a 60 mm tomato up to 1.5 mm thicker or thinner than half.
inline constexpr double kMaxKnifeOffset = 0.05;

/// The wobble of the knife through `model` (a variant's, after its organic deformation), drawn
/// from `seed`'s own stream: lean uniform in +-kMaxKnifeLeanRad, offset uniform in
/// +-kMaxKnifeOffset of the model's horizontal reach (metres). Deterministic in `seed` and the
/// model's bounds.
KnifeWobble draw_knife_wobble(const DsModel& model, uint64_t seed);

}  // namespace cutaway
