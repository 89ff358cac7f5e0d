// How an object is cut into pieces (spec/scene-format.md, Cuts; design/algorithms.md §4): a cut
// is a set of planes in the object's frame (axis +Y), and every piece is one convex cell of them.
#pragma once

#include <string>
#include <vector>

#include "cut_segments.h"

namespace cutaway {

/// The kinds of cut of the scene format and of `cutaway piece --cut`.
enum class CutType { Whole, Halves, Slices, Wedges, Dice, Plane };

/// One cut, in metres (object frame). Only the fields of its type are used.
struct CutSpec {
  CutType type = CutType::Whole;
  double thickness_m = 0;  ///< slices: distance between the parallel planes, > 0
  int count = 0;           ///< wedges: number of wedges, >= 2
  double size_m = 0;       ///< dice: edge of the cubes, > 0
  Plane plane;             ///< plane: the one cutting plane (both halves are pieces)
};

/// Parses the command line's `--cut` notation (design/architecture.md): `whole`, `halves`,
/// `slices:THICKNESS`, `wedges:COUNT`, `dice:SIZE` or `plane:SPEC` (SPEC as parse_plane_spec).
/// Lengths are in template units and become metres with `metres_per_unit`.
/// @throws std::invalid_argument naming the rule when `text` is not of these forms, a length is
///         not positive and finite, or a count is not a whole number in 2..64
CutSpec parse_cut_spec(const std::string& text, double metres_per_unit);

}  // namespace cutaway
