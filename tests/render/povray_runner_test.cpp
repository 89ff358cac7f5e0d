// The POV-Ray runner (render/povray_runner.h) on hand-written scenes: image size and content,
// errors with POV-Ray's own message, no partial output, a missing executable.
#include "render/povray_runner.h"

#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <stb/stb_image.h>

#include "base/atomic_file.h"
#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

// A red sphere left of centre on a black background, lit by a white light at the camera.
const char* const kScene = R"(#version 3.7;
global_settings { assumed_gamma 1.0 }
background { rgb <0, 0, 0> }
camera { perspective location <0, 0, 3> direction <0, 0, -1.5> right <1.5, 0, 0> up <0, 1, 0> }
light_source { <0, 0, 3> color rgb 1 }
sphere { <-0.5, 0, 0>, 0.3 pigment { rgb <1, 0, 0> } finish { ambient 0 diffuse 1 } }
)";

struct Pixels {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;
  const unsigned char* at(int x, int y) const { return &rgb[3 * (y * width + x)]; }
};

Pixels read_png(const fs::path& path) {
  const std::string bytes = test::read_file(path);
  Pixels p;
  int channels = 0;
  unsigned char* data =
      stbi_load_from_memory(reinterpret_cast<const unsigned char*>(bytes.data()),
                            static_cast<int>(bytes.size()), &p.width, &p.height, &channels, 3);
  if (data == nullptr) return p;
  p.rgb.assign(data, data + 3 * p.width * p.height);
  stbi_image_free(data);
  return p;
}

TEST(PovrayRunner, RendersPngOfTheAskedSize) {
  const fs::path dir = test::fresh_dir("povray_runner");
  write_file_atomically(dir / "scene.pov", kScene);
  PovrayOptions options;
  options.antialias = false;
  options.threads = 1;
  render_povray(dir / "scene.pov", dir / "out" / "image.png", 60, 40, options);
  const Pixels p = read_png(dir / "out" / "image.png");
  ASSERT_EQ(p.width, 60);
  ASSERT_EQ(p.height, 40);
  // The ray of image point (u, v) goes along (1.5 u, v, -1.5) and meets x = -0.5 at z = 0 for
  // u = -1/6: the sphere's centre is at column 60 (1/2 - 1/6) = 20, left of the middle.
  const unsigned char* centre = p.at(60 / 2 - 60 / 6, 20);
  EXPECT_GT(centre[0], 200);
  EXPECT_LT(centre[1], 10);
  const unsigned char* right = p.at(60 - 1 - (60 / 2 - 60 / 6), 20);  // mirrored: background
  EXPECT_EQ(right[0] + right[1] + right[2], 0);
  // Only the PNG is left beside the scene (no temporary files).
  EXPECT_EQ(test::files_in(dir), (std::vector<std::string>{"out/image.png", "scene.pov"}));
}

TEST(PovrayRunner, ParseErrorThrowsWithPovraysMessageAndWritesNothing) {
  const fs::path dir = test::fresh_dir("povray_runner_error");
  write_file_atomically(dir / "bad.pov", "#version 3.7;\nsphere { <0, 0, 0> 1 pigment { rgb }\n");
  write_file_atomically(dir / "image.png", "old");
  try {
    render_povray(dir / "bad.pov", dir / "image.png", 20, 20, PovrayOptions{});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("POV-Ray failed"), std::string::npos) << what;
    EXPECT_NE(what.find("Parse Error"), std::string::npos) << what;
  }
  EXPECT_EQ(test::read_file(dir / "image.png"), "old");
  EXPECT_EQ(test::files_in(dir), (std::vector<std::string>{"bad.pov", "image.png"}));
}

TEST(PovrayRunner, MissingExecutableOrSceneThrows) {
  const fs::path dir = test::fresh_dir("povray_runner_missing");
  write_file_atomically(dir / "scene.pov", kScene);
  PovrayOptions options;
  options.executable = "cutaway-no-such-povray";
  EXPECT_THROW(render_povray(dir / "scene.pov", dir / "a.png", 10, 10, options),
               std::runtime_error);
  options.executable = (dir / "no-such-povray").string();
  EXPECT_THROW(render_povray(dir / "scene.pov", dir / "a.png", 10, 10, options),
               std::runtime_error);
  EXPECT_THROW(render_povray(dir / "none.pov", dir / "a.png", 10, 10, PovrayOptions{}),
               std::runtime_error);
  EXPECT_THROW(render_povray(dir / "scene.pov", dir / "a.png", 0, 10, PovrayOptions{}),
               InternalError);
  PovrayOptions bad_quality;
  bad_quality.quality = 12;
  EXPECT_THROW(render_povray(dir / "scene.pov", dir / "a.png", 10, 10, bad_quality), InternalError);
  EXPECT_FALSE(fs::exists(dir / "a.png"));
}

}  // namespace
}  // namespace cutaway
