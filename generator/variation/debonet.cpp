#include "variation/debonet.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "base/constants.h"
#include "base/error.h"

namespace cutaway {

namespace {

/// Cyclic [1 4 6 4 1] / 16 filter, times `gain`.
CyclicSignal blur(const CyclicSignal& s, double gain) {
  CyclicSignal out(s.length, s.channels);
  const int n = s.length;
  const double w[5] = {1 / 16.0, 4 / 16.0, 6 / 16.0, 4 / 16.0, 1 / 16.0};
  for (int i = 0; i < n; ++i) {
    for (int c = 0; c < s.channels; ++c) {
      double a = 0;
      for (int k = -2; k <= 2; ++k) a += w[k + 2] * s.at(((i + k) % n + n) % n, c);
      out.at(i, c) = gain * a;
    }
  }
  return out;
}

CyclicSignal reduce(const CyclicSignal& s) {
  const CyclicSignal b = blur(s, 1.0);
  CyclicSignal out(s.length / 2, s.channels);
  for (int i = 0; i < out.length; ++i)
    for (int c = 0; c < s.channels; ++c) out.at(i, c) = b.at(2 * i, c);
  return out;
}

CyclicSignal expand(const CyclicSignal& s, int length) {
  CyclicSignal up(length, s.channels);
  for (int i = 0; i < s.length; ++i)
    for (int c = 0; c < s.channels; ++c) up.at(2 * i, c) = s.at(i, c);
  return blur(up, 2.0);
}

/// Parent feature vectors of every position of level `l` (all coarser bands at the ancestors),
/// unnormalised; `dims` components each.
std::vector<double> parent_features(const std::vector<CyclicSignal>& bands, int l, bool derivatives,
                                    int& dims) {
  const int n = bands[l].length, C = bands[l].channels;
  const int top = static_cast<int>(bands.size()) - 1;
  dims = (top - l) * C * (derivatives ? 2 : 1);
  std::vector<double> f(static_cast<size_t>(n) * dims);
  for (int i = 0; i < n; ++i) {
    int d = 0;
    for (int j = l + 1; j <= top; ++j) {
      const CyclicSignal& b = bands[j];
      const int a = (i >> (j - l)) % b.length;
      for (int c = 0; c < C; ++c) {
        f[static_cast<size_t>(i) * dims + d++] = b.at(a, c);
        if (derivatives) {
          f[static_cast<size_t>(i) * dims + d++] = b.at((a + 1) % b.length, c) - b.at(a, c);
        }
      }
    }
  }
  return f;
}

}  // namespace

std::vector<CyclicSignal> laplacian_pyramid(const CyclicSignal& signal, int min_length) {
  CUTAWAY_CHECK(signal.length >= 1);
  std::vector<CyclicSignal> bands;
  CyclicSignal g = signal;
  while (g.length % 2 == 0 && g.length / 2 >= std::max(min_length, 1)) {
    CyclicSignal coarse = reduce(g);
    const CyclicSignal up = expand(coarse, g.length);
    for (size_t k = 0; k < g.v.size(); ++k) g.v[k] -= up.v[k];
    bands.push_back(std::move(g));
    g = std::move(coarse);
  }
  bands.push_back(std::move(g));
  return bands;
}

CyclicSignal collapse_pyramid(const std::vector<CyclicSignal>& bands) {
  CUTAWAY_CHECK(!bands.empty());
  CyclicSignal g = bands.back();
  for (int l = static_cast<int>(bands.size()) - 2; l >= 0; --l) {
    CyclicSignal up = expand(g, bands[l].length);
    for (size_t k = 0; k < up.v.size(); ++k) up.v[k] += bands[l].v[k];
    g = std::move(up);
  }
  return g;
}

std::vector<CyclicSignal> synthesize_bands(const std::vector<CyclicSignal>& in,
                                           const DeBonetOptions& opt, Rng& rng) {
  CUTAWAY_CHECK(!in.empty());
  std::vector<CyclicSignal> out = in;  // the coarsest level is kept; finer ones overwritten
  const double threshold = std::max(0.0, opt.amount * opt.threshold);
  for (int l = static_cast<int>(in.size()) - 2; l >= 0; --l) {
    int dims = 0;
    const std::vector<double> fin = parent_features(in, l, opt.derivatives, dims);
    const std::vector<double> fout = parent_features(out, l, opt.derivatives, dims);
    const int n = in[l].length, C = in[l].channels;
    // Per-component scale: the component's range over the input (1 where it is constant).
    std::vector<double> inv_scale(dims, 1.0);
    for (int d = 0; d < dims; ++d) {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (int j = 0; j < n; ++j) {
        lo = std::min(lo, fin[static_cast<size_t>(j) * dims + d]);
        hi = std::max(hi, fin[static_cast<size_t>(j) * dims + d]);
      }
      if (hi - lo > 1e-300) inv_scale[d] = 1.0 / (hi - lo);
    }
    std::vector<int> candidates;
    for (int i = 0; i < n; ++i) {
      candidates.clear();
      int nearest = -1;
      double nearest_d = std::numeric_limits<double>::infinity();
      for (int j = 0; j < n; ++j) {
        double d = 0;
        for (int k = 0; k < dims; ++k) {
          d = std::max(d, std::abs(fout[static_cast<size_t>(i) * dims + k] -
                                   fin[static_cast<size_t>(j) * dims + k]) *
                              inv_scale[k]);
        }
        if (d < nearest_d || (d == nearest_d && j == i)) {
          nearest_d = d;
          nearest = j;
        }
        if (d <= threshold) candidates.push_back(j);
      }
      int pick = nearest;
      if (threshold > 0 && !candidates.empty()) {
        pick = candidates[rng.below(static_cast<uint32_t>(candidates.size()))];
      }
      for (int c = 0; c < C; ++c) out[l].at(i, c) = in[l].at(pick, c);
    }
  }
  return out;
}

CyclicSignal debonet_synthesize(const CyclicSignal& signal, const DeBonetOptions& opt, Rng& rng) {
  return collapse_pyramid(synthesize_bands(laplacian_pyramid(signal, opt.min_length), opt, rng));
}

PolarLoop polar_resample(const Polyline2& loop_xz, bool smooth, int count) {
  Polyline2 loop = fit_curve(loop_xz, true, smooth);
  // Counter-clockwise seen from +Y: the angle atan2(-z, x) increases, i.e. positive area in
  // the (x, -z) plane.
  Polyline2 flipped;
  for (const auto& p : loop) flipped.push_back({p.x, -p.y});
  if (signed_area(flipped) < 0) std::reverse(loop.begin(), loop.end());
  const size_t n = loop.size();
  Polyline2 started;
  for (size_t i = 0; i < n && started.empty(); ++i) {
    const glm::dvec2 a = loop[i], b = loop[(i + 1) % n];
    if (-a.y < 0 && -b.y >= 0) {
      const double s = (-a.y) / ((-a.y) - (-b.y));
      const glm::dvec2 c = a + (b - a) * s;
      if (c.x <= 0) continue;
      started.push_back(c);
      for (size_t k = 1; k <= n; ++k) {
        const glm::dvec2 q = loop[(i + k) % n];
        if (glm::distance(q, c) > 1e-12) started.push_back(q);
      }
    }
  }
  CUTAWAY_CHECK(!started.empty());
  const Polyline2 pts = resample_uniform(started, true, count);
  PolarLoop out;
  for (int i = 0; i < count; ++i) {
    const glm::dvec2 p = pts[i], q = pts[(i + 1) % count];
    out.rho.push_back(glm::length(p));
    double d = std::atan2(-q.y, q.x) - std::atan2(-p.y, p.x);
    while (d <= 0) d += 2 * kPi;
    while (d > 2 * kPi) d -= 2 * kPi;
    out.dphi.push_back(d);
  }
  return out;
}

Polyline2 loop_from_polar(const PolarLoop& polar) {
  const size_t n = polar.rho.size();
  CUTAWAY_CHECK(n >= 3 && polar.dphi.size() == n);
  double mean_r = 0, mean_d = 0;
  for (size_t i = 0; i < n; ++i) {
    mean_r += polar.rho[i] / n;
    mean_d += polar.dphi[i] / n;
  }
  std::vector<double> d(n);
  double sum = 0;
  for (size_t i = 0; i < n; ++i) sum += d[i] = std::max(polar.dphi[i], 1e-3 * mean_d);
  Polyline2 out;
  double phi = 0;
  for (size_t i = 0; i < n; ++i) {
    const double r = std::max(polar.rho[i], 1e-3 * mean_r);
    out.push_back({r * std::cos(phi), -r * std::sin(phi)});
    phi += d[i] * (2 * kPi / sum);
  }
  return out;
}

std::vector<Polyline2> synthesize_loops(const std::vector<Polyline2>& loops_xz,
                                        const std::vector<bool>& smooth, int count,
                                        const DeBonetOptions& options, Rng& rng) {
  CUTAWAY_CHECK(loops_xz.size() == smooth.size());
  const int L = static_cast<int>(loops_xz.size());
  if (L == 0) return {};
  CyclicSignal s(count, 2 * L);
  for (int k = 0; k < L; ++k) {
    const PolarLoop p = polar_resample(loops_xz[k], smooth[k], count);
    for (int i = 0; i < count; ++i) {
      s.at(i, 2 * k) = p.rho[i];
      s.at(i, 2 * k + 1) = p.dphi[i];
    }
  }
  const CyclicSignal o = debonet_synthesize(s, options, rng);
  std::vector<Polyline2> out;
  for (int k = 0; k < L; ++k) {
    PolarLoop p;
    for (int i = 0; i < count; ++i) {
      p.rho.push_back(o.at(i, 2 * k));
      p.dphi.push_back(o.at(i, 2 * k + 1));
    }
    out.push_back(loop_from_polar(p));
  }
  return out;
}

}  // namespace cutaway
