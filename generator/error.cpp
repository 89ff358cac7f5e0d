#include "error.h"

namespace cutaway {

namespace {
std::string format_input_error(const FileLoc& loc, const std::string& field,
                               const std::string& rule) {
  std::ostringstream s;
  s << loc.file << ':' << loc.line << ':' << loc.column << ": " << field << ": " << rule;
  return s.str();
}
}  // namespace

InputError::InputError(FileLoc loc, std::string field, std::string rule)
    : std::runtime_error(format_input_error(loc, field, rule)),
      loc_(std::move(loc)),
      field_(std::move(field)),
      rule_(std::move(rule)) {}

void check_failed(const char* file, int line, const char* condition, const std::string& detail) {
  std::ostringstream s;
  s << "internal error at " << file << ':' << line << ": check failed: " << condition;
  if (!detail.empty()) s << " (" << detail << ')';
  throw InternalError(s.str());
}

}  // namespace cutaway
