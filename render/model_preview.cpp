#include "render/model_preview.h"

#include <glad/gl.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numeric>
#include <stdexcept>
#include <string>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>

#include "assets/scene_assets.h"
#include "base/atomic_file.h"
#include "base/error.h"
#include "render/gl/gl_buffers.h"
#include "render/gl/gl_context.h"
#include "render/gl/gl_program.h"
#include "render/gl/offscreen_target.h"

namespace cutaway {
namespace {

constexpr int kMaxImageSide = 16384;
constexpr double kFitMargin = 1.08;  // bounding sphere radius * margin fills the view

/// One vertex as the preview shaders read it (locations 0..4 of shaders/preview.vert).
struct PreviewVertex {
  float position[3];  // metres, object frame
  float normal[3];    // area-weighted sum of face normals, object frame
  float front[3];     // linear RGB
  float back[3];      // linear RGB
  float alpha;
};

/// All surfaces' vertices, and their triangles as indices into them.
struct PreviewGeometry {
  std::vector<PreviewVertex> vertices;
  std::vector<glm::dvec3> positions;  // double copy of the positions, for depth sorting
  std::vector<uint32_t> indices;      // 3 per triangle
};

void check_options(const PreviewOptions& o) {
  auto fail = [](const std::string& what) { throw InternalError("render_model_preview: " + what); };
  if (o.width < 1 || o.height < 1 || o.width > kMaxImageSide || o.height > kMaxImageSide)
    fail("image size " + std::to_string(o.width) + "x" + std::to_string(o.height) +
         " is outside 1.." + std::to_string(kMaxImageSide));
  if (o.samples < 1) fail("samples must be >= 1, got " + std::to_string(o.samples));
  if (!(o.fov_deg >= 1 && o.fov_deg <= 170))
    fail("fov_deg must be in 1..170, got " + std::to_string(o.fov_deg));
  if (!(std::abs(o.elevation_deg) <= 89))
    fail("elevation_deg must be in -89..89, got " + std::to_string(o.elevation_deg));
  if (!std::isfinite(o.azimuth_deg)) fail("azimuth_deg must be finite");
  if (!(o.skin_alpha >= 0 && o.skin_alpha <= 1 && o.inner_alpha >= 0 && o.inner_alpha <= 1))
    fail("skin_alpha and inner_alpha must be in 0..1");
}

PreviewGeometry build_geometry(const DsModel& model, const PreviewOptions& options) {
  PreviewGeometry g;
  g.vertices.reserve(model.vertex_count());
  g.positions.reserve(model.vertex_count());
  g.indices.reserve(3 * model.face_count());
  for (size_t s = 0; s < model.surfaces.size(); ++s) {
    const DsSurface& surface = model.surfaces[s];
    const DsMesh& mesh = surface.mesh;
    const auto base = static_cast<uint32_t>(g.vertices.size());
    const float alpha = static_cast<float>(s == 0 ? options.skin_alpha : options.inner_alpha);

    // Smooth normals: sum of the incident faces' cross products (twice the area times the unit
    // normal), so larger faces weigh more.
    std::vector<glm::dvec3> normals(mesh.n_vertices(), glm::dvec3(0.0));
    for (const auto fh : mesh.faces()) {
      glm::dvec3 p[3];
      uint32_t v[3];
      int k = 0;
      for (const auto vh : mesh.fv_range(fh)) {  // a TriMesh face has exactly 3 vertices
        const auto& q = mesh.point(vh);
        p[k] = glm::dvec3(q[0], q[1], q[2]);
        v[k] = static_cast<uint32_t>(vh.idx());
        ++k;
      }
      const glm::dvec3 n = glm::cross(p[1] - p[0], p[2] - p[0]);
      for (int i = 0; i < 3; ++i) {
        normals[v[i]] += n;
        g.indices.push_back(base + v[i]);
      }
    }

    for (const auto vh : mesh.vertices()) {
      const auto& q = mesh.point(vh);
      const auto& data = mesh.data(vh);
      // A hollow side has no material to show; it takes the other side's colour.
      const OpenMesh::Vec3d front =
          surface.visible_front || !surface.visible_back ? data.front : data.back;
      const OpenMesh::Vec3d back =
          surface.visible_back || !surface.visible_front ? data.back : data.front;
      const glm::dvec3& n = normals[static_cast<size_t>(vh.idx())];
      PreviewVertex pv{};
      for (int i = 0; i < 3; ++i) {
        pv.position[i] = static_cast<float>(q[i]);
        pv.normal[i] = static_cast<float>(n[i]);
        pv.front[i] = static_cast<float>(front[i]);
        pv.back[i] = static_cast<float>(back[i]);
      }
      pv.alpha = alpha;
      g.vertices.push_back(pv);
      g.positions.emplace_back(q[0], q[1], q[2]);
    }
  }
  return g;
}

/// Reorders the triangles of `indices` back to front: ascending view-space centroid z (the
/// camera looks down -z), ties by original index, so the order is fully deterministic.
void sort_back_to_front(const glm::dmat4& view_from_object,
                        const std::vector<glm::dvec3>& positions, std::vector<uint32_t>& indices) {
  const size_t n = indices.size() / 3;
  std::vector<double> depth(n);
  const glm::dvec4 z_row(view_from_object[0][2], view_from_object[1][2], view_from_object[2][2],
                         view_from_object[3][2]);
  for (size_t t = 0; t < n; ++t) {
    const glm::dvec3 c = (positions[indices[3 * t]] + positions[indices[3 * t + 1]] +
                          positions[indices[3 * t + 2]]) /
                         3.0;
    depth[t] = glm::dot(z_row, glm::dvec4(c, 1.0));
  }
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return depth[a] < depth[b] || (depth[a] == depth[b] && a < b);
  });
  std::vector<uint32_t> sorted(indices.size());
  for (size_t t = 0; t < n; ++t)
    for (int i = 0; i < 3; ++i) sorted[3 * t + i] = indices[3 * order[t] + i];
  indices = std::move(sorted);
}

}  // namespace

Image render_model_preview(const DsModel& model, const PreviewOptions& options) {
  check_options(options);
  if (model.face_count() == 0)
    throw InternalError("render_model_preview: model '" + model.name + "' has no triangles");
  const glm::dvec3 centre = 0.5 * (model.bbox_min + model.bbox_max);
  const double diagonal_m = glm::length(model.bbox_max - model.bbox_min);
  if (!(diagonal_m > 0) || !std::isfinite(diagonal_m))
    throw InternalError("render_model_preview: model '" + model.name +
                        "' has an empty or non-finite bounding box (update_bounds()?)");
  PreviewGeometry geometry = build_geometry(model, options);
  // Bounding sphere about the bbox centre, through the farthest vertex (tighter than the bbox's
  // circumscribed sphere for round fruit).
  double radius = 0;
  for (const glm::dvec3& p : geometry.positions) radius = std::max(radius, glm::length(p - centre));

  // Camera: orbit the bbox centre; the bounding sphere fits the shorter side's field of view.
  const double aspect = static_cast<double>(options.width) / options.height;
  const double half_fov_short = glm::radians(options.fov_deg) / 2;
  const double half_fov_y =
      aspect >= 1 ? half_fov_short : std::atan(std::tan(half_fov_short) / aspect);
  const double distance = kFitMargin * radius / std::sin(half_fov_short);
  const double azimuth = glm::radians(options.azimuth_deg);
  const double elevation = glm::radians(options.elevation_deg);
  const glm::dvec3 eye_dir(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                           std::cos(elevation) * std::cos(azimuth));
  AssetCamera camera;  // the model's frame is the scene frame here
  camera.eye = centre + distance * eye_dir;
  camera.target = centre;
  camera.up = {0, 1, 0};
  const glm::dmat4 view_from_object = view_from_scene(camera);
  const double near_m = std::max(distance - 1.5 * radius, 0.01 * distance);
  const double far_m = distance + 1.5 * radius;
  const glm::dmat4 clip_from_view = glm::perspective(2 * half_fov_y, aspect, near_m, far_m);

  sort_back_to_front(view_from_object, geometry.positions, geometry.indices);

  const std::unique_ptr<GlContext> context = create_offscreen_context();
  // The vertex array and buffers below are not deleted one by one: they belong to `context`,
  // which frees them.
  const GlProgram program("preview.vert", "preview.frag");

  const OffscreenTarget target(*context, options.width, options.height, options.samples,
                               "render_model_preview");

  make_vertex_array(geometry.vertices, geometry.indices,
                    {{0, 3, offsetof(PreviewVertex, position)},
                     {1, 3, offsetof(PreviewVertex, normal)},
                     {2, 3, offsetof(PreviewVertex, front)},
                     {3, 3, offsetof(PreviewVertex, back)},
                     {4, 1, offsetof(PreviewVertex, alpha)}});

  glUseProgram(program.id());
  const glm::mat4 view_from_object_f(view_from_object), clip_from_view_f(clip_from_view);
  glUniformMatrix4fv(program.uniform("view_from_object"), 1, GL_FALSE,
                     glm::value_ptr(view_from_object_f));
  glUniformMatrix4fv(program.uniform("clip_from_view"), 1, GL_FALSE,
                     glm::value_ptr(clip_from_view_f));

  target.clear(options.background_srgb);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);
  glEnable(GL_BLEND);
  // Straight-alpha "over" in linear RGB; the destination alpha stays 1 (opaque background).
  glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(geometry.indices.size()), GL_UNSIGNED_INT,
                 nullptr);

  return target.resolve_and_read();
}

}  // namespace cutaway
