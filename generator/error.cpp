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

std::string quoted(std::string_view text, size_t max_bytes) {
  auto escape = [](std::string_view part, std::string& out) {
    static const char* const hex = "0123456789abcdef";
    for (const char ch : part) {
      const auto c = static_cast<unsigned char>(ch);
      if (c == '"' || c == '\\') {
        out += '\\';
        out += ch;
      } else if (c == '\n') {
        out += "\\n";
      } else if (c == '\t') {
        out += "\\t";
      } else if (c < 0x20 || c == 0x7f) {
        out += "\\x";
        out += hex[c >> 4];
        out += hex[c & 15];
      } else {
        out += ch;
      }
    }
  };
  std::string out = "\"";
  if (text.size() <= max_bytes) {
    escape(text, out);
  } else {
    // Cut at UTF-8 character starts so that the message stays valid UTF-8.
    auto start_of_char = [&](size_t i) {
      while (i > 0 && i < text.size() && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80) --i;
      return i;
    };
    const size_t head = start_of_char(max_bytes / 2);
    const size_t tail = start_of_char(text.size() - max_bytes / 4);
    escape(text.substr(0, head), out);
    out += "…(" + std::to_string(text.size()) + " bytes)…";
    escape(text.substr(tail), out);
  }
  out += '"';
  return out;
}

void check_failed(const char* file, int line, const char* condition, const std::string& detail) {
  std::ostringstream s;
  s << "internal error at " << file << ':' << line << ": check failed: " << condition;
  if (!detail.empty()) s << " (" << detail << ')';
  throw InternalError(s.str());
}

}  // namespace cutaway
