// The error types (doc/architecture.md, Errors and Style): InputError for bad user input (exit
// code 2, the message names file, line, column, field and rule), InternalError for broken
// internal invariants (CUTAWAY_CHECK, and arguments that break a function's documented
// preconditions; exit code 1) and EnvironmentError for failures of the environment (files,
// OpenGL, child processes; exit code 1). Expected outcomes are return values (outcome.h).
#pragma once

#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace cutaway {

/// A position in an input file. `line` and `column` are 1-based; 0 means unknown.
struct FileLoc {
  std::string file;
  int line = 0;
  int column = 0;
};

/// Bad user input. what() is "FILE:LINE:COL: FIELD: RULE", e.g.
/// "templates/tomato.yaml:14:11: surfaces[1].profile: a 'within' profile must be closed".
class InputError : public std::runtime_error {
 public:
  /// @param loc   where in the input the problem is (file, 1-based line and column)
  /// @param field the field path, e.g. "surfaces[1].profile"; "(file)" for the whole file
  /// @param rule  the rule that was broken, in words a user understands
  InputError(FileLoc loc, std::string field, std::string rule);

  const FileLoc& loc() const { return loc_; }
  const std::string& field() const { return field_; }
  const std::string& rule() const { return rule_; }

 private:
  FileLoc loc_;
  std::string field_;
  std::string rule_;
};

/// A broken internal invariant: a bug in cutaway, not in the input (exit code 1).
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

/// A failure of the environment, neither bad input nor a bug: a file that cannot be written,
/// no OpenGL context, POV-Ray or sbatch missing or failing (exit code 1). The message names the
/// file or program and the system's reason.
class EnvironmentError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Length of the valid UTF-8 character at s[i] (1..4), or 0 when s[i] does not start one
/// (a stray continuation byte, a truncated or overlong sequence, a surrogate, beyond U+10FFFF).
/// @pre i < s.size()
size_t utf8_length(std::string_view s, size_t i);

/// `text` as a message quotes a user's value: in double quotes, with backslash and double quote
/// escaped, \n, \r and \t written so, other control characters (C0, DEL, C1) and bytes that
/// are not UTF-8 as \xHH, zero-width, bidirectional-override and line-separator characters as
/// \uHHHH, so that the message is one line of visible UTF-8; the middle of a
/// text longer than `max_bytes` bytes is elided as "…(N bytes)…" (its first max_bytes/2 and
/// last max_bytes/4 bytes are kept, cut at character starts), so a 10 MB value makes a short
/// message. E.g. quoted("name ") is "\"name \"", quoted("a\x7f") is "\"a\\x7f\"".
std::string quoted(std::string_view text, size_t max_bytes = 60);
/// As above. Without these two overloads, argument-dependent lookup would pick std::quoted for
/// a std::string argument (an exact match, where the string_view one needs a conversion).
inline std::string quoted(const std::string& text, size_t max_bytes = 60) {
  return quoted(std::string_view(text), max_bytes);
}
inline std::string quoted(std::string& text, size_t max_bytes = 60) {
  return quoted(std::string_view(text), max_bytes);
}
/// As above, for a string literal or other NUL-terminated text.
inline std::string quoted(const char* text, size_t max_bytes = 60) {
  return quoted(std::string_view(text), max_bytes);
}

[[noreturn]] void check_failed(const char* file, int line, const char* condition,
                               const std::string& detail);

}  // namespace cutaway

/// CHECK-style assertion that stays on in Release builds (pbrt-v4 util/check.h).
#define CUTAWAY_CHECK(cond)                                              \
  do {                                                                   \
    if (!(cond)) ::cutaway::check_failed(__FILE__, __LINE__, #cond, ""); \
  } while (false)

/// Like CUTAWAY_CHECK, printing both values of a failed comparison.
#define CUTAWAY_CHECK_OP(a, op, b)                                                    \
  do {                                                                                \
    const auto& check_a_ = (a);                                                       \
    const auto& check_b_ = (b);                                                       \
    if (!(check_a_ op check_b_)) {                                                    \
      std::ostringstream check_s_;                                                    \
      check_s_ << #a " = " << check_a_ << ", " #b " = " << check_b_;                  \
      ::cutaway::check_failed(__FILE__, __LINE__, #a " " #op " " #b, check_s_.str()); \
    }                                                                                 \
  } while (false)
