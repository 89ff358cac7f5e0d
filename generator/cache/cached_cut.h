// Cut objects through the cut cache (doc/architecture.md, Cut cache): the key text of one cut
// object, and its pieces, the materials and textures it added to the scene and its collision
// shapes encoded as a cache entry's payload and read back. Scenes and batches cut every object
// through cut_through_cache(); a cached object gives the same output bytes as a fresh cut.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "assets/scene_assets.h"
#include "cache/cut_cache.h"
#include "cut/object_cut.h"
#include "placement/collision_shape.h"

namespace cutaway {

/// Everything that decides one cut object's bytes, for cut_cache_key().
struct CutKeyInputs {
  uint64_t template_hash = 0;   ///< Template::source_hash (the file and its meshes)
  double variation_amount = 1;  ///< the variation amount the variant was made with
  uint64_t variant_seed = 0;
  std::string object;           ///< the name cut_object() gives the object (names its meshes,
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

/// One cut object as a scene or batch uses it.
struct CachedCut {
  CutPieces pieces;
  std::vector<CollisionShape> collision;  ///< per kept piece, or empty (no options given)
  bool from_cache = false;                ///< read back, not cut
  double seconds_collision = 0;           ///< computing `collision` (0 when read back)
};

/// The cut object of `key`: read from `cache` when it holds it (its materials and textures
/// appended to `assets`, their indices rebased), else made by `cut` (which appends its own to
/// `assets` and must refer to existing materials only through `materials`), its collision
/// shapes computed when `collision` is given, and stored. `cache` may be null (no cache).
/// Either way `assets` and the result are the same, byte for byte.
/// @throws whatever `cut` throws; InternalError when `cut` left a mesh naming a material that
///         is neither new nor one of `materials`
CachedCut cut_through_cache(CutCache* cache, const std::string& key, SceneAssets& assets,
                            const PieceMaterials& materials,
                            const CollisionShapeOptions* collision,
                            const std::function<CutPieces()>& cut);

}  // namespace cutaway
