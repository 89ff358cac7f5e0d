#include "scene/scene_builder.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <glm/geometric.hpp>

#include "base/error.h"
#include "base/random.h"
#include "base/timer.h"
#include "io/template_parser.h"
#include "npr/colour_modulation.h"
#include "pieces/coarse_cap.h"
#include "scene/collision_shape.h"
#include "scene/container_mesh.h"
#include "scene/physics_settle.h"
#include "variation/variation.h"

namespace cutaway {

namespace {

using Clock = std::chrono::steady_clock;

/// The default view: from the front (+Z), 50 degrees above the horizon.
const glm::dvec3 kDefaultToCamera(0, std::sin(glm::radians(50.0)), std::cos(glm::radians(50.0)));

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

}  // namespace

uint64_t object_seed(uint64_t scene_seed, int item, int object, int purpose) {
  return derive_seed(scene_seed, {static_cast<uint64_t>(item), static_cast<uint64_t>(object),
                                  static_cast<uint64_t>(purpose)});
}

AssetCamera frame_box(const glm::dvec3& lo, const glm::dvec3& hi, const glm::dvec3& to_camera,
                      double fov_deg, double aspect) {
  AssetCamera cam;
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const glm::dvec3 back = glm::normalize(to_camera);
  glm::dvec3 right = glm::cross(-back, cam.up);
  right = glm::length(right) > 1e-9 ? glm::normalize(right) : glm::dvec3(1, 0, 0);
  const glm::dvec3 up = glm::cross(right, -back);
  const double tan_v = std::tan(0.5 * glm::radians(fov_deg)), tan_h = aspect * tan_v;
  // The distance from the centre at which every corner of the box is in view, with 4 % margin.
  double distance = 1e-3;
  for (int k = 0; k < 8; ++k) {
    const glm::dvec3 c((k & 1 ? hi.x : lo.x) - centre.x, (k & 2 ? hi.y : lo.y) - centre.y,
                       (k & 4 ? hi.z : lo.z) - centre.z);
    const double towards = glm::dot(c, back);
    distance = std::max({distance, towards + std::fabs(glm::dot(c, right)) / tan_h,
                         towards + std::fabs(glm::dot(c, up)) / tan_v});
  }
  distance *= 1.04;
  const double radius = std::max(1e-3, 0.5 * glm::distance(lo, hi));
  cam.target = centre;
  cam.eye = centre + back * distance;
  cam.fov_y_deg = fov_deg;
  cam.aspect = aspect;
  cam.znear = std::max(1e-3, 0.25 * (distance - radius));
  cam.zfar = distance + 4 * radius;
  return cam;
}

AssetCamera scene_camera(const Scene& scene, const glm::dvec3& pile_min,
                         const glm::dvec3& pile_max) {
  const double aspect = static_cast<double>(scene.render.width) / scene.render.height;
  if (!scene.camera) return frame_box(pile_min, pile_max, kDefaultToCamera, 40, aspect);
  AssetCamera cam;
  cam.eye = scene.camera->eye;
  cam.target = scene.camera->target;
  cam.fov_y_deg = scene.camera->fov_deg;
  cam.aspect = aspect;
  const double distance = glm::distance(cam.eye, cam.target);
  const double extent = glm::distance(pile_min, pile_max);
  cam.znear = std::max(1e-4, 0.02 * distance);
  cam.zfar = distance + 4 * extent + 1;
  return cam;
}

std::vector<AssetLight> studio_lights(const AssetCamera& camera) {
  const glm::dvec3 f = glm::normalize(camera.target - camera.eye);
  glm::dvec3 r = glm::cross(f, camera.up);
  r = glm::length(r) > 1e-9 ? glm::normalize(r) : glm::dvec3(1, 0, 0);
  const glm::dvec3 u = glm::normalize(glm::cross(r, f));
  // Directions towards each light; the light travels the other way.
  auto light = [&](const char* name, glm::dvec3 towards, double lux, glm::dvec3 colour) {
    AssetLight l;
    l.name = name;
    l.type = LightType::Directional;
    l.direction = -glm::normalize(towards);
    l.intensity = lux;
    l.colour = colour;
    return l;
  };
  return {light("key", -0.5 * r + 1.0 * u - 0.6 * f, 3.0, {1.0, 0.97, 0.92}),
          light("fill", 0.8 * r + 0.3 * u - 0.5 * f, 1.2, {0.92, 0.95, 1.0}),
          light("rim", 0.2 * r + 0.8 * u + 0.9 * f, 1.0, {1.0, 1.0, 1.0})};
}

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
  return {skin_id, skin_id, skin == cut ? skin_id : index(base + "_cut", cut)};
}

AssetMesh piece_mesh(const ShadedMesh& merged, const Piece& piece, PieceMaterials materials,
                     const std::string& name, const std::vector<glm::dvec2>& uv,
                     const std::vector<glm::uvec3>& coarse_caps) {
  AssetMesh out;
  out.name = name;
  out.position = merged.position;
  out.normal = merged.normal;
  out.colour = merged.colour;
  out.triangle = merged.triangle;
  out.uv = uv;
  const size_t n = merged.triangle.size();
  const size_t surface = surface_triangle_count(piece);
  const PiecePart* skin_surface = skin_part(piece);
  const size_t skin = skin_surface ? skin_surface->mesh.triangle.size() : 0;
  const struct {
    size_t first, count;
    int material;
  } runs[3] = {{0, skin, materials.skin},
               {skin, surface - skin, materials.wall},
               {surface, n - surface, materials.cut}};
  for (const auto& run : runs) {
    if (run.count == 0) continue;
    if (!out.primitives.empty() && out.primitives.back().material == run.material)
      out.primitives.back().count += run.count;
    else
      out.primitives.push_back({run.first, run.count, run.material, {}});
  }
  if (surface < n && out.primitives.back().first == surface)  // the caps alone
    out.primitives.back().coarse = coarse_caps;
  if (out.primitives.size() == 1 && out.primitives[0].material == 0) out.primitives.clear();
  return out;
}

PieceInfo piece_info(const Piece& piece, const ShadedMesh& merged, const std::string& template_name,
                     uint64_t seed, const CutSpec& cut) {
  PieceInfo info{template_name, seed, cut_label(cut), piece.cell, {}, signed_volume(merged)};
  for (const PiecePart& part : piece.parts) {
    const std::string kind = part.kind == PartKind::Skin   ? "skin"
                             : part.kind == PartKind::Wall ? "wall"
                                                           : "cap";
    if (std::find(info.parts.begin(), info.parts.end(), kind) == info.parts.end())
      info.parts.push_back(kind);
  }
  return info;
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
    assets.textures.push_back(
        {object + "_cut_material", atlas.material_width, atlas.material_height, 4,
         std::move(atlas.material)});
    cut.material_texture = static_cast<int>(assets.textures.size()) - 1;
  }
  assets.textures.push_back({object + "_cut", atlas.width, atlas.height, 3, std::move(atlas.srgb)});
  cut.base_colour_texture = static_cast<int>(assets.textures.size()) - 1;
  assets.materials.push_back(cut);
  materials.cut = static_cast<int>(assets.materials.size()) - 1;
  return materials;
}

std::vector<std::vector<glm::dvec2>> unwrap_skins(PieceSet& set, const std::vector<size_t>& kept) {
  std::vector<std::vector<glm::dvec2>> uv;
  for (size_t k : kept) {
    Piece& piece = set.pieces[k];
    uv.push_back(skin_part(piece) ? unwrap_skin(piece.parts[0].mesh) : std::vector<glm::dvec2>{});
  }
  return uv;
}

PieceMaterials add_skin_texture(SceneAssets& assets, const DsSurface& skin, const PieceSet& set,
                                const std::vector<size_t>& kept,
                                const std::vector<std::vector<glm::dvec2>>& skin_uv,
                                PieceMaterials materials, const std::string& object,
                                const ColourModulation* modulation, double strength,
                                const SkinTextureOptions& options,
                                std::vector<std::vector<glm::dvec2>>& uv) {
  std::vector<const ShadedMesh*> parts;
  std::vector<const std::vector<glm::dvec2>*> part_uv;
  for (size_t q = 0; q < kept.size(); ++q) {
    if (skin_uv[q].empty()) continue;
    const Piece& piece = set.pieces[kept[q]];
    parts.push_back(&skin_part(piece)->mesh);
    part_uv.push_back(&skin_uv[q]);
    uv[q].resize(part_vertex_offsets(piece).back(), glm::dvec2(0.0));
    std::copy(skin_uv[q].begin(), skin_uv[q].end(), uv[q].begin());  // the skin comes first
  }
  if (parts.empty()) return materials;
  const glm::ivec2 size = skin_texture_size(skin, options);
  assets.textures.push_back({object + "_skin", size.x, size.y, 3,
                             bake_skin_texture(parts, part_uv, size, modulation, strength, options),
                             true});
  AssetMaterial textured = assets.materials[static_cast<size_t>(materials.skin)];
  textured.name = object + "_skin";
  textured.base_colour_texture = static_cast<int>(assets.textures.size()) - 1;
  assets.materials.push_back(textured);
  materials.skin = static_cast<int>(assets.materials.size()) - 1;
  return materials;
}

/// The number of distinct cut planes among the piece's caps (normals apart by over 2.5 degrees).
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

CutObject cut_scene_object(SceneAssets& assets, const Variant& variant, uint64_t variant_seed,
                           const PieceMaterials& materials, const std::string& object,
                           const ObjectCutOptions& cut, const SceneBuildOptions& options,
                           SceneStats& st) {
  if (!options.diffusion) throw InternalError("cut_scene_object: no diffusion backend");
  auto t0 = Clock::now();
  const auto diffusion = options.diffusion(variant.model);
  st.seconds_backend += seconds_since(t0);
  PieceOptions piece_options;
  piece_options.section.edge_m = variant.tmpl.edge_m;
  piece_options.section.sampling = options.sampling;
  Outcome<PieceSet> made = cut_pieces(variant.model, cut.cut, *diffusion, piece_options);
  if (!made)  // every plane misses this variant: keep it whole
    made = cut_pieces(variant.model, CutSpec{}, *diffusion, piece_options);
  CutObject out;
  out.set = std::move(*made);
  PieceSet& set = out.set;
  st.seconds_sections += set.seconds_sections;
  st.seconds_diffuse += set.seconds_diffuse;
  st.seconds_clip += set.seconds_clip;
  st.diffused_points += set.diffused_points;
  st.recut_objects += set.attempts > 1;
  st.defective_pieces += set.defective_pieces;
  const size_t n = set.pieces.size();
  const size_t keep = std::clamp<size_t>(
      static_cast<size_t>(std::llround(cut.keep * static_cast<double>(n))), 1, n);
  out.kept = choose(n, keep, cut.keep_seed);
  const std::vector<size_t>& kept = out.kept;
  PieceMaterials object_materials = materials;
  std::vector<std::vector<glm::dvec2>> uv(kept.size());
  // The kept pieces merged before their skins were unwrapped: the layout and the node extras
  // see the pieces as cut (the unwrapped skins only add copies of vertices, which would
  // change nothing but the order in which the layout meets them).
  std::vector<ShadedMesh> as_cut;
  if (options.cap_colours == CapColours::Texture) {
    const auto t_bake = Clock::now();
    // Swept skins first: unwrapping adds vertices to the skin parts, which come first.
    const bool swept = variant.tmpl.surfaces[static_cast<size_t>(variant.tmpl.skin)].kind ==
                       SurfaceKind::Around;
    if (swept)
      for (size_t k : kept) as_cut.push_back(merge_parts(set.pieces[k]));
    const std::vector<std::vector<glm::dvec2>> skin_uv =
        swept ? unwrap_skins(set, kept) : std::vector<std::vector<glm::dvec2>>(kept.size());
    std::vector<const Piece*> kept_pieces;
    for (size_t k : kept) kept_pieces.push_back(&set.pieces[k]);
    const ColourModulation modulation(variant.tmpl.npr, cut.modulation_seed);
    object_materials = add_cap_texture(assets, set, kept_pieces, materials, object, &modulation,
                                       cut.perlin, cut.atlas, uv);
    object_materials =
        add_skin_texture(assets, variant.model.skin(), set, kept, skin_uv, object_materials,
                         object, &modulation, cut.perlin, options.skin, uv);
    st.seconds_bake += seconds_since(t_bake);
  }
  for (size_t q = 0; q < kept.size(); ++q) {
    const Piece& piece = set.pieces[kept[q]];
    ShadedMesh merged = merge_parts(piece);
    // Perlin colour modulation in the object frame: every piece of one object agrees.
    modulate_colours(merged, variant.tmpl.npr, cut.perlin, cut.modulation_seed);
    out.meshes.push_back(piece_mesh(merged, piece, object_materials,
                                    object + "_piece" + std::to_string(piece.cell), uv[q],
                                    options.cap_colours == CapColours::Texture
                                        ? coarse_caps(piece, set.sections)
                                        : std::vector<glm::uvec3>{}));
    out.shapes.push_back(as_cut.empty() ? std::move(merged) : std::move(as_cut[q]));
    out.infos.push_back(
        piece_info(piece, out.shapes.back(), variant.tmpl.name, variant_seed, cut.cut));
  }
  return out;
}

SceneAssets build_scene(const Scene& scene, uint64_t seed, const SceneBuildOptions& options,
                        SceneStats* stats) {
  if (!options.diffusion) throw InternalError("build_scene: no diffusion backend");
  SceneStats local;
  SceneStats& st = stats ? *stats : local;
  st = SceneStats{};
  int total = 0;
  for (const SceneItem& item : scene.items) total += item.count;

  SceneAssets assets;
  std::vector<ShadedMesh> shapes;  // kept pieces, object frame
  std::vector<AssetMesh> meshes;   // of each shape: as exported, once placed
  std::vector<LayoutPiece> arranged;  // of each shape: cap, arrangement, row (mesh set below)
  std::vector<double> densities;      // of each shape, kg/m^3
  std::vector<PieceInfo> infos;
  for (size_t i = 0; i < scene.items.size(); ++i) {
    const SceneItem& item = scene.items[i];
    Template tmpl = load_template(item.template_path);
    tmpl.variation_amount *= item.variation;
    const PieceMaterials item_materials =
        add_piece_materials(assets, tmpl.name, tmpl.skin_material, tmpl.cut_material);
    for (int j = 0; j < item.count; ++j) {
      const int ii = static_cast<int>(i);
      const auto t0 = Clock::now();
      const uint64_t variant_seed = object_seed(seed, ii, j, 1);
      const Variant variant = make_variant(tmpl, variant_seed);
      st.seconds_variants += seconds_since(t0);
      ObjectCutOptions cut;
      cut.cut = item.cut;
      cut.keep = item.keep;
      cut.keep_seed = object_seed(seed, ii, j, 2);
      cut.modulation_seed = object_seed(seed, ii, j, 3);
      cut.perlin = scene.render.perlin;
      cut.atlas = options.atlas;
      if (cut.atlas.texels_per_m == 0) cut.atlas.texels_per_m = 1000 * scene.render.texels_per_mm;
      const std::string object =
          "i" + std::to_string(i) + "_" + asset_name(tmpl.name) + "_" + std::to_string(j);
      CutObject made = cut_scene_object(assets, variant, variant_seed, item_materials, object,
                                        cut, options, st);
      for (size_t q = 0; q < made.kept.size(); ++q) {
        const Piece& piece = made.set.pieces[made.kept[q]];
        meshes.push_back(std::move(made.meshes[q]));
        shapes.push_back(std::move(made.shapes[q]));
        arranged.push_back({nullptr, largest_cap_normal(piece), item.arrange, st.objects,
                            piece.cell, cut_faces(piece)});
        densities.push_back(tmpl.density_kg_m3);
        infos.push_back(std::move(made.infos[q]));
      }
      ++st.objects;
      if (options.progress)
        options.progress(st.objects, total,
                         tmpl.name + " " + std::to_string(j + 1) + "/" +
                             std::to_string(item.count) + ": " + std::to_string(made.kept.size()) +
                             " of " + std::to_string(made.set.pieces.size()) + " pieces");
    }
  }
  st.pieces = static_cast<int>(shapes.size());

  // Placement, in a seeded order so that the kinds mix.
  const auto t0 = Clock::now();
  std::vector<size_t> order(shapes.size());
  std::iota(order.begin(), order.end(), size_t{0});
  {
    Rng rng(derive_seed(seed, {~0ull, 3}));
    for (size_t k = order.size(); k > 1; --k)
      std::swap(order[k - 1], order[rng.below(static_cast<uint32_t>(k))]);
  }
  std::vector<LayoutPiece> layout;
  for (size_t k : order) {
    layout.push_back(arranged[k]);
    layout.back().mesh = &shapes[k];
  }
  LayoutOptions layout_options = options.layout;
  layout_options.to_camera =
      scene.camera ? glm::normalize(scene.camera->eye - scene.camera->target) : kDefaultToCamera;
  const std::vector<Placement> drops =
      layout_pieces(layout, scene.container, layout_options, derive_seed(seed, {~0ull, 4}));
  st.seconds_layout = seconds_since(t0);

  // Settling: rigid bodies dropped from the layout's poses.
  const auto t_physics = Clock::now();
  std::vector<CollisionShape> collision(order.size());
  std::vector<SettleBody> bodies(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    if (!drops[k].placed) continue;
    collision[k] = collision_shape(shapes[order[k]], options.collision);
    st.decomposed_pieces += collision[k].decomposed;
    bodies[k] = {&collision[k], densities[order[k]], drops[k]};
  }
  const SettleResult settled = settle_pieces(bodies, scene.container, options.settle);
  const std::vector<Placement>& placements = settled.placements;
  st.seconds_physics = seconds_since(t_physics);
  st.simulated_seconds = settled.simulated_s;
  st.settled = settled.all_asleep;
  st.redropped = settled.redrops;
  st.lost = settled.lost;
  st.stability_motion_m = settled.stability_motion_m;
  st.stability_checks = settled.verify_rounds;

  assets.name = scene.name;
  assets.width = scene.render.width;
  assets.height = scene.render.height;
  assets.background = {0.72, 0.72, 0.74};
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  if (auto container = container_mesh(scene.container)) {
    for (const glm::dvec3& p : container->position) {
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    assets.instances.push_back({container->name, 0, {1, 0, 0, 0}, {0, 0, 0}, {}});
    assets.meshes.push_back(std::move(*container));
  }
  for (size_t k = 0; k < order.size(); ++k) {
    const Placement& place = placements[k];
    if (!place.placed) continue;
    const size_t s = order[k];
    for (const glm::dvec3& p : shapes[s].position) {
      const glm::dvec3 q = place.translation + place.rotation * p;
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
    st.triangles += meshes[s].triangle.size();
    assets.instances.push_back({meshes[s].name, static_cast<int>(assets.meshes.size()),
                                place.rotation, place.translation, infos[s]});
    assets.meshes.push_back(std::move(meshes[s]));
    ++st.placed;
  }
  if (assets.instances.empty()) lo = hi = glm::dvec3(0.0);
  assets.camera = scene_camera(scene, lo, hi);
  assets.lights = studio_lights(assets.camera);
  return assets;
}

}  // namespace cutaway
