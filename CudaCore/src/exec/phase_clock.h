// Wall time per named phase of an engine run (the "time" table of the CLIs and benchmarks).
#pragma once
#include <chrono>
#include <vector>

#include "exec/space.h"
#include "gdr/refine2d.h"  // PhaseTime

namespace gdr::exec {

class PhaseClock {
 public:
  explicit PhaseClock(std::vector<PhaseTime>& phases) : phases_(phases) {}
  // Adds the time since the last stop or restart to phase `name`, after the device is done.
  template <class Space>
  void stop(const char* name) {
    Ops<Space>::synchronize();
    const auto now = std::chrono::steady_clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    for (auto& p : phases_)
      if (p.name == name) {
        p.seconds += s;
        return;
      }
    phases_.push_back(PhaseTime{name, s});
  }
  void restart() { last_ = std::chrono::steady_clock::now(); }

 private:
  std::vector<PhaseTime>& phases_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

}  // namespace gdr::exec
