#include "render/image/image.h"

#include <stb_image_write.h>

#include <stdexcept>
#include <string>

#include "base/atomic_file.h"

namespace cutaway {

void write_png(const std::filesystem::path& path, const Image& image) {
  if (image.width < 1 || image.height < 1 ||
      image.rgba.size() != static_cast<size_t>(image.width) * image.height * 4)
    throw std::invalid_argument("write_png: image of " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " pixels has " +
                                std::to_string(image.rgba.size()) + " bytes, not w*h*4");
  std::string bytes;
  const auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, image.width, image.height, 4, image.rgba.data(),
                              image.width * 4))
    throw std::runtime_error("write_png: cannot encode " + path.string() + " as PNG");
  write_file_atomically(path, bytes);
}

}  // namespace cutaway
