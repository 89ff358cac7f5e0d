#include "render/gl/stroke_renderer.h"

#include <glad/gl.h>

#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "base/error.h"
#include "render/gl/gl_buffers.h"
#include "render/gl/gl_program.h"

namespace cutaway {
namespace {

/// One corner of a stroke's strip as shaders/stroke.vert reads it.
struct StrokeVertex {
  float pixel[2];
  float colour[3];
};

/// Appends the triangles of one run of projected points (pixels) with half widths `half`.
void add_run(const std::vector<glm::dvec2>& p, const std::vector<double>& half, bool closed,
             const glm::dvec3& colour, std::vector<StrokeVertex>* out) {
  const size_t n = p.size();
  if (n < 2) return;
  const size_t segments = closed ? n : n - 1;
  std::vector<glm::dvec2> dir(segments);
  glm::dvec2 last(1, 0);
  for (size_t k = 0; k < segments; ++k) {
    const glm::dvec2 d = p[(k + 1) % n] - p[k];
    const double len = glm::length(d);
    dir[k] = len > 1e-9 ? d / len : last;
    last = dir[k];
  }
  std::vector<glm::dvec2> left(n), right(n);
  for (size_t k = 0; k < n; ++k) {
    glm::dvec2 in, out;
    if (closed) {
      in = dir[(k + segments - 1) % segments];
      out = dir[k % segments];
    } else {
      in = dir[k == 0 ? 0 : k - 1];
      out = dir[k + 1 == n ? segments - 1 : k];
    }
    glm::dvec2 t = in + out;
    const double tl = glm::length(t);
    t = tl > 1e-9 ? t / tl : out;
    const glm::dvec2 normal(-t.y, t.x);
    const glm::dvec2 seg_normal(-out.y, out.x);
    const double miter = half[k] / std::max(0.5, glm::dot(normal, seg_normal));
    left[k] = p[k] + normal * miter;
    right[k] = p[k] - normal * miter;
  }
  const auto emit = [&](const glm::dvec2& q) {
    StrokeVertex v{};
    v.pixel[0] = static_cast<float>(q.x);
    v.pixel[1] = static_cast<float>(q.y);
    for (int i = 0; i < 3; ++i) v.colour[i] = static_cast<float>(colour[i]);
    out->push_back(v);
  };
  for (size_t k = 0; k < segments; ++k) {
    const size_t j = (k + 1) % n;
    emit(left[k]);
    emit(right[k]);
    emit(left[j]);
    emit(left[j]);
    emit(right[k]);
    emit(right[j]);
  }
}

}  // namespace

void draw_strokes(const std::vector<Stroke>& strokes, const AssetCamera& camera, int width,
                  int height, double width_scale) {
  if (strokes.empty()) return;
  const glm::dmat4 view = view_from_scene(camera);
  const double f = focal_length_px(camera, height);
  std::vector<StrokeVertex> vertices;
  for (const Stroke& s : strokes) {
    std::vector<glm::dvec2> run;
    std::vector<double> half;
    bool whole = true;
    const auto flush = [&](bool closed) {
      add_run(run, half, closed, s.colour, &vertices);
      run.clear();
      half.clear();
    };
    for (size_t k = 0; k < s.points.size(); ++k) {
      const glm::dvec3 v(view * glm::dvec4(s.points[k], 1.0));
      if (!(-v.z > camera.znear)) {
        whole = false;
        flush(false);
        continue;
      }
      run.emplace_back(width / 2.0 + f * v.x / -v.z, height / 2.0 - f * v.y / -v.z);
      const double w = k < s.width_px.size() ? s.width_px[k] : 1.0;
      half.push_back(0.5 * w * width_scale);
    }
    flush(s.closed && whole);
  }
  if (vertices.empty()) return;

  const GlProgram program("stroke.vert", "stroke.frag");
  // The vertex array and buffer belong to the caller's context, which frees them.
  make_vertex_array(vertices.data(), vertices.size() * sizeof(StrokeVertex),
                    static_cast<GLsizei>(sizeof(StrokeVertex)), nullptr, 0,
                    {{0, 2, offsetof(StrokeVertex, pixel)},
                     {1, 3, offsetof(StrokeVertex, colour)}});
  glUseProgram(program.id());
  glUniform2f(program.uniform("image_size"), static_cast<float>(width), static_cast<float>(height));
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices.size()));
  const GLenum error = glGetError();
  glUseProgram(0);
  glBindVertexArray(0);
  if (error != GL_NO_ERROR)
    throw EnvironmentError("draw_strokes: OpenGL error " + std::to_string(error));
}

}  // namespace cutaway
