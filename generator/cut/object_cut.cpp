#include "cut/object_cut.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include <glm/geometric.hpp>

#include "base/random.h"
#include "base/timer.h"
#include "material/colour_modulation.h"
#include "material/skin_pattern.h"
#include "pieces/coarse_cap.h"

namespace cutaway {

namespace {

using Clock = std::chrono::steady_clock;

/// A seeded choice of `keep` of n indices, in increasing order (partial Fisher-Yates).
std::vector<size_t> choose(size_t n, size_t keep, uint64_t seed) {
  std::vector<size_t> all(n);
  std::iota(all.begin(), all.end(), size_t{0});
  Rng rng(seed);
  for (size_t k = 0; k < keep && k + 1 < n; ++k) {
    const size_t j = k + rng.below(static_cast<uint32_t>(n - k));
    std::swap(all[k], all[j]);
  }
  all.resize(keep);
  std::sort(all.begin(), all.end());
  return all;
}

/// `piece` as an exportable mesh named `name`: `merged` is merge_parts of it (possibly
/// recoloured), its triangles those of the skin, the walls, the stones and the caps in turn;
/// one primitive per run of parts of one material (skin, walls, stones, caps; none when all
/// are material 0).
/// `uv`: #V texture coordinates (CapAtlas::uv and the skin's) or empty; `coarse_caps`: the
/// caps' coarse triangles (coarse_caps()) for the cap primitive, or empty.
AssetMesh piece_mesh(const ShadedMesh& merged, const Piece& piece, PieceMaterials materials,
                     const std::string& name, const std::vector<glm::dvec2>& uv,
                     const std::vector<glm::uvec3>& coarse_caps) {
  AssetMesh out;
  static_cast<ColouredMesh&>(out) = merged;
  out.name = name;
  out.uv = uv;
  const size_t n = merged.triangle.size();
  const size_t surface = surface_triangle_count(piece);
  const PiecePart* skin_surface = skin_part(piece);
  const size_t skin = skin_surface ? skin_surface->mesh.triangle.size() : 0;
  size_t stones = 0;  // the stones' parts follow the walls (cut_pieces)
  for (const PiecePart& part : piece.parts)
    if (part.kind == PartKind::Stone) stones += part.mesh.triangle.size();
  const struct {
    size_t first, count;
    int material;
  } runs[4] = {{0, skin, materials.skin},
               {skin, surface - skin - stones, materials.wall},
               {surface - stones, stones, materials.stone},
               {surface, n - surface, materials.cut}};
  for (const auto& run : runs) {
    if (run.count == 0) continue;
    if (!out.primitives.empty() && out.primitives.back().material == run.material)
      out.primitives.back().count += run.count;
    else out.primitives.push_back({run.first, run.count, run.material, {}});
  }
  if (surface < n && out.primitives.back().first == surface)  // the caps alone
    out.primitives.back().coarse = coarse_caps;
  if (out.primitives.size() == 1 && out.primitives[0].material == 0) out.primitives.clear();
  return out;
}

/// What `piece` is (its glTF node extras): template, variant seed, cut_label(cut), its cell,
/// the kinds of its parts and the volume of `merged` (merge_parts of it).
PieceInfo piece_info(const Piece& piece, const ShadedMesh& merged, const std::string& template_name,
                     uint64_t seed, const CutSpec& cut) {
  PieceInfo info{template_name, seed, cut_label(cut), piece.cell, {}, signed_volume(merged)};
  for (const PiecePart& part : piece.parts) {
    const std::string kind = part.kind == PartKind::Skin    ? "skin"
                             : part.kind == PartKind::Wall  ? "wall"
                             : part.kind == PartKind::Stone ? "stone"
                                                            : "cap";
    if (std::find(info.parts.begin(), info.parts.end(), kind) == info.parts.end())
      info.parts.push_back(kind);
  }
  return info;
}

/// Bakes the caps of `pieces` (of one object, cut into `set`) into a texture added to
/// `assets`, adds a copy of material `materials.cut` textured with it, named "<object>_cut",
/// its roughness and translucency the means of the diffused material channels and, where
/// those vary, a material map "<object>_cut_material" (cap_atlas.h), and returns the object's
/// materials with it, and per piece the texture coordinates of its merge_parts vertices in `uv`.
/// Pieces without caps: `materials` and empty uv.
PieceMaterials add_cap_texture(SceneAssets& assets, const PieceSet& set,
                               const std::vector<const Piece*>& pieces, PieceMaterials materials,
                               const std::string& object, const ColourModulation* modulation,
                               double strength, const CapAtlasOptions& options,
                               std::vector<std::vector<glm::dvec2>>& uv) {
  CapAtlas atlas = bake_cap_atlas(pieces, set.sections, modulation, strength, options);
  if (atlas.width == 0) {
    uv.assign(pieces.size(), {});
    return materials;
  }
  uv = std::move(atlas.uv);
  AssetMaterial cut = assets.materials[static_cast<size_t>(materials.cut)];
  cut.name = object + "_cut";
  // The diffused material channels: their mean as factors, and a map where they vary.
  cut.pbr.roughness = atlas.material_mean.x;
  cut.pbr.translucency = atlas.material_mean.y;
  if (!atlas.material.empty()) {
    assets.textures.push_back({object + "_cut_material", atlas.material_width,
                               atlas.material_height, 4, std::move(atlas.material), false, true});
    cut.material_texture = static_cast<int>(assets.textures.size()) - 1;
  }
  assets.textures.push_back({object + "_cut", atlas.width, atlas.height, 3, std::move(atlas.srgb)});
  cut.base_colour_texture = static_cast<int>(assets.textures.size()) - 1;
  assets.materials.push_back(cut);
  materials.cut = static_cast<int>(assets.materials.size()) - 1;
  return materials;
}

/// Where the kept pieces of `set` have parts of `kind` (PartKind::Wall: the walls of hollows and
/// the imprints of stones gone to another piece; PartKind::Stone: whole stones), adds a material
/// named "<object>_<suffix>" whose roughness and translucency are the means of those parts' own
/// (the side of the surface they show), with no clear coat and no sheen, and returns `materials`
/// with it as theirs (`wall` or `stone`). A stone is bare and dry, and a wall is the flesh or the
/// fibres of a cavity, not the skin: both took the skin's material before (an apricot's velvet
/// sheen made its stone pale cream in Blender; a cherry's glossy, clear-coated skin made the
/// imprint of its stone shine like a red bead). Without such parts: `materials`.
PieceMaterials add_own_material(SceneAssets& assets, const PieceSet& set, PieceMaterials materials,
                                const std::string& object, PartKind kind, const char* suffix) {
  glm::dvec2 sum(0.0);
  size_t count = 0;
  for (const Piece& piece : set.pieces)
    for (const PiecePart& part : piece.parts)
      if (part.kind == kind)
        for (const glm::dvec2& m : part.mesh.material) {
          sum += m;
          ++count;
        }
  if (count == 0) return materials;
  AssetMaterial own = assets.materials[static_cast<size_t>(materials.wall)];
  own.name = object + "_" + suffix;
  own.pbr = PbrMaterial{};
  own.pbr.roughness = sum.x / static_cast<double>(count);
  own.pbr.translucency = sum.y / static_cast<double>(count);
  assets.materials.push_back(own);
  (kind == PartKind::Stone ? materials.stone : materials.wall) =
      static_cast<int>(assets.materials.size()) - 1;
  return materials;
}

/// Unwraps the skin part of each piece of `set` (unwrap_skin: adds vertices along the seam and
/// at the poles) and returns per piece its coordinates, or nothing for a piece without skin.
std::vector<std::vector<glm::dvec2>> unwrap_skins(PieceSet& set) {
  std::vector<std::vector<glm::dvec2>> uv;
  for (Piece& piece : set.pieces) {
    uv.push_back(skin_part(piece) ? unwrap_skin(piece.parts[0].mesh) : std::vector<glm::dvec2>{});
  }
  return uv;
}

/// Bakes the unwrapped skins of the pieces of `set` (one object whose DS skin is `skin`)
/// into a texture "<object>_skin" repeating in u (skin_texture.h), adds a copy of material
/// `materials.skin` textured with it and returns the object's materials with it as the skin's;
/// writes each piece's skin coordinates into the first entries of uv[q] (sized to the
/// piece's merge_parts vertices). The skin's `patterns` and the Perlin `modulation` are baked
/// in per texel; where the patterns have a relief, textures "<object>_skin_normal" and
/// "<object>_skin_height" become the material's normal and height maps. No skins: `materials`
/// unchanged.
PieceMaterials add_skin_texture(SceneAssets& assets, const DsSurface& skin, const PieceSet& set,
                                const std::vector<std::vector<glm::dvec2>>& skin_uv,
                                PieceMaterials materials, const std::string& object,
                                const SkinPatterns* patterns, const ColourModulation* modulation,
                                double strength, const SkinTextureOptions& options,
                                std::vector<std::vector<glm::dvec2>>& uv) {
  std::vector<const ShadedMesh*> parts;
  std::vector<const std::vector<glm::dvec2>*> part_uv;
  for (size_t q = 0; q < set.pieces.size(); ++q) {
    if (skin_uv[q].empty()) continue;
    const Piece& piece = set.pieces[q];
    parts.push_back(&skin_part(piece)->mesh);
    part_uv.push_back(&skin_uv[q]);
    uv[q].resize(part_vertex_offsets(piece).back(), glm::dvec2(0.0));
    std::copy(skin_uv[q].begin(), skin_uv[q].end(), uv[q].begin());  // the skin comes first
  }
  if (parts.empty()) return materials;
  const glm::ivec2 size = skin_texture_size(skin, options);
  SkinTexture baked =
      bake_skin_texture(parts, part_uv, size, patterns, modulation, strength, options);
  AssetMaterial textured = assets.materials[static_cast<size_t>(materials.skin)];
  textured.name = object + "_skin";
  if (baked.relief) {
    ReliefMaps& relief = *baked.relief;
    assets.textures.push_back(
        {object + "_skin_normal", size.x, size.y, 3, std::move(relief.normal), true, true});
    textured.normal_texture = static_cast<int>(assets.textures.size()) - 1;
    assets.textures.push_back(
        {object + "_skin_height", size.x, size.y, 1, std::move(relief.height), true, true});
    textured.height_texture = static_cast<int>(assets.textures.size()) - 1;
    textured.height_bump =
        relief.texel_m > 0 ? (relief.high_m - relief.low_m) / relief.texel_m : 0.0;
  }
  assets.textures.push_back({object + "_skin", size.x, size.y, 3, std::move(baked.srgb), true});
  textured.base_colour_texture = static_cast<int>(assets.textures.size()) - 1;
  assets.materials.push_back(textured);
  materials.skin = static_cast<int>(assets.materials.size()) - 1;
  return materials;
}

}  // namespace

PieceMaterials add_piece_materials(SceneAssets& assets, const std::string& name,
                                   const PbrMaterial& skin, const PbrMaterial& cut) {
  auto index = [&assets](const std::string& material_name, const PbrMaterial& pbr) {
    if (pbr == PbrMaterial{}) return 0;
    for (size_t k = 0; k < assets.materials.size(); ++k)
      if (assets.materials[k].name == material_name) return static_cast<int>(k);
    assets.materials.push_back({material_name, pbr});
    return static_cast<int>(assets.materials.size()) - 1;
  };
  const std::string base = asset_name(name);
  const int skin_id = index(base + "_skin", skin);
  return {skin_id, skin_id, skin == cut ? skin_id : index(base + "_cut", cut), skin_id};
}

std::vector<glm::uvec3> coarse_caps(const Piece& piece, const std::vector<CrossSection>& sections) {
  std::vector<glm::uvec3> out;
  const std::vector<unsigned> offsets = part_vertex_offsets(piece);
  for (size_t k = 0; k < piece.parts.size(); ++k) {
    const PiecePart& part = piece.parts[k];
    if (part.kind != PartKind::Cap) continue;
    const CrossSection& section = sections.at(static_cast<size_t>(part.plane));
    for (const glm::uvec3& t : coarse_cap_triangles(part.mesh, section.u_axis, section.v_axis))
      out.push_back(t + offsets[k]);
  }
  return out;
}

int cut_faces(const Piece& piece) {
  std::vector<glm::dvec3> normals;
  for (const PiecePart& part : piece.parts) {
    if (part.kind != PartKind::Cap || part.mesh.normal.empty()) continue;
    bool seen = false;
    for (const glm::dvec3& n : normals) seen = seen || glm::dot(n, part.mesh.normal[0]) > 0.999;
    if (!seen) normals.push_back(part.mesh.normal[0]);
  }
  return static_cast<int>(normals.size());
}

glm::dvec3 largest_cap_normal(const Piece& piece) {
  double best = 0;
  glm::dvec3 normal(0.0);
  for (const PiecePart& part : piece.parts) {
    if (part.kind != PartKind::Cap || part.mesh.normal.empty()) continue;
    double area = 0;
    for (const glm::uvec3& t : part.mesh.triangle)
      area += 0.5 * glm::length(glm::cross(part.mesh.position[t[1]] - part.mesh.position[t[0]],
                                           part.mesh.position[t[2]] - part.mesh.position[t[0]]));
    if (area > best) {
      best = area;
      normal = part.mesh.normal[0];
    }
  }
  return normal;
}

Outcome<CutObject> cut_object(SceneAssets& assets, const Variant& variant, uint64_t variant_seed,
                              const PieceMaterials& materials, const std::string& object,
                              const DiffusionBackend& diffusion, const ObjectCutOptions& options,
                              ObjectCutStats& stats) {
  PieceOptions piece_options;
  piece_options.section.edge_m = variant.tmpl.edge_m;
  piece_options.section.sampling = options.sampling;
  piece_options.stone_seed = variant_seed;
  piece_options.keep_pieces = [&options](size_t n) {
    const size_t keep = std::clamp<size_t>(
        static_cast<size_t>(std::llround(options.keep * static_cast<double>(n))), 1, n);
    return choose(n, keep, options.keep_seed);
  };
  Outcome<PieceSet> made = cut_pieces(variant.model, options.cut, diffusion, piece_options);
  if (!made && !options.whole_when_missed) return Outcome<CutObject>::none(made.reason());
  if (!made)  // every plane misses this variant: keep it whole
    made = cut_pieces(variant.model, CutSpec{}, diffusion, piece_options);
  CutObject out;
  out.set = std::move(*made);
  out.backend = diffusion.name();
  PieceSet& set = out.set;
  stats.seconds_sections += set.seconds_sections;
  stats.seconds_diffuse += set.seconds_diffuse;
  stats.seconds_clip += set.seconds_clip;
  stats.diffused += set.diffused;
  stats.recut_objects += set.attempts > 1;
  stats.defective_pieces += set.defective_pieces;
  out.pieces_cut = set.pieces_cut;
  const size_t n = set.pieces.size();  // the kept ones
  PieceMaterials object_materials = materials;
  std::vector<std::vector<glm::dvec2>> uv(n);
  // The kept pieces merged before their skins were unwrapped: the layout and the node extras
  // see the pieces as cut (the unwrapped skins only add copies of vertices, which would
  // change nothing but the order in which the layout meets them).
  std::vector<ShadedMesh> as_cut;
  // The skin's patterns, seeded like the Perlin modulation: every piece of the object agrees.
  const SkinPatterns patterns(variant.tmpl.skin_patterns, options.modulation_seed, &variant.model);
  const bool textured = options.cap_colours == CapColours::Texture;
  if (textured) {
    const auto t_bake = Clock::now();
    // Swept skins first: unwrapping adds vertices to the skin parts, which come first.
    const bool swept =
        variant.tmpl.surfaces[static_cast<size_t>(variant.tmpl.skin)].kind == SurfaceKind::Around;
    if (swept)
      for (const Piece& piece : set.pieces) as_cut.push_back(merge_parts(piece));
    const std::vector<std::vector<glm::dvec2>> skin_uv =
        swept ? unwrap_skins(set) : std::vector<std::vector<glm::dvec2>>(n);
    std::vector<const Piece*> pieces;
    for (const Piece& piece : set.pieces) pieces.push_back(&piece);
    const ColourModulation modulation(variant.tmpl.npr, options.modulation_seed);
    object_materials = add_cap_texture(assets, set, pieces, materials, object, &modulation,
                                       options.perlin, options.atlas, uv);
    object_materials =
        add_skin_texture(assets, variant.model.skin(), set, skin_uv, object_materials, object,
                         patterns.empty() ? nullptr : &patterns, &modulation, options.perlin,
                         options.skin, uv);
    stats.seconds_bake += seconds_since(t_bake);
  }
  object_materials =
      add_own_material(assets, set, object_materials, object, PartKind::Stone, "stone");
  object_materials =
      add_own_material(assets, set, object_materials, object, PartKind::Wall, "wall");
  for (size_t q = 0; q < n; ++q) {
    const Piece& piece = set.pieces[q];
    ShadedMesh merged = merge_parts(piece);
    // The skin's patterns at its vertices (the skin part comes first), for vertex colours.
    if (const PiecePart* skin = skin_part(piece);
        skin && !patterns.empty() && merged.param.size() == merged.position.size()) {
      for (size_t v = 0; v < skin->mesh.position.size(); ++v)
        merged.colour[v] = patterns(merged.param[v], merged.position[v], merged.colour[v]);
    }
    // Perlin colour modulation in the object frame: every piece of one object agrees.
    modulate_colours(merged, variant.tmpl.npr, options.perlin, options.modulation_seed);
    out.meshes.push_back(
        piece_mesh(merged, piece, object_materials, object + "_piece" + std::to_string(piece.cell),
                   uv[q], textured ? coarse_caps(piece, set.sections) : std::vector<glm::uvec3>{}));
    out.shapes.push_back(as_cut.empty() ? std::move(merged) : std::move(as_cut[q]));
    out.infos.push_back(
        piece_info(piece, out.shapes.back(), variant.tmpl.name, variant_seed, options.cut));
    out.cap_normals.push_back(largest_cap_normal(piece));
    out.cut_faces.push_back(cut_faces(piece));
  }
  return out;
}

}  // namespace cutaway
