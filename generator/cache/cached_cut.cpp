#include "cache/cached_cut.h"

#include <nlohmann/json.hpp>

#include "base/byte_stream.h"
#include "base/error.h"
#include "base/source_fingerprint.h"
#include "cache/cut_entry_check.h"
#include "cache/cut_entry_codec.h"

namespace cutaway {

namespace {

/// The version of the payload's layout (and of the key's), part of every key.
constexpr int kPayloadVersion = 2;

// A field added to one of these structs must be added to the key below: their sizes remind.
static_assert(sizeof(ObjectCutOptions) == 176,
              "a new ObjectCutOptions field: add it to cut_cache_key");
static_assert(sizeof(CapAtlasOptions) == 24, "a new CapAtlasOptions field: add it to the key");
static_assert(sizeof(SkinTextureOptions) == 24,
              "a new SkinTextureOptions field: add it to the key");
static_assert(sizeof(CollisionShapeOptions) == 48,
              "a new CollisionShapeOptions field: add it to the key");
static_assert(sizeof(CutSpec) == 80, "a new CutSpec field: add it to cut_exact_text");

/// The options of a baked texture (CapAtlasOptions, SkinTextureOptions: the same fields).
template <typename TextureOptions>
nlohmann::ordered_json texture_json(const TextureOptions& t) {
  return {{"texels_per_m", t.texels_per_m},
          {"padding", t.padding},
          {"max_size", t.max_size},
          {"power_of_two", t.power_of_two}};
}

nlohmann::ordered_json collision_json(const CollisionShapeOptions* c) {
  if (!c) return nullptr;
  return {{"min_convexity", c->min_convexity},
          {"concavity", c->concavity},
          {"decomposition_triangles", c->decomposition_triangles},
          {"max_parts", c->max_parts},
          {"seed_corners", c->seed_corners},
          {"corner_tolerance_m", c->corner_tolerance_m},
          {"max_corners", c->max_corners}};
}

}  // namespace

std::string cut_cache_key(const CutKeyInputs& in) {
  if (!in.cut) throw InternalError("cut_cache_key: no cut options");
  const ObjectCutOptions& c = *in.cut;
  const nlohmann::ordered_json key = {{"cutaway", CUTAWAY_VERSION},
                                      {"sources", source_fingerprint()},
                                      {"payload", kPayloadVersion},
                                      {"template", in.template_hash},
                                      {"variation_amount", in.variation_amount},
                                      {"variant_seed", in.variant_seed},
                                      {"object", in.object},
                                      {"diffusion", in.diffusion},
                                      {"cut", cut_exact_text(c.cut)},
                                      {"whole_when_missed", c.whole_when_missed},
                                      {"keep", c.keep},
                                      {"keep_seed", c.keep_seed},
                                      {"modulation_seed", c.modulation_seed},
                                      {"perlin", c.perlin},
                                      {"sampling", static_cast<int>(c.sampling)},
                                      {"cap_colours", static_cast<int>(c.cap_colours)},
                                      {"atlas", texture_json(c.atlas)},
                                      {"skin", texture_json(c.skin)},
                                      {"collision", collision_json(in.collision)}};
  return key.dump();
}

CutEntry make_cut_entry(CutCache* cache, const std::string& key, const Template& tmpl,
                        const CollisionShapeOptions* collision,
                        const std::function<CutPieces(SceneAssets&, const PieceMaterials&)>& cut) {
  SceneAssets own;
  const PieceMaterials materials =
      add_piece_materials(own, tmpl.name, tmpl.skin_material, tmpl.cut_material);
  const int first_new = static_cast<int>(own.materials.size());
  if (cache) {
    if (std::optional<std::string> payload = cache->load(key)) {
      // Untrusted input, whatever its CRC: decoded and checked in full before it is used, and
      // made again (below) when it fails.
      std::string problem;
      try {
        SceneAssets scratch = own;
        CachedCut probe = decode_cut_payload(*payload, scratch, materials);
        const Check usable = check_cached_cut(probe.pieces, probe.collision, collision != nullptr,
                                              scratch, template_reach_m(tmpl));
        if (usable) return {std::move(*payload), true, 0};
        problem = usable.reason();
      } catch (const ByteStreamError& e) {
        problem = e.what();
      }
      cache->discard(key, problem);
    }
  }
  CachedCut made;
  made.pieces = cut(own, materials);
  double collision_seconds = 0;
  if (collision)
    made.collision = collision_shapes(made.pieces.shapes, *collision, &collision_seconds);
  CutEntry entry{encode_cut_payload(made, own, materials, first_new), false, collision_seconds};
  if (cache) cache->store(key, entry.payload);
  return entry;
}

CachedCut add_cut_entry(const CutEntry& entry, SceneAssets& assets,
                        const PieceMaterials& materials) {
  CachedCut out = decode_cut_payload(entry.payload, assets, materials);
  out.from_cache = entry.from_cache;
  out.seconds_collision = entry.seconds_collision;
  return out;
}

}  // namespace cutaway
