#include "npr/silhouettes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>

#include "base/constants.h"
#include "base/error.h"

namespace cutaway {
namespace {

constexpr int kMaxImageSide = 16384;

/// The camera as render_scene_preview sets it up: scene -> view (right-handed, looking down -z)
/// and view -> pixel (x right, y down from the top row, pixel centres at +0.5).
struct Projection {
  glm::dmat4 view_from_scene{1.0};
  double fx = 1, fy = 1;  // pixels per unit of x/-z and y/-z
  double cx = 0, cy = 0;  // image centre, pixels
  double znear = 0.01;
  double pixel_per_depth = 1;  // size of one pixel at depth d is d / pixel_per_depth

  glm::dvec3 view(const glm::dvec3& scene) const {
    return glm::dvec3(view_from_scene * glm::dvec4(scene, 1.0));
  }
  /// (pixel x, pixel y, depth) of a view-frame point; depth = -z.
  glm::dvec3 pixel(const glm::dvec3& v) const {
    const double d = -v.z;
    return {cx + fx * v.x / d, cy - fy * v.y / d, d};
  }
};

Projection make_projection(const AssetCamera& c, int width, int height) {
  Projection p;
  p.view_from_scene = view_from_scene(c);
  p.fy = focal_length_px(c, height);
  p.fx = p.fy;  // square pixels: the aspect is the image's
  p.cx = width / 2.0;
  p.cy = height / 2.0;
  p.znear = c.znear;
  p.pixel_per_depth = p.fy;
  return p;
}

/// Nearest depth per pixel over every instance's triangles (perspective-correct).
class DepthBuffer {
 public:
  DepthBuffer(int w, int h) : w_(w), h_(h), depth_(static_cast<size_t>(w) * h, kFar) {}

  void triangle(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    // a, b, c: (pixel x, pixel y, depth)
    const double area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (!(std::abs(area) > 1e-12)) return;
    const int x0 = std::max(0, static_cast<int>(std::floor(std::min({a.x, b.x, c.x}))));
    const int x1 = std::min(w_ - 1, static_cast<int>(std::ceil(std::max({a.x, b.x, c.x}))));
    const int y0 = std::max(0, static_cast<int>(std::floor(std::min({a.y, b.y, c.y}))));
    const int y1 = std::min(h_ - 1, static_cast<int>(std::ceil(std::max({a.y, b.y, c.y}))));
    if (x0 > x1 || y0 > y1) return;
    const double ia = 1 / a.z, ib = 1 / b.z, ic = 1 / c.z;
    const double inv = 1 / area;
    for (int y = y0; y <= y1; ++y) {
      const double py = y + 0.5;
      for (int x = x0; x <= x1; ++x) {
        const double px = x + 0.5;
        const double wa = ((b.x - px) * (c.y - py) - (b.y - py) * (c.x - px)) * inv;
        const double wb = ((c.x - px) * (a.y - py) - (c.y - py) * (a.x - px)) * inv;
        const double wc = 1 - wa - wb;
        if (wa < 0 || wb < 0 || wc < 0) continue;
        const auto d = static_cast<float>(1 / (wa * ia + wb * ib + wc * ic));
        float& cell = depth_[static_cast<size_t>(y) * w_ + x];
        if (d < cell) cell = d;
      }
    }
  }

  /// Whether a point at pixel (x, y) and depth d is within `tolerance` of the nearest surface
  /// at some pixel of its 3x3 neighbourhood (so silhouettes, where the neighbourhood reaches
  /// past the outline, count as visible).
  bool visible(double x, double y, double d, double tolerance) const {
    const int ix = static_cast<int>(std::floor(x)), iy = static_cast<int>(std::floor(y));
    if (ix < 0 || iy < 0 || ix >= w_ || iy >= h_) return false;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const int qx = ix + dx, qy = iy + dy;
        if (qx < 0 || qy < 0 || qx >= w_ || qy >= h_) return true;
        if (depth_[static_cast<size_t>(qy) * w_ + qx] >= d - tolerance) return true;
      }
    return false;
  }

 private:
  static constexpr float kFar = std::numeric_limits<float>::infinity();
  int w_, h_;
  std::vector<float> depth_;
};

/// The welded topology of one mesh: vertices merged by exact position, and every edge with the
/// (non-degenerate) faces around it.
struct Topology {
  std::vector<uint32_t> weld;            // per mesh vertex: welded id
  std::vector<uint32_t> representative;  // per welded id: one mesh vertex
  std::vector<glm::dvec3> face_normal;   // per triangle, unnormalised; zero when degenerate
  struct Edge {
    uint32_t a, b;                    // welded ids, a < b
    uint32_t first_face, face_count;  // into edge_faces
  };
  std::vector<Edge> edges;
  std::vector<uint32_t> edge_faces;
};

struct PositionHash {
  size_t operator()(const glm::dvec3& p) const {
    uint64_t h = 1469598103934665603ull;
    for (int i = 0; i < 3; ++i) {
      double v = p[i] == 0 ? 0.0 : p[i];  // -0 and +0 weld
      uint64_t bits;
      std::memcpy(&bits, &v, sizeof bits);
      h = (h ^ bits) * 1099511628211ull;
      h ^= h >> 29;
    }
    return static_cast<size_t>(h);
  }
};

Topology make_topology(const AssetMesh& mesh) {
  Topology t;
  std::unordered_map<glm::dvec3, uint32_t, PositionHash> ids;
  ids.reserve(mesh.position.size());
  t.weld.resize(mesh.position.size());
  for (size_t v = 0; v < mesh.position.size(); ++v) {
    glm::dvec3 p = mesh.position[v];
    for (int i = 0; i < 3; ++i)
      if (p[i] == 0) p[i] = 0.0;
    const auto [it, inserted] = ids.emplace(p, static_cast<uint32_t>(t.representative.size()));
    if (inserted) t.representative.push_back(static_cast<uint32_t>(v));
    t.weld[v] = it->second;
  }
  t.face_normal.resize(mesh.triangle.size(), glm::dvec3(0.0));
  std::vector<std::pair<uint64_t, uint32_t>> keyed;  // (edge key, face)
  keyed.reserve(3 * mesh.triangle.size());
  for (size_t f = 0; f < mesh.triangle.size(); ++f) {
    const glm::uvec3& tri = mesh.triangle[f];
    const uint32_t w[3] = {t.weld[tri.x], t.weld[tri.y], t.weld[tri.z]};
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;
    const glm::dvec3 n = glm::cross(mesh.position[tri.y] - mesh.position[tri.x],
                                    mesh.position[tri.z] - mesh.position[tri.x]);
    if (!(glm::length(n) > 0)) continue;
    t.face_normal[f] = n;
    for (int i = 0; i < 3; ++i) {
      const uint32_t a = std::min(w[i], w[(i + 1) % 3]), b = std::max(w[i], w[(i + 1) % 3]);
      keyed.emplace_back((static_cast<uint64_t>(a) << 32) | b, static_cast<uint32_t>(f));
    }
  }
  std::sort(keyed.begin(), keyed.end());
  for (size_t i = 0; i < keyed.size();) {
    size_t j = i;
    while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
    Topology::Edge e;
    e.a = static_cast<uint32_t>(keyed[i].first >> 32);
    e.b = static_cast<uint32_t>(keyed[i].first & 0xffffffffu);
    e.first_face = static_cast<uint32_t>(t.edge_faces.size());
    e.face_count = static_cast<uint32_t>(j - i);
    for (size_t k = i; k < j; ++k) t.edge_faces.push_back(keyed[k].second);
    t.edges.push_back(e);
    i = j;
  }
  return t;
}

/// Faces whose normals are closer than about 8 degrees lie in one face of the object: a seam
/// between them is a structure line, not a flat-shaded edge.
constexpr double kCoplanarCos = 0.99;

/// Feature edges projecting at least this long (pixels) are split into the runs of them in
/// sight, of at least kMinRun_px one-pixel samples each; shorter ones are kept whole when most
/// of them is in sight.
constexpr double kSplitEdge_px = 24;
constexpr int kMinRun_px = 4;

/// A visible feature edge of one instance.
struct FeatureEdge {
  uint32_t a, b;      // welded ids
  glm::dvec3 colour;  // of the face turned toward the eye
};

glm::dvec2 xy(const glm::dvec3& v) { return {v.x, v.y}; }

/// Links the edges into polylines of welded ids (see extract_strokes). `screen`: per welded id.
std::vector<std::pair<std::vector<uint32_t>, glm::dvec3>> link_edges(
    const std::vector<FeatureEdge>& edges, const std::vector<glm::dvec3>& screen,
    double max_turn_deg, std::vector<bool>* closed_out) {
  std::unordered_map<uint32_t, std::vector<uint32_t>> at;  // welded id -> edges
  for (uint32_t e = 0; e < edges.size(); ++e) {
    at[edges[e].a].push_back(e);
    at[edges[e].b].push_back(e);
  }
  const double min_cos = std::cos(glm::radians(max_turn_deg));
  std::vector<bool> used(edges.size(), false);
  std::vector<std::pair<std::vector<uint32_t>, glm::dvec3>> lines;
  closed_out->clear();

  // Extends `line` from its back while an unused edge continues it within the turn limit.
  const auto extend = [&](std::vector<uint32_t>& line, glm::dvec3& colour_sum, size_t& count) {
    for (;;) {
      const uint32_t end = line.back(), prev = line[line.size() - 2];
      const glm::dvec2 in = xy(screen[end]) - xy(screen[prev]);
      const double in_len = glm::length(in);
      double best = -2;
      uint32_t best_edge = UINT32_MAX;
      for (uint32_t e : at[end]) {
        if (used[e]) continue;
        const uint32_t next = edges[e].a == end ? edges[e].b : edges[e].a;
        const glm::dvec2 out = xy(screen[next]) - xy(screen[end]);
        const double out_len = glm::length(out);
        const double c = in_len > 0 && out_len > 0 ? glm::dot(in, out) / (in_len * out_len) : 1;
        if (c > best) {
          best = c;
          best_edge = e;
        }
      }
      if (best_edge == UINT32_MAX || best < min_cos) return;
      used[best_edge] = true;
      colour_sum += edges[best_edge].colour;
      ++count;
      const uint32_t next = edges[best_edge].a == end ? edges[best_edge].b : edges[best_edge].a;
      line.push_back(next);
      if (next == line.front()) return;  // closed loop
    }
  };

  for (uint32_t e = 0; e < edges.size(); ++e) {
    if (used[e]) continue;
    used[e] = true;
    std::vector<uint32_t> line = {edges[e].a, edges[e].b};
    glm::dvec3 colour_sum = edges[e].colour;
    size_t count = 1;
    extend(line, colour_sum, count);
    bool closed = line.size() > 3 && line.back() == line.front();
    if (closed) {
      line.pop_back();
    } else {
      std::reverse(line.begin(), line.end());
      extend(line, colour_sum, count);
      std::reverse(line.begin(), line.end());
    }
    lines.emplace_back(std::move(line), colour_sum / static_cast<double>(count));
    closed_out->push_back(closed);
  }
  return lines;
}

/// Scene-frame placement of an instance.
glm::dmat4 placement(const AssetInstance& inst) {
  return glm::translate(glm::dmat4(1.0), inst.translation) *
         glm::mat4_cast(glm::normalize(inst.rotation));
}

/// Step 1: the depth buffer of every instance's triangles, and each instance's vertices in
/// pixels (x, y, depth; depth -1 behind the near plane) in `pixels`.
DepthBuffer scene_depth(const SceneAssets& assets, const Projection& proj, int width, int height,
                        std::vector<std::vector<glm::dvec3>>& pixels) {
  DepthBuffer depth(width, height);
  pixels.assign(assets.instances.size(), {});
  for (size_t i = 0; i < assets.instances.size(); ++i) {
    const AssetInstance& inst = assets.instances[i];
    const AssetMesh& mesh = assets.meshes[static_cast<size_t>(inst.mesh)];
    const glm::dmat4 view_from_object = proj.view_from_scene * placement(inst);
    std::vector<glm::dvec3>& px = pixels[i];
    px.resize(mesh.position.size());
    for (size_t v = 0; v < mesh.position.size(); ++v) {
      const glm::dvec3 p(view_from_object * glm::dvec4(mesh.position[v], 1.0));
      px[v] = -p.z > proj.znear ? proj.pixel(p) : glm::dvec3(0, 0, -1);
    }
    for (const glm::uvec3& t : mesh.triangle) {
      if (px[t.x].z <= 0 || px[t.y].z <= 0 || px[t.z].z <= 0) continue;  // crosses znear
      depth.triangle(px[t.x], px[t.y], px[t.z]);
    }
  }
  return depth;
}

/// The points strokes run through, by id: a mesh's welded vertices, then points where a long
/// edge goes in or out of sight; in the object frame and in pixels with depth.
struct StrokePoints {
  std::vector<glm::dvec3> point, screen;

  /// The id of the point at screen parameter t of edge a-b (perspective-correct), added.
  uint32_t add_on(uint32_t a, uint32_t b, double t) {
    const double inv_d = (1 - t) / screen[a].z + t / screen[b].z;
    const double s = (t / screen[b].z) / inv_d;  // the object-space parameter
    point.push_back(glm::mix(point[a], point[b], s));
    screen.push_back(glm::dvec3(glm::mix(xy(screen[a]), xy(screen[b]), t), 1 / inv_d));
    return static_cast<uint32_t>(point.size() - 1);
  }
};

/// One instance's mesh as steps 2 and 3 see it.
struct InstanceView {
  const AssetMesh& mesh;
  const Topology& topo;
  const std::vector<glm::dvec3>& px;  ///< its vertices in pixels
  std::vector<int8_t> facing;         ///< per triangle: +1 toward the eye, -1 away, 0 degenerate
};

/// Steps 2 and 3 for one instance: its feature edges (borders, silhouettes between front- and
/// back-facing triangles, creases sharper than crease_deg) in sight, into `outlines`, and
/// with options.structure_width the seams inside smooth surfaces (structure lines inside cut
/// faces) in sight, into `structure`. An edge is in sight by the majority of its samples
/// against `depth`; a long edge partly hidden is split into its runs in sight.
void visible_feature_edges(const InstanceView& in, const DepthBuffer& depth, const Projection& proj,
                           const StrokeOptions& options, StrokePoints& points,
                           std::vector<FeatureEdge>& outlines,
                           std::vector<FeatureEdge>& structure) {
  const AssetMesh& mesh = in.mesh;
  const Topology& topo = in.topo;
  const double crease_cos = std::cos(glm::radians(options.crease_deg));
  // The mesh vertex of triangle f that welds to `w`.
  const auto corner = [&](uint32_t f, uint32_t w) {
    const glm::uvec3& tri = mesh.triangle[f];
    for (int k = 0; k < 3; ++k)
      if (topo.weld[tri[k]] == w) return tri[k];
    return tri[0];
  };
  // Two copies of a vertex that differ only in texture coordinates (made for a texture's
  // seam: a skin's t_section = 0, its poles) are one vertex of the surface.
  const auto same_copy = [&](uint32_t u, uint32_t v) {
    return u == v || (!mesh.uv.empty() && mesh.uv[u] != mesh.uv[v] &&
                      mesh.colour[u] == mesh.colour[v] && mesh.normal[u] == mesh.normal[v]);
  };
  for (const Topology::Edge& e : topo.edges) {
    const uint32_t* faces = &topo.edge_faces[e.first_face];
    bool feature = false, seam = false;
    int front_face = -1;
    for (uint32_t k = 0; k < e.face_count; ++k)
      if (in.facing[faces[k]] > 0) front_face = static_cast<int>(faces[k]);
    if (e.face_count != 2) {
      feature = true;
    } else {
      const uint32_t f0 = faces[0], f1 = faces[1];
      if (in.facing[f0] != in.facing[f1]) {
        feature = true;
      } else if (front_face >= 0) {
        const glm::dvec3 &n0 = topo.face_normal[f0], &n1 = topo.face_normal[f1];
        feature = glm::dot(n0, n1) < crease_cos * glm::length(n0) * glm::length(n1);
        // A seam inside a smooth surface: the two faces use different copies of the edge's
        // vertices. Cross-sections split their vertices exactly along the cut segments, so
        // these are the outlines of the structures inside a cut face.
        seam = !feature && options.structure_width > 0 &&
               glm::dot(n0, n1) > kCoplanarCos * glm::length(n0) * glm::length(n1) &&
               (!same_copy(corner(f0, e.a), corner(f1, e.a)) ||
                !same_copy(corner(f0, e.b), corner(f1, e.b)));
      }
    }
    if (!feature && !seam) continue;
    const uint32_t va = topo.representative[e.a], vb = topo.representative[e.b];
    const glm::dvec3 &pa = in.px[va], &pb = in.px[vb];
    if (pa.z <= 0 || pb.z <= 0) continue;
    const double length = glm::length(glm::dvec2(pb - pa));
    const int n = std::clamp(static_cast<int>(std::ceil(length)), 3, 512);
    std::vector<bool> sample_seen(static_cast<size_t>(n));
    int seen = 0;
    for (int k = 0; k < n; ++k) {
      const double t = (k + 0.5) / n;
      // Perspective-correct depth along the projected edge.
      const double inv_d = (1 - t) / pa.z + t / pb.z;
      const double d = 1 / inv_d;
      const glm::dvec2 s = glm::mix(glm::dvec2(pa), glm::dvec2(pb), t);
      const double tolerance = 1e-3 * d + 2.5 * d / proj.pixel_per_depth;
      sample_seen[static_cast<size_t>(k)] = depth.visible(s.x, s.y, d, tolerance);
      seen += sample_seen[static_cast<size_t>(k)];
    }
    const int cf = front_face >= 0 ? front_face : static_cast<int>(faces[0]);
    const glm::uvec3& tri = mesh.triangle[static_cast<size_t>(cf)];
    const glm::dvec3 colour = (mesh.colour[tri.x] + mesh.colour[tri.y] + mesh.colour[tri.z]) / 3.0;
    std::vector<FeatureEdge>& out = seam ? structure : outlines;
    if (length < kSplitEdge_px || seen == n) {  // short, or all in sight: by majority
      if (2 * seen >= n) out.push_back({e.a, e.b, colour});
      continue;
    }
    // A long edge partly hidden (a board's edge behind a piece): its runs in sight of at
    // least kMinRun_px samples, each a stroke edge of its own.
    for (int k = 0; k < n;) {
      if (!sample_seen[static_cast<size_t>(k)]) {
        ++k;
        continue;
      }
      int end = k;
      while (end < n && sample_seen[static_cast<size_t>(end)]) ++end;
      if (end - k >= kMinRun_px) {
        const uint32_t from = k == 0 ? e.a : points.add_on(e.a, e.b, static_cast<double>(k) / n);
        const uint32_t to = end == n ? e.b : points.add_on(e.a, e.b, static_cast<double>(end) / n);
        out.push_back({from, to, colour});
      }
      k = end;
    }
  }
}

/// Step 5 for one linked line (point ids `ids`, object frame): placed by `scene_from_object`,
/// smoothed (options.smoothing passes, each point moved at most smoothing_shift_px), tapered
/// along its projected arc length (closed lines keep 60 % of the width at least); none when
/// shorter than options.min_length_px.
std::optional<Stroke> taper_stroke(const std::vector<uint32_t>& ids, bool closed,
                                   const glm::dvec3& colour, double line_width,
                                   const glm::dmat4& scene_from_object,
                                   const std::vector<glm::dvec3>& point, const Projection& proj,
                                   const StrokeOptions& options) {
  if (ids.size() < 2) return std::nullopt;
  Stroke s;
  s.closed = closed;
  for (uint32_t w : ids) s.points.emplace_back(scene_from_object * glm::dvec4(point[w], 1.0));
  const size_t n = s.points.size();
  for (int pass = 0; pass < options.smoothing && n > 2; ++pass) {
    std::vector<glm::dvec3> q = s.points;
    for (size_t k = 0; k < n; ++k) {
      if (!s.closed && (k == 0 || k + 1 == n)) continue;
      const glm::dvec3& prev = s.points[(k + n - 1) % n];
      const glm::dvec3& next = s.points[(k + 1) % n];
      const glm::dvec3 shift = 0.25 * (prev + next) - 0.5 * s.points[k];
      const double limit =
          options.smoothing_shift_px * -proj.view(s.points[k]).z / proj.pixel_per_depth;
      const double length = glm::length(shift);
      q[k] = s.points[k] + (length > limit ? shift * (limit / length) : shift);
    }
    s.points = std::move(q);
  }
  // Projected arc length.
  std::vector<double> arc(n + 1, 0.0);
  std::vector<glm::dvec2> sp;
  for (const glm::dvec3& p : s.points) sp.emplace_back(proj.pixel(proj.view(p)));
  for (size_t k = 1; k <= n; ++k) {
    if (k == n && !s.closed) {
      arc[n] = arc[n - 1];
      break;
    }
    arc[k] = arc[k - 1] + glm::length(sp[k % n] - sp[k - 1]);
  }
  const double total = s.closed ? arc[n] : arc[n - 1];
  if (!(total >= options.min_length_px)) return std::nullopt;
  const double scale = options.strength * std::min(1.0, std::sqrt(total / (30 * line_width)));
  s.width_px.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const double t = arc[k] / total;
    const double profile = s.closed ? 0.8 + 0.2 * std::cos(2 * kPi * t)
                                    : 0.15 + 0.85 * std::pow(std::sin(kPi * t), 0.6);
    s.width_px[k] = line_width * scale * profile;
  }
  s.colour = options.darkening * colour;
  return s;
}

}  // namespace

std::vector<Stroke> extract_strokes(const SceneAssets& assets, const StrokeOptions& options) {
  const int width = options.width != 0 ? options.width : assets.width;
  const int height = options.height != 0 ? options.height : assets.height;
  if (width < 1 || height < 1 || width > kMaxImageSide || height > kMaxImageSide)
    throw InternalError("extract_strokes: image size " + std::to_string(width) + "x" +
                        std::to_string(height) + " is outside 1..16384");
  for (const AssetInstance& inst : assets.instances)
    if (inst.mesh < 0 || static_cast<size_t>(inst.mesh) >= assets.meshes.size())
      throw InternalError("extract_strokes: instance '" + inst.name + "' has no valid mesh index");
  std::vector<Stroke> strokes;
  if (!(options.strength > 0)) return strokes;

  const Projection proj = make_projection(assets.camera, width, height);
  std::vector<std::vector<glm::dvec3>> pixels;
  const DepthBuffer depth = scene_depth(assets, proj, width, height, pixels);
  const double base_width = options.width_px > 0 ? options.width_px : std::max(1.5, height / 320.0);
  std::unordered_map<int, Topology> topologies;  // per mesh index, built once

  for (size_t i = 0; i < assets.instances.size(); ++i) {
    const AssetInstance& inst = assets.instances[i];
    const AssetMesh& mesh = assets.meshes[static_cast<size_t>(inst.mesh)];
    if (mesh.triangle.empty()) continue;
    auto found = topologies.find(inst.mesh);
    if (found == topologies.end()) found = topologies.emplace(inst.mesh, make_topology(mesh)).first;
    const Topology& topo = found->second;
    // 2. Which triangles face the eye (in the mesh frame).
    InstanceView view{mesh, topo, pixels[i], std::vector<int8_t>(mesh.triangle.size(), 0)};
    const glm::dvec3 eye_object =
        glm::conjugate(glm::normalize(inst.rotation)) * (assets.camera.eye - inst.translation);
    for (size_t f = 0; f < mesh.triangle.size(); ++f) {
      const glm::dvec3& n = topo.face_normal[f];
      if (n == glm::dvec3(0.0)) continue;
      view.facing[f] = glm::dot(n, eye_object - mesh.position[mesh.triangle[f].x]) > 0 ? 1 : -1;
    }
    // 3. Feature edges in sight: outlines, and structure lines inside cut faces.
    StrokePoints points;
    points.point.resize(topo.representative.size());
    points.screen.resize(topo.representative.size());
    for (size_t w = 0; w < topo.representative.size(); ++w) {
      points.point[w] = mesh.position[topo.representative[w]];
      points.screen[w] = pixels[i][topo.representative[w]];
    }
    std::vector<FeatureEdge> visible, structure;
    visible_feature_edges(view, depth, proj, options, points, visible, structure);
    if (visible.empty() && structure.empty()) continue;

    // 4. Linking, outlines and structure lines apart.
    std::vector<bool> closed, structure_closed;
    auto lines = link_edges(visible, points.screen, options.max_turn_deg, &closed);
    const size_t outlines = lines.size();
    const auto structure_lines =
        link_edges(structure, points.screen, options.max_turn_deg, &structure_closed);
    lines.insert(lines.end(), structure_lines.begin(), structure_lines.end());
    closed.insert(closed.end(), structure_closed.begin(), structure_closed.end());

    // 5. Strokes: smoothed, filtered by length, tapered.
    const glm::dmat4 scene_from_object = placement(inst);
    for (size_t l = 0; l < lines.size(); ++l) {
      const double line_width = l < outlines ? base_width : base_width * options.structure_width;
      if (std::optional<Stroke> s =
              taper_stroke(lines[l].first, closed[l], lines[l].second, line_width,
                           scene_from_object, points.point, proj, options))
        strokes.push_back(std::move(*s));
    }
  }
  return strokes;
}

}  // namespace cutaway
