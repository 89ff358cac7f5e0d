// Images as the renderers produce them (previews, contact sheets, POV-Ray renders read back) and
// their one PNG writer.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace cutaway {

/// An 8-bit RGBA image: `rgba` holds width * height * 4 bytes, rows top first, pixels left to
/// right, R G B A each; colour is sRGB-encoded, alpha is linear (255 = opaque).
struct Image {
  int width = 0, height = 0;  ///< pixels
  std::vector<uint8_t> rgba;  ///< width * height * 4 bytes, sRGB8 + alpha, row 0 = top
};

/// `image` encoded as PNG (8-bit RGBA, stb_image_write).
/// @param image width, height > 0 and rgba.size() == width * height * 4
/// @throws InternalError when the image's size does not match its bytes
/// @throws EnvironmentError when encoding fails
std::string encode_png(const Image& image);

/// The image a PNG holds (any bit depth and colour type, converted to 8-bit RGBA; stb_image).
/// @throws EnvironmentError "not a PNG image: REASON" when `bytes` cannot be decoded
Image decode_png(std::string_view bytes);

/// Encodes `image` as PNG (encode_png) and writes it atomically
/// (write_file_atomically(): a failed write leaves no partial file).
/// @param image width, height > 0 and rgba.size() == width * height * 4
/// @throws InternalError when the image's size does not match its bytes
/// @throws EnvironmentError when encoding or writing fails
void write_png(const std::filesystem::path& path, const Image& image);

}  // namespace cutaway
