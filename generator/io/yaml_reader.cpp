#include "io/yaml_reader.h"

#include <cmath>
#include <filesystem>
#include <regex>
#include <set>
#include <sstream>

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/parser.h>

#include "base/colour.h"
#include "base/file_read.h"

namespace cutaway {

namespace {

constexpr int kMaxDepth = 64;

FileLoc loc_of(const YAML::Mark& mark, const std::string& file) {
  if (mark.is_null()) return FileLoc{file, 1, 1};
  return FileLoc{file, mark.line + 1, mark.column + 1};
}

/// Position (1-based line, column) of byte `offset` in `text`.
FileLoc loc_of_offset(std::string_view text, size_t offset, const std::string& file) {
  int line = 1, col = 1;
  for (size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      col = 1;
    } else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) {
      ++col;
    }
  }
  return FileLoc{file, line, col};
}

/// Offset of the first byte that is not valid UTF-8 (or a NUL), or npos.
size_t find_invalid_utf8(std::string_view s) {
  for (size_t i = 0; i < s.size();) {
    const size_t n = s[i] == 0 ? 0 : utf8_length(s, i);
    if (n == 0) return i;
    i += n;
  }
  return std::string_view::npos;
}

/// Offset where flow/block nesting first exceeds kMaxDepth, or npos. Counts '[' and '{' outside
/// quotes and comments, and indentation steps of block collections conservatively (by the
/// number of leading spaces / 1): a guard against stack exhaustion in the recursive parser.
size_t find_excessive_nesting(std::string_view s) {
  int depth = 0;
  char quote = 0;
  bool comment = false;
  for (size_t i = 0; i < s.size(); ++i) {
    const char c = s[i];
    if (c == '\n') {
      comment = false;
      if (quote == '\'' || quote == '"') continue;
      size_t indent = 0;
      while (i + 1 + indent < s.size() && (s[i + 1 + indent] == ' ' || s[i + 1 + indent] == '-'))
        ++indent;
      if (indent > 4 * kMaxDepth) return i + 1;
      continue;
    }
    if (comment) continue;
    if (quote) {
      if (c == '\\' && quote == '"') ++i;
      else if (c == quote) quote = 0;
      continue;
    }
    if (c == '#' && (i == 0 || s[i - 1] == ' ' || s[i - 1] == '\t')) comment = true;
    else if (c == '"' || c == '\'') quote = c;
    else if (c == '[' || c == '{') {
      if (++depth > kMaxDepth) return i;
    } else if (c == ']' || c == '}') {
      if (depth > 0) --depth;
    }
  }
  return std::string_view::npos;
}

/// Where an empty list item ("-" with nothing after it) is written. yaml-cpp marks such a null
/// at the next token, often on a later line: if only indentation precedes the mark on its line,
/// step back to the last character of the previous line with content (comments skipped).
FileLoc null_item_loc(const YAML::Mark& mark, const std::string* text, const std::string& file) {
  const FileLoc fallback = loc_of(mark, file);
  if (!text || mark.is_null() || mark.pos < 0 || static_cast<size_t>(mark.pos) > text->size()) {
    return fallback;
  }
  const std::string_view s(*text);
  size_t i = static_cast<size_t>(mark.pos);
  while (i > 0 && (s[i - 1] == ' ' || s[i - 1] == '\t')) --i;
  if (i > 0 && s[i - 1] != '\n' && s[i - 1] != '\r') return fallback;  // content before it
  while (i > 0) {
    // The line ending just before i: [begin, end).
    size_t end = i - 1;
    while (end > 0 && (s[end] == '\n' || s[end] == '\r')) --end;
    size_t begin = end;
    while (begin > 0 && s[begin - 1] != '\n') --begin;
    // Cut a comment: '#' at the line start or after a blank, outside quotes.
    size_t stop = end + 1;
    char quote = 0;
    for (size_t k = begin; k <= end && k < s.size(); ++k) {
      if (quote) {
        if (s[k] == quote) quote = 0;
      } else if (s[k] == '"' || s[k] == '\'') {
        quote = s[k];
      } else if (s[k] == '#' && (k == begin || s[k - 1] == ' ' || s[k - 1] == '\t')) {
        stop = k;
        break;
      }
    }
    while (stop > begin && (s[stop - 1] == ' ' || s[stop - 1] == '\t' || s[stop - 1] == '\r' ||
                            s[stop - 1] == '\n')) {
      --stop;
    }
    if (stop > begin) return loc_of_offset(s, stop - 1, file);
    i = begin;
  }
  return fallback;
}

std::string describe(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Null: return "nothing";
    case YAML::NodeType::Scalar: return quoted(n.Scalar());
    case YAML::NodeType::Sequence: return "a list";
    case YAML::NodeType::Map: return "a mapping";
    default: return "nothing";
  }
}

/// Parser events of one document, all ignored but where it starts.
struct DocumentStart : YAML::EventHandler {
  YAML::Mark mark;
  void OnDocumentStart(const YAML::Mark& m) override { mark = m; }
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark&, YAML::anchor_t) override {}
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}
};

}  // namespace

bool is_plain_key(std::string_view key) {
  if (key.empty() || key.size() > kMaxPlainKeyLength) return false;
  for (const char c : key) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                    c == '_' || c == '-';
    if (!ok) return false;
  }
  return true;
}

std::string child_path(const std::string& parent, std::string_view key) {
  if (!is_plain_key(key)) return parent + "[" + quoted(key) + "]";
  return parent == "(root)" ? std::string(key) : parent + "." + std::string(key);
}

YamlField::YamlField(YAML::Node node, std::string path, std::string file)
    : node_(std::move(node)), path_(std::move(path)), file_(std::move(file)) {}

YamlField::YamlField(YAML::Node node, std::string path, std::string file,
                     std::shared_ptr<const std::string> text)
    : node_(std::move(node)), path_(std::move(path)), file_(std::move(file)),
      text_(std::move(text)) {}

FileLoc YamlField::loc() const { return loc_ ? *loc_ : loc_of(node_.Mark(), file_); }

void YamlField::fail(const std::string& rule) const { throw InputError(loc(), path_, rule); }

void YamlField::expect_map() const {
  if (!node_.IsMap()) fail("must be a mapping (key: value), not " + describe(node_));
}

void YamlField::expect_sequence() const {
  if (!node_.IsSequence()) fail("must be a list, not " + describe(node_));
}

std::optional<YamlField> YamlField::get(const std::string& key) const {
  expect_map();
  for (const auto& kv : node_) {
    if (kv.first.IsScalar() && kv.first.Scalar() == key) {
      YamlField f(kv.second, child_path(path_, key), file_, text_);
      // An empty value ("key:", "key: ~") is reported at its key: yaml-cpp marks an empty
      // value at the next token (often the next line), or not at all.
      if (kv.second.IsNull()) f.loc_ = loc_of(kv.first.Mark(), file_);
      return f;
    }
  }
  return std::nullopt;
}

YamlField YamlField::require(const std::string& key) const {
  auto f = get(key);
  if (!f) fail("missing required field '" + key + "'");  // a name from the code, not the user
  return *f;
}

void YamlField::allow_only(std::initializer_list<std::string_view> allowed) const {
  expect_map();
  std::set<std::string> seen;
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar()) {
      throw InputError(loc_of(kv.first.Mark(), file_), path_, "keys must be plain names");
    }
    const std::string& key = kv.first.Scalar();
    bool ok = false;
    for (auto a : allowed) ok = ok || a == key;
    if (!ok) {
      std::string list;
      for (auto a : allowed) list += (list.empty() ? "" : ", ") + std::string(a);
      throw InputError(loc_of(kv.first.Mark(), file_), child_path(path_, key),
                       "unknown field " + quoted(key) + " (expected one of: " + list + ")");
    }
    if (!seen.insert(key).second) {
      throw InputError(loc_of(kv.first.Mark(), file_), child_path(path_, key),
                       "field " + quoted(key) + " is given twice");
    }
  }
}

size_t YamlField::size() const {
  expect_sequence();
  return node_.size();
}

YamlField YamlField::operator[](size_t i) const {
  expect_sequence();
  YamlField f(node_[i], path_ + "[" + std::to_string(i) + "]", file_, text_);
  if (f.node_.IsNull()) f.loc_ = null_item_loc(f.node_.Mark(), text_.get(), file_);
  return f;
}

std::string YamlField::string() const {
  if (!node_.IsScalar()) fail("must be a text value, not " + describe(node_));
  return node_.Scalar();
}

double YamlField::number() const {
  if (!node_.IsScalar()) fail("must be a number, not " + describe(node_));
  double v;
  if (!YAML::convert<double>::decode(node_, v)) fail("must be a number, not " + describe(node_));
  if (!std::isfinite(v)) fail("must be a finite number, not " + describe(node_));
  return v;
}

int64_t YamlField::integer() const {
  const double v = number();
  if (v != std::floor(v)) fail("must be a whole number, not " + describe(node_));
  // Beyond 9e15 a double no longer holds every whole number (2^53 is about 9.007e15).
  if (std::fabs(v) > 9.0e15)
    fail("must be a whole number of at most 9e15 in size, not " + describe(node_));
  return static_cast<int64_t>(v);
}

bool YamlField::boolean() const {
  bool v;
  if (!node_.IsScalar() || !YAML::convert<bool>::decode(node_, v)) {
    fail("must be true or false, not " + describe(node_));
  }
  return v;
}

double YamlField::number_in(double lo, double hi) const {
  const double v = number();
  if (v < lo || v > hi) {
    std::ostringstream s;
    // The value as written (printed, 10.000001 would read as 10); quoted when long.
    const std::string& written = node_.Scalar();
    s << "must be between " << lo << " and " << hi << ", not "
      << (written.size() <= 32 ? written : quoted(written));
    fail(s.str());
  }
  return v;
}

YamlField parse_yaml(std::string_view text, const std::string& file) {
  if (text.size() > kMaxInputFileBytes) {
    throw InputError(FileLoc{file, 1, 1}, "(file)",
                     "the file is larger than " + byte_size_words(kMaxInputFileBytes));
  }
  if (const size_t bad = find_invalid_utf8(text); bad != std::string_view::npos) {
    throw InputError(loc_of_offset(text, bad, file), "(file)",
                     "the file is not UTF-8 text (a YAML or JSON file was expected)");
  }
  if (const size_t deep = find_excessive_nesting(text); deep != std::string_view::npos) {
    throw InputError(loc_of_offset(text, deep, file), "(file)",
                     "nesting is deeper than " + std::to_string(kMaxDepth) + " levels");
  }
  YAML::Node root;
  try {
    root = YAML::Load(std::string(text));
    // A second document (after "---") is refused, not ignored: the events of the first two
    // are read (never more, however many documents follow). Only a line that starts with
    // "---" or "..." can begin a second document, so a file without one is not parsed twice.
    const auto marker = [&](std::string_view m) {
      return text.starts_with(m) || text.find("\n" + std::string(m)) != std::string_view::npos;
    };
    if (marker("---") || marker("...")) {
      std::istringstream in{std::string(text)};
      YAML::Parser parser(in);
      DocumentStart first, second;
      if (parser.HandleNextDocument(first) && parser.HandleNextDocument(second)) {
        throw InputError(loc_of(second.mark, file), "(file)",
                         "a second YAML document (after \"---\"): a file holds one document");
      }
    }
  } catch (const YAML::Exception& e) {
    // yaml-cpp appends some of the input to a few messages (an escape character, a version):
    // written as quoted() writes it when it holds anything to escape.
    std::string msg = e.msg;
    if (const std::string q = quoted(msg, 200); q != '"' + msg + '"') msg = q;
    throw InputError(loc_of(e.mark, file), "(file)", "YAML syntax error: " + msg);
  }
  if (!root.IsDefined() || root.IsNull()) {
    throw InputError(FileLoc{file, 1, 1}, "(root)", "the file is empty");
  }
  YamlField f(root, "(root)", file, std::make_shared<const std::string>(text));
  if (!root.IsMap()) f.fail("the top level must be a mapping (key: value), not " + describe(root));
  return f;
}

std::string read_input_file(const std::string& path) {
  try {
    return read_regular_file(path, kMaxInputFileBytes);
  } catch (const FileReadError& e) {
    throw InputError(FileLoc{path, 1, 1}, "(file)", "the file " + e.rule());
  }
}

YamlField load_yaml_file(const std::string& path) {
  return parse_yaml(read_input_file(path), path);
}

glm::dvec3 parse_colour(const YamlField& f) {
  if (f.is_scalar()) {
    const std::string s = f.string();
    static const std::regex hex("#[0-9a-fA-F]{6}");
    if (!std::regex_match(s, hex)) {
      f.fail("a colour must be \"#rrggbb\" (hex digits) or [r, g, b] with components in 0..1, "
             "not " +
             quoted(s));
    }
    glm::dvec3 c;
    for (int k = 0; k < 3; ++k) c[k] = std::stoi(s.substr(1 + 2 * k, 2), nullptr, 16) / 255.0;
    return srgb_to_linear(c);
  }
  if (!f.is_sequence() || f.size() != 3) {
    f.fail("a colour must be \"#rrggbb\" or [r, g, b] with components in 0..1");
  }
  glm::dvec3 c;
  for (int k = 0; k < 3; ++k) c[k] = f[k].number_in(0.0, 1.0);
  return srgb_to_linear(c);
}

}  // namespace cutaway
