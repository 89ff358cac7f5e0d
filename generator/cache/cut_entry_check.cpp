#include "cache/cut_entry_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "base/error.h"
#include "base/finite.h"
#include "variation/organic_deformation.h"

namespace cutaway {

namespace {

/// The widest a section makes a profile point: its loops' largest radius over their smallest
/// (at least the factor by which a loop resized through its point at angle 0 exceeds it).
double section_widening(const SectionSpec& section) {
  if (section.circle || section.loops.empty()) return 1;
  double lo = std::numeric_limits<double>::infinity(), hi = 0;
  for (const auto& loop : section.loops)
    for (const glm::dvec2& p : loop) {
      lo = std::min(lo, glm::length(p));
      hi = std::max(hi, glm::length(p));
    }
  return lo > 0 && std::isfinite(hi / lo) ? hi / lo : 1;
}

/// `check`, failing as "WHAT INDEX REASON".
Check indexed(const char* what, size_t index, const Check& check) {
  if (check) return check;
  return Check::none(std::string(what) + " " + std::to_string(index) + " " + check.reason());
}

/// The axis-aligned bounds of `points`.
struct Box {
  glm::dvec3 lo{std::numeric_limits<double>::infinity()};
  glm::dvec3 hi{-std::numeric_limits<double>::infinity()};
  void add(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
};

/// Whether every point of `points` lies within `reach_m` of the origin.
Check within_reach(const std::vector<glm::dvec3>& points, double reach_m) {
  for (const glm::dvec3& p : points)
    if (!(glm::length(p) <= reach_m))
      return Check::none("reaches " + std::to_string(glm::length(p)) +
                         " m from the object's origin, beyond its template's reach of " +
                         std::to_string(reach_m) + " m");
  return {};
}

Check check_shape(const ShadedMesh& m, double reach_m) {
  const size_t n = m.position.size();
  if (n == 0 || m.triangle.empty()) return Check::none("has no triangles");
  if (m.normal.size() != n || m.colour.size() != n || m.material.size() != n ||
      (!m.param.empty() && m.param.size() != n))
    return Check::none("has vertex attributes of other counts than its " + std::to_string(n) +
                       " positions");
  for (size_t v = 0; v < n; ++v)
    if (!all_finite(m.position[v]) || !all_finite(m.normal[v]) || !all_finite(m.colour[v]) ||
        !all_finite(m.material[v]) || (!m.param.empty() && !all_finite(m.param[v])))
      return Check::none("vertex " + std::to_string(v) + " has a non-finite value");
  for (const glm::uvec3& t : m.triangle)
    if (t.x >= n || t.y >= n || t.z >= n)
      return Check::none("has a triangle vertex index not below " + std::to_string(n));
  return within_reach(m.position, reach_m);
}

Check check_collision(const CollisionShape& c, double reach_m) {
  if (c.parts.empty()) return Check::none("has no convex parts");
  for (const ConvexPart& part : c.parts) {
    if (part.corners.size() < 4) return Check::none("has a part of fewer than 4 corners");
    for (const glm::dvec3& p : part.corners)
      if (!all_finite(p)) return Check::none("has a non-finite corner");
    if (!(part.outside_m >= 0) || !std::isfinite(part.outside_m))
      return Check::none("has a part whose margin is not finite and >= 0");
    if (Check reach = within_reach(part.corners, reach_m); !reach) return reach;
  }
  if (!std::isfinite(c.volume_m3) || !all_finite(c.centroid) || !std::isfinite(c.convexity))
    return Check::none("has non-finite mass properties");
  return {};
}

}  // namespace

double template_reach_m(const Template& tmpl) {
  double metres = 0;  // profiles and sections are parsed into metres, mesh files are in units
  for (const SurfaceSpec& s : tmpl.surfaces) {
    double widening = section_widening(s.section);
    for (const HeightSection& h : s.sections)
      widening = std::max(widening, section_widening(h.section));
    for (const glm::dvec2& p : s.profile)
      metres = std::max(metres, std::hypot(p.x * widening, p.y));
    if (s.mesh)
      for (const glm::dvec3& p : s.mesh->points)
        metres = std::max(metres, glm::length(p) * tmpl.metres_per_unit);
  }
  double spine = 0;
  for (const glm::dvec2& p : tmpl.spine.points) spine = std::max(spine, glm::length(p));
  double grain = 0;  // a grain's centre lies on or near a surface, its body around it
  for (const GrainSpec& g : tmpl.grains)
    grain = std::max(grain,
                     std::abs(g.depth) + std::max({g.semi_axes.x, g.semi_axes.y, g.semi_axes.z}));
  // A variant's organic deformation (lumps, lopsidedness, lean) moves points by at most its
  // reach, taken at the template's amount or 1, whichever is larger.
  const double organic =
      organic_reach_m(tmpl.organic, std::max(1.0, tmpl.variation_amount), metres, metres);
  return 2 * std::max(1.0, tmpl.variation_amount) * (metres + spine + grain) + organic;
}

Check check_cached_cut(CutPieces& p, const std::vector<CollisionShape>& collision,
                       bool collision_expected, SceneAssets& assets, double reach_m) {
  if (!assets.meshes.empty()) throw InternalError("check_cached_cut: the assets hold meshes");
  assets.meshes.swap(p.meshes);
  const Check a = check_assets(assets);
  assets.meshes.swap(p.meshes);
  if (!a) return a;
  const size_t n = p.meshes.size();
  if (p.shapes.size() != n || p.infos.size() != n || p.cap_normals.size() != n ||
      p.cut_faces.size() != n)
    return Check::none("has " + std::to_string(n) +
                       " meshes but other counts of shapes, infos, "
                       "cap normals or cut faces");
  if (collision.size() != (collision_expected ? n : 0))
    return Check::none("has " + std::to_string(collision.size()) + " collision shapes for " +
                       std::to_string(n) + " pieces");
  if (p.pieces_cut < n) return Check::none("keeps more pieces than its cut made");
  for (size_t q = 0; q < n; ++q) {
    if (Check c = indexed("shape", q, check_shape(p.shapes[q], reach_m)); !c) return c;
    if (Check c = indexed("mesh", q, within_reach(p.meshes[q].position, reach_m)); !c) return c;
    Box mesh, shape;
    for (const glm::dvec3& v : p.meshes[q].position) mesh.add(v);
    for (const glm::dvec3& v : p.shapes[q].position) shape.add(v);
    constexpr double kSamePlace = 1e-6;  // metres
    if (!(glm::all(glm::lessThanEqual(glm::abs(mesh.lo - shape.lo), glm::dvec3(kSamePlace))) &&
          glm::all(glm::lessThanEqual(glm::abs(mesh.hi - shape.hi), glm::dvec3(kSamePlace)))))
      return Check::none("mesh " + std::to_string(q) + " does not lie where its shape lies");
    if (!all_finite(p.cap_normals[q]))
      return Check::none("piece " + std::to_string(q) + " has a non-finite cap normal");
    if (!(p.infos[q].volume_m3 >= 0) || !std::isfinite(p.infos[q].volume_m3))
      return Check::none("piece " + std::to_string(q) + " has a volume not finite and >= 0");
    if (p.cut_faces[q] < 0)
      return Check::none("piece " + std::to_string(q) + " has a negative cut-face count");
    if (collision_expected)
      if (Check c = indexed("collision shape", q, check_collision(collision[q], reach_m)); !c)
        return c;
  }
  return {};
}

Check check_cached_placements(const std::vector<Placement>& placements, size_t bodies,
                              const Container& container, double none_radius_m) {
  if (placements.size() != bodies)
    return Check::none("holds " + std::to_string(placements.size()) + " placements for " +
                       std::to_string(bodies) + " pieces");
  const double half =
      container.type == ContainerType::None
          ? none_radius_m
          : std::max({container.diameter_m, container.width_m, container.depth_m}) / 2;
  const double top = std::max(container.height_m, 0.0) + 2.0, bottom = -1.0;
  for (size_t k = 0; k < placements.size(); ++k) {
    const Placement& p = placements[k];
    const std::string which = "placement " + std::to_string(k);
    if (!std::isfinite(p.rotation.w) ||
        !all_finite(glm::dvec3(p.rotation.x, p.rotation.y, p.rotation.z)) ||
        !(std::abs(glm::length(p.rotation) - 1) <= 1e-6))
      return Check::none(which + " has a rotation that is not a finite unit quaternion");
    if (!all_finite(p.translation)) return Check::none(which + " has a non-finite translation");
    if (!(std::hypot(p.translation.x, p.translation.z) <= half + 1.0) ||
        !(p.translation.y >= bottom && p.translation.y <= top))
      return Check::none(which + " lies outside the container's reach");
  }
  return {};
}

}  // namespace cutaway
