// The result of a step for which "nothing to make" is an expected outcome, not an error: a
// value, or the reason there is none in words ("the plane misses the object"); and of a check
// that passes or says which rule is broken (Check). Errors are exceptions (error.h): InputError
// for bad input, InternalError (CUTAWAY_CHECK) for broken invariants, EnvironmentError for a
// failing environment.
#pragma once

#include <optional>
#include <string>
#include <utility>

#include "base/error.h"

namespace cutaway {

/// A T, or the reason there is none. Like std::expected<T, std::string> (C++23), with only what
/// the pipeline uses: test it, read the value, or read the reason.
template <class T>
class Outcome {
 public:
  /// An outcome with a value.
  Outcome(T value) : value_(std::move(value)) {}  // NOLINT: implicit, as `return value;` reads

  /// An outcome without a value, for `reason`, a phrase a user understands (no final period).
  static Outcome none(std::string reason) {
    Outcome out;
    out.reason_ = std::move(reason);
    return out;
  }

  bool has_value() const { return value_.has_value(); }
  explicit operator bool() const { return has_value(); }

  /// The value. @pre has_value()
  T& operator*() & {
    CUTAWAY_CHECK(value_.has_value());
    return *value_;
  }
  const T& operator*() const& {
    CUTAWAY_CHECK(value_.has_value());
    return *value_;
  }
  T&& operator*() && {
    CUTAWAY_CHECK(value_.has_value());
    return std::move(*value_);
  }
  T* operator->() { return &**this; }
  const T* operator->() const { return &**this; }

  /// Why there is no value. @pre !has_value()
  const std::string& reason() const {
    CUTAWAY_CHECK(!value_.has_value());
    return reason_;
  }

 private:
  Outcome() = default;
  std::optional<T> value_;
  std::string reason_;
};

/// The outcome of a check: it passes, or the reason it does not (the rule broken, in words).
/// Checks return it instead of an empty string for "fine".
template <>
class Outcome<void> {
 public:
  /// A check that passes.
  Outcome() = default;

  /// A check that does not pass, for `reason`, a phrase a user understands (no final period).
  static Outcome none(std::string reason) {
    Outcome out;
    out.passed_ = false;
    out.reason_ = std::move(reason);
    return out;
  }

  bool has_value() const { return passed_; }
  explicit operator bool() const { return passed_; }

  /// Why the check does not pass. @pre !has_value()
  const std::string& reason() const {
    CUTAWAY_CHECK(!passed_);
    return reason_;
  }

 private:
  bool passed_ = true;
  std::string reason_;
};

/// The outcome of a check (Outcome<void>): passes, or says why not.
using Check = Outcome<void>;

}  // namespace cutaway
