// The command line's cut notation (`cutaway piece --cut`, `cutaway sheet TEMPLATE:CUT`;
// doc/command-line.md).
#pragma once

#include <string>

#include "base/outcome.h"
#include "pieces/cut_spec.h"

namespace cutaway {

/// Parses the command line's `--cut` notation (doc/architecture.md, Command line): `whole`,
/// `halves`, `slices:THICKNESS`, `wedges:COUNT`, `dice:SIZE` or `plane:SPEC` (SPEC as
/// parse_plane_spec).
/// Lengths are in template units and become metres with `metres_per_unit`.
/// @returns the cut, or none with the rule `text` breaks: not of these forms, a length not
///          positive and finite (or below kMinCutLength_m once in metres), a count not a whole
///          number in 2..64
Outcome<CutSpec> parse_cut_spec(const std::string& text, double metres_per_unit);

}  // namespace cutaway
