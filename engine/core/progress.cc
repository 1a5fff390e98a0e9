#include "engine/core/progress.h"

#include <unistd.h>

#include <algorithm>

namespace recon {

namespace {

std::string FormatDuration(double seconds) {
  const int s = static_cast<int>(seconds + 0.5);
  char buf[32];
  if (s >= 3600) {
    std::snprintf(buf, sizeof(buf), "%d:%02d:%02d", s / 3600, (s / 60) % 60, s % 60);
  } else {
    std::snprintf(buf, sizeof(buf), "%d:%02d", s / 60, s % 60);
  }
  return buf;
}

}  // namespace

ProgressLine::ProgressLine(std::string label, int64_t total, std::FILE* out)
    : label_(std::move(label)),
      total_(std::max<int64_t>(total, 1)),
      out_(out),
      is_tty_(isatty(fileno(out)) != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressLine::~ProgressLine() { Finish(); }

void ProgressLine::Advance(int64_t n, const std::string& detail) {
  std::lock_guard<std::mutex> lock(mutex_);
  done_ = std::min(done_ + n, total_);
  if (!detail.empty()) detail_ = detail;
  const auto now = std::chrono::steady_clock::now();
  const double since_draw = std::chrono::duration<double>(now - last_draw_).count();
  // The end is drawn at once, but once: a job that keeps reporting there (a training run
  // restarted by its rule) must not fill a log with copies of the same line.
  if (since_draw >= (is_tty_ ? 0.1 : 5.0) || (done_ == total_ && drawn_done_ != done_)) {
    last_draw_ = now;
    Draw(false);
  }
}

void ProgressLine::Finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (finished_) return;
  finished_ = true;
  // Without a terminal every line stays in the log: do not print the last state twice.
  if (is_tty_ || drawn_done_ != done_) Draw(true);
}

void ProgressLine::Draw(bool final_line) {
  drawn_done_ = done_;
  constexpr int kWidth = 30;
  const double fraction = static_cast<double>(done_) / static_cast<double>(total_);
  const int filled = static_cast<int>(fraction * kWidth);
  std::string bar(filled, '#');
  bar.append(kWidth - filled, '.');
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string timing = FormatDuration(elapsed) + " elapsed";
  if (!final_line && done_ > 0 && done_ < total_) {
    timing += ", " + FormatDuration(elapsed / fraction - elapsed) + " left";
  }
  std::fprintf(out_, "%s%s [%s] %lld/%lld %3d%% %s%s%s", is_tty_ ? "\r\033[K" : "", label_.c_str(),
               bar.c_str(), static_cast<long long>(done_), static_cast<long long>(total_),
               static_cast<int>(fraction * 100.0), timing.c_str(), detail_.empty() ? "" : "  ",
               detail_.c_str());
  if (!is_tty_ || final_line) std::fputc('\n', out_);
  std::fflush(out_);
}

}  // namespace recon
