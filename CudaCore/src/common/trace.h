// GDR_TRACE: the time of each step of a host stage on stderr, to find what a stage spends.
#pragma once
#include <chrono>
#include <cstdio>
#include <cstdlib>

namespace gdr {

class TraceSteps {
 public:
  explicit TraceSteps(const char* stage) : stage_(stage), on_(std::getenv("GDR_TRACE") != nullptr) {}
  bool on() const { return on_; }
  // The time since the previous step (or the start).
  void operator()(const char* step) {
    if (!on_) return;
    const auto now = std::chrono::steady_clock::now();
    std::fprintf(stderr, "gdr-trace %s, %s: %.4f s\n", stage_, step,
                 std::chrono::duration<double>(now - last_).count());
    last_ = now;
  }

 private:
  const char* stage_;
  bool on_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace gdr
