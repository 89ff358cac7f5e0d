// The one SceneAssets validation (assets/scene_assets.h): a valid scene passes, each broken
// element is named, the rules say what an exporter tolerates, every exporter applies it, and
// the one camera rule.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "assets/scene_assets.h"
#include "export/gltf_export.h"
#include "export/pov_export.h"

namespace cutaway {
namespace {

/// One triangle, placed once, seen by the default camera, one light, one texture.
SceneAssets triangle_scene() {
  SceneAssets a;
  a.name = "tri";
  AssetMesh m;
  m.name = "tri";
  m.position = {{0, 0, 0}, {0.1, 0, 0}, {0, 0.1, 0}};
  m.normal.assign(3, {0, 0, 1});
  m.colour.assign(3, {0.5, 0.2, 0.1});
  m.triangle = {{0, 1, 2}};
  a.meshes.push_back(m);
  a.instances.push_back({"tri", 0, {1, 0, 0, 0}, {0, 0, 0}, {}});
  a.lights.push_back({});
  a.textures.push_back({"tex", 2, 2, 3, std::vector<uint8_t>(12, 128)});
  return a;
}

bool names(const Check& check, const std::string& what) {
  return !check && check.reason().find(what) != std::string::npos;
}

// The centre of mass of a closed mesh, whatever its triangles' order or the origin: a corner
// tetrahedron's lies a quarter along each edge from the corner; an open sheet's is its box's.
TEST(VolumeCentroid, IsTheCentreOfTheVolumeOrOfTheBoxWithoutOne) {
  ColouredMesh tetra;
  const glm::dvec3 at(0.3, -0.2, 0.1);
  tetra.position = {at, at + glm::dvec3(0.04, 0, 0), at + glm::dvec3(0, 0.04, 0),
                    at + glm::dvec3(0, 0, 0.04)};
  tetra.triangle = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_LT(glm::distance(volume_centroid(tetra), at + glm::dvec3(0.01)), 1e-12);
  // Wound inwards: the same centre (the signed volume and moment change sign together).
  for (glm::uvec3& t : tetra.triangle) std::swap(t.y, t.z);
  EXPECT_LT(glm::distance(volume_centroid(tetra), at + glm::dvec3(0.01)), 1e-12);
  ColouredMesh sheet;
  sheet.position = {{0, 0, 0}, {0.1, 0, 0}, {0, 0, 0.3}};
  sheet.triangle = {{0, 2, 1}};
  EXPECT_LT(glm::distance(volume_centroid(sheet), glm::dvec3(0.05, 0, 0.15)), 1e-15);
  EXPECT_EQ(volume_centroid(ColouredMesh{}), glm::dvec3(0.0));
}

TEST(SceneAssetsCheck, AValidSceneHasNoDefect) {
  EXPECT_TRUE(check_assets(triangle_scene()));
  EXPECT_NO_THROW(require_valid_assets(triangle_scene(), {}, "test"));
}

TEST(SceneAssetsCheck, NamesEachBrokenElement) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Case {
    const char* what;
    void (*breaks)(SceneAssets&);
  };
  const Case cases[] = {
      {"texture 0 'tex'", [](SceneAssets& a) { a.textures[0].pixels.pop_back(); }},
      {"texture 0 'tex'", [](SceneAssets& a) { a.textures[0].channels = 2; }},
      {"material 0", [](SceneAssets& a) { a.materials[0].pbr.roughness = 2; }},
      {"material 0", [](SceneAssets& a) { a.materials[0].base_colour_texture = 1; }},
      {"mesh 0 'tri'", [](SceneAssets& a) { a.meshes[0].colour.pop_back(); }},
      {"mesh 0 'tri'", [](SceneAssets& a) { a.meshes[0].triangle[0].z = 3; }},
      {"mesh 0 'tri'",
       [](SceneAssets& a) {
         a.meshes[0].uv = {{0, 0}};
       }},
      {"mesh 0 'tri'",
       [](SceneAssets& a) {
         a.meshes[0].primitives = {{0, 1, 5, {}}};
       }},
      {"mesh 0 'tri'",
       [](SceneAssets& a) {
         a.meshes[0].primitives = {{0, 1, 0, {{0, 1, 9}}}};
       }},
      {"instance 0 'tri'", [](SceneAssets& a) { a.instances[0].mesh = 1; }},
      {"instance 0 'tri'",
       [](SceneAssets& a) {
         a.instances[0].rotation = {0, 0, 0, 0};
       }},
      {"camera", [](SceneAssets& a) { a.camera.target = a.camera.eye; }},
      {"light 0",
       [](SceneAssets& a) {
         a.lights[0].direction = {0, 0, 0};
       }},
      {"light 0", [](SceneAssets& a) { a.lights[0].intensity = -1; }},
      {"background", [](SceneAssets& a) { a.background.g = -1; }},
      {"no materials", [](SceneAssets& a) { a.materials.clear(); }},
  };
  for (const Case& c : cases) {
    SceneAssets a = triangle_scene();
    c.breaks(a);
    const Check check = check_assets(a);
    EXPECT_TRUE(names(check, c.what)) << c.what << ": '" << (check ? "" : check.reason()) << "'";
    EXPECT_THROW(scene_to_glb(a), InternalError) << c.what;
    EXPECT_THROW(scene_to_pov(a), InternalError) << c.what;
  }
  SceneAssets a = triangle_scene();
  a.meshes[0].position[1].x = nan;
  EXPECT_TRUE(names(check_assets(a), "vertex 1"));
}

TEST(SceneAssetsCheck, TheRulesSayWhatEachConsumerTolerates) {
  // A zero normal: POV-Ray and glTF replace it; the previews need real ones.
  SceneAssets a = triangle_scene();
  a.meshes[0].normal[0] = glm::dvec3(std::numeric_limits<double>::infinity());
  EXPECT_FALSE(check_assets(a));
  EXPECT_TRUE(check_assets(a, {.normals_repaired = true}));
  EXPECT_NO_THROW(scene_to_pov(a));
  EXPECT_NO_THROW(scene_to_glb(a));
  // A mesh without triangles: only glTF refuses it.
  a = triangle_scene();
  AssetMesh empty;
  empty.name = "empty";
  a.meshes.push_back(empty);
  EXPECT_TRUE(check_assets(a));
  EXPECT_TRUE(names(check_assets(a, {.meshes_need_triangles = true}), "mesh 1 'empty'"));
  EXPECT_NO_THROW(scene_to_pov(a));
  EXPECT_THROW(scene_to_glb(a), InternalError);
  // A textured material on a mesh without uv: the previews fall back to vertex colours.
  a = triangle_scene();
  a.materials.push_back({"textured", PbrMaterial{}, 0});
  a.meshes[0].primitives = {{0, 1, 1, {}}};
  EXPECT_TRUE(check_assets(a));
  EXPECT_FALSE(check_assets(a, {.textures_need_uv = true}));
  EXPECT_THROW(scene_to_glb(a), InternalError);
  a.meshes[0].uv.assign(3, glm::dvec2(0.5));
  EXPECT_NO_THROW(scene_to_glb(a));
  // An `up` along the view: glTF's look rotation does not use it.
  a = triangle_scene();
  a.camera.up = glm::normalize(a.camera.target - a.camera.eye);
  EXPECT_TRUE(names(check_assets(a), "camera: up"));
  EXPECT_TRUE(check_assets(a, {.camera_needs_up = false}));
  EXPECT_THROW(scene_to_pov(a), InternalError);
  EXPECT_NO_THROW(scene_to_glb(a));
}

}  // namespace
}  // namespace cutaway
