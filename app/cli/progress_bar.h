// A progress bar for long commands (`variants`, `batch`): "LABEL: [=====>    ] 12/40" on
// stderr, redrawn in place; only when stderr is a terminal (otherwise the commands log one line
// per step).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

namespace cutaway::cli {

class ProgressBar {
 public:
  /// A bar of `total` steps, shown only when `enabled` (the caller checks isatty) and total > 0.
  ProgressBar(std::string label, int total, bool enabled)
      : label_(std::move(label)), total_(total), on_(enabled && total > 0) {}
  /// Redraws the bar at `done` of the total steps; a newline after the last.
  void show(int done) const {
    if (!on_) return;
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(int64_t{done} * kWidth / total_);
    std::string bar(kWidth, ' ');
    for (int i = 0; i < filled; ++i) bar[i] = '=';
    if (filled < kWidth) bar[filled] = '>';
    std::fprintf(stderr, "\r%s: [%s] %d/%d", label_.c_str(), bar.c_str(), done, total_);
    if (done == total_) std::fputc('\n', stderr);
    std::fflush(stderr);
  }
  bool enabled() const { return on_; }

 private:
  std::string label_;
  int total_;
  bool on_;
};

}  // namespace cutaway::cli
