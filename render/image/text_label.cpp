#include "render/image/text_label.h"
#include "base/error.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb/stb_easy_font.h>
#pragma GCC diagnostic pop

namespace cutaway {

namespace {

/// The text with every byte outside printable ASCII (and '\n') replaced by a space.
std::string printable(const std::string& text) {
  std::string s = text;
  for (char& c : s)
    if (c != '\n' && (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126))
      c = ' ';
  return s;
}

}  // namespace

LabelSize label_size(const std::string& text, int scale) {
  if (scale < 1) throw InternalError("label_size: scale must be >= 1");
  std::string s = printable(text);
  if (s.empty()) return {};
  return {stb_easy_font_width(s.data()) * scale, stb_easy_font_height(s.data()) * scale};
}

void draw_label(Image& image, const std::string& text, int x, int y, int scale,
                const glm::dvec3& srgb) {
  if (scale < 1) throw InternalError("draw_label: scale must be >= 1");
  if (image.width < 0 || image.height < 0 ||
      image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4)
    throw InternalError("draw_label: malformed image");
  std::string s = printable(text);
  if (s.empty()) return;
  // stb_easy_font: 4 vertices of 16 bytes per quad; about 270 bytes per character suffice.
  std::vector<char> buffer(s.size() * 300 + 1024);
  unsigned char colour[4] = {0, 0, 0, 255};
  const int quads =
      stb_easy_font_print(0, 0, s.data(), colour, buffer.data(), static_cast<int>(buffer.size()));
  uint8_t rgb[3];
  for (int c = 0; c < 3; ++c)
    rgb[c] = static_cast<uint8_t>(std::lround(255 * std::clamp(srgb[c], 0.0, 1.0)));
  for (int q = 0; q < quads; ++q) {
    const float* v = reinterpret_cast<const float*>(buffer.data() + q * 64);
    // The four corners of an axis-aligned rectangle (x, y, z, colour) * 4; font units.
    float x0 = v[0], y0 = v[1], x1 = v[0], y1 = v[1];
    for (int k = 1; k < 4; ++k) {
      const float* p = reinterpret_cast<const float*>(buffer.data() + q * 64 + k * 16);
      x0 = std::min(x0, p[0]), y0 = std::min(y0, p[1]);
      x1 = std::max(x1, p[0]), y1 = std::max(y1, p[1]);
    }
    const int px0 = std::max(0, x + static_cast<int>(std::lround(x0 * scale)));
    const int py0 = std::max(0, y + static_cast<int>(std::lround(y0 * scale)));
    const int px1 = std::min(image.width, x + static_cast<int>(std::lround(x1 * scale)));
    const int py1 = std::min(image.height, y + static_cast<int>(std::lround(y1 * scale)));
    for (int py = py0; py < py1; ++py)
      for (int px = px0; px < px1; ++px) {
        uint8_t* pixel = &image.rgba[(static_cast<size_t>(py) * image.width + px) * 4];
        pixel[0] = rgb[0], pixel[1] = rgb[1], pixel[2] = rgb[2], pixel[3] = 255;
      }
  }
}

}  // namespace cutaway
