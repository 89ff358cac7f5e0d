// Mathematical constants shared by every stage of the pipeline (one definition each).
#pragma once

#include <numbers>

namespace cutaway {

/// pi as a double (radians per half turn).
inline constexpr double kPi = std::numbers::pi;

}  // namespace cutaway
