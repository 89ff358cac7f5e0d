// Cut objects through the cut cache (doc/architecture.md, Cut cache): the key text of one cut
// object, and its pieces, the materials and textures it added to the scene and its collision
// shapes encoded as a cache entry's payload and read back. Scenes and batches make every
// object's entry (make_cut_entry) and add it to their assets (add_cut_entry): a cached object
// gives the same output bytes as a fresh cut.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "assets/scene_assets.h"
#include "cache/cut_cache.h"
#include "cache/cut_entry_codec.h"
#include "cut/object_cut.h"
#include "placement/collision_shape.h"

namespace cutaway {

/// Everything that decides one cut object's bytes, for cut_cache_key().
struct CutKeyInputs {
  uint64_t template_hash = 0;   ///< Template::source_hash (the file and its meshes)
  double variation_amount = 1;  ///< the variation amount the variant was made with
  uint64_t variant_seed = 0;
  std::string object;  ///< the name cut_object() gives the object (names its meshes,
                       ///< textures and materials)
  /// The diffusion backend's settings that change colours (its resolved kind, cube size,
  /// directions), as the command line writes them.
  std::string diffusion;
  const ObjectCutOptions* cut = nullptr;  ///< required
  /// The collision shapes' options, or null when the caller needs no collision shapes.
  const CollisionShapeOptions* collision = nullptr;
};

/// The key text of a cut object: a JSON object of this program's version and sources
/// fingerprint (source_fingerprint.h) and every field of `in` and of its options, numbers
/// written so that they read back exactly. Two inputs give the same key exactly when they
/// give the same pieces.
std::string cut_cache_key(const CutKeyInputs& in);

/// One cut object as a cache entry's payload, and where it came from.
struct CutEntry {
  std::string payload;      ///< the cut pieces, their new materials and textures, hulls
  bool from_cache = false;  ///< read back, not cut
  /// Processor seconds computing the collision shapes, summed over threads (collision_shapes;
  /// 0 when read back).
  double seconds_collision = 0;
};

/// The cut object of `key` as an entry: read from `cache` when it holds a readable one, else
/// made by `cut` into a SceneAssets of its own (SceneAssets{}, then `tmpl`'s skin and cut
/// materials by add_piece_materials, which `cut` is given), its collision shapes computed when
/// `collision` is given, encoded, and stored. `cache` may be null (no cache). It touches
/// nothing else, so a scene makes its objects' entries side by side and adds them to its
/// assets in order (add_cut_entry).
/// @throws whatever `cut` throws; InternalError when `cut` left a mesh naming a material that
///         is neither new nor one of those it was given
CutEntry make_cut_entry(CutCache* cache, const std::string& key, const Template& tmpl,
                        const CollisionShapeOptions* collision,
                        const std::function<CutPieces(SceneAssets&, const PieceMaterials&)>& cut);

/// The cut object of `entry`, its textures and materials appended to `assets` with their
/// indices rebased; `materials` are the object's skin and cut materials in `assets`
/// (add_piece_materials). The same bytes as cutting into `assets` directly.
/// @throws ByteStreamError when the payload is not an encoded cut object
CachedCut add_cut_entry(const CutEntry& entry, SceneAssets& assets,
                        const PieceMaterials& materials);

}  // namespace cutaway
