// The convex cells of a cut (doc/algorithms.md §4; doc/scene-format.md, Cuts): the distinct
// cutting planes of a CutSpec and, for every piece, the half-spaces that bound it.
#pragma once

#include <vector>

#include <glm/vec3.hpp>

#include "model/ds_model.h"
#include "pieces/cut_spec.h"

namespace cutaway {

/// One face of a convex cell: the cell lies where dot(x - p, n) <= 0 for `outward` true and
/// where it is >= 0 otherwise (p, n: the plane's point and unit normal).
struct CellFace {
  int plane = -1;       ///< index into CutCells::planes
  bool outward = true;  ///< true: the plane's normal points out of the cell
};

/// A convex cell: the intersection of its faces' half-spaces (no faces: all of space).
struct Cell {
  std::vector<CellFace> faces;
};

/// The distinct planes of a cut (no two equal up to orientation) and its cells.
struct CutCells {
  std::vector<Plane> planes;
  std::vector<Cell> cells;
};

/// Whether x (metres) lies in the closed half-space of `face`, with slack `tolerance_m`.
bool in_half_space(const CutCells& cells, const CellFace& face, const glm::dvec3& x,
                   double tolerance_m = 0);

/// Whether x lies in every half-space of `cell` except those on plane `skip_plane` (-1: none).
bool in_cell(const CutCells& cells, const Cell& cell, const glm::dvec3& x, int skip_plane = -1,
             double tolerance_m = 0);

/// The planes and cells of `cut` for an object with bounds bbox_min..bbox_max (metres, object
/// frame, axis +Y through x = z = 0):
/// - whole: one cell, no planes;
/// - halves: the plane z = 0 (through the axis), two cells;
/// - plane: cut.plane, two cells;
/// - slices: planes y = const, `thickness_m` apart, centred on the bounds so that the two end
///   pieces are equally thick (1 to 1.5 thicknesses); one cell per slab. With a `bent_axis`
///   the same planes of the straight model (over its height range) are carried onto the bent
///   one (SpineBend::cross_plane): each is perpendicular to the spine where it crosses it, the
///   slices equally thick along the spine. The bend keeps every point of the object nearer the
///   spine than its centre of curvature (bend_model), where neighbouring planes meet, so each
///   slab still holds one slice;
/// - wedges: `count` half-planes through the axis at angles 2 pi k / count from +X towards -Z
///   (the template's angle convention); each wedge is the intersection of two half-spaces
///   (count 2: one half-space each); opposite half-planes share one plane;
/// - dice: planes x, y, z = const, `size_m` apart, centred on the bounds; one cell per box
///   that overlaps the bounds.
/// With a `cut_axis` (a variant whose axis leans, organic_deformation.h) the halves' plane and
/// the wedges' half-planes are turned to contain that axis instead of +Y (their normals made
/// perpendicular to it, through its point); slices stay horizontal (the lean is a shear, which
/// keeps horizontal planes horizontal), dice and a given plane stay as they are.
/// A `knife` wobble (a variant's, knife_wobble.h) then leans the halves' plane by its lean_rad
/// about the plane's line across the axis at the bounds' mid-height and moves it by its
/// offset_m along the normal; the other cuts do not use it. With `across` (the template's
/// `halves: across`) the halves' plane instead runs across the axis (its normal along the
/// cut_axis, or +Y) at the bounds' mid-height, the knife leaning it about a line in it through
/// the axis and moving it along its normal; with a bent axis it is the bend's cross plane at
/// the middle of the axis.
/// Deterministic order; a cell the object misses simply yields no piece (cut_pieces).
/// @pre the lengths of `cut` are positive and finite; count >= 2 for wedges
CutCells make_cut_cells(const CutSpec& cut, const glm::dvec3& bbox_min, const glm::dvec3& bbox_max,
                        const BentAxis* bent_axis = nullptr, const CutAxis* cut_axis = nullptr,
                        const KnifeWobble& knife = {}, bool across = false);

}  // namespace cutaway
