// check_ply (generator/io/ply_guard.h), the guard in front of OpenMesh's PLY reader, on crafted
// files: valid ASCII and binary files pass with their counts; broken headers, counts the file
// cannot hold, truncated bodies and bad face indices are refused with the rule, before the
// body and without allocating for the declared counts.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "io/ply_guard.h"
#include "test_support.h"

namespace cutaway {
namespace {

const FileLoc kLoc{"t.yaml", 7, 11};
const std::string kField = "surfaces[1].file";

/// The rule check_ply breaks on `ply` ("" when it passes).
std::string refusal(const std::string& ply) {
  try {
    check_ply(ply, kLoc, kField);
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), kField);
    EXPECT_EQ(e.loc().line, 7);
    EXPECT_EQ(e.loc().column, 11);
    return e.rule();
  }
  return "";
}

#define EXPECT_REFUSED(ply, fragment)                                                         \
  do {                                                                                        \
    const std::string rule_ = refusal(ply);                                                   \
    EXPECT_NE(rule_.find(fragment), std::string::npos)                                        \
        << "expected a refusal containing \"" << (fragment) << "\", got \"" << rule_ << "\""; \
  } while (false)

const std::string kXyz = "property float x\nproperty float y\nproperty float z\n";
const std::string kIndices = "property list uchar int vertex_indices\n";

/// An ASCII file: the header with `nv` vertices and `nf` faces (as text: any word), then `body`.
std::string ascii(const std::string& nv, const std::string& nf, const std::string& body,
                  const std::string& vertex_props = kXyz,
                  const std::string& face_props = kIndices) {
  return "ply\nformat ascii 1.0\ncomment test\nelement vertex " + nv + "\n" + vertex_props +
         "element face " + nf + "\n" + face_props + "end_header\n" + body;
}

const std::string kTetraVerts = "0 0 0\n1 0 0\n0 1 0\n0 0 1\n";
const std::string kTetraFaces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
const std::string kTetra = ascii("4", "4", kTetraVerts + kTetraFaces);

template <class T>
void put(std::string& out, T v, bool big_endian = false) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big_endian) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

/// A binary tetrahedron (float coordinates, uchar counts, int indices); `faces` overrides the
/// faces' indices, `nl` is the header's line break.
std::string binary(bool big_endian, std::vector<std::vector<int32_t>> faces = {},
                   const std::string& nl = "\n", const std::string& extra_header = "") {
  if (faces.empty()) faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  std::string h = std::string("ply\nformat ") +
                  (big_endian ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 4\n" + kXyz + "element face " +
                  std::to_string(faces.size()) + "\n" + kIndices + extra_header + "end_header\n";
  std::string out;
  for (char c : h) {
    if (c == '\n') out += nl;
    else out += c;
  }
  const float v[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const auto& p : v)
    for (float x : p) put(out, x, big_endian);
  for (const auto& f : faces) {
    put(out, static_cast<uint8_t>(f.size()));
    for (int32_t i : f) put(out, i, big_endian);
  }
  return out;
}

TEST(PlyGuard, ValidFilesPassWithTheirCounts) {
  const PlyCheck a = check_ply(kTetra, kLoc, kField);
  EXPECT_FALSE(a.binary);
  EXPECT_EQ(a.vertices, 4u);
  EXPECT_EQ(a.faces, 4u);
  EXPECT_EQ(a.triangles, 4u);
  EXPECT_EQ(kTetra.compare(a.header_end, 10, "end_header"), 0);
  for (bool big : {false, true}) {
    for (const std::string nl : {"\n", "\r\n"}) {
      const PlyCheck b = check_ply(binary(big, {}, nl), kLoc, kField);
      EXPECT_TRUE(b.binary);
      EXPECT_EQ(b.triangles, 4u);
    }
  }
  // Quads make two triangles each; a face property after the indices, an element after the
  // faces, no line break at the end, CRLF lines.
  const std::string quads =
      ascii("4", "2", "0 0 0\r\n1 0 0\r\n1 1 0\r\n0 1 0\r\n4 0 1 2 3 7\r\n4 3 2 1 0 8", kXyz,
            kIndices + "property uchar part\n");
  const PlyCheck q = check_ply(quads, kLoc, kField);
  EXPECT_EQ(q.faces, 2u);
  EXPECT_EQ(q.triangles, 4u);
  EXPECT_EQ(refusal(ascii("4", "4", kTetraVerts + kTetraFaces, kXyz, kIndices) +
                    "element material 1\nproperty float shine\n"),
            "");
}

TEST(PlyGuard, CountsMustBeWholeNumbersThatFit) {
  EXPECT_REFUSED(ascii("-5", "4", kTetraVerts + kTetraFaces),
                 "PLY header line 4: the vertex count must be a whole number >= 0, not \"-5\"");
  EXPECT_REFUSED(ascii("1e30", "4", kTetraVerts + kTetraFaces), "not \"1e30\"");
  EXPECT_REFUSED(ascii("abc", "4", kTetraVerts + kTetraFaces), "not \"abc\"");
  EXPECT_REFUSED(ascii("4", "+4", kTetraVerts + kTetraFaces), "the face count must be");
  EXPECT_REFUSED(ascii("4", "4.0", kTetraVerts + kTetraFaces), "not \"4.0\"");
  EXPECT_REFUSED(ascii("1000000000000000000000000000000", "4", kTetraVerts + kTetraFaces),
                 "the vertex count \"1000000000000000000000000000000\" is too large");
  EXPECT_REFUSED(ascii("18446744073709551617", "4", kTetraVerts + kTetraFaces), "too large");
  // A count in range, but more than the file can hold: refused before any allocation.
  EXPECT_REFUSED(ascii("1000000000", "4", kTetraVerts + kTetraFaces),
                 "the PLY header declares 1000000000 vertices but the file has only");
  EXPECT_REFUSED(ascii("4", "999999999999999999", kTetraVerts + kTetraFaces),
                 "declares 4 vertices and 999999999999999999 faces but the file has only");
  std::string b = binary(false);
  b.replace(b.find("vertex 4"), 8, "vertex 5");
  EXPECT_REFUSED(b, "declares 5 vertices and 4 faces but the file has only " +
                        std::to_string(b.size()) + " bytes (they need at least");
}

TEST(PlyGuard, CountsBeyondTheTemplateLimitsAreRefused) {
  // Files large enough for the counts, all zeros: refused on the count, before the body.
  const size_t nv = kMaxMeshVertices + 1;
  std::string big = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(nv) +
                    "\n" + kXyz + "element face 0\n" + kIndices + "end_header\n";
  big.resize(big.size() + nv * 12, '\0');
  EXPECT_REFUSED(big, "declares " + std::to_string(nv) +
                          " vertices; a template mesh may have at most " +
                          std::to_string(kMaxMeshVertices));
  const size_t nf = kMaxMeshFaces + 1;
  std::string many = "ply\nformat binary_little_endian 1.0\nelement vertex 3\n" + kXyz +
                     "element face " + std::to_string(nf) +
                     "\nproperty list uchar uchar vertex_indices\nend_header\n";
  many.resize(many.size() + 36 + nf * 4, '\0');
  EXPECT_REFUSED(many, "declares " + std::to_string(nf) +
                           " faces; a template mesh may have at most " +
                           std::to_string(kMaxMeshFaces));
}

TEST(PlyGuard, TruncatedBodiesAreRefused) {
  // Shorter than the counts can be: refused on the sizes alone.
  EXPECT_REFUSED(ascii("4", "4", kTetraVerts + "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1"),
                 "declares 4 vertices and 4 faces but the file has only");
  const std::string b = binary(false);
  EXPECT_REFUSED(b.substr(0, b.size() - 1),
                 "but the file has only " + std::to_string(b.size() - 1) + " bytes");
  // Long enough, but the numbers run out (blanks are no numbers) ...
  EXPECT_REFUSED(ascii("4", "4",
                       kTetraVerts + "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2" + std::string(40, ' ')),
                 "the file ends in face 3 (its header declares 4 faces)");
  EXPECT_REFUSED(ascii("4", "4", "0 0 0\n1 0 0\n0 1 0\n0 0\n" + std::string(40, '\n')),
                 "the file ends in vertex 3 (its header declares 4 vertices)");
  // ... or a list is longer than the bytes left.
  std::string c = binary(true);
  c[c.size() - 13] = static_cast<char>(200);
  EXPECT_REFUSED(c, "the file ends in face 3");
}

TEST(PlyGuard, FaceIndicesMustNameVerticesOfTheFile) {
  EXPECT_REFUSED(ascii("4", "4", kTetraVerts + "3 0 2 1\n3 0 1 7\n3 0 3 2\n3 1 2 3\n"),
                 "face 1 has vertex index 7, but the file has only 4 vertices");
  EXPECT_REFUSED(ascii("4", "4", kTetraVerts + "3 0 2 1\n3 0 1 3\n3 0 3 99999999999\n3 1 2 3\n"),
                 "face 2 has vertex index 99999999999, but the file has only 4 vertices");
  EXPECT_REFUSED(ascii("4", "4", kTetraVerts + "3 -1 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"),
                 "face 0 has vertex index -1, but the file has only 4 vertices");
  EXPECT_REFUSED(ascii("4", "4", kTetraVerts + "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 1\n"),
                 "face 3 uses vertex 1 twice");
  EXPECT_REFUSED(ascii("4", "4", kTetraVerts + "3 0 2 1\n2 0 1\n3 0 3 2\n3 1 2 3\n    "),
                 "face 1 has 2 corners (a face has 3 to 256)");
  EXPECT_REFUSED(ascii("4", "1", kTetraVerts + "300" + std::string(600, ' '), kXyz,
                       "property list uint16 int vertex_indices\n"),
                 "face 0 has 300 corners (a face has 3 to 256)");
  EXPECT_REFUSED(ascii("4", "4", kTetraVerts + "3 0 2 x\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"),
                 "face 0, property \"vertex_indices\": \"x\" is not a whole number");
  for (bool big : {false, true}) {
    EXPECT_REFUSED(binary(big, {{0, 2, 1}, {0, 1, 3}, {0, 3, 4}, {1, 2, 3}}),
                   "face 2 has vertex index 4, but the file has only 4 vertices");
    EXPECT_REFUSED(binary(big, {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, -2, 3}}),
                   "face 3 has vertex index -2, but the file has only 4 vertices");
  }
}

TEST(PlyGuard, AsciiNumbersMustParseAsTheirTypes) {
  EXPECT_REFUSED(ascii("4", "4", "0 0 0\n1 abc 0\n0 1 0\n0 0 1\n" + kTetraFaces),
                 "vertex 1, property \"y\": \"abc\" is not a decimal number");
  EXPECT_REFUSED(ascii("4", "4", "0 0 0\n1 0 0\n0 1e39 0\n0 0 1\n" + kTetraFaces),
                 "vertex 2, property \"y\": \"1e39\"");
  EXPECT_REFUSED(ascii("4", "4", "0 0 0\n1 0 0\n0 1 0\n0 0 nan\n" + kTetraFaces), "\"nan\"");
  EXPECT_EQ(refusal(ascii("4", "4", "0 0 0\n1. -.5 +2e-3\n0 1E2 0\n0 0 1e-50\n" + kTetraFaces)),
            "");
  EXPECT_REFUSED(
      ascii("4", "4", "0 0 0 256\n1 0 0 1\n0 1 0 1\n0 0 1 1\n" + kTetraFaces,
            kXyz + "property uchar front_red\n"),
      "vertex 0, property \"front_red\": \"256\" is not a whole number in the type's range");
}

TEST(PlyGuard, HeadersOpenMeshWouldMisreadAreRefused) {
  EXPECT_REFUSED("solid cube\nfacet normal 0 0 1\n", "not a PLY file");
  EXPECT_REFUSED("ply\nformat ascii 1.0\nelement vertex 4\n", "no 'end_header' line");
  EXPECT_REFUSED("ply\n" + std::string(70000, ' ') + "\n", "in its first 65536 bytes");
  EXPECT_REFUSED("ply\nformat binary_middle_endian 1.0\nend_header\n", "PLY header line 2");
  EXPECT_REFUSED("ply\ncomment first\nformat ascii 1.0\nend_header\n", "PLY header line 2");
  EXPECT_REFUSED("ply\nformat ascii 1.0\nproperty float x\nend_header\n",
                 "a property before any element");
  EXPECT_REFUSED("ply\nformat ascii 1.0\nelement vertex 0\n" + kXyz + "end_header\n",
                 "no 'face' element");
  EXPECT_REFUSED("ply\nformat ascii 1.0\nelement face 0\n" + kIndices + "element vertex 0\n" +
                     kXyz + "end_header\n",
                 "the 'vertex' element must come before 'face'");
  EXPECT_REFUSED(ascii("4", "4", "", "property float x\nproperty float y\n"), "no property 'z'");
  EXPECT_REFUSED(ascii("4", "4", "", "property int x\nproperty float y\nproperty float z\n"),
                 "the vertex property \"x\" must be float or double");
  EXPECT_REFUSED(ascii("4", "4", "", kXyz + "property float128 w\n"), "with a PLY type");
  EXPECT_REFUSED(ascii("4", "4", "", kXyz + "property float float\n"), "must not be a type name");
  EXPECT_REFUSED(ascii("4", "4", "", kXyz + "property double red\n"),
                 "the colour property \"red\" must be float or an integer type");
  EXPECT_REFUSED(ascii("4", "4", "", kXyz, "property list float int vertex_indices\n"),
                 "a list's count type must be uchar, uint8, uint16 or int, not \"float\"");
  EXPECT_REFUSED(ascii("4", "4", "", kXyz, "property list uchar float vertex_indices\n"),
                 "must have integer entries");
  EXPECT_REFUSED(ascii("4", "4", "", kXyz, "property uchar part\n" + kIndices),
                 "the first property of 'face' must be the list 'vertex_indices'");
  EXPECT_REFUSED(ascii("4", "4", "", kXyz + "property float x\n"), "\"x\" is given twice");
  EXPECT_REFUSED(ascii("4", "4", "", kXyz, kIndices + "end_header extra\n"), "must stand alone");
  EXPECT_REFUSED(ascii("4", "4", "", kXyz + "obj_info element 3\n"),
                 "must not contain the keyword \"element\"");
  EXPECT_REFUSED(ascii("4", "4", "", kXyz + "elemnt edge 3\n"), "unknown keyword \"elemnt\"");
  EXPECT_REFUSED("ply\nformat ascii 1.0\nelement vertex 4\n" + kXyz +
                     "element edge 1\nproperty list uchar int v\nelement face 4\n" + kIndices +
                     "end_header\n",
                 "only the 'vertex' and 'face' elements may have list properties");
  // Binary: OpenMesh looks for the body 12 bytes after the last header word before
  // end_header; a comment there, or blanks after that word, would shift it.
  EXPECT_REFUSED(binary(false, {}, "\n", "comment made by hand\n"),
                 "the line before 'end_header' must be an element or property line");
  std::string blanks = binary(false);
  blanks.replace(blanks.find("vertex_indices\n"), 15, "vertex_indices \n");
  EXPECT_REFUSED(blanks, "nothing after its last word");
  // An ASCII header may end with a comment.
  EXPECT_EQ(refusal(ascii("4", "4", kTetraVerts + kTetraFaces, kXyz, kIndices + "comment x\n")),
            "");
}

TEST(PlyGuard, MessagesQuoteWhatTheyEcho) {
  const std::string rule = refusal(ascii("4\x1b[2J" + std::string(5000, '9'), "4", ""));
  EXPECT_LT(rule.size(), 200u) << rule;
  for (unsigned char c : rule) EXPECT_GE(c, 0x20) << rule;
}

// Claims of 10^9 vertices and 4 * 10^6 faces in a file of a few hundred bytes: refused by
// the size rule, before the body is scanned, and without allocating for the counts. A child
// process checks them with 16 MiB of address space over what it has mapped: storage for the
// claims (12 GB of float vertices, 48 MB of faces' indices) would not fit, the guard's own
// few kilobytes fit many times over.
TEST(PlyGuard, HugeClaimsAreRefusedBeforeTheBodyWithoutAllocatingForThem) {
  const std::string vertices = ascii("1000000000", "4", kTetraVerts + kTetraFaces);
  const std::string faces = ascii("4", "4000000", kTetraVerts + kTetraFaces);
  EXPECT_REFUSED(vertices, "declares 1000000000 vertices but the file has only");
  EXPECT_REFUSED(faces, "declares 4 vertices and 4000000 faces but the file has only");
  const auto refused = [&] {
    return refusal(vertices).find("but the file has only") != std::string::npos &&
                   refusal(faces).find("but the file has only") != std::string::npos
               ? 0
               : 1;
  };
  EXPECT_EQ(test::exit_code_within_address_space(uint64_t{16} << 20, refused), 0)
      << "100: the guard allocated more than 16 MiB";
}

}  // namespace
}  // namespace cutaway
