#include "section/harmonic_sampling.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <tuple>

#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "base/colour.h"
#include "base/error.h"

namespace cutaway {

namespace {

/// Points in a uniform grid of cells `radius` wide, for "is any within radius" queries.
class DiscGrid {
 public:
  explicit DiscGrid(double radius) : radius_(radius) {}
  void add(const glm::dvec3& p) { cells_[cell(p)].push_back(p); }
  bool near(const glm::dvec3& p) const {
    const auto [x, y, z] = cell(p);
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto found = cells_.find({x + dx, y + dy, z + dz});
          if (found == cells_.end()) continue;
          for (const glm::dvec3& q : found->second)
            if (glm::distance(p, q) < radius_) return true;
        }
    return false;
  }

 private:
  std::tuple<long, long, long> cell(const glm::dvec3& p) const {
    return {static_cast<long>(std::floor(p.x / radius_)),
            static_cast<long>(std::floor(p.y / radius_)),
            static_cast<long>(std::floor(p.z / radius_))};
  }
  double radius_;
  std::map<std::tuple<long, long, long>, std::vector<glm::dvec3>> cells_;
};

/// Cotangent weight of every mesh edge (both triangles' halves summed), clamped to >= 0.05.
std::map<std::pair<unsigned, unsigned>, double> cotangent_weights(
    std::span<const glm::dvec3> position, std::span<const glm::uvec3> triangle) {
  std::map<std::pair<unsigned, unsigned>, double> weight;
  for (const glm::uvec3& t : triangle) {
    for (int k = 0; k < 3; ++k) {
      const unsigned a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      const glm::dvec3 u = position[a] - position[c], v = position[b] - position[c];
      const double sine = glm::length(glm::cross(u, v));
      const double cot = sine > 0 ? glm::dot(u, v) / sine : 0;
      weight[std::minmax(a, b)] += 0.5 * cot;
    }
  }
  for (auto& [edge, w] : weight) w = std::max(w, 0.05);
  return weight;
}

/// The steps of sample_harmonically over the state they share: the mesh's edges with their
/// cotangent weights, which vertices are still unknown (free and not diffused yet) and the
/// counts. first_samples(), then refine(); each diffusion is one batch.
class HarmonicSampler {
 public:
  HarmonicSampler(std::span<const glm::dvec3> position, std::span<const glm::uvec3> triangle,
                  const std::vector<bool>& free, std::span<glm::dvec3> colour,
                  std::span<glm::dvec2> material, const DiffusionBackend& diffusion,
                  HarmonicSamplingCounts& counts)
      : n_(position.size()), position_(position), free_(free), colour_(colour), material_(material),
        diffusion_(diffusion), counts_(counts), unknown_(free), neighbours_(n_) {
    for (const auto& [edge, w] : cotangent_weights(position, triangle)) {
      neighbours_[edge.first].emplace_back(edge.second, w);
      neighbours_[edge.second].emplace_back(edge.first, w);
    }
  }

  /// Steps 1 and 2: the first samples (a Poisson-disc set of radius `spacing`, and one in every
  /// connected set of free vertices with no known neighbour) diffused, the rest interpolated.
  void first_samples(double spacing);
  /// Step 3: the test rounds, the radius halved each round from half `options.spacing_m`, each
  /// followed by step 2.
  void refine(const HarmonicSamplingOptions& options);

 private:
  /// Diffuses the vertices `which` (one batch); they are known afterwards.
  void diffuse(const std::vector<size_t>& which);
  /// Greedy Poisson-disc choice among unknown vertices passing `eligible`; the free vertices
  /// diffused already are disc centres (boundary values are not: they say little about the
  /// interior).
  std::vector<size_t> poisson(double radius, const std::vector<bool>& eligible) const;
  /// The first vertex of each connected set of free vertices with no known neighbour and none
  /// of `chosen`.
  std::vector<size_t> unanchored(const std::vector<bool>& chosen) const;
  /// Harmonic interpolation of the unknown vertices.
  void interpolate();

  const size_t n_;
  std::span<const glm::dvec3> position_;
  const std::vector<bool>& free_;
  std::span<glm::dvec3> colour_;
  std::span<glm::dvec2> material_;
  const DiffusionBackend& diffusion_;
  HarmonicSamplingCounts& counts_;
  std::vector<bool> unknown_;                                         // free and not diffused yet
  std::vector<std::vector<std::pair<unsigned, double>>> neighbours_;  // (vertex, weight)
};

void HarmonicSampler::diffuse(const std::vector<size_t>& which) {
  std::vector<glm::dvec3> where;
  for (size_t i : which) where.push_back(position_[i]);
  diffusion_.diffuse_into(where, which, colour_, material_);
  for (size_t i : which) unknown_[i] = false;
  counts_.diffused += which.size();
}

std::vector<size_t> HarmonicSampler::poisson(double radius,
                                             const std::vector<bool>& eligible) const {
  DiscGrid grid(radius);
  for (size_t i = 0; i < n_; ++i)
    if (free_[i] && !unknown_[i]) grid.add(position_[i]);
  std::vector<size_t> picked;
  for (size_t i = 0; i < n_; ++i) {
    if (!unknown_[i] || !eligible[i] || grid.near(position_[i])) continue;
    picked.push_back(i);
    grid.add(position_[i]);
  }
  return picked;
}

std::vector<size_t> HarmonicSampler::unanchored(const std::vector<bool>& chosen) const {
  std::vector<size_t> firsts;
  std::vector<bool> seen(n_, false);
  for (size_t start = 0; start < n_; ++start) {
    if (!free_[start] || seen[start]) continue;
    std::vector<size_t> stack{start}, members;
    seen[start] = true;
    bool anchored = false;
    while (!stack.empty()) {
      const size_t i = stack.back();
      stack.pop_back();
      members.push_back(i);
      anchored = anchored || chosen[i];
      for (const auto& [j, w] : neighbours_[i]) {
        if (!free_[j]) anchored = true;
        else if (!seen[j]) {
          seen[j] = true;
          stack.push_back(j);
        }
      }
    }
    if (!anchored) firsts.push_back(*std::min_element(members.begin(), members.end()));
  }
  return firsts;
}

void HarmonicSampler::interpolate() {
  std::vector<int> row(n_, -1);
  int rows = 0;
  for (size_t i = 0; i < n_; ++i)
    if (unknown_[i]) row[i] = rows++;
  if (rows == 0) return;
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(rows, 5);
  for (size_t i = 0; i < n_; ++i) {
    if (!unknown_[i]) continue;
    double diagonal = 0;
    for (const auto& [j, w] : neighbours_[i]) {
      diagonal += w;
      if (unknown_[j]) {
        entries.emplace_back(row[i], row[j], -w);
      } else {
        rhs.row(row[i]) += w * Eigen::RowVectorXd{{colour_[j].x, colour_[j].y, colour_[j].z,
                                                   material_[j].x, material_[j].y}};
      }
    }
    entries.emplace_back(row[i], row[i], diagonal);
  }
  Eigen::SparseMatrix<double> laplace(rows, rows);
  laplace.setFromTriplets(entries.begin(), entries.end());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(laplace);
  const Eigen::MatrixXd x = solver.info() == Eigen::Success ? solver.solve(rhs) : Eigen::MatrixXd();
  if (solver.info() != Eigen::Success || !x.allFinite()) {  // never seen: diffuse them all
    std::vector<size_t> all;
    for (size_t i = 0; i < n_; ++i)
      if (unknown_[i]) all.push_back(i);
    diffuse(all);
    return;
  }
  for (size_t i = 0; i < n_; ++i) {
    if (!unknown_[i]) continue;
    const auto r = x.row(row[i]);
    colour_[i] = glm::dvec3(r(0), r(1), r(2));
    material_[i] = glm::dvec2(r(3), r(4));
  }
}

void HarmonicSampler::first_samples(double spacing) {
  std::vector<size_t> first = poisson(spacing, free_);
  std::vector<bool> chosen(n_, false);
  for (size_t i : first) chosen[i] = true;
  for (size_t i : unanchored(chosen)) first.push_back(i);
  diffuse(first);
  interpolate();
}

void HarmonicSampler::refine(const HarmonicSamplingOptions& options) {
  std::vector<bool> active = unknown_;
  for (double radius = 0.5 * options.spacing_m;; radius *= 0.5) {
    const bool last = radius < options.min_spacing_m;
    std::vector<size_t> tests;
    if (last) {
      for (size_t i = 0; i < n_; ++i)
        if (unknown_[i] && active[i]) tests.push_back(i);
    } else {
      tests = poisson(radius, active);
    }
    if (tests.empty()) break;
    ++counts_.rounds;
    std::vector<glm::dvec3> c_interp;
    std::vector<glm::dvec2> m_interp;
    for (size_t i : tests) {
      c_interp.push_back(colour_[i]);
      m_interp.push_back(material_[i]);
    }
    diffuse(tests);
    DiscGrid failures(1.5 * radius);
    bool any_failed = false;
    for (size_t k = 0; k < tests.size(); ++k) {
      const size_t i = tests[k];
      if (options.tolerance.accepts(colour_[i], material_[i], c_interp[k], m_interp[k])) continue;
      ++counts_.failed;
      failures.add(position_[i]);
      any_failed = true;
    }
    interpolate();
    if (last || !any_failed) break;
    for (size_t i = 0; i < n_; ++i) active[i] = unknown_[i] && failures.near(position_[i]);
  }
}

}  // namespace

HarmonicSamplingCounts sample_harmonically(
    std::span<const glm::dvec3> position, std::span<const glm::uvec3> triangle,
    const std::vector<bool>& free, std::span<glm::dvec3> colour, std::span<glm::dvec2> material,
    const DiffusionBackend& diffusion, const HarmonicSamplingOptions& options) {
  const size_t n = position.size();
  if (free.size() != n || colour.size() != n || material.size() != n)
    throw InternalError("sample_harmonically: one flag, colour and material per vertex");
  if (!(options.spacing_m > 0)) throw InternalError("sample_harmonically: the spacing must be > 0");
  HarmonicSamplingCounts counts;
  for (bool f : free) counts.free += f;
  if (counts.free == 0) return counts;

  HarmonicSampler sampler(position, triangle, free, colour, material, diffusion, counts);
  // 1. First samples, and one in every connected set of free vertices with no known neighbour;
  // 2. the rest interpolated.
  sampler.first_samples(options.spacing_m);
  // 3. Test rounds.
  sampler.refine(options);
  return counts;
}

}  // namespace cutaway
