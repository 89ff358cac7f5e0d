#include "io/text_rules.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include "base/error.h"

namespace cutaway {

namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_blank(char c) { return c == ' ' || c == '\t'; }

/// Whether s[begin, end) is [sign] (digits [. digits*] | . digits) [(e|E) [sign] digits].
bool is_decimal_grammar(std::string_view s) {
  size_t i = 0;
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  size_t digits = 0;
  while (i < s.size() && is_digit(s[i])) ++i, ++digits;
  if (i < s.size() && s[i] == '.') {
    ++i;
    while (i < s.size() && is_digit(s[i])) ++i, ++digits;
  }
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    size_t exp_digits = 0;
    while (i < s.size() && is_digit(s[i])) ++i, ++exp_digits;
    if (exp_digits == 0) return false;
  }
  return i == s.size();
}

}  // namespace

std::string_view trim_blanks(std::string_view s) {
  while (!s.empty() && is_blank(s.front())) s.remove_prefix(1);
  while (!s.empty() && is_blank(s.back())) s.remove_suffix(1);
  return s;
}

bool is_plain_name(std::string_view s) { return check_name(s).has_value(); }

Check check_name(std::string_view s) {
  if (s.empty()) return Check::none("a name must not be empty");
  if (s.size() > kMaxNameLength) {
    return Check::none("a name has at most " + std::to_string(kMaxNameLength) +
                       " characters, not " + std::to_string(s.size()));
  }
  for (char c : s) {
    if (!((c >= 'a' && c <= 'z') || is_digit(c) || c == '_' || c == '-')) {
      return Check::none("a name uses only a-z, 0-9, '_' and '-', not " + quoted(s));
    }
  }
  return {};
}

Outcome<double> parse_decimal(std::string_view s, const std::string& what) {
  const std::string_view core = trim_blanks(s);
  if (core.size() > kMaxNumberLength) {
    return Outcome<double>::none(what + " must be a number of at most " +
                                 std::to_string(kMaxNumberLength) + " characters, not " +
                                 quoted(s));
  }
  if (!is_decimal_grammar(core))
    return Outcome<double>::none(what + " must be a number, not " + quoted(s));
  const std::string text(core);
  errno = 0;
  const double v = std::strtod(text.c_str(), nullptr);
  // ERANGE also reports underflow (a subnormal or 0 result), which is a fine value here.
  if (!std::isfinite(v)) return Outcome<double>::none(what + " is too large: " + quoted(s));
  return v;
}

Outcome<uint64_t> parse_seed(std::string_view s) {
  const auto refuse = [s] {
    return Outcome<uint64_t>::none("must be a whole number from 0 to " + std::to_string(kMaxSeed) +
                                   ", not " + quoted(s));
  };
  if (s.empty() || s.size() > 19) return refuse();
  uint64_t value = 0;
  for (const char c : s) {
    if (c < '0' || c > '9') return refuse();
    value = value * 10 + static_cast<uint64_t>(c - '0');  // 19 digits fit in 64 bits
  }
  if (value > kMaxSeed) return refuse();
  return value;
}

}  // namespace cutaway
