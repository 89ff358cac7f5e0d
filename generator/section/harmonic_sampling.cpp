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

}  // namespace

HarmonicSamplingCounts sample_harmonically(
    std::span<const glm::dvec3> position, std::span<const glm::uvec3> triangle,
    const std::vector<bool>& free, std::span<glm::dvec3> colour, std::span<glm::dvec2> material,
    const DiffusionBackend& diffusion, const HarmonicSamplingOptions& options) {
  const size_t n = position.size();
  if (free.size() != n || colour.size() != n || material.size() != n)
    throw InternalError("sample_harmonically: one flag, colour and material per vertex");
  if (!(options.spacing_m > 0))
    throw InternalError("sample_harmonically: the spacing must be > 0");
  HarmonicSamplingCounts counts;
  std::vector<bool> unknown = free;  // free and not diffused yet
  for (bool f : free) counts.free += f;
  if (counts.free == 0) return counts;

  const auto weight = cotangent_weights(position, triangle);
  std::vector<std::vector<std::pair<unsigned, double>>> neighbours(n);
  for (const auto& [edge, w] : weight) {
    neighbours[edge.first].emplace_back(edge.second, w);
    neighbours[edge.second].emplace_back(edge.first, w);
  }

  auto diffuse = [&](const std::vector<size_t>& which) {
    std::vector<glm::dvec3> where;
    for (size_t i : which) where.push_back(position[i]);
    diffusion.diffuse_into(where, which, colour, material);
    for (size_t i : which) unknown[i] = false;
    counts.diffused += which.size();
  };
  // Greedy Poisson-disc choice among unknown vertices passing `eligible`; the free vertices
  // diffused already are disc centres (boundary values are not: they say little about the
  // interior).
  auto poisson = [&](double radius, const std::vector<bool>& eligible) {
    DiscGrid grid(radius);
    for (size_t i = 0; i < n; ++i)
      if (free[i] && !unknown[i]) grid.add(position[i]);
    std::vector<size_t> picked;
    for (size_t i = 0; i < n; ++i) {
      if (!unknown[i] || !eligible[i] || grid.near(position[i])) continue;
      picked.push_back(i);
      grid.add(position[i]);
    }
    return picked;
  };
  // Harmonic interpolation of the unknown vertices.
  auto interpolate = [&] {
    std::vector<int> row(n, -1);
    int rows = 0;
    for (size_t i = 0; i < n; ++i)
      if (unknown[i]) row[i] = rows++;
    if (rows == 0) return;
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(rows, 5);
    for (size_t i = 0; i < n; ++i) {
      if (!unknown[i]) continue;
      double diagonal = 0;
      for (const auto& [j, w] : neighbours[i]) {
        diagonal += w;
        if (unknown[j]) {
          entries.emplace_back(row[i], row[j], -w);
        } else {
          rhs.row(row[i]) += w * Eigen::RowVectorXd{{colour[j].x, colour[j].y, colour[j].z,
                                                     material[j].x, material[j].y}};
        }
      }
      entries.emplace_back(row[i], row[i], diagonal);
    }
    Eigen::SparseMatrix<double> laplace(rows, rows);
    laplace.setFromTriplets(entries.begin(), entries.end());
    const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(laplace);
    const Eigen::MatrixXd x =
        solver.info() == Eigen::Success ? solver.solve(rhs) : Eigen::MatrixXd();
    if (solver.info() != Eigen::Success || !x.allFinite()) {  // never seen: diffuse them all
      std::vector<size_t> all;
      for (size_t i = 0; i < n; ++i)
        if (unknown[i]) all.push_back(i);
      diffuse(all);
      return;
    }
    for (size_t i = 0; i < n; ++i) {
      if (!unknown[i]) continue;
      const auto r = x.row(row[i]);
      colour[i] = glm::dvec3(r(0), r(1), r(2));
      material[i] = glm::dvec2(r(3), r(4));
    }
  };

  // 1. First samples, and one in every connected set of free vertices with no known neighbour.
  std::vector<size_t> first = poisson(options.spacing_m, free);
  {
    std::vector<bool> chosen(n, false), seen(n, false);
    for (size_t i : first) chosen[i] = true;
    for (size_t start = 0; start < n; ++start) {
      if (!free[start] || seen[start]) continue;
      std::vector<size_t> stack{start}, members;
      seen[start] = true;
      bool anchored = false;
      while (!stack.empty()) {
        const size_t i = stack.back();
        stack.pop_back();
        members.push_back(i);
        anchored = anchored || chosen[i];
        for (const auto& [j, w] : neighbours[i]) {
          if (!free[j])
            anchored = true;
          else if (!seen[j]) {
            seen[j] = true;
            stack.push_back(j);
          }
        }
      }
      if (!anchored) first.push_back(*std::min_element(members.begin(), members.end()));
    }
  }
  diffuse(first);
  interpolate();

  // 3. Test rounds.
  std::vector<bool> active = unknown;
  for (double radius = 0.5 * options.spacing_m;; radius *= 0.5) {
    const bool last = radius < options.min_spacing_m;
    std::vector<size_t> tests;
    if (last) {
      for (size_t i = 0; i < n; ++i)
        if (unknown[i] && active[i]) tests.push_back(i);
    } else {
      tests = poisson(radius, active);
    }
    if (tests.empty()) break;
    ++counts.rounds;
    std::vector<glm::dvec3> c_interp;
    std::vector<glm::dvec2> m_interp;
    for (size_t i : tests) {
      c_interp.push_back(colour[i]);
      m_interp.push_back(material[i]);
    }
    diffuse(tests);
    DiscGrid failures(1.5 * radius);
    bool any_failed = false;
    for (size_t k = 0; k < tests.size(); ++k) {
      const size_t i = tests[k];
      if (options.tolerance.accepts(colour[i], material[i], c_interp[k], m_interp[k])) continue;
      ++counts.failed;
      failures.add(position[i]);
      any_failed = true;
    }
    interpolate();
    if (last || !any_failed) break;
    for (size_t i = 0; i < n; ++i) active[i] = unknown[i] && failures.near(position[i]);
  }
  return counts;
}

}  // namespace cutaway
