// Progress on stderr: a redrawn bar when stderr is a terminal, otherwise a plain line now and
// then for long runs. Nothing for short runs or under --quiet.
#pragma once
#include <chrono>
#include <mutex>
#include <string>

namespace gdr::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool enabled);
  ~ProgressBar();

  // fraction in [0,1], or negative when unknown (the label alone is shown).
  void update(double fraction, const std::string& label);
  // Prints a message line (e.g. a warning) without mangling the bar.
  void message(const std::string& line);
  // Removes the bar; call before printing the summary.
  void finish();

 private:
  using Clock = std::chrono::steady_clock;
  void clear_line();

  bool enabled_;
  bool tty_;
  bool drawn_ = false;
  Clock::time_point start_;
  Clock::time_point last_draw_;
  std::string last_label_;
  std::mutex mutex_;
};

}  // namespace gdr::cli
