// Regression tests for hostile or degenerate input that once crashed, hung or misbehaved, run
// end to end through the CLI. Each case must end with exit code 0 and its output written, or
// with exit code 2, one short message that names the option or template field at fault, and
// nothing written; never a signal, another exit code or unbounded work (bounded by its peak
// resident memory; a refusal writes its message alone):
//   - section planes that graze the surface (avocado, strawberry, apple, onion);
//   - a persimmon diced in 12 mm cubes, as a scene and as a piece with several seeds;
//   - numbers: a plane at y = 1e400, a plane normal with a subnormal component (1e-320), a
//     30,000-digit dice size and a 30,000-digit plane coordinate;
//   - a template name of 50,000 characters, a scene name and a scene's template name of 60,000;
//   - a colour blur of 1e-30 or 1e-300 mm (spheres, onion and the mesh-based kidney);
//   - grains: a region along the profile 1e-7 or 1e-9 wide, mesh edges far larger than the
//     fruit (10^4 and 10^6 mm);
//   - bounded work: grain spacings of 0.05 and 1e-6 mm (millions of grains and more) and grains
//     of 10^6 mm are refused at once, by `piece` and by `check`.
// The templates and scenes are in tests/data/reliability/ (copies of shipped templates with one
// hostile value each); the long numbers are generated here. Outputs go into fresh folders.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <vector>

#include <sys/resource.h>

#include "test_support.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;

const std::string kData = "tests/data/reliability/";

/// What a case must end with.
enum class Expect {
  kWrites,           ///< exit 0, output written
  kWritesOrRefuses,  ///< exit 0 with output, or a clean refusal (exit 2, nothing written)
  kRefuses,          ///< exit 2, a short message, nothing written
};

struct Case {
  std::string name;               ///< test name suffix
  std::vector<std::string> args;  ///< "{out}" stands for `out` in a fresh folder
  Expect expect = Expect::kWrites;
  std::string out;  ///< what -o names, relative to the fresh folder ("" none)
  /// Refusals: the option or field the message must name. With `located`, the message must
  /// begin "INPUT:LINE:COL: FIELD: " where INPUT is args[1].
  std::string field;
  bool located = false;
  std::vector<std::string> rules;   ///< refusals: the message contains each of these ...
  std::vector<std::string> any_of;  ///< ... and one of these (when not empty)
  bool validate = false;            ///< the output is a .glb the Khronos validator must accept
  /// Most peak resident memory over the program's start (test::cutaway_start), MiB; 0: not
  /// bounded. kRefusalMiB or kSmallRunMiB.
  uint64_t max_extra_mib = 0;
};

/// A case refused before its work: measured 18 MiB over the start at most (the cucumber's
/// grain spacing of 1e-6 mm, refused once the model is built), the others 8 MiB or less.
/// Millions of grains, or a 30,000-digit number spelled out, would not fit.
constexpr uint64_t kRefusalMiB = 64;
/// A section, a piece of a halved or plane-cut fruit, a model with grains, two variants:
/// measured 58 MiB over the start at most (the onion halved, blur 1e-300), whatever the
/// thread count (1 and 16 alike).
constexpr uint64_t kSmallRunMiB = 256;

std::ostream& operator<<(std::ostream& os, const Case& c) { return os << c.name; }

std::string test_name(const ::testing::TestParamInfo<Case>& info) { return info.param.name; }

/// Whether `err` begins "INPUT:LINE:COL: FIELD: ".
bool located_message(const std::string& err, const std::string& input, const std::string& field) {
  if (err.rfind(input + ":", 0) != 0) return false;
  size_t i = input.size() + 1;
  for (int number = 0; number < 2; ++number) {
    const size_t digits = i;
    while (i < err.size() && std::isdigit(static_cast<unsigned char>(err[i]))) ++i;
    if (i == digits || i >= err.size() || err[i] != ':') return false;
    ++i;
  }
  return err.compare(i, field.size() + 3, " " + field + ": ") == 0;
}

/// Runs the case and checks its outcome against `c.expect`.
void run_case(const Case& c) {
  const fs::path dir = test::fresh_dir("reliability");
  std::vector<std::string> args = c.args;
  for (auto& a : args)
    if (a == "{out}") a = (dir / c.out).string();
  // No address-space limit (the cases were never run under one); 600 s of CPU time stop a
  // hang (the persimmon scene takes 20 s).
  const test::LimitedRun r = test::run_cutaway_limited(args, RLIM_INFINITY, 600);
  const uint64_t extra_rss =
      r.peak_rss_bytes - std::min(r.peak_rss_bytes, test::cutaway_start().peak_rss_bytes);
  std::printf("%s: exit %d, peak %.1f MiB over the start, wrote %llu bytes, %zu on stderr\n",
              c.name.c_str(), r.exit_code, extra_rss / 1048576.0,
              static_cast<unsigned long long>(r.written_bytes), r.err.size());
  const std::string err = r.err.substr(0, 2000);

  // A signal or any code but 0 and 2 is a failure.
  ASSERT_TRUE(r.signal == 0 && (r.exit_code == 0 || r.exit_code == 2))
      << "exit " << r.exit_code << ", signal " << r.signal << "\n"
      << err;
  if (c.max_extra_mib > 0 && test::kPeakMemoryBounds) {
    EXPECT_LT(extra_rss, c.max_extra_mib << 20)
        << "peak resident memory: the work must stay bounded";
  }
  if (c.expect == Expect::kWrites) {
    EXPECT_EQ(r.exit_code, 0) << err;
  }
  if (c.expect == Expect::kRefuses) {
    EXPECT_EQ(r.exit_code, 2) << err;
  }

  if (r.exit_code == 0) {
    if (c.out.empty()) return;
    EXPECT_TRUE(fs::exists(dir / c.out)) << c.out << " not written\n" << err;
    EXPECT_FALSE(test::files_in(dir).empty()) << "nothing written\n" << err;
    if (c.validate) {
      const test::GltfReport v = test::validate_gltf(dir / c.out);
      EXPECT_EQ(v.errors, 0) << v.output;
    }
    return;
  }
  EXPECT_LT(r.err.size(), 1000u) << err;
  // Its message is all it writes (measured: 226 bytes at most), not an output made and removed.
  EXPECT_LT(r.written_bytes, 4096u) << "bytes written by a refusal";
  EXPECT_EQ(r.err.find("internal error"), std::string::npos) << err;
  EXPECT_NE(r.err.find(c.field), std::string::npos) << c.field << " not named in\n" << err;
  if (c.located) {
    EXPECT_TRUE(located_message(r.err, args.at(1), c.field)) << err;
  }
  for (const auto& rule : c.rules) {
    EXPECT_NE(r.err.find(rule), std::string::npos) << "'" << rule << "' missing in\n" << err;
  }
  if (!c.any_of.empty()) {
    bool found = false;
    for (const auto& rule : c.any_of) found = found || r.err.find(rule) != std::string::npos;
    EXPECT_TRUE(found) << "none of the expected rules in\n" << err;
  }
  EXPECT_TRUE(test::files_in(dir).empty()) << "a refusal must write nothing";
}

// ---------------------------------------------------------------------------------------------
// Section and cut planes at the edge of the object or with subnormal normals.

class ReliabilityPlane : public ::testing::TestWithParam<Case> {};

TEST_P(ReliabilityPlane, CutsOrRefusesCleanly) { run_case(GetParam()); }

const std::vector<std::string> kGrazing{"misses", "only touches"};

// One case a few rows, as the table reads:
// clang-format off
INSTANTIATE_TEST_SUITE_P(
    Reliability, ReliabilityPlane,
    ::testing::Values(
        // Planes through the outermost vertices of shipped templates.
        Case{"avocado_x_at_the_widest_vertex",
             {"section", "templates/avocado.yaml", "--plane", "x=34.99615995755195", "-o", "{out}"},
             Expect::kWrites, "x.ply", "", false, {}, {}, false, kSmallRunMiB},
        Case{"strawberry_y_at_the_top",
             {"section", "templates/strawberry.yaml", "--plane", "y=42.025383561849594", "-o",
              "{out}"},
             Expect::kWrites, "x.ply", "", false, {}, {}, false, kSmallRunMiB},
        Case{"apple_z_grazing",
             {"section", "templates/apple.yaml", "--plane", "z=39.3501227962017", "-o", "{out}"},
             Expect::kWritesOrRefuses, "x.ply", "--plane", false, {}, kGrazing, false,
             kSmallRunMiB},
        Case{"onion_z_grazing",
             {"section", "templates/onion.yaml", "--plane", "z=-39.4587516784668", "-o", "{out}"},
             Expect::kWritesOrRefuses, "x.ply", "--plane", false, {}, kGrazing, false,
             kSmallRunMiB},
        // A normal with a subnormal x component (1e-320): through the origin the plane only
        // meets the tomato's bottom pole; 30 mm up it cuts the tomato.
        Case{"section_subnormal_normal_at_the_pole",
             {"section", "templates/tomato.yaml", "--plane", "0,0,0/1e-320,1,0", "-o", "{out}"},
             Expect::kWritesOrRefuses, "x.ply", "--plane", false, {}, {}, false, kSmallRunMiB},
        Case{"piece_subnormal_normal_at_the_pole",
             {"piece", "templates/tomato.yaml", "--cut", "plane:0,0,0/1e-320,1,0", "-o", "{out}"},
             Expect::kWritesOrRefuses, "x.glb", "--cut", false, {}, {}, false, kSmallRunMiB},
        Case{"section_subnormal_normal_through_the_middle",
             {"section", "templates/tomato.yaml", "--plane", "0,30,0/1e-320,1,0", "-o", "{out}"},
             Expect::kWrites, "x.ply", "", false, {}, {}, false, kSmallRunMiB},
        Case{"piece_subnormal_normal_through_the_middle",
             {"piece", "templates/tomato.yaml", "--cut", "plane:0,30,0/1e-320,1,0", "-o", "{out}"},
             Expect::kWrites, "x.glb", "", false, {}, {}, false, kSmallRunMiB}),
    test_name);
// clang-format on

// ---------------------------------------------------------------------------------------------
// Numbers out of range or absurdly long on the command line.

class ReliabilityNumber : public ::testing::TestWithParam<Case> {};

TEST_P(ReliabilityNumber, RefusedWithAShortMessage) { run_case(GetParam()); }

// One case a few rows, as the table reads:
// clang-format off
INSTANTIATE_TEST_SUITE_P(Reliability, ReliabilityNumber,
                         ::testing::Values(Case{"plane_coordinate_1e400",
                                                {"section", "templates/tomato.yaml", "--plane",
                                                 "y=1e400", "-o", "{out}"},
                                                Expect::kRefuses,
                                                "x.ply",
                                                "--plane",
                                                false,
                                                {"too large"},
                                                {},
                                                false,
                                                kRefusalMiB},
                                           Case{"dice_size_of_30000_digits",
                                                {"piece", "templates/tomato.yaml", "--cut",
                                                 "dice:" + std::string(30000, '1'), "-o", "{out}"},
                                                Expect::kRefuses, "x.glb", "--cut", false, {}, {},
                                                false, kRefusalMiB},
                                           Case{"plane_coordinate_of_30000_digits",
                                                {"section", "templates/tomato.yaml", "--plane",
                                                 "y=" + std::string(30000, '2'), "-o", "{out}"},
                                                Expect::kRefuses, "x.ply", "--plane", false, {}, {},
                                                false, kRefusalMiB}),
                         test_name);
// clang-format on

// ---------------------------------------------------------------------------------------------
// Names of 50,000 and 60,000 characters: one located line, not an echo of the name.

class ReliabilityLongName : public ::testing::TestWithParam<Case> {};

TEST_P(ReliabilityLongName, RefusedWithAShortLocatedMessage) { run_case(GetParam()); }

// One case a few rows, as the table reads:
// clang-format off
INSTANTIATE_TEST_SUITE_P(Reliability, ReliabilityLongName,
                         ::testing::Values(Case{"template_name",
                                                {"check", kData + "long-name-50000.yaml"},
                                                Expect::kRefuses,
                                                "",
                                                "name",
                                                true,
                                                {},
                                                {},
                                                false,
                                                kRefusalMiB},
                                           Case{"scene_name",
                                                {"check", kData + "scene-long-name.yaml"},
                                                Expect::kRefuses, "", "name", true, {}, {}, false,
                                                kRefusalMiB},
                                           Case{"scene_template_name",
                                                {"check", kData + "scene-long-template-name.yaml"},
                                                Expect::kRefuses, "", "items[0].template", true, {},
                                                {}, false, kRefusalMiB}),
                         test_name);
// clang-format on

// ---------------------------------------------------------------------------------------------
// Colour blurs of 1e-30 and 1e-300 mm, on surfaces of revolution and on meshes.

class ReliabilityBlur : public ::testing::TestWithParam<Case> {};

TEST_P(ReliabilityBlur, WritesTheOutput) { run_case(GetParam()); }

// One case a few rows, as the table reads:
// clang-format off
INSTANTIATE_TEST_SUITE_P(
    Reliability, ReliabilityBlur,
    ::testing::Values(
        Case{"spheres_section_blur_1e_30",
             {"section", kData + "spheres-blur-1e-30.yaml", "--plane", "z=0", "-o", "{out}"},
             Expect::kWrites, "x.ply", "", false, {}, {}, false, kSmallRunMiB},
        Case{"kidney_section_blur_1e_30",
             {"section", kData + "kidney-blur-1e-30.yaml", "--plane", "z=0", "-o", "{out}"},
             Expect::kWrites, "x.ply", "", false, {}, {}, false, kSmallRunMiB},
        Case{"onion_piece_blur_1e_300",
             {"piece", kData + "onion-blur-1e-300.yaml", "--cut", "halves", "-o", "{out}"},
             Expect::kWrites, "x.glb", "", false, {}, {}, false, kSmallRunMiB},
        Case{"kidney_piece_blur_1e_300",
             {"piece", kData + "kidney-blur-1e-300.yaml", "--cut", "halves", "-o", "{out}"},
             Expect::kWrites, "x.glb", "", false, {}, {}, false, kSmallRunMiB}),
    test_name);
// clang-format on

// ---------------------------------------------------------------------------------------------
// Grains in regions too thin to hold one, and meshes far coarser than the fruit, seeded.

class ReliabilityGrains : public ::testing::TestWithParam<Case> {};

TEST_P(ReliabilityGrains, WritesAValidModel) { run_case(GetParam()); }

// One case a few rows, as the table reads:
// clang-format off
INSTANTIATE_TEST_SUITE_P(
    Reliability, ReliabilityGrains,
    ::testing::Values(
        Case{"tomato_grain_region_1e_7",
             {"model", kData + "tomato-grain-region-1e-7.yaml", "--seed", "1", "-o", "{out}"},
             Expect::kWrites, "x.glb", "", false, {}, {}, true, kSmallRunMiB},
        Case{"tomato_grain_region_1e_7_variants",
             {"variants", kData + "tomato-grain-region-1e-7.yaml", "--count", "2", "-o", "{out}"},
             Expect::kWrites, "variants", "", false, {}, {}, false, kSmallRunMiB},
        Case{"star_fruit_edge_1e6",
             {"model", kData + "star-fruit-edge-1e6.yaml", "--seed", "1", "-o", "{out}"},
             Expect::kRefuses, "x.glb", "resolution.edge", true,
             {"at most 1/8 of the skin's height"}, {}, false, kRefusalMiB},
        Case{"pepper_edge_1e4",
             {"model", kData + "pepper-edge-1e4.yaml", "--seed", "1", "-o", "{out}"},
             Expect::kRefuses, "x.glb", "resolution.edge", true,
             {"at most 1/8 of the skin's height"}, {}, false, kRefusalMiB},
        Case{"persimmon_grain_region_1e_9",
             {"model", kData + "persimmon-grain-region-1e-9.yaml", "--seed", "1", "-o", "{out}"},
             Expect::kWrites, "x.glb", "", false, {}, {}, true, kSmallRunMiB}),
    test_name);
// clang-format on

// ---------------------------------------------------------------------------------------------
// Grain sets that would take unbounded work: refused at once, before any output.

class ReliabilityBoundedWork : public ::testing::TestWithParam<Case> {};

TEST_P(ReliabilityBoundedWork, RefusedAtOnce) { run_case(GetParam()); }

// One case a few rows, as the table reads:
// clang-format off
INSTANTIATE_TEST_SUITE_P(
    Reliability, ReliabilityBoundedWork,
    ::testing::Values(Case{"strawberry_spacing_0_05_piece",
                           {"piece", kData + "strawberry-grain-spacing-0.05.yaml", "--cut",
                            "halves", "--seed", "1", "-o", "{out}"},
                           Expect::kRefuses,
                           "x.glb",
                           "grains[0].spacing",
                           true,
                           {"too small"},
                           {},
                           false,
                           kRefusalMiB},
                      Case{"strawberry_spacing_0_05_check",
                           {"check", kData + "strawberry-grain-spacing-0.05.yaml"},
                           Expect::kRefuses, "", "grains[0].spacing", true, {"too small"}, {},
                           false, kRefusalMiB},
                      Case{"cucumber_spacing_1e_6_piece",
                           {"piece", kData + "cucumber-grain-spacing-1e-6.yaml", "--cut", "halves",
                            "--seed", "1", "-o", "{out}"},
                           Expect::kRefuses, "x.glb", "grains[0].spacing", true, {"too small"}, {},
                           false, kRefusalMiB},
                      Case{"cucumber_spacing_1e_6_check",
                           {"check", kData + "cucumber-grain-spacing-1e-6.yaml"}, Expect::kRefuses,
                           "", "grains[0].spacing", true, {"too small"}, {}, false, kRefusalMiB},
                      Case{"strawberry_grain_1e6_piece",
                           {"piece", kData + "strawberry-grain-ellipsoid-1e6.yaml", "--cut",
                            "halves", "--seed", "1", "-o", "{out}"},
                           Expect::kRefuses, "x.glb", "grains[0].shape", true, {}, {}, false,
                           kRefusalMiB},
                      Case{"strawberry_grain_1e6_check",
                           {"check", kData + "strawberry-grain-ellipsoid-1e6.yaml"},
                           Expect::kRefuses, "", "grains[0].shape", true, {}, {}, false,
                           kRefusalMiB}),
    test_name);
// clang-format on

// ---------------------------------------------------------------------------------------------
// A persimmon diced in 12 mm cubes (about 100 pieces; several seconds each). The scene names
// the template, found by name from tests/data/reliability/.

class ReliabilityPersimmonDice : public ::testing::TestWithParam<Case> {};

TEST_P(ReliabilityPersimmonDice, Writes) { run_case(GetParam()); }

// One case a few rows, as the table reads:
// clang-format off
INSTANTIATE_TEST_SUITE_P(Reliability, ReliabilityPersimmonDice,
                         ::testing::Values(Case{"scene_default_seed",
                                                {"scene", kData + "scene-persimmon-dice12.yaml",
                                                 "-o", "{out}"},
                                                Expect::kWrites,
                                                "x.glb",
                                                "",
                                                false,
                                                {},
                                                {},
                                                true,
                                                0},
                                           Case{"scene_seed_3",
                                                {"scene", kData + "scene-persimmon-dice12.yaml",
                                                 "--seed", "3", "-o", "{out}"},
                                                Expect::kWrites, "x.glb", "", false, {}, {}, true,
                                                0},
                                           Case{"piece_seed_1",
                                                {"piece", "templates/persimmon.yaml", "--cut",
                                                 "dice:12", "--seed", "1", "-o", "{out}"},
                                                Expect::kWrites, "x.glb", "", false, {}, {}, true,
                                                0},
                                           Case{"piece_seed_2",
                                                {"piece", "templates/persimmon.yaml", "--cut",
                                                 "dice:12", "--seed", "2", "-o", "{out}"},
                                                Expect::kWrites, "x.glb", "", false, {}, {}, false,
                                                0},
                                           Case{"piece_seed_4",
                                                {"piece", "templates/persimmon.yaml", "--cut",
                                                 "dice:12", "--seed", "4", "-o", "{out}"},
                                                Expect::kWrites, "x.glb", "", false, {}, {}, false,
                                                0},
                                           Case{"piece_seed_15",
                                                {"piece", "templates/persimmon.yaml", "--cut",
                                                 "dice:12", "--seed", "15", "-o", "{out}"},
                                                Expect::kWrites, "x.glb", "", false, {}, {}, false,
                                                0}),
                         test_name);
// clang-format on

}  // namespace
}  // namespace cutaway
