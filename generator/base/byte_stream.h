// A plain binary encoding (cut cache entries, content hashes of parsed data): values and arrays
// of them written as their bytes, little-endian as on every machine cutaway builds for, lengths
// as 64-bit counts. Doubles keep every bit, so that a cached piece gives the same output bytes
// as a freshly cut one.
#pragma once

#include <bit>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

namespace cutaway {

static_assert(std::endian::native == std::endian::little, "the encoding is little-endian");

/// Thrown by ByteReader when the bytes end early or a count is implausible (damaged data).
class ByteStreamError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Appends values to a byte string.
class ByteWriter {
 public:
  /// One trivially copyable value (numbers, glm vectors and quaternions), as its bytes.
  template <typename T>
  void put(const T& value) {
    static_assert(std::is_trivially_copyable_v<T>);
    bytes_.append(reinterpret_cast<const char*>(&value), sizeof value);
  }
  /// A count, then the elements' bytes.
  template <typename T>
  void put_vector(const std::vector<T>& values) {
    static_assert(std::is_trivially_copyable_v<T>);
    put<uint64_t>(values.size());
    bytes_.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
  }
  /// A count, then the characters.
  void put_string(std::string_view text) {
    put<uint64_t>(text.size());
    bytes_.append(text);
  }
  const std::string& bytes() const { return bytes_; }
  std::string take() { return std::move(bytes_); }

 private:
  std::string bytes_;
};

/// Reads back what a ByteWriter wrote, in the same order.
class ByteReader {
 public:
  explicit ByteReader(std::string_view bytes) : bytes_(bytes) {}
  /// @throws ByteStreamError when fewer than sizeof(T) bytes are left
  template <typename T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    T value;
    std::memcpy(&value, take(sizeof value), sizeof value);
    return value;
  }
  /// @throws ByteStreamError when the count exceeds the bytes left
  template <typename T>
  std::vector<T> get_vector() {
    static_assert(std::is_trivially_copyable_v<T>);
    const uint64_t n = count(sizeof(T));
    std::vector<T> values(n);
    if (n > 0) std::memcpy(values.data(), take(n * sizeof(T)), n * sizeof(T));
    return values;
  }
  /// @throws ByteStreamError when the count exceeds the bytes left
  std::string get_string() {
    const uint64_t n = count(1);
    return std::string(take(n), n);
  }
  /// A count of elements of `size` bytes each that the bytes left can hold.
  /// @throws ByteStreamError otherwise
  uint64_t count(size_t size) {
    const uint64_t n = get<uint64_t>();
    if (n > (bytes_.size() - at_) / size) throw ByteStreamError("a count beyond the data");
    return n;
  }
  /// Whether every byte was read.
  bool done() const { return at_ == bytes_.size(); }

 private:
  const char* take(size_t n) {
    if (n > bytes_.size() - at_) throw ByteStreamError("the data ends early");
    const char* p = bytes_.data() + at_;
    at_ += n;
    return p;
  }
  std::string_view bytes_;
  size_t at_ = 0;
};

}  // namespace cutaway
