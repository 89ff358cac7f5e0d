// The OpenGL PMVC backend (render/pmvc_gl.h; design/algorithms.md §2, Backends: gl).
#include "pmvc_gl.h"

#include <glad/gl.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "diffusion/cube_directions.h"
#include "diffusion/diffusion_sheets.h"
#include "gl_context.h"
#include "gl_buffers.h"
#include "gl_program.h"
#include "shader_sources.h"

namespace cutaway {
namespace {

/// Near plane, metres. With the reversed float depth buffer the precision does not depend on
/// it, so it can be far below any sheet spacing (kMinSheetOffset_m).
constexpr float kNear_m = 1e-7f;
/// Upper bound on the colour, material and depth targets of one batch, bytes.
constexpr size_t kMaxBatchBytes = size_t{64} << 20;
/// One batch point as shaders/pmvc.vert reads it: its position and the rows of R^T for its
/// cube's rotation R (cube_rotation; identity when the cubes are not turned).
struct BatchPoint {
  glm::vec4 eye;         // xyz: metres
  glm::vec4 to_cube[3];  // xyz: row i of R^T
};

/// One vertex as shaders/pmvc.vert reads it.
struct SheetVertex {
  glm::vec3 position;      // metres
  glm::vec3 colour_front;  // linear RGB
  glm::vec3 colour_back;   // linear RGB; = colour_front on a sheet that is not two-faced
  glm::vec2 material_front;  // (roughness, translucency)
  glm::vec2 material_back;   // = material_front on a sheet that is not two-faced
};

void check_gl(const char* what) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR)
    throw std::runtime_error(std::string("gl diffusion: OpenGL error 0x") +
                             [](GLenum e) {
                               char buf[16];
                               std::snprintf(buf, sizeof buf, "%04x", e);
                               return std::string(buf);
                             }(error) +
                             " " + what);
}

class GlDiffusion final : public DiffusionBackend {
 public:
  GlDiffusion(const DsModel& model, const DiffusionOptions& options)
      : n_(options.cube_size), rotate_cubes_(options.rotate_cubes) {
    if (n_ < 1)
      throw std::invalid_argument("gl diffusion: cube_size must be >= 1, got " +
                                  std::to_string(n_));
    context_ = create_offscreen_context();
    check_capabilities();
    GLint max_size = 0, max_layers = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_size);
    glGetIntegerv(GL_MAX_ARRAY_TEXTURE_LAYERS, &max_layers);
    if (n_ > max_size)
      throw std::invalid_argument("gl diffusion: cube_size " + std::to_string(n_) +
                                  " exceeds the texture size limit " + std::to_string(max_size));
    const size_t bytes_per_point = size_t{6} * n_ * n_ * (16 + 8 + 4);
    batch_ = static_cast<int>(std::clamp<size_t>(kMaxBatchBytes / bytes_per_point, 1,
                                                 static_cast<size_t>(max_layers / 6)));

    render_ = std::make_unique<GlProgram>("pmvc.vert", "pmvc.frag");
    reduce_ = std::make_unique<GlProgram>("pmvc_reduce.comp");
    upload_sheets(model);
    create_targets();
    check_gl("while setting up");
  }

  ~GlDiffusion() override {
    // The context owns every object; make it current so the program deletes in the right one.
    try {
      context_->make_current();
      render_.reset();
      reduce_.reset();
    } catch (...) {
    }
  }

  std::string name() const override { return "gl"; }

  void diffuse_channels(std::span<const glm::dvec3> points, std::span<glm::dvec3> colour,
                        std::span<glm::dvec2> material) const override {
    check_channel_sizes(points.size(), colour.size(), material.size());
    std::fill(colour.begin(), colour.end(), glm::dvec3(0.0));
    std::fill(material.begin(), material.end(), glm::dvec2(0.0));
    if (points.empty() || index_count_ == 0) return;
    const std::lock_guard lock(mutex_);
    context_->make_current();
    std::vector<BatchPoint> eyes;
    // Per point: (sum colour w, sum w), (sum material w, 0, 0).
    std::vector<glm::dvec4> sums(2 * static_cast<size_t>(batch_));
    for (size_t base = 0; base < points.size(); base += eyes.size()) {
      const size_t count = std::min<size_t>(batch_, points.size() - base);
      eyes.resize(count);
      for (size_t i = 0; i < count; ++i) {
        const glm::dvec3& p = points[base + i];
        const glm::dmat3 r = rotate_cubes_ ? cube_rotation(p) : glm::dmat3(1.0);
        eyes[i].eye = glm::vec4(glm::vec3(p), 1.0f);
        for (int row = 0; row < 3; ++row)  // row `row` of R^T is column `row` of R
          eyes[i].to_cube[row] = glm::vec4(glm::vec3(r[row]), 0.0f);
      }
      render(eyes);
      reduce(static_cast<int>(count), sums);
      for (size_t i = 0; i < count; ++i) {
        const double w = sums[2 * i].w;
        if (w <= 0) continue;
        colour[base + i] = glm::dvec3(sums[2 * i]) / w;
        if (!material.empty()) material[base + i] = glm::dvec2(sums[2 * i + 1]) / w;
      }
    }
  }

 private:
  /// Draws the batch: one instance per (point, face), into layer 6 point + face.
  void render(const std::vector<BatchPoint>& eyes) const {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glViewport(0, 0, n_, n_);
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_GREATER);  // reversed depth: nearer is larger
    glDepthMask(GL_TRUE);
    glDisable(GL_CULL_FACE);
    glDisable(GL_BLEND);
    glFrontFace(GL_CW);  // the cube faces are mirrored: see shaders/pmvc.frag
    const GLfloat zero[4] = {0, 0, 0, 0};
    const GLfloat far_depth = 0;
    glClearBufferfv(GL_COLOR, 0, zero);
    glClearBufferfv(GL_COLOR, 1, zero);
    glClearBufferfv(GL_DEPTH, 0, &far_depth);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, eye_buffer_);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                    static_cast<GLsizeiptr>(eyes.size() * sizeof(BatchPoint)), eyes.data());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, eye_buffer_);
    glUseProgram(render_->id());
    glUniform1f(near_location_, kNear_m);
    glBindVertexArray(vertex_array_);
    glDrawElementsInstanced(GL_TRIANGLES, index_count_, GL_UNSIGNED_INT, nullptr,
                            static_cast<GLsizei>(6 * eyes.size()));
    check_gl("while rendering the cube maps");
  }

  /// Sums the layers of `count` points into sums[0 .. 2 count - 1] (two per point).
  void reduce(int count, std::vector<glm::dvec4>& sums) const {
    glUseProgram(reduce_->id());
    glUniform1i(n_location_, n_);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D_ARRAY, colour_);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D_ARRAY, material_);
    glActiveTexture(GL_TEXTURE0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, solid_angle_buffer_);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, sum_buffer_);
    glDispatchCompute(static_cast<GLuint>(count), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, sum_buffer_);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                       static_cast<GLsizeiptr>(2 * count * sizeof(glm::dvec4)), sums.data());
    check_gl("while summing the cube maps");
  }

  void check_capabilities() const {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    std::string missing;
    if (major < 4 || (major == 4 && minor < 3)) missing += " OpenGL 4.3 (compute shaders);";
    if (!GLAD_GL_VERSION_4_5 && !GLAD_GL_ARB_clip_control) missing += " ARB_clip_control;";
    if (!GLAD_GL_ARB_shader_viewport_layer_array)
      missing += " ARB_shader_viewport_layer_array;";
    if (!missing.empty()) {
      missing.pop_back();
      throw std::runtime_error("gl diffusion: the OpenGL context (" + context_->description() +
                               ") lacks" + missing);
    }
  }

  /// Uploads every sheet's vertices and triangles, once (one vertex and one index buffer).
  void upload_sheets(const DsModel& model) {
    std::vector<SheetVertex> vertices;
    std::vector<uint32_t> indices;
    for (const DiffusionSheet& s : make_diffusion_sheets(model)) {
      const auto base = static_cast<uint32_t>(vertices.size());
      for (size_t v = 0; v < s.position.size(); ++v)
        vertices.push_back({s.position[v], s.colour_front[v],
                            s.two_faced ? s.colour_back[v] : s.colour_front[v], s.material_front[v],
                            s.two_faced ? s.material_back[v] : s.material_front[v]});
      for (const glm::uvec3& t : s.triangle)
        for (int k = 0; k < 3; ++k) indices.push_back(base + t[k]);
    }
    index_count_ = static_cast<GLsizei>(indices.size());
    vertex_array_ = make_vertex_array(vertices, indices,
                                      {{0, 3, offsetof(SheetVertex, position)},
                                       {1, 3, offsetof(SheetVertex, colour_front)},
                                       {2, 3, offsetof(SheetVertex, colour_back)},
                                       {3, 2, offsetof(SheetVertex, material_front)},
                                       {4, 2, offsetof(SheetVertex, material_back)}});
    glBindVertexArray(0);
  }

  void create_targets() {
    const GLsizei layers = 6 * batch_;
    glGenTextures(1, &colour_);
    glBindTexture(GL_TEXTURE_2D_ARRAY, colour_);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RGBA32F, n_, n_, layers);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenTextures(1, &material_);
    glBindTexture(GL_TEXTURE_2D_ARRAY, material_);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_RG32F, n_, n_, layers);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D_ARRAY, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glGenTextures(1, &depth_);
    glBindTexture(GL_TEXTURE_2D_ARRAY, depth_);
    glTexStorage3D(GL_TEXTURE_2D_ARRAY, 1, GL_DEPTH_COMPONENT32F, n_, n_, layers);
    glBindTexture(GL_TEXTURE_2D_ARRAY, 0);
    glGenFramebuffers(1, &framebuffer_);
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_);
    glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, colour_, 0);
    glFramebufferTexture(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, material_, 0);
    glFramebufferTexture(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, depth_, 0);
    const GLenum draw_buffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glDrawBuffers(2, draw_buffers);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("gl diffusion: layered RGBA32F + RG32F + DEPTH32F framebuffer of " +
                               std::to_string(n_) + "^2 x " + std::to_string(layers) +
                               " is incomplete (status " + std::to_string(status) + ")");

    const CubeDirections directions = make_cube_directions(n_);
    GLuint buffers[3] = {0, 0, 0};
    glGenBuffers(3, buffers);
    eye_buffer_ = buffers[0];
    solid_angle_buffer_ = buffers[1];
    sum_buffer_ = buffers[2];
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, eye_buffer_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(batch_ * sizeof(BatchPoint)),
                 nullptr, GL_DYNAMIC_DRAW);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, solid_angle_buffer_);
    glBufferData(GL_SHADER_STORAGE_BUFFER,
                 static_cast<GLsizeiptr>(directions.solid_angle.size() * sizeof(double)),
                 directions.solid_angle.data(), GL_STATIC_DRAW);
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, sum_buffer_);
    glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(2 * batch_ * sizeof(glm::dvec4)),
                 nullptr, GL_DYNAMIC_READ);
    near_location_ = render_->uniform("near_m");
    n_location_ = glGetUniformLocation(reduce_->id(), "n");
    if (n_location_ < 0) throw std::runtime_error("shaders/pmvc_reduce.comp: no uniform 'n'");
  }

  int n_ = 0;
  bool rotate_cubes_ = true;
  int batch_ = 1;  // points per batch
  std::unique_ptr<GlContext> context_;
  std::unique_ptr<GlProgram> render_;
  // GL objects below belong to context_ and are freed with it.
  std::unique_ptr<GlProgram> reduce_;
  GLuint vertex_array_ = 0;
  GLsizei index_count_ = 0;
  GLuint colour_ = 0, material_ = 0, depth_ = 0, framebuffer_ = 0;
  GLuint eye_buffer_ = 0, solid_angle_buffer_ = 0, sum_buffer_ = 0;
  GLint near_location_ = -1, n_location_ = -1;
  mutable std::mutex mutex_;
};

}  // namespace

std::unique_ptr<DiffusionBackend> make_gl_diffusion(const DsModel& model,
                                                    const DiffusionOptions& options) {
  return std::make_unique<GlDiffusion>(model, options);
}

}  // namespace cutaway
