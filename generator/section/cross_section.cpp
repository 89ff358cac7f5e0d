#include "section/cross_section.h"

// CGAL's own checks stay on in this file, also in Release builds. Delaunay refinement with
// inexact constructions can corrupt its triangulation near a nearly degenerate input (a plane
// nearly tangent to a surface cuts a sliver loop; the midpoint of a tiny constrained edge lands
// outside both of its faces, CGAL Refine_edges.h "n == zone.fh", or a circumcentre of three
// nearly collinear points is infinite), and without the checks it goes on to crash. With them
// the failure is an exception, and the refinement is dropped (step 3). Exact constructions
// avoid the failure but cost unbounded time in the same cases (numbers of thousands of bits).
#ifndef CGAL_DEBUG
#define CGAL_DEBUG
#endif

#include <array>
#include <chrono>
#include <functional>
#include <map>
#include <queue>
#include <tuple>
#include <utility>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <glm/geometric.hpp>

#include "base/error.h"
#include "base/finite.h"
#include "base/timer.h"
#include "section/band_sampling.h"
#include "section/grain_neighbourhood.h"
#include "section/harmonic_sampling.h"
#include "section/split_lines.h"

namespace cutaway {

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using CdtBase = CGAL::Constrained_Delaunay_triangulation_2<K, Tds, CGAL::Exact_predicates_tag>;
using Cdt = CGAL::Constrained_triangulation_plus_2<CdtBase>;
/// CGAL's size and angle criteria with a floor: a triangle whose shortest edge is below
/// `min_edge` (metres) is never bad, so refinement does not chase features far below the
/// template's resolution (sliver loops of a nearly tangent plane, tiny angles between cut
/// segments).
class Criteria : public CGAL::Delaunay_mesh_size_criteria_2<Cdt> {
 public:
  using Base = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
  Criteria(double shape_bound, double size_bound, double min_edge)
      : Base(shape_bound, size_bound), min_edge_(min_edge) {}

  class Is_bad : public Base::Is_bad {
   public:
    Is_bad(const Base::Is_bad& base, double min_edge)
        : Base::Is_bad(base), min_squared_(min_edge * min_edge) {}
    using Base::Is_bad::operator();
    CGAL::Mesh_2::Face_badness operator()(const Cdt::Face_handle& f, Quality& q) const {
      const CGAL::Mesh_2::Face_badness badness = Base::Is_bad::operator()(f, q);
      if (badness == CGAL::Mesh_2::NOT_BAD) return badness;
      for (int i = 0; i < 3; ++i) {
        const double squared = CGAL::to_double(
            CGAL::squared_distance(f->vertex(i)->point(), f->vertex(Cdt::ccw(i))->point()));
        if (squared < min_squared_) return CGAL::Mesh_2::NOT_BAD;
      }
      return badness;
    }

   private:
    double min_squared_;
  };
  Is_bad is_bad_object() const { return Is_bad(Base::is_bad_object(), min_edge_); }

 private:
  double min_edge_;
};
using Mesher = CGAL::Delaunay_mesher_2<Cdt, Criteria>;
using Vertex = Cdt::Vertex_handle;
using Face = Cdt::Face_handle;
using Point2 = K::Point_2;

/// A cut segment in plane coordinates.
struct Segment2 {
  glm::dvec2 a, b, front;  // front: the front side's direction in the plane
  int index;               // into the cut segment list
};

glm::dvec2 to2(const Point2& p) { return {CGAL::to_double(p.x()), CGAL::to_double(p.y())}; }

/// Whether some finite face around vertex v lies in the meshed domain (v is a vertex of the cap).
bool in_domain(const Cdt& cdt, Vertex v) {
  auto f = cdt.incident_faces(v), done = f;
  do {
    if (!cdt.is_infinite(f) && f->is_in_domain()) return true;
  } while (++f != done);
  return false;
}

/// Whether a surface's cut segments can bound the domain: the skin, and surfaces hidden on a
/// side (the walls of hollows). The others only divide colours.
bool bounds_domain(const DsSurface& surface) {
  return surface.role == SurfaceRole::Skin || !surface.visible_front || !surface.visible_back;
}

/// Which side of the constrained edge (a, b), all or a piece of segment s, the point c lies on:
/// +1 on s's front side, -1 on its back, 0 on the line. For the whole segment, the side of its
/// line that its front points to. For a piece (another constraint split s at a vertex, which
/// may lie a hair off s's line), the side of the piece itself by an exact orientation test,
/// mapped to front or back by s's front: a thin face beside the piece can lie on the other side
/// of s's line. (The whole-segment rule stays: on a cut that barely grazes the skin, the
/// segments' fronts are far from perpendicular to them, and only it reads them right.)
int side_of(const Segment2& s, const Point2& a, const Point2& b, const Point2& c) {
  const glm::dvec2 pa = to2(a), pb = to2(b);
  if ((pa == s.a && pb == s.b) || (pa == s.b && pb == s.a)) {
    const double d = glm::dot(to2(c) - s.a, s.front);
    return d > 0 ? 1 : (d < 0 ? -1 : 0);
  }
  const int turn = static_cast<int>(CGAL::orientation(a, b, c));  // +1: left of a -> b
  const glm::dvec2 d = pb - pa;
  const double left_is_front = glm::dot(glm::dvec2(-d.y, d.x), s.front);
  return left_is_front > 0 ? turn : (left_is_front < 0 ? -turn : 0);
}

}  // namespace

void plane_frame(const Plane& plane, glm::dvec3& u, glm::dvec3& v) {
  const glm::dvec3 n = plane.normal;
  glm::dvec3 axis(1, 0, 0);
  if (std::fabs(n.y) < std::fabs(n.x) && std::fabs(n.y) <= std::fabs(n.z)) axis = {0, 1, 0};
  else if (std::fabs(n.z) < std::fabs(n.x) && std::fabs(n.z) < std::fabs(n.y)) axis = {0, 0, 1};
  u = glm::normalize(axis - n * glm::dot(axis, n));
  v = glm::cross(n, u);
}

namespace {

/// The stages of make_cross_section over the state they share: the cut segments in plane
/// coordinates, the triangulation and the output being filled. Each stage is one method, run
/// once, in order (make_cross_section).
class SectionMesher {
 public:
  SectionMesher(const DsModel& model, const Plane& plane, const CrossSectionOptions& options,
                const CapRestriction& restriction)
      : model_(model), plane_(plane), options_(options), restriction_(restriction),
        adaptive_(options.sampling == CapSampling::Adaptive), near_grains_(model, plane) {
    cs_.plane = plane;
    plane_frame(plane, cs_.u_axis, cs_.v_axis);
  }

  /// Step 0: the cut segments, nearly collinear ones merged, in plane coordinates.
  /// @returns false when none lies on the skin (the plane misses the object)
  bool collect_segments();
  /// Step 1 input: the constraints (cut segments and a restriction's split lines, arranged so
  /// that no two cross) and, adaptive, the blurred segments' chains.
  void arrange_constraints();
  /// Steps 1 and 2: the constrained Delaunay triangulation with the blur bands' ladder points,
  /// and the domain. @returns false when it has no area (the plane only touches the object)
  bool triangulate_domain();
  /// Step 3: conforming Delaunay refinement inside the domain, dropped when it fails; then the
  /// restriction's cells.
  void refine();
  /// The centroids of the faces in the domain (MeshedSection::triangle_centroids).
  std::vector<glm::dvec3> centroids() const;
  /// Takes the faces whose centroid `keep` rejects out of the domain.
  void restrict_to(const std::function<bool(const glm::dvec3&)>& keep);
  /// Between meshing and colouring: the wall time from pause() to resume() is not counted.
  void pause() { paused_at_ = std::chrono::steady_clock::now(); }
  void resume() { start_ += std::chrono::steady_clock::now() - paused_at_; }
  /// Step 4 (adaptive): the blur bands' lines sampled by band_sampling.h.
  void sample_band_lines(const DiffusionBackend& diffusion);
  /// Step 5: output vertices (cut vertices split per side) and triangles.
  /// @returns false when no triangle is left (the plane only touches the object)
  bool split_vertices();
  /// Step 6: PMVC colours of the points not sampled yet; adaptive, the interior by harmonic
  /// sampling. @returns the cross-section
  CrossSection diffuse_rest(const DiffusionBackend& diffusion);
  /// The grains near the plane.
  const GrainNeighbourhood& grains() const { return near_grains_; }

 private:
  /// Ladder points (plane coordinates) -> band line, arc length and the band's half width.
  struct Rung {
    int line;
    double arc_length, width;
  };

  /// The input segment that a constrained edge (a, b) lies on (null on a split line).
  const Segment2* segment_on(Vertex a, Vertex b) const;
  /// Where a vertex at plane coordinates q lies in the object frame.
  glm::dvec3 lift(const glm::dvec2& q) const;
  /// Whether p is within a quarter edge of a split line.
  bool near_split_line(const glm::dvec2& p) const;
  /// Whether p lies on a cut segment other than seg2_[own], up to rounding (a millionth of an
  /// edge).
  bool on_other_segment(const glm::dvec2& p, size_t own) const;
  /// Inserts the ladder points of the blur bands (step 1).
  void insert_blur_bands();
  /// Marks the faces of each region bounded by the skin's and the walls' cut segments in or out
  /// of the domain (step 2): out where it reaches the infinite face, else by the majority of its
  /// faces' sides of the bounding segments beside them (out on the skin's front or a wall's
  /// hidden side; a tie is out).
  void mark_domain();
  /// A new output vertex at p on `surface` (-1: interior), black for now.
  unsigned add_vertex(const Point2& p, int surface);
  /// Step 5 for an in-domain vertex v: one output vertex, or one per wedge of faces between
  /// constrained edges around a cut vertex.
  void split_vertex(Vertex v);

  const DsModel& model_;
  const Plane& plane_;
  const CrossSectionOptions& options_;
  const CapRestriction& restriction_;
  const bool adaptive_;
  const GrainNeighbourhood near_grains_;  ///< adaptive: points near them are diffused; both:
                                          ///< they are counted
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point paused_at_ = start_;
  double seconds_sampling_ = 0;
  CrossSection cs_;

  std::vector<CutSegment> segments_;
  std::vector<Segment2> seg2_;
  // Cut vertices keep their 3D positions: one within kOnPlane_m of the plane is a surface
  // vertex that lies on it only by symbolic perturbation, and the clipped skin has it there.
  std::map<std::pair<double, double>, glm::dvec3> lifted_;
  std::vector<Line2> lines_;
  std::vector<Constraint2> constraints_;
  SegmentChains chains_;
  std::map<std::pair<double, double>, Rung> ladder_;
  Cdt cdt_;
  std::map<std::pair<Vertex, Vertex>, int> segment_of_;  // constraint end points -> index

  // Band samples: vertex -> colour and material channels.
  std::map<Vertex, std::pair<glm::dvec3, glm::dvec2>> samples_;
  std::map<std::pair<Vertex, Face>, unsigned> corner_id_;
  // One PMVC evaluation per location: the duplicates of a blurred cut vertex share it.
  std::vector<glm::dvec3> to_diffuse_;
  std::vector<std::vector<unsigned>> diffuse_targets_;
  std::vector<unsigned> interpolated_;  // adaptive: interior vertices left to harmonic sampling
};

bool SectionMesher::collect_segments() {
  // Merging is for the swept surfaces' doubled segments; grain loops are small and stay as cut.
  std::vector<CutSegment> swept, grains;  // grains: kept as cut
  for (const CutSegment& s : cut_segments(model_, plane_)) {
    const DsSurface& surface = model_.surfaces[s.surface];
    const bool boundary =
        surface.role == SurfaceRole::Skin || surface.visible_front != surface.visible_back;
    const bool keep = surface.role == SurfaceRole::Grain || (boundary && !options_.merge_boundary);
    (keep ? grains : swept).push_back(s);
  }
  segments_ = merge_collinear_segments(swept, options_.merge_tolerance * options_.edge_m,
                                       options_.edge_m, restriction_.split_planes);
  segments_.insert(segments_.end(), grains.begin(), grains.end());
  cs_.cut_segments = segments_.size();
  bool hits_skin = false;
  for (const auto& s : segments_) hits_skin = hits_skin || s.surface == 0;
  if (!hits_skin) return false;

  auto project = [&](const glm::dvec3& p) {
    const glm::dvec3 d = p - plane_.point;
    return glm::dvec2(glm::dot(d, cs_.u_axis), glm::dot(d, cs_.v_axis));
  };
  for (size_t i = 0; i < segments_.size(); ++i) {
    const CutSegment& s = segments_[i];
    const glm::dvec2 a = project(s.a), b = project(s.b);
    lifted_.emplace(std::make_pair(a.x, a.y), s.a);
    lifted_.emplace(std::make_pair(b.x, b.y), s.b);
    seg2_.push_back({a,
                     b,
                     {glm::dot(s.front_normal, cs_.u_axis), glm::dot(s.front_normal, cs_.v_axis)},
                     static_cast<int>(i)});
  }
  return true;
}

void SectionMesher::arrange_constraints() {
  std::vector<std::pair<glm::dvec2, glm::dvec2>> ends;
  glm::dvec2 lo(0.0), hi(0.0);
  for (const Segment2& s : seg2_) {
    ends.emplace_back(s.a, s.b);
    lo = ends.size() == 1 ? glm::min(s.a, s.b) : glm::min(lo, glm::min(s.a, s.b));
    hi = ends.size() == 1 ? glm::max(s.a, s.b) : glm::max(hi, glm::max(s.a, s.b));
  }
  lines_ = split_lines(plane_, cs_.u_axis, cs_.v_axis, restriction_.split_planes);
  constraints_ = arrange_split_lines(ends, lines_, lo - glm::dvec2(2 * options_.edge_m),
                                     hi + glm::dvec2(2 * options_.edge_m), kOnPlane_m);

  // Adaptive sampling: the blurred cut segments of each surface joined into chains, along which
  // the lines of their blur bands are sampled (band_sampling.h).
  if (adaptive_) {
    std::vector<std::array<glm::dvec2, 2>> ends2;
    std::vector<int> group;
    for (const Segment2& s : seg2_) {
      const CutSegment& cut = segments_[s.index];
      ends2.push_back({s.a, s.b});
      group.push_back(cut.at_a.blur > 0 || cut.at_b.blur > 0 ? cut.surface : -1);
    }
    chains_ = chain_segments(ends2, group);
  }
}

const Segment2* SectionMesher::segment_on(Vertex a, Vertex b) const {
  for (auto ctx = cdt_.contexts_begin(a, b); ctx != cdt_.contexts_end(a, b); ++ctx) {
    // The constraint's vertex iterator is forward-only: walk it to find the last vertex.
    const Vertex first = *ctx->vertices_begin();
    Vertex last = first;
    for (auto it = ctx->vertices_begin(); it != ctx->vertices_end(); ++it) last = *it;
    auto found = segment_of_.find(std::minmax(first, last));
    if (found != segment_of_.end()) return &seg2_[found->second];
  }
  return nullptr;
}

glm::dvec3 SectionMesher::lift(const glm::dvec2& q) const {
  const auto exact = lifted_.find({q.x, q.y});
  return exact != lifted_.end() ? exact->second
                                : plane_.point + cs_.u_axis * q.x + cs_.v_axis * q.y;
}

bool SectionMesher::near_split_line(const glm::dvec2& p) const {
  for (const Line2& l : lines_)
    if (std::fabs(glm::dot(p, l.normal) - l.offset) < 0.25 * options_.edge_m) return true;
  return false;
}

bool SectionMesher::on_other_segment(const glm::dvec2& p, size_t own) const {
  const double reach = 1e-6 * options_.edge_m;
  for (size_t k = 0; k < seg2_.size(); ++k) {
    if (k == own) continue;
    const glm::dvec2 d = seg2_[k].b - seg2_[k].a;
    const double len2 = glm::dot(d, d);
    const double t = len2 > 0 ? std::clamp(glm::dot(p - seg2_[k].a, d) / len2, 0.0, 1.0) : 0.0;
    if (glm::distance(p, seg2_[k].a + t * d) < reach) return true;
  }
  return false;
}

bool SectionMesher::triangulate_domain() {
  for (const Constraint2& c : constraints_) {
    const Vertex va = cdt_.insert(Point2(c.a.x, c.a.y));
    const Vertex vb = cdt_.insert(Point2(c.b.x, c.b.y));
    if (va == vb) continue;
    cdt_.insert_constraint(va, vb);
    if (c.segment >= 0) segment_of_.emplace(std::minmax(va, vb), seg2_[c.segment].index);
  }
  insert_blur_bands();
  if (cdt_.dimension() < 2) return false;
  mark_domain();
  return true;
}

void SectionMesher::insert_blur_bands() {
  // Blur bands (paper §3.1, Fig. 2): pairs of vertices on the two sheets of a blurred cut
  // segment, +-blur along its front direction, every max(1.5 blur, edge / 5) along it, so that
  // the steep transition across the band is sampled as a ladder parallel to the cut line
  // (sparser pairs leave line vertices of the refinement without partners, and the colour
  // across the band zigzags). Not near a split line: a point a hair's breadth off a constraint
  // makes refinement split it endlessly. Not on another cut segment (a blur as wide as the gap
  // to a parallel surface): it would split that constraint where the clipped surfaces have no
  // seam vertex, and the pieces would not close.
  for (size_t i = 0; i < seg2_.size(); ++i) {
    const Segment2& s = seg2_[i];
    const CutSegment& cut = segments_[s.index];
    const double front_len = glm::length(s.front);
    const double blur = 0.5 * (cut.at_a.blur + cut.at_b.blur);
    if (blur < kMinBlur_m || front_len == 0) continue;
    const double spacing = std::max(1.5 * blur, 0.2 * options_.edge_m);
    const int pairs = std::max(1, static_cast<int>(std::ceil(glm::distance(s.a, s.b) / spacing)));
    const glm::dvec2 across = s.front / front_len;
    for (int k = 0; k < pairs; ++k) {
      const double t = (k + 0.5) / pairs;
      const glm::dvec2 p = s.a + (s.b - s.a) * t;
      const double b = cut.at_a.blur + (cut.at_b.blur - cut.at_a.blur) * t;
      for (const int side : {1, -1}) {
        const glm::dvec2 q = p + across * (side * b);
        if (near_split_line(q) || on_other_segment(q, i)) continue;
        cdt_.insert(Point2(q.x, q.y));
        if (adaptive_ && chains_.chain[s.index] >= 0)
          ladder_.emplace(std::make_pair(q.x, q.y),
                          Rung{band_line(chains_.chain[s.index], side),
                               chains_.arc_length(s.index, t, glm::distance(s.a, s.b)), b});
      }
    }
  }
}

void SectionMesher::mark_domain() {
  // Flood regions across unconstrained edges and decide each region once.
  std::map<Face, int> region;
  std::vector<bool> region_in;
  for (auto f = cdt_.all_faces_begin(); f != cdt_.all_faces_end(); ++f) {
    if (region.count(f)) continue;
    const int id = static_cast<int>(region_in.size());
    // Each face of the region beside a bounding segment votes by its side of it; the region is
    // in where it does not reach the infinite face and more votes say in than out. (One face
    // misread among the votes, a sliver whose third corner lies a hair off a segment whose
    // front is skewed, had put a sharp-tipped calyx's whole berry out when any vote decided.)
    bool infinite = false;
    int votes_in = 0, votes_out = 0;
    std::queue<Face> queue;
    queue.push(f);
    region[f] = id;
    while (!queue.empty()) {
      const Face g = queue.front();
      queue.pop();
      if (cdt_.is_infinite(g)) infinite = true;
      for (int i = 0; i < 3; ++i) {
        const Face nb = g->neighbor(i);
        // Split lines divide cells, not regions, and so do the segments of surfaces that are
        // seen on both sides (grains, structure): flood across them. A grain's loop that lies
        // wholly in a hollow or outside the skin is then decided by what surrounds it.
        const Segment2* s = g->is_constrained(i)
                                ? segment_on(g->vertex(Cdt::cw(i)), g->vertex(Cdt::ccw(i)))
                                : nullptr;
        if (!s || !bounds_domain(model_.surfaces[segments_[s->index].surface])) {
          if (!region.count(nb)) {
            region[nb] = id;
            queue.push(nb);
          }
          continue;
        }
        if (cdt_.is_infinite(g)) continue;
        const int side = side_of(*s, g->vertex(Cdt::cw(i))->point(),
                                 g->vertex(Cdt::ccw(i))->point(), g->vertex(i)->point());
        const DsSurface& surface = model_.surfaces[segments_[s->index].surface];
        if (side == 0) continue;
        const bool out = side > 0 ? surface.role == SurfaceRole::Skin || !surface.visible_front
                                  : !surface.visible_back;
        ++(out ? votes_out : votes_in);
      }
    }
    region_in.push_back(!infinite && votes_in > votes_out);
  }
  for (auto f = cdt_.all_faces_begin(); f != cdt_.all_faces_end(); ++f) {
    f->set_in_domain(region_in[region[f]]);
  }
}

void SectionMesher::refine() {
  // Angle and size criteria, no triangle edge below 1e-3 edge. A budget counted in refinement
  // steps, so that the result does not depend on the machine: constraints that meet at tiny
  // angles can make refinement cascade without end. When the budget runs out, or CGAL's checks
  // find that rounding corrupted the triangulation, the refinement is dropped whole and the cap
  // is the constrained Delaunay triangulation of step 1 alone: coarser, but valid, and its
  // boundary is exactly the cut segments.
  try {
    Mesher mesher(cdt_, Criteria(options_.shape_bound, options_.interior_edge * options_.edge_m,
                                 1e-3 * options_.edge_m));
    mesher.init(true);
    const size_t budget = 10 * cdt_.number_of_vertices() + 10000;
    for (size_t step = 0; step < budget && !mesher.is_refinement_done(); ++step)
      mesher.step_by_step_refine_mesh();
    cs_.refinement_capped = !mesher.is_refinement_done();
  } catch (const CGAL::Failure_exception&) {
    cs_.refinement_capped = true;
  }
  if (cs_.refinement_capped) {
    cdt_.clear();
    segment_of_.clear();
    // The same input triangulated the first time, so it has area again.
    CUTAWAY_CHECK(triangulate_domain());
  }
  if (restriction_.keep) restrict_to(restriction_.keep);
}

std::vector<glm::dvec3> SectionMesher::centroids() const {
  std::vector<glm::dvec3> out;
  for (auto f = cdt_.finite_faces_begin(); f != cdt_.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    const glm::dvec2 c =
        (to2(f->vertex(0)->point()) + to2(f->vertex(1)->point()) + to2(f->vertex(2)->point())) /
        3.0;
    out.push_back(plane_.point + cs_.u_axis * c.x + cs_.v_axis * c.y);
  }
  return out;
}

void SectionMesher::restrict_to(const std::function<bool(const glm::dvec3&)>& keep) {
  const std::vector<glm::dvec3> at = centroids();
  size_t k = 0;
  for (auto f = cdt_.finite_faces_begin(); f != cdt_.finite_faces_end(); ++f)
    if (f->is_in_domain() && !keep(at[k++])) f->set_in_domain(false);
}

void SectionMesher::sample_band_lines(const DiffusionBackend& diffusion) {
  const auto meshed = std::chrono::steady_clock::now();
  if (adaptive_) {
    // The blur bands' lines first: ladder points and vertices on blurred cut segments.
    std::vector<Vertex> band_vertices;
    std::vector<BandPoint> band_points;
    for (auto v = cdt_.finite_vertices_begin(); v != cdt_.finite_vertices_end(); ++v) {
      if (!in_domain(cdt_, v)) continue;
      const glm::dvec2 q = to2(v->point());
      if (const auto rung = ladder_.find({q.x, q.y}); rung != ladder_.end()) {
        band_vertices.push_back(v);
        band_points.push_back(
            {rung->second.line, rung->second.arc_length, lift(q), rung->second.width});
        continue;
      }
      auto e = cdt_.incident_edges(v), last = e;
      do {
        if (cdt_.is_infinite(e->first) && cdt_.is_infinite(e->first->neighbor(e->second))) continue;
        if (!cdt_.is_constrained(*e)) continue;
        const Vertex a = e->first->vertex(Cdt::cw(e->second));
        const Vertex b = e->first->vertex(Cdt::ccw(e->second));
        const Segment2* s = segment_on(v, a == Vertex(v) ? b : a);
        if (!s || chains_.chain[s->index] < 0) continue;
        const double length = glm::distance(s->a, s->b);
        const double t =
            length > 0 ? std::clamp(glm::dot(q - s->a, s->b - s->a) / (length * length), 0.0, 1.0)
                       : 0;
        band_vertices.push_back(v);
        const CutSegment& cut = segments_[s->index];
        band_points.push_back({band_line(chains_.chain[s->index], 0),
                               chains_.arc_length(s->index, t, length), lift(q),
                               cut.at_a.blur + (cut.at_b.blur - cut.at_a.blur) * t});
        break;
      } while (++e != last);
    }
    mark_irregular_band_points(band_points, chains_);
    for (BandPoint& b : band_points) b.exact = b.exact || near_grains_.near(b.position);
    std::vector<glm::dvec3> colours(band_points.size());
    std::vector<glm::dvec2> materials(band_points.size());
    const BandSamplingCounts band =
        sample_bands(band_points, diffusion,
                     {options_.band_spacing * options_.edge_m,
                      {options_.tolerance, options_.material_tolerance}},
                     colours, materials);
    for (size_t i = 0; i < band_vertices.size(); ++i)
      samples_.emplace(band_vertices[i], std::make_pair(colours[i], materials[i]));
    cs_.diffused.all = band.diffused;
    cs_.diffused.on_bands = band.diffused;
  }
  seconds_sampling_ = seconds_since(meshed);
}

unsigned SectionMesher::add_vertex(const Point2& p, int surface) {
  cs_.position.push_back(lift(to2(p)));
  cs_.colour.push_back(glm::dvec3(0.0));
  cs_.material.push_back(glm::dvec2(0.0));
  cs_.cut_surface.push_back(surface);
  return static_cast<unsigned>(cs_.position.size() - 1);
}

bool SectionMesher::split_vertices() {
  for (auto v = cdt_.finite_vertices_begin(); v != cdt_.finite_vertices_end(); ++v)
    if (in_domain(cdt_, v)) split_vertex(v);
  for (auto f = cdt_.finite_faces_begin(); f != cdt_.finite_faces_end(); ++f) {
    if (!f->is_in_domain()) continue;
    glm::uvec3 t;
    for (int k = 0; k < 3; ++k) t[k] = corner_id_.at({f->vertex(k), f});
    cs_.triangle.push_back(t);
  }
  return !cs_.triangle.empty();
}

void SectionMesher::split_vertex(Vertex v) {
  // The faces around v in counter-clockwise order, split at constrained edges.
  std::vector<Face> faces;
  auto fc = cdt_.incident_faces(v), done = fc;
  do {
    faces.push_back(fc);
  } while (++fc != done);
  // Whether the edge between faces[k] and the next face counter-clockwise is constrained:
  // in face (v, a, b) that edge is (v, b), opposite a = vertex(ccw(index of v)).
  auto constrained_after = [&](size_t k) {
    const Face f = faces[k];
    return f->is_constrained(Cdt::ccw(f->index(v)));
  };
  size_t start = faces.size(), constrained = 0;
  for (size_t k = 0; k < faces.size(); ++k) {
    if (constrained_after(k)) {
      if (start == faces.size()) start = (k + 1) % faces.size();
      ++constrained;
    }
  }
  // Off the cut segments, or at the open end of one (both sides meet there): diffused.
  if (constrained < 2) {
    const unsigned id = add_vertex(v->point(), -1);
    ++cs_.interior_vertices;
    if (const auto sampled = samples_.find(v); sampled != samples_.end()) {
      std::tie(cs_.colour[id], cs_.material[id]) = sampled->second;
    } else if (adaptive_ && !near_grains_.near(cs_.position[id])) {
      interpolated_.push_back(id);
    } else {
      to_diffuse_.push_back(cs_.position[id]);
      diffuse_targets_.push_back({id});
    }
    for (const Face& f : faces) corner_id_[{v, f}] = id;
    return;
  }
  std::vector<unsigned> blurred;
  for (size_t n = 0; n < faces.size();) {
    // One wedge: faces from `start` up to and including the next constrained edge.
    std::vector<Face> wedge;
    size_t k = (start + n) % faces.size();
    while (true) {
      wedge.push_back(faces[k]);
      ++n;
      if (constrained_after(k) || n >= faces.size()) break;
      k = (k + 1) % faces.size();
    }
    bool wedge_in = false;
    for (const Face& f : wedge) wedge_in = wedge_in || (!cdt_.is_infinite(f) && f->is_in_domain());
    if (!wedge_in) continue;
    // The wedge is bounded by the constrained edge (v, w) before its first face and the one
    // after its last face; one of them lies on a cut segment unless both are split lines.
    const Face first = wedge.front(), last = wedge.back();
    const int i = first->index(v), j = last->index(v);
    Vertex c = first->vertex(Cdt::cw(i)), w = first->vertex(Cdt::ccw(i));
    const Segment2* s = segment_on(v, w);
    if (!s) {
      w = last->vertex(Cdt::cw(j));
      s = segment_on(v, w);
      c = last->vertex(Cdt::ccw(j));
    }
    int surface = -1;
    glm::dvec3 colour(0.0);
    glm::dvec2 material(0.0);
    bool diffuse = true;
    if (s) {
      const CutSegment& cut = segments_[s->index];
      surface = cut.surface;
      const glm::dvec2 p = to2(v->point());
      const double len2 = glm::dot(s->b - s->a, s->b - s->a);
      const double t = len2 > 0 ? std::clamp(glm::dot(p - s->a, s->b - s->a) / len2, 0.0, 1.0) : 0;
      const DsAttributes at = lerp(cut.at_a, cut.at_b, t);
      const bool front = side_of(*s, v->point(), w->point(), c->point()) > 0;
      colour = at.colour(front);
      material = at.material(front);
      diffuse = at.blur > 0;
    }
    const unsigned id = add_vertex(v->point(), surface);
    cs_.colour[id] = colour;
    cs_.material[id] = material;
    if (diffuse) blurred.push_back(id);
    for (const Face& f : wedge) corner_id_[{v, f}] = id;
  }
  if (blurred.empty()) return;
  if (const auto sampled = samples_.find(v); sampled != samples_.end()) {
    for (unsigned id : blurred) std::tie(cs_.colour[id], cs_.material[id]) = sampled->second;
  } else {
    to_diffuse_.push_back(cs_.position[blurred.front()]);
    diffuse_targets_.push_back(std::move(blurred));
  }
}

CrossSection SectionMesher::diffuse_rest(const DiffusionBackend& diffusion) {
  // Every point left (dense), or the cut vertices off the bands and then the interior by
  // harmonic sampling (adaptive).
  for (const glm::dvec3& p : to_diffuse_) CUTAWAY_CHECK(all_finite(p));
  cs_.diffused.all += to_diffuse_.size();
  const auto triangulated = std::chrono::steady_clock::now();
  cs_.seconds_triangulate =
      std::chrono::duration<double>(triangulated - start_).count() - seconds_sampling_;
  std::vector<glm::dvec3> colours(to_diffuse_.size());
  std::vector<glm::dvec2> materials(to_diffuse_.size());
  diffusion.diffuse_channels(to_diffuse_, colours, materials);
  cs_.seconds_diffuse = seconds_sampling_ + seconds_since(triangulated);
  for (size_t i = 0; i < colours.size(); ++i) {
    for (unsigned id : diffuse_targets_[i]) {
      cs_.colour[id] = colours[i];
      cs_.material[id] = materials[i];
    }
  }
  if (adaptive_) {
    const auto interior = std::chrono::steady_clock::now();
    std::vector<bool> free(cs_.position.size(), false);
    for (unsigned id : interpolated_) free[id] = true;
    const HarmonicSamplingCounts counts =
        sample_harmonically(cs_.position, cs_.triangle, free, cs_.colour, cs_.material, diffusion,
                            {options_.harmonic_spacing * options_.edge_m,
                             options_.harmonic_min_spacing * options_.edge_m,
                             {options_.tolerance, options_.material_tolerance}});
    cs_.diffused.all += counts.diffused;
    cs_.seconds_diffuse += seconds_since(interior);
  }
  return std::move(cs_);
}

/// A backend passed through that counts the points it is asked for near grains
/// (DiffusedPoints::near_grains).
class GrainCountingDiffusion final : public DiffusionBackend {
 public:
  GrainCountingDiffusion(const DiffusionBackend& backend, const GrainNeighbourhood& grains)
      : backend_(backend), grains_(grains) {}
  void diffuse_channels(std::span<const glm::dvec3> points, std::span<glm::dvec3> colour,
                        std::span<glm::dvec2> material) const override {
    for (const glm::dvec3& p : points) near_ += grains_.near(p);
    backend_.diffuse_channels(points, colour, material);
  }
  std::string name() const override { return backend_.name(); }
  size_t rays_cast() const override { return backend_.rays_cast(); }
  int threads() const override { return backend_.threads(); }
  size_t near() const { return near_; }

 private:
  const DiffusionBackend& backend_;
  const GrainNeighbourhood& grains_;
  mutable size_t near_ = 0;
};

}  // namespace

/// What a MeshedSection holds: the mesher and its own copies of what the mesher refers to.
struct MeshedSection::Stages {
  Stages(const DsModel& model, const Plane& p, const CrossSectionOptions& o,
         const CapRestriction& r)
      : plane(p), options(o), restriction(r), mesher(model, plane, options, restriction) {}
  const Plane plane;
  const CrossSectionOptions options;
  const CapRestriction restriction;
  SectionMesher mesher;
};

MeshedSection::MeshedSection(std::unique_ptr<Stages> stages) : stages_(std::move(stages)) {}
MeshedSection::MeshedSection(MeshedSection&&) noexcept = default;
MeshedSection& MeshedSection::operator=(MeshedSection&&) noexcept = default;
MeshedSection::~MeshedSection() = default;

std::vector<glm::dvec3> MeshedSection::triangle_centroids() const {
  return stages_->mesher.centroids();
}

void MeshedSection::restrict_to(const std::function<bool(const glm::dvec3&)>& keep) {
  stages_->mesher.restrict_to(keep);
}

Outcome<MeshedSection> mesh_cross_section(const DsModel& model, const Plane& plane,
                                          const CrossSectionOptions& options,
                                          const CapRestriction& restriction) {
  auto stages = std::make_unique<MeshedSection::Stages>(model, plane, options, restriction);
  SectionMesher& mesher = stages->mesher;
  if (!mesher.collect_segments()) return Outcome<MeshedSection>::none(kPlaneMisses);
  mesher.arrange_constraints();
  if (!mesher.triangulate_domain()) return Outcome<MeshedSection>::none(kPlaneOnlyTouches);
  mesher.refine();
  mesher.pause();
  return MeshedSection(std::move(stages));
}

Outcome<CrossSection> colour_cross_section(MeshedSection section,
                                           const DiffusionBackend& diffusion) {
  SectionMesher& mesher = section.stages_->mesher;
  mesher.resume();
  const GrainCountingDiffusion counted(diffusion, mesher.grains());
  mesher.sample_band_lines(counted);
  if (!mesher.split_vertices()) return Outcome<CrossSection>::none(kPlaneOnlyTouches);
  CrossSection out = mesher.diffuse_rest(counted);
  out.diffused.near_grains = counted.near();
  return out;
}

Outcome<CrossSection> make_cross_section(const DsModel& model, const Plane& plane,
                                         const DiffusionBackend& diffusion,
                                         const CrossSectionOptions& options,
                                         const CapRestriction& restriction) {
  Outcome<MeshedSection> meshed = mesh_cross_section(model, plane, options, restriction);
  if (!meshed) return Outcome<CrossSection>::none(meshed.reason());
  return colour_cross_section(std::move(*meshed), diffusion);
}

}  // namespace cutaway
