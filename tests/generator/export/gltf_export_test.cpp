// glTF export of DS models (generator/export/gltf_export.h): structure read back with tinygltf,
// colours and winding of the two sides, determinism, and the Khronos validator.
#include "export/gltf_export.h"

#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include <tiny_gltf.h>

#include "io/template_parser.h"
#include "model/model_builder.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

const DsModel& fixture_model(const std::string& name) {
  static std::map<std::string, DsModel> cache;
  auto it = cache.find(name);
  if (it == cache.end()) {
    const auto path = test::source_path("tests/data/" + name + ".yaml");
    it = cache.emplace(name, build_model(load_template(path.string()))).first;
  }
  return it->second;
}

tinygltf::Model load_glb(const std::string& bytes) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  const bool ok = loader.LoadBinaryFromMemory(&m, &err, &warn,
                                              reinterpret_cast<const unsigned char*>(bytes.data()),
                                              static_cast<unsigned int>(bytes.size()));
  EXPECT_TRUE(ok) << err << warn;
  return m;
}

/// An accessor's data as a flat array of T (tightly packed views only).
template <class T>
std::vector<T> accessor_data(const tinygltf::Model& m, int index, int components) {
  const auto& a = m.accessors.at(index);
  const auto& v = m.bufferViews.at(a.bufferView);
  EXPECT_TRUE(v.byteStride == 0 || v.byteStride == sizeof(T) * components);
  const auto& buf = m.buffers.at(v.buffer).data;
  const size_t n = a.count * components;
  EXPECT_LE(v.byteOffset + a.byteOffset + n * sizeof(T), buf.size());
  std::vector<T> out(n);
  std::memcpy(out.data(), buf.data() + v.byteOffset + a.byteOffset, n * sizeof(T));
  return out;
}

class GltfExport : public ::testing::TestWithParam<std::string> {};

TEST_P(GltfExport, OneMeshPerSurfaceWithAFrontAndABackPrimitive) {
  const DsModel& model = fixture_model(GetParam());
  const tinygltf::Model m = load_glb(model_to_glb(model, GltfModelOptions{}));
  ASSERT_EQ(m.meshes.size(), model.surfaces.size());
  ASSERT_EQ(m.scenes.size(), 1u);
  EXPECT_EQ(m.scenes[0].nodes.size(), model.surfaces.size());
  EXPECT_EQ(m.asset.version, "2.0");
  for (size_t s = 0; s < model.surfaces.size(); ++s) {
    const DsMesh& mesh = model.surfaces[s].mesh;
    const tinygltf::Mesh& gm = m.meshes[s];
    SCOPED_TRACE(gm.name);
    EXPECT_EQ(gm.name, model.surfaces[s].name);
    ASSERT_EQ(gm.primitives.size(), 2u);
    const auto& front = gm.primitives[0];
    const auto& back = gm.primitives[1];
    EXPECT_EQ(front.attributes.at("POSITION"), back.attributes.at("POSITION"));
    const auto pos = accessor_data<float>(m, front.attributes.at("POSITION"), 3);
    ASSERT_EQ(pos.size(), mesh.n_vertices() * 3);
    const auto& pa = m.accessors[front.attributes.at("POSITION")];
    ASSERT_EQ(pa.minValues.size(), 3u);
    for (size_t i = 0; i < mesh.n_vertices(); ++i) {
      const auto& p = mesh.point(DsMesh::VertexHandle(static_cast<int>(i)));
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(pos[i * 3 + k], static_cast<float>(p[k]));  // metres, object frame
        ASSERT_GE(pos[i * 3 + k], pa.minValues[k]);
        ASSERT_LE(pos[i * 3 + k], pa.maxValues[k]);
      }
    }
    // COLOR_0: linear front colours on the front primitive, back colours on the back one.
    const auto cf = accessor_data<float>(m, front.attributes.at("COLOR_0"), 3);
    const auto cb = accessor_data<float>(m, back.attributes.at("COLOR_0"), 3);
    const auto nf = accessor_data<float>(m, front.attributes.at("NORMAL"), 3);
    const auto nb = accessor_data<float>(m, back.attributes.at("NORMAL"), 3);
    for (size_t i = 0; i < mesh.n_vertices(); ++i) {
      const auto& d = mesh.data(DsMesh::VertexHandle(static_cast<int>(i)));
      double len = 0;
      for (int k = 0; k < 3; ++k) {
        ASSERT_EQ(cf[i * 3 + k], static_cast<float>(d.front[k]));
        ASSERT_EQ(cb[i * 3 + k], static_cast<float>(d.back[k]));
        ASSERT_EQ(nb[i * 3 + k], -nf[i * 3 + k]);
        len += nf[i * 3 + k] * nf[i * 3 + k];
      }
      ASSERT_NEAR(len, 1.0, 1e-5);
    }
    // The back primitive is the front one with every triangle's winding reversed.
    const auto fi = accessor_data<uint32_t>(m, front.indices, 1);
    const auto bi = accessor_data<uint32_t>(m, back.indices, 1);
    ASSERT_EQ(fi.size(), mesh.n_faces() * 3);
    ASSERT_EQ(bi.size(), fi.size());
    size_t f = 0;
    for (auto fh : mesh.faces()) {
      int k = 0;
      for (auto vh : mesh.fv_range(fh)) ASSERT_EQ(fi[f * 3 + k++], static_cast<uint32_t>(vh.idx()));
      ASSERT_EQ(bi[f * 3 + 0], fi[f * 3 + 0]);
      ASSERT_EQ(bi[f * 3 + 1], fi[f * 3 + 2]);
      ASSERT_EQ(bi[f * 3 + 2], fi[f * 3 + 1]);
      ++f;
    }
    // Alpha-blended, single-sided materials: the skin more transparent than the inside.
    for (const auto* prim : {&front, &back}) {
      const auto& mat = m.materials.at(prim->material);
      EXPECT_FALSE(mat.doubleSided);
      EXPECT_EQ(mat.alphaMode, "BLEND");
      EXPECT_DOUBLE_EQ(mat.pbrMetallicRoughness.baseColorFactor[3],
                       s == 0 ? GltfModelOptions{}.skin_alpha : GltfModelOptions{}.inner_alpha);
      EXPECT_EQ(prim->mode, TINYGLTF_MODE_TRIANGLES);
    }
  }
}

TEST_P(GltfExport, IsDeterministicAndPassesTheKhronosValidator) {
  const DsModel& model = fixture_model(GetParam());
  const std::string a = model_to_glb(model, GltfModelOptions{});
  const std::string b = model_to_glb(model, GltfModelOptions{});
  EXPECT_TRUE(a == b);
  const fs::path dir = test::fresh_dir("gltf_export_" + GetParam());
  write_model_glb(dir / "m.glb", model, GltfModelOptions{});
  std::ifstream in(dir / "m.glb", std::ios::binary);
  std::stringstream written;
  written << in.rdbuf();
  EXPECT_TRUE(written.str() == a) << "write_model_glb wrote other bytes";
  EXPECT_EQ(test::files_in(dir), std::vector<std::string>{"m.glb"});  // no temporary left
  const test::GltfReport r = test::validate_gltf(dir / "m.glb");
  EXPECT_EQ(r.errors, 0) << r.output;
}

INSTANTIATE_TEST_SUITE_P(Fixtures, GltfExport,
                         ::testing::Values("nfold_circle", "nfold_polar", "mesh_octahedra"),
                         [](const auto& info) { return info.param; });

TEST(GltfExportOptions, OpaqueAlphaGivesOpaqueMaterials) {
  GltfModelOptions opt;
  opt.skin_alpha = 1.0;
  opt.inner_alpha = 0.5;
  const tinygltf::Model m = load_glb(model_to_glb(fixture_model("mesh_octahedra"), opt));
  ASSERT_EQ(m.meshes.size(), 2u);
  EXPECT_EQ(m.materials.at(m.meshes[0].primitives[0].material).alphaMode, "OPAQUE");
  EXPECT_EQ(m.materials.at(m.meshes[1].primitives[0].material).alphaMode, "BLEND");
  EXPECT_DOUBLE_EQ(
      m.materials.at(m.meshes[1].primitives[1].material).pbrMetallicRoughness.baseColorFactor[3],
      0.5);
}

}  // namespace
}  // namespace cutaway
