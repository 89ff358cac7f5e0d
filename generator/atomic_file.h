// Output files are written to a temporary file beside the target and renamed into place, so a
// failed run never leaves a partial file (design/architecture.md, Command line).
#pragma once

#include <filesystem>
#include <string_view>

namespace cutaway {

/// Writes `bytes` to `path` atomically: a temporary file "PATH.tmp-XXXXXX" in the same
/// directory, flushed, then renamed over `path`. Creates missing parent directories.
/// @throws std::runtime_error when the file cannot be written (the temporary file is removed).
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace cutaway
