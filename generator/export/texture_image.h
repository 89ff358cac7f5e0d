// Textures as image files: the one encoder of AssetTexture images, for glTF (embedded, or files
// beside a .gltf) and POV-Ray (files beside the scene). Base colours may be JPEG (a tenth of
// the PNG's bytes on a baked cap atlas, at a mean error under 2/255); material, normal and
// height maps hold linear data (AssetTexture::linear), so they are always PNG.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "assets/scene_assets.h"

namespace cutaway {

/// How base-colour textures (RGB, sRGB) are stored; linear maps are always PNG.
enum class TextureFormat {
  Png,   ///< lossless, 8-bit RGB
  Jpeg,  ///< baseline JPEG at kJpegQuality, chroma subsampled 2 x 2 (glTF core, POV-Ray,
         ///< Blender and every browser read it)
  /// GPU textures for glTF (KHR_texture_basisu): every texture, base colour and linear maps,
  /// as KTX2 (ktx2_texture.h); image files for POV-Ray, which reads no KTX2, as Jpeg.
  Ktx2,
};

/// The format image files take where KTX2 cannot go (POV-Ray): Jpeg for Ktx2, else `format`.
inline TextureFormat image_file_format(TextureFormat format) {
  return format == TextureFormat::Ktx2 ? TextureFormat::Jpeg : format;
}

/// The JPEG quality (1..100) of base-colour textures.
inline constexpr int kJpegQuality = 90;

/// "png", "jpeg" or "ktx2" as a TextureFormat.
/// @throws InternalError for any other name
TextureFormat parse_texture_format(std::string_view name);

/// Whether `texture` is written as JPEG under `format`: an sRGB RGB texture with format Jpeg.
bool is_jpeg(const AssetTexture& texture, TextureFormat format);

/// The MIME type of `texture`'s image under `format`: "image/ktx2", "image/jpeg" or
/// "image/png".
const char* texture_mime_type(const AssetTexture& texture, TextureFormat format);

/// `texture` as image bytes: JPEG (is_jpeg) or PNG (8-bit grey, RGB or RGBA), by
/// stb_image_write.
/// Deterministic: the same texture and format give the same bytes.
/// @throws InternalError when its size and pixel count disagree or it is empty, and for Ktx2
///         (encode_ktx2 encodes those, knowing what the texture holds)
std::string encode_texture(const AssetTexture& texture, TextureFormat format);

/// The file names, beside a scene file at `scene` (.pov, .gltf), of the assets' textures:
/// "<scene stem>_<texture name>.ktx2", ".jpg" or ".png" (is_jpeg), in the order of
/// SceneAssets::textures.
std::vector<std::string> texture_file_names(const std::filesystem::path& scene,
                                            const SceneAssets& assets, TextureFormat format);

}  // namespace cutaway
