// The anatomy of the shipped templates, measured where a user sees it: the cut face's baked
// texture in the glTF file `cutaway piece` writes (doc/templates.md, Anatomy).
// - The kiwi's black seeds cover at least 2 % of a cut face at mid height with a luminance under
//   15 % of white (they were pale rings once: a blur sheet ran through them).
// - A tomato cut across at mid height (the cut that shows all its locules) shows at least 15
//   separate seeds differing from the gel around them by at least 10 % in luminance (they were
//   the gel's colour once).
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

/// The cut texture of a glTF file: its sRGB texels and which of them the cut faces' triangles
/// cover (their UVs rasterised at the texture's resolution, at texel centres).
struct CutFace {
  int width = 0, height = 0;
  std::vector<glm::dvec3> srgb;  ///< width * height, 0..1, row 0 at the top
  std::vector<uint8_t> covered;  ///< width * height
  /// The relative luminance (linear RGB) of texel t.
  double luminance(size_t t) const {
    const glm::dvec3 c = srgb_to_linear(srgb[t]);
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
  }
};

/// The texture image named `image_name` of the .glb and its cut-face coverage.
CutFace cut_face(const fs::path& glb, const std::string& image_name) {
  tinygltf::TinyGLTF loader;
  tinygltf::Model m;
  std::string err, warn;
  CutFace out;
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
  out.width = w;
  out.height = h;
  out.covered.assign(static_cast<size_t>(w) * h, 0);
  for (size_t t = 0; t < out.covered.size(); ++t)
    out.srgb.push_back(glm::dvec3(px[3 * t], px[3 * t + 1], px[3 * t + 2]) / 255.0);
  stbi_image_free(px);
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
            const double cx = i + 0.5, cy = j + 0.5;
            bool inside = true;
            for (int k = 0; k < 3 && inside; ++k) {
              const int a = k, b = (k + 1) % 3;
              const double e = (x[b] - x[a]) * (cy - y[a]) - (cx - x[a]) * (y[b] - y[a]);
              inside = area > 0 ? e >= 0 : e <= 0;
            }
            if (inside) out.covered[static_cast<size_t>(j) * w + i] = 1;
          }
      }
    }
  return out;
}

/// Runs `cutaway piece TEMPLATE --seed SEED --cut CUT` into dir/NAME.glb (float vertices, PNG
/// textures) and returns the file.
fs::path cut_piece(const fs::path& dir, const std::string& name, int seed, const std::string& cut) {
  const fs::path glb = dir / (name + std::to_string(seed) + ".glb");
  const test::RunResult r =
      test::run_cutaway({"piece", test::source_path("templates/" + name + ".yaml").string(),
                         "--seed", std::to_string(seed), "--cut", cut, "--compress", "none",
                         "--textures", "png", "-o", glb.string()});
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return glb;
}

TEST(Anatomy, KiwiSeedsAreDarkOnTheBakedCutFace) {
  const fs::path dir = test::fresh_dir("anatomy_kiwi");
  for (const int seed : {1, 2, 3}) {
    const CutFace f = cut_face(cut_piece(dir, "kiwi", seed, "plane:y=35"), "kiwi_cut");
    size_t face = 0, dark = 0;
    for (size_t t = 0; t < f.covered.size(); ++t) {
      if (!f.covered[t]) continue;
      ++face;
      dark += f.luminance(t) < 0.15;
    }
    ASSERT_GT(face, 10000u);
    const double share = static_cast<double>(dark) / face;
    std::printf("kiwi seed %d: %zu of %zu cut-face texels under 15 %% luminance (%.2f %%)\n", seed,
                dark, face, 100 * share);
    EXPECT_GE(share, 0.02) << "seed " << seed;
  }
}

/// The 4-connected components of the texels `mark` sets, each as its texel indices.
std::vector<std::vector<size_t>> components(const CutFace& f, const std::vector<uint8_t>& mark) {
  std::vector<std::vector<size_t>> out;
  std::vector<uint8_t> seen(mark.size(), 0);
  for (size_t start = 0; start < mark.size(); ++start) {
    if (!mark[start] || seen[start]) continue;
    std::vector<size_t> comp, stack{start};
    seen[start] = 1;
    while (!stack.empty()) {
      const size_t t = stack.back();
      stack.pop_back();
      comp.push_back(t);
      const int x = static_cast<int>(t % f.width), y = static_cast<int>(t / f.width);
      const int nx[4] = {x - 1, x + 1, x, x}, ny[4] = {y, y, y - 1, y + 1};
      for (int k = 0; k < 4; ++k) {
        if (nx[k] < 0 || ny[k] < 0 || nx[k] >= f.width || ny[k] >= f.height) continue;
        const size_t u = static_cast<size_t>(ny[k]) * f.width + nx[k];
        if (mark[u] && !seen[u]) {
          seen[u] = 1;
          stack.push_back(u);
        }
      }
    }
    out.push_back(std::move(comp));
  }
  return out;
}

TEST(Anatomy, ATomatoCutAcrossShowsItsSeedsInTheGel) {
  // A seed: a blob of at least 6 texels near the seeds' colour, whose mean luminance differs
  // from the gel around it (the texels 3 to 4 texels out from its box that are near the gel's
  // colour) by at least 10 %, with gel on at least half of that ring.
  const glm::dvec3 seed_colour = glm::dvec3(0xf4, 0xea, 0xd0) / 255.0;
  const glm::dvec3 gel_colour = glm::dvec3(0xe0, 0xb4, 0x50) / 255.0;
  const fs::path dir = test::fresh_dir("anatomy_tomato");
  for (const int seed : {1, 2, 3}) {
    const CutFace f = cut_face(cut_piece(dir, "tomato", seed, "plane:y=26"), "tomato_cut");
    std::vector<uint8_t> seedlike(f.covered.size(), 0), gellike(f.covered.size(), 0);
    for (size_t t = 0; t < f.covered.size(); ++t) {
      if (!f.covered[t]) continue;
      seedlike[t] = glm::distance(f.srgb[t], seed_colour) < 0.1;
      gellike[t] = glm::distance(f.srgb[t], gel_colour) < 0.15;
    }
    int seeds = 0;
    for (const std::vector<size_t>& blob : components(f, seedlike)) {
      if (blob.size() < 6) continue;
      double lum = 0;
      int x0 = f.width, x1 = 0, y0 = f.height, y1 = 0;
      for (size_t t : blob) {
        lum += f.luminance(t) / blob.size();
        x0 = std::min(x0, static_cast<int>(t % f.width));
        x1 = std::max(x1, static_cast<int>(t % f.width));
        y0 = std::min(y0, static_cast<int>(t / f.width));
        y1 = std::max(y1, static_cast<int>(t / f.width));
      }
      double gel = 0;
      size_t ring = 0, gel_count = 0;
      for (int y = std::max(0, y0 - 4); y <= std::min(f.height - 1, y1 + 4); ++y)
        for (int x = std::max(0, x0 - 4); x <= std::min(f.width - 1, x1 + 4); ++x) {
          if (x >= x0 - 2 && x <= x1 + 2 && y >= y0 - 2 && y <= y1 + 2) continue;
          const size_t t = static_cast<size_t>(y) * f.width + x;
          if (!f.covered[t]) continue;
          ++ring;
          if (gellike[t]) {
            ++gel_count;
            gel += f.luminance(t);
          }
        }
      if (ring == 0 || gel_count * 2 < ring) continue;
      gel /= gel_count;
      seeds += std::fabs(lum - gel) >= 0.1 * gel;
    }
    std::printf("tomato seed %d: %d seeds in the gel of the cut face across\n", seed, seeds);
    EXPECT_GE(seeds, 15) << "seed " << seed;
  }
}

}  // namespace
}  // namespace cutaway
