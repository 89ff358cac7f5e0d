#include "diffusion/sheet_rays.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include <embree3/rtcore.h>
#include <glm/geometric.hpp>

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
  return static_cast<double>(f) >= x ? f : std::nextafter(f, std::numeric_limits<float>::infinity());
}

}  // namespace

struct SheetRayCaster::Embree {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

namespace {

/// What the filter needs: Embree hands this back as the query's context (the standard way to
/// pass data to a filter: Embree's context is the first member).
struct Query {
  RTCIntersectContext embree;
  const std::vector<DiffusionSheet>* sheets;
  glm::dvec3 origin;  ///< the true origin (Embree's is moved back by `back`)
  double back;        ///< metres Embree's origin lies behind the true one
  double margin;
  SheetHit* best;  ///< per lane, indexed by the ray's id
  unsigned lanes;  ///< lanes in use in this packet: ids 0 .. lanes - 1
};

/// Collects the (sheet, triangle) of every grown triangle whose bounds reach the point
/// query's sphere.
bool collect_near(RTCPointQueryFunctionArguments* args) {
  static_cast<std::vector<std::pair<unsigned, unsigned>>*>(args->userPtr)
      ->emplace_back(args->geomID, args->primID);
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

/// cross_triangle on triangle `triangle` of `sheet` from `origin` along `d`.
std::optional<TriangleCrossing> cross_sheet_triangle(const DiffusionSheet& sheet, unsigned triangle,
                                                     const glm::dvec3& origin, const glm::dvec3& d) {
  const glm::uvec3 corners = sheet.triangle[triangle];
  return cross_triangle(origin, d, glm::dvec3(sheet.position[corners[0]]),
                        glm::dvec3(sheet.position[corners[1]]),
                        glm::dvec3(sheet.position[corners[2]]));
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
    const auto crossing =
        cross_sheet_triangle((*query.sheets)[sheet_index], triangle, query.origin, d);
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

SheetRayCaster::SheetRayCaster(const std::vector<DiffusionSheet>& sheets, int threads)
    : sheets_(sheets), embree_(new Embree) {
  glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-lo);
  for (const DiffusionSheet& s : sheets)
    for (const glm::vec3& p : s.position) {
      lo = glm::min(lo, glm::dvec3(p));
      hi = glm::max(hi, glm::dvec3(p));
    }
  const double diagonal = hi.x >= lo.x ? glm::length(hi - lo) : 0.0;
  margin_ = std::max(1e-6 * diagonal, 1e-9);
  back_ = 100 * margin_;
  near_radius_ = 4 * margin_;

  std::string config = "threads=" + std::to_string(std::max(threads, 0));
  if (const char* isa = std::getenv("CUTAWAY_EMBREE_ISA"); isa && *isa)
    config += std::string(",isa=") + isa;
  embree_->device = rtcNewDevice(config.c_str());
  if (!embree_->device) {
    delete embree_;
    throw std::runtime_error("cannot initialise Embree (rtcNewDevice(\"" + config + "\") failed)");
  }
  embree_->scene = rtcNewScene(embree_->device);
  rtcSetSceneFlags(embree_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(embree_->scene, RTC_BUILD_QUALITY_HIGH);
  // Each sheet as its own geometry (ID = sheet index), each triangle with its own three
  // grown corners.
  for (size_t i = 0; i < sheets.size(); ++i) {
    const DiffusionSheet& s = sheets[i];
    RTCGeometry g = rtcNewGeometry(embree_->device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * s.triangle.size()));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), s.triangle.size()));
    for (size_t t = 0; t < s.triangle.size(); ++t) {
      glm::dvec3 corner[3];
      for (int k = 0; k < 3; ++k) corner[k] = glm::dvec3(s.position[s.triangle[t][k]]);
      grow_triangle(corner[0], corner[1], corner[2], margin_);
      for (int k = 0; k < 3; ++k) {
        for (int axis = 0; axis < 3; ++axis) vb[9 * t + 3 * k + axis] = static_cast<float>(corner[k][axis]);
        ib[3 * t + k] = static_cast<unsigned>(3 * t + k);
      }
    }
    rtcSetGeometryIntersectFilterFunction(g, decide_proposal);
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
  Query query;
  rtcInitIntersectContext(&query.embree);
  query.embree.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  query.sheets = &sheets_;
  query.origin = origin;
  query.back = back_;
  query.margin = margin_;
  // The triangles next to the origin, tested for every ray: from an origin within rounding
  // distance of a triangle's plane, Embree's t of a grazing ray may come out negative.
  thread_local std::vector<std::pair<unsigned, unsigned>> near;
  near.clear();
  RTCPointQuery point;
  point.x = static_cast<float>(origin.x);
  point.y = static_cast<float>(origin.y);
  point.z = static_cast<float>(origin.z);
  point.time = 0.0f;
  point.radius = float_at_least(near_radius_);
  RTCPointQueryContext point_context;
  rtcInitPointQueryContext(&point_context);
  rtcPointQuery(embree_->scene, &point, &point_context, collect_near, &near);
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
    for (int l = 0; l < lanes; ++l) {
      SheetHit& best = hits[base + static_cast<size_t>(l)];
      const glm::dvec3 d(directions[base + static_cast<size_t>(l)]);
      for (const auto& [sheet, triangle] : near) {
        const auto crossing = cross_sheet_triangle(sheets_[sheet], triangle, origin, d);
        if (crossing && comes_before(*crossing, static_cast<int>(sheet), triangle, best))
          best = SheetHit{static_cast<int>(sheet), triangle, *crossing};
      }
    }
  }
}

}  // namespace cutaway
