// A thin reading layer over yaml-cpp for cutaway's declarative files (templates and scenes):
// every access knows its field path and source position, so every rule broken by the input
// becomes an InputError "FILE:LINE:COL: field.path: rule" (doc/template-format.md, Errors).
#pragma once

#include <cstdint>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>
#include <yaml-cpp/yaml.h>

#include "base/error.h"

namespace cutaway {

/// One node of a parsed YAML document together with its field path and file name.
class YamlField {
 public:
  YamlField(YAML::Node node, std::string path, std::string file);
  /// As above, with the document's text: lets loc() place null values (an empty "key:" or "-"),
  /// which yaml-cpp marks at the next token, where they are written.
  YamlField(YAML::Node node, std::string path, std::string file,
            std::shared_ptr<const std::string> text);

  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }
  /// 1-based line and column of the node's first character. An empty value is placed at its
  /// key ("key:") or at its "-" (a list item).
  FileLoc loc() const;
  /// Throws InputError at this node: "FILE:LINE:COL: PATH: RULE".
  [[noreturn]] void fail(const std::string& rule) const;

  bool is_map() const { return node_.IsMap(); }
  bool is_sequence() const { return node_.IsSequence(); }
  bool is_scalar() const { return node_.IsScalar(); }
  bool is_null() const { return node_.IsNull(); }

  /// Map access. Requires a map (else fails with "must be a mapping").
  /// `require` fails with "missing required field 'KEY'" when absent.
  YamlField require(const std::string& key) const;
  std::optional<YamlField> get(const std::string& key) const;
  /// Fails at the first key not in `allowed` ("unknown field \"KEY\" (expected one of ...)"),
  /// and at a key given twice, each at the key's path (child_path) with the key quoted (quoted():
  /// escaped, long keys elided). Requires a map.
  void allow_only(std::initializer_list<std::string_view> allowed) const;

  /// Sequence access. Requires a sequence (else fails with "must be a list").
  size_t size() const;
  YamlField operator[](size_t i) const;

  /// Scalars. Each fails with a rule naming the expected type and the value found (quoted()).
  std::string string() const;
  double number() const;    ///< finite (NaN and infinities are refused)
  int64_t integer() const;  ///< a whole number, |n| <= 9e15 (where doubles hold them all)
  bool boolean() const;
  /// A number within [lo, hi] ("must be between LO and HI").
  double number_in(double lo, double hi) const;

  const YAML::Node& node() const { return node_; }

 private:
  void expect_map() const;
  void expect_sequence() const;
  YAML::Node node_;
  std::string path_;
  std::string file_;
  std::shared_ptr<const std::string> text_;  ///< the whole document (may be null)
  std::optional<FileLoc> loc_;               ///< where an empty value is written, when known
};

/// The longest key a field path shows as it is (longer keys are quoted, and elided).
inline constexpr size_t kMaxPlainKeyLength = 64;

/// Whether a mapping key stands in field paths as it is: 1..kMaxPlainKeyLength characters of
/// A-Z, a-z, 0-9, '_' and '-'.
bool is_plain_key(std::string_view key);

/// The field path of `key` in the mapping at `parent`: "parent.key" ("key" when `parent` is
/// "(root)") for a plain key (is_plain_key), else `parent["key"]` with the key as quoted()
/// writes it (escaped, elided when long), e.g. `symmetry[""]`, `symmetry["name "]`,
/// `(root)["f\x7frmat"]`: a message shows where the key is even when it is empty, ends in a
/// blank or holds control characters.
std::string child_path(const std::string& parent, std::string_view key);

/// A COLOR of the template and scene formats: "#rrggbb" or [r, g, b] with components in 0..1,
/// both sRGB (doc/template-format.md). Returns linear RGB.
/// @throws InputError at `f` naming the accepted forms
glm::dvec3 parse_colour(const YamlField& f);

/// Parses YAML text (YAML 1.2 / JSON, UTF-8). Refuses empty input, invalid UTF-8, NUL bytes,
/// nesting deeper than 64 levels and YAML syntax errors with an InputError at the position.
/// @param text      the file's bytes
/// @param file      the name used in messages
/// @return the root field (path "(root)")
YamlField parse_yaml(std::string_view text, const std::string& file);

/// The largest template, scene or batch file (bytes): 16 MiB.
inline constexpr size_t kMaxInputFileBytes = size_t{16} << 20;

/// The bytes of the input file at `path`, read through read_regular_file (base/file_read.h):
/// a FIFO, device or directory is refused without reading from it, and a file larger than
/// 16 MiB before it is read.
/// @throws InputError "PATH:1:1: (file): the file RULE", RULE as FileReadError's (e.g. "does
///         not exist", "is larger than 16 MiB")
std::string read_input_file(const std::string& path);

/// Reads `path` and parses it with parse_yaml.
YamlField load_yaml_file(const std::string& path);

}  // namespace cutaway
