#include "app/edit/web_libraries.h"

#include <system_error>

namespace cutaway {

namespace {

bool allowed_part(std::string_view part) {
  if (part.empty() || part.size() > 128 || part.front() == '.') return false;
  for (const char c : part) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '.' || c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

/// Whether `inner` is `outer` or below it (both canonical).
bool is_inside(const std::filesystem::path& inner, const std::filesystem::path& outer) {
  auto i = inner.begin();
  for (auto o = outer.begin(); o != outer.end(); ++o, ++i) {
    if (i == inner.end() || *i != *o) return false;
  }
  return true;
}

}  // namespace

std::vector<WebLibrary> editor_libraries() {
  return {{"yaml", CUTAWAY_YAML_JS_DIR}, {"three", CUTAWAY_THREE_JS_DIR}};
}

std::optional<std::filesystem::path> library_file(const std::filesystem::path& folder,
                                                  std::string_view relative) {
  if (relative.size() < 4 || relative.substr(relative.size() - 3) != ".js") return std::nullopt;
  std::filesystem::path path = folder;
  for (size_t start = 0;;) {
    const size_t slash = relative.find('/', start);
    const std::string_view part = relative.substr(start, slash - start);
    if (!allowed_part(part)) return std::nullopt;
    path /= part;
    if (slash == std::string_view::npos) break;
    start = slash + 1;
  }
  std::error_code ec;
  const std::filesystem::path root = std::filesystem::canonical(folder, ec);
  if (ec) return std::nullopt;
  const std::filesystem::path file = std::filesystem::canonical(path, ec);
  if (ec || !std::filesystem::is_regular_file(file, ec) || !is_inside(file, root))
    return std::nullopt;
  return file;
}

}  // namespace cutaway
