// The small lexical rules shared by the template and scene formats and the command line: plain
// names and decimal numbers. Both are scanned by hand in one pass (no std::regex: its recursive
// matcher overflows the stack on inputs of a few ten thousand characters).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "base/outcome.h"

namespace cutaway {

/// The longest name a template or scene may have (it becomes part of output file names).
inline constexpr size_t kMaxNameLength = 64;
/// The longest text accepted as one decimal number (digits, sign, point and exponent).
inline constexpr size_t kMaxNumberLength = 64;

/// `s` without leading and trailing blanks (spaces and tabs).
std::string_view trim_blanks(std::string_view s);

/// Whether `s` is a plain name: 1..kMaxNameLength characters of a-z, 0-9, '_' and '-'.
bool is_plain_name(std::string_view s);

/// Passes when `s` is a plain name, else fails with the rule it breaks, in words.
Check check_name(std::string_view s);

/// Parses a decimal number: optional blanks, optional sign, digits with an optional point (or a
/// point and digits), an optional exponent, optional blanks; nothing else (no hex, inf or nan).
/// Values below the smallest double become 0 or a subnormal; they are accepted.
/// @param what  names the value in the message, e.g. "the slice thickness"
/// @returns the number, or none with "WHAT must be a number, not '...'" (malformed or longer
///          than kMaxNumberLength characters) or "WHAT is too large: '...'" (beyond the double
///          range)
Outcome<double> parse_decimal(std::string_view s, const std::string& what);

/// The largest seed the command line accepts (--seed): 2^63 - 1.
inline constexpr uint64_t kMaxSeed = 9223372036854775807ULL;

/// Parses a seed as the command line writes it: 1 to 19 decimal digits, nothing else (no sign,
/// blanks or exponent), at most kMaxSeed.
/// @returns the seed, or none with "must be a whole number from 0 to 9223372036854775807, not
///          '...'"
Outcome<uint64_t> parse_seed(std::string_view s);

}  // namespace cutaway
