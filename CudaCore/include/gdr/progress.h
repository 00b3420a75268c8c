// Progress and abort hooks passed from filters / the CLI into long-running work.
#pragma once
#include <functional>
#include <string>

namespace gdr {

struct Callbacks {
  // fraction in [0,1] (an estimate), and a short phase label. May be empty.
  std::function<void(double fraction, const std::string& phase)> progress;
  // Polled between phases; returning true stops the run with Status::Aborted.
  std::function<bool()> abort;
  // Non-fatal notes (fallbacks, merged duplicates, capped refinement). May be empty.
  std::function<void(const std::string& message)> warning;
};

}  // namespace gdr
