#include "scene_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/gtx/quaternion.hpp>

#include "base/constants.h"
#include "container_mesh.h"
#include "random.h"

namespace cutaway {

namespace {

constexpr double kBlocked = std::numeric_limits<double>::infinity();

/// A piece's footprint: per cell of a grid anchored at the origin, the lowest and highest
/// points of the piece's surface over that cell (metres), over cells [a0, a0 + na) x [b0, ...).
/// Exact (up to rounding) since every triangle is clipped to every cell it overlaps.
struct Footprint {
  int a0 = 0, b0 = 0, na = 0, nb = 0;
  std::vector<double> bottom, top;  // na * nb; bottom = +inf where the piece is absent
};

Footprint footprint(const std::vector<glm::dvec3>& p, const std::vector<glm::uvec3>& triangles,
                    double cs) {
  Footprint f;
  glm::dvec3 lo(kBlocked), hi(-kBlocked);
  for (const glm::dvec3& q : p) {
    lo = glm::min(lo, q);
    hi = glm::max(hi, q);
  }
  f.a0 = static_cast<int>(std::floor(lo.x / cs));
  f.b0 = static_cast<int>(std::floor(lo.z / cs));
  f.na = static_cast<int>(std::floor(hi.x / cs)) - f.a0 + 1;
  f.nb = static_cast<int>(std::floor(hi.z / cs)) - f.b0 + 1;
  f.bottom.assign(static_cast<size_t>(f.na) * f.nb, kBlocked);
  f.top.assign(f.bottom.size(), -kBlocked);
  std::vector<glm::dvec3> poly, next;
  for (const glm::uvec3& t : triangles) {
    const glm::dvec3 a = p[t[0]], b = p[t[1]], c = p[t[2]];
    const int a_lo = static_cast<int>(std::floor(std::min({a.x, b.x, c.x}) / cs));
    const int a_hi = static_cast<int>(std::floor(std::max({a.x, b.x, c.x}) / cs));
    const int b_lo = static_cast<int>(std::floor(std::min({a.z, b.z, c.z}) / cs));
    const int b_hi = static_cast<int>(std::floor(std::max({a.z, b.z, c.z}) / cs));
    for (int i = a_lo; i <= a_hi; ++i) {
      for (int j = b_lo; j <= b_hi; ++j) {
        // The part of the triangle over the cell (clipped by its four sides in x and z, y
        // interpolated): its lowest and highest points are among the clipped vertices.
        poly = {a, b, c};
        const double bounds[4] = {i * cs, (i + 1) * cs, j * cs, (j + 1) * cs};
        for (int side = 0; side < 4 && !poly.empty(); ++side) {
          const int axis = side < 2 ? 0 : 2;
          const double sign = side % 2 == 0 ? 1 : -1, limit = bounds[side];
          next.clear();
          for (size_t k = 0; k < poly.size(); ++k) {
            const glm::dvec3& u = poly[k];
            const glm::dvec3& v = poly[(k + 1) % poly.size()];
            const double du = sign * (u[axis] - limit), dv = sign * (v[axis] - limit);
            if (du >= 0) next.push_back(u);
            if ((du >= 0) != (dv >= 0)) next.push_back(u + (v - u) * (du / (du - dv)));
          }
          std::swap(poly, next);
        }
        if (poly.empty()) continue;
        const size_t k = static_cast<size_t>(i - f.a0) * f.nb + (j - f.b0);
        for (const glm::dvec3& q : poly) {
          f.bottom[k] = std::min(f.bottom[k], q.y);
          f.top[k] = std::max(f.top[k], q.y);
        }
      }
    }
  }
  return f;
}

/// A unit vector perpendicular to d.
glm::dvec3 perpendicular(const glm::dvec3& d) {
  const glm::dvec3 a = std::fabs(d.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  return glm::normalize(glm::cross(d, a));
}

/// A piece turned into its placing orientation, centred over the origin in x and z.
struct Turned {
  glm::dquat rotation{1, 0, 0, 0};
  glm::dvec3 centre{0.0};       ///< subtracted from the turned vertices
  std::vector<glm::dvec3> q;    ///< the turned, centred vertices
  Footprint f;
};

Turned turn(const LayoutPiece& piece, const glm::dquat& rotation, double cs) {
  Turned t;
  t.rotation = glm::normalize(rotation);
  t.q.resize(piece.mesh->position.size());
  for (size_t v = 0; v < t.q.size(); ++v) {
    t.q[v] = t.rotation * piece.mesh->position[v];
    t.centre += t.q[v];
  }
  t.centre /= static_cast<double>(t.q.size());
  t.centre.y = 0;
  for (glm::dvec3& v : t.q) v -= t.centre;
  t.f = footprint(t.q, piece.mesh->triangle, cs);
  return t;
}

/// The height field of the pile over the container: cell (i, j) covers
/// [x0 + i cs, x0 + (i + 1) cs] x [x0 + j cs, ...]; the piece's local cell (a, b) lands on
/// (i + a, j + b).
class HeightField {
 public:
  HeightField(const Container& container, const LayoutOptions& o)
      : container_(&container), options_(&o), cs_(o.cell_m) {
    const double radius = rest_radius(container, o.none_radius_m);
    n_ = static_cast<int>(std::ceil(2 * radius / cs_)) + 1;
    x0_ = -0.5 * (n_ - 1) * cs_;
    surface_.assign(static_cast<size_t>(n_) * n_, -kBlocked);
  }

  int cells() const { return n_; }
  /// The centre of the piece placed at cell (i, j), x and z.
  glm::dvec2 at(int i, int j) const { return {x0_ + i * cs_, x0_ + j * cs_}; }
  /// The cell of a point, rounded.
  glm::ivec2 cell(double x, double z) const {
    return {static_cast<int>(std::lround((x - x0_) / cs_)),
            static_cast<int>(std::lround((z - x0_) / cs_))};
  }

  /// The lowest height at which piece t placed at (i, j) is above the container and the pile,
  /// or kBlocked where a vertex is outside the resting area.
  double rest(const Turned& t, int i, int j) const {
    double y = -kBlocked;
    const glm::dvec2 o = at(i, j);
    for (const glm::dvec3& v : t.q) {
      const auto h = rest_height(*container_, v.x + o.x, v.z + o.y, options_->none_radius_m);
      if (!h) return kBlocked;
      y = std::max(y, *h - v.y);
    }
    for (int a = 0; a < t.f.na; ++a) {
      for (int b = 0; b < t.f.nb; ++b) {
        const size_t k = static_cast<size_t>(a) * t.f.nb + b;
        if (t.f.bottom[k] == kBlocked) continue;
        const int gi = i + t.f.a0 + a, gj = j + t.f.b0 + b;
        if (gi < 0 || gj < 0 || gi >= n_ || gj >= n_) return kBlocked;
        y = std::max(y, surface_[static_cast<size_t>(gi) * n_ + gj] - t.f.bottom[k]);
      }
    }
    return y;
  }

  /// Whether no piece lies within `gap` cells of t's footprint placed at (i, j).
  bool free(const Turned& t, int i, int j, int gap) const {
    for (int a = -gap; a < t.f.na + gap; ++a) {
      for (int b = -gap; b < t.f.nb + gap; ++b) {
        const int gi = i + t.f.a0 + a, gj = j + t.f.b0 + b;
        if (gi < 0 || gj < 0 || gi >= n_ || gj >= n_) continue;
        if (surface_[static_cast<size_t>(gi) * n_ + gj] != -kBlocked) return false;
      }
    }
    return true;
  }

  /// Raises the field to the top of t placed at (i, j) with its origin at height y.
  void raise(const Turned& t, int i, int j, double y) {
    for (int a = 0; a < t.f.na; ++a) {
      for (int b = 0; b < t.f.nb; ++b) {
        const size_t k = static_cast<size_t>(a) * t.f.nb + b;
        if (t.f.bottom[k] == kBlocked) continue;
        double& s = surface_[static_cast<size_t>(i + t.f.a0 + a) * n_ + (j + t.f.b0 + b)];
        s = std::max(s, y + t.f.top[k]);
      }
    }
  }

  Placement placement(const Turned& t, int i, int j, double y) const {
    const glm::dvec2 o = at(i, j);
    return {true, t.rotation, glm::dvec3(o.x, y, o.y) - t.centre};
  }

 private:
  const Container* container_;
  const LayoutOptions* options_;
  double cs_, x0_;
  int n_;
  std::vector<double> surface_;
};

/// The pile's and scatter's orientation: the largest cap towards `facing` (tilted), spun about
/// it; a whole object upright, tilted and spun.
glm::dquat facing_rotation(const LayoutPiece& piece, const glm::dvec3& facing,
                           const LayoutOptions& options, Rng& rng) {
  const glm::dvec3 up(0, 1, 0);
  const glm::dvec3 tilt_axis =
      glm::angleAxis(rng.uniform(0, 2 * kPi), facing) * perpendicular(facing);
  const double tilt = glm::radians(options.tilt_deg) * rng.uniform();
  const double spin = rng.uniform(0, 2 * kPi);
  if (glm::length(piece.cap_normal) > 0) {
    const glm::dvec3 target = glm::angleAxis(tilt, tilt_axis) * facing;
    return glm::angleAxis(spin, target) * glm::rotation(glm::normalize(piece.cap_normal), target);
  }
  return glm::angleAxis(tilt, tilt_axis) * glm::angleAxis(spin, up);
}

/// Places one fan row: the pieces `row` (indices into pieces, in rank order).
void place_fan(const std::vector<LayoutPiece>& pieces, const std::vector<size_t>& row,
               const LayoutOptions& options, Rng& rng, HeightField& field,
               std::vector<Placement>& out) {
  const glm::dvec3 up(0, 1, 0);
  const double heading = rng.uniform(0, 2 * kPi);
  const glm::dvec3 d(std::cos(heading), 0, std::sin(heading));  // the row's direction
  // Each piece's cap up, leaning along the row; a whole object upright.
  const glm::dvec3 lean = glm::angleAxis(glm::radians(options.fan_tilt_deg), glm::cross(d, up)) *
                          up;  // tilted from up towards +d
  std::vector<Turned> turned;
  std::vector<double> along;  // each piece's centre along the row, from the first's
  for (size_t k = 0; k < row.size(); ++k) {
    const LayoutPiece& piece = pieces[row[k]];
    // The first piece, with none under it, lies flat: dropped leaning, it tipped over and slid
    // away from the second.
    const glm::dquat r = glm::length(piece.cap_normal) > 0
                             ? glm::rotation(glm::normalize(piece.cap_normal), k == 0 ? up : lean)
                             : glm::dquat(1, 0, 0, 0);
    turned.push_back(turn(piece, r, options.cell_m));
    double lo = kBlocked, hi = -kBlocked;
    for (const glm::dvec3& v : turned.back().q) {
      lo = std::min(lo, glm::dot(v, d));
      hi = std::max(hi, glm::dot(v, d));
    }
    along.push_back(k == 0 ? 0 : along.back() + options.fan_step * (hi - lo));
  }
  const double middle = 0.5 * along.back();
  // Candidate row centres; each row is tried on a copy of the height field.
  double best_score = kBlocked;
  std::vector<Placement> best;
  HeightField best_field = field;
  const int n = field.cells();
  for (int attempt = 0; attempt < 4 * options.candidates; ++attempt) {
    if (attempt >= options.candidates && !best.empty()) break;
    const glm::dvec2 c = field.at(static_cast<int>(rng.below(static_cast<uint32_t>(n))),
                                  static_cast<int>(rng.below(static_cast<uint32_t>(n))));
    HeightField trial = field;
    std::vector<Placement> placed;
    double score = options.centre_weight * glm::length(c) * static_cast<double>(row.size());
    for (size_t k = 0; k < row.size() && score < kBlocked; ++k) {
      const double s = along[k] - middle;
      const glm::ivec2 ij = trial.cell(c.x + s * d.x, c.y + s * d.z);
      const double y = trial.rest(turned[k], ij.x, ij.y);
      if (y == kBlocked) {
        score = kBlocked;
        break;
      }
      score += y;
      trial.raise(turned[k], ij.x, ij.y, y + options.clearance_m);
      placed.push_back(trial.placement(turned[k], ij.x, ij.y, y + options.clearance_m));
    }
    if (score < best_score) {
      best_score = score;
      best = std::move(placed);
      best_field = std::move(trial);
    }
  }
  if (best.empty()) return;  // no room for the row
  field = std::move(best_field);
  for (size_t k = 0; k < row.size(); ++k) out[row[k]] = best[k];
}

}  // namespace

std::vector<Placement> layout_pieces(const std::vector<LayoutPiece>& pieces,
                                     const Container& container, const LayoutOptions& options,
                                     uint64_t seed) {
  HeightField field(container, options);
  const int n = field.cells();
  const glm::dvec3 up(0, 1, 0);
  const glm::dvec3 facing = glm::normalize(up + glm::normalize(options.to_camera));
  std::vector<Placement> out(pieces.size());

  // Fan rows first, by group, each in rank order after the object's ends.
  std::map<int, std::vector<size_t>> rows;
  for (size_t p = 0; p < pieces.size(); ++p) {
    if (pieces[p].arrange == Arrangement::Fan) rows[pieces[p].group].push_back(p);
  }
  for (auto& [group, row] : rows) {
    std::stable_sort(row.begin(), row.end(), [&](size_t a, size_t b) {
      const bool end_a = pieces[a].cut_faces < 2, end_b = pieces[b].cut_faces < 2;
      return end_a != end_b ? end_a : pieces[a].rank < pieces[b].rank;
    });
    Rng rng(derive_seed(seed, {~0ull, static_cast<uint64_t>(group)}));
    place_fan(pieces, row, options, rng, field, out);
  }

  std::vector<glm::dvec2> scattered;  // where the scattered pieces went
  const int gap = static_cast<int>(std::ceil(options.scatter_gap_m / options.cell_m));
  for (size_t p = 0; p < pieces.size(); ++p) {
    const LayoutPiece& piece = pieces[p];
    if (piece.arrange == Arrangement::Fan) continue;
    Rng rng(derive_seed(seed, {p}));
    const Turned t = turn(piece, facing_rotation(piece, facing, options, rng), options.cell_m);
    const bool scatter = piece.arrange == Arrangement::Scatter;
    double best_score = kBlocked, best_y = 0;
    int best_i = -1, best_j = -1;
    // A position for the piece at cell (i, j), scored: pile, the lowest near the axis; scatter,
    // with its footprint grown by `gap_cells` free, the farthest from the scattered pieces.
    const auto consider = [&](int i, int j, int gap_cells) {
      if (scatter && !field.free(t, i, j, gap_cells)) return;
      const double y = field.rest(t, i, j);
      if (y == kBlocked) return;
      const glm::dvec2 at = field.at(i, j);
      double score = y + options.centre_weight * glm::length(at);
      if (scatter && !scattered.empty()) {
        double nearest = kBlocked;
        for (const glm::dvec2& o : scattered) nearest = std::min(nearest, glm::length(at - o));
        score = -nearest;
      }
      if (score < best_score) {
        best_score = score;
        best_y = y;
        best_i = i;
        best_j = j;
      }
    };
    // Scatter on a crowded board: the gap halves, then goes, before a piece is left out; with
    // no gap, every cell on a grid of a scan step is tried after the random ones.
    for (int g = scatter ? gap : 0; best_i < 0; g /= 2) {
      for (int attempt = 0; attempt < 4 * options.candidates; ++attempt) {
        if (attempt >= options.candidates && best_i >= 0) break;  // more only while none fits
        const int i = static_cast<int>(rng.below(static_cast<uint32_t>(n)));
        const int j = static_cast<int>(rng.below(static_cast<uint32_t>(n)));
        consider(i, j, g);
      }
      if (g == 0) {
        const int step = std::max(1, static_cast<int>(std::lround(options.scan_step_m /
                                                                   options.cell_m)));
        for (int i = 0; scatter && best_i < 0 && i < n; i += step)
          for (int j = 0; j < n; j += step) consider(i, j, 0);
        break;
      }
    }
    if (best_i < 0) continue;  // not placed: the container is full
    const double y = best_y + options.clearance_m;
    field.raise(t, best_i, best_j, y);
    out[p] = field.placement(t, best_i, best_j, y);
    if (scatter) scattered.push_back(field.at(best_i, best_j));
  }
  return out;
}

}  // namespace cutaway
