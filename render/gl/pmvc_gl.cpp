// The OpenGL PMVC backend (render/gl/pmvc_gl.h; doc/algorithms.md §2, Backends: gl).
#include "render/gl/pmvc_gl.h"

#include <glad/gl.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "base/error.h"
#include "diffusion/adaptive_directions.h"
#include "diffusion/cube_directions.h"
#include "diffusion/diffusion_sheets.h"
#include "diffusion/sheet_bvh.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"

namespace cutaway {
namespace {

/// Points per dispatch: one work group each (at most 65535 in x), 2 x 32 bytes of sums each.
constexpr int kBatchPoints = 16384;
/// Stack entries of the traversal in shaders/pmvc_trace.comp: the deepest BVH it can walk.
constexpr int kMaxBvhDepth = 64;

/// One batch point as shaders/pmvc_trace.comp reads it: its position and the columns of the
/// rotation R of its cube (cube_rotation; identity when the cubes are not turned).
struct BatchPoint {
  glm::vec4 eye;          // xyz: metres
  glm::vec4 to_world[3];  // xyz: column i of R
};

/// One BVH triangle as the shader reads it (leaf order).
struct GpuTriangle {
  glm::vec4 v0, e1, e2;  // xyz: first vertex and the edges to the second and third, metres
  glm::vec4 normal;      // xyz: unit normal of the front face
  glm::uvec4 vertex;     // xyz: indices into the vertex attributes; w: 2 sheet + two-faced
};

/// One sheet vertex's attributes as the shader reads them.
struct GpuVertex {
  glm::vec4 colour_front;  // rgb: linear
  glm::vec4 colour_back;   // rgb: linear; = colour_front on a sheet that is not two-faced
  glm::vec4 material;      // xy: front (roughness, translucency); zw: back
};

void check_gl(const char* what) {
  const GLenum error = glGetError();
  if (error != GL_NO_ERROR) {
    char code[16];
    std::snprintf(code, sizeof code, "%04x", error);
    throw EnvironmentError(std::string("gl diffusion: OpenGL error 0x") + code + " " + what);
  }
}

/// A shader storage buffer holding `data` (GL_STATIC_DRAW), or `bytes` uninitialised bytes.
template <typename T>
GLuint storage_buffer(const std::vector<T>& data, size_t bytes = 0, GLenum usage = GL_STATIC_DRAW) {
  GLuint buffer = 0;
  glGenBuffers(1, &buffer);
  glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffer);
  const size_t size = data.empty() ? bytes : data.size() * sizeof(T);
  glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(std::max<size_t>(size, 16)),
               data.empty() ? nullptr : data.data(), usage);
  return buffer;
}

/// Directions as the shader reads them: std430 pads a vec3 array to vec4s.
std::vector<glm::vec4> padded(const std::vector<glm::vec3>& directions) {
  std::vector<glm::vec4> out;
  out.reserve(directions.size());
  for (const glm::vec3& d : directions) out.emplace_back(d, 0.0f);
  return out;
}

class GlDiffusion final : public DiffusionBackend {
 public:
  GlDiffusion(const DsModel& model, const DiffusionOptions& options)
      : rotate_cubes_(options.rotate_cubes), threads_(options.threads) {
    if (options.cube_size < 1)
      throw InternalError("gl diffusion: cube_size must be >= 1, got " +
                          std::to_string(options.cube_size));
    context_ = create_offscreen_context();
    check_capabilities();
    trace_ = std::make_unique<GlProgram>("pmvc_trace.comp");
    direction_count_location_ = trace_->uniform("direction_count");
    adaptive_location_ = trace_->uniform("adaptive");
    fine_n_location_ = trace_->uniform("fine_n");
    pair_count_location_ = trace_->uniform("pair_count");
    upload_sheets(model);
    if (uses_adaptive_directions(options)) {
      const AdaptiveDirections adaptive = make_adaptive_directions(options.cube_size);
      upload_directions(adaptive.coarse);
      upload_fine_level(adaptive);
    } else {
      upload_directions(make_cube_directions(options.cube_size));
      fine_directions_buffer_ = storage_buffer(std::vector<glm::vec4>{});
      fine_solid_angle_buffer_ = storage_buffer(std::vector<double>{});
      pairs_buffer_ = storage_buffer(std::vector<glm::uvec2>{});
    }
    points_buffer_ = storage_buffer(std::vector<BatchPoint>{}, kBatchPoints * sizeof(BatchPoint),
                                    GL_DYNAMIC_DRAW);
    sums_buffer_ = storage_buffer(std::vector<glm::dvec4>{}, 2 * kBatchPoints * sizeof(glm::dvec4),
                                  GL_DYNAMIC_READ);
    check_gl("while setting up");
  }

  ~GlDiffusion() override {
    // The context owns every object; make it current so the program deletes in the right one.
    try {
      context_->make_current();
      trace_.reset();
    } catch (...) {
    }
  }

  std::string name() const override { return "gl"; }
  int threads() const override { return threads_; }

  size_t rays_cast() const override {
    const std::lock_guard lock(mutex_);
    return rays_;
  }

  void diffuse_channels(std::span<const glm::dvec3> points, std::span<glm::dvec3> colour,
                        std::span<glm::dvec2> material) const override {
    check_channel_sizes(points.size(), colour.size(), material.size());
    std::fill(colour.begin(), colour.end(), glm::dvec3(0.0));
    std::fill(material.begin(), material.end(), glm::dvec2(0.0));
    if (points.empty() || !has_triangles_) return;
    const std::lock_guard lock(mutex_);
    context_->make_current();
    std::vector<BatchPoint> batch;
    // Per point: (sum colour w, sum w), (sum material w, 0, 0).
    std::vector<glm::dvec4> sums;
    for (size_t base = 0; base < points.size(); base += batch.size()) {
      const size_t count = std::min<size_t>(kBatchPoints, points.size() - base);
      batch.resize(count);
      for (size_t i = 0; i < count; ++i) {
        const glm::dvec3& p = points[base + i];
        const glm::dmat3 r = rotate_cubes_ ? cube_rotation(p) : glm::dmat3(1.0);
        batch[i].eye = glm::vec4(glm::vec3(p), 1.0f);
        for (int column = 0; column < 3; ++column)
          batch[i].to_world[column] = glm::vec4(glm::vec3(r[column]), 0.0f);
      }
      trace(batch, sums);
      for (size_t i = 0; i < count; ++i) {
        rays_ += static_cast<size_t>(sums[2 * i + 1].z);
        const double w = sums[2 * i].w;
        if (w <= 0) continue;
        colour[base + i] = glm::dvec3(sums[2 * i]) / w;
        if (!material.empty()) material[base + i] = glm::dvec2(sums[2 * i + 1]) / w;
      }
    }
  }

 private:
  /// One dispatch: a work group per batch point; reads back two sums per point.
  void trace(const std::vector<BatchPoint>& batch, std::vector<glm::dvec4>& sums) const {
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, points_buffer_);
    glBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                    static_cast<GLsizeiptr>(batch.size() * sizeof(BatchPoint)), batch.data());
    const GLuint bindings[] = {
        nodes_buffer_,      triangles_buffer_,       vertices_buffer_,
        directions_buffer_, solid_angle_buffer_,     points_buffer_,
        sums_buffer_,       fine_directions_buffer_, fine_solid_angle_buffer_,
        pairs_buffer_};
    for (GLuint i = 0; i < 10; ++i) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, i, bindings[i]);
    glUseProgram(trace_->id());
    glUniform1i(direction_count_location_, direction_count_);
    glUniform1i(adaptive_location_, fine_n_ > 0 ? 1 : 0);
    glUniform1i(fine_n_location_, fine_n_);
    glUniform1i(pair_count_location_, pair_count_);
    glDispatchCompute(static_cast<GLuint>(batch.size()), 1, 1);
    glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    sums.resize(2 * batch.size());
    glBindBuffer(GL_SHADER_STORAGE_BUFFER, sums_buffer_);
    glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0,
                       static_cast<GLsizeiptr>(sums.size() * sizeof(glm::dvec4)), sums.data());
    check_gl("while casting the rays");
  }

  void check_capabilities() const {
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major < 4 || (major == 4 && minor < 3))
      throw EnvironmentError("gl diffusion: the OpenGL context (" + context_->description() +
                             ") lacks OpenGL 4.3 (compute shaders)");
  }

  /// Uploads the BVH nodes, its triangles in leaf order and every sheet vertex's attributes.
  void upload_sheets(const DsModel& model) {
    const std::vector<DiffusionSheet> sheets = make_diffusion_sheets(model);
    const SheetBvh bvh = build_sheet_bvh(sheets);
    if (bvh.depth > kMaxBvhDepth)
      throw EnvironmentError("gl diffusion: the sheets' BVH is " + std::to_string(bvh.depth) +
                             " levels deep; the GPU traversal walks at most " +
                             std::to_string(kMaxBvhDepth));
    std::vector<GpuVertex> vertices;
    std::vector<uint32_t> first_vertex;  // per sheet
    for (const DiffusionSheet& s : sheets) {
      first_vertex.push_back(static_cast<uint32_t>(vertices.size()));
      for (size_t v = 0; v < s.position.size(); ++v) {
        const glm::vec3 back = s.two_faced ? s.colour_back[v] : s.colour_front[v];
        const glm::vec2 material_back = s.two_faced ? s.material_back[v] : s.material_front[v];
        vertices.push_back({glm::vec4(s.colour_front[v], 0.0f), glm::vec4(back, 0.0f),
                            glm::vec4(s.material_front[v], material_back)});
      }
    }
    std::vector<GpuTriangle> triangles;
    triangles.reserve(bvh.triangles.size());
    for (const SheetTriangleRef& ref : bvh.triangles) {
      const DiffusionSheet& s = sheets[ref.sheet];
      const glm::uvec3 t = s.triangle[ref.triangle];
      const glm::vec3 a = s.position[t[0]], b = s.position[t[1]], c = s.position[t[2]];
      const uint32_t base = first_vertex[ref.sheet];
      triangles.push_back({glm::vec4(a, 0.0f), glm::vec4(b - a, 0.0f), glm::vec4(c - a, 0.0f),
                           glm::vec4(s.face_normal[ref.triangle], 0.0f),
                           glm::uvec4(base + t[0], base + t[1], base + t[2],
                                      2 * ref.sheet + (s.two_faced ? 1 : 0))});
    }
    has_triangles_ = !triangles.empty();
    static_assert(sizeof(SheetBvh::Node) == 32, "std430 Node is 32 bytes");
    nodes_buffer_ = storage_buffer(bvh.nodes);
    triangles_buffer_ = storage_buffer(triangles);
    vertices_buffer_ = storage_buffer(vertices);
  }

  void upload_directions(const CubeDirections& directions) {
    direction_count_ = static_cast<int>(directions.direction.size());
    directions_buffer_ = storage_buffer(padded(directions.direction));
    solid_angle_buffer_ = storage_buffer(directions.solid_angle);
  }

  /// Adaptive directions: the fine level and the coarse pairs (the coarse level is the first).
  void upload_fine_level(const AdaptiveDirections& adaptive) {
    fine_directions_buffer_ = storage_buffer(padded(adaptive.fine.direction));
    fine_solid_angle_buffer_ = storage_buffer(adaptive.fine.solid_angle);
    pairs_buffer_ = storage_buffer(adaptive.pairs);
    fine_n_ = adaptive.fine.n;
    pair_count_ = static_cast<int>(adaptive.pairs.size());
  }

  bool rotate_cubes_ = true;
  int threads_ = 0;  ///< DiffusionOptions::threads, for the work around the backend
  std::unique_ptr<GlContext> context_;
  // GL objects below belong to context_ and are freed with it.
  std::unique_ptr<GlProgram> trace_;
  GLint direction_count_location_ = -1, adaptive_location_ = -1, fine_n_location_ = -1,
        pair_count_location_ = -1;
  int direction_count_ = 0;
  int fine_n_ = 0;  ///< adaptive directions: the fine level's n; 0: every texel is cast
  int pair_count_ = 0;
  bool has_triangles_ = false;
  GLuint nodes_buffer_ = 0, triangles_buffer_ = 0, vertices_buffer_ = 0;
  GLuint directions_buffer_ = 0, solid_angle_buffer_ = 0, points_buffer_ = 0, sums_buffer_ = 0;
  GLuint fine_directions_buffer_ = 0, fine_solid_angle_buffer_ = 0, pairs_buffer_ = 0;
  mutable std::mutex mutex_;
  mutable size_t rays_ = 0;  ///< guarded by mutex_
};

}  // namespace

std::unique_ptr<DiffusionBackend> make_gl_diffusion(const DsModel& model,
                                                    const DiffusionOptions& options) {
  return std::make_unique<GlDiffusion>(model, options);
}

}  // namespace cutaway
