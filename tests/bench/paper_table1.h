// The paper's Table 1 (Takayama et al. 2010) for the benchmarks, read from
// tests/data/paper-table1.tsv. Header-only: each benchmark is one translation unit.
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <istream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace cutaway::bench {

/// One row of Table 1.
struct PaperRow {
  std::string title, symmetry, design_min, cut_s, vertices, faces, size_kb;
};

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

/// The rows of tests/data/paper-table1.tsv; `source` receives its path.
/// @throws std::runtime_error when the file cannot be read or has no rows
inline std::vector<PaperRow> read_table1(std::string* source) {
  const std::filesystem::path tsv =
      std::filesystem::path(CUTAWAY_SOURCE_DIR) / "tests" / "data" / "paper-table1.tsv";
  std::ifstream in(tsv);
  std::vector<PaperRow> rows = parse_table1(in);
  if (rows.empty()) throw std::runtime_error("cannot read Table 1 from " + tsv.string());
  *source = tsv.string();
  return rows;
}

/// The row of `title`, or nothing.
inline const PaperRow* find_row(const std::vector<PaperRow>& rows, const std::string& title) {
  for (const PaperRow& r : rows)
    if (r.title == title) return &r;
  return nullptr;
}

}  // namespace cutaway::bench
