// A cut object, and a scene's settled placements, as the bytes of a cut cache entry's
// payload, and back (doc/architecture.md, Cut
// cache): its kept pieces, the textures and materials it added to the scene (indices rebased
// onto the scene that reads it), its collision shapes. Values keep every bit (byte_stream.h),
// so a decoded object gives the same output bytes as a fresh cut. Decoding treats the bytes as
// untrusted: every count is checked against the bytes left and what each element costs at
// least, every material and texture code against what the entry holds; cut_entry_check.h then
// checks what was decoded.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "assets/scene_assets.h"
#include "cut/object_cut.h"
#include "placement/collision_shape.h"
#include "placement/physics_settle.h"

namespace cutaway {

/// One cut object as a scene or batch uses it.
struct CachedCut {
  CutPieces pieces;
  std::vector<CollisionShape> collision;  ///< per kept piece, or empty (no options given)
  bool from_cache = false;                ///< read back, not cut
  /// Processor seconds computing `collision`, summed over threads (0 when read back).
  double seconds_collision = 0;
};

/// The payload of `cut`, whose pieces name `materials` (the object's skin, wall and cut
/// materials in `assets`) or materials `assets` holds from index `first_new_material` on, and
/// whose new materials name textures of `assets` from index 0 on (a cut object made or decoded
/// into assets of its own that held only `materials` and no textures).
/// @throws InternalError when a piece names a material that is neither given nor new
std::string encode_cut_payload(const CachedCut& cut, const SceneAssets& assets,
                               const PieceMaterials& materials, int first_new_material);

/// What encode_cut_payload wrote, its textures and materials appended to `assets` (indices
/// rebased onto them) and its pieces naming `materials` for the given ones; `assets` is left
/// unchanged when the payload is damaged.
/// @throws ByteStreamError on a damaged payload (ends early, a count beyond the data, a code
///         beyond the entry's materials or textures, bytes after the object)
CachedCut decode_cut_payload(std::string_view payload, SceneAssets& assets,
                             const PieceMaterials& materials);

/// `settled` as a cache payload: its placements and its counts.
std::string encode_settled(const SettleResult& settled);

/// What encode_settled wrote, or nullopt when the payload is damaged or holds other than
/// `bodies` placements.
std::optional<SettleResult> decode_settled(std::string_view payload, size_t bodies);

}  // namespace cutaway
