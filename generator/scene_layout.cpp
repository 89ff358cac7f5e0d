#include "scene_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>
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

}  // namespace

std::vector<Placement> layout_pieces(const std::vector<LayoutPiece>& pieces,
                                     const Container& container, const LayoutOptions& options,
                                     uint64_t seed) {
  const double cs = options.cell_m;
  const double radius = rest_radius(container, options.none_radius_m);
  const int n = static_cast<int>(std::ceil(2 * radius / cs)) + 1;
  const double x0 = -0.5 * (n - 1) * cs;  // cell i covers [x0 + i cs, x0 + (i + 1) cs]
  // The height field of the pile: the top of the pieces placed so far (the container is
  // checked at the pieces' vertices, exactly: its resting surfaces are convex).
  std::vector<double> surface(static_cast<size_t>(n) * n, -kBlocked);

  const glm::dvec3 up(0, 1, 0);
  const glm::dvec3 facing = glm::normalize(up + glm::normalize(options.to_camera));
  std::vector<Placement> out(pieces.size());
  for (size_t p = 0; p < pieces.size(); ++p) {
    Rng rng(derive_seed(seed, {p}));
    const LayoutPiece& piece = pieces[p];
    // Orientation: the largest cap towards `facing` (tilted), spun about it.
    const glm::dvec3 tilt_axis = glm::angleAxis(rng.uniform(0, 2 * kPi), facing) *
                                 perpendicular(facing);
    const double tilt = glm::radians(options.tilt_deg) * rng.uniform();
    const double spin = rng.uniform(0, 2 * kPi);
    glm::dquat rotation;
    if (glm::length(piece.cap_normal) > 0) {
      const glm::dvec3 target = glm::angleAxis(tilt, tilt_axis) * facing;
      rotation = glm::angleAxis(spin, target) *
                 glm::rotation(glm::normalize(piece.cap_normal), target);
    } else {
      rotation = glm::angleAxis(tilt, tilt_axis) * glm::angleAxis(spin, up);
    }
    rotation = glm::normalize(rotation);
    // The turned piece, centred over the origin in x and z.
    std::vector<glm::dvec3> q(piece.mesh->position.size());
    glm::dvec3 centre(0.0);
    for (size_t v = 0; v < q.size(); ++v) {
      q[v] = rotation * piece.mesh->position[v];
      centre += q[v];
    }
    centre /= static_cast<double>(q.size());
    centre.y = 0;
    for (glm::dvec3& v : q) v -= centre;
    const Footprint f = footprint(q, piece.mesh->triangle, cs);

    // Candidate positions: random cells; the piece's local cell (a, b) lands on (i + a, j + b).
    auto rest = [&](int i, int j) {
      double y = -kBlocked;
      const double tx = x0 + i * cs, tz = x0 + j * cs;
      for (const glm::dvec3& v : q) {
        const auto h = rest_height(container, v.x + tx, v.z + tz, options.none_radius_m);
        if (!h) return kBlocked;
        y = std::max(y, *h - v.y);
      }
      for (int a = 0; a < f.na; ++a) {
        for (int b = 0; b < f.nb; ++b) {
          const size_t k = static_cast<size_t>(a) * f.nb + b;
          if (f.bottom[k] == kBlocked) continue;
          const int gi = i + f.a0 + a, gj = j + f.b0 + b;
          if (gi < 0 || gj < 0 || gi >= n || gj >= n) return kBlocked;
          y = std::max(y, surface[static_cast<size_t>(gi) * n + gj] - f.bottom[k]);
        }
      }
      return y;
    };
    double best_score = kBlocked, best_y = 0;
    int best_i = -1, best_j = -1;
    for (int attempt = 0; attempt < 4 * options.candidates; ++attempt) {
      if (attempt >= options.candidates && best_i >= 0) break;  // more only while none fits
      const int i = static_cast<int>(rng.below(static_cast<uint32_t>(n)));
      const int j = static_cast<int>(rng.below(static_cast<uint32_t>(n)));
      const double y = rest(i, j);
      if (y == kBlocked) continue;
      const double score = y + options.centre_weight * std::hypot(x0 + i * cs, x0 + j * cs);
      if (score < best_score) {
        best_score = score;
        best_y = y;
        best_i = i;
        best_j = j;
      }
    }
    if (best_i < 0) continue;  // not placed: the container is full
    const double y = best_y + options.clearance_m;
    for (int a = 0; a < f.na; ++a) {
      for (int b = 0; b < f.nb; ++b) {
        const size_t k = static_cast<size_t>(a) * f.nb + b;
        if (f.bottom[k] == kBlocked) continue;
        double& s = surface[static_cast<size_t>(best_i + f.a0 + a) * n + (best_j + f.b0 + b)];
        s = std::max(s, y + f.top[k]);
      }
    }
    out[p].placed = true;
    out[p].rotation = rotation;
    out[p].translation = glm::dvec3(x0 + best_i * cs, y, x0 + best_j * cs) - centre;
  }
  return out;
}

}  // namespace cutaway
