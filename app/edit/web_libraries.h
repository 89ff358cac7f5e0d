// The browser libraries the editor's page imports, served by `cutaway edit` from the folders
// their Debian packages install (no network access at run time): eemeli/yaml's browser build
// (node-yaml), which edits the template's YAML keeping its comments and layout, and three.js
// (libjs-three), which shows the DS model in 3D.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace cutaway {

/// One library: the files of `folder` are served at /lib/NAME/RELATIVE_PATH.
struct WebLibrary {
  std::string name;              ///< a-z only, e.g. "yaml"
  std::filesystem::path folder;  ///< absolute
};

/// yaml (/usr/share/nodejs/yaml/browser/dist) and three (/usr/share/javascript/three), or the
/// folders given to CMake as CUTAWAY_YAML_JS_DIR and CUTAWAY_THREE_JS_DIR.
std::vector<WebLibrary> editor_libraries();

/// The file that the URL path `relative` (what follows /lib/NAME/) names in `folder`, or
/// nullopt when it may not be served: only `.js` files; every part of the path 1..128
/// characters of A-Z, a-z, 0-9, '.', '_', '-', not starting with '.' (so no "..", no hidden
/// files, no empty parts); and the file, symbolic links followed, must be a regular file
/// inside `folder` (also followed). A request never reaches a file outside the library.
std::optional<std::filesystem::path> library_file(const std::filesystem::path& folder,
                                                  std::string_view relative);

}  // namespace cutaway
