// The analytic PMVC reference of design/algorithms.md §2(b), shared by the backends' tests: two
// concentric spheres (templates/spheres.yaml), inner radius a showing colour A outwards, outer
// radius b showing colour B inwards.
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>

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
/// of radii a < r < b (algorithms.md §2(b)).
inline double inner_share(double a, double b, double r) {
  const double theta0 = std::asin(a / r);
  auto d1 = [&](double t) { return r * std::cos(t) - std::sqrt(std::max(0.0, a * a - r * r * std::sin(t) * std::sin(t))); };
  auto d2 = [&](double t) { return r * std::cos(t) + std::sqrt(b * b - r * r * std::sin(t) * std::sin(t)); };
  const double wa = integrate([&](double t) { return std::sin(t) / d1(t); }, 0, theta0);
  const double wb = integrate([&](double t) { return std::sin(t) / d2(t); }, theta0, std::numbers::pi);
  return wa / (wa + wb);
}

}  // namespace cutaway::test
