// Skin textures (generator/material/skin_texture.h): unwrapping gives every skin triangle of a cut
// piece coordinates that span less than half the texture in u (the seam is split, not
// stretched across the texture), copies only along the seam and at the poles, and the baked
// texture shows the skin's front colour where its vertices map.
#include "io/cut_notation.h"
#include "material/skin_texture.h"

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include "base/colour.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "pieces/cut_spec.h"
#include "pieces/pieces.h"
#include "test_support.h"

namespace cutaway {
namespace {

TEST(SkinTexture, CornersAcrossTheSeamAndAtAPoleUnwrap) {
  ShadedMesh m;
  m.param = {{0.5, 0.95}, {0.5, 0.02}, {0.6, 0.97}, {1.0, 0.0}, {0.9, 0.3}, {0.9, 0.4}};
  const auto seam = skin_corner_uv(m, {0, 1, 2});
  EXPECT_DOUBLE_EQ(seam[0].x, 0.95);
  EXPECT_DOUBLE_EQ(seam[1].x, 1.02);  // continued past 1: the texture repeats in u
  EXPECT_DOUBLE_EQ(seam[2].x, 0.97);
  EXPECT_DOUBLE_EQ(seam[0].y, 0.5);  // v = 1 - t_profile
  const auto pole = skin_corner_uv(m, {3, 4, 5});
  EXPECT_DOUBLE_EQ(pole[0].x, 0.35);  // the pole takes the mean u of the other two
  EXPECT_DOUBLE_EQ(pole[0].y, 0.0);
}

struct Cut {
  Template tmpl;
  DsModel model;
  PieceSet set;
};

const Cut& apple_halves() {
  static const Cut* c = [] {
    auto* out = new Cut;
    out->tmpl = load_template(test::source_path("templates/apple.yaml").string());
    out->model = build_model(out->tmpl);
    const auto diffusion = make_cpu_diffusion(out->model, {8, 0});
    PieceOptions options;
    options.section.edge_m = out->tmpl.edge_m;
    out->set = *cut_pieces(out->model, *parse_cut_spec("plane:y=25", 1e-3), *diffusion, options);
    return out;
  }();
  return *c;
}

TEST(SkinTexture, UnwrappedSkinsSpanLessThanHalfTheTextureAndOnlyCopySeamAndPoles) {
  const Cut& c = apple_halves();
  size_t seam_copies = 0;
  for (const Piece& piece : c.set.pieces) {
    ASSERT_EQ(piece.parts[0].kind, PartKind::Skin);
    ShadedMesh skin = piece.parts[0].mesh;
    const size_t before = skin.position.size();
    const std::vector<glm::dvec2> uv = unwrap_skin(skin);
    ASSERT_EQ(uv.size(), skin.position.size());
    ASSERT_EQ(skin.triangle.size(), piece.parts[0].mesh.triangle.size());
    for (const glm::uvec3& t : skin.triangle) {
      const double lo = std::min({uv[t.x].x, uv[t.y].x, uv[t.z].x});
      const double hi = std::max({uv[t.x].x, uv[t.y].x, uv[t.z].x});
      EXPECT_LT(hi - lo, 0.5);
      EXPECT_GE(lo, 0.0);
      EXPECT_LT(hi, 1.5);
    }
    // Every copy sits where its original does, on the seam (u 0 or 1) or at a pole.
    for (size_t v = before; v < skin.position.size(); ++v) {
      const glm::dvec2 p = skin.param[v];
      const bool pole = p.x <= 1e-12 || p.x >= 1 - 1e-12;
      const bool seam = std::fabs(uv[v].x - std::round(uv[v].x)) < 1e-9 || p.y < 0.02 || p.y > 0.98;
      EXPECT_TRUE(pole || seam) << "copy at t = (" << p.x << ", " << p.y << ")";
      seam_copies += seam && !pole;
    }
  }
  EXPECT_GT(seam_copies, 0u);  // both halves straddle t_section = 0
}

/// The apple halves' skins, unwrapped, and the pointers bake_skin_texture takes.
struct UnwrappedSkins {
  std::vector<ShadedMesh> skins;
  std::vector<std::vector<glm::dvec2>> uv;
  std::vector<const ShadedMesh*> parts;
  std::vector<const std::vector<glm::dvec2>*> part_uv;

  explicit UnwrappedSkins(const Cut& c) {
    for (const Piece& piece : c.set.pieces) {
      skins.push_back(piece.parts[0].mesh);
      uv.push_back(unwrap_skin(skins.back()));
    }
    for (size_t k = 0; k < skins.size(); ++k) {
      parts.push_back(&skins[k]);
      part_uv.push_back(&uv[k]);
    }
  }
};

TEST(SkinTexture, TheTextureShowsTheSkinColourWhereItsVerticesMap) {
  const Cut& c = apple_halves();
  const UnwrappedSkins unwrapped(c);
  const auto& [skins, uv, parts, part_uv] = unwrapped;
  const SkinTextureOptions options;
  const glm::ivec2 size = skin_texture_size(c.model.skin(), options);
  // An 80 mm apple: about 250 mm around and 100 mm along its profile.
  EXPECT_GT(size.x, 400);
  EXPECT_LT(size.x, 600);
  EXPECT_GT(size.y, 120);
  EXPECT_EQ(size.x % 4, 0);  // GPU block compression's block
  EXPECT_EQ(size.y % 4, 0);
  SkinTextureOptions powers = options;
  powers.power_of_two = true;
  const glm::ivec2 p2 = skin_texture_size(c.model.skin(), powers);
  EXPECT_EQ(p2.x & (p2.x - 1), 0) << p2.x;  // 512: the next power of two
  EXPECT_EQ(p2.y & (p2.y - 1), 0) << p2.y;
  EXPECT_GE(p2.x, size.x);
  EXPECT_LT(p2.x, 2 * size.x);
  const std::vector<uint8_t> a =
      bake_skin_texture(parts, part_uv, size, nullptr, nullptr, 0, options).srgb;
  const std::vector<uint8_t> b =
      bake_skin_texture(parts, part_uv, size, nullptr, nullptr, 0, options).srgb;
  ASSERT_EQ(a.size(), static_cast<size_t>(size.x) * size.y * 3);
  EXPECT_EQ(a, b);
  // Every vertex away from the poles: the texel it maps to shows its colour (the skin's colour
  // varies slowly; the rasteriser interpolates it linearly).
  double sum = 0, worst = 0;
  size_t n = 0;
  for (size_t k = 0; k < skins.size(); ++k)
    for (size_t v = 0; v < skins[k].position.size(); ++v) {
      const double tp = skins[k].param[v].x;
      if (tp < 0.05 || tp > 0.95) continue;
      const int x = static_cast<int>(std::floor(uv[k][v].x * size.x)) % size.x;
      const int y = std::clamp(static_cast<int>(uv[k][v].y * size.y), 0, size.y - 1);
      const size_t i = 3 * (static_cast<size_t>(y) * size.x + x);
      const glm::dvec3 want = 255.0 * linear_to_srgb(skins[k].colour[v]);
      const double e = std::max(
          {std::fabs(a[i] - want.x), std::fabs(a[i + 1] - want.y), std::fabs(a[i + 2] - want.z)});
      sum += e;
      worst = std::max(worst, e);
      ++n;
    }
  ASSERT_GT(n, 200u);
  std::printf("skin texels vs vertex colours over %zu vertices: mean %.2f, max %.2f (of 255)\n", n,
              sum / n, worst);
  EXPECT_LT(sum / n, 2.0);
  EXPECT_LT(worst, 12.0);
  EXPECT_FALSE(bake_skin_texture(parts, part_uv, size, nullptr, nullptr, 0, options).relief);
}

TEST(SkinTexture, ARaisedNetTiltsTheNormalMapOnItsLinesOnly) {
  const Cut& c = apple_halves();
  const UnwrappedSkins unwrapped(c);
  const auto& [skins, uv, parts, part_uv] = unwrapped;
  SkinPatternLayer net;
  net.kind = SkinPatternLayer::Kind::Net;
  net.spacing_m = 0.012;
  net.size_m = 0.002;
  net.softness = 0.8;
  net.opacity = 0;
  net.relief_m = 0.0005;
  const SkinPatterns patterns({net}, 5);
  const SkinTextureOptions options;
  const glm::ivec2 size = skin_texture_size(c.model.skin(), options);
  const SkinTexture baked = bake_skin_texture(parts, part_uv, size, &patterns, nullptr, 0, options);
  ASSERT_TRUE(baked.relief);
  const ReliefMaps& relief = *baked.relief;
  ASSERT_EQ(relief.normal.size(), static_cast<size_t>(size.x) * size.y * 3);
  ASSERT_EQ(relief.height.size(), static_cast<size_t>(size.x) * size.y);
  EXPECT_NEAR(relief.low_m, 0.0, 1e-9);
  EXPECT_NEAR(relief.high_m, 0.0005, 1e-5);
  // Opacity 0: the colour is the plain skin's.
  EXPECT_EQ(baked.srgb, bake_skin_texture(parts, part_uv, size, nullptr, nullptr, 0, options).srgb);
  // Away from the poles: texels inside the cells (height 0, no line within two texels) are flat,
  // (128, 128, 255); a good share of the texels on the lines' flanks tilt.
  size_t flat_cells = 0, tilted_cells = 0, tilted_lines = 0, lines = 0;
  for (int y = size.y / 8; y < size.y - size.y / 8; ++y)
    for (int x = 0; x < size.x; ++x) {
      const size_t i = static_cast<size_t>(y) * size.x + x;
      const bool tilted =
          std::abs(relief.normal[3 * i] - 128) > 3 || std::abs(relief.normal[3 * i + 1] - 128) > 3;
      bool near_line = false;
      for (int dy = -2; dy <= 2; ++dy)
        for (int dx = -2; dx <= 2; ++dx) {
          const size_t j = static_cast<size_t>(y + dy) * size.x + (x + dx + size.x) % size.x;
          near_line = near_line || relief.height[j] > 0;
        }
      if (!near_line) {
        ++(tilted ? tilted_cells : flat_cells);
        EXPECT_GE(relief.normal[3 * i + 2], 250);
      } else if (relief.height[i] > 0 && relief.height[i] < 255) {
        ++lines;
        tilted_lines += tilted;
      }
    }
  EXPECT_EQ(tilted_cells, 0u);
  EXPECT_GT(flat_cells, 1000u);
  ASSERT_GT(lines, 1000u);
  EXPECT_GT(tilted_lines, lines / 2) << tilted_lines << " of " << lines;
}

}  // namespace
}  // namespace cutaway
