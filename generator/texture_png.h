// Textures as PNG files: the one encoder of AssetTexture images, for glTF (embedded) and
// POV-Ray (files beside the scene).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "scene_assets.h"

namespace cutaway {

/// `texture` as PNG bytes (stb_image_write, 8-bit RGB or RGBA; deterministic: the same texture gives
/// the same bytes).
/// @throws std::invalid_argument when its size and pixel count disagree or it is empty
std::string encode_png(const AssetTexture& texture);

/// The file names, beside a scene file at `scene` (.pov, .gltf), of the assets' textures:
/// "<scene stem>_<texture name>.png", in the order of SceneAssets::textures.
std::vector<std::string> texture_file_names(const std::filesystem::path& scene,
                                            const SceneAssets& assets);

}  // namespace cutaway
