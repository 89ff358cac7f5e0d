#include "export/pov_export.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <map>
#include <stdexcept>
#include <span>
#include <string_view>
#include <system_error>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/trigonometric.hpp>

#include "base/atomic_file.h"
#include "base/constants.h"
#include "base/error.h"
#include "base/finite.h"
#include "export/texture_image.h"

namespace cutaway {

namespace {

constexpr double kPointFadeDistance_m = 0.01;  // POV-Ray fade_distance of point lights
constexpr size_t kMaxIdentifier = 40;          // POV-Ray's identifier length limit

// Appends `v` with 6 significant digits (the text of "%.6g"), independent of the C locale.
void append_number(std::string& out, double v, int digits = 6) {
  if (v == 0) v = 0;  // -0 -> 0
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, digits);
  out.append(buf, r.ptr);
}

/// A mesh2 list item: `<x,y,z>` with `digits` significant digits, no spaces.
void append_mesh_vector(std::string& out, const glm::dvec3& v, int digits) {
  out += '<';
  for (int k = 0; k < 3; ++k) {
    if (k) out += ',';
    append_number(out, v[k], digits);
  }
  out += '>';
}

void append_vector(std::string& out, const glm::dvec3& v) {
  out += '<';
  append_number(out, v.x);
  out += ", ";
  append_number(out, v.y);
  out += ", ";
  append_number(out, v.z);
  out += '>';
}

/// `v` as POV-Ray reads it back from append_vector's text (6 significant digits).
glm::dvec3 written(const glm::dvec3& v) {
  glm::dvec3 out;
  for (int k = 0; k < 3; ++k) {
    std::string text;
    append_number(text, v[k]);
    std::from_chars(text.data(), text.data() + text.size(), out[k]);
  }
  return out;
}

std::string vector_text(const glm::dvec3& v) {
  std::string s;
  append_vector(s, v);
  return s;
}

std::string mesh_identifier(size_t k, const std::string& name) {
  std::string id = "Mesh_" + std::to_string(k) + "_" + asset_name(name);
  if (id.size() > kMaxIdentifier) id.resize(kMaxIdentifier);
  return id;
}

void require(bool ok, const std::string& what) {
  if (!ok) throw InternalError("POV-Ray export: " + what);
}

// Shading normals that POV-Ray accepts: a zero or non-finite normal becomes the area-weighted
// normal of the vertex's triangles, or +Y when those have no area either.
std::vector<glm::dvec3> usable_normals(const AssetMesh& m) {
  std::vector<glm::dvec3> n(m.normal.size());
  std::vector<glm::dvec3> face_sum;  // computed only when needed
  for (size_t i = 0; i < n.size(); ++i) {
    const glm::dvec3 v = m.normal[i];
    const double len = all_finite(v) ? glm::length(v) : 0.0;
    if (len > 1e-12 && std::isfinite(len)) {
      n[i] = v / len;
      continue;
    }
    if (face_sum.empty()) {
      face_sum.assign(m.position.size(), glm::dvec3(0.0));
      for (const auto& t : m.triangle) {
        const glm::dvec3 a =
            glm::cross(m.position[t.y] - m.position[t.x], m.position[t.z] - m.position[t.x]);
        face_sum[t.x] += a;
        face_sum[t.y] += a;
        face_sum[t.z] += a;
      }
    }
    const double fl = glm::length(face_sum[i]);
    n[i] = fl > 1e-300 && std::isfinite(fl) ? face_sum[i] / fl : glm::dvec3(0, 1, 0);
  }
  return n;
}

void write_camera(std::string& out, const AssetCamera& c) {
  const auto [forward, right, up] = camera_frame(c);
  const double tan_half = std::tan(c.fov_y_deg * kPi / 360.0);

  out += "// Camera: eye ";
  append_vector(out, c.eye);
  out += ", target ";
  append_vector(out, c.target);
  out += ", up ";
  append_vector(out, c.up);
  out += ", vertical fov ";
  append_number(out, c.fov_y_deg);
  out += " deg, aspect ";
  append_number(out, c.aspect);
  out += ".\n// Explicit vectors instead of look_at: rays go along direction + u*right + v*up, so\n"
         "// the image matches the OpenGL/glTF view (POV-Ray's handedness does not enter).\n";
  out += "camera {\n  perspective\n  location ";
  append_vector(out, c.eye);
  out += "\n  direction ";
  append_vector(out, forward * (0.5 / tan_half));
  out += "\n  right ";
  append_vector(out, right * c.aspect);
  out += "\n  up ";
  append_vector(out, up);
  out += "\n}\n\n";
}

/// A round area light `diameter` metres across, facing along `dir` (unit): soft shadows as a
/// source of that apparent size gives (9 x 9 samples, refined adaptively; no jitter, so the
/// same scene renders to the same pixels).
void write_area(std::string& out, const glm::dvec3& dir, double diameter) {
  const glm::dvec3 side = glm::normalize(glm::cross(dir, stable_camera_up(dir)));
  const glm::dvec3 other = glm::cross(side, dir);
  out += "\n  area_light ";
  append_vector(out, side * diameter);
  out += ", ";
  append_vector(out, other * diameter);
  out += ", 9, 9\n  adaptive 1\n  circular\n  orient";
}

void write_lights(std::string& out, const SceneAssets& a) {
  BoundingSphere b = shadow_casters_bounds(a);
  if (b.radius == 0) b.radius = 1;
  // Only one light casts shadows: the others fill them in instead of leaving them black.
  const auto shadow_caster = static_cast<size_t>(shadow_casting_light(a));
  for (size_t i = 0; i < a.lights.size(); ++i) {
    const AssetLight& l = a.lights[i];
    out += "// Light " + std::to_string(i) + ": " + asset_name(l.name);
    if (l.type == LightType::Directional) {
      const glm::dvec3 dir = glm::normalize(l.direction);
      const double far_m = 10 * b.radius + 10;
      out += ", directional, ";
      append_number(out, l.intensity);
      out += " lux\nlight_source {\n  ";
      append_vector(out, b.centre - dir * far_m);
      out += "\n  color rgb ";
      append_vector(out, l.colour * (l.intensity / kLumensPerWatt / kPi));
      out += "\n  parallel\n  point_at ";
      append_vector(out, b.centre);
      if (i != shadow_caster) out += "\n  shadowless";
      else if (l.angle_deg > 0)
        write_area(out, dir, 2 * far_m * std::tan(glm::radians(0.5 * l.angle_deg)));
      out += "\n}\n\n";
    } else {
      out += ", point, ";
      append_number(out, l.intensity);
      out += " cd\nlight_source {\n  ";
      append_vector(out, l.position);
      out += "\n  color rgb ";
      append_vector(out, l.colour * (l.intensity / kLumensPerWatt /
                                     (2 * kPi * kPointFadeDistance_m * kPointFadeDistance_m)));
      out += "\n  fade_distance ";
      append_number(out, kPointFadeDistance_m);
      out += "\n  fade_power 2";
      if (i != shadow_caster) out += "\n  shadowless";
      out += "\n}\n\n";
    }
  }
}

/// The POV-Ray finish identifier of material k: Cutaway_Finish for material 0, the scene's
/// plain one, and Cutaway_Finish_<k> for the others.
std::string finish_identifier(size_t k) {
  return k == 0 ? "Cutaway_Finish" : "Cutaway_Finish_" + std::to_string(k);
}

/// `#declare` of the finish of `material` (scene_to_pov documents the mapping).
void write_finish(std::string& out, const PbrMaterial& pbr, size_t k) {
  out += "#declare " + finish_identifier(k) + " = finish { ambient 1 diffuse 1";
  if (pbr.translucency > 0) {  // POV-Ray 3.7's backside illumination
    out += ", ";
    append_number(out, pbr.translucency);
  }
  out += " specular ";
  append_number(out, 0.625 * (1 - pbr.roughness));
  out += " roughness ";
  append_number(out, 0.0005 + 0.05 * pbr.roughness * pbr.roughness);
  if (pbr.clearcoat > 0) {
    // A phong highlight keeps its peak as it widens, where glTF's normalised lobe (the preview,
    // Blender) spreads the same reflected light thinner: up to roughness 0.1 the peak is the
    // key's disc itself, beyond it the peak falls about as (0.15 / (roughness + 0.05))^1.5 (the
    // preview's coat under the key at 0.2, 0.25 and 0.45: 0.64, 0.48 and 0.14 of its peak at
    // 0.1; this gives 0.46, 0.35 and 0.16). Without the fall a soft film veiled a small dark
    // cut face in pale light (a cherry's).
    const double spread = std::min(1.0, std::pow(0.15 / (pbr.clearcoat_roughness + 0.05), 1.5));
    out += " phong ";
    append_number(out, 0.6 * pbr.clearcoat * spread);
    out += " phong_size ";
    append_number(out, std::round(4 / (pbr.clearcoat_roughness + 0.05)));
  }
  out += " }\n";
}

/// The image file of material `material` when it is textured, has a file and the mesh has
/// uv; else empty (the faces keep their vertex colours).
std::string image_of(const SceneAssets& a, const AssetMesh& m, int material,
                     const std::vector<std::string>& texture_files) {
  const int t = a.materials[static_cast<size_t>(material)].base_colour_texture;
  if (t < 0 || m.uv.empty() || static_cast<size_t>(t) >= texture_files.size()) return "";
  return texture_files[static_cast<size_t>(t)];
}

/// The POV-Ray normal block of material `material`'s relief when it has a height map with a
/// file (a bump_map under the texture's uv_mapping, its bump_size the material's height_bump:
/// one full grey step per texel tilts the normal by that slope); else empty.
std::string relief_of(const SceneAssets& a, int material,
                      const std::vector<std::string>& texture_files) {
  const AssetMaterial& m = a.materials[static_cast<size_t>(material)];
  const int t = m.height_texture;
  if (t < 0 || static_cast<size_t>(t) >= texture_files.size()) return "";
  std::string out = " normal { bump_map { png \"" + texture_files[static_cast<size_t>(t)] +
                    "\" interpolate 2 bump_size ";
  append_number(out, m.height_bump);
  return out + " } }";
}

void write_mesh(std::string& out, const SceneAssets& a, const AssetMesh& m, const std::string& id,
                size_t k, const std::vector<std::string>& texture_files) {
  // The faces with their materials and images: a textured primitive's coarse triangles where
  // it has them and its image is written (its colour is in the texture), else the mesh's own.
  std::vector<glm::uvec3> faces;
  std::vector<int> face_material;
  std::vector<std::string> images;  // per primitive; empty: vertex colours
  std::vector<size_t> face_primitive;
  const std::vector<AssetPrimitive> plain{{0, m.triangle.size(), 0, {}}};
  for (const AssetPrimitive& p : m.primitives.empty() ? plain : m.primitives) {
    const std::string& image = images.emplace_back(image_of(a, m, p.material, texture_files));
    const std::span<const glm::uvec3> drawn = primitive_triangles(m, p, !image.empty());
    faces.insert(faces.end(), drawn.begin(), drawn.end());
    face_material.resize(faces.size(), p.material);
    face_primitive.resize(faces.size(), images.size() - 1);
  }
  auto face_image = [&](size_t f) -> const std::string& { return images[face_primitive[f]]; };
  // The distinct textures by their written text: first a (colour, finish) pair per vertex in
  // vertex order (the finish of the first vertex-coloured face using it; in a mesh without
  // textured faces, material 0 for an unused vertex: so a mesh of one plain material is written
  // as before materials), then in
  // order of first use the pairs of other corners and one uv-mapped image per textured face.
  std::map<std::string, size_t> texture_index;
  std::vector<std::string> colours;
  auto index_of = [&](std::string text) {
    const auto [it, inserted] = texture_index.emplace(text, colours.size());
    if (inserted) colours.push_back(std::move(text));
    return static_cast<unsigned>(it->second);
  };
  auto pair_of = [&](unsigned vertex, int material) {
    return index_of("texture { pigment { rgb " + vector_text(m.colour[vertex]) + " } finish { " +
                    finish_identifier(static_cast<size_t>(material)) + " } }");
  };
  std::vector<int> vertex_material(m.position.size(), -1);
  bool any_image = false;
  for (size_t f = 0; f < faces.size(); ++f) {
    any_image = any_image || !face_image(f).empty();
    for (int c = 0; c < 3 && face_image(f).empty(); ++c)
      if (vertex_material[faces[f][c]] < 0) vertex_material[faces[f][c]] = face_material[f];
  }
  for (unsigned v = 0; v < m.position.size(); ++v)
    if (vertex_material[v] >= 0 || !any_image) pair_of(v, std::max(vertex_material[v], 0));
  std::vector<glm::uvec3> face_textures(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    if (!face_image(f).empty()) {
      face_textures[f].x = index_of(
          "texture { uv_mapping pigment { image_map { " +
          std::string(face_image(f).ends_with(".jpg") ? "jpeg" : "png") + " \"" + face_image(f) +
          "\" interpolate 2 } }" + relief_of(a, face_material[f], texture_files) + " finish { " +
          finish_identifier(static_cast<size_t>(face_material[f])) + " } }");
      continue;
    }
    for (int c = 0; c < 3; ++c) face_textures[f][c] = pair_of(faces[f][c], face_material[f]);
  }

  out += "// Mesh " + std::to_string(k) + ": " + asset_name(m.name) + " (" +
         std::to_string(m.position.size()) + " vertices, " + std::to_string(faces.size()) +
         " triangles, distinct colours: " + std::to_string(colours.size()) + ")\n";
  // The lists one item per line without indentation (a big scene's .pov is mostly these):
  // positions with 6 significant digits (a micrometre on a 10 cm fruit), normals with 4, uv with
  // 5 (a tenth of a texel of a 2048-texel texture).
  out += "#declare " + id + " = mesh2 {\n  vertex_vectors {\n" + std::to_string(m.position.size());
  for (const auto& p : m.position) {
    out += ",\n";
    append_mesh_vector(out, p, 6);
  }
  out += "\n  }\n";
  if (!m.normal.empty()) {
    out += "  normal_vectors {\n" + std::to_string(m.normal.size());
    for (const auto& n : usable_normals(m)) {
      out += ",\n";
      append_mesh_vector(out, n, 4);
    }
    out += "\n  }\n";
  }
  if (any_image) {  // POV-Ray's image v runs up from the bottom row, glTF's down from the top
    out += "  uv_vectors {\n" + std::to_string(m.uv.size());
    for (const glm::dvec2& q : m.uv) {
      out += ",\n<";
      append_number(out, q.x, 5);
      out += ',';
      append_number(out, 1 - q.y, 5);
      out += '>';
    }
    out += "\n  }\n";
  }
  out += "  texture_list {\n    " + std::to_string(colours.size());
  for (const auto& c : colours) out += ",\n    " + c;
  // uv_indices are left out: POV-Ray then takes the face_indices, which they would repeat.
  out += "\n  }\n  face_indices {\n" + std::to_string(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    const glm::uvec3 t = faces[f], x = face_textures[f];
    out += ",\n<" + std::to_string(t.x) + ',' + std::to_string(t.y) + ',' + std::to_string(t.z) +
           ">," + std::to_string(x.x);
    if (face_image(f).empty()) out += ',' + std::to_string(x.y) + ',' + std::to_string(x.z);
  }
  out += "\n  }\n}\n\n";
}

void write_instance(std::string& out, const AssetInstance& inst, const std::string& id, size_t i) {
  const glm::dquat q = inst.rotation;
  const double qlen = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
  // glm matrices are column-major: r[c] is the image of the c-th basis vector, which is the
  // c-th row of POV-Ray's matrix (it maps row vectors: p' = p * M).
  const glm::dmat3 r = glm::mat3_cast(q / qlen);
  out += "// Instance " + std::to_string(i) + ": " + asset_name(inst.name) + "\nobject {\n  " + id +
         "\n  matrix <";
  for (int c = 0; c < 3; ++c) {
    for (int row = 0; row < 3; ++row) {
      const double v = r[c][row];
      append_number(out, std::abs(v) < 1e-12 ? 0.0 : v);  // exact zeros, not 6e-17
      out += ", ";
    }
  }
  append_number(out, inst.translation.x);
  out += ", ";
  append_number(out, inst.translation.y);
  out += ", ";
  append_number(out, inst.translation.z);
  out += ">";
  if (inst.backdrop) out += "\n  no_shadow";  // staging: the lights stand inside it
  out += "\n}\n\n";
}

/// The strokes as tubes (spheres joined by cones): widths in pixels of an image assets.height
/// pixels high become radii at each point's depth along the camera's view direction, and every
/// point moves toward the eye by its radius so that the tube stays in front of the surface it
/// outlines.
void write_strokes(std::string& out, const SceneAssets& a, const std::vector<Stroke>& strokes) {
  const AssetCamera& c = a.camera;
  const glm::dvec3 forward = glm::normalize(c.target - c.eye);
  const double metres_per_pixel_per_depth =
      2 * std::tan(c.fov_y_deg * kPi / 360) / std::max(1, a.height);
  out += "// Silhouette strokes (Northrup and Markosian 2000): spheres joined by cones.\n";
  out += "#declare Cutaway_Stroke_Finish = finish { emission 1 ambient 0 diffuse 0 specular 0 "
         "}\n\n";
  for (size_t s = 0; s < strokes.size(); ++s) {
    const Stroke& stroke = strokes[s];
    require(stroke.width_px.size() == stroke.points.size(),
            "stroke " + std::to_string(s) + ": widths and points differ in number");
    std::vector<glm::dvec3> centres;
    std::vector<double> radii;
    const size_t n = stroke.points.size();
    for (size_t k = 0; k <= n; ++k) {
      if (k == n && !stroke.closed) break;
      const glm::dvec3& p = stroke.points[k % n];
      require(all_finite(p) && std::isfinite(stroke.width_px[k % n]),
              "stroke " + std::to_string(s) + ": non-finite point or width");
      const double depth = glm::dot(p - c.eye, forward);
      if (!(depth > 0)) continue;
      const double r =
          std::max(1e-6, 0.5 * stroke.width_px[k % n] * depth * metres_per_pixel_per_depth);
      // As written: two points whose text is the same would make a cone of zero length, which
      // POV-Ray refuses ("Degenerate cone/cylinder", a fatal parse error).
      const glm::dvec3 q = written(p + r * glm::normalize(c.eye - p));
      if (!centres.empty() && q == centres.back()) continue;
      centres.push_back(q);
      radii.push_back(r);
    }
    if (centres.size() < 2) continue;
    // A sphere at every point and a cone between neighbours: the same tube as a linear
    // sphere_sweep, but POV-Ray's sphere_sweep shows spikes on such thin strokes.
    out += "union {\n";
    for (size_t k = 0; k < centres.size(); ++k) {
      out += "  sphere { ";
      append_vector(out, centres[k]);
      out += ", ";
      append_number(out, radii[k]);
      out += " }\n";
      if (k + 1 == centres.size()) break;
      out += "  cone { ";
      append_vector(out, centres[k]);
      out += ", ";
      append_number(out, radii[k]);
      out += ", ";
      append_vector(out, centres[k + 1]);
      out += ", ";
      append_number(out, radii[k + 1]);
      out += " }\n";
    }
    out += "  pigment { rgb ";
    append_vector(out, stroke.colour);
    out += " } finish { Cutaway_Stroke_Finish } no_shadow }\n";
  }
}

}  // namespace

std::string scene_to_pov(const SceneAssets& assets, const std::vector<Stroke>* strokes,
                         const std::vector<std::string>& texture_files) {
  // POV-Ray replaces zero shading normals (usable_normals).
  require_valid_assets(assets, {.normals_repaired = true}, "POV-Ray export");

  std::string out;
  out += "// " + asset_name(assets.name) + ": a scene written by cutaway (POV-Ray 3.7).\n";
  out += "// Units: metres, +Y up. Colours: linear RGB (assumed_gamma 1.0).\n";
  out += "// Render: povray +I<this file> +FN +W" + std::to_string(assets.width) + " +H" +
         std::to_string(assets.height) + " +A0.3 File_Gamma=sRGB\n\n";
  // The sky as POV-Ray's ambient light: the radiance ambient_lux / (683 pi) that a uniform sky
  // of ambient_lux gives a white face, as Blender's world does (finishes: ambient 1).
  out += "#version 3.7;\n\nglobal_settings { assumed_gamma 1.0 ambient_light rgb ";
  const double sky = assets.ambient_lux / (kLumensPerWatt * kPi);
  append_vector(out, glm::dvec3(sky));
  out += " }\n\n";
  out += "background { rgb ";
  append_vector(out, assets.background);
  out += " }\n\n";
  write_camera(out, assets.camera);
  write_lights(out, assets);
  // Material 0 keeps the finish of scenes written before materials: a small, sharp highlight.
  out += "#declare Cutaway_Finish = finish { ambient 1 diffuse 1 specular 0.25 "
         "roughness 0.02 }\n";
  for (size_t k = 1; k < assets.materials.size(); ++k)
    write_finish(out, assets.materials[k].pbr, k);
  out += "\n";

  std::vector<std::string> ids(assets.meshes.size());
  for (size_t k = 0; k < assets.meshes.size(); ++k) {
    if (assets.meshes[k].triangle.empty()) continue;  // POV-Ray refuses empty meshes
    ids[k] = mesh_identifier(k, assets.meshes[k].name);
    write_mesh(out, assets, assets.meshes[k], ids[k], k, texture_files);
  }
  for (size_t i = 0; i < assets.instances.size(); ++i) {
    const auto& id = ids[static_cast<size_t>(assets.instances[i].mesh)];
    if (!id.empty()) write_instance(out, assets.instances[i], id, i);
  }
  if (strokes != nullptr && !strokes->empty()) {
    out += "\n";
    write_strokes(out, assets, *strokes);
  }
  return out;
}

void write_scene_pov(const std::filesystem::path& path, const SceneAssets& assets,
                     const std::vector<Stroke>* strokes, std::optional<TextureFormat> textures) {
  std::vector<std::string> files;
  if (textures) {
    textures = image_file_format(*textures);
    files = texture_file_names(path, assets, *textures);
    for (size_t t = 0; t < files.size(); ++t)
      write_file_atomically(path.parent_path() / files[t],
                            encode_texture(assets.textures[t], *textures));
  }
  write_file_atomically(path, scene_to_pov(assets, strokes, files));
}

}  // namespace cutaway
