#include "diffusion/sheet_rays.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>
#include <glm/vector_relational.hpp>

#include "base/error.h"

namespace cutaway {

std::optional<TriangleCrossing> cross_triangle(const glm::dvec3& o, const glm::dvec3& d,
                                               const glm::dvec3& a, const glm::dvec3& b,
                                               const glm::dvec3& c) {
  const glm::dvec3 e1 = b - a, e2 = c - a;
  const glm::dvec3 p = glm::cross(d, e2);
  const double det = glm::dot(e1, p);
  if (!(det != 0)) return std::nullopt;  // in the triangle's plane, degenerate, or NaN
  const glm::dvec3 s = o - a;
  const double u = glm::dot(s, p) / det;
  if (!(u >= 0 && u <= 1)) return std::nullopt;
  const glm::dvec3 q = glm::cross(s, e1);
  const double v = glm::dot(d, q) / det;
  if (!(v >= 0 && u + v <= 1)) return std::nullopt;
  const double t = glm::dot(e2, q) / det;
  if (!(t > 0)) return std::nullopt;
  return TriangleCrossing{t, u, v};
}

namespace {

/// How much farther than the best crossing so far Embree still proposes triangles (relative;
/// the margin is added on top): well above its float error on t.
constexpr double kFarSlack = 1e-5;

/// The sine of the angle under which a ray is grazing: a ray that meets a triangle's plane
/// this flat (or flatter) within the grazing radius of its origin is decided by the exact test
/// against every triangle there, not left to Embree's float edge tests, whose error in the
/// plane grows as one over this sine (a ray from a point on a curved sheet, nearly tangent to
/// it, crosses the sheet again a fraction of a millimetre away).
constexpr double kGrazingSine = 1e-2;

/// Triangle (a, b, c) grown in its plane: every edge moved out by `margin` (scaled about the
/// incentre by 1 + margin / inradius, at most 4 times: a sliver grows by 3 inradii). A
/// degenerate triangle stays as it is.
void grow_triangle(glm::dvec3& a, glm::dvec3& b, glm::dvec3& c, double margin) {
  const double la = glm::length(b - c), lb = glm::length(c - a), lc = glm::length(a - b);
  const double perimeter = la + lb + lc;
  const double doubled_area = glm::length(glm::cross(b - a, c - a));
  if (!(doubled_area > 0) || !(perimeter > 0)) return;
  const double inradius = doubled_area / perimeter;
  const glm::dvec3 incentre = (la * a + lb * b + lc * c) / perimeter;
  const double scale = 1 + std::min(margin / inradius, 3.0);
  a = incentre + (a - incentre) * scale;
  b = incentre + (b - incentre) * scale;
  c = incentre + (c - incentre) * scale;
}

/// The smallest float >= x (x >= 0).
float float_at_least(double x) {
  const float f = static_cast<float>(x);
  return static_cast<double>(f) >= x ? f
                                     : std::nextafter(f, std::numeric_limits<float>::infinity());
}

}  // namespace

struct SheetRayCaster::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

/// What the filter and the point query need: Embree hands Query back as the query's context
/// (the standard way to pass data to a filter: Embree's context is the first member).
struct SheetRayCaster::Query {
  RTCIntersectContext embree;
  const std::vector<const float*>* corners;
  glm::dvec3 origin;  ///< the true origin (Embree's is moved back by `back`)
  double back;        ///< metres Embree's origin lies behind the true one
  double margin;
  double grazing_radius;
  SheetHit* best;  ///< per lane, indexed by the ray's id
  unsigned lanes;  ///< lanes in use in this packet: ids 0 .. lanes - 1
  std::vector<std::pair<unsigned, unsigned>>* near;  ///< the point query's triangles
};

namespace {

using Query = SheetRayCaster::Query;
/// Floats per corner in Embree's vertex buffer: the grown corner, then the sheet's own. The
/// filter's exact test reads the cache lines Embree's traversal has just read (the scene is
/// compact: Embree's leaves point into this buffer instead of copying the corners).
constexpr size_t kVertexFloats = 6;

/// Corner k of triangle t of a sheet, as the sheet has it, from its Embree vertex buffer.
glm::dvec3 own_corner(const float* vertices, size_t t, int k) {
  const float* v = vertices + kVertexFloats * (3 * t + static_cast<size_t>(k)) + 3;
  return {v[0], v[1], v[2]};
}

/// cross_triangle on triangle t of the sheet with Embree vertex buffer `vertices`.
std::optional<TriangleCrossing> cross_corners(const float* vertices, size_t t,
                                              const glm::dvec3& origin, const glm::dvec3& d) {
  return cross_triangle(origin, d, own_corner(vertices, t, 0), own_corner(vertices, t, 1),
                        own_corner(vertices, t, 2));
}

/// Collects the (sheet, triangle) of every triangle Embree finds near the point query's sphere
/// that a grazing ray may cross within grazing_radius of the origin: its bounding box within
/// that radius of the origin, its plane within grazing_radius * kGrazingSine (in double; a
/// superset of those triangles, so the decided hit is the same whichever kernel found them).
/// That holds every triangle within rounding distance of the origin too. Embree hands over
/// whole leaves, most of them far.
bool collect_near(RTCPointQueryFunctionArguments* args) {
  const Query& q = *static_cast<const Query*>(args->userPtr);
  const float* vertices = (*q.corners)[args->geomID];
  const glm::dvec3 a = own_corner(vertices, args->primID, 0),
                   b = own_corner(vertices, args->primID, 1),
                   c = own_corner(vertices, args->primID, 2);
  const glm::dvec3 lo = glm::min(a, glm::min(b, c)) - q.grazing_radius;
  const glm::dvec3 hi = glm::max(a, glm::max(b, c)) + q.grazing_radius;
  if (glm::any(glm::lessThan(q.origin, lo)) || glm::any(glm::greaterThan(q.origin, hi)))
    return false;
  const glm::dvec3 n = glm::cross(b - a, c - a);
  const double area2 = glm::length(n);
  if (area2 > 0 && std::abs(glm::dot(n, q.origin - a)) > q.grazing_radius * kGrazingSine * area2)
    return false;
  q.near->emplace_back(args->geomID, args->primID);
  return false;
}

/// Embree's intersection filter: decides each proposed triangle by cross_triangle on the
/// original, keeps the best crossing per ray in Query::best, and lets Embree cut the ray short
/// only beyond that crossing plus the slack (accepting the proposal with a longer tfar).
/// Whether `crossing` of (sheet, triangle) comes before `best`: nearer, or as near and of a
/// lower (sheet, triangle).
bool comes_before(const TriangleCrossing& crossing, int sheet, unsigned triangle,
                  const SheetHit& best) {
  return best.sheet < 0 || crossing.t < best.at.t ||
         (crossing.t == best.at.t &&
          (sheet < best.sheet || (sheet == best.sheet && triangle < best.triangle)));
}

void decide_proposal(const RTCFilterFunctionNArguments* args) {
  const Query& query = *reinterpret_cast<const Query*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned sheet_index = RTCHitN_geomID(args->hit, args->N, i);
    const unsigned triangle = RTCHitN_primID(args->hit, args->N, i);
    const unsigned lane = RTCRayN_id(args->ray, args->N, i);
    if (lane >= query.lanes) {  // an unused lane, traced anyway by a fallback that skips `valid`
      args->valid[i] = 0;
      continue;
    }
    const glm::dvec3 d(RTCRayN_dir_x(args->ray, args->N, i), RTCRayN_dir_y(args->ray, args->N, i),
                       RTCRayN_dir_z(args->ray, args->N, i));
    const auto crossing = cross_corners((*query.corners)[sheet_index], triangle, query.origin, d);
    SheetHit& best = query.best[lane];
    const int s = static_cast<int>(sheet_index);
    const bool better = crossing && comes_before(*crossing, s, triangle, best);
    if (!better) {
      args->valid[i] = 0;  // Embree goes on with the tfar it had
      continue;
    }
    best = SheetHit{s, triangle, *crossing};
    // Accepted: Embree keeps this tfar (its filters may change it) and goes on up to it.
    RTCRayN_tfar(args->ray, args->N, i) =
        float_at_least((crossing->t + query.back) * (1 + kFarSlack) + query.margin);
  }
}

}  // namespace

SheetHits sheet_hits_from_environment() {
  const char* hits = std::getenv("CUTAWAY_PMVC_HITS");
  return hits && std::string(hits) == "embree" ? SheetHits::EmbreeFloat : SheetHits::Decided;
}

SheetRayCaster::SheetRayCaster(const std::vector<DiffusionSheet>& sheets, int threads,
                               SheetHits hits)
    : sheets_(sheets), mode_(hits), embree_(new Embree) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const DiffusionSheet& s : sheets)
    for (const glm::vec3& p : s.position) {
      lo = glm::min(lo, glm::dvec3(p));
      hi = glm::max(hi, glm::dvec3(p));
    }
  const double diagonal = hi.x >= lo.x ? glm::length(hi - lo) : 0.0;
  margin_ = mode_ == SheetHits::Decided ? std::max(1e-6 * diagonal, 1e-9) : 0.0;
  back_ = 100 * margin_;
  grazing_radius_ = 1e4 * margin_;

  std::string config = "threads=" + std::to_string(std::max(threads, 0));
  if (const char* isa = std::getenv("CUTAWAY_EMBREE_ISA"); isa && *isa)
    config += std::string(",isa=") + isa;
  embree_->device = rtcNewDevice(config.c_str());
  if (!embree_->device) {
    delete embree_;
    throw EnvironmentError("cannot initialise Embree (rtcNewDevice(\"" + config + "\") failed)");
  }
  embree_->scene = rtcNewScene(embree_->device);
  rtcSetSceneFlags(embree_->scene, mode_ == SheetHits::Decided
                                       ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_COMPACT
                                       : RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);
  // Each sheet as its own geometry (ID = sheet index); decided: each triangle with its own
  // three grown corners, and the filter.
  for (size_t i = 0; i < sheets.size(); ++i) {
    const DiffusionSheet& s = sheets[i];
    RTCGeometry g = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), s.triangle.size()));
    if (mode_ == SheetHits::Decided) {
      auto* vb = static_cast<float*>(
          rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                  kVertexFloats * sizeof(float), 3 * s.triangle.size()));
      corners_.push_back(vb);
      for (size_t t = 0; t < s.triangle.size(); ++t) {
        glm::dvec3 corner[3];
        for (int k = 0; k < 3; ++k) corner[k] = glm::dvec3(s.position[s.triangle[t][k]]);
        grow_triangle(corner[0], corner[1], corner[2], margin_);
        for (int k = 0; k < 3; ++k) {
          float* v = vb + kVertexFloats * (3 * t + static_cast<size_t>(k));
          const glm::vec3& own = s.position[s.triangle[t][k]];
          for (int axis = 0; axis < 3; ++axis) {
            v[axis] = static_cast<float>(corner[k][axis]);
            v[3 + axis] = own[axis];
          }
          ib[3 * t + k] = static_cast<unsigned>(3 * t + k);
        }
      }
      rtcSetGeometryIntersectFilterFunction(g, decide_proposal);
    } else {
      auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
          g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), s.position.size()));
      for (size_t v = 0; v < s.position.size(); ++v)
        for (int k = 0; k < 3; ++k) vb[3 * v + k] = s.position[v][k];
      for (size_t t = 0; t < s.triangle.size(); ++t)
        for (int k = 0; k < 3; ++k) ib[3 * t + k] = s.triangle[t][k];
    }
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(embree_->scene, g, static_cast<unsigned>(i));
    rtcReleaseGeometry(g);
  }
  rtcCommitScene(embree_->scene);
}

SheetRayCaster::~SheetRayCaster() {
  rtcReleaseScene(embree_->scene);
  rtcReleaseDevice(embree_->device);
  delete embree_;
}

void SheetRayCaster::cast(const glm::dvec3& origin, std::span<const glm::vec3> directions,
                          std::span<SheetHit> hits) const {
  thread_local std::vector<std::pair<unsigned, unsigned>> near;
  Query query;
  rtcInitIntersectContext(&query.embree);
  query.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  query.corners = &corners_;
  query.origin = origin;
  query.back = back_;
  query.margin = margin_;
  query.grazing_radius = grazing_radius_;
  query.near = &near;
  // The triangles next to the origin, tested for every ray: from an origin within rounding
  // distance of a triangle's plane, Embree's t of a grazing ray may come out negative; and
  // those a grazing ray may cross close by, where Embree's float edge tests may miss.
  near.clear();
  if (mode_ == SheetHits::Decided) {
    RTCPointQuery point;
    point.x = static_cast<float>(origin.x);
    point.y = static_cast<float>(origin.y);
    point.z = static_cast<float>(origin.z);
    point.time = 0.0f;
    point.radius = float_at_least(grazing_radius_);
    RTCPointQueryContext point_context;
    rtcInitPointQueryContext(&point_context);
    rtcPointQuery(embree_->scene, &point, &point_context, collect_near, &query);
  }
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[16];
  for (size_t base = 0; base < directions.size(); base += 16) {
    const int lanes = static_cast<int>(std::min<size_t>(16, directions.size() - base));
    query.best = &hits[base];
    query.lanes = static_cast<unsigned>(lanes);
    for (int l = 0; l < 16; ++l) {
      valid[l] = l < lanes ? -1 : 0;
      const glm::vec3 d = directions[base + static_cast<size_t>(std::min(l, lanes - 1))];
      const glm::dvec3 from = origin - glm::dvec3(d) * query.back;
      rh.ray.org_x[l] = static_cast<float>(from.x);
      rh.ray.org_y[l] = static_cast<float>(from.y);
      rh.ray.org_z[l] = static_cast<float>(from.z);
      rh.ray.dir_x[l] = d.x;
      rh.ray.dir_y[l] = d.y;
      rh.ray.dir_z[l] = d.z;
      rh.ray.tnear[l] = 0.0f;
      // An unused lane is also inactive by Embree's other rule (tfar < tnear): without native
      // 16-wide packets rtcIntersect16 falls back to a ray stream that ignores `valid`.
      rh.ray.tfar[l] = l < lanes ? std::numeric_limits<float>::infinity() : -1.0f;
      rh.ray.mask[l] = 0xFFFFFFFFu;
      rh.ray.time[l] = 0.0f;
      rh.ray.id[l] = static_cast<unsigned>(l);
      rh.ray.flags[l] = 0;
      rh.hit.geomID[l] = RTC_INVALID_GEOMETRY_ID;
      if (l < lanes) hits[base + static_cast<size_t>(l)] = SheetHit{};
    }
    rtcIntersect16(valid, embree_->scene, &query.embree, &rh);
    if (mode_ == SheetHits::EmbreeFloat) {
      for (int l = 0; l < lanes; ++l) {
        if (rh.hit.geomID[l] == RTC_INVALID_GEOMETRY_ID) continue;
        hits[base + static_cast<size_t>(l)] =
            SheetHit{static_cast<int>(rh.hit.geomID[l]), rh.hit.primID[l],
                     TriangleCrossing{rh.ray.tfar[l], rh.hit.u[l], rh.hit.v[l]}};
      }
      continue;
    }
    for (int l = 0; l < lanes; ++l) {
      SheetHit& best = hits[base + static_cast<size_t>(l)];
      const glm::dvec3 d(directions[base + static_cast<size_t>(l)]);
      for (const auto& [sheet, triangle] : near) {
        const auto crossing = cross_corners(corners_[sheet], triangle, origin, d);
        if (crossing && comes_before(*crossing, static_cast<int>(sheet), triangle, best))
          best = SheetHit{static_cast<int>(sheet), triangle, *crossing};
      }
    }
  }
}

}  // namespace cutaway
