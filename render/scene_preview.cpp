#include "scene_preview.h"

#include <glad/gl.h>

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

#include "gl_context.h"
#include "gl_buffers.h"
#include "gl_program.h"
#include "offscreen_target.h"
#include "stroke_renderer.h"

namespace cutaway {
namespace {

constexpr int kMaxImageSide = 16384;
constexpr int kMaxLights = 16;              // shaders/scene.frag: kMaxLights
constexpr double kReferenceLux = 3.0;       // AssetLight's default intensity shows at scale 1

/// One vertex as shaders/scene.vert reads it (locations 0..2).
struct SceneVertex {
  float position[3];  // metres, mesh frame
  float normal[3];    // mesh frame
  float colour[3];    // linear RGB
};

/// Where one uploaded mesh's triangles lie in the shared index buffer.
struct MeshRange {
  size_t first_index = 0;  // offset into the index buffer, in indices
  size_t index_count = 0;  // 0: not uploaded (no instances, or no triangles)
};

[[noreturn]] void fail(const std::string& what) {
  throw std::invalid_argument("render_scene_preview: " + what);
}

bool finite(const glm::dvec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void check_mesh(const AssetMesh& m, size_t index) {
  const std::string name = "mesh " + std::to_string(index) + " '" + m.name + "'";
  const size_t n = m.position.size();
  if (m.normal.size() != n || m.colour.size() != n)
    fail(name + " has " + std::to_string(n) + " positions, " + std::to_string(m.normal.size()) +
         " normals and " + std::to_string(m.colour.size()) + " colours (must be equal)");
  for (size_t v = 0; v < n; ++v)
    if (!finite(m.position[v]) || !finite(m.normal[v]) || !finite(m.colour[v]))
      fail(name + ": vertex " + std::to_string(v) + " has a non-finite position, normal or colour");
  for (size_t t = 0; t < m.triangle.size(); ++t)
    for (int i = 0; i < 3; ++i)
      if (m.triangle[t][i] >= n)
        fail(name + ": triangle " + std::to_string(t) + " has vertex index " +
             std::to_string(m.triangle[t][i]) + ", not below " + std::to_string(n));
}

void check_camera(const AssetCamera& c) {
  if (!finite(c.eye) || !finite(c.target) || !finite(c.up))
    fail("camera: eye, target and up must be finite");
  const glm::dvec3 forward = c.target - c.eye;
  if (!(glm::length(forward) > 0)) fail("camera: eye and target coincide");
  if (!(glm::length(c.up) > 0) ||
      !(glm::length(glm::cross(glm::normalize(forward), c.up)) > 1e-9 * glm::length(c.up)))
    fail("camera: up is zero or parallel to the view direction");
  if (!(c.fov_y_deg > 0 && c.fov_y_deg < 180))
    fail("camera: fov_y_deg must be in (0, 180), got " + std::to_string(c.fov_y_deg));
  if (!(c.znear > 0 && c.znear < c.zfar && std::isfinite(c.zfar)))
    fail("camera: need 0 < znear < zfar (finite), got " + std::to_string(c.znear) + ", " +
         std::to_string(c.zfar));
}

void check_light(const AssetLight& l, size_t index) {
  const std::string name = "light " + std::to_string(index) + " '" + l.name + "'";
  if (!finite(l.position) || !finite(l.direction) || !finite(l.colour) ||
      !std::isfinite(l.intensity))
    fail(name + " has a non-finite field");
  if (l.intensity < 0 || l.colour.r < 0 || l.colour.g < 0 || l.colour.b < 0)
    fail(name + " has a negative intensity or colour");
  if (l.type == LightType::Directional && !(glm::length(l.direction) > 0))
    fail(name + " is directional with a zero direction");
}

/// Checks everything the render reads; returns the image size (width, height).
glm::ivec2 check_input(const SceneAssets& a, const ScenePreviewOptions& o) {
  const int width = o.width != 0 ? o.width : a.width;
  const int height = o.height != 0 ? o.height : a.height;
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    fail("image size " + std::to_string(width) + "x" + std::to_string(height) +
         " is outside 1.." + std::to_string(kMaxImageSide));
  if (o.samples < 1) fail("samples must be >= 1, got " + std::to_string(o.samples));
  if (!(o.exposure > 0 && std::isfinite(o.exposure)))
    fail("exposure must be positive and finite, got " + std::to_string(o.exposure));
  check_camera(a.camera);
  if (a.lights.size() > kMaxLights)
    fail(std::to_string(a.lights.size()) + " lights, at most " + std::to_string(kMaxLights));
  for (size_t i = 0; i < a.lights.size(); ++i) check_light(a.lights[i], i);
  if (!finite(a.background) || a.background.r < 0 || a.background.g < 0 || a.background.b < 0)
    fail("background must be finite and >= 0");
  std::vector<bool> checked(a.meshes.size(), false);
  for (size_t i = 0; i < a.instances.size(); ++i) {
    const AssetInstance& inst = a.instances[i];
    const std::string name = "instance " + std::to_string(i) + " '" + inst.name + "'";
    if (inst.mesh < 0 || static_cast<size_t>(inst.mesh) >= a.meshes.size())
      fail(name + " has mesh index " + std::to_string(inst.mesh) + ", not in 0.." +
           std::to_string(static_cast<long>(a.meshes.size()) - 1));
    const glm::dquat& q = inst.rotation;
    if (!std::isfinite(q.w) || !std::isfinite(q.x) || !std::isfinite(q.y) ||
        !std::isfinite(q.z) || !(glm::length(q) > 0) || !finite(inst.translation))
      fail(name + " has a zero or non-finite rotation, or a non-finite translation");
    const auto m = static_cast<size_t>(inst.mesh);
    if (!checked[m]) check_mesh(a.meshes[m], m);
    checked[m] = true;
  }
  return {width, height};
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
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, target.width(),
                          target.height());
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth);
  if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE ||
      glGetError() != GL_NO_ERROR)
    throw std::runtime_error("render_scene_preview: cannot attach a depth buffer with " +
                             std::to_string(target.samples()) + " samples on " +
                             context.description());
}

}  // namespace

Image render_scene_preview(const SceneAssets& assets, const ScenePreviewOptions& options) {
  const glm::ivec2 size = check_input(assets, options);

  // Every instanced mesh once, in one vertex and one index buffer (indices already offset).
  std::vector<SceneVertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<MeshRange> ranges(assets.meshes.size());
  std::vector<bool> used(assets.meshes.size(), false);
  for (const AssetInstance& inst : assets.instances) used[static_cast<size_t>(inst.mesh)] = true;
  for (size_t m = 0; m < assets.meshes.size(); ++m) {
    const AssetMesh& mesh = assets.meshes[m];
    if (!used[m] || mesh.triangle.empty()) continue;
    const auto base = static_cast<uint32_t>(vertices.size());
    for (size_t v = 0; v < mesh.position.size(); ++v) {
      SceneVertex sv{};
      for (int i = 0; i < 3; ++i) {
        sv.position[i] = static_cast<float>(mesh.position[v][i]);
        sv.normal[i] = static_cast<float>(mesh.normal[v][i]);
        sv.colour[i] = static_cast<float>(mesh.colour[v][i]);
      }
      vertices.push_back(sv);
    }
    ranges[m].first_index = indices.size();
    ranges[m].index_count = 3 * mesh.triangle.size();
    for (const glm::uvec3& t : mesh.triangle)
      indices.insert(indices.end(), {base + t.x, base + t.y, base + t.z});
  }

  const AssetCamera& camera = assets.camera;
  const glm::dmat4 view_from_scene = glm::lookAt(camera.eye, camera.target, camera.up);
  const double aspect = static_cast<double>(size.x) / size.y;
  const glm::mat4 clip_from_view(
      glm::perspective(glm::radians(camera.fov_y_deg), aspect, camera.znear, camera.zfar));
  const glm::dmat3 view_rotation(view_from_scene);

  const std::unique_ptr<GlContext> context = create_offscreen_context();
  // The vertex array, buffers and depth renderbuffer below are not deleted one by one: they
  // belong to `context`, which frees them.
  const GlProgram program("scene.vert", "scene.frag");
  const OffscreenTarget target(*context, size.x, size.y, options.samples,
                               "render_scene_preview");
  attach_depth_buffer(target, *context);

  make_vertex_array(vertices, indices, {{0, 3, offsetof(SceneVertex, position)},
                                        {1, 3, offsetof(SceneVertex, normal)},
                                        {2, 3, offsetof(SceneVertex, colour)}});

  // Lights in the view frame; the documented mapping: scale = colour * (lux / 3) * exposure.
  glUseProgram(program.id());
  std::vector<float> light_vector(4 * kMaxLights, 0.0f), light_scale(3 * kMaxLights, 0.0f);
  for (size_t i = 0; i < assets.lights.size(); ++i) {
    const AssetLight& light = assets.lights[i];
    glm::dvec4 v;
    if (light.type == LightType::Directional)
      v = glm::dvec4(view_rotation * -glm::normalize(light.direction), 0.0);
    else
      v = glm::dvec4(glm::dvec3(view_from_scene * glm::dvec4(light.position, 1.0)), 1.0);
    const glm::dvec3 scale = light.colour * (light.intensity / kReferenceLux * options.exposure);
    for (int k = 0; k < 4; ++k) light_vector[4 * i + k] = static_cast<float>(v[k]);
    for (int k = 0; k < 3; ++k) light_scale[3 * i + k] = static_cast<float>(scale[k]);
  }
  glUniform1i(program.uniform("light_count"), static_cast<GLint>(assets.lights.size()));
  glUniform4fv(program.uniform("light_vector"), kMaxLights, light_vector.data());
  glUniform3fv(program.uniform("light_scale"), kMaxLights, light_scale.data());
  const glm::vec3 up_view(view_rotation * glm::dvec3(0, 1, 0));
  glUniform3fv(program.uniform("up_view"), 1, glm::value_ptr(up_view));
  glUniform1f(program.uniform("ambient_scale"), static_cast<float>(options.exposure));
  glUniformMatrix4fv(program.uniform("clip_from_view"), 1, GL_FALSE,
                     glm::value_ptr(clip_from_view));
  const GLint view_from_object_location = program.uniform("view_from_object");

  target.bind();
  glClearColor(static_cast<float>(assets.background.r), static_cast<float>(assets.background.g),
               static_cast<float>(assets.background.b), 1.0f);
  glClearDepth(1.0);
  glDepthMask(GL_TRUE);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDisable(GL_CULL_FACE);  // two-sided: open or flipped triangles still show
  glDisable(GL_BLEND);

  for (const AssetInstance& inst : assets.instances) {
    const MeshRange& range = ranges[static_cast<size_t>(inst.mesh)];
    if (range.index_count == 0) continue;
    const glm::dmat4 scene_from_object = glm::translate(glm::dmat4(1.0), inst.translation) *
                                         glm::mat4_cast(glm::normalize(inst.rotation));
    const glm::mat4 view_from_object(view_from_scene * scene_from_object);
    glUniformMatrix4fv(view_from_object_location, 1, GL_FALSE, glm::value_ptr(view_from_object));
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(range.index_count), GL_UNSIGNED_INT,
                   reinterpret_cast<const void*>(range.first_index * sizeof(uint32_t)));
  }
  if (options.strokes != nullptr) draw_strokes(*options.strokes, camera, size.x, size.y);

  return target.resolve_and_read();
}

}  // namespace cutaway
