// POV-Ray export (generator/export/pov_export.h): the text's structure and determinism, and a
// render of a small asymmetric scene with the system's povray (render/povray_runner.h) checked
// against a pinhole projection of the same camera (not mirrored, not flipped) and an analytic
// Lambert colour.
#include "base/constants.h"
#include "export/pov_export.h"
#include "npr/silhouettes.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <set>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/quaternion.hpp>
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include "base/colour.h"
#include "render/image/image.h"
#include "render/povray_runner.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

const glm::dvec3 kRed{0.7, 0.04, 0.03};     // the cube, linear RGB
const glm::dvec3 kBlue{0.03, 0.06, 0.6};    // the tetrahedron's front face, linear RGB
const glm::dvec3 kPaleBlue{0.1, 0.2, 0.9};  // its back apex
const glm::dvec3 kBackground{0.05, 0.25, 0.1};

// Axis-aligned cube of edge `edge_m` about the origin: 24 vertices (flat faces), one colour.
AssetMesh coloured_cube(const std::string& name, double edge_m, const glm::dvec3& colour) {
  AssetMesh m;
  m.name = name;
  const double h = edge_m / 2;
  for (int axis = 0; axis < 3; ++axis) {
    for (int sign : {1, -1}) {
      glm::dvec3 n(0.0);
      n[axis] = sign;
      // Two axes spanning the face, ordered so that (u x v) = n (counter-clockwise outside).
      glm::dvec3 u(0.0), v(0.0);
      u[(axis + 1) % 3] = 1;
      v[(axis + 2) % 3] = 1;
      if (sign < 0) std::swap(u, v);
      const auto base = static_cast<unsigned>(m.position.size());
      const int corners[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
      for (const auto& c : corners) {
        m.position.push_back(h * (n + double(c[0]) * u + double(c[1]) * v));
        m.normal.push_back(n);
        m.colour.push_back(colour);
      }
      m.triangle.push_back({base, base + 1, base + 2});
      m.triangle.push_back({base, base + 2, base + 3});
    }
  }
  return m;
}

// Tetrahedron with a front face (normal +Z) in the plane z = 0.2, flat faces (12 vertices),
// the apex behind it pale blue, every other vertex blue.
AssetMesh tetrahedron() {
  const glm::dvec3 p[4] = {{-0.3, -0.25, 0.2}, {0.3, -0.25, 0.2}, {0, 0.3, 0.2}, {0, 0, -0.3}};
  const glm::dvec3 centroid = (p[0] + p[1] + p[2] + p[3]) / 4.0;
  AssetMesh m;
  m.name = "tetra";
  for (const auto& f :
       {glm::uvec3{0, 1, 2}, glm::uvec3{0, 2, 3}, glm::uvec3{2, 1, 3}, glm::uvec3{1, 0, 3}}) {
    glm::uvec3 t = f;
    glm::dvec3 n = glm::cross(p[t.y] - p[t.x], p[t.z] - p[t.x]);
    if (glm::dot(n, p[t.x] - centroid) < 0) {
      std::swap(t.y, t.z);
      n = -n;
    }
    const auto base = static_cast<unsigned>(m.position.size());
    for (unsigned k = 0; k < 3; ++k) {
      m.position.push_back(p[t[k]]);
      m.normal.push_back(glm::normalize(n));
      m.colour.push_back(t[k] == 3 ? kPaleBlue : kBlue);
    }
    m.triangle.push_back({base, base + 1, base + 2});
  }
  return m;
}

// Seen from +Z: a red cube left and low, the same cube turned, up in the middle, a blue
// tetrahedron right and low, its front face's tip turned to the left; a directional light from the
// upper right front and a point light above and behind (it does not reach the faces that face the
// camera).
SceneAssets test_scene() {
  SceneAssets s;
  s.name = "pov test";
  s.meshes = {coloured_cube("cube", 0.5, kRed), tetrahedron()};
  AssetInstance left{"left cube", 0, glm::dquat(1, 0, 0, 0), {-0.8, -0.3, 0}};
  AssetInstance top{
      "top_cube", 0, glm::angleAxis(0.6, glm::normalize(glm::dvec3(1, 1, 0))), {0, 0.6, 0}};
  AssetInstance right{"right_tetra",
                      1,
                      glm::angleAxis(kPi / 2, glm::dvec3(0, 0, 1)),
                      {0.8, -0.3, 0}};  // turned: its tip points left (-X)
  s.instances = {left, top, right};
  s.camera.eye = {0, 0, 3};
  s.camera.target = {0, 0, 0};
  s.camera.up = {0, 1, 0};
  s.camera.fov_y_deg = 40;
  s.camera.aspect = 4.0 / 3;
  AssetLight sun;
  sun.name = "sun";
  sun.type = LightType::Directional;
  sun.direction = glm::normalize(glm::dvec3(-0.5, -0.5, -1));
  sun.intensity = kPi * kLumensPerWatt;  // POV-Ray brightness 1
  AssetLight lamp;
  lamp.name = "lamp";
  lamp.type = LightType::Point;
  lamp.position = {0, 2, -1};
  lamp.intensity = 10 * kLumensPerWatt;
  s.lights = {sun, lamp};
  s.background = kBackground;
  s.width = 120;
  s.height = 90;
  return s;
}

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// The block "KEYWORD { N, ... }" after `from`: N and the number of entries starting with
// `entry` (e.g. '<' for vectors, "texture" for textures).
struct Block {
  int declared = -1;
  size_t entries = 0;
};
Block block(const std::string& text, size_t from, const std::string& keyword,
            const std::string& entry) {
  Block b;
  const size_t open = text.find(keyword + " {", from);
  if (open == std::string::npos) return b;
  const size_t close = text.find("\n  }", open);
  const std::string body =
      text.substr(open + keyword.size() + 2, close - open - keyword.size() - 2);
  b.declared = std::stoi(body);
  b.entries = count(body, entry);
  return b;
}

TEST(PovExport, DeterministicAndStructured) {
  const SceneAssets s = test_scene();
  const std::string a = scene_to_pov(s), b = scene_to_pov(s);
  EXPECT_EQ(a, b);
  EXPECT_NE(a.find("#version 3.7;"), std::string::npos);
  // No sky in the test scene: no ambient light; a sky of ambient_lux gives a white face its
  // radiance, ambient_lux / (683 pi), as Blender's world does.
  EXPECT_NE(a.find("global_settings { assumed_gamma 1.0 ambient_light rgb <0, 0, 0> }"),
            std::string::npos);
  SceneAssets sky = s;
  sky.ambient_lux = 0.12 * kPi * kLumensPerWatt;
  EXPECT_NE(scene_to_pov(sky).find("ambient_light rgb <0.12, 0.12, 0.12> }"), std::string::npos);
  EXPECT_NE(a.find("background { rgb <0.05, 0.25, 0.1> }"), std::string::npos);
  EXPECT_NE(a.find("metres"), std::string::npos);
  EXPECT_EQ(count(a, "light_source {"), 2u);
  EXPECT_EQ(count(a, "parallel"), 1u);

  // Each mesh declared once, used once per instance.
  EXPECT_EQ(count(a, "= mesh2 {"), 2u);
  EXPECT_EQ(count(a, "#declare Mesh_0_cube = mesh2"), 1u);
  EXPECT_EQ(count(a, "#declare Mesh_1_tetra = mesh2"), 1u);
  EXPECT_EQ(count(a, "object {"), 3u);
  EXPECT_EQ(count(a, "Mesh_0_cube\n"), 2u);
  EXPECT_EQ(count(a, "Mesh_1_tetra\n"), 1u);

  // Entry counts match the meshes; colours are deduplicated (cube: 1, tetrahedron: 2).
  const size_t distinct[2] = {1, 2};
  for (size_t k = 0; k < s.meshes.size(); ++k) {
    const auto& m = s.meshes[k];
    const size_t at = a.find("#declare Mesh_" + std::to_string(k));
    ASSERT_NE(at, std::string::npos);
    const Block v = block(a, at, "vertex_vectors", "<");
    const Block n = block(a, at, "normal_vectors", "<");
    const Block t = block(a, at, "texture_list", "texture {");
    const Block f = block(a, at, "face_indices", "<");
    EXPECT_EQ(v.declared, static_cast<int>(m.position.size()));
    EXPECT_EQ(v.entries, m.position.size());
    EXPECT_EQ(n.declared, static_cast<int>(m.normal.size()));
    EXPECT_EQ(n.entries, m.normal.size());
    EXPECT_EQ(t.declared, static_cast<int>(distinct[k]));
    EXPECT_EQ(t.entries, distinct[k]);
    EXPECT_EQ(f.declared, static_cast<int>(m.triangle.size()));
    EXPECT_EQ(f.entries, m.triangle.size());
  }
  // Names are sanitised in comments.
  EXPECT_NE(a.find("// Instance 0: left_cube"), std::string::npos);
  EXPECT_NE(a.find("// pov_test:"), std::string::npos);

  // The file is the same text, written atomically (no temporary left beside it).
  const fs::path dir = test::fresh_dir("pov_export");
  write_scene_pov(dir / "scene.pov", s);
  EXPECT_EQ(test::read_file(dir / "scene.pov"), a);
  EXPECT_EQ(test::files_in(dir), std::vector<std::string>{"scene.pov"});
}

TEST(PovExport, StrokePointsThatWriteAlikeMakeNoDegenerateCone) {
  // Two points 0.2 um apart (more than the 0.1 um that used to tell points apart) are distinct
  // but write alike with 6 significant digits near 1 m: a cone between them would have equal
  // ends, which POV-Ray refuses ("Degenerate cone/cylinder", a fatal parse error).
  const SceneAssets assets = test_scene();
  Stroke stroke;
  stroke.points = {{1.0, 0.1, 0.2}, {1.0000002, 0.1, 0.2}, {1.01, 0.12, 0.2}, {1.01, 0.12, 0.2}};
  stroke.width_px = {1, 1, 1, 1};
  Stroke closed = stroke;
  closed.closed = true;
  closed.points = {{1.1, 0.1, 0.2}, {1.12, 0.1, 0.2}, {1.1000002, 0.1, 0.2}};
  closed.width_px = {1, 1, 1};
  const std::vector<Stroke> strokes = {stroke, closed};
  const std::string pov = scene_to_pov(assets, &strokes);
  size_t cones = 0;
  for (size_t at = pov.find("cone { "); at != std::string::npos; at = pov.find("cone { ", at + 1)) {
    const size_t a0 = pov.find('<', at), a1 = pov.find('>', a0);
    const size_t b0 = pov.find('<', a1), b1 = pov.find('>', b0);
    EXPECT_NE(pov.substr(a0, a1 - a0), pov.substr(b0, b1 - b0)) << pov.substr(at, b1 - at);
    ++cones;
  }
  EXPECT_GE(cones, 2u);
}

TEST(PovExport, InstanceMatrixIsRowVectorForm) {
  SceneAssets s = test_scene();
  // 90 degrees about +Y maps x to -z and z to x; POV-Ray's rows are the images of x, y, z.
  s.instances = {{"turned", 0, glm::angleAxis(kPi / 2, glm::dvec3(0, 1, 0)), {1, 2, -0.5}}};
  const std::string text = scene_to_pov(s);
  EXPECT_NE(text.find("matrix <0, 0, -1, 0, 1, 0, 1, 0, 0, 1, 2, -0.5>"), std::string::npos)
      << text.substr(text.find("object {"));
}

TEST(PovExport, NumbersAndEdgeCases) {
  SceneAssets s = test_scene();
  s.meshes[0].position[4] = {-0.0, 1e-7, 123456789.0};  // not on the +X face
  s.meshes[0].normal[1] = {0, 0, 0};  // on the +X face: becomes +X, its face normal
  AssetMesh empty;
  empty.name = "empty";
  s.meshes.push_back(empty);
  s.instances.push_back({"nothing", 2, glm::dquat(1, 0, 0, 0), {0, 0, 0}});
  const std::string text = scene_to_pov(s);
  EXPECT_NE(text.find("\n<0,1e-07,1.23457e+08>,\n"), std::string::npos);
  const size_t normals = text.find("normal_vectors");
  ASSERT_NE(normals, std::string::npos);
  const std::string cube_normals = text.substr(normals, text.find("}", normals) - normals);
  EXPECT_EQ(cube_normals.find("<0,0,0>"), std::string::npos) << "a zero normal was written";
  EXPECT_EQ(count(cube_normals, "<1,0,0>"), 4u) << cube_normals;
  EXPECT_EQ(text.find("Mesh_2_empty"), std::string::npos) << "an empty mesh was declared";
  EXPECT_EQ(text.find("nan"), std::string::npos);
}

TEST(PovExport, RefusesBrokenAssets) {
  const SceneAssets good = test_scene();
  SceneAssets s = good;
  s.meshes[0].triangle[0].z = 24;
  EXPECT_THROW(scene_to_pov(s), InternalError);
  s = good;
  s.meshes[1].colour.pop_back();
  EXPECT_THROW(scene_to_pov(s), InternalError);
  s = good;
  s.instances[0].mesh = 2;
  EXPECT_THROW(scene_to_pov(s), InternalError);
  s = good;
  s.camera.up = {0, 0, 1};  // parallel to the view direction
  EXPECT_THROW(scene_to_pov(s), InternalError);
  s = good;
  s.meshes[0].position[3].x = std::nan("");
  EXPECT_THROW(scene_to_pov(s), InternalError);
  s = good;
  s.lights[0].direction = {0, 0, 0};
  EXPECT_THROW(scene_to_pov(s), InternalError);
}

// Pixel (column, row from the top) of scene point `p` under the OpenGL pinhole of `c`.
glm::dvec2 project(const AssetCamera& c, const glm::dvec3& p, int width, int height) {
  const glm::dvec3 f = glm::normalize(c.target - c.eye);
  const glm::dvec3 r = glm::normalize(glm::cross(f, c.up));
  const glm::dvec3 u = glm::cross(r, f);
  const glm::dvec3 d = p - c.eye;
  const double t = std::tan(c.fov_y_deg * kPi / 360);
  const double x_ndc = glm::dot(d, r) / (glm::dot(d, f) * t * c.aspect);
  const double y_ndc = glm::dot(d, u) / (glm::dot(d, f) * t);
  return {(x_ndc + 1) / 2 * width, (1 - y_ndc) / 2 * height};
}

struct Png {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  // Linear RGB of the pixel containing image point `at`.
  glm::dvec3 linear(const glm::dvec2& at) const {
    const int x = static_cast<int>(at.x), y = static_cast<int>(at.y);
    const unsigned char* p = &rgb[3 * (static_cast<size_t>(y) * width + x)];
    return srgb_to_linear(glm::dvec3(p[0], p[1], p[2]) / 255.0);
  }
  glm::dvec3 srgb8(int x, int y) const {
    const unsigned char* p = &rgb[3 * (static_cast<size_t>(y) * width + x)];
    return {p[0], p[1], p[2]};
  }
};

Png read_png(const fs::path& path) {
  const std::string bytes = test::read_file(path);
  Png png;
  int channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                            static_cast<int>(bytes.size()), &png.width, &png.height, &channels, 3);
  if (pixels == nullptr) return png;
  png.rgb.assign(pixels, pixels + 3 * png.width * png.height);
  stbi_image_free(pixels);
  return png;
}

bool reddish(const glm::dvec3& c) { return c.r > 3 * c.g && c.r > 3 * c.b && c.r > 0.05; }
bool bluish(const glm::dvec3& c) { return c.b > 3 * c.r && c.b > 2 * c.g && c.b > 0.05; }

TEST(PovExport, RendersLikeTheOpenGlCamera) {
  const SceneAssets s = test_scene();
  const fs::path dir = test::fresh_dir("pov_export_render");
  write_scene_pov(dir / "scene.pov", s);
  PovrayOptions options;
  options.threads = 2;
  render_povray(dir / "scene.pov", dir / "scene.png", s.width, s.height, options);
  const Png png = read_png(dir / "scene.png");
  ASSERT_EQ(png.width, s.width);
  ASSERT_EQ(png.height, s.height);

  // Background where nothing is: the corners, sRGB of the linear background.
  const glm::dvec3 bg = 255.0 * linear_to_srgb(kBackground);
  const int corners[4][2] = {
      {0, 0}, {s.width - 1, 0}, {0, s.height - 1}, {s.width - 1, s.height - 1}};
  for (const auto& c : corners) {
    EXPECT_LE(glm::length(png.srgb8(c[0], c[1]) - bg), 2.5) << "corner " << c[0] << "," << c[1];
  }

  // The left cube's front face (normal +Z) at its centre: ambient + Lambert from the sun
  // (brightness 1, cos = n . -direction), no specular there, the lamp behind it.
  const glm::dvec3 left_front = s.instances[0].translation + glm::dvec3(0, 0, 0.25);
  const glm::dvec2 left_px = project(s.camera, left_front, s.width, s.height);
  const double cos_sun = glm::dot(glm::dvec3(0, 0, 1), -s.lights[0].direction);
  const glm::dvec3 expected = kRed * (0.15 + 0.8 * cos_sun);
  const glm::dvec3 got = png.linear(left_px);
  EXPECT_NEAR(got.r, expected.r, 0.03);
  EXPECT_NEAR(got.g, expected.g, 0.01);
  EXPECT_NEAR(got.b, expected.b, 0.01);
  EXPECT_LT(left_px.x, s.width / 2.0);

  // Red left, blue right, and not the other way round (the image is not mirrored).
  const glm::dvec3 tetra_front = s.instances[2].translation + glm::dvec3(0.2 / 3, 0, 0.2);
  const glm::dvec2 right_px = project(s.camera, tetra_front, s.width, s.height);
  EXPECT_TRUE(reddish(png.linear(left_px)));
  EXPECT_TRUE(bluish(png.linear(right_px)));
  EXPECT_FALSE(reddish(png.linear({s.width - 1 - left_px.x, left_px.y})));
  EXPECT_FALSE(bluish(png.linear({s.width - 1 - right_px.x, right_px.y})));
  double red_x = 0, blue_x = 0;
  int reds = 0, blues = 0;
  for (int y = 0; y < png.height; ++y) {
    for (int x = 0; x < png.width; ++x) {
      const glm::dvec3 c = png.linear({x + 0.5, y + 0.5});
      if (reddish(c) && y > png.height / 2) red_x += x, ++reds;
      if (bluish(c)) blue_x += x, ++blues;
    }
  }
  ASSERT_GT(reds, 20);
  ASSERT_GT(blues, 20);
  EXPECT_LT(red_x / reds, png.width / 2.0);
  EXPECT_GT(blue_x / blues, png.width / 2.0);

  // The tetrahedron's front face turned a quarter counter-clockwise (seen from +Z): its tip
  // (0, 0.3) went to (-0.3, 0), so (0.2, 0.2) is on the face and (-0.2, 0.2) is not; the
  // transposed (inverse) rotation would give the opposite.
  const glm::dvec3 tetra_at = s.instances[2].translation + glm::dvec3(0, 0, 0.2);
  EXPECT_TRUE(
      bluish(png.linear(project(s.camera, tetra_at + glm::dvec3(0.2, 0.2, 0), s.width, s.height))));
  EXPECT_FALSE(bluish(
      png.linear(project(s.camera, tetra_at + glm::dvec3(-0.2, 0.2, 0), s.width, s.height))));

  // The turned cube is up (not flipped vertically): its centre shows red, the point mirrored
  // across the horizontal midline shows background.
  const glm::dvec2 top_px = project(s.camera, s.instances[1].translation, s.width, s.height);
  EXPECT_LT(top_px.y, s.height / 2.0);
  EXPECT_TRUE(reddish(png.linear(top_px)));
  const glm::dvec3 below =
      png.srgb8(static_cast<int>(top_px.x), s.height - 1 - static_cast<int>(top_px.y));
  EXPECT_LE(glm::length(below - bg), 2.5);
}

TEST(PovExport, ARoughClearCoatGetsADimmerWiderPhong) {
  SceneAssets s = test_scene();
  s.materials.push_back(
      {"cut", {.roughness = 0.85, .clearcoat = 0.4, .clearcoat_roughness = 0.45}});
  s.meshes[0].primitives = {{0, s.meshes[0].triangle.size(), 1}};
  // 0.6 * 0.4 * (0.15 / 0.5)^1.5 = 0.03944: as dim as glTF's lobe spread over a rough film,
  // not the 0.24 of a sharp one, whose peak a phong keeps however wide it is.
  EXPECT_EQ(count(scene_to_pov(s), "#declare Cutaway_Finish_1 = finish { ambient 1 diffuse 1 "
                                   "specular 0.09375 roughness 0.036625 phong 0.039436 "
                                   "phong_size 8 }"),
            1u);
}

TEST(PovExport, AFinishPerMaterialOnTheFacesThatUseIt) {
  SceneAssets s = test_scene();
  s.materials.push_back(
      {"cut",
       {.roughness = 0.2, .translucency = 0.5, .clearcoat = 0.8, .clearcoat_roughness = 0.05}});
  // Mesh 0: its first two triangles plain, the rest wet.
  const size_t n = s.meshes[0].triangle.size();
  s.meshes[0].primitives = {{0, 2, 0}, {2, n - 2, 1}};
  const std::string text = scene_to_pov(s);
  EXPECT_EQ(count(text, "#declare Cutaway_Finish = finish { ambient 1 diffuse 1 specular "
                        "0.25 roughness 0.02 }"),
            1u);
  // Translucency as POV-Ray 3.7's backside illumination; the clear coat as a sharp phong.
  EXPECT_EQ(count(text, "#declare Cutaway_Finish_1 = finish { ambient 1 diffuse 1, 0.5 "
                        "specular 0.5 roughness 0.0025 phong 0.48 phong_size 40 }"),
            1u)
      << text.substr(0, 2000);
  EXPECT_GE(count(text, "finish { Cutaway_Finish_1 }"), 1u);
  // Every texture of mesh 1 (no primitives) uses the plain finish.
  const size_t mesh1 = text.find("// Mesh 1");
  ASSERT_NE(mesh1, std::string::npos);
  const std::string body = text.substr(mesh1, text.find("// Mesh 2") - mesh1);
  EXPECT_EQ(count(body, "Cutaway_Finish_1"), 0u);
  // POV-Ray reads it.
  const fs::path dir = test::fresh_dir("pov_export_materials");
  write_scene_pov(dir / "scene.pov", s);
  PovrayOptions options;
  options.threads = 2;
  render_povray(dir / "scene.pov", dir / "scene.png", s.width, s.height, options);
  EXPECT_EQ(read_png(dir / "scene.png").width, s.width);
  // A material index out of range is refused.
  s.meshes[0].primitives[1].material = 2;
  EXPECT_THROW(scene_to_pov(s), InternalError);
}

TEST(PovExport, TexturedFacesUseTheirImageBesideTheScene) {
  // Mesh 0 (a red cube) mapped onto a 16 x 16 texture, blue on the left, yellow on the right;
  // its image as PNG and as JPEG.
  SceneAssets s = test_scene();
  test::texture_with_halves(s, 0, 16);
  for (const auto& [format, type, file] :
       {std::tuple{TextureFormat::Png, "png", "scene_halves.png"},
        std::tuple{TextureFormat::Jpeg, "jpeg", "scene_halves.jpg"}}) {
    SCOPED_TRACE(type);
    const fs::path dir = test::fresh_dir(std::string("pov_export_texture_") + type);
    write_scene_pov(dir / "scene.pov", s, nullptr, format);
    EXPECT_EQ(test::files_in(dir), (std::vector<std::string>{"scene.pov", file}));
    const std::string text = test::read_file(dir / "scene.pov");
    EXPECT_EQ(count(text, std::string("image_map { ") + type + " \"" + file + "\" interpolate 2 }"),
              1u);
    EXPECT_EQ(count(text, "uv_vectors {"), 1u);
    // No uv_indices: POV-Ray takes the face indices (the render below shows both halves).
    EXPECT_EQ(count(text, "uv_indices {"), 0u);
    PovrayOptions options;
    options.threads = 2;
    render_povray(dir / "scene.pov", dir / "scene.png", s.width, s.height, options);
    const test::PngInfo png = test::png_info(dir / "scene.png");
    EXPECT_GT(png.blue, 20u);
    EXPECT_GT(png.yellow, 20u);
  }
  // Without texture files the faces keep their vertex colours.
  EXPECT_EQ(count(scene_to_pov(s), "image_map"), 0u);
}

TEST(PovExport, AHeightMapBumpsTheTexturedFacesByItsBumpSize) {
  SceneAssets s = test_scene();
  test::texture_with_halves(s, 0, 16);
  const fs::path dir = test::fresh_dir("pov_export_relief");
  PovrayOptions options;
  options.threads = 2;
  write_scene_pov(dir / "plain.pov", s, nullptr, TextureFormat::Png);
  render_povray(dir / "plain.pov", dir / "plain.png", s.width, s.height, options);
  // Ridges four texels apart across the texture, one texel slope 0.8 per full grey step.
  AssetTexture ridges{"relief", 16, 16, 1, {}, false, true};
  for (int y = 0; y < 16; ++y)
    for (int x = 0; x < 16; ++x) ridges.pixels.push_back(x % 4 == 0 ? 255 : 0);
  s.textures.push_back(ridges);
  s.materials.back().height_texture = static_cast<int>(s.textures.size()) - 1;
  s.materials.back().height_bump = 0.8;
  write_scene_pov(dir / "scene.pov", s, nullptr, TextureFormat::Png);
  const std::string text = test::read_file(dir / "scene.pov");
  EXPECT_EQ(count(text, "image_map { png \"scene_halves.png\" interpolate 2 } } normal { "
                        "bump_map { png \"scene_relief.png\" interpolate 2 bump_size 0.8 } }"),
            1u);
  render_povray(dir / "scene.pov", dir / "scene.png", s.width, s.height, options);
  // The ridges change the shading of the cube's faces, not where it is.
  const std::vector<uint8_t> plain = decode_png(test::read_file(dir / "plain.png")).rgba;
  const std::vector<uint8_t> bumped = decode_png(test::read_file(dir / "scene.png")).rgba;
  ASSERT_EQ(plain.size(), bumped.size());
  size_t changed = 0;
  for (size_t i = 0; i < plain.size(); ++i) changed += std::abs(plain[i] - bumped[i]) > 8;
  EXPECT_GT(changed, 200u);
  // Without texture files there is no bump either.
  EXPECT_EQ(count(scene_to_pov(s), "bump_map"), 0u);
}

}  // namespace
}  // namespace cutaway
