#include "placement/scene_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <tuple>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/gtx/quaternion.hpp>
#include <oneapi/tbb/parallel_for.h>

#include "base/constants.h"
#include "base/random.h"
#include "placement/container_mesh.h"

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
    if (a_lo == a_hi && b_lo == b_hi) {  // within one cell (most triangles): nothing to clip
      const size_t k = static_cast<size_t>(a_lo - f.a0) * f.nb + (b_lo - f.b0);
      f.bottom[k] = std::min({f.bottom[k], a.y, b.y, c.y});
      f.top[k] = std::max({f.top[k], a.y, b.y, c.y});
      continue;
    }
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
  glm::dvec3 lo{0.0}, hi{0.0};  ///< their bounds
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
  t.lo = t.hi = t.q.front();
  for (const glm::dvec3& v : t.q) {
    t.lo = glm::min(t.lo, v);
    t.hi = glm::max(t.hi, v);
  }
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
    if (container_->type == ContainerType::Board) {
      // A board's top is flat and rectangular: every vertex is on it when the corners of the
      // bounds are (adding o is monotonic, so the extreme vertices give the extreme sums), and
      // the lowest vertex decides the height. The same answer as asking every vertex, at once.
      std::optional<double> h;
      for (const glm::dvec3& v : {t.lo, t.hi}) {
        h = rest_height(*container_, v.x + o.x, v.z + o.y, options_->none_radius_m);
        if (!h) return kBlocked;
      }
      y = *h - t.lo.y;
    } else {
      for (const glm::dvec3& v : t.q) {
        const auto h = rest_height(*container_, v.x + o.x, v.z + o.y, options_->none_radius_m);
        if (!h) return kBlocked;
        y = std::max(y, *h - v.y);
      }
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

  /// Whether the four corners of t's bounds placed at (i, j) are over the resting area (on a
  /// board, where it is flat and rectangular, every vertex is then over it).
  bool over_area(const Turned& t, int i, int j) const {
    const glm::dvec2 o = at(i, j);
    for (const double x : {t.lo.x, t.hi.x})
      for (const double z : {t.lo.z, t.hi.z})
        if (!rest_height(*container_, x + o.x, z + o.y, options_->none_radius_m)) return false;
    return true;
  }

  /// Whether no piece lies within `gap` cells of t's footprint placed at (i, j): no cell of
  /// the footprint's rectangle grown by `gap` is occupied (a summed-area table makes it one
  /// lookup of four corners).
  bool free(const Turned& t, int i, int j, int gap) {
    count_occupied();
    const int a0 = std::clamp(i + t.f.a0 - gap, 0, n_);
    const int a1 = std::clamp(i + t.f.a0 + t.f.na + gap, 0, n_);
    const int b0 = std::clamp(j + t.f.b0 - gap, 0, n_);
    const int b1 = std::clamp(j + t.f.b0 + t.f.nb + gap, 0, n_);
    if (a0 >= a1 || b0 >= b1) return true;
    const auto at = [&](int a, int b) { return occupied_[static_cast<size_t>(a) * (n_ + 1) + b]; };
    return at(a1, b1) - at(a0, b1) - at(a1, b0) + at(a0, b0) == 0;
  }

  /// Brings the summed-area table of occupied cells up to date (free() does it when needed;
  /// called before free() is asked from several threads at once, it makes free() read-only).
  void count_occupied() {
    if (occupied_dirty_) {
      // occupied_[(a) * (n + 1) + b]: the occupied cells in [0, a) x [0, b).
      occupied_.assign(static_cast<size_t>(n_ + 1) * (n_ + 1), 0);
      for (int a = 0; a < n_; ++a) {
        for (int b = 0; b < n_; ++b) {
          occupied_[static_cast<size_t>(a + 1) * (n_ + 1) + b + 1] =
              (surface_[static_cast<size_t>(a) * n_ + b] != -kBlocked) +
              occupied_[static_cast<size_t>(a) * (n_ + 1) + b + 1] +
              occupied_[static_cast<size_t>(a + 1) * (n_ + 1) + b] -
              occupied_[static_cast<size_t>(a) * (n_ + 1) + b];
        }
      }
      occupied_dirty_ = false;
    }
  }

  /// Raises the field to the top of t placed at (i, j) with its origin at height y.
  void raise(const Turned& t, int i, int j, double y) {
    occupied_dirty_ = true;
    for (int a = 0; a < t.f.na; ++a) {
      for (int b = 0; b < t.f.nb; ++b) {
        const size_t k = static_cast<size_t>(a) * t.f.nb + b;
        if (t.f.bottom[k] == kBlocked) continue;
        double& s = surface_[static_cast<size_t>(i + t.f.a0 + a) * n_ + (j + t.f.b0 + b)];
        s = std::max(s, y + t.f.top[k]);
      }
    }
  }

  /// Sets the cells under t placed at (i, j) back to their heights in `from` (a field of the
  /// same container and options).
  void restore(const HeightField& from, const Turned& t, int i, int j) {
    occupied_dirty_ = true;
    for (int a = 0; a < t.f.na; ++a) {
      for (int b = 0; b < t.f.nb; ++b) {
        const size_t k = static_cast<size_t>(a) * t.f.nb + b;
        if (t.f.bottom[k] == kBlocked) continue;
        const size_t c = static_cast<size_t>(i + t.f.a0 + a) * n_ + (j + t.f.b0 + b);
        surface_[c] = from.surface_[c];
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
  std::vector<int32_t> occupied_;  ///< summed-area table of the occupied cells, for free()
  bool occupied_dirty_ = true;     ///< surface_ changed since occupied_ was summed
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

/// One object's fan pieces turned for each of `headings` row directions (evenly spaced from
/// `heading0`, radians), each turn computed once per piece, direction and pose: a row split in
/// two reuses them.
class FanTurns {
 public:
  FanTurns(const std::vector<LayoutPiece>& pieces, const LayoutOptions& options, int headings,
           double heading0)
      : pieces_(&pieces), options_(&options), headings_(headings), heading0_(heading0) {}

  int headings() const { return headings_; }
  /// The row direction of heading h, a horizontal unit vector.
  glm::dvec3 direction(int h) const {
    const double a = heading0_ + 2 * kPi * h / headings_;
    return {std::cos(a), 0, std::sin(a)};
  }
  /// Piece p with its cap up (`flat`) or leaning fan_tilt_deg along direction h; a whole
  /// object upright.
  const Turned& get(size_t p, int h, bool flat) {
    auto [it, added] = cache_.try_emplace({p, h, flat});
    if (added) it->second = make(p, h, flat);
    return it->second;
  }

  /// Turns, side by side, what fan rows of `row` will ask for: each of its pieces in every
  /// heading, flat where `flat` says (turns are independent, so the cache holds the same
  /// values as when they are made one by one).
  void prepare(const std::vector<size_t>& row, const std::vector<bool>& flat) {
    std::vector<std::tuple<size_t, int, bool>> missing;
    for (int h = 0; h < headings_; ++h)
      for (size_t k = 0; k < row.size(); ++k)
        if (!cache_.count({row[k], h, flat[k]})) missing.emplace_back(row[k], h, flat[k]);
    std::vector<Turned> made(missing.size());
    oneapi::tbb::parallel_for(size_t{0}, missing.size(), [&](size_t i) {
      made[i] = make(std::get<0>(missing[i]), std::get<1>(missing[i]), std::get<2>(missing[i]));
    });
    for (size_t i = 0; i < missing.size(); ++i) cache_.emplace(missing[i], std::move(made[i]));
  }

 private:
  Turned make(size_t p, int h, bool flat) const {
    const glm::dvec3 up(0, 1, 0), d = direction(h);
    const glm::dvec3 lean =  // tilted from up towards +d
        glm::angleAxis(glm::radians(options_->fan_tilt_deg), glm::cross(d, up)) * up;
    const LayoutPiece& piece = (*pieces_)[p];
    const glm::dquat r = glm::length(piece.cap_normal) > 0
                             ? glm::rotation(glm::normalize(piece.cap_normal), flat ? up : lean)
                             : glm::dquat(1, 0, 0, 0);
    return turn(piece, r, options_->cell_m);
  }

 private:
  const std::vector<LayoutPiece>* pieces_;
  const LayoutOptions* options_;
  int headings_;
  double heading0_;
  std::map<std::tuple<size_t, int, bool>, Turned> cache_;
};

/// A fan row laid out in one direction: each piece turned and its centre's distance along the
/// row from the row's middle.
struct FanRow {
  glm::dvec3 d{1, 0, 0};  ///< the row's direction, horizontal unit
  std::vector<const Turned*> turned;
  std::vector<double> along;
};

/// Which pieces of a fan row lie flat. The first, with none under it: dropped leaning, it
/// tipped over and slid away from the second. So does an end closing the row: leaning, the
/// lowest point of its rounded side lay under the slice before it, and it rolled off the row.
std::vector<bool> lying_flat(const std::vector<LayoutPiece>& pieces,
                             const std::vector<size_t>& row) {
  std::vector<bool> flat(row.size());
  for (size_t k = 0; k < row.size(); ++k) flat[k] = k == 0 || pieces[row[k]].cut_faces < 2;
  return flat;
}

FanRow fan_row(const std::vector<LayoutPiece>& pieces, const std::vector<size_t>& row, int h,
               const LayoutOptions& options, FanTurns& turns) {
  FanRow f;
  f.d = turns.direction(h);
  const std::vector<bool> flat = lying_flat(pieces, row);
  for (size_t k = 0; k < row.size(); ++k) {
    f.turned.push_back(&turns.get(row[k], h, flat[k]));
    double lo = kBlocked, hi = -kBlocked;
    for (const glm::dvec3& v : f.turned.back()->q) {
      lo = std::min(lo, glm::dot(v, f.d));
      hi = std::max(hi, glm::dot(v, f.d));
    }
    f.along.push_back(k == 0 ? 0 : f.along.back() + options.fan_step * (hi - lo));
  }
  const double middle = 0.5 * f.along.back();
  for (double& a : f.along) a -= middle;
  return f;
}

/// Places one fan row: the pieces `row` (indices into pieces, in row order). Candidates are
/// a random heading (one of fan_headings) and a random centre; a row keeps a gap of free
/// ground to the rows and pieces before it, relaxed like scatter's down to none, and, where
/// `may_overlap`, may then lie over them. Returns false (nothing placed) where no candidate fits.
bool place_fan(const std::vector<LayoutPiece>& pieces, const std::vector<size_t>& row,
               bool may_overlap, const LayoutOptions& options, FanTurns& turns, Rng& rng,
               HeightField& field, std::vector<Placement>& out) {
  std::vector<FanRow> headings(static_cast<size_t>(turns.headings()));
  turns.prepare(row, lying_flat(pieces, row));
  const int n = field.cells();
  const int gap = static_cast<int>(std::ceil(options.scatter_gap_m / options.cell_m));
  // Each candidate is tried on `trial` (the row's own pieces rest on each other), which is
  // restored where the candidate raised it; the best one is then raised on the field.
  struct Drop {
    glm::ivec2 ij;
    double y;
  };
  double best_score = kBlocked;
  size_t best_heading = 0;
  std::vector<Drop> best, drops;
  HeightField trial = field;
  // Gap g in cells, halving to 0; then -1: the row may lie over earlier pieces.
  for (int g = gap; best.empty(); g = g > 0 ? g / 2 : g - 1) {
    if (g < (may_overlap ? -1 : 0)) return false;
    for (int attempt = 0; attempt < 4 * options.candidates; ++attempt) {
      if (attempt >= options.candidates && !best.empty()) break;  // more only while none fits
      const size_t h = rng.below(static_cast<uint32_t>(headings.size()));
      if (headings[h].turned.empty())
        headings[h] = fan_row(pieces, row, static_cast<int>(h), options, turns);
      const FanRow& f = headings[h];
      const glm::dvec2 c = field.at(static_cast<int>(rng.below(static_cast<uint32_t>(n))),
                                    static_cast<int>(rng.below(static_cast<uint32_t>(n))));
      drops.clear();
      double score = options.centre_weight * glm::length(c) * static_cast<double>(row.size());
      for (size_t k = 0; k < row.size(); ++k) {
        const glm::ivec2 ij = field.cell(c.x + f.along[k] * f.d.x, c.y + f.along[k] * f.d.z);
        // Free of the pieces before this row (the row's own pieces overlap by design).
        const Turned& t = *f.turned[k];
        const double y =
            g >= 0 && !field.free(t, ij.x, ij.y, g) ? kBlocked : trial.rest(t, ij.x, ij.y);
        if (y == kBlocked) {
          score = kBlocked;
          break;
        }
        score += y;
        drops.push_back({ij, y + options.clearance_m});
        trial.raise(t, ij.x, ij.y, drops.back().y);
      }
      for (size_t k = 0; k < drops.size(); ++k)
        trial.restore(field, *f.turned[k], drops[k].ij.x, drops[k].ij.y);
      if (score < best_score) {
        best_score = score;
        best_heading = h;
        std::swap(best, drops);
      }
    }
  }
  const FanRow& f = headings[best_heading];
  for (size_t k = 0; k < row.size(); ++k) {
    field.raise(*f.turned[k], best[k].ij.x, best[k].ij.y, best[k].y);
    out[row[k]] = field.placement(*f.turned[k], best[k].ij.x, best[k].ij.y, best[k].y);
  }
  return true;
}

/// Places a fan row on free ground; a row that fits nowhere (longer than the plate, or the
/// plate crowded) is split in two shorter rows while each keeps fan_min_row pieces, and only
/// a row that cannot be split may lie over the pieces before it. Pieces of a row that fits
/// nowhere at all are left unplaced.
void place_fan_rows(const std::vector<LayoutPiece>& pieces, const std::vector<size_t>& row,
                    const LayoutOptions& options, FanTurns& turns, Rng& rng, HeightField& field,
                    std::vector<Placement>& out) {
  const size_t min_row = static_cast<size_t>(std::max(1, options.fan_min_row));
  const bool splits = row.size() >= 2 * min_row;
  if (place_fan(pieces, row, !splits, options, turns, rng, field, out) || !splits) return;
  const auto half = row.begin() + static_cast<std::ptrdiff_t>(row.size() / 2);
  for (const std::vector<size_t>& part :
       {std::vector<size_t>(row.begin(), half), std::vector<size_t>(half, row.end())})
    place_fan_rows(pieces, part, options, turns, rng, field, out);
}

/// Places the fan pieces, a row per group, each in rank order between the object's ends: the
/// first end starts the row (its cap a flat rest for the next slice), the other ends it.
void place_fan_groups(const std::vector<LayoutPiece>& pieces, const LayoutOptions& options,
                      uint64_t seed, HeightField& field, std::vector<Placement>& out) {
  std::map<int, std::vector<size_t>> rows;
  for (size_t p = 0; p < pieces.size(); ++p) {
    if (pieces[p].arrange == Arrangement::Fan) rows[pieces[p].group].push_back(p);
  }
  for (auto& [group, row] : rows) {
    std::stable_sort(row.begin(), row.end(),
                     [&](size_t a, size_t b) { return pieces[a].rank < pieces[b].rank; });
    // The first end starts the row (its cap a flat rest for the next slice), the other ends it.
    std::vector<size_t> ends, slices;
    for (size_t p : row) (pieces[p].cut_faces < 2 ? ends : slices).push_back(p);
    row.clear();
    if (!ends.empty()) row.push_back(ends[0]);
    row.insert(row.end(), slices.begin(), slices.end());
    row.insert(row.end(), ends.begin() + std::min<size_t>(1, ends.size()), ends.end());
    Rng rng(derive_seed(seed, {~0ull, static_cast<uint64_t>(group)}));
    FanTurns turns(pieces, options, options.fan_headings, rng.uniform(0, 2 * kPi));
    place_fan_rows(pieces, row, options, turns, rng, field, out);
  }
}

}  // namespace

std::vector<Placement> layout_pieces(const std::vector<LayoutPiece>& pieces,
                                     const Container& container, const LayoutOptions& given,
                                     uint64_t seed) {
  // Scale-aware: a container too wide for cells of cell_m gets larger cells, so that the
  // height field keeps at most kMaxLayoutCells cells a side (a 100 m bowl would need 10^10).
  LayoutOptions options = given;
  options.cell_m = std::max(given.cell_m, 2 * rest_radius(container, given.none_radius_m) /
                                              (kMaxLayoutCells - 1));
  HeightField field(container, options);
  const int n = field.cells();
  const glm::dvec3 up(0, 1, 0);
  // Halfway between up and the camera, the camera taken no lower than the horizon: one below
  // the container would turn the caps down into it, one straight below leave no direction.
  glm::dvec3 to_camera = glm::normalize(options.to_camera);
  to_camera.y = std::max(0.0, to_camera.y);
  const glm::dvec3 facing = glm::normalize(up + to_camera);
  std::vector<Placement> out(pieces.size());

  place_fan_groups(pieces, options, seed, field, out);

  // Candidates are scored side by side in a round container, where each asks the container's
  // height under every vertex of the piece; on a board a candidate takes a few microseconds
  // (the piece's bounds, its footprint) and threads cost more than they save (bench_settle,
  // 320 pieces: layout 1.57 s one by one, 1.90 s side by side).
  const bool side_by_side = container.type != ContainerType::Board;
  std::vector<glm::dvec2> scattered;  // where the scattered pieces went
  struct Beside {
    glm::dvec2 at;  // centre, x and z
    double radius;  // of the footprint's bounds, metres
  };
  std::map<int, std::vector<Beside>> groups;  // per object arranged together, its pieces laid
  const int gap = static_cast<int>(std::ceil(options.scatter_gap_m / options.cell_m));
  const int step = std::max(1, static_cast<int>(std::lround(options.scan_step_m / options.cell_m)));
  // The pieces of one object arranged `together` are laid one after another, where the first
  // of them comes, so that the ground beside the first is still free for the others.
  std::map<int, std::vector<size_t>> of_object;
  for (size_t p = 0; p < pieces.size(); ++p)
    if (pieces[p].arrange == Arrangement::Together && pieces[p].group >= 0)
      of_object[pieces[p].group].push_back(p);
  std::vector<size_t> sequence;
  std::set<int> laid;  // the objects whose pieces are in `sequence`
  for (size_t p = 0; p < pieces.size(); ++p) {
    if (pieces[p].arrange != Arrangement::Together || pieces[p].group < 0) {
      sequence.push_back(p);
    } else if (laid.insert(pieces[p].group).second) {
      const std::vector<size_t>& together = of_object[pieces[p].group];
      sequence.insert(sequence.end(), together.begin(), together.end());
    }
  }
  for (const size_t p : sequence) {
    const LayoutPiece& piece = pieces[p];
    if (piece.arrange == Arrangement::Fan && out[p].placed) continue;
    Rng rng(derive_seed(seed, {p}));
    const Turned t = turn(piece, facing_rotation(piece, facing, options, rng), options.cell_m);
    // Pile pieces heap from the start; scattered ones once no free ground is left, and the
    // pieces of a fan row that fitted nowhere, as a real board or plate heaps up.
    bool heap = !is_scattered(piece.arrange);
    const double centre_weight =
        piece.arrange == Arrangement::Pile ? options.centre_weight : options.heap_centre_weight;
    double best_score = kBlocked, best_y = 0;
    int best_i = -1, best_j = -1;
    // The pieces of its own object scattered before it (none: kAlone), and its own radius.
    const double radius = 0.5 * std::hypot(t.hi.x - t.lo.x, t.hi.z - t.lo.z);
    static const std::vector<Beside> kAlone;
    const auto mates_of = groups.find(piece.group);
    const std::vector<Beside>& mates = mates_of == groups.end() ? kAlone : mates_of->second;
    // A position for the piece at cell (i, j), scored: heaped, the lowest near the axis;
    // scattered, with its footprint grown by `gap_cells` free, the nearest to its object's
    // pieces where there are any, else the farthest from the scattered pieces. kBlocked where
    // it does not fit (or, for `room_beside`, leaves no room beside). Reads the field only.
    struct Scored {
      double score = kBlocked, y = 0;
    };
    // Whether a piece of t's footprint would be free, as t at (i, j) is, in one of 8
    // directions beside it (its centre 2 radii and the gap away), the corners of its bounds
    // over the resting area (exact on a board; in a bowl asking every vertex, as rest() does,
    // made the layout 27 times slower).
    bool room_beside = false;
    const double step_beside = (2 * radius + options.scatter_gap_m) / options.cell_m;
    const auto has_room_beside = [&](int i, int j, int gap_cells) {
      for (int k = 0; k < 8; ++k) {
        const double a = kPi / 4 * k;
        const int di = static_cast<int>(std::lround(step_beside * std::cos(a)));
        const int dj = static_cast<int>(std::lround(step_beside * std::sin(a)));
        if (field.free(t, i + di, j + dj, gap_cells) && field.over_area(t, i + di, j + dj))
          return true;
      }
      return false;
    };
    const auto score_at = [&](int i, int j, int gap_cells) {
      Scored s;
      if (!heap && !field.free(t, i, j, gap_cells)) return s;
      if (room_beside && !has_room_beside(i, j, gap_cells)) return s;
      const double y = field.rest(t, i, j);
      if (y == kBlocked) return s;
      const glm::dvec2 at = field.at(i, j);
      s = {y + centre_weight * glm::length(at), y};
      if (!heap && !mates.empty()) {
        double nearest = kBlocked;
        for (const Beside& m : mates) nearest = std::min(nearest, glm::length(at - m.at));
        s.score = nearest;
      } else if (!heap && !scattered.empty()) {
        double nearest = kBlocked;
        for (const glm::dvec2& o : scattered) nearest = std::min(nearest, glm::length(at - o));
        s.score = -nearest;
      }
      return s;
    };
    // Candidates (`cells`) scored side by side into `scored`, then taken in their order: the
    // best, the first of equals.
    std::vector<glm::ivec2> cells;
    std::vector<Scored> scored;
    const auto score_cells = [&](int gap_cells) {
      scored.assign(cells.size(), Scored{});
      const auto score = [&](size_t k) { scored[k] = score_at(cells[k].x, cells[k].y, gap_cells); };
      if (!side_by_side) {
        for (size_t k = 0; k < cells.size(); ++k) score(k);
        return;
      }
      if (!heap) field.count_occupied();  // free() is asked: read-only from here
      oneapi::tbb::parallel_for(size_t{0}, cells.size(), score);
    };
    const auto take_best = [&] {
      for (size_t k = 0; k < cells.size(); ++k) {
        if (scored[k].score < best_score) {
          best_score = scored[k].score;
          best_y = scored[k].y;
          best_i = cells[k].x;
          best_j = cells[k].y;
        }
      }
    };
    // Random positions, more only while none fits; then every position on a grid of a scan
    // step. Scatter on a crowded board: the gap halves, then goes, before the piece heaps.
    // The first `candidates` are all tried; after them a fit ends the search, so a later block
    // counts up to its first fit, and the generator is left as after drawing those alone.
    // A candidate cell: anywhere, or round a seeded one of `mates`, at 0.8 to 2 times the
    // two footprints' radii and the gap.
    const auto draw = [&](Rng& r, bool beside) -> glm::ivec2 {
      if (!beside) {
        const int i = static_cast<int>(r.below(static_cast<uint32_t>(n)));
        return {i, static_cast<int>(r.below(static_cast<uint32_t>(n)))};
      }
      const Beside& m = mates[r.below(static_cast<uint32_t>(mates.size()))];
      const double angle = r.uniform(0, 2 * kPi);
      const double reach = r.uniform(0.8, 2.0) * (m.radius + radius + options.scatter_gap_m);
      return field.cell(m.at.x + reach * std::cos(angle), m.at.y + reach * std::sin(angle));
    };
    // `beside`: only the `candidates` drawn round the mates.
    const auto search = [&](int gap_cells, bool beside) {
      const int draws = beside ? options.candidates : 4 * options.candidates;
      for (int attempt = 0; attempt < draws;) {
        if (attempt >= options.candidates && best_i >= 0) break;
        const int block = attempt < options.candidates
                              ? options.candidates - attempt
                              : std::min(options.candidates, draws - attempt);
        Rng ahead = rng;
        cells.resize(static_cast<size_t>(block));
        for (glm::ivec2& c : cells) c = draw(ahead, beside);
        score_cells(gap_cells);
        if (attempt >= options.candidates) {  // up to the first fit
          const auto fit = std::find_if(scored.begin(), scored.end(),
                                        [](const Scored& c) { return c.score != kBlocked; });
          const size_t used =
              fit == scored.end() ? cells.size() : static_cast<size_t>(fit - scored.begin()) + 1;
          cells.resize(used);
          scored.resize(used);
        }
        take_best();
        for (size_t k = 0; k < cells.size(); ++k) draw(rng, beside);  // the draws they took
        attempt += static_cast<int>(cells.size());
      }
    };
    const auto scan = [&] {
      for (int i = 0; best_i < 0 && i < n; i += step) {
        cells.clear();
        for (int j = 0; j < n; j += step) cells.push_back({i, j});
        score_cells(0);
        take_best();
      }
    };
    if (!heap) {
      if (!mates.empty()) search(gap, true);
      // The first of an object's pieces where the next has room beside it, then anywhere.
      const auto together = of_object.find(piece.group);
      room_beside = mates.empty() && together != of_object.end() && together->second.size() > 1;
      for (int g = gap; best_i < 0 && room_beside && g > 0; g /= 2) search(g, false);
      room_beside = false;
      for (int g = gap; best_i < 0 && g > 0; g /= 2) search(g, false);
      if (best_i < 0) search(0, false);
      if (best_i < 0) scan();
      if (best_i < 0) heap = true;
    }
    if (heap && best_i < 0) search(0, false);
    if (heap && best_i < 0 && piece.arrange != Arrangement::Pile) scan();
    if (best_i < 0) continue;  // not placed: the piece is larger than the container
    const double y = best_y + options.clearance_m;
    field.raise(t, best_i, best_j, y);
    out[p] = field.placement(t, best_i, best_j, y);
    if (!heap) {
      scattered.push_back(field.at(best_i, best_j));
      if (piece.arrange == Arrangement::Together && piece.group >= 0)
        groups[piece.group].push_back({field.at(best_i, best_j), radius});
    }
  }
  return out;
}

std::vector<size_t> placement_order(size_t n, uint64_t seed) {
  std::vector<size_t> order(n);
  std::iota(order.begin(), order.end(), size_t{0});
  Rng rng(derive_seed(seed, {~0ull, 3}));
  for (size_t k = order.size(); k > 1; --k)
    std::swap(order[k - 1], order[rng.below(static_cast<uint32_t>(k))]);
  return order;
}

LayoutView layout_view(const Container& container, const glm::dvec3& to_camera) {
  const double level = std::hypot(to_camera.x, to_camera.z);
  // The elevation to a nanoradian: a camera moved round the scene keeps it to the last bits
  // only up to rounding, and the direction is part of the placements' cache key.
  const double elevation = std::round(std::atan2(to_camera.y, level) * 1e9) / 1e9;
  const double azimuth = level < 1e-9 ? 0.0 : std::atan2(to_camera.x, to_camera.z);
  const double side =
      container.type == ContainerType::Board ? kPi / 2 * std::round(azimuth / (kPi / 2)) : 0.0;
  const glm::dvec3 direction{std::sin(side) * std::cos(elevation), std::sin(elevation),
                             std::cos(side) * std::cos(elevation)};
  return {direction, container.type == ContainerType::Board ? 0.0 : azimuth};
}

}  // namespace cutaway
