#include "variation/grains.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <sstream>

#include <glm/geometric.hpp>

#include "base/area_sampling.h"
#include "base/constants.h"
#include "base/error.h"
#include "base/point_grid.h"
#include "model/inside_test.h"

namespace cutaway {

namespace {

constexpr uint64_t kPurposeGrains = 0x677261696e;  // "grain"

glm::dvec3 point(const DsMesh& m, DsMesh::VertexHandle v) { return to_glm(m.point(v)); }

bool in_range(double x, const glm::dvec2& r) { return x >= r.x - 1e-12 && x <= r.y + 1e-12; }

glm::dvec3 any_perpendicular(const glm::dvec3& n) {
  const glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(n, a));
}

/// The triangles of `on` whose three vertices' params lie in the grain's region.
struct RegionTriangles {
  std::vector<std::array<int, 3>> vertices;
  std::vector<double> area;  ///< m^2, per triangle
};

RegionTriangles region_triangles(const GrainSpec& spec, const DsMesh& m) {
  RegionTriangles r;
  for (auto fh : m.faces()) {
    std::array<int, 3> t;
    int k = 0;
    bool inside = true;
    for (auto vh : m.fv_range(fh)) {
      t[k++] = vh.idx();
      const auto& par = m.data(vh).param;
      inside &= in_range(par[0], spec.region_profile) && in_range(par[1], spec.region_section);
    }
    if (!inside) continue;
    const glm::dvec3 a = point(m, m.vertex_handle(t[0])), b = point(m, m.vertex_handle(t[1])),
                     c = point(m, m.vertex_handle(t[2]));
    const double area = 0.5 * glm::length(glm::cross(b - a, c - a));
    if (!(area > 0)) continue;
    r.vertices.push_back(t);
    r.area.push_back(area);
  }
  return r;
}

/// The vertices of grain g's ellipsoid mesh (a UV sphere of opt.rings x opt.segments, poles on
/// the normal axis), metres: the bottom pole, the rings from the bottom up, the top pole.
std::vector<glm::dvec3> ellipsoid_points(const GrainPlacement& g, const GrainOptions& opt) {
  const int R = std::max(2, opt.rings), S = std::max(3, opt.segments);
  std::vector<glm::dvec3> out;
  out.reserve(2 + static_cast<size_t>(R - 1) * S);
  auto add = [&](double x, double y, double z) {
    out.push_back(g.centre + g.axis_profile * (g.semi_axes.x * x) +
                  g.axis_section * (g.semi_axes.y * y) + g.axis_normal * (g.semi_axes.z * z));
  };
  add(0, 0, -1);  // bottom pole
  for (int i = 1; i < R; ++i) {
    const double th = kPi * i / R - kPi / 2;
    for (int j = 0; j < S; ++j) {
      const double ph = 2 * kPi * j / S;
      add(std::cos(th) * std::cos(ph), std::cos(th) * std::sin(ph), std::sin(th));
    }
  }
  add(0, 0, 1);  // top pole
  return out;
}

/// The triangles of every ellipsoid mesh, as indices into ellipsoid_points, wound outwards:
/// (x, y, z) right-handed with x, y tangent and z the normal, counter-clockwise about +z is
/// outward at the top.
std::vector<std::array<int, 3>> ellipsoid_faces(const GrainOptions& opt) {
  const int R = std::max(2, opt.rings), S = std::max(3, opt.segments);
  const int top = 1 + (R - 1) * S;
  auto ring = [&](int i, int j) { return 1 + (i - 1) * S + (j % S); };
  std::vector<std::array<int, 3>> out;
  for (int j = 0; j < S; ++j) out.push_back({0, ring(1, j + 1), ring(1, j)});
  for (int i = 1; i + 1 < R; ++i)
    for (int j = 0; j < S; ++j) {
      out.push_back({ring(i, j), ring(i, j + 1), ring(i + 1, j + 1)});
      out.push_back({ring(i, j), ring(i + 1, j + 1), ring(i + 1, j)});
    }
  for (int j = 0; j < S; ++j) out.push_back({ring(R - 1, j), ring(R - 1, j + 1), top});
  return out;
}

/// The triangles of grain g's ellipsoid mesh, as add_ellipsoids makes it.
std::vector<std::array<glm::dvec3, 3>> ellipsoid_triangles(const GrainPlacement& g,
                                                           const GrainOptions& opt) {
  const std::vector<glm::dvec3> p = ellipsoid_points(g, opt);
  std::vector<std::array<glm::dvec3, 3>> out;
  for (const auto& f : ellipsoid_faces(opt)) out.push_back({p[f[0]], p[f[1]], p[f[2]]});
  return out;
}

/// The surface of `model` (not a grain set) named `name`. @pre there is one
const DsSurface& surface_named(const std::string& name, const DsModel& model) {
  const DsSurface* on = nullptr;
  for (const auto& s : model.surfaces)
    if (s.name == name && s.role != SurfaceRole::Grain) on = &s;
  CUTAWAY_CHECK(on != nullptr);
  return *on;
}

/// Counts a dart rejected for crossing surface `hit` in `crossings` (when given).
void count_crossing(std::vector<size_t>* crossings, int hit) {
  if (!crossings) return;
  if (crossings->size() <= static_cast<size_t>(hit)) crossings->resize(hit + 1, 0);
  ++(*crossings)[static_cast<size_t>(hit)];
}

/// One run of dart throwing (Poisson-disc sampling: Cook 1986, "Stochastic sampling in computer
/// graphics"): the accepted grains, the test of a new centre against them, and the count of
/// consecutive rejected darts that ends the run.
class DartThrow {
 public:
  DartThrow(double spacing, const GrainOptions& opt)
      : spacing_(spacing), grid_{spacing, {}}, opt_(opt) {}

  /// Whether to throw another dart: fewer than max_consecutive_failures rejected in a row and
  /// fewer than max_grains accepted.
  bool running() const {
    return failures_ < opt_.max_consecutive_failures && out_.size() < opt_.max_grains;
  }

  /// Whether `centre` lies at least the spacing from every accepted centre; a dart that does
  /// not is rejected (counted).
  bool far_enough(const glm::dvec3& centre) {
    bool ok = true;
    grid_.visit_near(centre, [&](size_t j) {
      ok = glm::distance(out_[j].centre, centre) >= spacing_;
      return ok;
    });
    if (!ok) ++failures_;
    return ok;
  }

  /// Whether grain `g` is refused for crossing surface `hit` (>= 0; -1: crosses nothing); a
  /// refused dart is counted, and in `crossings` too.
  bool crosses(int hit, std::vector<size_t>* crossings) {
    if (hit < 0) return false;
    count_crossing(crossings, hit);
    ++failures_;
    return true;
  }

  /// Rejects a dart for another reason (the grain reaches into a blur).
  void reject() { ++failures_; }

  /// Keeps grain `g` and starts the count of consecutive rejections again.
  void accept(const GrainPlacement& g) {
    failures_ = 0;
    grid_.add(g.centre, out_.size());
    out_.push_back(g);
  }

  std::vector<GrainPlacement>& grains() { return out_; }

 private:
  double spacing_;  ///< metres
  PointGrid grid_;
  const GrainOptions& opt_;
  std::vector<GrainPlacement> out_;
  int failures_ = 0;
};

/// A grain's size and turn jitter, drawn for every dart (accepted or not) so that the random
/// stream does not depend on acceptance order.
struct GrainJitter {
  double size;  ///< factor on the semi-axes, 1 +- jitter
  double turn;  ///< radians about the normal, +- jitter * pi / 2
};

GrainJitter draw_jitter(const GrainSpec& spec, Rng& rng) {
  GrainJitter j;
  j.size = 1 + spec.jitter * rng.uniform(-1.0, 1.0);
  j.turn = spec.jitter * 0.5 * kPi * rng.uniform(-1.0, 1.0);
  return j;
}

/// Grain at `centre` with normal axis `n` (unit) and profile axis `profile` (unit, at right
/// angles to n) turned by the jitter's turn about n; the section axis completes the frame.
GrainPlacement oriented_grain(const GrainSpec& spec, const glm::dvec3& surface_point,
                              const glm::dvec3& centre, const glm::dvec3& n,
                              const glm::dvec3& profile, const GrainJitter& j) {
  GrainPlacement g;
  g.surface_point = surface_point;
  g.centre = centre;
  g.axis_profile = std::cos(j.turn) * profile + std::sin(j.turn) * glm::cross(n, profile);
  g.axis_section = glm::cross(n, g.axis_profile);
  g.axis_normal = n;
  g.semi_axes = spec.semi_axes * j.size;
  return g;
}

const DsSurface& grain_support(const GrainSpec& spec, const DsModel& model) {
  return surface_named(spec.on, model);
}

/// The most grains a set may get: its surface region's area over the area a grain's Poisson
/// disc claims in the densest packing (sqrt(3)/2 spacing^2), or for grains through a region the
/// volume inside `inside` over the volume a ball of diameter spacing claims in the densest
/// packing (spacing^3 / sqrt(2)).
double most_grains(const GrainSpec& spec, const DsModel& model) {
  if (!spec.inside.empty()) {
    const double volume = std::fabs(signed_volume(surface_named(spec.inside, model).mesh));
    return volume / (spec.spacing * spec.spacing * spec.spacing / std::sqrt(2.0));
  }
  const double area =
      AreaSampler(region_triangles(spec, grain_support(spec, model).mesh).area).total();
  return area / (0.5 * std::sqrt(3.0) * spec.spacing * spec.spacing);
}

}  // namespace

void check_grain_limits(const Template& tmpl, const DsModel& model) {
  const DsMesh& skin = model.skin().mesh;
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (auto vh : skin.vertices()) {
    lo = glm::min(lo, point(skin, vh));
    hi = glm::max(hi, point(skin, vh));
  }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z});
  double before = 0;  // the most grains of the sets before this one
  for (const GrainSpec& spec : tmpl.grains) {
    // A core is a grain of its own (as many vertices) inside each grain.
    const double most = most_grains(spec, model) * (spec.core ? 2 : 1);
    if (before + most > kMaxGrains) {
      std::ostringstream s;
      s << "the spacing is too small for the region: up to " << static_cast<long long>(most)
        << (spec.core ? " grains and cores" : " grains") << " could fit";
      if (before > 0) s << ", " << static_cast<long long>(before) << " in the sets before it";
      s << " (at most " << kMaxGrains << " over all grain sets)";
      throw InputError(spec.spacing_loc, spec.path + ".spacing", s.str());
    }
    before += most;
    const double largest = std::max({spec.semi_axes.x, spec.semi_axes.y, spec.semi_axes.z});
    if (largest > extent) {
      std::ostringstream s;
      s << "a grain's semi-axis (" << largest * 1e3 << " mm) is larger than the object ("
        << extent * 1e3 << " mm across)";
      throw InputError(spec.shape_loc, spec.path + ".shape", s.str());
    }
    if (spec.spacing < largest) {
      std::ostringstream s;
      s << "the spacing (" << spec.spacing * 1e3 << " mm) is smaller than the grain's largest"
        << " semi-axis (" << largest * 1e3 << " mm): a grain would hold another's centre";
      throw InputError(spec.spacing_loc, spec.path + ".spacing", s.str());
    }
    if (spec.depth > extent) {
      std::ostringstream s;
      s << "the depth (" << spec.depth * 1e3 << " mm) is larger than the object (" << extent * 1e3
        << " mm across)";
      throw InputError(spec.loc, spec.path + ".depth", s.str());
    }
  }
}

std::vector<GrainPlacement> place_grains(const GrainSpec& spec, const DsSurface& on, Rng& rng,
                                         const GrainOptions& opt, const CrossingTest* obstacles,
                                         std::vector<size_t>* crossings) {
  CUTAWAY_CHECK(spec.spacing > 0);
  const DsMesh& m = on.mesh;
  const std::vector<glm::dvec3> normals = vertex_normals(m);
  const RegionTriangles region = region_triangles(spec, m);
  const auto& tris = region.vertices;
  const AreaSampler sampler(region.area);
  if (tris.empty()) return {};
  DartThrow darts(spec.spacing, opt);
  const double side = spec.on_front ? 1.0 : -1.0;
  while (darts.running()) {
    const AreaSample drawn = sampler.draw(rng);
    const size_t ti = drawn.triangle;
    const glm::dvec3& w = drawn.weights;
    glm::dvec3 p(0.0), n(0.0);
    glm::dvec3 pos[3];
    double tp[3];
    for (int k = 0; k < 3; ++k) {
      const auto vh = m.vertex_handle(tris[ti][k]);
      pos[k] = point(m, vh);
      tp[k] = m.data(vh).param[0];
      p += w[k] * pos[k];
      n += w[k] * normals[tris[ti][k]];
    }
    const glm::dvec3 fn = glm::cross(pos[1] - pos[0], pos[2] - pos[0]);
    n = glm::length(n) > 1e-12 ? glm::normalize(n) : glm::normalize(fn);
    const glm::dvec3 centre = p + side * spec.depth * n;
    const bool far_enough = darts.far_enough(centre);
    const GrainJitter jitter = draw_jitter(spec, rng);
    if (!far_enough) continue;
    // Gradient of t_profile over the triangle.
    const glm::dvec3 e1 = pos[1] - pos[0], e2 = pos[2] - pos[0];
    const double fa2 = glm::dot(fn, fn);
    glm::dvec3 grad(0.0);
    if (fa2 > 0) {
      grad = ((tp[1] - tp[0]) * glm::cross(e2, fn) + (tp[2] - tp[0]) * glm::cross(fn, e1)) / fa2;
    }
    grad -= glm::dot(grad, n) * n;
    const glm::dvec3 tprof =
        glm::length(grad) > 1e-12 ? glm::normalize(grad) : any_perpendicular(n);
    const GrainPlacement g = oriented_grain(spec, p, centre, n, tprof, jitter);
    if (obstacles && darts.crosses(obstacles->crossed(ellipsoid_triangles(g, opt)), crossings))
      continue;
    darts.accept(g);
  }
  return std::move(darts.grains());
}

RegionCells region_cells(const DsMesh& mesh, const InsideTest& inside, double spacing) {
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (auto vh : mesh.vertices()) {
    lo = glm::min(lo, point(mesh, vh));
    hi = glm::max(hi, point(mesh, vh));
  }
  RegionCells r;
  if (!(lo.x <= hi.x)) return r;
  // Cells of the spacing, at most 128 along the longest side.
  r.size = std::max(spacing, std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / 128);
  const glm::ivec3 n = glm::max(glm::ivec3(glm::ceil((hi - lo) / r.size)), glm::ivec3(1));
  std::vector<uint8_t> mark(static_cast<size_t>(n.x) * n.y * n.z, 0);
  const auto index = [&](int i, int j, int k) {
    return (static_cast<size_t>(k) * n.y + j) * n.x + i;
  };
  const auto cell_of = [&](const glm::dvec3& p) {
    return glm::clamp(glm::ivec3(glm::floor((p - lo) / r.size)), glm::ivec3(0), n - 1);
  };
  for (auto fh : mesh.faces()) {  // cells a triangle's bounding box reaches: the boundary
    glm::dvec3 a(INFINITY), b(-INFINITY);
    for (auto vh : mesh.fv_range(fh)) {
      a = glm::min(a, point(mesh, vh));
      b = glm::max(b, point(mesh, vh));
    }
    const glm::ivec3 c0 = cell_of(a), c1 = cell_of(b);
    for (int k = c0.z; k <= c1.z; ++k)
      for (int j = c0.y; j <= c1.y; ++j)
        for (int i = c0.x; i <= c1.x; ++i) mark[index(i, j, k)] = 1;
  }
  for (int k = 0; k < n.z; ++k)  // and those wholly inside: their centre is
    for (int j = 0; j < n.y; ++j)
      for (int i = 0; i < n.x; ++i) {
        const glm::dvec3 corner = lo + glm::dvec3(i, j, k) * r.size;
        const bool boundary = mark[index(i, j, k)] != 0;
        if (!boundary && !inside.inside(corner + 0.5 * r.size)) continue;
        r.corners.push_back(corner);
        r.interior.push_back(boundary ? 0 : 1);
      }
  return r;
}

std::vector<GrainPlacement> place_grains_inside(const GrainSpec& spec, const InsideTest& inside,
                                                const InsideTest* outside, const RegionCells& cells,
                                                Rng& rng, const GrainOptions& opt,
                                                const CrossingTest* obstacles,
                                                std::vector<size_t>* crossings) {
  CUTAWAY_CHECK(spec.spacing > 0);
  if (cells.corners.empty()) return {};
  DartThrow darts(spec.spacing, opt);
  size_t thrown = 0;
  const uint32_t cell_count = static_cast<uint32_t>(cells.corners.size());
  while (darts.running() && thrown < opt.max_region_darts) {
    ++thrown;
    const uint32_t cell = rng.below(cell_count);
    const glm::dvec3& corner = cells.corners[cell];
    const double ux = rng.uniform(), uy = rng.uniform(), uz = rng.uniform();
    const glm::dvec3 centre = corner + cells.size * glm::dvec3(ux, uy, uz);
    const GrainJitter jitter = draw_jitter(spec, rng);
    if (!(cells.interior[cell] || inside.inside(centre)) || (outside && outside->inside(centre)))
      continue;
    if (!darts.far_enough(centre)) continue;
    // The frame of the object's fields: normal out from the axis, profile axis up, section
    // axis around; then the jitter's turn about the normal.
    const double r = std::sqrt(centre.x * centre.x + centre.z * centre.z);
    const glm::dvec3 n = r > 1e-9 ? glm::dvec3(centre.x / r, 0, centre.z / r) : glm::dvec3(1, 0, 0);
    const GrainPlacement g = oriented_grain(spec, centre, centre, n, glm::dvec3(0, 1, 0), jitter);
    if (obstacles) {
      if (obstacles->within_blur(centre)) {
        darts.reject();
        continue;
      }
      // The ellipsoid's mesh lies within its largest semi-axis of the centre: with every
      // triangle farther than that nothing can cross it. Its inside holds the ball of half its
      // smallest semi-axis: a surface that comes nearer than that (closed surfaces and sheets
      // do not end there) crosses it. The exact test only between the two.
      const double reach = std::max({g.semi_axes.x, g.semi_axes.y, g.semi_axes.z});
      const double core = 0.5 * std::min({g.semi_axes.x, g.semi_axes.y, g.semi_axes.z});
      const CrossingTest::Nearest near = obstacles->nearest(centre);
      const int hit = near.distance > reach  ? -1
                      : near.distance < core ? near.surface
                                             : obstacles->crossed(ellipsoid_triangles(g, opt));
      if (darts.crosses(hit, crossings)) continue;
    }
    darts.accept(g);
  }
  return std::move(darts.grains());
}

void add_ellipsoids(const std::vector<GrainPlacement>& grains, const glm::dvec3& front,
                    const glm::dvec3& back, double blur, const GrainOptions& opt, DsMesh& mesh) {
  const std::vector<std::array<int, 3>> faces = ellipsoid_faces(opt);
  for (const auto& g : grains) {
    std::vector<DsMesh::VertexHandle> vh;
    for (const glm::dvec3& p : ellipsoid_points(g, opt)) {
      const auto h = mesh.add_vertex(DsMesh::Point(p.x, p.y, p.z));
      auto& d = mesh.data(h);
      d.front = {front.x, front.y, front.z};
      d.back = {back.x, back.y, back.z};
      d.blur = vertex_blur(blur);
      vh.push_back(h);
    }
    for (const auto& f : faces) mesh.add_face(vh[f[0]], vh[f[1]], vh[f[2]]);
  }
}

DsSurface grain_cores(const GrainSpec& spec, const std::vector<GrainPlacement>& grains,
                      const GrainOptions& opt) {
  CUTAWAY_CHECK(spec.core.has_value());
  const GrainSpec::Core& core = *spec.core;
  std::vector<GrainPlacement> cores = grains;
  for (GrainPlacement& g : cores) g.semi_axes *= core.scale;
  DsSurface s;
  s.name = grain_core_name(spec);
  s.role = SurfaceRole::Grain;
  add_ellipsoids(cores, core.front, core.back, 0.0, opt, s.mesh);
  set_material(s.mesh, core.material_front, core.material_back);
  return s;
}

void scatter_grains(const Template& t, DsModel& model, uint64_t seed, const GrainOptions& opt) {
  check_grain_limits(t, model);
  for (size_t gi = 0; gi < t.grains.size(); ++gi) {
    const GrainSpec& spec = t.grains[gi];
    Rng rng(derive_seed(seed, {kPurposeGrains, gi}));
    // Grains on a surface may cross it; grains through a region may cross none.
    const DsSurface* on = spec.on.empty() ? nullptr : &grain_support(spec, model);
    std::vector<const DsMesh*> others;
    std::vector<const DsSurface*> named;
    for (const DsSurface& s : model.surfaces) {
      if (&s == on) continue;
      others.push_back(&s.mesh);
      named.push_back(&s);
    }
    // Through a region, the blur's sheets too: a grain one passes through would show its
    // colours inside. (Grains on a surface may reach into their neighbours' blur as before:
    // a potato's eyes sit in its cortex's.)
    const CrossingTest obstacles(others, on == nullptr);
    std::vector<size_t> crossings;
    std::vector<GrainPlacement> grains;
    if (on) {
      grains = place_grains(spec, *on, rng, opt, &obstacles, &crossings);
    } else {
      const DsSurface& in = surface_named(spec.inside, model);
      const DsSurface* out = spec.outside.empty() ? nullptr : &surface_named(spec.outside, model);
      for (const DsSurface* s : {&in, out})
        if (s && !closed_surface(s->mesh))
          throw InputError(spec.loc, spec.path + (s == &in ? ".inside" : ".outside"),
                           "surface " + quoted(s->name) +
                               " is not closed (it has a span): grains need a closed surface "
                               "to lie inside or outside of");
      const InsideTest inside(in.mesh);
      std::unique_ptr<InsideTest> outside;
      if (out) outside = std::make_unique<InsideTest>(out->mesh);
      grains = place_grains_inside(spec, inside, outside.get(),
                                   region_cells(in.mesh, inside, spec.spacing), rng, opt,
                                   &obstacles, &crossings);
    }
    if (grains.empty() && !crossings.empty()) {
      const size_t most = static_cast<size_t>(std::max_element(crossings.begin(), crossings.end()) -
                                              crossings.begin());
      const DsSurface& hit = *named[most];
      throw InputError(spec.loc, spec.path,
                       "grains " + quoted(spec.name) + " touch or cross " +
                           (hit.role == SurfaceRole::Grain ? "grains " : "surface ") +
                           quoted(hit.name) +
                           " wherever they are placed: make them smaller or sit them deeper, or "
                           "narrow their region (a grain may cross only the surface it sits on)");
    }
    if (grains.empty()) continue;  // no surface without faces: exporters and sheets need some
    DsSurface s;
    s.name = spec.name;
    s.role = SurfaceRole::Grain;
    for (const GrainPlacement& g : grains) s.grain_sites.push_back(g.surface_point);
    add_ellipsoids(grains, spec.front, spec.back, spec.blur, opt, s.mesh);
    set_material(s.mesh, spec.material_front, spec.material_back);
    model.surfaces.push_back(std::move(s));
    if (spec.core) model.surfaces.push_back(grain_cores(spec, grains, opt));
  }
  update_bounds(model);
}

}  // namespace cutaway
