#include "render/image/image.h"

#include <stb_image.h>
#include <stb_image_write.h>

#include <stdexcept>
#include <string>

#include "base/atomic_file.h"
#include "base/error.h"

namespace cutaway {

std::string encode_png(const Image& image) {
  if (image.width < 1 || image.height < 1 ||
      image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4)
    throw InternalError("encode_png: image of " + std::to_string(image.width) + "x" +
                        std::to_string(image.height) + " pixels has " +
                        std::to_string(image.rgba.size()) + " bytes, not w*h*4");
  std::string bytes;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, 4, image.rgba.data(),
                              image.width * 4))
    throw EnvironmentError("encode_png: cannot encode the image as PNG");
  return bytes;
}

Image decode_png(std::string_view bytes) {
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                            static_cast<int>(bytes.size()), &w, &h, &channels, 4);
  if (pixels == nullptr)
    throw EnvironmentError(std::string("not a PNG image: ") + stbi_failure_reason());
  Image image;
  image.width = w;
  image.height = h;
  image.rgba.assign(pixels, pixels + static_cast<size_t>(w) * h * 4);
  stbi_image_free(pixels);
  return image;
}

void write_png(const std::filesystem::path& path, const Image& image) {
  write_file_atomically(path, encode_png(image));
}

}  // namespace cutaway
