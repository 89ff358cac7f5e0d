#include "export/texture_image.h"
#include "base/error.h"

#include <stdexcept>

#include <stb/stb_image_write.h>

namespace cutaway {

TextureFormat parse_texture_format(std::string_view name) {
  if (name == "png") return TextureFormat::Png;
  if (name == "jpeg") return TextureFormat::Jpeg;
  if (name == "ktx2") return TextureFormat::Ktx2;
  throw InternalError("texture format must be png, jpeg or ktx2, not '" + std::string(name) + "'");
}

bool is_jpeg(const AssetTexture& texture, TextureFormat format) {
  return format == TextureFormat::Jpeg && texture.channels == 3 && !texture.linear;
}

const char* texture_mime_type(const AssetTexture& texture, TextureFormat format) {
  if (format == TextureFormat::Ktx2) return "image/ktx2";
  return is_jpeg(texture, format) ? "image/jpeg" : "image/png";
}

std::string encode_texture(const AssetTexture& texture, TextureFormat format) {
  if (texture.width <= 0 || texture.height <= 0 ||
      (texture.channels != 1 && texture.channels != 3 && texture.channels != 4) ||
      texture.pixels.size() !=
          static_cast<size_t>(texture.width) * texture.height * texture.channels)
    throw InternalError("texture '" + texture.name + "': size and pixels disagree");
  if (format == TextureFormat::Ktx2)
    throw InternalError("texture '" + texture.name + "': KTX2 is encode_ktx2's");
  std::string out;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                               static_cast<size_t>(size));
  };
  const bool ok =
      is_jpeg(texture, format)
          ? stbi_write_jpg_to_func(append, &out, texture.width, texture.height, 3,
                                   texture.pixels.data(), kJpegQuality)
          : stbi_write_png_to_func(append, &out, texture.width, texture.height, texture.channels,
                                   texture.pixels.data(), texture.width * texture.channels);
  if (!ok) throw InternalError("texture '" + texture.name + "': image encoding failed");
  return out;
}

std::vector<std::string> texture_file_names(const std::filesystem::path& scene,
                                            const SceneAssets& assets, TextureFormat format) {
  std::vector<std::string> out;
  for (const AssetTexture& t : assets.textures)
    out.push_back(scene.stem().string() + "_" + asset_name(t.name) +
                  (format == TextureFormat::Ktx2 ? ".ktx2"
                   : is_jpeg(t, format)          ? ".jpg"
                                                 : ".png"));
  return out;
}

}  // namespace cutaway
