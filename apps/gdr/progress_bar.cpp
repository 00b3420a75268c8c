#include "progress_bar.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

namespace gdr::cli {

namespace {
constexpr double kTtyDelay = 0.3;       // s before the bar appears (no flicker on tiny runs)
constexpr double kTtyInterval = 0.1;    // s between redraws
constexpr double kPlainDelay = 5.0;     // s before the first plain line
constexpr double kPlainInterval = 10.0; // s between plain lines
constexpr int kWidth = 30;
}  // namespace

ProgressBar::ProgressBar(bool enabled)
    : enabled_(enabled), tty_(isatty(STDERR_FILENO) != 0), start_(Clock::now()),
      last_draw_(start_) {}

ProgressBar::~ProgressBar() { finish(); }

void ProgressBar::clear_line() {
  if (drawn_) {
    std::fputs("\r\033[K", stderr);
    drawn_ = false;
  }
}

void ProgressBar::update(double fraction, const std::string& label) {
  if (!enabled_) return;
  std::lock_guard<std::mutex> lock(mutex_);
  const auto now = Clock::now();
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double since = std::chrono::duration<double>(now - last_draw_).count();
  const bool new_label = label != last_label_;
  last_label_ = label;
  char pct[16] = "";
  if (fraction >= 0)
    std::snprintf(pct, sizeof pct, "%3d%%", static_cast<int>(100 * std::min(fraction, 1.0)));

  if (tty_) {
    if (elapsed < kTtyDelay || (!new_label && since < kTtyInterval)) return;
    std::string bar;
    if (fraction >= 0) {
      const int filled = static_cast<int>(kWidth * std::clamp(fraction, 0.0, 1.0));
      bar = "[" + std::string(filled, '#') + std::string(kWidth - filled, '.') + "] ";
    }
    std::fprintf(stderr, "\r%s%s %7.1f s  %s\033[K", bar.c_str(), pct, elapsed, label.c_str());
    std::fflush(stderr);
    drawn_ = true;
  } else {
    const double interval = drawn_ ? kPlainInterval : kPlainDelay;
    if (elapsed < kPlainDelay || std::chrono::duration<double>(now - last_draw_).count() < interval)
      return;
    std::fprintf(stderr, "gdr: %s%s%s (%.1f s)\n", pct, fraction >= 0 ? " " : "", label.c_str(),
                 elapsed);
    std::fflush(stderr);
    drawn_ = true;  // in plain mode: at least one line was printed
  }
  last_draw_ = now;
}

void ProgressBar::message(const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (tty_) clear_line();
  std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
}

void ProgressBar::finish() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (tty_) clear_line();
  std::fflush(stderr);
}

}  // namespace gdr::cli
