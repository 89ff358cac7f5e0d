#include "cache/cut_entry_codec.h"

#include <optional>

#include "base/byte_stream.h"
#include "base/error.h"

namespace cutaway {

namespace {

// The fewest bytes each element of the payload takes (its counts and fixed fields), which
// every count read back is checked against (ByteReader::count), so that no crafted count can
// allocate more than a small multiple of the entry's own size.
constexpr size_t kTextureBytes = 8 + 3 * 4 + 8 + 2;
constexpr size_t kMaterialBytes = 8 + sizeof(PbrMaterial) + 4 * 4 + 8;
constexpr size_t kColouredBytes = 4 * 8;
constexpr size_t kPrimitiveBytes = 8 + 8 + 4 + 8;
constexpr size_t kPieceInfoBytes = 8 + 8 + 8 + 4 + 8 + 8;
constexpr size_t kPieceBytes = kColouredBytes + 8 + 8 + 8 +  // the mesh
                               kColouredBytes + 8 + 8 +      // its shape
                               kPieceInfoBytes + sizeof(glm::dvec3) + 4;
constexpr size_t kConvexPartBytes = 8 + 8;
constexpr size_t kCollisionBytes = 8 + 8 + sizeof(glm::dvec3) + 8 + 1;

/// Where the materials of the cut object are: those it was given (`materials`), then the ones
/// it added from index `first_new`. Encodes a material index as 0, 1, 2 (the given skin, wall,
/// cut) or 3 + k (the k-th added one), and back.
struct MaterialRebase {
  PieceMaterials given;
  int first_new = 0;

  int32_t encode(int m) const {
    if (m >= first_new) return 3 + (m - first_new);
    if (m == given.skin) return 0;
    if (m == given.wall) return 1;
    if (m == given.cut) return 2;
    throw InternalError("cut cache: a piece names material " + std::to_string(m) +
                        ", neither its object's nor a new one");
  }
  int decode(int32_t code) const {
    if (code >= 3) return first_new + (code - 3);
    if (code < 0) throw ByteStreamError("a material code below 0");
    return code == 0 ? given.skin : (code == 1 ? given.wall : given.cut);
  }
};

void put_coloured(ByteWriter& w, const ColouredMesh& m) {
  w.put_vector(m.position);
  w.put_vector(m.normal);
  w.put_vector(m.colour);
  w.put_vector(m.triangle);
}

void get_coloured(ByteReader& r, ColouredMesh& m) {
  m.position = r.get_vector<glm::dvec3>();
  m.normal = r.get_vector<glm::dvec3>();
  m.colour = r.get_vector<glm::dvec3>();
  m.triangle = r.get_vector<glm::uvec3>();
}

void put_asset_mesh(ByteWriter& w, const AssetMesh& m, const MaterialRebase& rebase) {
  put_coloured(w, m);
  w.put_string(m.name);
  w.put_vector(m.uv);
  w.put<uint64_t>(m.primitives.size());
  for (const AssetPrimitive& p : m.primitives) {
    w.put<uint64_t>(p.first);
    w.put<uint64_t>(p.count);
    w.put<int32_t>(rebase.encode(p.material));
    w.put_vector(p.coarse);
  }
}

AssetMesh get_asset_mesh(ByteReader& r, const MaterialRebase& rebase) {
  AssetMesh m;
  get_coloured(r, m);
  m.name = r.get_string();
  m.uv = r.get_vector<glm::dvec2>();
  m.primitives.resize(r.count(kPrimitiveBytes));
  for (AssetPrimitive& p : m.primitives) {
    p.first = r.get<uint64_t>();
    p.count = r.get<uint64_t>();
    p.material = rebase.decode(r.get<int32_t>());
    p.coarse = r.get_vector<glm::uvec3>();
  }
  return m;
}

void put_piece_info(ByteWriter& w, const PieceInfo& info) {
  w.put_string(info.template_name);
  w.put(info.seed);
  w.put_string(info.cut);
  w.put<int32_t>(info.cell);
  w.put<uint64_t>(info.parts.size());
  for (const std::string& part : info.parts) w.put_string(part);
  w.put(info.volume_m3);
}

PieceInfo get_piece_info(ByteReader& r) {
  PieceInfo info;
  info.template_name = r.get_string();
  info.seed = r.get<uint64_t>();
  info.cut = r.get_string();
  info.cell = r.get<int32_t>();
  info.parts.resize(r.count(8));  // each a string: its count
  for (std::string& part : info.parts) part = r.get_string();
  info.volume_m3 = r.get<double>();
  return info;
}

void put_collision(ByteWriter& w, const CollisionShape& c) {
  w.put<uint64_t>(c.parts.size());
  for (const ConvexPart& part : c.parts) {
    w.put_vector(part.corners);
    w.put(part.outside_m);
  }
  w.put(c.volume_m3);
  w.put(c.centroid);
  w.put(c.convexity);
  w.put<uint8_t>(c.decomposed);
}

CollisionShape get_collision(ByteReader& r) {
  CollisionShape c;
  c.parts.resize(r.count(kConvexPartBytes));
  for (ConvexPart& part : c.parts) {
    part.corners = r.get_vector<glm::dvec3>();
    part.outside_m = r.get<double>();
  }
  c.volume_m3 = r.get<double>();
  c.centroid = r.get<glm::dvec3>();
  c.convexity = r.get<double>();
  c.decomposed = r.get<uint8_t>() != 0;
  return c;
}

/// A texture index of an added material: -1, or k for the k-th added texture.
int32_t encode_texture(int t, int first_new) {
  if (t < 0) return -1;
  if (t < first_new) throw InternalError("cut cache: a new material names an older texture");
  return t - first_new;
}

/// The payload: the cut object, the materials and textures it added to the scene (from
/// `first_material` and `first_texture` on), its collision shapes.
std::string encode_cut(const CachedCut& made, const SceneAssets& assets,
                       const MaterialRebase& rebase, int first_texture) {
  ByteWriter w;
  w.put<uint64_t>(assets.textures.size() - static_cast<size_t>(first_texture));
  for (size_t k = static_cast<size_t>(first_texture); k < assets.textures.size(); ++k) {
    const AssetTexture& t = assets.textures[k];
    w.put_string(t.name);
    w.put<int32_t>(t.width);
    w.put<int32_t>(t.height);
    w.put<int32_t>(t.channels);
    w.put_vector(t.pixels);
    w.put<uint8_t>(t.wrap_u);
    w.put<uint8_t>(t.linear);
  }
  w.put<uint64_t>(assets.materials.size() - static_cast<size_t>(rebase.first_new));
  for (size_t k = static_cast<size_t>(rebase.first_new); k < assets.materials.size(); ++k) {
    const AssetMaterial& m = assets.materials[k];
    w.put_string(m.name);
    w.put(m.pbr);
    w.put<int32_t>(encode_texture(m.base_colour_texture, first_texture));
    w.put<int32_t>(encode_texture(m.material_texture, first_texture));
    w.put<int32_t>(encode_texture(m.normal_texture, first_texture));
    w.put<int32_t>(encode_texture(m.height_texture, first_texture));
    w.put<double>(m.height_bump);
  }
  const CutPieces& p = made.pieces;
  w.put_string(p.backend);
  w.put<uint64_t>(p.pieces_cut);
  w.put<uint64_t>(p.meshes.size());
  for (size_t q = 0; q < p.meshes.size(); ++q) {
    put_asset_mesh(w, p.meshes[q], rebase);
    put_coloured(w, p.shapes[q]);
    w.put_vector(p.shapes[q].material);
    w.put_vector(p.shapes[q].param);
    put_piece_info(w, p.infos[q]);
    w.put(p.cap_normals[q]);
    w.put<int32_t>(p.cut_faces[q]);
  }
  w.put<uint64_t>(made.collision.size());
  for (const CollisionShape& c : made.collision) put_collision(w, c);
  return w.take();
}

/// A texture index read back for a scene whose added textures start at `first_new`.
int decode_texture(int32_t code, int first_new, size_t added) {
  if (code < 0) return -1;
  if (static_cast<size_t>(code) >= added) throw ByteStreamError("a texture beyond the entry's");
  return first_new + code;
}

/// Reads what encode_cut wrote, appending its textures and materials to `assets`; leaves
/// `assets` unchanged when the payload is damaged.
/// @throws ByteStreamError on a damaged payload
CachedCut decode_cut(std::string_view payload, SceneAssets& assets,
                     const PieceMaterials& materials) {
  ByteReader r(payload);
  std::vector<AssetTexture> textures(r.count(kTextureBytes));
  for (AssetTexture& t : textures) {
    t.name = r.get_string();
    t.width = r.get<int32_t>();
    t.height = r.get<int32_t>();
    t.channels = r.get<int32_t>();
    t.pixels = r.get_vector<uint8_t>();
    t.wrap_u = r.get<uint8_t>() != 0;
    t.linear = r.get<uint8_t>() != 0;
  }
  const int first_texture = static_cast<int>(assets.textures.size());
  std::vector<AssetMaterial> added(r.count(kMaterialBytes));
  for (AssetMaterial& m : added) {
    m.name = r.get_string();
    m.pbr = r.get<PbrMaterial>();
    m.base_colour_texture = decode_texture(r.get<int32_t>(), first_texture, textures.size());
    m.material_texture = decode_texture(r.get<int32_t>(), first_texture, textures.size());
    m.normal_texture = decode_texture(r.get<int32_t>(), first_texture, textures.size());
    m.height_texture = decode_texture(r.get<int32_t>(), first_texture, textures.size());
    m.height_bump = r.get<double>();
  }
  const MaterialRebase rebase{materials, static_cast<int>(assets.materials.size())};
  CachedCut out;
  CutPieces& p = out.pieces;
  p.backend = r.get_string();
  p.pieces_cut = r.get<uint64_t>();
  const uint64_t n = r.count(kPieceBytes);
  for (uint64_t q = 0; q < n; ++q) {
    p.meshes.push_back(get_asset_mesh(r, rebase));
    ShadedMesh shape;
    get_coloured(r, shape);
    shape.material = r.get_vector<glm::dvec2>();
    shape.param = r.get_vector<glm::dvec2>();
    p.shapes.push_back(std::move(shape));
    p.infos.push_back(get_piece_info(r));
    p.cap_normals.push_back(r.get<glm::dvec3>());
    p.cut_faces.push_back(r.get<int32_t>());
  }
  out.collision.resize(r.count(kCollisionBytes));
  for (CollisionShape& c : out.collision) c = get_collision(r);
  if (!r.done()) throw ByteStreamError("bytes after the cut object");
  for (const AssetMesh& m : p.meshes)
    for (const AssetPrimitive& prim : m.primitives)
      if (prim.material >= rebase.first_new + static_cast<int>(added.size()))
        throw ByteStreamError("a material beyond the entry's");
  for (AssetTexture& t : textures) assets.textures.push_back(std::move(t));
  for (AssetMaterial& m : added) assets.materials.push_back(std::move(m));
  return out;
}

}  // namespace

std::string encode_cut_payload(const CachedCut& cut, const SceneAssets& assets,
                               const PieceMaterials& materials, int first_new_material) {
  return encode_cut(cut, assets, MaterialRebase{materials, first_new_material}, 0);
}

CachedCut decode_cut_payload(std::string_view payload, SceneAssets& assets,
                             const PieceMaterials& materials) {
  return decode_cut(payload, assets, materials);
}

std::string encode_settled(const SettleResult& s) {
  ByteWriter w;
  w.put<uint64_t>(s.placements.size());
  for (const Placement& p : s.placements) {
    w.put<uint8_t>(p.placed);
    w.put(p.rotation);
    w.put(p.translation);
  }
  w.put(s.simulated_s);
  w.put<int32_t>(s.steps);
  w.put<int64_t>(s.body_steps);
  w.put<uint8_t>(s.all_asleep);
  w.put(s.stability_motion_m);
  w.put<uint8_t>(s.stable);
  w.put<int32_t>(s.verify_rounds);
  w.put<int32_t>(s.kept_round);
  w.put<int32_t>(s.redrops);
  w.put<int32_t>(s.lost);
  return w.take();
}

std::optional<SettleResult> decode_settled(std::string_view payload, size_t bodies) {
  try {
    ByteReader r(payload);
    SettleResult s;
    constexpr size_t kPlacementBytes = 1 + sizeof(glm::dquat) + sizeof(glm::dvec3);
    const uint64_t n = r.count(kPlacementBytes);
    if (n != bodies) return std::nullopt;  // checked before anything is allocated
    s.placements.resize(n);
    for (Placement& p : s.placements) {
      p.placed = r.get<uint8_t>() != 0;
      p.rotation = r.get<glm::dquat>();
      p.translation = r.get<glm::dvec3>();
    }
    s.simulated_s = r.get<double>();
    s.steps = r.get<int32_t>();
    s.body_steps = r.get<int64_t>();
    s.all_asleep = r.get<uint8_t>() != 0;
    s.stability_motion_m = r.get<double>();
    s.stable = r.get<uint8_t>() != 0;
    s.verify_rounds = r.get<int32_t>();
    s.kept_round = r.get<int32_t>();
    s.redrops = r.get<int32_t>();
    s.lost = r.get<int32_t>();
    if (!r.done()) return std::nullopt;
    return s;
  } catch (const ByteStreamError&) {
    return std::nullopt;
  }
}

}  // namespace cutaway
