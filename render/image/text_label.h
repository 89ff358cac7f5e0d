// Short text labels drawn into an Image (contact-sheet captions): the stb_easy_font bitmap
// font (Debian libstb-dev), its quads rasterised as solid pixel rectangles, no anti-aliasing.
#pragma once

#include <string>

#include <glm/vec3.hpp>

#include "render/image/image.h"

namespace cutaway {

/// Width and height in pixels that draw_label() covers for `text` at `scale` (pixels per font
/// unit, >= 1): stb_easy_font's extent (about 6 units per character, 12 per line) times scale.
/// Only printable ASCII is drawn; other bytes advance like a space.
struct LabelSize {
  int width = 0, height = 0;
};
LabelSize label_size(const std::string& text, int scale);

/// Draws `text` with its top-left corner at pixel (x, y) of `image`, every font quad filled
/// with the opaque sRGB colour `srgb` (0..1 per component), each font unit `scale` x `scale`
/// pixels. Pixels outside the image are skipped, so a label may be clipped but never writes
/// out of bounds.
/// @throws InternalError when scale < 1 or the image is malformed
void draw_label(Image& image, const std::string& text, int x, int y, int scale,
                const glm::dvec3& srgb = glm::dvec3(0.0));

}  // namespace cutaway
