#include "io/ply_guard.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

namespace cutaway {

namespace {

/// The header must end within this many bytes.
constexpr size_t kMaxPlyHeaderBytes = 64 << 10;
/// The longest ASCII number accepted in a PLY body.
constexpr size_t kMaxPlyNumberLength = 64;

/// A PLY scalar type.
struct PlyType {
  std::string_view name;
  int size;        ///< bytes in a binary file
  bool integer;    ///< else floating point
  int64_t lo, hi;  ///< range of an integer type
};

constexpr PlyType kPlyTypes[] = {
    {"char", 1, true, -128, 127},
    {"int8", 1, true, -128, 127},
    {"uchar", 1, true, 0, 255},
    {"uint8", 1, true, 0, 255},
    {"short", 2, true, -32768, 32767},
    {"int16", 2, true, -32768, 32767},
    {"ushort", 2, true, 0, 65535},
    {"uint16", 2, true, 0, 65535},
    {"int", 4, true, INT32_MIN, INT32_MAX},
    {"int32", 4, true, INT32_MIN, INT32_MAX},
    {"uint", 4, true, 0, UINT32_MAX},
    {"uint32", 4, true, 0, UINT32_MAX},
    {"float", 4, false, 0, 0},
    {"float32", 4, false, 0, 0},
    {"double", 8, false, 0, 0},
    {"float64", 8, false, 0, 0},
};

const PlyType* ply_type(std::string_view name) {
  for (const auto& t : kPlyTypes)
    if (t.name == name) return &t;
  return nullptr;
}

struct PlyProperty {
  std::string name;
  const PlyType* type = nullptr;        ///< the value type (of a list: of its entries)
  const PlyType* count_type = nullptr;  ///< a list's count type; null for a scalar
  bool is_vertex_indices = false;
};

struct PlyElement {
  std::string name;
  uint64_t count = 0;
  int line = 0;
  std::vector<PlyProperty> properties;
  bool is_vertex() const { return name == "vertex"; }
  bool is_face() const { return name == "face"; }
};

/// "vertices", "faces" or "\"edge\" elements": a number of elements in words.
std::string plural(const PlyElement& e) {
  if (e.is_vertex()) return "vertices";
  if (e.is_face()) return "faces";
  return quoted(e.name, 24) + " elements";
}

/// "vertex 12", "face 3" or "\"edge\" element 7".
std::string one(const PlyElement& e, uint64_t i) {
  const std::string n = std::to_string(i);
  if (e.is_vertex()) return "vertex " + n;
  if (e.is_face()) return "face " + n;
  return quoted(e.name, 24) + " element " + n;
}

/// a * b + c, saturated at UINT64_MAX.
uint64_t mul_add_sat(uint64_t a, uint64_t b, uint64_t c) {
  uint64_t m, r;
  if (__builtin_mul_overflow(a, b, &m) || __builtin_add_overflow(m, c, &r)) return UINT64_MAX;
  return r;
}

/// Whether `s` is a whole decimal number: an optional sign and 1..19 digits; its value in `v`.
bool parse_integer(std::string_view s, int64_t& v) {
  size_t i = 0;
  const bool negative = !s.empty() && s[0] == '-';
  if (!s.empty() && (s[0] == '-' || s[0] == '+')) i = 1;
  while (i + 1 < s.size() && s[i] == '0') ++i;  // leading zeros
  if (i == s.size() || s.size() - i > 18) return false;
  int64_t x = 0;
  for (; i < s.size(); ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
    x = 10 * x + (s[i] - '0');
  }
  v = negative ? -x : x;
  return true;
}

/// Whether `s` is a decimal number (optional sign, digits with an optional point, optional
/// exponent; no inf, nan or hex) that a float holds (|v| <= FLT_MAX: OpenMesh reads ASCII
/// coordinates into floats, and a stream stops at the first number out of range).
bool is_float_text(std::string_view s) {
  if (s.empty() || s.size() > kMaxPlyNumberLength) return false;
  size_t i = 0, digits = 0;
  if (s[i] == '+' || s[i] == '-') ++i;
  for (; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i) ++digits;
  if (i < s.size() && s[i] == '.') {
    for (++i; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i) ++digits;
  }
  if (digits == 0) return false;
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    size_t exp_digits = 0;
    for (; i < s.size() && s[i] >= '0' && s[i] <= '9'; ++i) ++exp_digits;
    if (exp_digits == 0) return false;
  }
  if (i != s.size()) return false;
  const std::string text(s);  // NUL-terminated for strtod (the "C" locale: '.' is the point)
  const double v = std::strtod(text.c_str(), nullptr);
  return std::isfinite(v) && std::fabs(v) <= FLT_MAX;
}

bool is_blank(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

/// The whitespace-separated words of a header line.
std::vector<std::string_view> words_of(std::string_view line) {
  std::vector<std::string_view> w;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    size_t j = i;
    while (j < line.size() && !is_blank(line[j])) ++j;
    if (j > i) w.push_back(line.substr(i, j - i));
    i = j;
  }
  return w;
}

/// check_ply's state: the bytes, where the template names them, and the parsed header.
class PlyGuard {
 public:
  PlyGuard(std::string_view bytes, const FileLoc& loc, const std::string& field)
      : bytes_(bytes), loc_(loc), field_(field) {}

  PlyCheck run() {
    parse_header();
    check_sizes();
    if (out_.binary) {
      walk_binary();
    } else {
      walk_ascii();
    }
    return out_;
  }

 private:
  [[noreturn]] void fail(const std::string& rule) const { throw InputError(loc_, field_, rule); }
  [[noreturn]] void fail_line(int line, const std::string& rule) const {
    fail("PLY header line " + std::to_string(line) + ": " + rule);
  }

  /// What parse_header() carries from one header line to the next.
  struct HeaderScan {
    bool seen_face = false, seen_vertex = false;
    std::vector<PlyElement> after_face;  // parsed for their syntax only
    size_t last_item_end = 0;  // where OpenMesh's header tokenizer stops before end_header
    bool last_item_comment = false;
  };

  void parse_header();
  /// Parses header line `line_no` (`line`, its words `w`) that starts with obj_info, element,
  /// property or an unknown keyword.
  void parse_item(int line_no, std::string_view line, const std::vector<std::string_view>& w,
                  HeaderScan& scan);
  /// Parses an element line: kept in elements_ up to and including `face`, in
  /// scan.after_face after it.
  void parse_element(int line_no, std::string_view line, const std::vector<std::string_view>& w,
                     HeaderScan& scan);
  void parse_property(int line, const std::vector<std::string_view>& w);
  /// Checks that the header declares the vertex element (with x, y and z) and the face element
  /// (its first property the list vertex_indices), and takes their counts.
  void check_vertex_and_face(const HeaderScan& scan);
  void check_binary_start(size_t end_header, size_t last_item_end, bool last_item_comment);
  void check_sizes();
  void walk_binary();
  void walk_ascii();
  [[noreturn]] void truncated(const PlyElement& e, uint64_t i) const {
    fail("the file ends in " + one(e, i) + " (its header declares " + std::to_string(e.count) +
         " " + plural(e) + ")");
  }
  /// Checks corner `k` (vertex index `v`) of face `f`; `seen` holds the face's earlier corners.
  void check_corner(uint64_t f, int64_t v, std::vector<int64_t>& seen) const;
  /// Checks the corner count `n` of face `f` and counts its triangles.
  void check_corner_count(uint64_t f, int64_t n);

  std::string_view bytes_;
  const FileLoc& loc_;
  const std::string& field_;
  bool big_endian_ = false;
  size_t body_ = 0;                   ///< offset of the first byte after the header
  std::vector<PlyElement> elements_;  ///< up to and including `face`
  PlyCheck out_;
};

void PlyGuard::parse_header() {
  size_t pos = 0;
  int line_no = 0;
  HeaderScan scan;
  while (true) {
    const size_t nl = bytes_.find('\n', pos);
    if (nl == std::string_view::npos || nl >= kMaxPlyHeaderBytes) {
      if (line_no == 0 && bytes_.substr(0, 3) != "ply" && bytes_.substr(0, 3) != "PLY") {
        fail("not a PLY file (its first line must be 'ply')");
      }
      fail("the PLY header has no 'end_header' line" +
           std::string(nl == std::string_view::npos ? "" : " in its first 65536 bytes"));
    }
    ++line_no;
    const std::string_view line = bytes_.substr(pos, nl - pos);
    const size_t line_start = pos;
    pos = nl + 1;
    const auto w = words_of(line);
    if (line_no == 1) {
      if (w.size() != 1 || (w[0] != "ply" && w[0] != "PLY")) {
        fail("not a PLY file (its first line must be 'ply')");
      }
      continue;
    }
    if (line_no == 2) {
      // OpenMesh reads the three words after 'ply' as the format, whatever they are.
      if (w.size() != 3 || w[0] != "format" || !is_float_text(w[2]) ||
          (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian")) {
        fail_line(2, "must be 'format ascii 1.0', 'format binary_little_endian 1.0' or "
                     "'format binary_big_endian 1.0', not " +
                         quoted(line));
      }
      out_.binary = w[1] != "ascii";
      big_endian_ = w[1] == "binary_big_endian";
      scan.last_item_end = line_start + (w[2].data() + w[2].size() - line.data());
      continue;
    }
    if (w.empty()) continue;
    const std::string_view key = w[0];
    if (key == "comment") {
      scan.last_item_end = pos;  // OpenMesh reads a comment to its line's end
      scan.last_item_comment = true;
      continue;
    }
    if (key == "end_header") {
      if (w.size() != 1) fail_line(line_no, "'end_header' must stand alone on its line");
      out_.header_end = line_start;
      body_ = pos;
      check_binary_start(line_start, scan.last_item_end, scan.last_item_comment);
      break;
    }
    scan.last_item_end = line_start + (w.back().data() + w.back().size() - line.data());
    scan.last_item_comment = false;
    parse_item(line_no, line, w, scan);
  }
  check_vertex_and_face(scan);
}

void PlyGuard::parse_item(int line_no, std::string_view line,
                          const std::vector<std::string_view>& w, HeaderScan& scan) {
  const std::string_view key = w[0];
  if (key == "obj_info") {
    // OpenMesh reads an obj_info line word by word, as keywords.
    for (size_t k = 1; k < w.size(); ++k) {
      if (w[k] == "element" || w[k] == "property" || w[k] == "comment" || w[k] == "end_header" ||
          w[k] == "obj_info" || w[k] == "format") {
        fail_line(line_no, "an obj_info line must not contain the keyword " + quoted(w[k]));
      }
    }
  } else if (key == "element") {
    parse_element(line_no, line, w, scan);
  } else if (key == "property") {
    if (elements_.empty() && scan.after_face.empty()) {
      fail_line(line_no, "a property before any element");
    }
    if (scan.after_face.empty()) {
      parse_property(line_no, w);
    } else if (!(w.size() == 3 && ply_type(w[1])) &&
               !(w.size() == 5 && w[1] == "list" && ply_type(w[2]) && ply_type(w[3]))) {
      fail_line(line_no, "write 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME' "
                         "with PLY types, not " +
                             quoted(line));
    }
  } else {
    fail_line(line_no, "unknown keyword " + quoted(key, 24) +
                           " (expected comment, obj_info, element, property or end_header)");
  }
}

void PlyGuard::parse_element(int line_no, std::string_view line,
                             const std::vector<std::string_view>& w, HeaderScan& scan) {
  if (w.size() != 3) fail_line(line_no, "write 'element NAME COUNT', not " + quoted(line));
  PlyElement e;
  e.name = std::string(w[1]);
  e.line = line_no;
  const std::string what = e.is_vertex() ? "vertex" : e.is_face() ? "face" : quoted(w[1], 24);
  const std::string_view count = w[2];
  bool digits = !count.empty();
  for (char c : count) digits = digits && c >= '0' && c <= '9';
  if (!digits) {
    fail_line(line_no,
              "the " + what + " count must be a whole number >= 0, not " + quoted(count, 24));
  }
  size_t first = 0;
  while (first + 1 < count.size() && count[first] == '0') ++first;
  if (count.size() - first > 18) {
    fail_line(line_no, "the " + what + " count " + quoted(count, 48) +
                           " is too large (a template mesh has at most " +
                           std::to_string(kMaxMeshVertices) + " vertices and " +
                           std::to_string(kMaxMeshFaces) + " faces)");
  }
  e.count = std::stoull(std::string(count.substr(first)));
  if (scan.seen_face) {
    scan.after_face.push_back(std::move(e));
    return;
  }
  if (e.is_vertex()) {
    if (scan.seen_vertex) fail_line(line_no, "a second 'vertex' element");
    scan.seen_vertex = true;
  }
  if (e.is_face()) {
    if (!scan.seen_vertex) fail_line(line_no, "the 'vertex' element must come before 'face'");
    scan.seen_face = true;
  }
  elements_.push_back(std::move(e));
}

void PlyGuard::check_vertex_and_face(const HeaderScan& scan) {
  if (!scan.seen_vertex) fail("the PLY header declares no 'vertex' element");
  if (!scan.seen_face) fail("the PLY header declares no 'face' element");
  for (const PlyElement& e : elements_) {
    if (e.is_vertex()) {
      for (const char* axis : {"x", "y", "z"}) {
        bool found = false;
        for (const auto& p : e.properties) found = found || p.name == axis;
        if (!found) {
          fail_line(e.line, std::string("the 'vertex' element has no property '") + axis + "'");
        }
      }
      out_.vertices = e.count;
    }
    if (e.is_face()) {
      if (e.properties.empty() || !e.properties[0].is_vertex_indices) {
        fail_line(e.line, "the first property of 'face' must be the list 'vertex_indices' "
                          "(property list uchar int vertex_indices)");
      }
      out_.faces = e.count;
    }
  }
}

void PlyGuard::parse_property(int line, const std::vector<std::string_view>& w) {
  PlyElement& e = elements_.back();
  PlyProperty p;
  const bool list = w.size() >= 2 && w[1] == "list";
  if (list) {
    if (w.size() != 5 || !ply_type(w[2]) || !ply_type(w[3])) {
      fail_line(line, "write 'property list COUNT_TYPE TYPE NAME' with PLY types (char, uchar, "
                      "short, ushort, int, uint, float, double or int8 ... float64)");
    }
    if (w[2] != "uchar" && w[2] != "uint8" && w[2] != "uint16" && w[2] != "int") {
      fail_line(line,
                "a list's count type must be uchar, uint8, uint16 or int, not " + quoted(w[2]));
    }
    p.count_type = ply_type(w[2]);
    p.type = ply_type(w[3]);
    p.name = std::string(w[4]);
    if (!e.is_vertex() && !e.is_face()) {
      fail_line(line, "only the 'vertex' and 'face' elements may have list properties");
    }
  } else {
    if (w.size() != 3 || !ply_type(w[1])) {
      fail_line(line, "write 'property TYPE NAME' with a PLY type (char, uchar, short, ushort, "
                      "int, uint, float, double or int8 ... float64)");
    }
    p.type = ply_type(w[1]);
    p.name = std::string(w[2]);
  }
  if (ply_type(p.name)) fail_line(line, "a property's name must not be a type name");
  for (const auto& q : e.properties) {
    if (q.name == p.name) fail_line(line, "the property " + quoted(p.name, 24) + " is given twice");
  }
  // Properties OpenMesh reads into fixed C++ types: only the types it reads correctly.
  const std::string_view n = p.name;
  const bool is_float = !p.type->integer;
  if (e.is_vertex() && !list &&
      (n == "x" || n == "y" || n == "z" || n == "nx" || n == "ny" || n == "nz" || n == "u" ||
       n == "v" || n == "s" || n == "t") &&
      !is_float) {
    fail_line(line, "the vertex property " + quoted(n) + " must be float or double");
  }
  const bool colour =
      n == "red" || n == "green" || n == "blue" || n == "alpha" ||
      (e.is_vertex() && (n == "diffuse_red" || n == "diffuse_green" || n == "diffuse_blue"));
  if (!list && colour && p.type->size == 8) {
    fail_line(line, "the colour property " + quoted(n) + " must be float or an integer type");
  }
  if (e.is_face() && !list && n == "texnumber" && is_float) {
    fail_line(line, "the face property 'texnumber' must have an integer type");
  }
  if (e.is_face() && list && n == "texcoord" && !is_float) {
    fail_line(line, "the face list 'texcoord' must have float or double entries");
  }
  if (e.is_face() && list && (n == "vertex_indices" || n == "vertex_index")) {
    if (!p.type->integer) {
      fail_line(line, "the face list " + quoted(n) + " must have integer entries (vertex indices)");
    }
    for (const auto& q : e.properties) {
      if (q.is_vertex_indices) fail_line(line, "a second vertex index list");
    }
    p.is_vertex_indices = true;
  }
  e.properties.push_back(std::move(p));
}

/// OpenMesh finds a binary body by stepping back to the end of the last header word it read
/// before 'end_header' and skipping "\nend_header\n" (12 bytes) or "\r\nend_header\r\n" (14):
/// the body must start there.
void PlyGuard::check_binary_start(size_t end_header, size_t last_item_end, bool last_item_comment) {
  if (!out_.binary) return;
  const bool crlf = bytes_.substr(last_item_end, 2) == "\r\n";
  const size_t openmesh_body = last_item_end + (crlf ? 14 : 12);
  if (last_item_comment || openmesh_body != body_ ||
      bytes_.substr(end_header, 10) != "end_header") {
    fail("binary PLY: the line before 'end_header' must be an element or property line, with "
         "nothing after its last word, and end with the same line break as 'end_header' "
         "(\\n or \\r\\n)");
  }
}

void PlyGuard::check_sizes() {
  const uint64_t size = bytes_.size();
  uint64_t need = body_;
  std::vector<std::string> declared;  // "N vertices", "M faces", ...
  for (const PlyElement& e : elements_) {
    declared.push_back(std::to_string(e.count) + " " + plural(e));
    uint64_t per = 0;
    for (const auto& p : e.properties) {
      if (out_.binary) {
        per += p.count_type ? p.count_type->size + (p.is_vertex_indices ? 3 * p.type->size : 0)
                            : p.type->size;
      } else {
        per += 2 + (p.is_vertex_indices ? 3 * 2 : 0);  // "0 " per number
      }
    }
    need = mul_add_sat(e.count, per, need);
    // ASCII: the last number needs no blank after it.
    if (need > size + (out_.binary ? 0 : 1)) {
      std::string what;
      for (size_t k = 0; k < declared.size(); ++k) {
        what += (k == 0 ? "" : k + 1 == declared.size() ? " and " : ", ") + declared[k];
      }
      fail("the PLY header declares " + what + " but the file has only " + std::to_string(size) +
           " bytes (" +
           (need == UINT64_MAX ? std::string("they need more")
                               : "they need at least " + std::to_string(need)) +
           ")");
    }
  }
  for (const PlyElement& e : elements_) {
    const uint64_t limit = e.is_vertex() ? kMaxMeshVertices : kMaxMeshFaces;
    if (e.count > limit) {
      fail("the PLY header declares " + std::to_string(e.count) + " " + plural(e) +
           "; a template mesh may have at most " + std::to_string(limit));
    }
  }
}

void PlyGuard::check_corner_count(uint64_t f, int64_t n) {
  if (n < 3 || n > static_cast<int64_t>(kMaxMeshFaceCorners)) {
    fail("face " + std::to_string(f) + " has " + std::to_string(n) + " corners (a face has 3 to " +
         std::to_string(kMaxMeshFaceCorners) + ")");
  }
  out_.triangles += static_cast<size_t>(n - 2);
  if (out_.triangles > kMaxMeshFaces) {
    fail("the faces make more than " + std::to_string(kMaxMeshFaces) +
         " triangles (a template mesh may have at most that many)");
  }
}

void PlyGuard::check_corner(uint64_t f, int64_t v, std::vector<int64_t>& seen) const {
  if (v < 0 || static_cast<uint64_t>(v) >= out_.vertices) {
    fail("face " + std::to_string(f) + " has vertex index " + std::to_string(v) +
         ", but the file has only " + std::to_string(out_.vertices) + " vertices");
  }
  for (int64_t u : seen) {
    if (u == v) {
      fail("face " + std::to_string(f) + " uses vertex " + std::to_string(v) +
           " twice (OpenMesh would leave the face out)");
    }
  }
  seen.push_back(v);
}

void PlyGuard::walk_binary() {
  size_t pos = body_;
  const size_t size = bytes_.size();
  // An integer of type t at pos (the caller checked that its bytes are there).
  auto integer_at = [&](const PlyType& t) {
    uint64_t u = 0;
    for (int k = 0; k < t.size; ++k) {
      const auto b = static_cast<unsigned char>(bytes_[pos + (big_endian_ ? k : t.size - 1 - k)]);
      u = (u << 8) | b;
    }
    pos += t.size;
    if (t.lo < 0 && (u >> (8 * t.size - 1)) != 0) {
      return static_cast<int64_t>(u) - (int64_t{1} << (8 * t.size));  // two's complement
    }
    return static_cast<int64_t>(u);
  };
  std::vector<int64_t> seen;
  for (const PlyElement& e : elements_) {
    for (uint64_t i = 0; i < e.count; ++i) {
      for (const auto& p : e.properties) {
        if (!p.count_type) {
          if (size - pos < static_cast<size_t>(p.type->size)) truncated(e, i);
          pos += p.type->size;
          continue;
        }
        if (size - pos < static_cast<size_t>(p.count_type->size)) truncated(e, i);
        const int64_t n = integer_at(*p.count_type);
        if (n < 0) {
          fail(one(e, i) + ": the list " + quoted(p.name, 24) + " has " + std::to_string(n) +
               " entries");
        }
        if (p.is_vertex_indices) check_corner_count(i, n);
        if (static_cast<uint64_t>(n) > (size - pos) / p.type->size) truncated(e, i);
        if (!p.is_vertex_indices) {
          pos += static_cast<size_t>(n) * p.type->size;
          continue;
        }
        seen.clear();
        for (int64_t k = 0; k < n; ++k) check_corner(i, integer_at(*p.type), seen);
      }
    }
  }
}

void PlyGuard::walk_ascii() {
  size_t pos = body_;
  // The next whitespace-separated word, as OpenMesh's stream reads it ("" at the end).
  auto next = [&]() -> std::string_view {
    while (pos < bytes_.size() && is_blank(bytes_[pos])) ++pos;
    const size_t start = pos;
    while (pos < bytes_.size() && !is_blank(bytes_[pos])) ++pos;
    return bytes_.substr(start, pos - start);
  };
  auto bad = [&](const PlyElement& e, uint64_t i, const PlyProperty& p, std::string_view word,
                 const PlyType& t, const char* what) {
    fail(one(e, i) + ", property " + quoted(p.name, 24) + ": " + quoted(word, 24) + " is not " +
         what + " (" + std::string(t.name) + ")");
  };
  // Reads and checks one number of type t; returns it when an integer.
  auto number = [&](const PlyElement& e, uint64_t i, const PlyProperty& p, const PlyType& t,
                    const char* integer_what) -> int64_t {
    const std::string_view word = next();
    if (word.empty()) truncated(e, i);
    if (!t.integer) {
      if (!is_float_text(word)) bad(e, i, p, word, t, "a decimal number within the float range");
      return 0;
    }
    int64_t v;
    if (!parse_integer(word, v) || v < t.lo || v > t.hi) bad(e, i, p, word, t, integer_what);
    return v;
  };
  std::vector<int64_t> seen;
  for (const PlyElement& e : elements_) {
    for (uint64_t i = 0; i < e.count; ++i) {
      for (const auto& p : e.properties) {
        if (!p.count_type) {
          number(e, i, p, *p.type, "a whole number in the type's range");
          continue;
        }
        const int64_t n = number(e, i, p, *p.count_type, "a list length in the type's range");
        if (n < 0) {
          fail(one(e, i) + ": the list " + quoted(p.name, 24) + " has " + std::to_string(n) +
               " entries");
        }
        if (p.is_vertex_indices) {
          check_corner_count(i, n);
          seen.clear();
        }
        for (int64_t k = 0; k < n; ++k) {
          if (!p.is_vertex_indices) {
            number(e, i, p, *p.type, "a whole number in the type's range");
            continue;
          }
          // OpenMesh reads an ASCII index as an unsigned int, whatever the declared type.
          const std::string_view word = next();
          if (word.empty()) truncated(e, i);
          int64_t v;
          if (!parse_integer(word, v)) {
            bool digits = true;
            for (char c : word) digits = digits && ((c >= '0' && c <= '9') || c == '-' || c == '+');
            if (!digits) bad(e, i, p, word, *p.type, "a whole number");
            fail("face " + std::to_string(i) + " has vertex index " + quoted(word, 48) +
                 ", but the file has only " + std::to_string(out_.vertices) + " vertices");
          }
          check_corner(i, v, seen);
        }
      }
    }
  }
}

}  // namespace

PlyCheck check_ply(std::string_view bytes, const FileLoc& loc, const std::string& field) {
  return PlyGuard(bytes, loc, field).run();
}

std::string prepare_ply(std::string ply, bool binary, size_t header_end) {
  if (binary) return ply;
  std::string text;
  size_t pos = 0;
  while (pos < header_end) {
    size_t nl = ply.find('\n', pos);
    const std::string_view line(ply.data() + pos, nl - pos);
    pos = nl + 1;
    const auto w = words_of(line);
    if (w.size() == 3 && w[0] == "property" &&
        (w[1] == "char" || w[1] == "uchar" || w[1] == "int8" || w[1] == "uint8")) {
      text += "property int " + std::string(w[2]) + (line.ends_with('\r') ? "\r" : "") + '\n';
    } else {
      text += line;
      text += '\n';
    }
  }
  text.append(ply, header_end);
  return text;
}

}  // namespace cutaway
