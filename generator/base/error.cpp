#include "base/error.h"

#include <algorithm>
#include <cstdint>

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
    : std::runtime_error(format_input_error(loc, field, rule)), loc_(std::move(loc)),
      field_(std::move(field)), rule_(std::move(rule)) {}

size_t utf8_length(std::string_view s, size_t i) {
  const auto c = static_cast<unsigned char>(s[i]);
  if (c < 0x80) return 1;
  size_t n;
  uint32_t cp;
  if ((c & 0xE0) == 0xC0) {
    n = 2;
    cp = c & 0x1F;
  } else if ((c & 0xF0) == 0xE0) {
    n = 3;
    cp = c & 0x0F;
  } else if ((c & 0xF8) == 0xF0) {
    n = 4;
    cp = c & 0x07;
  } else {
    return 0;
  }
  if (i + n > s.size()) return 0;
  for (size_t k = 1; k < n; ++k) {
    const auto d = static_cast<unsigned char>(s[i + k]);
    if ((d & 0xC0) != 0x80) return 0;
    cp = (cp << 6) | (d & 0x3F);
  }
  const uint32_t min_cp[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < min_cp[n] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return 0;
  return n;
}

namespace {

/// Whether the 3-byte UTF-8 character at s[i] is one that changes how a line shows without
/// showing itself: zero-width characters and marks U+200B..U+200F, the line and paragraph
/// separators U+2028, U+2029, the bidirectional embeddings, overrides and isolates
/// U+202A..U+202E, U+2066..U+2069, and the byte order mark U+FEFF.
bool is_invisible_format(std::string_view s, size_t i) {
  const auto b0 = static_cast<unsigned char>(s[i]), b1 = static_cast<unsigned char>(s[i + 1]),
             b2 = static_cast<unsigned char>(s[i + 2]);
  const uint32_t cp = ((b0 & 0x0F) << 12) | ((b1 & 0x3F) << 6) | (b2 & 0x3F);
  return (cp >= 0x200B && cp <= 0x200F) || (cp >= 0x2028 && cp <= 0x202E) ||
         (cp >= 0x2066 && cp <= 0x2069) || cp == 0xFEFF;
}

/// Appends `part` to `out` with '"' and '\' escaped, \n, \r and \t written so, other control
/// characters (C0, DEL and the C1 range U+0080..U+009F) and bytes that are not UTF-8 as \xHH
/// (one per byte), invisible format characters (is_invisible_format) as \uHHHH; other
/// characters as they are.
void escape_into(std::string_view part, std::string& out) {
  static const char* const hex = "0123456789abcdef";
  auto byte = [&](unsigned char c) {
    out += "\\x";
    out += hex[c >> 4];
    out += hex[c & 15];
  };
  for (size_t i = 0; i < part.size();) {
    const auto c = static_cast<unsigned char>(part[i]);
    const size_t n = utf8_length(part, i);
    if (n == 0) {
      byte(c);
      ++i;
    } else if (n == 2 && c == 0xC2 && static_cast<unsigned char>(part[i + 1]) < 0xA0) {
      byte(c);  // a C1 control character
      byte(static_cast<unsigned char>(part[i + 1]));
      i += 2;
    } else if (n == 3 && is_invisible_format(part, i)) {
      uint32_t cp = ((c & 0x0F) << 12) | ((static_cast<unsigned char>(part[i + 1]) & 0x3F) << 6) |
                    (static_cast<unsigned char>(part[i + 2]) & 0x3F);
      out += "\\u";
      for (int shift = 12; shift >= 0; shift -= 4) out += hex[(cp >> shift) & 15];
      i += 3;
    } else if (n > 1) {
      out.append(part.substr(i, n));
      i += n;
    } else {
      if (c == '"' || c == '\\') {
        out += '\\';
        out += static_cast<char>(c);
      } else if (c == '\n') {
        out += "\\n";
      } else if (c == '\r') {
        out += "\\r";
      } else if (c == '\t') {
        out += "\\t";
      } else if (c < 0x20 || c == 0x7f) {
        byte(c);
      } else {
        out += static_cast<char>(c);
      }
      ++i;
    }
  }
}

}  // namespace

std::string quoted(std::string_view text, size_t max_bytes) {
  std::string out = "\"";
  if (text.size() <= max_bytes) {
    escape_into(text, out);
  } else {
    // Cut at UTF-8 character starts so that no character is split (escape_into would write
    // the halves as bytes).
    auto start_of_char = [&](size_t i) {
      for (size_t k = 0; k < 3 && i > 0 && (static_cast<unsigned char>(text[i]) & 0xC0) == 0x80;
           ++k)
        --i;
      return i;
    };
    const size_t head = start_of_char(max_bytes / 2);
    const size_t tail = std::max(head, start_of_char(text.size() - max_bytes / 4));
    escape_into(text.substr(0, head), out);
    out += "…(" + std::to_string(text.size()) + " bytes)…";
    escape_into(text.substr(tail), out);
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
