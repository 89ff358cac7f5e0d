// Golden images (doc/golden-images.md): small seeded renders of a model, a cross-section, the
// halves of a tomato and the tiny scene, each plain and with NPR (Perlin colour modulation and,
// where the renderer draws them, silhouette strokes), compared with tests/golden/*.png.
//
// Tolerance: an image passes when at most 0.5% of its pixels differ from the reference by more
// than 16 (of 255) in some channel; OpenGL runs on OSMesa llvmpipe, deterministic on one
// machine but not byte-identical across Mesa versions. A failing case writes NAME-image.png,
// NAME-reference.png and NAME-difference.png (|image - reference| times 4) under
// build/test-tmp/golden/ and prints their paths. CUTAWAY_UPDATE_GOLDEN=1 writes the references
// instead of comparing (scripts/update-golden.sh).
#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "cut/piece_views.h"
#include "io/cut_notation.h"
#include "io/plane_spec.h"
#include "io/scene_parser.h"
#include "io/template_parser.h"
#include "material/colour_modulation.h"
#include "model/model_builder.h"
#include "npr/silhouettes.h"
#include "pieces/cut_spec.h"
#include "pieces/pieces.h"
#include "render/diffusion_backends.h"
#include "render/model_preview.h"
#include "render/scene_preview.h"
#include "render/section_preview.h"
#include "scene/scene_builder.h"
#include "section/cross_section.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 160, kHeight = 120;
constexpr int kChannelTolerance = 16;     // of 255
constexpr double kPixelFraction = 0.005;  // of all pixels may differ by more
constexpr int kCube = 4;                  // PMVC cube-map texels per face edge: fast

bool updating() {
  const char* v = std::getenv("CUTAWAY_UPDATE_GOLDEN");
  return v != nullptr && std::string(v) == "1";
}

/// Compares `image` with tests/golden/NAME.png (or writes it there when updating).
void check_golden(const std::string& name, const Image& image) {
  const fs::path reference_path = test::source_path("tests/golden/" + name + ".png");
  if (updating()) {
    fs::create_directories(reference_path.parent_path());
    write_png(reference_path, image);
    std::printf("wrote %s\n", reference_path.c_str());
    return;
  }
  const std::string bytes = test::read_file(reference_path);
  ASSERT_FALSE(bytes.empty()) << reference_path << " is missing: run scripts/update-golden.sh";
  int w = 0, h = 0, channels = 0;
  unsigned char* pixels =
      stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                            static_cast<int>(bytes.size()), &w, &h, &channels, 4);
  ASSERT_NE(pixels, nullptr) << reference_path << " is not a PNG";
  Image reference;
  reference.width = w;
  reference.height = h;
  reference.rgba.assign(pixels, pixels + static_cast<size_t>(4) * w * h);
  stbi_image_free(pixels);

  size_t differing = 0;
  Image difference = image;
  const bool same_size = image.width == w && image.height == h;
  if (same_size) {
    for (size_t p = 0; p < static_cast<size_t>(w) * h; ++p) {
      int worst = 0;
      for (int c = 0; c < 3; ++c) {
        const int d = std::abs(int(image.rgba[4 * p + c]) - int(reference.rgba[4 * p + c]));
        worst = std::max(worst, d);
        difference.rgba[4 * p + c] = static_cast<uint8_t>(std::min(255, 4 * d));
      }
      difference.rgba[4 * p + 3] = 255;
      if (worst > kChannelTolerance) ++differing;
    }
  }
  const auto allowed = static_cast<size_t>(kPixelFraction * image.width * image.height);
  if (same_size && differing <= allowed) return;
  const fs::path dir = fs::path(CUTAWAY_TEST_TMP) / "golden";
  fs::create_directories(dir);
  const fs::path out_image = dir / (name + "-image.png");
  const fs::path out_reference = dir / (name + "-reference.png");
  const fs::path out_difference = dir / (name + "-difference.png");
  write_png(out_image, image);
  write_png(out_reference, reference);
  if (same_size) write_png(out_difference, difference);
  ADD_FAILURE() << name << ": " << differing << " pixels differ by more than " << kChannelTolerance
                << " (at most " << allowed << " may); image " << image.width << "x" << image.height
                << ", reference " << w << "x" << h << "\n  image:      " << out_image.string()
                << "\n  reference:  " << out_reference.string()
                << (same_size ? "\n  difference: " + out_difference.string() : std::string());
}

const Template& tomato_template() {
  static const Template t = load_template(test::source_path("templates/tomato.yaml").string());
  return t;
}

std::unique_ptr<DiffusionBackend> cpu_diffusion(const DsModel& model) {
  return make_diffusion(model, {kCube, 0}, DiffusionChoice::Cpu);
}

TEST(Golden, Model) {
  PreviewOptions o;
  o.width = kWidth;
  o.height = kHeight;
  check_golden("model-tomato", render_model_preview(build_model(tomato_template()), o));
}

void section_case(const std::string& name, double perlin) {
  const DsModel model = build_model(tomato_template());
  const auto diffusion = cpu_diffusion(model);
  CrossSection section =
      *make_cross_section(model, *parse_plane_spec("y=26", tomato_template().metres_per_unit),
                          *diffusion, {tomato_template().edge_m});
  if (perlin > 0)
    modulate_colours(section.position, section.colour, tomato_template().npr, perlin, 0);
  SectionPreviewOptions o;
  o.width = kWidth;
  o.height = kHeight;
  check_golden(name, render_section_preview(section, o));
}

TEST(Golden, Section) { section_case("section-tomato", 0); }
TEST(Golden, SectionNpr) { section_case("section-tomato-npr", 1); }

void pieces_case(const std::string& name, double npr) {
  SceneAssets assets;
  assets.name = tomato_template().name;
  const PieceMaterials materials =
      add_piece_materials(assets, tomato_template().name, tomato_template().skin_material,
                          tomato_template().cut_material);
  ObjectCutOptions cut;
  cut.cut = *parse_cut_spec("halves", tomato_template().metres_per_unit);
  cut.perlin = npr;
  cut.cap_colours = CapColours::Vertex;
  ObjectCutStats stats;
  const Variant variant{tomato_template(), build_model(tomato_template())};
  const CutObject object = *cut_object(assets, variant, 0, materials, tomato_template().name,
                                       *cpu_diffusion(variant.model), cut, stats);
  assets = piece_assets(std::move(assets), object, 0.3, kWidth, kHeight);
  StrokeOptions so;
  so.strength = npr;
  const std::vector<Stroke> strokes = extract_strokes(assets, so);
  ScenePreviewOptions o;
  o.strokes = &strokes;
  check_golden(name, render_scene_preview(assets, o));
}

TEST(Golden, Pieces) { pieces_case("pieces-tomato-halves", 0); }
TEST(Golden, PiecesNpr) { pieces_case("pieces-tomato-halves-npr", 1); }

void scene_case(const std::string& name, double npr) {
  Scene scene = load_scene(test::source_path("tests/data/scenes/tiny.yaml").string());
  scene.render.perlin = npr;
  scene.render.silhouettes = npr;
  SceneBuildOptions options;
  options.diffusion = cpu_diffusion;
  const SceneAssets assets = build_scene(scene, scene.seed, options);
  StrokeOptions so;
  so.width = kWidth;
  so.height = kHeight;
  so.strength = scene.render.silhouettes;
  const std::vector<Stroke> strokes = extract_strokes(assets, so);
  ScenePreviewOptions o;
  o.width = kWidth;
  o.height = kHeight;
  o.strokes = &strokes;
  check_golden(name, render_scene_preview(assets, o));
}

TEST(Golden, Scene) { scene_case("scene-tiny", 0); }
TEST(Golden, SceneNpr) { scene_case("scene-tiny-npr", 1); }

}  // namespace
}  // namespace cutaway
