#include "texture_png.h"

#include <stdexcept>

#include <stb/stb_image_write.h>

namespace cutaway {

std::string encode_png(const AssetTexture& texture) {
  if (texture.width <= 0 || texture.height <= 0 ||
      (texture.channels != 3 && texture.channels != 4) ||
      texture.pixels.size() !=
          static_cast<size_t>(texture.width) * texture.height * texture.channels)
    throw std::invalid_argument("texture '" + texture.name + "': size and pixels disagree");
  std::string out;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<size_t>(size));
  };
  if (!stbi_write_png_to_func(append, &out, texture.width, texture.height, texture.channels,
                              texture.pixels.data(), texture.width * texture.channels))
    throw std::invalid_argument("texture '" + texture.name + "': PNG encoding failed");
  return out;
}

std::vector<std::string> texture_file_names(const std::filesystem::path& scene,
                                            const SceneAssets& assets) {
  std::vector<std::string> out;
  for (const AssetTexture& t : assets.textures)
    out.push_back(scene.stem().string() + "_" + asset_name(t.name) + ".png");
  return out;
}

}  // namespace cutaway
