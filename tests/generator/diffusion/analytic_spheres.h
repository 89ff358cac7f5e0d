// The analytic PMVC reference of doc/algorithms.md §2(b), shared by the backends' tests: two
// concentric spheres (templates/spheres.yaml), inner radius a showing colour A outwards, outer
// radius b showing colour B inwards.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "base/constants.h"
#include "diffusion/diffusion.h"

namespace cutaway::test {

/// Composite 8-point Gauss-Legendre quadrature of f over [a, b] with `pieces` sub-intervals.
template <class F>
double integrate(F f, double a, double b, int pieces = 4000) {
  static const double x[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267,
                              0.9602898564975363};
  static const double w[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745,
                              0.1012285362903763};
  double sum = 0;
  const double h = (b - a) / pieces;
  for (int i = 0; i < pieces; ++i) {
    const double c = a + (i + 0.5) * h;
    for (int k = 0; k < 4; ++k) {
      sum += w[k] * (f(c - 0.5 * h * x[k]) + f(c + 0.5 * h * x[k])) * 0.5 * h;
    }
  }
  return sum;
}

/// Share of the inner sphere's colour at distance r from the centre of two concentric spheres
/// of radii a < r < b (doc/algorithms.md §2(b)).
inline double inner_share(double a, double b, double r) {
  const double theta0 = std::asin(a / r);
  auto d1 = [&](double t) {
    return r * std::cos(t) - std::sqrt(std::max(0.0, a * a - r * r * std::sin(t) * std::sin(t)));
  };
  auto d2 = [&](double t) {
    return r * std::cos(t) + std::sqrt(b * b - r * r * std::sin(t) * std::sin(t));
  };
  const double wa = integrate([&](double t) { return std::sin(t) / d1(t); }, 0, theta0);
  const double wb = integrate([&](double t) { return std::sin(t) / d2(t); }, theta0, kPi);
  return wa / (wa + wb);
}

/// How a backend did against inner_share on templates/spheres.yaml.
struct TwoSphereErrors {
  size_t points = 0;
  double mean = 0, max = 0;  ///< |colour - expected| / sqrt(2), linear RGB
  double seconds = 0;        ///< wall time of the diffusion
};

/// Diffuses at points along four rays from the centre of templates/spheres.yaml (radii 20 and
/// 40 mm; inner sphere green outwards, outer sphere red inwards), 25 per ray, each at least
/// `edge_m` away from both spheres, and compares with inner_share.
inline TwoSphereErrors two_sphere_errors(const DiffusionBackend& backend, double edge_m) {
  const double a = 0.020, b = 0.040;
  std::vector<glm::dvec3> points;
  std::vector<double> expected;
  // Rays from the centre in several directions, off the axes and on them.
  const glm::dvec3 dirs[] = {{1, 0, 0},
                             {0, 1, 0},
                             glm::normalize(glm::dvec3(1, 0.7, -0.4)),
                             glm::normalize(glm::dvec3(-0.3, -0.8, 0.5))};
  for (const auto& d : dirs) {
    for (double r = a + edge_m; r <= b - edge_m + 1e-12; r += (b - a - 2 * edge_m) / 24) {
      points.push_back(d * r);
      expected.push_back(inner_share(a, b, r));
    }
  }
  const auto start = std::chrono::steady_clock::now();
  const std::vector<glm::dvec3> colours = backend.diffuse(points);
  TwoSphereErrors e;
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  e.points = points.size();
  for (size_t i = 0; i < points.size(); ++i) {
    const glm::dvec3 want(1 - expected[i], expected[i], 0);
    const double err = glm::length(colours[i] - want) / std::sqrt(2.0);
    e.mean += err / points.size();
    e.max = std::max(e.max, err);
  }
  return e;
}

}  // namespace cutaway::test
