// Placements through the cut cache (doc/architecture.md, Cut cache): a scene's layout and
// settling depend only on its cut objects, their arrangement, the seed, the container and the
// layout and settling options, so a run that changes none of them (another output format,
// resolution, light, zoom) reads the settled placements back instead of settling again. The
// payload (encode_settled, decode_settled) is in cut_entry_codec.h.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cache/cut_entry_codec.h"
#include "placement/container.h"
#include "placement/physics_settle.h"
#include "placement/scene_layout.h"

namespace cutaway {

/// Everything that decides a scene's placements, for placement_cache_key().
struct PlacementKeyInputs {
  std::vector<std::string> cut_keys;      ///< each object's cut_cache_key, in scene order
  std::vector<Arrangement> arrange;       ///< each object's arrangement, in scene order
  uint64_t seed = 0;                      ///< the scene's seed (placement order, layout)
  const Container* container = nullptr;   ///< required
  const LayoutOptions* layout = nullptr;  ///< required: with the camera's to_camera
  const SettleOptions* settle = nullptr;  ///< required
};

/// The key text of a scene's placements: a JSON object of this program's version and sources
/// fingerprint, a hash of each object's cut key, and every field of the other inputs (numbers
/// written so that they read back exactly).
std::string placement_cache_key(const PlacementKeyInputs& in);

}  // namespace cutaway
