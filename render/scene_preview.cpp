#include "render/scene_preview.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>

#include "base/constants.h"
#include "base/error.h"
#include "render/gl/gl_buffers.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/gl/offscreen_target.h"
#include "render/gl/stroke_renderer.h"

namespace cutaway {
namespace {

constexpr int kMaxImageSide = 16384;
constexpr int kMaxLights = 16;  // shaders/scene.frag: kMaxLights
// A white Lambertian face lit head-on by E lux shows E / (683 pi) (Blender's and POV-Ray's
// mapping, doc/lighting.md).
constexpr double kReferenceLux = kLumensPerWatt * kPi;

/// One vertex as shaders/scene.vert reads it (locations 0..3).
struct SceneVertex {
  float position[3];  // metres, mesh frame
  float normal[3];    // mesh frame
  float colour[3];    // linear RGB
  float uv[2];        // texture coordinates; 0 for meshes without
};

/// One primitive of an uploaded mesh: its triangles in the shared index buffer, drawn with one
/// material.
struct MeshDraw {
  size_t first_index = 0;  // offset into the index buffer, in indices
  size_t index_count = 0;
  int texture = -1;         // base colour: index into SceneAssets::textures, or -1: vertex colours
  int normal_texture = -1;  // relief: index into SceneAssets::textures, or -1: none
  // The roughness per texel: the material map (RGBA, G roughness), or -1: `roughness` holds.
  int material_texture = -1;
  float roughness = 0;  // the material's perceptual roughness (its highlight: shaders/scene.frag)
  float clearcoat = 0, clearcoat_roughness = 0;  // its clear layer's weight and roughness
};

[[noreturn]] void fail(const std::string& what) {
  throw InternalError("render_scene_preview: " + what);
}

/// Checks everything the render reads; returns the image size (width, height).
glm::ivec2 check_input(const SceneAssets& a, const ScenePreviewOptions& o) {
  const int width = o.width != 0 ? o.width : a.width;
  const int height = o.height != 0 ? o.height : a.height;
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    fail("image size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." +
         std::to_string(kMaxImageSide));
  if (o.samples < 1) fail("samples must be >= 1, got " + std::to_string(o.samples));
  if (!(o.exposure > 0 && std::isfinite(o.exposure)))
    fail("exposure must be positive and finite, got " + std::to_string(o.exposure));
  if (a.lights.size() > kMaxLights)
    fail(std::to_string(a.lights.size()) + " lights, at most " + std::to_string(kMaxLights));
  require_valid_assets(a, {}, "render_scene_preview");
  return {width, height};
}

/// The draws of `mesh`, whose triangles start at `first_index` in the index buffer: one per
/// primitive (one of material 0 when it has none), textured where its material has a base
/// colour texture (or a normal map) and the mesh has texture coordinates.
std::vector<MeshDraw> mesh_draws(const SceneAssets& a, const AssetMesh& mesh, size_t first_index) {
  const std::vector<AssetPrimitive> plain{{0, mesh.triangle.size(), 0, {}}};
  std::vector<MeshDraw> draws;
  for (const AssetPrimitive& p : mesh.primitives.empty() ? plain : mesh.primitives) {
    const AssetMaterial& material = a.materials[static_cast<size_t>(p.material)];
    draws.push_back({first_index + 3 * p.first, 3 * p.count,
                     mesh.uv.empty() ? -1 : material.base_colour_texture,
                     mesh.uv.empty() ? -1 : material.normal_texture,
                     mesh.uv.empty() ? -1 : material.material_texture,
                     static_cast<float>(material.pbr.roughness),
                     static_cast<float>(material.pbr.clearcoat),
                     static_cast<float>(material.pbr.clearcoat_roughness)});
  }
  return draws;
}

/// Uploads `texture` (RGB or RGBA, row 0 at the top) as a GL_SRGB8 texture (GL_RGB8 or GL_RGBA8
/// when it is linear: a normal map, a material map) with mipmaps, filtered trilinearly, repeating
/// in s where it wraps in u (else clamped) and clamped in t. Row 0 lies at t = 0, so glTF texture
/// coordinates (v down from the top row) address it as they are. The texture belongs to the current
/// context, which frees it.
/// @throws InternalError when it is larger than GL_MAX_TEXTURE_SIZE
/// @throws EnvironmentError when OpenGL reports an error
GLuint upload_texture(const AssetTexture& texture, size_t index, const GlContext& context) {
  const std::string name = "texture " + std::to_string(index) + " '" + texture.name + "'";
  GLint max_side = 0;
  glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_side);
  if (texture.width > max_side || texture.height > max_side)
    fail(name + " is " + std::to_string(texture.width) + "x" + std::to_string(texture.height) +
         ", larger than GL_MAX_TEXTURE_SIZE " + std::to_string(max_side) + " on " +
         context.description());
  GLuint id = 0;
  glGenTextures(1, &id);
  glBindTexture(GL_TEXTURE_2D, id);
  if (texture.channels != 3 && !(texture.channels == 4 && texture.linear))
    fail(name + " has " + std::to_string(texture.channels) +
         " channels: a base colour or normal map has 3, a material map 4");
  const bool rgba = texture.channels == 4;
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);  // rows of channels * width bytes, unpadded
  glTexImage2D(GL_TEXTURE_2D, 0,
               rgba             ? GL_RGBA8
               : texture.linear ? GL_RGB8
                                : GL_SRGB8,
               texture.width, texture.height, 0, rgba ? GL_RGBA : GL_RGB, GL_UNSIGNED_BYTE,
               texture.pixels.data());
  glGenerateMipmap(GL_TEXTURE_2D);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, texture.wrap_u ? GL_REPEAT : GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  if (glGetError() != GL_NO_ERROR)
    throw EnvironmentError("render_scene_preview: cannot upload " + name + " on " +
                           context.description());
  return id;
}

/// A depth renderbuffer matching `target` (size and samples), attached to its framebuffer.
/// The renderbuffer belongs to the current context, which frees it.
void attach_depth_buffer(const OffscreenTarget& target, const GlContext& context) {
  target.bind();  // binds the framebuffer that is drawn into
  GLuint depth = 0;
  glGenRenderbuffers(1, &depth);
  glBindRenderbuffer(GL_RENDERBUFFER, depth);
  if (target.samples() > 1)
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, target.samples(), GL_DEPTH_COMPONENT24,
                                     target.width(), target.height());
  else
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, target.width(), target.height());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
      glGetError() != GL_NO_ERROR)
    throw EnvironmentError("render_scene_preview: cannot attach a depth buffer with " +
                           std::to_string(target.samples()) + " samples on " +
                           context.description());
}

/// Every instanced mesh once, in one vertex and one index buffer (indices already offset), and
/// the draws of its primitives.
struct SceneGeometry {
  std::vector<SceneVertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<std::vector<MeshDraw>> draws;  // per mesh; empty: not uploaded
};

/// The geometry of the meshes that some instance of `assets` shows and that have triangles.
SceneGeometry scene_geometry(const SceneAssets& assets) {
  SceneGeometry g;
  g.draws.resize(assets.meshes.size());
  std::vector<bool> used(assets.meshes.size(), false);
  for (const AssetInstance& inst : assets.instances) used[static_cast<size_t>(inst.mesh)] = true;
  for (size_t m = 0; m < assets.meshes.size(); ++m) {
    const AssetMesh& mesh = assets.meshes[m];
    if (!used[m] || mesh.triangle.empty()) continue;
    const auto base = static_cast<uint32_t>(g.vertices.size());
    for (size_t v = 0; v < mesh.position.size(); ++v) {
      SceneVertex sv{};
      for (int i = 0; i < 3; ++i) {
        sv.position[i] = static_cast<float>(mesh.position[v][i]);
        sv.normal[i] = static_cast<float>(mesh.normal[v][i]);
        sv.colour[i] = static_cast<float>(mesh.colour[v][i]);
      }
      if (!mesh.uv.empty())
        for (int i = 0; i < 2; ++i) sv.uv[i] = static_cast<float>(mesh.uv[v][i]);
      g.vertices.push_back(sv);
    }
    g.draws[m] = mesh_draws(assets, mesh, g.indices.size());
    for (const glm::uvec3& t : mesh.triangle)
      g.indices.insert(g.indices.end(), {base + t.x, base + t.y, base + t.z});
  }
  return g;
}

/// Each base colour, normal and material texture that some draw of `draws` samples, uploaded
/// once (upload_texture()); per texture of `assets`, its id (0: not uploaded).
std::vector<GLuint> upload_textures(const SceneAssets& assets,
                                    const std::vector<std::vector<MeshDraw>>& draws,
                                    const GlContext& context) {
  std::vector<GLuint> textures(assets.textures.size(), 0);
  for (const std::vector<MeshDraw>& list : draws)
    for (const MeshDraw& draw : list)
      for (const int index : {draw.texture, draw.normal_texture, draw.material_texture}) {
        if (index < 0) continue;
        const auto t = static_cast<size_t>(index);
        if (textures[t] == 0) textures[t] = upload_texture(assets.textures[t], t, context);
      }
  return textures;
}

/// Sets the uniforms of `program` (in use) that hold for the whole scene: the lights in the
/// view frame (the documented mapping: scale = colour * lux / (683 pi) * exposure), the view's up,
/// the ambient scale (the sky's radiance times the exposure) and the projection.
void set_scene_uniforms(const GlProgram& program, const SceneAssets& assets, const glm::dmat4& view,
                        const glm::mat4& clip_from_view, double exposure) {
  const glm::dmat3 view_rotation(view);
  std::vector<float> light_vector(4 * kMaxLights, 0.0f), light_scale(3 * kMaxLights, 0.0f),
      light_radius(kMaxLights, 0.0f);
  for (size_t i = 0; i < assets.lights.size(); ++i) {
    const AssetLight& light = assets.lights[i];
    glm::dvec4 v;
    if (light.type == LightType::Directional)
      v = glm::dvec4(view_rotation * -glm::normalize(light.direction), 0.0);
    else v = glm::dvec4(glm::dvec3(view * glm::dvec4(light.position, 1.0)), 1.0);
    const glm::dvec3 scale = light.colour * (light.intensity / kReferenceLux * exposure);
    for (int k = 0; k < 4; ++k) light_vector[4 * i + k] = static_cast<float>(v[k]);
    for (int k = 0; k < 3; ++k) light_scale[3 * i + k] = static_cast<float>(scale[k]);
    if (light.type == LightType::Directional)
      light_radius[i] = static_cast<float>(glm::radians(0.5 * light.angle_deg));
  }
  glUniform1i(program.uniform("light_count"), static_cast<GLint>(assets.lights.size()));
  glUniform4fv(program.uniform("light_vector"), kMaxLights, light_vector.data());
  glUniform3fv(program.uniform("light_scale"), kMaxLights, light_scale.data());
  glUniform1fv(program.uniform("light_radius"), kMaxLights, light_radius.data());
  const glm::vec3 up_view(view_rotation * glm::dvec3(0, 1, 0));
  glUniform3fv(program.uniform("up_view"), 1, glm::value_ptr(up_view));
  // The sky's radiance, ambient_lux / (683 pi), as Blender's world and POV-Ray show it.
  glUniform1f(program.uniform("ambient_scale"),
              static_cast<float>(exposure * assets.ambient_lux / kReferenceLux));
  glUniformMatrix4fv(program.uniform("clip_from_view"), 1, GL_FALSE,
                     glm::value_ptr(clip_from_view));
}

/// The locations of the uniforms set per instance and per draw (shaders/scene.vert,
/// shaders/scene.frag).
struct DrawUniforms {
  explicit DrawUniforms(const GlProgram& program)
      : view_from_object(program.uniform("view_from_object")),
        textured(program.uniform("textured")), relief(program.uniform("relief")),
        roughness_mapped(program.uniform("roughness_mapped")),
        roughness(program.uniform("roughness")), clearcoat(program.uniform("clearcoat")),
        clearcoat_roughness(program.uniform("clearcoat_roughness")) {}
  GLint view_from_object, textured, relief, roughness_mapped, roughness, clearcoat,
      clearcoat_roughness;
};

/// Scene from object transform of `inst`: its translation after its (normalised) rotation.
glm::dmat4 scene_from_object(const AssetInstance& inst) {
  return glm::translate(glm::dmat4(1.0), inst.translation) *
         glm::mat4_cast(glm::normalize(inst.rotation));
}

/// Triangles drawn between waits for the rasteriser: a software rasteriser (Mesa's llvmpipe,
/// OSMesa's) bins the triangles by screen tile in scenes of tens of MB and queues the scenes
/// for its threads, which fall behind on millions of triangles, so the queue grew to about
/// 750 MB.
constexpr size_t kTrianglesPerFinish = 200000;

/// Draws the triangles of `draw` with the program, uniforms and textures in use; waits for the
/// rasteriser (glFinish) once `pending` (triangles drawn since the last wait, updated) reaches
/// kTrianglesPerFinish. The pixels do not depend on where the waits fall.
void draw_triangles(const MeshDraw& draw, size_t& pending) {
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(draw.index_count), GL_UNSIGNED_INT,
                 reinterpret_cast<const void*>(draw.first_index * sizeof(uint32_t)));
  pending += draw.index_count / 3;
  if (pending >= kTrianglesPerFinish) {
    glFinish();
    pending = 0;
  }
}

/// Binds `target` and clears it to `background` and the far depth, with the depth test on,
/// no culling and no blending.
void clear_target(const OffscreenTarget& target, const glm::dvec3& background) {
  target.bind();
  glClearColor(static_cast<float>(background.r), static_cast<float>(background.g),
               static_cast<float>(background.b), 1.0f);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);  // two-sided: open or flipped triangles still show
  glDisable(GL_BLEND);
}

/// Draws every instance of `assets` whose mesh has draws, with the texture ids `textures`
/// (base colours bound to texture unit 0, normal maps to unit 1, material maps to unit 3).
void draw_instances(const SceneAssets& assets, const std::vector<std::vector<MeshDraw>>& draws,
                    const std::vector<GLuint>& textures, const glm::dmat4& view,
                    const DrawUniforms& uniforms) {
  size_t pending = 0;
  for (const AssetInstance& inst : assets.instances) {
    const std::vector<MeshDraw>& list = draws[static_cast<size_t>(inst.mesh)];
    if (list.empty()) continue;
    const glm::mat4 view_from_object(view * scene_from_object(inst));
    glUniformMatrix4fv(uniforms.view_from_object, 1, GL_FALSE, glm::value_ptr(view_from_object));
    for (const MeshDraw& draw : list) {
      glUniform1i(uniforms.textured, draw.texture >= 0 ? 1 : 0);
      if (draw.texture >= 0) {
        glActiveTexture(GL_TEXTURE0);
        glBindTexture(GL_TEXTURE_2D, textures[static_cast<size_t>(draw.texture)]);
      }
      glUniform1i(uniforms.relief, draw.normal_texture >= 0 ? 1 : 0);
      if (draw.normal_texture >= 0) {
        glActiveTexture(GL_TEXTURE1);
        glBindTexture(GL_TEXTURE_2D, textures[static_cast<size_t>(draw.normal_texture)]);
      }
      glUniform1i(uniforms.roughness_mapped, draw.material_texture >= 0 ? 1 : 0);
      if (draw.material_texture >= 0) {
        glActiveTexture(GL_TEXTURE3);
        glBindTexture(GL_TEXTURE_2D, textures[static_cast<size_t>(draw.material_texture)]);
      }
      glUniform1f(uniforms.roughness, draw.roughness);
      glUniform1f(uniforms.clearcoat, draw.clearcoat);
      glUniform1f(uniforms.clearcoat_roughness, draw.clearcoat_roughness);
      draw_triangles(draw, pending);
    }
  }
}

/// The shadow map of the shadow-casting light (shadow_casting_light()): a depth texture seen
/// from the light, and the transform from the scene frame to its texture coordinates and depth.
struct ShadowMap {
  int light = -1;              // index of the light whose term it darkens; -1: no shadows
  GLuint texture = 0;          // depth, GL_DEPTH_COMPONENT24, kShadowMapSide square
  glm::dmat4 from_scene{1.0};  // scene frame -> (u, v, depth) in 0..1
  double width_m = 0;          // metres the map's side spans
  double depth_m = 0;          // metres its depth 0..1 spans
  double softness = 0;         // tan of the light's angular radius
};

constexpr int kShadowMapSide = 2048;

/// Draws the depth of every instance of `assets` but the backdrop (what casts shadows) into a
/// depth texture seen from the shadow-casting light when it is directional, with an orthographic
/// view that holds shadow_casters_bounds(); the texture belongs to the current context. No
/// shadows (light -1) without such a light or without casters.
/// @throws EnvironmentError when OpenGL cannot make the map
ShadowMap draw_shadow_map(const SceneAssets& assets,
                          const std::vector<std::vector<MeshDraw>>& draws,
                          const GlContext& context) {
  ShadowMap map;
  const int caster = shadow_casting_light(assets);
  const BoundingSphere bounds = shadow_casters_bounds(assets);
  if (caster < 0 || bounds.radius <= 0) return map;
  const AssetLight& light = assets.lights[static_cast<size_t>(caster)];
  if (light.type != LightType::Directional || light.intensity <= 0) return map;

  const double r = 1.02 * bounds.radius + 1e-3;
  const glm::dvec3 direction = glm::normalize(light.direction);
  const glm::dvec3 eye = bounds.centre - direction * (r + 0.01);
  const glm::dmat4 view = glm::lookAt(eye, bounds.centre, stable_camera_up(direction));
  const glm::dmat4 clip = glm::ortho(-r, r, -r, r, 0.0, 2 * r + 0.02);
  map.light = caster;
  map.width_m = 2 * r;
  map.depth_m = 2 * r + 0.02;
  map.softness = std::tan(glm::radians(0.5 * light.angle_deg));
  map.from_scene = glm::translate(glm::dmat4(1.0), glm::dvec3(0.5)) *
                   glm::scale(glm::dmat4(1.0), glm::dvec3(0.5)) * clip * view;

  glGenTextures(1, &map.texture);
  glBindTexture(GL_TEXTURE_2D, map.texture);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_DEPTH_COMPONENT24, kShadowMapSide, kShadowMapSide, 0,
               GL_DEPTH_COMPONENT, GL_UNSIGNED_INT, nullptr);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  GLuint framebuffer = 0;
  glGenFramebuffers(1, &framebuffer);
  glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
  glFramebufferTexture2D(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_TEXTURE_2D, map.texture, 0);
  glDrawBuffer(GL_NONE);
  glReadBuffer(GL_NONE);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
      glGetError() != GL_NO_ERROR)
    throw EnvironmentError("render_scene_preview: cannot make a shadow map on " +
                           context.description());

  const GlProgram depth_program("scene.vert", "shadow.frag");
  glUseProgram(depth_program.id());
  const glm::mat4 clip_f(clip);
  glUniformMatrix4fv(depth_program.uniform("clip_from_view"), 1, GL_FALSE, glm::value_ptr(clip_f));
  const GLint view_from_object = depth_program.uniform("view_from_object");
  glViewport(0, 0, kShadowMapSide, kShadowMapSide);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glClear(GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);
  size_t pending = 0;
  for (const AssetInstance& inst : assets.instances) {
    const std::vector<MeshDraw>& list = draws[static_cast<size_t>(inst.mesh)];
    if (inst.backdrop || list.empty()) continue;
    const glm::mat4 light_from_object(view * scene_from_object(inst));
    glUniformMatrix4fv(view_from_object, 1, GL_FALSE, glm::value_ptr(light_from_object));
    for (const MeshDraw& draw : list) draw_triangles(draw, pending);
  }
  glFinish();
  return map;
}

/// Sets the shadow uniforms of `program` (in use) for `map`, seen from `view`, and binds its
/// texture to texture unit 2.
void set_shadow_uniforms(const GlProgram& program, const ShadowMap& map, const glm::dmat4& view) {
  glUniform1i(program.uniform("shadow_light"), map.light);
  glUniform1i(program.uniform("shadow_map"), 2);
  glActiveTexture(GL_TEXTURE2);
  glBindTexture(GL_TEXTURE_2D, map.texture);
  const glm::mat4 shadow_from_view(map.from_scene * glm::inverse(view));
  glUniformMatrix4fv(program.uniform("shadow_from_view"), 1, GL_FALSE,
                     glm::value_ptr(shadow_from_view));
  glUniform1f(program.uniform("shadow_width_m"), static_cast<float>(map.width_m));
  glUniform1f(program.uniform("shadow_depth_m"), static_cast<float>(map.depth_m));
  glUniform1f(program.uniform("shadow_softness"), static_cast<float>(map.softness));
}

}  // namespace

Image render_scene_preview(const SceneAssets& assets, const ScenePreviewOptions& options) {
  const glm::ivec2 size = check_input(assets, options);
  SceneGeometry geometry = scene_geometry(assets);

  const AssetCamera& camera = assets.camera;
  const glm::dmat4 view = view_from_scene(camera);
  const double aspect = static_cast<double>(size.x) / size.y;
  const glm::mat4 clip_from_view(
      glm::perspective(glm::radians(camera.fov_y_deg), aspect, camera.znear, camera.zfar));

  const std::unique_ptr<GlContext> context = create_offscreen_context();
  // The vertex array, buffers and depth renderbuffer below are not deleted one by one: they
  // belong to `context`, which frees them.
  const GlProgram program("scene.vert", "scene.frag");
  const OffscreenTarget target(*context, size.x, size.y, options.samples, "render_scene_preview");
  attach_depth_buffer(target, *context);

  make_vertex_array(geometry.vertices, geometry.indices,
                    {{0, 3, offsetof(SceneVertex, position)},
                     {1, 3, offsetof(SceneVertex, normal)},
                     {2, 3, offsetof(SceneVertex, colour)},
                     {3, 2, offsetof(SceneVertex, uv)}});
  // OpenGL holds its own copy now: ours goes before the textures and the shadow map take
  // theirs (a big scene's vertices and indices are hundreds of MB).
  std::vector<SceneVertex>().swap(geometry.vertices);
  std::vector<uint32_t>().swap(geometry.indices);
  const std::vector<GLuint> textures = upload_textures(assets, geometry.draws, *context);
  const ShadowMap shadows = draw_shadow_map(assets, geometry.draws, *context);

  glUseProgram(program.id());
  set_scene_uniforms(program, assets, view, clip_from_view, options.exposure);
  set_shadow_uniforms(program, shadows, view);
  const DrawUniforms uniforms(program);
  glUniform1i(program.uniform("base_colour"), 0);   // texture unit 0
  glUniform1i(program.uniform("normal_map"), 1);    // texture unit 1
  glUniform1i(program.uniform("material_map"), 3);  // texture unit 3 (2: the shadow map)

  clear_target(target, assets.background);
  draw_instances(assets, geometry.draws, textures, view, uniforms);
  if (options.strokes != nullptr) draw_strokes(*options.strokes, camera, size.x, size.y);

  return target.resolve_and_read();
}

}  // namespace cutaway
