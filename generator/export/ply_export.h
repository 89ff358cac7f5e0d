// PLY export of cross-sections (OpenMesh's PLY writer): positions in metres, uchar sRGB colours.
#pragma once

#include <string>

#include "section/cross_section.h"

namespace cutaway {

/// Encodes the cross-section as binary little-endian PLY: vertex x, y, z (float, metres, object
/// frame) and red, green, blue (uchar, sRGB-encoded), faces as vertex index lists.
std::string section_to_ply(const CrossSection& section);

}  // namespace cutaway
