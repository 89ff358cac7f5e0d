#include "export/gltf_export.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/parallel_for.h>
#include <tiny_gltf.h>
#include <unistd.h>

#include "base/atomic_file.h"
#include "base/error.h"
#include "export/gltf_buffers.h"
#include "export/gltf_materials.h"
#include "export/gltf_meshes.h"
#include "export/ktx2_texture.h"
#include "export/texture_image.h"

namespace cutaway {

namespace {

using namespace gltf;  // the export's parts: buffers, meshes, materials

/// An empty glTF 2.0 model with one (empty) buffer and scene 0 as the default.
tinygltf::Model new_model() {
  tinygltf::Model m;
  m.asset.version = "2.0";
  m.asset.generator = "cutaway";
  m.buffers.emplace_back();
  m.defaultScene = 0;
  return m;
}

/// The model as .glb bytes.
std::string to_glb(tinygltf::Model& m) {
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  writer.WriteGltfSceneToStream(&m, out, false, true);
  return out.str();
}

// ---- scenes -------------------------------------------------------------------------------

/// The unit quaternion turning a node so that its local -Z points along `forward` and its +Y
/// lies in the plane of `forward` and `up` (towards `up`). When `up` is (nearly) parallel to
/// `forward`, +Y of the scene is tried next, then -Z of the scene. Returned with w >= 0.
glm::dquat look_rotation(glm::dvec3 forward, glm::dvec3 up) {
  const glm::dvec3 f = glm::normalize(forward);
  glm::dvec3 right(0.0);
  for (const glm::dvec3& u : {up, glm::dvec3(0, 1, 0), glm::dvec3(0, 0, -1)}) {
    const glm::dvec3 r = glm::cross(f, u);
    if (glm::length(r) > 1e-9 * std::max(1.0, glm::length(u))) {
      right = glm::normalize(r);
      break;
    }
  }
  const glm::dvec3 true_up = glm::cross(right, f);
  const glm::dmat3 worldFromNode(right, true_up, -f);  // columns: the node's +X, +Y, +Z
  glm::dquat q = glm::normalize(glm::quat_cast(worldFromNode));
  if (q.w < 0) q = -q;
  return q;
}

/// glTF's [x, y, z, w] order of a glm quaternion (+ 0.0 turns -0 into 0 in the JSON).
std::vector<double> gltf_rotation(const glm::dquat& q) {
  return {q.x + 0.0, q.y + 0.0, q.z + 0.0, q.w + 0.0};
}

std::vector<double> gltf_vec3(const glm::dvec3& v) { return {v.x + 0.0, v.y + 0.0, v.z + 0.0}; }

/// What glTF tolerates beyond the rules of check_assets: zero normals (written as +Y), a
/// camera without `up` (its look rotation does not use it); and what it needs: triangles in
/// every mesh, uv wherever a material is textured.
constexpr AssetRules kGltfRules{.camera_needs_up = false,
                                .normals_repaired = true,
                                .meshes_need_triangles = true,
                                .textures_need_uv = true};

/// A scene as a tinygltf model (scene_model()) and what tinygltf does not write itself.
struct SceneModel {
  tinygltf::Model model;  ///< all binary data in buffer 0 (no URI)
  /// With Meshopt compression, buffer 1 is the fallback: its byteLength.
  size_t fallback_bytes = 0;
  /// (buffer view, its "extensions" object) of each encoded view (SceneBuffers).
  std::vector<std::pair<int, nlohmann::json>> view_extensions;
  /// With image files: (file name, image bytes) of each used texture.
  std::vector<std::pair<std::string, std::string>> images;
};

/// The steps of scene_model over the state they share: the model and scene being filled and
/// which glTF material, texture and mesh each of the assets' became. Each step is one method,
/// run once, in order (scene_model).
class SceneModelBuilder {
 public:
  /// `assets` are valid (kGltfRules); `image_files` and `fallback_files` as scene_model's.
  SceneModelBuilder(const SceneAssets& assets, const GltfSceneOptions& options,
                    const std::vector<std::string>* image_files,
                    const std::vector<std::string>* fallback_files)
      : assets_(assets), options_(options), image_files_(image_files),
        fallback_files_(fallback_files), m_(new_model()),
        left_out_(left_out_meshes(assets, options)),
        gltf_material_(used_materials(assets, left_out_)) {
    if (options.compression == GltfCompression::Meshopt) m_.buffers.emplace_back();
    scene_.name = assets.name;
  }

  /// The textures of the used materials, as images in the buffer (JPEG or PNG,
  /// texture_image.h; KTX2, ktx2_texture.h, several encoded at once) or image files, in the
  /// assets' order.
  void add_textures();
  /// The used materials, in their order.
  void add_materials();
  /// The meshes (add_asset_mesh()) and the extensions their compression requires.
  void add_meshes();
  /// The root node and each instance's nodes.
  void add_instances();
  /// The camera and the lights, and how a viewer shows the lights' units.
  void add_camera_and_lights();
  /// The model, once every step has run.
  SceneModel finish();

 private:
  /// Which materials some mesh that is written uses (an unused one is a validator notice): 0
  /// for those, -1 for the others.
  static std::vector<int> used_materials(const SceneAssets& assets,
                                         const std::vector<bool>& left_out);
  /// Per mesh, whether it is left out: shown only by the backdrop, when options.backdrop is
  /// false.
  static std::vector<bool> left_out_meshes(const SceneAssets& assets,
                                           const GltfSceneOptions& options);
  /// Whether `inst` is left out (the backdrop, when options.backdrop is false).
  bool left_out(const AssetInstance& inst) const { return inst.backdrop && !options_.backdrop; }
  /// The sampler of a texture: clamped, or repeating in u where it wraps in u (a texture
  /// that runs around, the skin's); each added once.
  int sampler_index(bool wrap_u);
  /// Adds texture `t` of the assets with its image, `bytes` (encoded as options.textures
  /// says), and with KTX2 its `fallback` image when not empty; returns the glTF texture.
  int add_texture(size_t t, std::string bytes, std::string fallback);
  /// Adds an image of texture `t` (`bytes` of `mime_type`): into the buffer, or as the file
  /// `files`[t] when writing files; returns the glTF image.
  int add_image(size_t t, std::string bytes, const char* mime_type,
                const std::vector<std::string>* files);
  /// Adds `node` and lists it in the scene.
  void add_node(tinygltf::Node node);
  /// Adds the node of `inst`, its mesh node and its hull nodes, in this order.
  void add_instance(const AssetInstance& inst);
  /// The node of `inst`'s mesh; its levels of detail go to lod_nodes_.
  tinygltf::Node mesh_node(const AssetInstance& inst);
  /// The collision hull nodes of `inst` (none without collision), their meshes added.
  std::vector<tinygltf::Node> hull_nodes(const AssetInstance& inst);

  const SceneAssets& assets_;
  const GltfSceneOptions& options_;
  const std::vector<std::string>* image_files_;
  const std::vector<std::string>* fallback_files_;
  tinygltf::Model m_;
  std::vector<bool> left_out_;  // per mesh of the assets
  tinygltf::Scene scene_;
  size_t fallback_bytes_ = 0;
  std::vector<std::pair<int, nlohmann::json>> view_extensions_;
  std::vector<std::pair<std::string, std::string>> images_;
  std::vector<int> gltf_material_;         // per material of the assets; -1: unused
  std::vector<int> gltf_texture_;          // per texture of the assets; -1: unused
  std::vector<AddedMesh> added_;           // per mesh of the assets
  size_t main_nodes_ = 0;                  // the nodes in the scene's list
  std::vector<tinygltf::Node> lod_nodes_;  // after the others
  int hull_material_ = -1;                 // the collision hulls' one material, once needed
};

std::vector<bool> SceneModelBuilder::left_out_meshes(const SceneAssets& assets,
                                                     const GltfSceneOptions& options) {
  std::vector<bool> out(assets.meshes.size(), false);
  if (options.backdrop) return out;
  std::vector<bool> shown(assets.meshes.size(), false);
  for (const AssetInstance& inst : assets.instances) {
    const auto m = static_cast<size_t>(inst.mesh);
    if (inst.backdrop) out[m] = true;
    else shown[m] = true;
  }
  for (size_t m = 0; m < out.size(); ++m) out[m] = out[m] && !shown[m];
  return out;
}

std::vector<int> SceneModelBuilder::used_materials(const SceneAssets& assets,
                                                   const std::vector<bool>& left_out) {
  std::vector<int> gltf_material(assets.materials.size(), -1);
  for (size_t m = 0; m < assets.meshes.size(); ++m) {
    if (left_out[m]) continue;
    const AssetMesh& mesh = assets.meshes[m];
    if (mesh.primitives.empty()) gltf_material[0] = 0;
    for (const AssetPrimitive& p : mesh.primitives)
      gltf_material[static_cast<size_t>(p.material)] = 0;
  }
  return gltf_material;
}

void SceneModelBuilder::add_textures() {
  gltf_texture_.assign(assets_.textures.size(), -1);
  std::vector<Ktx2Content> content(assets_.textures.size(), Ktx2Content::Colour);
  for (size_t k = 0; k < assets_.materials.size(); ++k) {
    const AssetMaterial& material = assets_.materials[k];
    for (const int t :
         {material.base_colour_texture, material.material_texture, material.normal_texture})
      if (gltf_material_[k] >= 0 && t >= 0) gltf_texture_[static_cast<size_t>(t)] = 0;
    if (material.normal_texture >= 0)
      content[static_cast<size_t>(material.normal_texture)] = Ktx2Content::Normal;
  }
  std::vector<std::string> bytes(assets_.textures.size()), fallback(assets_.textures.size());
  if (options_.textures == TextureFormat::Ktx2) {
    if (options_.basisu.empty()) throw InternalError("KTX2 textures asked for without basisu");
    // Each texture by its own single-threaded basisu, several at once: the same bytes in any
    // order.
    const std::string identity = basisu_identity(options_.basisu);
    oneapi::tbb::parallel_for(size_t{0}, assets_.textures.size(), [&](size_t t) {
      if (gltf_texture_[t] < 0) return;
      const AssetTexture& texture = assets_.textures[t];
      const Ktx2Content kind = content[t] == Ktx2Content::Normal ? Ktx2Content::Normal
                               : texture.linear                  ? Ktx2Content::Data
                                                                 : Ktx2Content::Colour;
      bytes[t] = stored_ktx2(texture, kind, options_.basisu, identity,
                             options_.texture_store ? &*options_.texture_store : nullptr);
    });
    m_.extensionsUsed.push_back("KHR_texture_basisu");
    if (options_.texture_fallback) {
      for (size_t t = 0; t < assets_.textures.size(); ++t)
        if (gltf_texture_[t] >= 0)
          fallback[t] = encode_texture(assets_.textures[t], image_file_format(options_.textures));
    } else {
      m_.extensionsRequired.push_back("KHR_texture_basisu");
    }
  } else {
    for (size_t t = 0; t < assets_.textures.size(); ++t)
      if (gltf_texture_[t] >= 0) bytes[t] = encode_texture(assets_.textures[t], options_.textures);
  }
  for (size_t t = 0; t < assets_.textures.size(); ++t)
    if (gltf_texture_[t] >= 0)
      gltf_texture_[t] = add_texture(t, std::move(bytes[t]), std::move(fallback[t]));
}

int SceneModelBuilder::sampler_index(bool wrap_u) {
  const int wrap_s = wrap_u ? TINYGLTF_TEXTURE_WRAP_REPEAT : TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  for (size_t k = 0; k < m_.samplers.size(); ++k)
    if (m_.samplers[k].wrapS == wrap_s) return static_cast<int>(k);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_LINEAR;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR;
  sampler.wrapS = wrap_s;
  sampler.wrapT = TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE;
  m_.samplers.push_back(sampler);
  return static_cast<int>(m_.samplers.size()) - 1;
}

int SceneModelBuilder::add_image(size_t t, std::string bytes, const char* mime_type,
                                 const std::vector<std::string>* files) {
  tinygltf::Image image;
  image.name = assets_.textures[t].name;
  image.mimeType = mime_type;
  if (files) {
    image.uri = uri_encode(files->at(t));
    images_.emplace_back(files->at(t), std::move(bytes));
  } else {
    image.bufferView = add_view(m_, bytes.data(), bytes.size(), 0);
  }
  m_.images.push_back(image);
  return static_cast<int>(m_.images.size()) - 1;
}

int SceneModelBuilder::add_texture(size_t t, std::string bytes, std::string fallback) {
  const AssetTexture& asset = assets_.textures[t];
  tinygltf::Texture texture;
  texture.name = asset.name;
  texture.sampler = sampler_index(asset.wrap_u);
  if (!fallback.empty())  // the JPEG or PNG first: what readers without KTX2 take
    texture.source =
        add_image(t, std::move(fallback),
                  texture_mime_type(asset, image_file_format(options_.textures)), fallback_files_);
  const int source =
      add_image(t, std::move(bytes), texture_mime_type(asset, options_.textures), image_files_);
  if (options_.textures == TextureFormat::Ktx2)
    texture.extensions["KHR_texture_basisu"] =
        tinygltf::Value(tinygltf::Value::Object{{"source", tinygltf::Value(source)}});
  else texture.source = source;
  m_.textures.push_back(texture);
  return static_cast<int>(m_.textures.size()) - 1;
}

void SceneModelBuilder::add_materials() {
  for (size_t k = 0; k < assets_.materials.size(); ++k) {
    if (gltf_material_[k] < 0) continue;
    gltf_material_[k] = static_cast<int>(m_.materials.size());
    add_pbr_material(m_, assets_.materials[k], gltf_texture_);
  }
}

void SceneModelBuilder::add_meshes() {
  std::vector<const AssetMesh*> written;
  for (size_t m = 0; m < assets_.meshes.size(); ++m)
    if (!left_out_[m]) written.push_back(&assets_.meshes[m]);
  SceneBuffers out(m_, options_.compression, meshopt_grid(written, assets_.textures));
  for (size_t m = 0; m < assets_.meshes.size(); ++m)
    added_.push_back(left_out_[m]
                         ? AddedMesh{}
                         : add_asset_mesh(out, assets_.meshes[m], gltf_material_, options_.lods,
                                          options_.pivot_at_centre_of_mass));
  out.finish();
  fallback_bytes_ = out.fallback_bytes();
  view_extensions_ = out.view_extensions();
  auto require = [this](const std::string& extension) {
    m_.extensionsUsed.push_back(extension);
    m_.extensionsRequired.push_back(extension);
  };
  if (options_.compression != GltfCompression::None) require("KHR_mesh_quantization");
  if (options_.compression == GltfCompression::Meshopt) require("EXT_meshopt_compression");
  if (out.uvs_on_grid()) {
    const auto [offset, scale] = out.uv_transform();
    add_texture_transform(m_, offset, scale);
  }
}

void SceneModelBuilder::add_node(tinygltf::Node node) {
  m_.nodes.push_back(std::move(node));
  scene_.nodes.push_back(static_cast<int>(m_.nodes.size()) - 1);
}

void SceneModelBuilder::add_instances() {
  // Node order: the root, each instance's node followed by its mesh node and hull nodes, the
  // camera, the lights (those in the scene's list: the root, the camera, the lights); then the
  // level nodes, outside the scene's list.
  main_nodes_ = 1 + (options_.camera_and_lights ? 1 + assets_.lights.size() : 0);
  for (const AssetInstance& inst : assets_.instances) {
    if (left_out(inst)) continue;
    main_nodes_ += 2;
    if (writes_hull_nodes(options_.collision)) main_nodes_ += inst.collision.size();
  }
  tinygltf::Node root;
  root.name = assets_.name;
  m_.nodes.push_back(root);
  scene_.nodes.push_back(0);
  for (const AssetInstance& inst : assets_.instances)
    if (!left_out(inst)) add_instance(inst);
}

void SceneModelBuilder::add_instance(const AssetInstance& inst) {
  const double qlen = glm::length(inst.rotation);
  glm::dquat q = inst.rotation / qlen;
  if (q.w < 0) q = -q;
  tinygltf::Node node;
  node.name = inst.name;
  node.rotation = gltf_rotation(q);
  node.translation = gltf_vec3(inst.translation);
  tinygltf::Node mesh = mesh_node(inst);
  if (!inst.piece.template_name.empty()) {
    const PieceInfo& info = inst.piece;
    tinygltf::Value::Array parts;
    for (const std::string& kind : info.parts) parts.emplace_back(kind);
    tinygltf::Value::Object extras;
    extras["template"] = tinygltf::Value(info.template_name);
    // A decimal string: a 64-bit seed does not fit a JSON number exactly.
    extras["seed"] = tinygltf::Value(std::to_string(info.seed));
    extras["cut"] = tinygltf::Value(info.cut);
    extras["piece"] = tinygltf::Value(info.cell);
    extras["parts"] = tinygltf::Value(parts);
    extras["volume_m3"] = tinygltf::Value(info.volume_m3);
    node.extras = tinygltf::Value(std::move(extras));
  } else if (inst.backdrop) {  // staging, which an engine or a viewer may drop
    node.extras = tinygltf::Value(tinygltf::Value::Object{{"backdrop", tinygltf::Value(true)}});
  }
  const int index = static_cast<int>(m_.nodes.size());
  node.children = {index + 1};
  std::vector<tinygltf::Node> hulls = hull_nodes(inst);
  for (size_t k = 0; k < hulls.size(); ++k)
    node.children.push_back(index + 2 + static_cast<int>(k));
  m_.nodes.push_back(std::move(node));
  m_.nodes.push_back(std::move(mesh));
  for (tinygltf::Node& hull_node : hulls) m_.nodes.push_back(std::move(hull_node));
  m_.nodes[0].children.push_back(index);
}

tinygltf::Node SceneModelBuilder::mesh_node(const AssetInstance& inst) {
  // The mesh below the instance, with the mesh's frame (quantized positions back to metres:
  // offset + scale q) as its own transform: the instance's transform is the same whatever
  // the compression.
  const AddedMesh& mesh = added_[static_cast<size_t>(inst.mesh)];
  tinygltf::Node node;
  node.name = inst.name + "_mesh";
  // Only pieces are loose: a board or plate stays where it is.
  if (options_.collision == GltfCollision::GodotRigid && !inst.piece.template_name.empty())
    node.name += "-rigid";
  node.mesh = mesh.index;
  if (mesh.frame.offset != glm::dvec3(0.0)) node.translation = gltf_vec3(mesh.frame.offset);
  if (mesh.frame.scale != 1.0) node.scale = {mesh.frame.scale, mesh.frame.scale, mesh.frame.scale};
  // Levels of detail (MSFT_lod): a node per level, placed as the mesh node, outside the
  // scene's list; level l is shown down to 0.2 * 4^-l of the screen's height, the last one
  // always.
  if (!mesh.lods.empty()) {
    tinygltf::Value::Array ids, coverage;
    for (size_t l = 0; l < mesh.lods.size(); ++l) {
      tinygltf::Node level = node;
      level.name = inst.name + "_LOD" + std::to_string(l + 1);
      level.mesh = mesh.lods[l];
      ids.emplace_back(static_cast<int>(main_nodes_ + lod_nodes_.size()));
      lod_nodes_.push_back(std::move(level));
      coverage.emplace_back(0.2 * std::ldexp(1.0, -2 * static_cast<int>(l)));
    }
    coverage.emplace_back(0.0);
    node.extensions["MSFT_lod"] =
        tinygltf::Value(tinygltf::Value::Object{{"ids", tinygltf::Value(ids)}});
    node.extras = tinygltf::Value(
        tinygltf::Value::Object{{"MSFT_screencoverage", tinygltf::Value(coverage)}});
  }
  return node;
}

std::vector<tinygltf::Node> SceneModelBuilder::hull_nodes(const AssetInstance& inst) {
  std::vector<tinygltf::Node> nodes;
  if (!writes_hull_nodes(options_.collision)) return nodes;
  const std::string& mesh_name = assets_.meshes[static_cast<size_t>(inst.mesh)].name;
  // Hulls are see-through (alpha 0, blended) where a viewer does not read their names as
  // collision: Blender, three.js and model viewers draw nothing over the piece.
  if (!inst.collision.empty() && hull_material_ < 0)
    hull_material_ = add_material(m_, "collision", 0.0);
  for (size_t k = 0; k < inst.collision.size(); ++k) {
    const AssetHull& hull = inst.collision[k];
    char number[24];
    std::snprintf(number, sizeof number, "%02zu", k);
    tinygltf::Mesh hull_mesh;
    hull_mesh.name = options_.collision == GltfCollision::Godot
                         ? inst.name + "_collision" + std::to_string(k) + "-convcolonly"
                         : "UCX_" + mesh_name + "_" + number;
    std::vector<float> xyz;
    for (const glm::dvec3& p : hull.position)
      for (int c = 0; c < 3; ++c) xyz.push_back(static_cast<float>(p[c]) + 0.0f);
    std::vector<uint32_t> idx;
    for (const glm::uvec3& t : hull.triangle) idx.insert(idx.end(), {t.x, t.y, t.z});
    tinygltf::Primitive prim;
    prim.mode = TINYGLTF_MODE_TRIANGLES;
    prim.attributes["POSITION"] = add_vec3_accessor(m_, xyz, true);
    prim.indices = add_index_accessor(m_, idx);
    prim.material = hull_material_;
    hull_mesh.primitives.push_back(prim);
    m_.meshes.push_back(hull_mesh);
    tinygltf::Node hull_node;
    hull_node.name = hull_mesh.name;
    hull_node.mesh = static_cast<int>(m_.meshes.size()) - 1;
    hull_node.extras = tinygltf::Value(
        tinygltf::Value::Object{{"collision", tinygltf::Value(std::string("convex"))}});
    nodes.push_back(std::move(hull_node));
  }
  return nodes;
}

void SceneModelBuilder::add_camera_and_lights() {
  // How to show the lights' physical units (doc/lighting.md): three.js's
  // toneMappingExposure, and the sky a viewer adds as its world or ambient light.
  tinygltf::Value::Object view;
  view["exposure"] = tinygltf::Value(1 / kLumensPerWatt);
  if (assets_.ambient_lux > 0) view["ambient_lux"] = tinygltf::Value(assets_.ambient_lux);
  scene_.extras = tinygltf::Value(std::move(view));
  const AssetCamera& cam = assets_.camera;
  tinygltf::Camera camera;
  camera.name = "camera";
  camera.type = "perspective";
  camera.perspective.yfov = glm::radians(cam.fov_y_deg);
  camera.perspective.aspectRatio = cam.aspect;
  camera.perspective.znear = cam.znear;
  camera.perspective.zfar = cam.zfar;
  m_.cameras.push_back(camera);
  tinygltf::Node camera_node;
  camera_node.name = "camera";
  camera_node.camera = 0;
  camera_node.rotation = gltf_rotation(look_rotation(cam.target - cam.eye, cam.up));
  camera_node.translation = gltf_vec3(cam.eye);
  add_node(camera_node);

  for (const AssetLight& light : assets_.lights) {
    tinygltf::Light gl;
    gl.name = light.name;
    gl.color = gltf_vec3(light.colour);
    gl.intensity = light.intensity;
    tinygltf::Node node;
    node.name = light.name;
    if (light.type == LightType::Directional) {
      gl.type = "directional";
      node.rotation = gltf_rotation(look_rotation(light.direction, glm::dvec3(0, 1, 0)));
      if (light.angle_deg > 0)  // glTF's lights have no size: Blender's sun angle, as extras
        node.extras = tinygltf::Value(
            tinygltf::Value::Object{{"angle_deg", tinygltf::Value(light.angle_deg)}});
    } else {
      gl.type = "point";
      node.translation = gltf_vec3(light.position);
    }
    m_.lights.push_back(gl);
    tinygltf::Value::Object ref;
    ref["light"] = tinygltf::Value(static_cast<int>(m_.lights.size()) - 1);
    node.extensions["KHR_lights_punctual"] = tinygltf::Value(ref);
    add_node(node);
  }
}

SceneModel SceneModelBuilder::finish() {
  if (!m_.lights.empty()) m_.extensionsUsed.push_back("KHR_lights_punctual");
  for (tinygltf::Node& node : lod_nodes_) m_.nodes.push_back(std::move(node));
  if (options_.lods > 0) m_.extensionsUsed.push_back("MSFT_lod");
  m_.scenes.push_back(scene_);
  return {std::move(m_), fallback_bytes_, std::move(view_extensions_), std::move(images_)};
}

/// The scene as a tinygltf model with all binary data in buffer 0 (no URI; with Meshopt
/// compression, buffer 1 is the fallback) and the extensions of the encoded buffer views. With
/// `image_files` (texture_file_names(), one per texture), each used texture's image refers to
/// its file instead and the images are returned with their file names; `fallback_files` name
/// the texture fallback's images so (options.texture_fallback).
SceneModel scene_model(const SceneAssets& assets, const GltfSceneOptions& options,
                       const std::vector<std::string>* image_files = nullptr,
                       const std::vector<std::string>* fallback_files = nullptr) {
  require_valid_assets(assets, kGltfRules, "scene assets");
  SceneModelBuilder builder(assets, options, image_files, fallback_files);
  builder.add_textures();
  builder.add_materials();
  builder.add_meshes();
  builder.add_instances();
  if (options.camera_and_lights) builder.add_camera_and_lights();
  return builder.finish();
}

/// Rewrites every fractional number under `j` as the shortest decimal that reads back as the
/// same float32 (at most 9 significant digits, where a double takes 17): engines hold node
/// transforms, factors and texture transforms in float32, so the digits past it only cost
/// bytes (gltfpack writes its numbers the same way). Integers are left as they are, and so is
/// every "extras" object: our own data (exposure, volumes), read back at full precision.
void write_numbers_as_float32(nlohmann::json& j) {
  if (j.is_object()) {
    for (auto& [key, value] : j.items())
      if (key != "extras") write_numbers_as_float32(value);
  } else if (j.is_array()) {
    for (nlohmann::json& value : j) write_numbers_as_float32(value);
  } else if (j.is_number_float()) {
    const auto f = static_cast<float>(j.get<double>());
    if (!std::isfinite(f)) return;
    char text[32];
    const auto end = std::to_chars(text, text + sizeof text, f).ptr;
    double shortest = 0;
    std::from_chars(text, end, shortest);
    j = shortest;
  }
}

/// A scene's glTF JSON (buffers without URIs), the bytes of buffer 0 and, with image files,
/// the images.
struct EncodedScene {
  nlohmann::json doc;
  std::vector<unsigned char> bin;
  std::vector<std::pair<std::string, std::string>> images;  ///< (file name, image bytes)
};

/// scene_model() serialised: buffer 0 holds `bin`; with Meshopt compression buffer 1 is the
/// EXT_meshopt_compression fallback, which holds no bytes.
EncodedScene encode_scene(const SceneAssets& assets, const GltfSceneOptions& options,
                          const std::vector<std::string>* image_files = nullptr,
                          const std::vector<std::string>* fallback_files = nullptr) {
  SceneModel model = scene_model(assets, options, image_files, fallback_files);
  tinygltf::Model& m = model.model;
  EncodedScene scene;
  scene.bin.swap(m.buffers[0].data);
  scene.images = std::move(model.images);
  std::ostringstream out;
  tinygltf::TinyGLTF writer;
  // Image files are written here, not by tinygltf: it keeps each image's uri (its own writer
  // turned a KTX2 file's uri, whose type it does not know, into an empty one).
  writer.SetImageWriter(nullptr, nullptr);
  writer.WriteGltfSceneToStream(&m, out, false, false);
  scene.doc = nlohmann::json::parse(out.str());
  scene.doc["buffers"][0] = {{"byteLength", scene.bin.size()}};
  if (options.compression == GltfCompression::Meshopt) {
    scene.doc["buffers"][1] = {{"byteLength", model.fallback_bytes},
                               {"extensions", {{"EXT_meshopt_compression", {{"fallback", true}}}}}};
    for (const auto& [view, extensions] : model.view_extensions)
      scene.doc["bufferViews"][static_cast<size_t>(view)]["extensions"] = extensions;
  }
  for (const auto& [key, value] : options.scene_extras.items())
    scene.doc["scenes"][0]["extras"][key] = value;
  // Accessor bounds stay exact: a float accessor's min and max must equal its data.
  for (auto& [key, value] : scene.doc.items())
    if (key != "accessors") write_numbers_as_float32(value);
  return scene;
}

/// Writes `bytes` to a fresh temporary file beside `target` (flushed) and returns its path.
std::filesystem::path stage_file(const std::filesystem::path& target, std::string_view bytes) {
  std::string tmp = target.string() + ".tmp-XXXXXX";
  const int fd = mkstemp(tmp.data());
  if (fd < 0) {
    throw EnvironmentError("cannot write " + target.string() + ": " + std::strerror(errno));
  }
  ::close(fd);
  try {
    write_file_atomically(tmp, bytes);
  } catch (...) {
    ::unlink(tmp.c_str());
    throw;
  }
  return tmp;
}

void rename_or_throw(const std::filesystem::path& from, const std::filesystem::path& to) {
  if (std::rename(from.c_str(), to.c_str()) != 0) {
    throw EnvironmentError("cannot write " + to.string() + ": " + std::strerror(errno));
  }
}

}  // namespace

std::string model_to_glb(const DsModel& model, const GltfModelOptions& options) {
  tinygltf::Model m = new_model();
  const int skin_mat = add_material(m, "skin", options.skin_alpha);
  const int inner_mat = add_material(m, "inner", options.inner_alpha);
  tinygltf::Scene scene;
  scene.name = model.name;
  for (const DsSurface& s : model.surfaces) {
    const DsMesh& mesh = s.mesh;
    std::vector<float> pos, front, back;
    for (auto vh : mesh.vertices()) {
      const auto& p = mesh.point(vh);
      const auto& d = mesh.data(vh);
      for (int k = 0; k < 3; ++k) {
        pos.push_back(static_cast<float>(p[k]));
        front.push_back(static_cast<float>(d.front[k]));
        back.push_back(static_cast<float>(d.back[k]));
      }
    }
    std::vector<float> normals, flipped;
    for (glm::dvec3 n : vertex_normals(mesh)) {
      if (n == glm::dvec3(0.0)) n = {0, 1, 0};  // glTF normals must be unit length
      for (int k = 0; k < 3; ++k) {
        normals.push_back(static_cast<float>(n[k]));
        flipped.push_back(static_cast<float>(-n[k]));
      }
    }
    std::vector<uint32_t> idx, rev;
    for (auto fh : mesh.faces()) {
      std::array<uint32_t, 3> v;
      int k = 0;
      for (auto vh : mesh.fv_range(fh)) v[k++] = static_cast<uint32_t>(vh.idx());
      idx.insert(idx.end(), {v[0], v[1], v[2]});
      rev.insert(rev.end(), {v[0], v[2], v[1]});
    }
    const int apos = add_vec3_accessor(m, pos, true);
    const int mat = s.role == SurfaceRole::Skin ? skin_mat : inner_mat;
    tinygltf::Mesh gm;
    gm.name = s.name;
    for (int side = 0; side < 2; ++side) {
      tinygltf::Primitive prim;
      prim.mode = TINYGLTF_MODE_TRIANGLES;
      prim.material = mat;
      prim.attributes["POSITION"] = apos;
      prim.attributes["NORMAL"] = add_vec3_accessor(m, side == 0 ? normals : flipped, false);
      prim.attributes["COLOR_0"] = add_vec3_accessor(m, side == 0 ? front : back, false);
      prim.indices = add_index_accessor(m, side == 0 ? idx : rev);
      gm.primitives.push_back(prim);
    }
    m.meshes.push_back(gm);
    tinygltf::Node node;
    node.name = s.name;
    node.mesh = static_cast<int>(m.meshes.size()) - 1;
    m.nodes.push_back(node);
    scene.nodes.push_back(static_cast<int>(m.nodes.size()) - 1);
  }
  m.scenes.push_back(scene);
  return to_glb(m);
}

GltfGeometryCounts count_glb_geometry(std::string_view glb) {
  const auto refuse = [](const std::string& why) {
    return EnvironmentError("not a binary glTF file: " + why);
  };
  const auto u32 = [&glb](size_t at) {
    uint32_t v = 0;
    std::memcpy(&v, glb.data() + at, 4);
    return v;
  };
  if (glb.size() < 20 || glb.substr(0, 4) != "glTF") throw refuse("no glTF header");
  const size_t json_bytes = u32(12);
  if (u32(16) != 0x4E4F534Au || json_bytes > glb.size() - 20) throw refuse("no JSON chunk");
  const nlohmann::json doc =
      nlohmann::json::parse(glb.substr(20, json_bytes), nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) throw refuse("its JSON chunk does not parse");
  GltfGeometryCounts counts;
  try {
    const nlohmann::json& nodes = doc.at("nodes");
    std::vector<size_t> todo;
    for (const auto& n : doc.at("scenes").at(doc.value("scene", 0)).at("nodes"))
      todo.push_back(n.get<size_t>());
    while (!todo.empty()) {
      const nlohmann::json& node = nodes.at(todo.back());
      todo.pop_back();
      for (const auto& child : node.value("children", nlohmann::json::array()))
        todo.push_back(child.get<size_t>());
      // Collision hulls are not drawn.
      if (!node.contains("mesh") ||
          node.value("extras", nlohmann::json::object()).contains("collision"))
        continue;
      for (const auto& p : doc.at("meshes").at(node.at("mesh").get<size_t>()).at("primitives")) {
        counts.triangles +=
            doc.at("accessors").at(p.at("indices").get<size_t>()).at("count").get<size_t>() / 3;
        counts.vertices += doc.at("accessors")
                               .at(p.at("attributes").at("POSITION").get<size_t>())
                               .at("count")
                               .get<size_t>();
      }
    }
  } catch (const nlohmann::json::exception& e) {
    throw refuse(e.what());
  }
  return counts;
}

std::string section_to_glb(const CrossSection& section) {
  tinygltf::Model m = new_model();
  std::vector<float> pos, normal, colour;
  for (size_t i = 0; i < section.position.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      pos.push_back(static_cast<float>(section.position[i][k]));
      normal.push_back(static_cast<float>(section.plane.normal[k]));
      colour.push_back(static_cast<float>(section.colour[i][k]));
    }
  }
  std::vector<uint32_t> idx;
  for (const glm::uvec3& t : section.triangle) idx.insert(idx.end(), {t.x, t.y, t.z});
  tinygltf::Primitive prim;
  prim.mode = TINYGLTF_MODE_TRIANGLES;
  prim.material = add_material(m, "cut face", 1.0, true);
  prim.attributes["POSITION"] = add_vec3_accessor(m, pos, true);
  prim.attributes["NORMAL"] = add_vec3_accessor(m, normal, false);
  prim.attributes["COLOR_0"] = add_vec3_accessor(m, colour, false);
  prim.indices = add_index_accessor(m, idx);
  tinygltf::Mesh mesh;
  mesh.name = "cross-section";
  mesh.primitives.push_back(prim);
  m.meshes.push_back(mesh);
  tinygltf::Node node;
  node.name = "cross-section";
  node.mesh = 0;
  m.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes.push_back(0);
  m.scenes.push_back(scene);
  return to_glb(m);
}

void write_model_glb(const std::filesystem::path& path, const DsModel& model,
                     const GltfModelOptions& options) {
  write_file_atomically(path, model_to_glb(model, options));
}

std::string scene_to_glb(const SceneAssets& assets, const GltfSceneOptions& options) {
  const EncodedScene scene = encode_scene(assets, options);
  // GLB (glTF 2.0 §4.4): a 12-byte header, the JSON chunk padded with spaces, the BIN chunk
  // padded with zeros, each length a multiple of 4, little-endian.
  std::string json = scene.doc.dump();
  json.resize((json.size() + 3) / 4 * 4, ' ');
  const size_t bin_bytes = (scene.bin.size() + 3) / 4 * 4;
  std::string glb;
  glb.reserve(28 + json.size() + bin_bytes);
  auto u32 = [&glb](uint32_t v) {
    for (int k = 0; k < 4; ++k) glb += static_cast<char>((v >> (8 * k)) & 0xff);
  };
  glb += "glTF";
  u32(2);
  u32(static_cast<uint32_t>(12 + 8 + json.size() + (bin_bytes == 0 ? 0 : 8 + bin_bytes)));
  u32(static_cast<uint32_t>(json.size()));
  glb += "JSON";
  glb += json;
  if (bin_bytes > 0) {
    u32(static_cast<uint32_t>(bin_bytes));
    glb += std::string("BIN\0", 4);
    glb.append(reinterpret_cast<const char*>(scene.bin.data()), scene.bin.size());
    glb.resize(glb.size() + bin_bytes - scene.bin.size(), '\0');
  }
  return glb;
}

GltfCollision parse_gltf_collision(std::string_view name) {
  if (name == "none") return GltfCollision::None;
  if (name == "godot") return GltfCollision::Godot;
  if (name == "unreal") return GltfCollision::Unreal;
  if (name == "godot-rigid") return GltfCollision::GodotRigid;
  throw InternalError("unknown collision naming '" + std::string(name) +
                      "' (none, godot, unreal or godot-rigid)");
}

GltfCompression parse_gltf_compression(std::string_view name) {
  if (name == "none") return GltfCompression::None;
  if (name == "quantize") return GltfCompression::Quantize;
  if (name == "meshopt") return GltfCompression::Meshopt;
  throw InternalError("unknown glTF compression '" + std::string(name) +
                      "' (none, quantize or meshopt)");
}

void write_scene_gltf(const std::filesystem::path& path, const SceneAssets& assets,
                      const GltfSceneOptions& options) {
  namespace fs = std::filesystem;
  std::string ext = path.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".glb" && ext != ".gltf") {
    throw InternalError("scene export: unknown extension '" + path.extension().string() + "' of " +
                        path.string() + " (expected .glb or .gltf)");
  }
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw EnvironmentError("cannot write " + path.string() + ": no directory " + dir.string());
  }
  if (ext == ".glb") {
    write_file_atomically(path, scene_to_glb(assets, options));
    return;
  }
  // .gltf: the textures as image files beside it, written first (each atomically).
  const std::vector<std::string> image_files = texture_file_names(path, assets, options.textures);
  const std::vector<std::string> fallback_files =
      texture_file_names(path, assets, image_file_format(options.textures));
  EncodedScene scene = encode_scene(assets, options, &image_files, &fallback_files);
  for (const auto& [name, bytes] : scene.images) write_file_atomically(dir / name, bytes);
  // .gltf: buffer 0 is the .bin beside it.
  fs::path bin_path = path;
  bin_path.replace_extension(".bin");
  const std::vector<unsigned char>& bin = scene.bin;
  scene.doc["buffers"][0]["uri"] = uri_encode(bin_path.filename().string());
  const std::string json_text = scene.doc.dump(2) + "\n";

  const fs::path bin_tmp =
      stage_file(bin_path, std::string_view(reinterpret_cast<const char*>(bin.data()), bin.size()));
  fs::path json_tmp;
  try {
    json_tmp = stage_file(path, json_text);
    rename_or_throw(bin_tmp, bin_path);
  } catch (...) {
    ::unlink(bin_tmp.c_str());
    if (!json_tmp.empty()) ::unlink(json_tmp.c_str());
    throw;
  }
  try {
    rename_or_throw(json_tmp, path);
  } catch (...) {
    ::unlink(json_tmp.c_str());
    ::unlink(bin_path.c_str());
    throw;
  }
}

}  // namespace cutaway
