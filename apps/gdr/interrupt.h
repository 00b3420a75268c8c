// Ctrl-C (SIGINT) and SIGTERM stop a run cleanly instead of killing it: a signal only sets a
// flag, which the engine polls between phases and iterations (Callbacks::abort) and the
// command checks between its own steps; the command then says so and exits with
// 128 + the signal number. Output files are written atomically, so a signal that comes
// while they are written lets them complete; one that comes before leaves them unwritten.
#pragma once
#include <csignal>

namespace gdr::cli {

class InterruptHandler {
 public:
  InterruptHandler();   // installs the handlers
  ~InterruptHandler();  // restores the previous ones
  InterruptHandler(const InterruptHandler&) = delete;
  InterruptHandler& operator=(const InterruptHandler&) = delete;

  static int received();  // the signal received, 0 if none

 private:
  struct sigaction old_int_, old_term_;
};

}  // namespace gdr::cli
