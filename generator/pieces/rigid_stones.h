// Rigid surfaces under a cut (doc/algorithms.md §4, Stones stay whole): a stone, pit or shell
// that a knife does not cross. The whole stone goes to one piece, the one whose cell holds
// most of it; every piece the stone reaches has its imprint as a cavity. For the cut, a rigid
// surface is therefore hollow inside (caps end at it, walls show the flesh's colour against
// it), what it encloses is never cut, and the piece that holds it gets the stone's surface
// outside its own cell.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include <glm/vec3.hpp>

#include "model/ds_model.h"
#include "pieces/cut_cells.h"
#include "pieces/shaded_mesh.h"

namespace cutaway {

/// One rigid surface of a model as a cut sees it.
struct RigidStone {
  int surface = -1;  ///< index into DsModel::surfaces
  /// Its front is its outside (the mesh encloses a positive volume): the colour it shows to a
  /// piece that holds it is its back's.
  bool front_outside = true;
  /// The points of a regular grid (kStoneGridSteps along its longest side) that lie inside it:
  /// each stands for an equal share of its volume. Metres, object frame.
  std::vector<glm::dvec3> samples;
  double volume_m3 = 0;  ///< the volume it encloses (its mesh's signed volume, made positive)
};

/// Grid steps along a stone's longest bounding-box side for RigidStone::samples (a 40 mm stone
/// gets a 1 mm grid, about 10^4 points inside).
inline constexpr int kStoneGridSteps = 40;

/// A model prepared for a cut that keeps its rigid surfaces whole.
struct StonePlan {
  /// The model as its cut's sections see it: every rigid surface hollow on its inside, and
  /// every surface inside a rigid one (its stone's own layers, grains) left empty (no
  /// triangles; the indices of the surfaces are those of the model).
  DsModel hollowed;
  std::vector<RigidStone> stones;  ///< in surface order
};

/// The plan for `model`'s rigid surfaces (DsSurface::rigid), or none when it has none. A
/// surface counts as inside a rigid one when its first vertex lies inside it (check_model
/// refuses surfaces that cross a rigid one; a grain is small; inside_test.h). Deterministic.
/// @pre every rigid surface is closed (check_model)
std::optional<StonePlan> plan_stones(const DsModel& model);

/// The cell of `cells` that holds `stone`: the one with most of its samples (a sample on a
/// face counts for the first cell that has it), ties broken by `seed`; -1 when no cell holds a
/// sample (the cut misses the stone entirely: it stays in whatever piece has it, uncut).
int holder_cell(const RigidStone& stone, const CutCells& cells, uint64_t seed);

/// The part of `mesh` outside the convex `cell`, as one mesh per face of the cell: part k lies
/// beyond face k and inside faces 0..k-1 (the mesh is split face by face, so neighbouring
/// parts share their crossing vertices exactly: clip_to_half_space computes each crossing once
/// per edge). Empty parts are left out.
std::vector<ShadedMesh> outside_cell(const ShadedMesh& mesh, const CutCells& cells,
                                     const Cell& cell);

}  // namespace cutaway
