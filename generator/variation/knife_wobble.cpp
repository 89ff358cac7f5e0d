#include "variation/knife_wobble.h"

#include <algorithm>

#include "base/random.h"

namespace cutaway {
namespace {

constexpr uint64_t kPurposeKnife = 0x6b6e696665;  // "knife"

}  // namespace

KnifeWobble draw_knife_wobble(const DsModel& model, uint64_t seed) {
  Rng rng(derive_seed(seed, {kPurposeKnife}));
  const double reach =
      0.5 * std::max(model.bbox_max.x - model.bbox_min.x, model.bbox_max.z - model.bbox_min.z);
  KnifeWobble k;
  k.lean_rad = rng.uniform(-kMaxKnifeLeanRad, kMaxKnifeLeanRad);
  k.offset_m = rng.uniform(-kMaxKnifeOffset, kMaxKnifeOffset) * reach;
  return k;
}

}  // namespace cutaway
