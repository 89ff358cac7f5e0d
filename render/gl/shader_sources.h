// The GLSL sources of shaders/, embedded into the binary at build time by
// cmake/embed_files.cmake, so the executable runs from anywhere.
#pragma once

#include <optional>
#include <string_view>

namespace cutaway {

/// The text of the shader file shaders/FILE_NAME as it was at build time.
/// @param file_name the bare file name, e.g. "preview.vert" (no folder)
/// @returns a view into static storage, valid for the whole program, or none when no such
///          shader was embedded
std::optional<std::string_view> shader_source(std::string_view file_name);

}  // namespace cutaway
