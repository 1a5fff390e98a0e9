#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
#include <string>

namespace recon {

/// A one-line progress bar for long CLI work: "label [#####.....] 12/40  30% 0:42 left".
/// On a terminal it redraws in place; when stderr is not a terminal (CI logs) it prints a line
/// at most every few seconds so logs stay readable. Thread-safe.
class ProgressLine {
 public:
  ProgressLine(std::string label, int64_t total, std::FILE* out = stderr);
  ~ProgressLine();

  /// Adds `n` finished units; `detail` replaces the text after the bar (e.g. "exact run 3").
  void Advance(int64_t n = 1, const std::string& detail = "");
  /// Prints the final state and a newline.
  void Finish();

 private:
  void Draw(bool final_line);

  std::string label_;
  int64_t total_;
  int64_t done_ = 0;
  int64_t drawn_done_ = -1;  ///< done_ at the last line printed (so Finish does not repeat it)
  std::string detail_;
  std::FILE* out_;
  bool is_tty_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point last_draw_;
  std::mutex mutex_;
};

}  // namespace recon
