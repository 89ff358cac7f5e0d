#include "variation/fold_pca.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <glm/geometric.hpp>

#include "base/constants.h"
#include "base/error.h"
#include "model/template_checks.h"

namespace cutaway {

namespace {

glm::dvec2 xz_at(double rho, double phi) { return {rho * std::cos(phi), -rho * std::sin(phi)}; }

/// Point of segment p-q on the ray from the axis at angle `phi`.
glm::dvec2 on_ray(const glm::dvec2& p, const glm::dvec2& q, double phi) {
  const glm::dvec2 d = xz_at(1.0, phi);
  const double cp = d.x * p.y - d.y * p.x, cq = d.x * q.y - d.y * q.x;
  const double s = cp == cq ? 0.0 : cp / (cp - cq);
  return p + (q - p) * std::clamp(s, 0.0, 1.0);
}

/// The part of a star-shaped loop between the rays at angles a0 < a1 (a1 - a0 <= 2 pi),
/// counter-clockwise seen from +Y.
Polyline2 arc_between(const Polyline2& loop_xz, bool smooth, double a0, double a1) {
  Polyline2 loop = fit_curve(loop_xz, true, smooth);
  Polyline2 flipped;
  for (const auto& p : loop) flipped.push_back({p.x, -p.y});
  if (signed_area(flipped) < 0) std::reverse(loop.begin(), loop.end());
  const size_t n = loop.size();
  // Unwrapped angles over two laps.
  std::vector<double> phi(2 * n + 1);
  phi[0] = horizontal_angle(loop[0]);
  for (size_t i = 1; i <= 2 * n; ++i) {
    double d = wrap_angle(horizontal_angle(loop[i % n]) - horizontal_angle(loop[(i - 1) % n]));
    phi[i] = phi[i - 1] + d;
  }
  const double shift = 2 * kPi * std::floor((a0 - phi[0]) / (2 * kPi));
  a0 -= shift;
  a1 -= shift;
  Polyline2 out;
  for (size_t i = 0; i < 2 * n; ++i) {
    const glm::dvec2 p = loop[i % n], q = loop[(i + 1) % n];
    if (out.empty()) {
      if (phi[i] <= a0 && a0 < phi[i + 1]) out.push_back(on_ray(p, q, a0 + shift));
      else continue;
    }
    if (phi[i + 1] >= a1) {
      out.push_back(on_ray(p, q, a1 + shift));
      break;
    }
    if (glm::distance(q, out.back()) > 1e-12) out.push_back(q);
  }
  CUTAWAY_CHECK(out.size() >= 2);
  return out;
}

struct Pie {
  double lo, hi, width;  // the fold's span and the canonical pie angle
  glm::dvec2 to_canonical(const glm::dvec2& xz, double centre) const {
    const double phi = centre + wrap_angle(horizontal_angle(xz) - centre);
    const double theta = ((phi - lo) / (hi - lo) - 0.5) * width;
    const double rho = glm::length(xz);
    return {rho * std::cos(theta), rho * std::sin(theta)};
  }
  glm::dvec2 to_xz(const glm::dvec2& c) const {
    const double a = std::atan2(c.y, c.x) / width + 0.5;
    return xz_at(glm::length(c), lo + a * (hi - lo));
  }
};

Pie pie_of(const Template& t, int k, int n) {
  const auto [lo, hi] = fold_span(t, k);
  return {lo, hi, 2 * kPi / n};
}

}  // namespace

FoldFeatures fold_features(const Template& t, const FoldPcaOptions& opt) {
  CUTAWAY_CHECK(t.symmetry == Symmetry::NFold);
  const int N = t.folds;
  FoldFeatures f;
  f.folds = N;
  f.samples.assign(N, {});
  const double W = 2 * kPi / N;
  for (int si = 0; si < static_cast<int>(t.surfaces.size()); ++si) {
    const SurfaceSpec& s = t.surfaces[si];
    for (int sec = s.sections.empty() ? -1 : 0; sec < static_cast<int>(s.sections.size()); ++sec) {
      const SectionSpec& section =
          sec < 0 ? s.section : s.sections[static_cast<size_t>(sec)].section;
      if (s.kind == SurfaceKind::Around && !section.circle) {
        f.surface.push_back(si);
        f.section.push_back(sec);
        f.open.push_back(true);
        f.points.push_back(opt.arc_samples);
        for (int k = 0; k < N; ++k) {
          const Pie pie = pie_of(t, k, N);
          const Polyline2 arc = resample_uniform(
              arc_between(section.loops[0], s.smooth, pie.lo, pie.hi), false, opt.arc_samples);
          for (int i = 0; i < opt.arc_samples; ++i) {
            glm::dvec2 c;
            const double rho = glm::length(arc[i]);
            if (i == 0) c = {rho * std::cos(-W / 2), rho * std::sin(-W / 2)};
            else if (i + 1 == opt.arc_samples) c = {rho * std::cos(W / 2), rho * std::sin(W / 2)};
            else c = pie.to_canonical(arc[i], t.fold_angles[k]);
            f.samples[k].push_back(c.x);
            f.samples[k].push_back(c.y);
          }
        }
      } else if (s.kind == SurfaceKind::Within) {
        f.surface.push_back(si);
        f.section.push_back(sec);
        f.open.push_back(false);
        f.points.push_back(opt.loop_samples);
        const int M = opt.loop_samples;
        Polyline2 reference;
        for (int k = 0; k < N; ++k) {
          const int li = section.loops.size() == 1 ? 0 : k;
          const Pie pie = pie_of(t, li, N);
          Polyline2 c;
          for (const auto& p : fit_curve(section.loops[li], true, s.smooth))
            c.push_back(pie.to_canonical(p, t.fold_angles[li]));
          if (signed_area(c) < 0) std::reverse(c.begin(), c.end());
          const auto start =
              std::max_element(c.begin(), c.end(), [](auto& a, auto& b) { return a.x < b.x; });
          std::rotate(c.begin(), start, c.end());
          Polyline2 r = resample_uniform(c, true, M);
          if (k == 0) {
            reference = r;
          } else {
            int best = 0;
            double best_sum = 1e300;
            for (int sh = 0; sh < M; ++sh) {
              double sum = 0;
              for (int i = 0; i < M; ++i) sum += glm::distance(reference[i], r[(i + sh) % M]);
              if (sum < best_sum) {
                best_sum = sum;
                best = sh;
              }
            }
            std::rotate(r.begin(), r.begin() + best, r.end());
          }
          for (const auto& p : r) {
            f.samples[k].push_back(p.x);
            f.samples[k].push_back(p.y);
          }
        }
      }
    }
  }
  return f;
}

FoldPca fold_pca(const FoldFeatures& f) {
  const int N = f.folds;
  CUTAWAY_CHECK(N >= 1 && static_cast<int>(f.samples.size()) == N);
  const int D = static_cast<int>(f.samples[0].size());
  FoldPca pca;
  pca.mean.assign(D, 0.0);
  if (D == 0) return pca;
  Eigen::MatrixXd X(N, D);
  for (int k = 0; k < N; ++k)
    for (int d = 0; d < D; ++d) X(k, d) = f.samples[k][d];
  const Eigen::RowVectorXd mean = X.colwise().mean();
  for (int d = 0; d < D; ++d) pca.mean[d] = mean(d);
  if (N < 2) return pca;
  X.rowwise() -= mean;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(X, Eigen::ComputeThinV);
  const Eigen::VectorXd s = svd.singularValues();
  const Eigen::MatrixXd V = svd.matrixV();
  for (int p = 0; p < s.size(); ++p) {
    const double sigma = s(p) / std::sqrt(static_cast<double>(N - 1));
    if (!(sigma > 1e-12)) continue;
    std::vector<double> axis(D);
    int big = 0;
    for (int d = 0; d < D; ++d) {
      axis[d] = V(d, p);
      if (std::abs(axis[d]) > std::abs(axis[big])) big = d;
    }
    if (axis[big] < 0)
      for (double& a : axis) a = -a;
    pca.axes.push_back(std::move(axis));
    pca.sigma.push_back(sigma);
  }
  return pca;
}

std::vector<double> draw_fold(const FoldPca& pca, double amount, Rng& rng) {
  std::vector<double> v = pca.mean;
  for (size_t p = 0; p < pca.axes.size(); ++p) {
    const double c = amount * rng.normal() * pca.sigma[p];
    for (size_t d = 0; d < v.size(); ++d) v[d] += c * pca.axes[p][d];
  }
  return v;
}

std::vector<std::vector<Polyline2>> fold_curves_xz(const FoldFeatures& f,
                                                   const std::vector<std::vector<double>>& vectors,
                                                   const std::vector<double>& angles,
                                                   const FoldPcaOptions& opt) {
  const int Np = static_cast<int>(vectors.size());
  CUTAWAY_CHECK(Np >= 1 && static_cast<int>(angles.size()) == Np);
  Template frame;  // only for fold_span
  frame.fold_angles = angles;
  const double W = 2 * kPi / f.folds;
  std::vector<Pie> pies;
  for (int k = 0; k < Np; ++k) {
    const auto [lo, hi] = fold_span(frame, k);
    pies.push_back({lo, hi, W});
  }
  std::vector<std::vector<Polyline2>> out(f.surface.size());
  size_t offset = 0;
  for (size_t ci = 0; ci < f.surface.size(); ++ci) {
    const int M = f.points[ci];
    std::vector<Polyline2> canon(Np);
    for (int k = 0; k < Np; ++k) {
      CUTAWAY_CHECK(vectors[k].size() == f.samples[0].size());
      for (int i = 0; i < M; ++i)
        canon[k].push_back({vectors[k][offset + 2 * i], vectors[k][offset + 2 * i + 1]});
    }
    offset += 2 * static_cast<size_t>(M);
    if (f.open[ci]) {
      // Blend across each fold line k | k+1: both ends move to the mean radius.
      const int B = std::clamp(opt.blend_points, 1, M / 2);
      const glm::dvec2 up(std::cos(W / 2), std::sin(W / 2)),
          down(std::cos(W / 2), -std::sin(W / 2));
      std::vector<Polyline2> blended = canon;
      for (int k = 0; k < Np; ++k) {
        const int k1 = (k + 1) % Np;
        const double R = 0.5 * (glm::length(canon[k].back()) + glm::length(canon[k1].front()));
        const glm::dvec2 de = R * up - canon[k].back(), ds = R * down - canon[k1].front();
        for (int j = 0; j < B; ++j) {
          const double w = 1.0 - static_cast<double>(j) / B;
          blended[k][M - 1 - j] += de * w;
          blended[k1][j] += ds * w;
        }
        blended[k].back() = R * up;
        blended[k1].front() = R * down;
      }
      canon = std::move(blended);
    }
    for (int k = 0; k < Np; ++k) {
      Polyline2 xz;
      for (int i = 0; i < M; ++i) xz.push_back(pies[k].to_xz(canon[k][i]));
      if (f.open[ci]) {
        // Exactly on the fold lines, shared with the neighbours.
        xz.front() = xz_at(glm::length(canon[k].front()), pies[k].lo);
        xz.back() = xz_at(glm::length(canon[k].back()),
                          pies[(k + 1) % Np].lo + (k + 1 == Np ? 2 * kPi : 0.0));
      }
      out[ci].push_back(std::move(xz));
    }
  }
  return out;
}

Template rebuild_folds(const Template& t, const FoldFeatures& f,
                       const std::vector<std::vector<double>>& vectors, const FoldPcaOptions& opt,
                       const std::vector<double>& fold_angles_out) {
  const int Np = static_cast<int>(vectors.size());
  CUTAWAY_CHECK(fold_angles_out.empty() || static_cast<int>(fold_angles_out.size()) == Np);
  Template out = t;
  out.folds = Np;
  if (!fold_angles_out.empty()) {
    out.fold_angles = fold_angles_out;
  } else if (Np != t.folds) {
    out.fold_angles.clear();
    for (int k = 0; k < Np; ++k) out.fold_angles.push_back(t.fold_angles[0] + k * 2 * kPi / Np);
  }
  const auto curves = fold_curves_xz(f, vectors, out.fold_angles, opt);
  for (size_t ci = 0; ci < f.surface.size(); ++ci) {
    SurfaceSpec& surface = out.surfaces[f.surface[ci]];
    SectionSpec& sec = f.section[ci] < 0
                           ? surface.section
                           : surface.sections[static_cast<size_t>(f.section[ci])].section;
    sec.loops.clear();
    if (f.open[ci]) {
      Polyline2 loop;
      for (const auto& arc : curves[ci]) loop.insert(loop.end(), arc.begin(), arc.end() - 1);
      sec.loops.push_back(std::move(loop));
    } else {
      sec.loops = curves[ci];
    }
    if (!surface.sections.empty()) surface.section = surface.sections.front().section;
  }
  return out;
}

}  // namespace cutaway
