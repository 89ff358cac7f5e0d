#include "render/section_preview.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "base/error.h"
#include "render/gl/gl_buffers.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/gl/offscreen_target.h"

namespace cutaway {
namespace {

constexpr int kMaxImageSide = 16384;

/// One vertex as shaders/section.vert reads it (locations 0 and 1).
struct SectionVertex {
  float section[2];  // (u, v) metres, relative to the image centre
  float colour[3];   // linear RGB
};

[[noreturn]] void fail(const std::string& what) {
  throw InternalError("render_section_preview: " + what);
}

void check_input(const CrossSection& s, const SectionPreviewOptions& o) {
  if (o.width < 1 || o.width > kMaxImageSide)
    fail("width " + std::to_string(o.width) + " is outside 1.." + std::to_string(kMaxImageSide));
  if (o.height < 0 || o.height > kMaxImageSide)
    fail("height " + std::to_string(o.height) + " is outside 1.." + std::to_string(kMaxImageSide) +
         " (or 0 for the section's aspect)");
  if (o.samples < 1) fail("samples must be >= 1, got " + std::to_string(o.samples));
  if (!(o.margin >= 0 && o.margin <= 1))
    fail("margin must be in 0..1, got " + std::to_string(o.margin));
  if (s.triangle.empty() || s.position.empty()) fail("the section has no triangles");
  if (s.colour.size() != s.position.size())
    fail("the section has " + std::to_string(s.position.size()) + " positions but " +
         std::to_string(s.colour.size()) + " colours");
  for (size_t t = 0; t < s.triangle.size(); ++t)
    for (int i = 0; i < 3; ++i)
      if (s.triangle[t][i] >= s.position.size())
        fail("triangle " + std::to_string(t) + " has vertex index " +
             std::to_string(s.triangle[t][i]) + ", not below " + std::to_string(s.position.size()));
}

}  // namespace

Image render_section_preview(const CrossSection& section, const SectionPreviewOptions& options) {
  check_input(section, options);

  // In-plane coordinates, relative to the plane's point (doubles; floats only after centring).
  std::vector<glm::dvec2> uv(section.position.size());
  glm::dvec2 lo(INFINITY), hi(-INFINITY);
  for (size_t i = 0; i < uv.size(); ++i) {
    const glm::dvec3 d = section.position[i] - section.plane.point;
    uv[i] = glm::dvec2(glm::dot(d, section.u_axis), glm::dot(d, section.v_axis));
    if (!std::isfinite(uv[i].x) || !std::isfinite(uv[i].y))
      fail("vertex " + std::to_string(i) + " is not finite in the plane's (u, v) frame");
    lo = glm::min(lo, uv[i]);
    hi = glm::max(hi, uv[i]);
  }
  const glm::dvec2 extent_m = hi - lo;
  if (!(extent_m.x > 0 && extent_m.y > 0))
    fail("the section's extent in the (u, v) frame is degenerate (" + std::to_string(extent_m.x) +
         " x " + std::to_string(extent_m.y) + " m)");

  // Fit: the extent grown by the margin on every side, one scale for both axes, centred.
  const double border_m = options.margin * std::max(extent_m.x, extent_m.y);
  const glm::dvec2 framed_m = extent_m + 2.0 * border_m;
  const int width = options.width;
  int height = options.height;
  if (height == 0)
    height = std::clamp(static_cast<int>(std::lround(width * framed_m.y / framed_m.x)), 1,
                        kMaxImageSide);
  const double pixels_per_m = std::min(width / framed_m.x, height / framed_m.y);
  const glm::dvec2 centre = 0.5 * (lo + hi);
  const glm::dvec2 clip_from_section(2.0 * pixels_per_m / width, 2.0 * pixels_per_m / height);

  std::vector<SectionVertex> vertices(uv.size());
  for (size_t i = 0; i < uv.size(); ++i) {
    const glm::dvec2 p = uv[i] - centre;
    vertices[i] = SectionVertex{{static_cast<float>(p.x), static_cast<float>(p.y)},
                                {static_cast<float>(section.colour[i].r),
                                 static_cast<float>(section.colour[i].g),
                                 static_cast<float>(section.colour[i].b)}};
  }
  std::vector<uint32_t> indices;
  indices.reserve(3 * section.triangle.size());
  for (const glm::uvec3& t : section.triangle) indices.insert(indices.end(), {t.x, t.y, t.z});

  const std::unique_ptr<GlContext> context = create_offscreen_context();
  // The vertex array and buffers below are not deleted one by one: they belong to `context`,
  // which frees them.
  const GlProgram program("section.vert", "section.frag");
  // 32-bit float: the vertex colours reach the sRGB8 encoding without half-float rounding.
  const OffscreenTarget target(*context, width, height, options.samples, "render_section_preview",
                               GL_RGBA32F);

  make_vertex_array(vertices, indices,
                    {{0, 2, offsetof(SectionVertex, section)},
                     {1, 3, offsetof(SectionVertex, colour)}});

  glUseProgram(program.id());
  glUniform2f(program.uniform("clip_from_section"), static_cast<float>(clip_from_section.x),
              static_cast<float>(clip_from_section.y));

  target.clear(options.background_srgb);
  glDisable(GL_DEPTH_TEST);  // one plane: no occlusion; split duplicates coincide exactly
  glDisable(GL_CULL_FACE);
  glDisable(GL_BLEND);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(indices.size()), GL_UNSIGNED_INT, nullptr);

  return target.resolve_and_read();
}

}  // namespace cutaway
