#include "placement/container_mesh.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>

#include "base/constants.h"

namespace cutaway {

namespace {

double bowl_wall(const Container& c) { return 0.03 * c.diameter_m; }
double bowl_floor(const Container& c) { return 0.08 * c.height_m; }
double plate_well(const Container& c) { return 0.62 * 0.5 * c.diameter_m; }
double plate_floor(const Container& c) { return 0.3 * c.height_m; }

/// Inner (resting) surface heights of the round containers at distance r from the axis.
double bowl_inner(const Container& c, double r) {
  const double R = 0.5 * c.diameter_m - bowl_wall(c), f = bowl_floor(c);
  const double s = std::min(1.0, r / R);
  return f + (c.height_m - f) * (1 - std::sqrt(std::max(0.0, 1 - s * s)));
}
double plate_inner(const Container& c, double r) {
  const double w = plate_well(c), R = 0.5 * c.diameter_m, f = plate_floor(c);
  if (r <= w) return f;
  return f + (c.height_m - f) * std::pow(std::min(1.0, (r - w) / (R - w)), 1.6);
}

/// Revolves a closed profile of (r, y) points (counter-clockwise in the (r, y) half-plane seen
/// from +Z, i.e. the outward side to the right when walking along it... as given: inside first
/// from the axis outwards, then back along the outside) about +Y. Points with r = 0 become
/// poles. Vertex normals from the profile's own normals (each point: the average of its two
/// segments'), so creases come out where the profile says (points repeated at creases).
AssetMesh lathe(const std::vector<glm::dvec2>& profile, const std::vector<glm::dvec2>& normals,
                const glm::dvec3& colour, int segments) {
  AssetMesh mesh;
  const int n = static_cast<int>(profile.size());
  std::vector<int> first(n);
  for (int i = 0; i < n; ++i) {
    first[i] = static_cast<int>(mesh.position.size());
    const int ring = profile[i].x == 0 ? 1 : segments;
    for (int k = 0; k < ring; ++k) {
      const double a = 2 * kPi * k / segments;
      const double c = std::cos(a), s = -std::sin(a);
      mesh.position.push_back({profile[i].x * c, profile[i].y, profile[i].x * s});
      mesh.normal.push_back(
          glm::normalize(glm::dvec3(normals[i].x * c, normals[i].y, normals[i].x * s)));
      mesh.colour.push_back(colour);
    }
  }
  auto at = [&](int i, int k) {
    return static_cast<unsigned>(first[i] + (profile[i].x == 0 ? 0 : k % segments));
  };
  for (int i = 0; i + 1 < n; ++i) {
    if (profile[i] == profile[i + 1]) continue;  // a crease: the repeated point
    for (int k = 0; k < segments; ++k) {
      const unsigned a = at(i, k), b = at(i, k + 1), c = at(i + 1, k), d = at(i + 1, k + 1);
      // Walking from profile point i to i+1 with the angle increasing (towards -Z from +X),
      // the outward side is to the right of the profile direction in the (r, y) plane.
      if (a != b) mesh.triangle.push_back({a, c, b});
      if (c != d) mesh.triangle.push_back({b, c, d});
    }
  }
  return mesh;
}

/// Appends a profile segment sampled from a function, with normals from its tangent (outward to
/// the right of the walking direction in (r, y)).
void append_curve(std::vector<glm::dvec2>& pts, std::vector<glm::dvec2>& nrm, int samples,
                  const auto& curve) {
  for (int k = 0; k <= samples; ++k) {
    const double t = static_cast<double>(k) / samples, h = 1e-4;
    const glm::dvec2 p = curve(t);
    const glm::dvec2 tangent = curve(std::min(1.0, t + h)) - curve(std::max(0.0, t - h));
    pts.push_back(p);
    nrm.push_back(glm::normalize(glm::dvec2(tangent.y, -tangent.x)));
  }
}

/// The coordinates a rounded box's face grid takes along one axis from lo to hi: `band` steps
/// across each rounded edge of radius r and one flat step across the rest of the side.
std::vector<double> rounded_steps(double lo, double hi, double r, int band) {
  std::vector<double> out;
  for (int k = 0; k < band; ++k) out.push_back(lo + r * k / band);
  out.push_back(lo + r);
  for (int k = 0; k <= band; ++k) out.push_back(hi - r + r * k / band);
  return out;
}

/// The box lo..hi with every edge and corner rounded to radius r (< half its smallest side):
/// each face a grid (rounded_steps) whose points p are moved to q = c + r (p - c) / |p - c|, c
/// the point of the box shrunk by r nearest to p, with that direction as the normal; on the flat
/// part q = p. The faces' own vertices are not shared (their positions and normals agree along
/// the seams). Counter-clockwise seen from outside.
AssetMesh rounded_box_mesh(const glm::dvec3& lo, const glm::dvec3& hi, double r,
                           const glm::dvec3& colour) {
  constexpr int kBand = 4;  // steps across a rounded edge (a quarter circle)
  AssetMesh mesh;
  for (int axis = 0; axis < 3; ++axis) {
    const int u = (axis + 1) % 3, v = (axis + 2) % 3;
    const std::vector<double> us = rounded_steps(lo[u], hi[u], r, kBand);
    const std::vector<double> vs = rounded_steps(lo[v], hi[v], r, kBand);
    for (int side = 0; side < 2; ++side) {
      const unsigned base = static_cast<unsigned>(mesh.position.size());
      for (double b : vs) {
        for (double a : us) {
          glm::dvec3 p;
          p[axis] = side ? hi[axis] : lo[axis];
          p[u] = a;
          p[v] = b;
          const glm::dvec3 c = glm::clamp(p, lo + r, hi - r);
          const glm::dvec3 n = glm::normalize(p - c);
          mesh.position.push_back(c + r * n);
          mesh.normal.push_back(n);
          mesh.colour.push_back(colour);
        }
      }
      const unsigned nu = static_cast<unsigned>(us.size());
      for (unsigned j = 0; j + 1 < vs.size(); ++j) {
        for (unsigned i = 0; i + 1 < nu; ++i) {
          const unsigned a = base + j * nu + i, b = a + 1, c = a + nu, d = c + 1;
          // (u, v) increasing is counter-clockwise about +axis.
          if (side) {
            mesh.triangle.push_back({a, b, d});
            mesh.triangle.push_back({a, d, c});
          } else {
            mesh.triangle.push_back({a, d, b});
            mesh.triangle.push_back({a, c, d});
          }
        }
      }
    }
  }
  return mesh;
}

}  // namespace

std::optional<AssetMesh> container_mesh(const Container& c, int segments, int profile_samples) {
  std::vector<glm::dvec2> pts, nrm;
  const double R = 0.5 * c.diameter_m, H = c.height_m;
  switch (c.type) {
    case ContainerType::None: return std::nullopt;
    case ContainerType::Board: {
      const glm::dvec3 lo(-0.5 * c.width_m, 0, -0.5 * c.depth_m),
          hi(0.5 * c.width_m, H, 0.5 * c.depth_m);
      const double r = std::min({kBoardEdgeRadius_m, 0.3 * H, 0.3 * c.width_m, 0.3 * c.depth_m});
      AssetMesh mesh = rounded_box_mesh(lo, hi, r, c.colour);
      // The top seen from above: the wood's texture (board_wood.h) lies on it, and the sides
      // take its rows and columns at the edges.
      for (const glm::dvec3& p : mesh.position)
        mesh.uv.push_back({(p.x - lo.x) / c.width_m, (p.z - lo.z) / c.depth_m});
      mesh.name = "board";
      return mesh;
    }
    case ContainerType::Bowl: {
      const double inner_R = R - bowl_wall(c), foot = 0.45 * R;
      // Inside, from the axis out to the rim, with normals pointing up and inwards.
      append_curve(pts, nrm, profile_samples, [&](double t) {
        const double r = inner_R * std::sin(t * kPi / 2);
        return glm::dvec2(r, bowl_inner(c, r));
      });
      for (glm::dvec2& n : nrm) n = -n;  // the inside faces the axis and up
      // The rounded rim from the inner to the outer edge.
      const size_t rim_start = pts.size();
      append_curve(pts, nrm, 8, [&](double t) {
        const double a = kPi * t, w = bowl_wall(c);
        return glm::dvec2(inner_R + 0.5 * w * (1 - std::cos(a)), H + 0.5 * w * std::sin(a));
      });
      for (size_t k = rim_start; k < nrm.size(); ++k) nrm[k] = -nrm[k];
      // Outside, from the rim down to the foot.
      append_curve(pts, nrm, profile_samples, [&](double t) {
        const double a = t * kPi / 2;
        return glm::dvec2(foot + (R - foot) * std::cos(a), H * (1 - std::sin(a)));
      });
      for (size_t k = nrm.size() - profile_samples - 1; k < nrm.size(); ++k) nrm[k] = -nrm[k];
      // The flat bottom back to the axis (a crease at the foot).
      pts.push_back(pts.back());
      nrm.push_back({0, -1});
      pts.push_back({0, 0});
      nrm.push_back({0, -1});
      break;
    }
    case ContainerType::Plate: {
      const double foot = 0.5 * R;
      append_curve(pts, nrm, profile_samples, [&](double t) {
        const double r = R * t;
        return glm::dvec2(r, plate_inner(c, r));
      });
      for (glm::dvec2& n : nrm) n = -n;
      const double w = 0.004;
      pts.push_back(pts.back());
      nrm.push_back({1, 0});
      pts.push_back({R + 0.5 * w, H - 0.5 * w});
      nrm.push_back({1, 0});
      pts.push_back({R, H - w});
      nrm.push_back({1, -0.3});
      pts.push_back({foot, 0});
      nrm.push_back({0.2, -1});
      pts.push_back(pts.back());
      nrm.push_back({0, -1});
      pts.push_back({0, 0});
      nrm.push_back({0, -1});
      break;
    }
  }
  AssetMesh mesh = lathe(pts, nrm, c.colour, segments);
  mesh.name = c.type == ContainerType::Bowl ? "bowl" : "plate";
  return mesh;
}

std::optional<double> rest_height(const Container& c, double x, double z, double none_radius_m) {
  if (c.type == ContainerType::Board) {
    if (std::fabs(x) > 0.5 * c.width_m || std::fabs(z) > 0.5 * c.depth_m) return std::nullopt;
    return c.height_m;
  }
  // A round container: by the distance from the axis (the layout asks for every vertex of
  // every candidate position, so a board does not compute it).
  const double r = std::hypot(x, z);
  switch (c.type) {
    case ContainerType::None:
      if (r > none_radius_m) return std::nullopt;
      return 0.0;
    case ContainerType::Board: break;
    case ContainerType::Bowl:
      if (r >= 0.5 * c.diameter_m - bowl_wall(c)) return std::nullopt;
      return bowl_inner(c, r);
    case ContainerType::Plate:
      if (r >= 0.5 * c.diameter_m) return std::nullopt;
      return plate_inner(c, r);
  }
  return std::nullopt;
}

double resting_overhang(const Container& c, double x, double z, double none_radius_m) {
  if (c.type == ContainerType::Board) {
    return std::hypot(std::max(0.0, std::fabs(x) - 0.5 * c.width_m),
                      std::max(0.0, std::fabs(z) - 0.5 * c.depth_m));
  }
  return std::max(0.0, std::hypot(x, z) - rest_radius(c, none_radius_m));
}

double heap_capacity(const Container& c, double none_radius_m) {
  // A cone of slope kHeapSlope over a disc of radius r.
  const auto cone = [](double r) { return kPi * r * r * (kHeapSlope * r) / 3; };
  switch (c.type) {
    case ContainerType::None: return cone(none_radius_m);
    case ContainerType::Board: {
      // A hip roof over W x D (W >= D): ridge height h = D/2 slope, volume h D (3 W - D) / 6.
      const double w = std::max(c.width_m, c.depth_m), d = std::min(c.width_m, c.depth_m);
      return kHeapSlope * 0.5 * d * d * (3 * w - d) / 6;
    }
    case ContainerType::Bowl: {
      const double a = 0.5 * c.diameter_m - bowl_wall(c);
      return 2.0 / 3.0 * kPi * a * a * (c.height_m - bowl_floor(c)) + cone(a);
    }
    case ContainerType::Plate: return cone(0.5 * c.diameter_m);
  }
  return cone(none_radius_m);
}

double rest_radius(const Container& c, double none_radius_m) {
  switch (c.type) {
    case ContainerType::None: return none_radius_m;
    case ContainerType::Board: return 0.5 * std::hypot(c.width_m, c.depth_m);
    case ContainerType::Bowl: return 0.5 * c.diameter_m - bowl_wall(c);
    case ContainerType::Plate: return 0.5 * c.diameter_m;
  }
  return none_radius_m;
}

}  // namespace cutaway
