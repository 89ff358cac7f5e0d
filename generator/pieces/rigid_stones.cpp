#include "pieces/rigid_stones.h"

#include <algorithm>
#include <cmath>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "base/random.h"
#include "model/inside_test.h"
#include "pieces/clip_mesh.h"

namespace cutaway {

namespace {

/// Purpose of the seed that breaks ties between cells holding equal shares of a stone.
constexpr uint64_t kPurposeStoneTie = 0x73746f6e65ull;  // "stone"

}  // namespace

std::optional<StonePlan> plan_stones(const DsModel& model) {
  std::vector<int> rigid;
  for (size_t s = 1; s < model.surfaces.size(); ++s)
    if (model.surfaces[s].rigid) rigid.push_back(static_cast<int>(s));
  if (rigid.empty()) return std::nullopt;
  StonePlan plan;
  plan.hollowed = model;
  std::vector<bool> inside_stone(model.surfaces.size(), false);
  for (int s : rigid) {
    const DsSurface& surface = model.surfaces[static_cast<size_t>(s)];
    const InsideTest test(surface.mesh);
    RigidStone stone;
    stone.surface = s;
    const double volume = signed_volume(surface.mesh);
    stone.front_outside = volume >= 0;
    stone.volume_m3 = std::fabs(volume);
    // Everything inside the stone stays with it, uncut.
    for (size_t j : surfaces_inside(model, static_cast<size_t>(s), test)) inside_stone[j] = true;
    // Its volume as grid points, at the centres of the grid's cells.
    const auto [lo, hi] = mesh_bounds(surface.mesh);
    const double step = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z}) / kStoneGridSteps;
    if (step > 0) {
      const glm::ivec3 n = glm::max(glm::ivec3(glm::ceil((hi - lo) / step)), glm::ivec3(1));
      for (int i = 0; i < n.x; ++i)
        for (int j = 0; j < n.y; ++j)
          for (int k = 0; k < n.z; ++k) {
            const glm::dvec3 p = lo + step * (glm::dvec3(i, j, k) + 0.5);
            if (test.inside(p)) stone.samples.push_back(p);
          }
    }
    // Hollow inside for the cut's sections and walls.
    DsSurface& hollow = plan.hollowed.surfaces[static_cast<size_t>(s)];
    (stone.front_outside ? hollow.visible_back : hollow.visible_front) = false;
    plan.stones.push_back(std::move(stone));
  }
  for (size_t j = 0; j < inside_stone.size(); ++j)
    if (inside_stone[j]) plan.hollowed.surfaces[j].mesh = DsMesh();
  // A stone inside another stone goes with the outer one.
  std::erase_if(plan.stones,
                [&](const RigidStone& s) { return inside_stone[static_cast<size_t>(s.surface)]; });
  return plan;
}

int holder_cell(const RigidStone& stone, const CutCells& cells, uint64_t seed) {
  std::vector<size_t> count(cells.cells.size(), 0);
  for (const glm::dvec3& p : stone.samples) {
    for (size_t c = 0; c < cells.cells.size(); ++c) {
      if (in_cell(cells, cells.cells[c], p)) {
        ++count[c];
        break;
      }
    }
  }
  const size_t most = count.empty() ? 0 : *std::max_element(count.begin(), count.end());
  if (most == 0) return -1;
  std::vector<int> tied;
  for (size_t c = 0; c < count.size(); ++c)
    if (count[c] == most) tied.push_back(static_cast<int>(c));
  if (tied.size() == 1) return tied[0];
  Rng rng(derive_seed(seed, {kPurposeStoneTie, static_cast<uint64_t>(stone.surface)}));
  return tied[rng.below(static_cast<uint32_t>(tied.size()))];
}

std::vector<ShadedMesh> outside_cell(const ShadedMesh& mesh, const CutCells& cells,
                                     const Cell& cell) {
  std::vector<ShadedMesh> parts;
  ShadedMesh rest = mesh;
  for (const CellFace& f : cell.faces) {
    if (rest.triangle.empty()) break;
    const Plane& plane = cells.planes[static_cast<size_t>(f.plane)];
    // Inside the face's half-space: dot <= 0 for an outward normal.
    ShadedMesh beyond = clip_to_half_space(rest, plane, f.outward);
    rest = clip_to_half_space(rest, plane, !f.outward);
    if (!beyond.triangle.empty()) parts.push_back(std::move(beyond));
  }
  return parts;
}

}  // namespace cutaway
