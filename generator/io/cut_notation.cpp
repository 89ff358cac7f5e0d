#include "io/cut_notation.h"

#include <cmath>

#include "base/error.h"
#include "io/plane_spec.h"
#include "io/text_rules.h"

namespace cutaway {

namespace {

const char* const kForms =
    "write whole, halves, slices:THICKNESS, wedges:COUNT, dice:SIZE or plane:SPEC";

/// A positive length in units of `metres_per_unit` as metres, at least kMinCutLength_m.
Outcome<double> parse_cut_length(const std::string& s, const std::string& what,
                                 double metres_per_unit) {
  using R = Outcome<double>;
  const R v = parse_decimal(s, what);
  if (!v) return v;
  if (!(*v > 0)) return R::none(what + " must be positive, not " + quoted(s));
  const double m = *v * metres_per_unit;
  if (!std::isfinite(m)) return R::none(what + " is too large: " + quoted(s));
  if (m < kMinCutLength_m * (1 - 1e-9))  // 0.05 cm is 0.5 mm too
    return R::none(what + " must be at least 0.5 mm, not " + quoted(s));
  return m;
}

}  // namespace

Outcome<CutSpec> parse_cut_spec(const std::string& text, double metres_per_unit) {
  using R = Outcome<CutSpec>;
  CutSpec cut;
  const size_t colon = text.find(':');
  const std::string kind = text.substr(0, colon);
  const bool has_arg = colon != std::string::npos;
  const std::string arg = has_arg ? text.substr(colon + 1) : "";
  if (kind == "whole" || kind == "halves") {
    if (has_arg) return R::none(quoted(text) + ": '" + kind + "' takes no value");
    cut.type = kind == "whole" ? CutType::Whole : CutType::Halves;
    return cut;
  }
  if (kind == "slices" || kind == "wedges" || kind == "dice" || kind == "plane") {
    if (!has_arg || arg.empty()) {
      const char* value = kind == "slices"   ? "THICKNESS"
                          : kind == "wedges" ? "COUNT"
                          : kind == "dice"   ? "SIZE"
                                             : "SPEC";
      return R::none(quoted(text) + ": write " + kind + ":" + value);
    }
  }
  if (kind == "slices") {
    cut.type = CutType::Slices;
    const Outcome<double> thickness = parse_cut_length(arg, "the slice thickness", metres_per_unit);
    if (!thickness) return R::none(thickness.reason());
    cut.thickness_m = *thickness;
    return cut;
  }
  if (kind == "dice") {
    cut.type = CutType::Dice;
    const Outcome<double> size = parse_cut_length(arg, "the dice size", metres_per_unit);
    if (!size) return R::none(size.reason());
    cut.size_m = *size;
    return cut;
  }
  if (kind == "wedges") {
    const Outcome<double> n = parse_decimal(arg, "the wedge count");
    if (!n) return R::none(n.reason());
    if (*n != std::floor(*n) || *n < 2 || *n > 64)
      return R::none("the wedge count must be a whole number from 2 to 64, not " + quoted(arg));
    cut.type = CutType::Wedges;
    cut.count = static_cast<int>(*n);
    return cut;
  }
  if (kind == "plane") {
    cut.type = CutType::Plane;
    const Outcome<Plane> plane = parse_plane_spec(arg, metres_per_unit);
    if (!plane) return R::none(plane.reason());
    cut.plane = *plane;
    return cut;
  }
  return R::none(quoted(text) + " is not a cut: " + kForms);
}

}  // namespace cutaway
