// How a `halves` cut runs: the template's `halves` field (doc/template-format.md).
#pragma once

namespace cutaway {

/// How a `halves` cut runs (cut_cells.h, pieces.h): `Along` the axis (the default), `Across` it
/// at mid-height (citrus, persimmon: the cut that shows their segments or star), or along it
/// `Beside` the rigid stone, moved clear of it (a mango's cheeks: a knife cannot go through its
/// stone, and the cheek's cut face is whole flesh).
enum class HalvesCut { Along, Across, Beside };

}  // namespace cutaway
