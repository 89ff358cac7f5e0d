// The anatomy of the shipped templates, measured where a user sees it: the cut face's baked
// texture in the glTF file `cutaway piece` writes (doc/templates.md, Anatomy).
// - The kiwi's black seeds cover at least 2 % of a cut face at mid height with a luminance under
//   15 % of white (they were pale rings once: a blur sheet ran through them).
#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <tiny_gltf.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "base/colour.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

/// The floats of a float accessor (tightly packed or strided).
std::vector<float> floats_of(const tinygltf::Model& m, int accessor, int components) {
  const tinygltf::Accessor& a = m.accessors.at(static_cast<size_t>(accessor));
  EXPECT_EQ(a.componentType, TINYGLTF_COMPONENT_TYPE_FLOAT);
  const tinygltf::BufferView& v = m.bufferViews.at(static_cast<size_t>(a.bufferView));
  const size_t stride = v.byteStride ? v.byteStride : sizeof(float) * components;
  const unsigned char* base = m.buffers[0].data.data() + v.byteOffset + a.byteOffset;
  std::vector<float> out(a.count * components);
  for (size_t i = 0; i < a.count; ++i)
    std::memcpy(&out[i * components], base + i * stride, sizeof(float) * components);
  return out;
}

/// The indices of a primitive.
std::vector<uint32_t> indices_of(const tinygltf::Model& m, const tinygltf::Primitive& prim) {
  const tinygltf::Accessor& a = m.accessors.at(static_cast<size_t>(prim.indices));
  const tinygltf::BufferView& v = m.bufferViews.at(static_cast<size_t>(a.bufferView));
  const unsigned char* base = m.buffers[0].data.data() + v.byteOffset + a.byteOffset;
  std::vector<uint32_t> out(a.count);
  for (size_t i = 0; i < a.count; ++i) {
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) {
      uint16_t s;
      std::memcpy(&s, base + 2 * i, 2);
      out[i] = s;
    } else {
      std::memcpy(&out[i], base + 4 * i, 4);
    }
  }
  return out;
}

/// Of the texels of the cut texture `image_name` that the cut faces' triangles cover (their
/// UVs rasterised at the texture's resolution, texel centres), how many there are and how many
/// have a relative luminance (linear RGB) under `dark`.
struct CutFaceTexels {
  size_t face = 0, dark = 0;
};

CutFaceTexels cut_face_texels(const fs::path& glb, const std::string& image_name, double dark) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  CutFaceTexels out;
  EXPECT_TRUE(loader.LoadBinaryFromFile(&m, &err, &warn, glb.string())) << err;
  int image = -1;
  for (size_t i = 0; i < m.images.size(); ++i)
    if (m.images[i].name == image_name) image = static_cast<int>(i);
  EXPECT_GE(image, 0) << image_name;
  if (image < 0) return out;
  const tinygltf::BufferView& iv =
      m.bufferViews.at(static_cast<size_t>(m.images[image].bufferView));
  int w = 0, h = 0, n = 0;
  unsigned char* px = stbi_load_from_memory(m.buffers[0].data.data() + iv.byteOffset,
                                            static_cast<int>(iv.byteLength), &w, &h, &n, 3);
  EXPECT_NE(px, nullptr);
  if (!px) return out;
  std::vector<uint8_t> covered(static_cast<size_t>(w) * h, 0);
  for (const tinygltf::Mesh& mesh : m.meshes)
    for (const tinygltf::Primitive& prim : mesh.primitives) {
      if (prim.material < 0 || !prim.attributes.count("TEXCOORD_0")) continue;
      const int tex = m.materials[prim.material].pbrMetallicRoughness.baseColorTexture.index;
      if (tex < 0 || m.textures[tex].source != image) continue;
      const std::vector<float> uv = floats_of(m, prim.attributes.at("TEXCOORD_0"), 2);
      const std::vector<uint32_t> idx = indices_of(m, prim);
      for (size_t t = 0; t + 2 < idx.size(); t += 3) {
        double x[3], y[3];
        for (int k = 0; k < 3; ++k) {
          x[k] = uv[2 * idx[t + k]] * w;
          y[k] = uv[2 * idx[t + k] + 1] * h;
        }
        const double area = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
        if (area == 0) continue;
        const int x0 = std::max(0, static_cast<int>(std::floor(std::min({x[0], x[1], x[2]}))));
        const int x1 = std::min(w - 1, static_cast<int>(std::ceil(std::max({x[0], x[1], x[2]}))));
        const int y0 = std::max(0, static_cast<int>(std::floor(std::min({y[0], y[1], y[2]}))));
        const int y1 = std::min(h - 1, static_cast<int>(std::ceil(std::max({y[0], y[1], y[2]}))));
        for (int j = y0; j <= y1; ++j)
          for (int i = x0; i <= x1; ++i) {
            const double px_ = i + 0.5, py = j + 0.5;
            bool inside = true;
            for (int k = 0; k < 3 && inside; ++k) {
              const int a = k, b = (k + 1) % 3;
              const double e = (x[b] - x[a]) * (py - y[a]) - (px_ - x[a]) * (y[b] - y[a]);
              inside = area > 0 ? e >= 0 : e <= 0;
            }
            if (inside) covered[static_cast<size_t>(j) * w + i] = 1;
          }
      }
    }
  for (size_t t = 0; t < covered.size(); ++t) {
    if (!covered[t]) continue;
    ++out.face;
    const glm::dvec3 c =
        srgb_to_linear(glm::dvec3(px[3 * t], px[3 * t + 1], px[3 * t + 2]) / 255.0);
    out.dark += 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b < dark;
  }
  stbi_image_free(px);
  return out;
}

TEST(Anatomy, KiwiSeedsAreDarkOnTheBakedCutFace) {
  const fs::path dir = test::fresh_dir("anatomy_kiwi");
  for (const int seed : {1, 2, 3}) {
    const fs::path glb = dir / ("kiwi" + std::to_string(seed) + ".glb");
    const test::RunResult r = test::run_cutaway(
        {"piece", test::source_path("templates/kiwi.yaml").string(), "--seed", std::to_string(seed),
         "--cut", "plane:y=35", "--compress", "none", "--textures", "png", "-o", glb.string()});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const CutFaceTexels t = cut_face_texels(glb, "kiwi_cut", 0.15);
    ASSERT_GT(t.face, 10000u);
    const double share = static_cast<double>(t.dark) / t.face;
    std::printf("kiwi seed %d: %zu of %zu cut-face texels under 15 %% luminance (%.2f %%)\n", seed,
                t.dark, t.face, 100 * share);
    EXPECT_GE(share, 0.02) << "seed " << seed;
  }
}

}  // namespace
}  // namespace cutaway
