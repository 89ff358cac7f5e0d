// Texture images (generator/export/texture_image.h): JPEG base colours stay close to the baked
// texels at a fraction of the PNG's bytes, material maps stay PNG, encoding is deterministic, and
// file names and MIME types follow the format.
#include "export/texture_image.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include "io/cut_notation.h"
#include "io/template_parser.h"
#include "material/cap_atlas.h"
#include "model/model_builder.h"
#include "pieces/cut_spec.h"
#include "test_support.h"

namespace cutaway {
namespace {

/// The Perlin-modulated cap atlas of a tomato cut in 8 wedges, at the market scene's density
/// (3 texels per mm).
CapAtlas tomato_cap_atlas() {
  const Template tmpl = load_template(test::source_path("templates/tomato.yaml").string());
  const DsModel model = build_model(tmpl);
  const auto diffusion = make_cpu_diffusion(model, {16, 0});
  PieceOptions options;
  options.section.edge_m = tmpl.edge_m;
  const PieceSet set = *cut_pieces(model, *parse_cut_spec("wedges:8", 1e-3), *diffusion, options);
  std::vector<const Piece*> pieces;
  for (const Piece& p : set.pieces) pieces.push_back(&p);
  const ColourModulation modulation(tmpl.npr, 7);
  CapAtlasOptions atlas_options;
  atlas_options.texels_per_m = 3000;
  return bake_cap_atlas(pieces, set.sections, &modulation, 1.0, atlas_options);
}

TEST(TextureImage, JpegBaseColoursStayCloseAtAFractionOfThePngBytes) {
  const CapAtlas atlas = tomato_cap_atlas();
  const AssetTexture texture{"tomato_cut", atlas.width, atlas.height, 3, atlas.srgb};
  const std::string png = encode_texture(texture, TextureFormat::Png);
  const std::string jpeg = encode_texture(texture, TextureFormat::Jpeg);
  EXPECT_EQ(jpeg, encode_texture(texture, TextureFormat::Jpeg));  // deterministic
  int w = 0, h = 0, n = 0;
  std::unique_ptr<uint8_t, void (*)(void*)> decoded(
      stbi_load_from_memory(reinterpret_cast<const uint8_t*>(jpeg.data()),
                            static_cast<int>(jpeg.size()), &w, &h, &n, 3),
      stbi_image_free);
  ASSERT_TRUE(decoded);
  ASSERT_EQ(w, texture.width);
  ASSERT_EQ(h, texture.height);
  // The error on the islands' texels, the largest of the three channels' in sRGB steps.
  double sum = 0;
  size_t texels = 0, over_8 = 0;
  for (size_t i = 0; i < texture.pixels.size(); i += 3) {
    const uint8_t* p = &texture.pixels[i];
    if (!atlas.covered[i / 3]) continue;
    int worst = 0;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, std::abs(int(decoded.get()[i + c]) - p[c]));
    sum += worst;
    over_8 += worst > 8 ? 1 : 0;
    ++texels;
  }
  ASSERT_GT(texels, 10000u);
  const double mean = sum / static_cast<double>(texels);
  std::printf("tomato wedge atlas %d x %d: png %zu bytes, jpeg %zu bytes (%.1fx); jpeg error on "
              "%zu island texels: mean %.2f/255, %.2f %% over 8/255\n",
              texture.width, texture.height, png.size(), jpeg.size(),
              double(png.size()) / double(jpeg.size()), texels, mean,
              100.0 * double(over_8) / double(texels));
  // Measured: png 225 KB, jpeg 22.5 KB (10x); mean 1.95/255, 0.18 % of texels over 8/255
  // (the largest channel error; luma errors are a third of it: the error is mostly the 2 x 2
  // chroma subsampling, half a pixel where the texels are twice what the camera resolves).
  EXPECT_LT(jpeg.size() * 5, png.size());
  EXPECT_LT(mean, 2.5);
  EXPECT_LT(double(over_8), 0.005 * double(texels));
}

TEST(TextureImage, MaterialMapsStayPngAndNamesFollowTheFormat) {
  SceneAssets assets;
  assets.textures.push_back({"a cut", 2, 2, 3, std::vector<uint8_t>(12, 100)});
  assets.textures.push_back({"cut_material", 2, 2, 4, std::vector<uint8_t>(16, 200)});
  EXPECT_EQ(texture_file_names("out/salad.pov", assets, TextureFormat::Jpeg),
            (std::vector<std::string>{"salad_a_cut.jpg", "salad_cut_material.png"}));
  EXPECT_EQ(texture_file_names("out/salad.gltf", assets, TextureFormat::Png),
            (std::vector<std::string>{"salad_a_cut.png", "salad_cut_material.png"}));
  EXPECT_STREQ(texture_mime_type(assets.textures[0], TextureFormat::Jpeg), "image/jpeg");
  EXPECT_STREQ(texture_mime_type(assets.textures[1], TextureFormat::Jpeg), "image/png");
  // The encoded bytes are of the kind the name says (JPEG's SOI marker, PNG's signature).
  EXPECT_EQ(encode_texture(assets.textures[0], TextureFormat::Jpeg).substr(0, 2), "\xFF\xD8");
  EXPECT_EQ(encode_texture(assets.textures[1], TextureFormat::Jpeg).substr(1, 3), "PNG");
  EXPECT_EQ(parse_texture_format("jpeg"), TextureFormat::Jpeg);
  EXPECT_EQ(parse_texture_format("png"), TextureFormat::Png);
  EXPECT_THROW(parse_texture_format("jpg"), InternalError);
  assets.textures[0].pixels.pop_back();
  EXPECT_THROW(encode_texture(assets.textures[0], TextureFormat::Jpeg), InternalError);
}

}  // namespace
}  // namespace cutaway
