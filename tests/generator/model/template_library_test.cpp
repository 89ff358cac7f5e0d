// The template library (the models of Table 1 of Takayama et al. 2010): every model the paper
// lists ships as templates/NAME.yaml, loads, builds with at least half of the paper's DS faces,
// and cuts as halves, slices (about a quarter of its height thick) and six wedges into closed,
// consistently oriented pieces. The kidney's PLY files are reproduced by their script.
#include <algorithm>
#include <cstdlib>
#include <array>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "diffusion/diffusion.h"
#include "io/cut_notation.h"
#include "io/template_parser.h"
#include "model/model_builder.h"
#include "pieces/cut_spec.h"
#include "pieces/pieces.h"
#include "test_support.h"

namespace cutaway {
namespace {

/// One row of the paper's Table 1 (tests/data/paper-table1.tsv): the template's file name and
/// the model's DS face count.
struct PaperModel {
  const char* name;
  size_t faces;
  bool has_axis;  ///< wedges about +Y make sense (not for the kidney)
};

// Written out, so that the tests are instantiated without reading a file; checked against the
// table's file below.
const PaperModel kTable1[] = {
    {"tomato", 20412, true},   {"onion", 8110, true},       {"persimmon", 18208, true},
    {"pepper", 18328, true},   {"avocado", 5341, true},     {"apple", 7685, true},
    {"okra", 18480, true},     {"star_fruit", 12190, true}, {"strawberry", 32049, true},
    {"cucumber", 28592, true}, {"kiwi", 38688, true},       {"volcano", 20673, true},
    {"kidney", 5694, false},
};

void PrintTo(const PaperModel& m, std::ostream* os) { *os << m.name; }

std::string template_path(const PaperModel& m) {
  return test::source_path(std::string("templates/") + m.name + ".yaml").string();
}

TEST(TemplateLibrary, EveryModelOfTable1IsShipped) {
  for (const PaperModel& m : kTable1) {
    EXPECT_TRUE(std::filesystem::is_regular_file(template_path(m))) << m.name;
  }
}

TEST(TemplateLibrary, TheListMatchesThePapersTable) {
  const auto tsv = test::source_path("tests/data/paper-table1.tsv");
  ASSERT_TRUE(std::filesystem::is_regular_file(tsv)) << tsv;
  std::map<std::string, size_t> rows;
  std::istringstream in(test::read_file(tsv));
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.rfind("title\t", 0) == 0) continue;
    std::vector<std::string> cells;
    std::istringstream ls(line);
    for (std::string c; std::getline(ls, c, '\t');) cells.push_back(c);
    ASSERT_GE(cells.size(), 6u) << line;
    rows[cells[0]] = std::stoul(cells[5]);
  }
  EXPECT_EQ(rows.size(), std::size(kTable1));
  for (const PaperModel& m : kTable1) {
    ASSERT_TRUE(rows.count(m.name)) << m.name;
    EXPECT_EQ(rows[m.name], m.faces) << m.name;
  }
}

class TemplateLibrary : public ::testing::TestWithParam<PaperModel> {};

TEST_P(TemplateLibrary, LoadsBuildsAndCutsIntoClosedPieces) {
  const PaperModel& m = GetParam();
  const Template tmpl = load_template(template_path(m));
  EXPECT_EQ(tmpl.name, m.name);
  const DsModel model = build_model(tmpl);
  EXPECT_GE(2 * model.face_count(), m.faces) << "fewer than half of Table 1's DS faces";
  EXPECT_LT(model.face_count(), 100000u) << "too heavy for scenes that cut many";

  const auto diffusion = make_cpu_diffusion(model, {4, 0});
  PieceOptions options;
  options.section.edge_m = tmpl.edge_m;
  const double height = (model.bbox_max.y - model.bbox_min.y) / tmpl.metres_per_unit;
  std::vector<std::string> cuts = {"halves", "slices:" + std::to_string(height / 4)};
  if (m.has_axis) cuts.push_back("wedges:6");
  for (const std::string& cut : cuts) {
    SCOPED_TRACE(cut);
    const PieceSet set =
        *cut_pieces(model, *parse_cut_spec(cut, tmpl.metres_per_unit), *diffusion, options);
    EXPECT_GE(set.pieces.size(), cut == "halves" ? 2u : 3u);
    for (const Piece& piece : set.pieces) {
      const ShadedMesh mesh = merge_parts(piece);
      EXPECT_TRUE(test::closed_and_oriented(mesh)) << "piece of cell " << piece.cell;
      EXPECT_GT(signed_volume(mesh), 0) << "piece of cell " << piece.cell;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Table1, TemplateLibrary, ::testing::ValuesIn(kTable1),
                         [](const auto& info) { return std::string(info.param.name); });

TEST(TemplateLibrary, KidneyMeshesAreReproducedByTheirScript) {
  if (std::system("python3 --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "no python3";
  const auto dir = test::fresh_dir("kidney");
  const std::string command = "python3 '" + test::source_path("scripts/make_kidney.py").string() +
                              "' '" + dir.string() + "'";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  const std::vector<std::string> made = test::files_in(dir);
  ASSERT_FALSE(made.empty());
  for (const std::string& f : made) {
    SCOPED_TRACE(f);
    const std::string committed = test::read_file(test::source_path("templates/" + f));
    ASSERT_FALSE(committed.empty()) << "templates/" << f << " is missing";
    EXPECT_TRUE(committed == test::read_file(dir / f)) << "differs from the script's output";
  }
}

}  // namespace
}  // namespace cutaway
