// `mesh` surfaces read from PLY (io/mesh_file.h, model/mesh_surface.h): ASCII and binary
// little-endian files, per-vertex DS attributes as uchar or float sRGB, blur in template units,
// fallbacks, refusals.
#include "io/mesh_file.h"
#include "model/mesh_surface.h"

#include <gtest/gtest.h>

#include <array>
#include <cstring>
#include <fstream>
#include <optional>

#include "base/colour.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// What to put in a test PLY file.
struct PlySpec {
  bool binary = false;
  /// "": no colour properties; "uchar" / "float": all six of that type; "mixed": red uchar,
  /// green and blue float.
  std::string colours;
  bool blur = false;
  bool drop_last_face = false;  ///< an open mesh
  bool reverse = false;         ///< every face wound the other way (inwards)
  bool isolated = false;        ///< an extra vertex no face uses, written first
};

/// A closed octahedron of radius 10 (file units), outward winding; vertex i has front colour
/// (10 i, 20 i, 30 i) / 255 sRGB, back colour (255 - 10 i, 100, 5 i) / 255 and blur 0.5 i.
constexpr double kRadius = 10;
const double kVerts[6][3] = {{kRadius, 0, 0},  {-kRadius, 0, 0}, {0, kRadius, 0},
                             {0, -kRadius, 0}, {0, 0, kRadius},  {0, 0, -kRadius}};
const int kFaces[8][3] = {{0, 2, 4}, {4, 2, 1}, {1, 2, 5}, {5, 2, 0},
                          {4, 3, 0}, {1, 3, 4}, {5, 3, 1}, {0, 3, 5}};

glm::dvec3 front_srgb_255(int i) { return {10.0 * i, 20.0 * i, 30.0 * i}; }
glm::dvec3 back_srgb_255(int i) { return {255.0 - 10 * i, 100.0, 5.0 * i}; }

template <class T>
void put(std::string& out, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  out.append(b, sizeof(T));
}

void write_ply(const fs::path& file, const PlySpec& s) {
  static const char* names[6] = {"front_red", "front_green", "front_blue",
                                 "back_red",  "back_green",  "back_blue"};
  const int nfaces = s.drop_last_face ? 7 : 8;
  std::string h = "ply\nformat ";
  h += s.binary ? "binary_little_endian 1.0\n" : "ascii 1.0\n";
  h += "comment cutaway mesh_surface_test\nelement vertex " + std::to_string(s.isolated ? 7 : 6) +
       "\n";
  h += "property float x\nproperty float y\nproperty float z\n";
  auto is_uchar = [&](int k) {
    return s.colours == "uchar" || (s.colours == "mixed" && k % 3 == 0);
  };
  if (!s.colours.empty()) {
    for (int k = 0; k < 6; ++k)
      h += std::string("property ") + (is_uchar(k) ? "uchar " : "float ") + names[k] + "\n";
  }
  if (s.blur) h += "property float blur\n";
  h += "element face " + std::to_string(nfaces) + "\nproperty list uchar int vertex_indices\n";
  h += "end_header\n";
  std::string body;
  for (int j = s.isolated ? -1 : 0; j < 6; ++j) {
    const int i = std::max(j, 0);
    const glm::dvec3 f = j < 0 ? glm::dvec3(255) : front_srgb_255(i);
    const glm::dvec3 b = j < 0 ? glm::dvec3(255) : back_srgb_255(i);
    const double c[6] = {f.x, f.y, f.z, b.x, b.y, b.z};
    if (s.binary) {
      for (double x : kVerts[i]) put(body, static_cast<float>(x));
      if (!s.colours.empty()) {
        for (int k = 0; k < 6; ++k) {
          if (is_uchar(k)) put(body, static_cast<unsigned char>(c[k]));
          else put(body, static_cast<float>(c[k] / 255.0));
        }
      }
      if (s.blur) put(body, static_cast<float>(0.5 * i));
    } else {
      std::ostringstream line;
      line.precision(9);
      line << kVerts[i][0] << " " << kVerts[i][1] << " " << kVerts[i][2];
      if (!s.colours.empty()) {
        for (int k = 0; k < 6; ++k) {
          if (is_uchar(k)) line << " " << static_cast<int>(c[k]);
          else line << " " << c[k] / 255.0;
        }
      }
      if (s.blur) line << " " << 0.5 * i;
      body += line.str() + "\n";
    }
  }
  for (int f = 0; f < nfaces; ++f) {
    int c[3] = {kFaces[f][0], kFaces[f][1], kFaces[f][2]};
    if (s.reverse) std::swap(c[1], c[2]);
    for (int& v : c) v += s.isolated ? 1 : 0;
    if (s.binary) {
      put(body, static_cast<unsigned char>(3));
      for (int v : c) put(body, static_cast<int32_t>(v));
    } else {
      body += "3 " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
              std::to_string(c[2]) + "\n";
    }
  }
  std::ofstream(file, std::ios::binary) << h << body;
}

/// A template with one mesh surface (the skin, or a non-skin surface inside a big skin).
std::string mesh_template(const std::string& file, const std::string& units, bool as_skin,
                          const std::string& extra = "") {
  std::string t = "format: cutaway-template/1\nname: meshy\nunits: " + units +
                  "\nsymmetry: {type: none}\nresolution: {edge: 1}\nsurfaces:\n";
  if (!as_skin) t += "  - {name: outer, kind: mesh, role: skin, file: big.ply}\n";
  t += "  - name: part\n    kind: mesh\n    file: " + file + "\n";
  if (as_skin) t += "    role: skin\n";
  t += "    front: \"#ff8000\"\n    back: \"#0040ff\"\n    blur: 0.2\n" + extra;
  return t;
}

/// big.ply: a closed octahedron of radius 100 (file units), the skin of mesh_template(.., false).
void write_big_skin(const fs::path& dir) {
  std::ofstream(dir / "big.ply") << "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\n"
                                    "property float y\nproperty float z\nelement face 8\n"
                                    "property list uchar int vertex_indices\nend_header\n"
                                    "100 0 0\n-100 0 0\n0 100 0\n0 -100 0\n0 0 100\n0 0 -100\n"
                                    "3 0 2 4\n3 4 2 1\n3 1 2 5\n3 5 2 0\n3 4 3 0\n3 1 3 4\n"
                                    "3 5 3 1\n3 0 3 5\n";
}

/// Imports the template's surface named "part".
DsSurface import_part(const fs::path& dir, const std::string& text) {
  const Template t = parse_template(text, (dir / "t.yaml").string(), dir.string());
  for (const auto& s : t.surfaces)
    if (s.name == "part") return mesh_surface(s, t);
  ADD_FAILURE() << "no surface 'part'";
  return {};
}

void expect_file_colours(const DsSurface& s, double tol) {
  ASSERT_EQ(s.mesh.n_vertices(), 6u);
  for (int i = 0; i < 6; ++i) {
    const auto& d = s.mesh.data(DsMesh::VertexHandle(i));
    const glm::dvec3 f = srgb_to_linear(front_srgb_255(i) / 255.0);
    const glm::dvec3 b = srgb_to_linear(back_srgb_255(i) / 255.0);
    for (int k = 0; k < 3; ++k) {
      EXPECT_NEAR(d.front[k], f[k], tol) << "vertex " << i << " front " << k;
      EXPECT_NEAR(d.back[k], b[k], tol) << "vertex " << i << " back " << k;
    }
  }
}

struct Format {
  bool binary;
  std::string colours;
};

class MeshImportColours : public ::testing::TestWithParam<Format> {};

TEST_P(MeshImportColours, PlyColoursBecomeLinearAndBlurScalesByUnits) {
  const Format f = GetParam();
  const fs::path dir = test::fresh_dir("mesh_surface_colours");
  write_ply(dir / "m.ply", {f.binary, f.colours, true});
  const DsSurface s = import_part(dir, mesh_template("m.ply", "cm", true));
  // uchar is exact; float sRGB went through float32.
  expect_file_colours(s, f.colours == "uchar" ? 1e-12 : 1e-6);
  for (int i = 0; i < 6; ++i) {
    const DsMesh::VertexHandle v(i);
    EXPECT_NEAR(s.mesh.data(v).blur, 0.5 * i * 0.01, 1e-9);  // cm -> m
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(s.mesh.point(v)[k], kVerts[i][k] * 0.01, 1e-9);
  }
  EXPECT_EQ(s.mesh.n_faces(), 8u);
  EXPECT_EQ(s.role, SurfaceRole::Skin);
}

INSTANTIATE_TEST_SUITE_P(Formats, MeshImportColours,
                         ::testing::Values(Format{false, "uchar"}, Format{false, "float"},
                                           Format{true, "uchar"}, Format{true, "float"},
                                           Format{false, "mixed"}, Format{true, "mixed"}),
                         [](const auto& info) {
                           return std::string(info.param.binary ? "Binary" : "Ascii") + "_" +
                                  info.param.colours;
                         });

TEST(MeshImport, WithoutPropertiesTheSurfaceColoursApply) {
  for (bool binary : {false, true}) {
    const fs::path dir = test::fresh_dir("mesh_surface_fallback");
    write_ply(dir / "m.ply", {binary, "", false});
    const DsSurface s = import_part(dir, mesh_template("m.ply", "mm", true));
    ASSERT_EQ(s.mesh.n_vertices(), 6u);
    const glm::dvec3 f = srgb_to_linear(glm::dvec3(255, 128, 0) / 255.0);
    const glm::dvec3 b = srgb_to_linear(glm::dvec3(0, 64, 255) / 255.0);
    for (auto v : s.mesh.vertices()) {
      const auto& d = s.mesh.data(v);
      for (int k = 0; k < 3; ++k) {
        EXPECT_DOUBLE_EQ(d.front[k], f[k]);
        EXPECT_DOUBLE_EQ(d.back[k], b[k]);
      }
      EXPECT_DOUBLE_EQ(d.blur, 0.2e-3);  // the surface's blur, mm -> m
    }
  }
}

TEST(MeshImport, BlurFromTheFileOverridesTheSurfaceBlurOnly) {
  const fs::path dir = test::fresh_dir("mesh_surface_blur_only");
  write_ply(dir / "m.ply", {true, "", true});
  const DsSurface s = import_part(dir, mesh_template("m.ply", "mm", true));
  const glm::dvec3 f = srgb_to_linear(glm::dvec3(255, 128, 0) / 255.0);
  for (int i = 0; i < 6; ++i) {
    const auto& d = s.mesh.data(DsMesh::VertexHandle(i));
    EXPECT_NEAR(d.blur, 0.5e-3 * i, 1e-12);
    EXPECT_DOUBLE_EQ(d.front[0], f.x);
  }
}

TEST(MeshImport, AnOpenMeshIsRefusedAsSkinButAcceptedInside) {
  const fs::path dir = test::fresh_dir("mesh_surface_open");
  write_ply(dir / "open.ply", {false, "", false, true});
  try {
    import_part(dir, mesh_template("open.ply", "mm", true));
    FAIL() << "an open skin was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("closed"), std::string::npos) << e.what();
    EXPECT_EQ(e.field(), "surfaces[0].file");
  }
  // Inside a big closed skin, an open mesh is an ordinary (open) DS.
  write_big_skin(dir);
  const std::string text = mesh_template("open.ply", "mm", false);
  const DsSurface s = import_part(dir, text);
  EXPECT_EQ(s.mesh.n_faces(), 7u);
  int boundary = 0;
  for (auto h : s.mesh.halfedges()) boundary += s.mesh.is_boundary(h);
  EXPECT_EQ(boundary, 3);
  const DsModel model = build_model(parse_template(text, (dir / "t.yaml").string(), dir.string()));
  ASSERT_EQ(model.surfaces.size(), 2u);
  EXPECT_EQ(model.surfaces[0].name, "outer");
}

TEST(MeshImport, AClosedMeshWoundInwardsIsTurnedOutwards) {
  for (bool binary : {false, true}) {
    const fs::path dir = test::fresh_dir("mesh_surface_inwards");
    write_ply(dir / "in.ply", {binary, "uchar", false, false, true});
    const DsSurface s = import_part(dir, mesh_template("in.ply", "mm", true));
    const double r = kRadius * 1e-3;
    EXPECT_NEAR(signed_volume(s.mesh), 4.0 / 3.0 * r * r * r, 1e-15);  // octahedron, outward
    expect_file_colours(s, 1e-12);  // front stays the outside's colour
  }
  // An open mesh keeps the file's winding, whichever way it turns.
  const fs::path dir = test::fresh_dir("mesh_surface_open_winding");
  write_ply(dir / "open.ply", {false, "", false, true, true});
  write_big_skin(dir);
  const DsSurface open = import_part(dir, mesh_template("open.ply", "mm", false));
  ASSERT_EQ(open.mesh.n_faces(), 7u);
  std::vector<int> first;
  for (auto v : open.mesh.fv_range(DsMesh::FaceHandle(0))) first.push_back(v.idx());
  // File face 0 is (0, 4, 2) reversed: the same cyclic order.
  const std::vector<int> want{0, 4, 2};
  bool same = false;
  for (int k = 0; k < 3; ++k) {
    same = same ||
           (first[0] == want[k] && first[1] == want[(k + 1) % 3] && first[2] == want[(k + 2) % 3]);
  }
  EXPECT_TRUE(same) << first[0] << " " << first[1] << " " << first[2];
}

TEST(MeshImport, VerticesNoFaceUsesAreLeftOut) {
  const fs::path dir = test::fresh_dir("mesh_surface_isolated");
  write_ply(dir / "iso.ply", {true, "float", true, false, false, true});
  const DsSurface s = import_part(dir, mesh_template("iso.ply", "cm", true));
  ASSERT_EQ(s.mesh.n_vertices(), 6u);
  expect_file_colours(s, 1e-6);
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(s.mesh.data(DsMesh::VertexHandle(i)).blur, 0.5e-2 * i, 1e-9);
    EXPECT_FALSE(s.mesh.is_isolated(DsMesh::VertexHandle(i)));
  }
}

TEST(MeshImport, NonManifoldMeshesAreRefused) {
  const fs::path dir = test::fresh_dir("mesh_surface_non_manifold");
  write_big_skin(dir);
  const std::string header = "ply\nformat ascii 1.0\nelement vertex 6\nproperty float x\n"
                             "property float y\nproperty float z\nelement face %F\n"
                             "property list uchar int vertex_indices\nend_header\n"
                             "10 0 0\n-10 0 0\n0 10 0\n0 -10 0\n0 0 10\n0 0 -10\n";
  auto with_faces = [&](const std::string& faces, int n) {
    std::string h = header;
    h.replace(h.find("%F"), 2, std::to_string(n));
    return h + faces;
  };
  // Three faces on the edge 0-2.
  std::ofstream(dir / "fin.ply") << with_faces("3 0 2 4\n3 2 0 5\n3 0 2 1\n", 3);
  // A closed octahedron with one face flipped.
  std::ofstream(dir / "flip.ply") << with_faces(
      "3 0 4 2\n3 4 2 1\n3 1 2 5\n3 5 2 0\n3 4 3 0\n3 1 3 4\n3 5 3 1\n3 0 3 5\n", 8);
  for (const char* file : {"fin.ply", "flip.ply"}) {
    for (bool skin : {true, false}) {
      try {
        import_part(dir, mesh_template(file, "mm", skin));
        ADD_FAILURE() << file << " was accepted";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("2-manifold"), std::string::npos) << e.what();
      }
    }
  }
}

TEST(MeshImport, AMissingOrForeignFileIsRefused) {
  const fs::path dir = test::fresh_dir("mesh_surface_missing");
  // The skin's file is read while parsing (for the default edge length) or building.
  EXPECT_THROW(build_model(parse_template(mesh_template("nope.ply", "mm", true),
                                          (dir / "t.yaml").string(), dir.string())),
               InputError);
  try {
    import_part(dir, mesh_template("nope.ply", "mm", true));
    FAIL() << "a missing file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos) << e.what();
  }
  write_ply(dir / "m.ply", {false, "uchar", false});
  fs::copy_file(dir / "m.ply", dir / "m.obj");
  EXPECT_THROW(import_part(dir, mesh_template("m.obj", "mm", true)), InputError);
  std::ofstream(dir / "junk.ply") << "this is not a PLY file\n";
  EXPECT_THROW(import_part(dir, mesh_template("junk.ply", "mm", true)), InputError);
  EXPECT_THROW(read_mesh_file((dir / "nope.ply").string(), {}, "f"), InputError);
}

TEST(MeshImport, BoundsAreInMetres) {
  const fs::path dir = test::fresh_dir("mesh_surface_bounds");
  write_ply(dir / "m.ply", {true, "float", true});
  const MeshBounds b = mesh_bounds(read_mesh_file((dir / "m.ply").string(), {}, "f"), 1e-2);
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(b.min[k], -0.1, 1e-12);
    EXPECT_NEAR(b.max[k], 0.1, 1e-12);
  }
}

}  // namespace
}  // namespace cutaway
