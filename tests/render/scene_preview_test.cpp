// render_scene_preview (render/scene_preview.h): image size, background, where instances
// project (not mirrored, camera convention), lighting, quaternion placement, textured
// materials (sRGB decoding, glTF texture coordinates, wrapping in u), determinism, refusals.
// Small images keep it fast on software OpenGL. A failing test leaves its image in
// build/test-tmp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "base/colour.h"
#include "base/constants.h"
#include "render/scene_preview.h"
#include "test_support.h"

namespace cutaway {
namespace {

constexpr int kPreviewWidth = 160, kPreviewHeight = 120;

/// An axis-aligned box about the origin with half-extents `half` (metres), one colour, flat
/// faces (4 vertices each, outward normals, counter-clockwise seen from outside).
AssetMesh box(const std::string& name, const glm::dvec3& half, const glm::dvec3& colour,
              const glm::dvec3& offset = glm::dvec3(0.0)) {
  AssetMesh m;
  m.name = name;
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      glm::dvec3 n(0.0), u(0.0), v(0.0);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1;  // u x v = +axis; swapped for the negative side
      v[(axis + 2) % 3] = 1;
      if (sign < 0) std::swap(u, v);
      const auto base = static_cast<unsigned>(m.position.size());
      for (const auto& [a, b] : {std::pair{-1, -1}, {1, -1}, {1, 1}, {-1, 1}}) {
        m.position.push_back(offset + half * (n + double(a) * u + double(b) * v));
        m.normal.push_back(n);
        m.colour.push_back(colour);
      }
      m.triangle.push_back({base, base + 1, base + 2});
      m.triangle.push_back({base, base + 2, base + 3});
    }
  }
  return m;
}

AssetInstance instance(const std::string& name, int mesh, const glm::dvec3& translation,
                       const glm::dquat& rotation = glm::dquat(1, 0, 0, 0)) {
  AssetInstance i;
  i.name = name;
  i.mesh = mesh;
  i.translation = translation;
  i.rotation = rotation;
  return i;
}

/// A red cube left of the origin, a green cube right of it, seen from the front and above;
/// the light comes from behind and above, so the front faces (+Z) are turned away from it.
SceneAssets two_cubes() {
  SceneAssets a;
  a.name = "two_cubes";
  a.meshes.push_back(box("red_cube", glm::dvec3(0.15), {0.8, 0.05, 0.05}));
  a.meshes.push_back(box("green_cube", glm::dvec3(0.15), {0.05, 0.6, 0.05}));
  a.instances.push_back(instance("red", 0, {-0.3, 0, 0}));
  a.instances.push_back(instance("green", 1, {0.3, 0, 0}));
  a.camera.eye = {0, 0.6, 1.2};
  a.camera.target = {0, 0, 0};
  a.camera.up = {0, 1, 0};
  a.camera.fov_y_deg = 40;
  a.camera.znear = 0.05;
  a.camera.zfar = 10;
  AssetLight sun;
  sun.name = "sun";
  sun.direction = glm::normalize(glm::dvec3(0, -0.6, 0.8));  // travels down and toward +Z
  sun.intensity = 3 * kLumensPerWatt;  // a sun of 3 W/m^2: a white face lit head-on shows 0.95
  a.lights.push_back(sun);
  a.ambient_lux = 0.12 * kPi * kLumensPerWatt;  // the studio sky: 0.12 from above
  a.background = {0.25, 0.5, 0.75};             // exact in half floats
  a.width = kPreviewWidth;
  a.height = kPreviewHeight;
  return a;
}

/// The pixel (x right, y down from the top) that the scene point `p` projects to, with the
/// camera convention of AssetCamera (glm::lookAt + glm::perspective, image aspect).
glm::ivec2 project(const SceneAssets& a, const glm::dvec3& p) {
  const AssetCamera& c = a.camera;
  const glm::dmat4 clip_from_scene =
      glm::perspective(glm::radians(c.fov_y_deg), double(a.width) / a.height, c.znear, c.zfar) *
      glm::lookAt(c.eye, c.target, c.up);
  const glm::dvec4 clip = clip_from_scene * glm::dvec4(p, 1.0);
  const double x = (0.5 + 0.5 * clip.x / clip.w) * a.width;
  const double y = (0.5 - 0.5 * clip.y / clip.w) * a.height;
  return {static_cast<int>(std::floor(x)), static_cast<int>(std::floor(y))};
}

glm::ivec3 pixel(const Image& im, const glm::ivec2& at) {
  EXPECT_TRUE(at.x >= 0 && at.x < im.width && at.y >= 0 && at.y < im.height);
  const size_t i = (static_cast<size_t>(at.y) * im.width + at.x) * 4;
  return {im.rgba[i], im.rgba[i + 1], im.rgba[i + 2]};
}

glm::ivec3 srgb8(const glm::dvec3& linear) {
  const glm::dvec3 s = linear_to_srgb(linear);
  return {int(std::lround(255 * s.r)), int(std::lround(255 * s.g)), int(std::lround(255 * s.b))};
}

/// Writes `im` for inspection; returns where.
std::string keep(const Image& im, const std::string& name) {
  const auto path = test::fresh_dir("scene_preview") / (name + ".png");
  write_png(path, im);
  return path.string();
}

TEST(ScenePreview, DrawsTheCubesWhereTheCameraSeesThem) {
  const SceneAssets a = two_cubes();
  ScenePreviewOptions o;
  o.samples = 4;
  const Image im = render_scene_preview(a, o);
  ASSERT_EQ(im.width, kPreviewWidth);
  ASSERT_EQ(im.height, kPreviewHeight);
  ASSERT_EQ(im.rgba.size(), static_cast<size_t>(kPreviewWidth) * kPreviewHeight * 4);
  for (size_t i = 3; i < im.rgba.size(); i += 4) ASSERT_EQ(im.rgba[i], 255);

  const glm::ivec3 background = srgb8(a.background);
  for (const glm::ivec2 corner :
       {glm::ivec2(0, 0), glm::ivec2(kPreviewWidth - 1, 0), glm::ivec2(0, kPreviewHeight - 1),
        glm::ivec2(kPreviewWidth - 1, kPreviewHeight - 1)})
    EXPECT_EQ(pixel(im, corner), background) << corner.x << "," << corner.y;

  // The centres of the front faces (+Z, toward the camera): red on the left, green on the right.
  const glm::ivec2 red_at = project(a, {-0.3, 0, 0.15});
  const glm::ivec2 green_at = project(a, {0.3, 0, 0.15});
  ASSERT_LT(red_at.x, kPreviewWidth / 2);
  ASSERT_GT(green_at.x, kPreviewWidth / 2);
  const glm::ivec3 red = pixel(im, red_at), green = pixel(im, green_at);
  EXPECT_GT(red.r, red.g + 40) << red.r << " " << red.g << " " << red.b;
  EXPECT_GT(red.r, red.b + 40);
  EXPECT_GT(green.g, green.r + 40) << green.r << " " << green.g << " " << green.b;
  EXPECT_GT(green.g, green.b + 40);
  // Between the cubes, and above them, is background.
  EXPECT_EQ(pixel(im, project(a, {0, 0, 0.15})), background);
  EXPECT_EQ(pixel(im, project(a, {-0.3, 0.4, 0})), background);
  // Up is up: below the cubes is background too, and the red cube's top edge is where it
  // projects (red just under it, background just over it).
  EXPECT_EQ(pixel(im, project(a, {-0.3, -0.3, 0.15})), background);
  const glm::ivec2 back_top = project(a, {-0.3, 0.15, -0.15});
  EXPECT_EQ(pixel(im, back_top - glm::ivec2(0, 2)), background);
  EXPECT_NE(pixel(im, back_top + glm::ivec2(0, 2)), background);
  if (HasFailure()) ADD_FAILURE() << "image: " << keep(im, "two_cubes");
}

TEST(ScenePreview, ALitFaceIsBrighterThanOneTurnedAway) {
  const SceneAssets a = two_cubes();
  ScenePreviewOptions o;
  o.samples = 4;
  const Image im = render_scene_preview(a, o);
  for (const double x : {-0.3, 0.3}) {
    const glm::ivec3 top = pixel(im, project(a, {x, 0.15, 0}));    // faces the light (0.6)
    const glm::ivec3 front = pixel(im, project(a, {x, 0, 0.15}));  // turned away (-0.8)
    const int top_sum = top.r + top.g + top.b, front_sum = front.r + front.g + front.b;
    EXPECT_GT(top_sum, front_sum + 60) << "x = " << x;
    EXPECT_GT(front_sum, 30) << "the ambient term keeps shadowed faces from black";
  }
  // Exposure scales the light: twice the exposure, a brighter front face.
  o.exposure = 2;
  const Image bright = render_scene_preview(a, o);
  EXPECT_GT(pixel(bright, project(a, {-0.3, 0, 0.15})).r, pixel(im, project(a, {-0.3, 0, 0.15})).r);
  EXPECT_EQ(pixel(bright, {0, 0}), srgb8(a.background));  // the background is not scaled
}

TEST(ScenePreview, PlacesInstancesOfOneMeshByQuaternionThenTranslation) {
  SceneAssets a = two_cubes();
  a.meshes.clear();
  a.instances.clear();
  // A bar from x = 0 to x = 0.5 (in its own frame), drawn twice: as it is, and turned 90
  // degrees about +Y, which takes +X to -Z (away from the camera).
  a.meshes.push_back(box("bar", {0.25, 0.03, 0.03}, {0.8, 0.05, 0.05}, {0.25, 0, 0}));
  a.instances.push_back(instance("plain", 0, {0, 0.2, 0}));
  a.instances.push_back(
      instance("turned", 0, {0, -0.2, 0}, glm::angleAxis(glm::radians(90.0), glm::dvec3(0, 1, 0))));
  ScenePreviewOptions o;
  o.samples = 1;
  const Image im = render_scene_preview(a, o);
  const glm::ivec3 background = srgb8(a.background);
  const auto on_bar = [&](const glm::dvec3& p) {
    const glm::ivec3 c = pixel(im, project(a, p));
    return c != background && c.r > c.g + 40;
  };
  EXPECT_TRUE(on_bar({0.4, 0.23, 0}));    // plain bar, its top, toward +X
  EXPECT_FALSE(on_bar({-0.2, 0.23, 0}));  // nothing at -X
  EXPECT_TRUE(on_bar({0, -0.17, -0.4}));  // turned bar, its top, toward -Z
  EXPECT_FALSE(on_bar({0.4, -0.17, 0}));
  EXPECT_FALSE(on_bar({0, -0.17, 0.3}));
  if (HasFailure()) ADD_FAILURE() << "image: " << keep(im, "bars");
}

TEST(ScenePreview, SameInputGivesSameBytesAndOptionsOverrideTheSize) {
  const SceneAssets a = two_cubes();
  ScenePreviewOptions o;
  o.width = 80;
  o.height = 60;
  const Image first = render_scene_preview(a, o);
  const Image second = render_scene_preview(a, o);
  EXPECT_EQ(first.width, 80);
  EXPECT_EQ(first.height, 60);
  EXPECT_TRUE(first.rgba == second.rgba);
}

TEST(ScenePreview, NoInstancesGiveTheBackgroundAlone) {
  SceneAssets a = two_cubes();
  a.instances.clear();
  a.lights.clear();
  const Image im = render_scene_preview(a, ScenePreviewOptions{32, 24, 1, 1.0});
  const glm::ivec3 background = srgb8(a.background);
  for (int y = 0; y < im.height; ++y)
    for (int x = 0; x < im.width; ++x) ASSERT_EQ(pixel(im, {x, y}), background);
}

TEST(ScenePreview, RefusesBadInput) {
  const ScenePreviewOptions small{16, 12, 1, 1.0};
  const auto refused = [&](SceneAssets a, ScenePreviewOptions o) {
    try {
      render_scene_preview(a, o);
    } catch (const InternalError&) {
      return true;
    }
    return false;
  };
  SceneAssets a = two_cubes();
  a.instances[1].mesh = 2;
  EXPECT_TRUE(refused(a, small));
  a = two_cubes();
  a.meshes[0].normal.pop_back();
  EXPECT_TRUE(refused(a, small));
  a = two_cubes();
  a.meshes[1].triangle[0].y = 99;
  EXPECT_TRUE(refused(a, small));
  a = two_cubes();
  a.camera.target = a.camera.eye;
  EXPECT_TRUE(refused(a, small));
  a = two_cubes();
  a.camera.up = a.camera.target - a.camera.eye;
  EXPECT_TRUE(refused(a, small));
  a = two_cubes();
  a.camera.znear = 0;
  EXPECT_TRUE(refused(a, small));
  a = two_cubes();
  a.lights.resize(17, a.lights[0]);
  EXPECT_TRUE(refused(a, small));
  a = two_cubes();
  a.instances[0].rotation = glm::dquat(0, 0, 0, 0);
  EXPECT_TRUE(refused(a, small));
  // Textures, materials, texture coordinates and primitives.
  const auto textured = [] {
    SceneAssets t = two_cubes();
    test::texture_with_halves(t, 0, 8);
    return t;
  };
  EXPECT_FALSE(refused(textured(), small));
  a = textured();
  a.materials[1].base_colour_texture = 1;
  EXPECT_TRUE(refused(a, small));
  a = textured();
  a.materials[1].material_texture = -2;
  EXPECT_TRUE(refused(a, small));
  a = textured();
  a.materials[1].pbr.roughness = 1.5;
  EXPECT_TRUE(refused(a, small));
  a = textured();
  a.textures[0].pixels.pop_back();
  EXPECT_TRUE(refused(a, small));
  a = textured();
  a.textures[0].channels = 4;  // a material map cannot be a base colour
  a.textures[0].pixels.resize(8 * 8 * 4);
  EXPECT_TRUE(refused(a, small));
  a = textured();
  a.meshes[0].uv.pop_back();
  EXPECT_TRUE(refused(a, small));
  a = textured();
  a.meshes[0].primitives[0].count -= 1;  // leaves the last triangle out
  EXPECT_TRUE(refused(a, small));
  a = textured();
  a.meshes[0].primitives[0].material = 2;
  EXPECT_TRUE(refused(a, small));
  EXPECT_TRUE(refused(two_cubes(), ScenePreviewOptions{16, 12, 0, 1.0}));
  EXPECT_TRUE(refused(two_cubes(), ScenePreviewOptions{16, 20000, 1, 1.0}));
  EXPECT_TRUE(refused(two_cubes(), ScenePreviewOptions{16, 12, 1, 0.0}));
}

/// One cube, its front (+Z) and top faces lit, seen from the front and a little above, mapped
/// onto the blue-left, yellow-right texture of test::texture_with_halves: its front face runs
/// from u = 0 at x = -0.15 to u = 1 at x = 0.15 and from v = 0 at y = -0.15 up to v = 1.
SceneAssets textured_cube() {
  SceneAssets a = two_cubes();
  a.name = "textured_cube";
  a.meshes = {box("cube", glm::dvec3(0.15), {0.8, 0.05, 0.05})};
  a.instances = {instance("cube", 0, glm::dvec3(0.0))};
  a.camera.eye = {0, 0.35, 0.9};
  a.lights[0].direction = glm::normalize(glm::dvec3(0.2, -0.5, -1));
  test::texture_with_halves(a, 0, 64);
  return a;
}

/// Whether `c` is clearly blue or clearly yellow, as test::png_info counts them.
bool blue(const glm::ivec3& c) { return c.b > 2 * c.r && c.b > 60; }
bool yellow(const glm::ivec3& c) { return c.r > 2 * c.b && c.g > 2 * c.b && c.g > 60; }

TEST(ScenePreview, TexturedMaterialsTakeTheirColourFromTheTexture) {
  const SceneAssets a = textured_cube();
  ScenePreviewOptions o;
  o.samples = 4;
  const Image im = render_scene_preview(a, o);
  const std::string path = keep(im, "textured_cube");
  // The front face: blue left of its middle, yellow right of it; the top face (u along +Z):
  // blue at the back, yellow at the front. Never the red of the vertex colours.
  for (const double x : {-0.12, -0.04})
    EXPECT_TRUE(blue(pixel(im, project(a, {x, 0, 0.15})))) << "front, x = " << x;
  for (const double x : {0.04, 0.12})
    EXPECT_TRUE(yellow(pixel(im, project(a, {x, 0, 0.15})))) << "front, x = " << x;
  EXPECT_TRUE(blue(pixel(im, project(a, {0, 0.15, -0.1}))));
  EXPECT_TRUE(yellow(pixel(im, project(a, {0, 0.15, 0.1}))));
  const test::PngInfo info = test::png_info(path);
  const size_t cube = info.not_background;
  EXPECT_GT(cube, size_t{kPreviewWidth * kPreviewHeight / 10});
  EXPECT_GT(info.blue, cube / 4);
  EXPECT_GT(info.yellow, cube / 4);
  EXPECT_GT(info.blue + info.yellow, cube * 4 / 5) << "the cube is blue and yellow but its edges";
  EXPECT_TRUE(render_scene_preview(a, o).rgba == im.rgba) << "the same input, the same bytes";

  // The texture is decoded from sRGB: the blue half looks like a vertex-coloured cube of the
  // decoded blue, to within rounding.
  SceneAssets plain = a;
  for (glm::dvec3& c : plain.meshes[0].colour) c = srgb_to_linear(glm::dvec3(20, 40, 230) / 255.0);
  plain.meshes[0].primitives.clear();
  const Image reference = render_scene_preview(plain, o);
  for (const glm::dvec3& p : {glm::dvec3(-0.1, -0.05, 0.15), glm::dvec3(0, 0.15, -0.1)}) {
    const glm::ivec3 d = pixel(im, project(a, p)) - pixel(reference, project(a, p));
    EXPECT_LE(std::max({std::abs(d.r), std::abs(d.g), std::abs(d.b)}), 1) << p.x << "," << p.z;
  }
  if (HasFailure()) ADD_FAILURE() << "image: " << path;
}

/// textured_cube() with a uniform normal map whose texels hold `rgb` (linear, relief_map.h).
SceneAssets normal_mapped_cube(glm::ivec3 rgb) {
  SceneAssets a = textured_cube();
  AssetTexture map{"relief", 4, 4, 3, {}, false, true};
  for (int i = 0; i < 16; ++i)
    for (int k = 0; k < 3; ++k) map.pixels.push_back(static_cast<uint8_t>(rgb[k]));
  a.textures.push_back(map);
  a.materials.back().normal_texture = static_cast<int>(a.textures.size()) - 1;
  return a;
}

TEST(ScenePreview, ANormalMapTiltsTheShadingUpTheTextureAndAcrossIt) {
  ScenePreviewOptions o;
  o.samples = 1;
  const Image plain = render_scene_preview(textured_cube(), o);
  const Image flat = render_scene_preview(normal_mapped_cube({128, 128, 255}), o);
  // The front face's texture runs up with v, so the map's +Y (up the texture, -v) leans its
  // normal down, away from the light (which comes from above and in front, a little from -X),
  // and -Y leans it up, toward the light; +X leans it toward +X, away from the light.
  const Image down = render_scene_preview(normal_mapped_cube({128, 192, 221}), o);
  const Image up = render_scene_preview(normal_mapped_cube({128, 64, 221}), o);
  const Image right = render_scene_preview(normal_mapped_cube({192, 128, 221}), o);
  const SceneAssets a = textured_cube();
  auto brightness = [&](const Image& im, const glm::dvec3& p) {
    const glm::ivec3 c = pixel(im, project(a, p));
    return c.r + c.g + c.b;
  };
  for (const glm::dvec3& p : {glm::dvec3(-0.08, 0, 0.15), glm::dvec3(0.08, -0.05, 0.15)}) {
    EXPECT_NEAR(brightness(flat, p), brightness(plain, p), 6) << p.x;
    EXPECT_LT(brightness(down, p), brightness(flat, p) - 30) << p.x;
    EXPECT_GT(brightness(up, p), brightness(flat, p) + 10) << p.x;
    EXPECT_LT(brightness(right, p), brightness(flat, p) - 5) << p.x;
  }
  if (HasFailure()) ADD_FAILURE() << "images: " << keep(down, "relief_down");
}

/// textured_cube() with a material map (RGBA, G roughness) of two texels: `left` roughness
/// on the front face's left half (u < 0.5), `right` on its right half; the light mirrored by
/// the front face at (-0.075, 0, 0.15) into the camera, so the left half holds the highlight.
SceneAssets material_mapped_cube(double left, double right) {
  SceneAssets a = textured_cube();
  const glm::dvec3 to_eye = glm::normalize(a.camera.eye - glm::dvec3(-0.075, 0, 0.15));
  a.lights[0].direction = -glm::dvec3(-to_eye.x, -to_eye.y, to_eye.z);  // travels to the face
  const auto g = [](double r) { return static_cast<uint8_t>(std::lround(255 * r)); };
  a.textures.push_back(
      {"material", 2, 1, 4, {255, g(left), 0, 0, 255, g(right), 0, 0}, false, true});
  a.materials.back().material_texture = static_cast<int>(a.textures.size()) - 1;
  return a;
}

TEST(ScenePreview, AMaterialMapSetsTheRoughnessPerTexel) {
  ScenePreviewOptions o;
  o.samples = 1;
  const SceneAssets a = material_mapped_cube(0.6, 0.6);
  SceneAssets plain = a;
  plain.materials.back().material_texture = -1;
  plain.materials.back().pbr.roughness = 0.6;
  const Image uniform = render_scene_preview(a, o), reference = render_scene_preview(plain, o);
  const Image glossy_left = render_scene_preview(material_mapped_cube(0.15, 1.0), o);
  const Image rough = render_scene_preview(material_mapped_cube(1.0, 1.0), o);
  auto brightness = [&](const Image& im, const glm::dvec3& p) {
    const glm::ivec3 c = pixel(im, project(a, p));
    return c.r + c.g + c.b;
  };
  const glm::dvec3 highlight(-0.075, 0, 0.15), right(0.075, 0, 0.15);
  for (const glm::dvec3& p : {highlight, right, glm::dvec3(-0.1, -0.08, 0.15)}) {
    // A map that holds the material's roughness everywhere draws as the factor alone.
    EXPECT_NEAR(brightness(uniform, p), brightness(reference, p), 3) << p.x << "," << p.y;
  }
  // The glossy texels hold a tight, strong highlight where the light is mirrored; the rough
  // half is the same in both.
  EXPECT_GT(brightness(glossy_left, highlight), brightness(rough, highlight) + 60);
  EXPECT_NEAR(brightness(glossy_left, right), brightness(rough, right), 3);
  if (HasFailure()) ADD_FAILURE() << "image: " << keep(glossy_left, "material_map");
}

TEST(ScenePreview, AClearCoatMirrorsTheLightOverARoughBase) {
  // A rough face (roughness 1 everywhere) with the light mirrored at (-0.075, 0, 0.15).
  ScenePreviewOptions o;
  o.samples = 1;
  const SceneAssets rough = material_mapped_cube(1.0, 1.0);
  SceneAssets wet = rough;
  wet.materials.back().pbr.clearcoat = 1.0;
  wet.materials.back().pbr.clearcoat_roughness = 0.05;
  SceneAssets wide = wet;  // the same light as a disc 30 degrees across
  wide.lights[0].angle_deg = 30;
  const Image bare = render_scene_preview(rough, o), coated = render_scene_preview(wet, o);
  const Image disc = render_scene_preview(wide, o);
  auto brightness = [&](const Image& im, const glm::dvec3& p) {
    const glm::ivec3 c = pixel(im, project(rough, p));
    return c.r + c.g + c.b;
  };
  const glm::dvec3 mirrored(-0.075, 0, 0.15), beside(-0.02, 0, 0.15), far(0.1, -0.08, 0.15);
  // The coat mirrors the light where it is mirrored, far brighter than the rough base, and
  // only there; a disc of light spreads the mirrored patch, weaker at its centre.
  EXPECT_GT(brightness(coated, mirrored), brightness(bare, mirrored) + 150);
  EXPECT_NEAR(brightness(coated, far), brightness(bare, far), 12);
  EXPECT_GT(brightness(disc, beside), brightness(coated, beside) + 30);
  EXPECT_LT(brightness(disc, mirrored), brightness(coated, mirrored));
  if (HasFailure())
    ADD_FAILURE() << "images: " << keep(coated, "clearcoat") << ", " << keep(disc, "disc");
}

TEST(ScenePreview, TextureCoordinatesFollowGltfAndRepeatInUWhereTheTextureWraps) {
  SceneAssets a = textured_cube();
  ScenePreviewOptions o;
  o.samples = 4;
  // u from 0 to 2 across each face. A texture that wraps in u: blue, yellow, blue, yellow from
  // left to right; one that does not is clamped: yellow from the middle on.
  for (glm::dvec2& uv : a.meshes[0].uv) uv.x *= 2;
  a.textures[0].wrap_u = true;
  const Image repeated = render_scene_preview(a, o);
  EXPECT_TRUE(blue(pixel(repeated, project(a, {-0.11, 0, 0.15}))));
  EXPECT_TRUE(yellow(pixel(repeated, project(a, {-0.04, 0, 0.15}))));
  EXPECT_TRUE(blue(pixel(repeated, project(a, {0.04, 0, 0.15}))));
  EXPECT_TRUE(yellow(pixel(repeated, project(a, {0.11, 0, 0.15}))));
  a.textures[0].wrap_u = false;
  const Image clamped = render_scene_preview(a, o);
  EXPECT_TRUE(blue(pixel(clamped, project(a, {-0.11, 0, 0.15}))));
  EXPECT_TRUE(yellow(pixel(clamped, project(a, {0.04, 0, 0.15}))));
  EXPECT_TRUE(yellow(pixel(clamped, project(a, {0.11, 0, 0.15}))));
  if (HasFailure())
    ADD_FAILURE() << "images: " << keep(repeated, "repeated_u") << ", "
                  << keep(clamped, "clamped_u");

  // Blue in the top rows of the texture: v = 0 is the top row, so blue where v is small, at
  // the bottom of the front face.
  a = textured_cube();
  AssetTexture& t = a.textures[0];
  const uint8_t top[3] = {20, 40, 230}, bottom[3] = {240, 220, 20};  // the halves' colours
  t.pixels.clear();
  for (int y = 0; y < t.height; ++y) {
    const uint8_t* colour = y < t.height / 2 ? top : bottom;
    for (int x = 0; x < t.width; ++x) t.pixels.insert(t.pixels.end(), colour, colour + 3);
  }
  const Image rows = render_scene_preview(a, o);
  EXPECT_TRUE(blue(pixel(rows, project(a, {0, -0.1, 0.15}))));
  EXPECT_TRUE(yellow(pixel(rows, project(a, {0, 0.1, 0.15}))));
  if (HasFailure()) ADD_FAILURE() << "image: " << keep(rows, "top_rows");
}

TEST(ScenePreview, DefaultMaterialsDrawExactlyAsVertexColours) {
  const SceneAssets plain = two_cubes();
  ScenePreviewOptions o;
  o.samples = 4;
  const Image reference = render_scene_preview(plain, o);
  // Texture coordinates, and primitives of another material with the default PbrMaterial,
  // change nothing; nor does a textured material on a mesh without texture coordinates.
  SceneAssets a = plain;
  a.materials.push_back({"another", PbrMaterial{}, -1});
  for (AssetMesh& m : a.meshes) {
    m.uv.assign(m.position.size(), glm::dvec2(0.5, 0.5));
    m.primitives = {{0, 4, 1, {}}, {4, m.triangle.size() - 4, 0, {}}};
  }
  EXPECT_TRUE(render_scene_preview(a, o).rgba == reference.rgba);
  a = plain;
  test::texture_with_halves(a, 0, 8);
  a.meshes[0].uv.clear();
  EXPECT_TRUE(render_scene_preview(a, o).rgba == reference.rgba);
  // A rougher material's highlight differs.
  a = plain;
  a.materials[0].pbr.roughness = 1;
  EXPECT_FALSE(render_scene_preview(a, o).rgba == reference.rgba);
}

/// A cube whose centre floats 0.2 m over a wide floor (a thin box, top at y = 0), lit by a sun
/// travelling down and toward +X at 45 degrees: its shadow falls on x 0..0.4, z -0.1..0.1.
SceneAssets cube_over_floor(double angle_deg) {
  SceneAssets a = two_cubes();
  a.meshes = {box("floor", {1.0, 0.01, 1.0}, {0.5, 0.5, 0.5}, {0, -0.01, 0}),
              box("cube", glm::dvec3(0.1), {0.5, 0.5, 0.5})};
  a.instances = {instance("floor", 0, {0, 0, 0}), instance("cube", 1, {0, 0.2, 0})};
  a.camera.eye = {0, 1.0, 1.2};
  a.camera.target = {0, 0, 0};
  a.lights[0].direction = glm::normalize(glm::dvec3(1, -1, 0));
  a.lights[0].angle_deg = angle_deg;
  return a;
}

int brightness(const Image& im, const SceneAssets& a, const glm::dvec3& p) {
  const glm::ivec3 c = pixel(im, project(a, p));
  return c.r + c.g + c.b;
}

TEST(ScenePreview, TheBrightestLightCastsASoftShadowThatTheBackdropDoesNot) {
  ScenePreviewOptions o;
  o.samples = 4;
  const SceneAssets a = cube_over_floor(12);
  const Image im = render_scene_preview(a, o);
  const int lit = brightness(im, a, {-0.4, 0, 0.3});
  // An open floor is lit alike everywhere, but for the sheen of its reflection (glTF's
  // specular lobe has long tails), which changes with the angle it is seen at.
  EXPECT_NEAR(brightness(im, a, {0.5, 0, -0.3}), lit, 9);
  // The middle of the shadow has the light's direct term removed: the sky alone is left.
  const int umbra = brightness(im, a, {0.2, 0, 0});
  EXPECT_LT(umbra, lit - 60) << "lit " << lit << ", in the shadow " << umbra;
  // Its far edge is soft: a penumbra about 3 cm either side (a 12 degree source, 0.3 m above).
  const int edge = brightness(im, a, {0.4, 0, 0});
  EXPECT_GT(edge, umbra + 10);
  EXPECT_LT(edge, lit - 10);
  // A point-like sun has a sharp edge: 2 cm beyond it fully lit, 2 cm inside fully shadowed.
  SceneAssets sharp = cube_over_floor(0);
  const Image hard = render_scene_preview(sharp, o);
  EXPECT_NEAR(brightness(hard, sharp, {0.42, 0, 0}), lit, 9);
  EXPECT_NEAR(brightness(hard, sharp, {0.38, 0, 0}), umbra, 3);
  // Staging casts no shadow: the cube as a backdrop leaves the floor lit.
  SceneAssets staged = cube_over_floor(12);
  staged.instances[1].backdrop = true;
  EXPECT_NEAR(brightness(render_scene_preview(staged, o), staged, {0.2, 0, 0}), lit, 9);
  if (HasFailure()) ADD_FAILURE() << "image: " << keep(im, "cube_over_floor");
}

}  // namespace
}  // namespace cutaway
