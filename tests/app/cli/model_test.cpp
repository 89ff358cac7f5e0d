// `cutaway model` end to end for every shipped template: exit code, glb (Khronos validator, one
// mesh per surface with two primitives), PNG (size, not flat), byte-identical reruns, and
// refusals that leave nothing behind.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <set>
#include <sstream>

#include <stb/stb_image.h>
#include <tiny_gltf.h>

#include "io/template_parser.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

uint32_t big_endian_u32(const std::string& s, size_t at) {
  uint32_t v = 0;
  for (size_t i = 0; i < 4; ++i) v = v << 8 | static_cast<unsigned char>(s.at(at + i));
  return v;
}

constexpr int kSize = 160;

class ModelCommand : public ::testing::TestWithParam<fs::path> {};

TEST_P(ModelCommand, WritesAValidGlbAndAPngDeterministically) {
  const fs::path tmpl = GetParam();
  const std::string stem = tmpl.stem().string();
  std::string runs[2][2];  // [run][glb, png]
  for (int run = 0; run < 2; ++run) {
    const fs::path dir = test::fresh_dir("cli_model_" + stem + "_" + std::to_string(run));
    const test::RunResult r =
        test::run_cutaway({"model", tmpl.string(), "-o", (dir / "x.glb").string(), "--png",
                           (dir / "x.png").string(), "--size", std::to_string(kSize)});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    ASSERT_EQ(test::files_in(dir), (std::vector<std::string>{"x.glb", "x.png"}));
    runs[run][0] = test::read_file(dir / "x.glb");
    runs[run][1] = test::read_file(dir / "x.png");
    if (run == 0) {
      const test::GltfReport v = test::validate_gltf(dir / "x.glb");
      EXPECT_EQ(v.errors, 0) << v.output;
    }
  }
  EXPECT_TRUE(runs[0][0] == runs[1][0]) << "the glb differs between two runs";
  EXPECT_TRUE(runs[0][1] == runs[1][1]) << "the PNG differs between two runs";

  // glb: one mesh per surface, each with a front and a back primitive.
  const Template t = load_template(tmpl.string());
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  const std::string& glb = runs[0][0];
  ASSERT_TRUE(loader.LoadBinaryFromMemory(&m, &err, &warn,
                                          reinterpret_cast<const unsigned char*>(glb.data()),
                                          static_cast<unsigned int>(glb.size())))
      << err;
  ASSERT_EQ(m.meshes.size(), t.surfaces.size());
  std::set<std::string> names;
  for (const auto& mesh : m.meshes) {
    EXPECT_EQ(mesh.primitives.size(), 2u) << mesh.name;
    names.insert(mesh.name);
  }
  for (const auto& s : t.surfaces) EXPECT_TRUE(names.count(s.name)) << s.name;
  EXPECT_EQ(m.meshes[0].name, t.surfaces[t.skin].name);  // the skin first

  // PNG: signature, IHDR size, and a picture that is not one flat colour.
  const std::string& png = runs[0][1];
  ASSERT_GT(png.size(), 33u);
  EXPECT_EQ(png.substr(0, 8), std::string("\x89PNG\r\n\x1a\n", 8));
  EXPECT_EQ(png.substr(12, 4), "IHDR");
  EXPECT_EQ(big_endian_u32(png, 16), static_cast<uint32_t>(kSize));
  EXPECT_EQ(big_endian_u32(png, 20), static_cast<uint32_t>(kSize));
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels = stbi_load_from_memory(reinterpret_cast<const unsigned char*>(png.data()),
                                                static_cast<int>(png.size()), &w, &h, &channels, 4);
  ASSERT_NE(pixels, nullptr) << stbi_failure_reason();
  EXPECT_EQ(w, kSize);
  EXPECT_EQ(h, kSize);
  size_t differing = 0;
  for (int i = 0; i < w * h; ++i) differing += std::memcmp(pixels + 4 * i, pixels, 4) != 0;
  stbi_image_free(pixels);
  EXPECT_GT(differing, static_cast<size_t>(w * h / 20)) << "the picture is (nearly) flat";
}

std::string template_name(const ::testing::TestParamInfo<fs::path>& info) {
  std::string n = info.param.stem().string();
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Shipped, ModelCommand, ::testing::ValuesIn(test::shipped_templates()),
                         template_name);

TEST(ModelCommandRefuses, AWrongOutputExtensionWithExitCodeTwoAndNoFile) {
  const fs::path dir = test::fresh_dir("cli_model_wrong_extension");
  const std::string tmpl = test::source_path("templates/spheres.yaml").string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"model", tmpl, "-o", (dir / "x.gltf").string()},
           {"model", tmpl, "-o", (dir / "x.gltf").string(), "--png", (dir / "x.png").string()},
           {"model", tmpl, "-o", (dir / "x.glb").string(), "--png", (dir / "x.jpg").string()}}) {
    const test::RunResult r = test::run_cutaway(args);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("must end in"), std::string::npos) << r.err;
    EXPECT_TRUE(test::files_in(dir).empty());
  }
}

TEST(ModelCommandRefuses, ABadTemplateWithExitCodeTwoAndNoFile) {
  const fs::path dir = test::fresh_dir("cli_model_bad_template");
  std::ofstream(dir / "bad.yaml") << "format: cutaway-template/1\nname: bad\n";
  const test::RunResult r =
      test::run_cutaway({"model", (dir / "bad.yaml").string(), "-o", (dir / "x.glb").string(),
                         "--png", (dir / "x.png").string()});
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("bad.yaml"), std::string::npos) << r.err;
  EXPECT_EQ(test::files_in(dir), std::vector<std::string>{"bad.yaml"});
}

}  // namespace
}  // namespace cutaway
