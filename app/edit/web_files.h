// The editor's page (app/edit/web/), embedded into the binary at build time by
// cmake/embed_files.cmake, so `cutaway edit` serves it from anywhere without network access.
#pragma once

#include <optional>
#include <string_view>

namespace cutaway {

/// The bytes of app/edit/web/FILE_NAME as it was at build time.
/// @param file_name the bare file name, e.g. "editor.js" (no folder)
/// @returns a view into static storage, valid for the whole program, or none when no such
///          file was embedded
std::optional<std::string_view> editor_web_file(std::string_view file_name);

}  // namespace cutaway
