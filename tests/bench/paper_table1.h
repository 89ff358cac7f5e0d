// The paper's Table 1 (Takayama et al. 2010) for the benchmarks: read from
// ../shared/reference/paper-table1.tsv beside the repository when present, else from the copy
// below. Header-only: each benchmark is one translation unit.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <istream>
#include <sstream>
#include <string>
#include <vector>

namespace cutaway::bench {

/// One row of Table 1.
struct PaperRow {
  std::string title, symmetry, design_min, cut_s, vertices, faces, size_kb;
};

/// Table 1 as shipped with the reference material (title symmetry design_min cut_s vertices
/// faces size_kb), used when the TSV is absent.
inline const char* const kTable1 =
    "title\tsymmetry\tdesign_min\tcut_s\tvertices\tfaces\tsize_kb\n"
    "tomato\tnfold\t25\t6.1\t10619\t20412\t669\n"
    "onion\tcylindrical\t10\t1.9\t4184\t8110\t264\n"
    "persimmon\tnfold\t16\t8.1\t9162\t18208\t584\n"
    "pepper\tnfold\t20\t6.8\t9317\t18328\t592\n"
    "avocado\tcylindrical\t8\t0.8\t2699\t5341\t172\n"
    "apple\tnfold\t25\t3.3\t4074\t7685\t255\n"
    "okra\tnfold\t17\t3.7\t9400\t18480\t597\n"
    "star_fruit\tnfold\t15\t3.2\t6357\t12190\t400\n"
    "strawberry\tcylindrical\t141\t7.7\t18158\t32049\t1110\n"
    "cucumber\tnfold\t184\t7.9\t14984\t28592\t942\n"
    "kiwi\tnfold\t162\t27.7\t21438\t38688\t1321\n"
    "volcano\tcylindrical\t187\t10.9\t11057\t20673\t690\n"
    "kidney\tnone\t362\t3.9\t2939\t5694\t185\n";

/// The rows of a Table 1 TSV in file order (comment lines start with '#'; columns by header).
inline std::vector<PaperRow> parse_table1(std::istream& in) {
  std::vector<PaperRow> rows;
  std::vector<std::string> header;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, '\t');) cells.push_back(c);
    if (header.empty()) {
      header = cells;
      continue;
    }
    auto cell = [&](const char* name) -> std::string {
      const auto it = std::find(header.begin(), header.end(), name);
      const size_t k = static_cast<size_t>(it - header.begin());
      return it != header.end() && k < cells.size() ? cells[k] : "-";
    };
    rows.push_back({cell("title"), cell("symmetry"), cell("design_min"), cell("cut_s"),
                    cell("vertices"), cell("faces"), cell("size_kb")});
  }
  return rows;
}

inline std::vector<PaperRow> read_table1(std::string* source) {
  const std::filesystem::path tsv =
      std::filesystem::path(CUTAWAY_SOURCE_DIR) / ".." / "shared" / "reference" / "paper-table1.tsv";
  std::ifstream in(tsv);
  if (in) {
    std::vector<PaperRow> rows = parse_table1(in);
    if (!rows.empty()) {
      *source = std::filesystem::weakly_canonical(tsv).string();
      return rows;
    }
  }
  *source = "built-in copy";
  std::istringstream copy(kTable1);
  return parse_table1(copy);
}

/// The row of `title`, or nothing.
inline const PaperRow* find_row(const std::vector<PaperRow>& rows, const std::string& title) {
  for (const PaperRow& r : rows)
    if (r.title == title) return &r;
  return nullptr;
}

}  // namespace cutaway::bench
