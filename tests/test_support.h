// Shared helpers of the tests: running the CLI, fresh temporary folders, glTF validation.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace cutaway::test {

/// What one run of the `cutaway` executable did.
struct RunResult {
  int exit_code = -1;
  std::string out;  ///< stdout
  std::string err;  ///< stderr
};

/// Runs build/cutaway with `args` (no shell interpretation of the arguments), in the source
/// directory, and captures exit code, stdout and stderr.
RunResult run_cutaway(const std::vector<std::string>& args);

/// A fresh, empty directory under the build tree, named after `name`, the running test and
/// the process (parallel test processes never share one).
std::filesystem::path fresh_dir(const std::string& name);

/// Absolute path of a file in the source tree, e.g. source_path("templates/tomato.yaml").
std::filesystem::path source_path(const std::string& relative);

/// The bytes of the file at `path` (empty when it cannot be read).
std::string read_file(const std::filesystem::path& path);

/// Every regular file below `dir` (recursively), relative paths, sorted.
std::vector<std::string> files_in(const std::filesystem::path& dir);

/// Result of the Khronos glTF validator on one file.
struct GltfReport {
  int errors = -1;           ///< -1: the validator did not run
  std::string output;        ///< its JSON line (messages included)
};

/// Runs the Khronos glTF validator (node + npm gltf-validator from node_modules/, installed by
/// `make test`) on `file`. The validator missing is a test failure, never a skip.
GltfReport validate_gltf(const std::filesystem::path& file);

/// The template files shipped in templates/ (absolute paths, sorted).
std::vector<std::filesystem::path> shipped_templates();

}  // namespace cutaway::test
