// Shared declarations of the gdr command-line tool: exit codes, usage errors, subcommands.
#pragma once
#include <stdexcept>
#include <string>
#include <vector>

namespace gdr::cli {

// Documented in `gdr --help` and README.md.
enum ExitCode : int {
  kExitOk = 0,
  kExitInvalidMesh = 1,  // --check found an invalid mesh; selfcheck failed
  kExitUsage = 2,        // bad command line
  kExitInput = 3,        // unreadable or refused input (file, format, geometry, parameters)
  kExitDevice = 4,       // no usable GPU for --backend gpu, out of device or host memory
  kExitInternal = 5,     // a bug: an engine invariant failed, or an unexpected exception
  kExitSignalBase = 128  // + the signal that stopped the run: 130 Ctrl-C, 143 SIGTERM
};

// A mistake on the command line; main() prints it with a pointer to the command's --help.
class UsageError : public std::runtime_error {
 public:
  UsageError(const std::string& command, const std::string& message)
      : std::runtime_error(message), command_(command) {}
  const std::string& command() const { return command_; }

 private:
  std::string command_;
};

// Subcommands; `args` excludes the program and subcommand names. Return an ExitCode.
int run_2d(const std::vector<std::string>& args);
int run_tet(const std::vector<std::string>& args);
int run_rdt(const std::vector<std::string>& args);
int run_info(const std::vector<std::string>& args);
int run_selfcheck(const std::vector<std::string>& args);

}  // namespace gdr::cli
