// gdr: command-line front end of the GPU Delaunay refinement engine.
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "build_info.h"
#include "cli.h"
#include "gdr/error.h"
#include "process_settings.h"

namespace {

using namespace gdr::cli;

const char* kHelp = R"(gdr - quality Delaunay meshing on the GPU (CUDA) or the CPU (OpenMP)

Usage:
  gdr 2d INPUT.poly -o OUTPUT [options]   refine a 2D planar straight-line graph
  gdr tet INPUT -o OUTPUT [options]       quality tetrahedral mesh of a closed 3D surface
  gdr rdt INPUT -o OUTPUT [options]       surface (and volume) mesh approximating a 3D surface
  gdr info INPUT                          describe an input file (counts, bounding box, kind)
  gdr selfcheck                           show the build and device, mesh a small test case
  gdr --version                           print the version and build configuration
  gdr --help | gdr 2d --help              this text | all options of a subcommand

Examples:
  gdr 2d apps/gdr/examples/gear.poly -o gear.vtu --min-angle 25 --remove-exterior --check
  gdr 2d shape.poly -o shape.node --max-area 0.01 --backend cpu
  gdr tet apps/gdr/examples/bushing.off -o bushing.vtu --radius-edge 1.4 --check
  gdr info apps/gdr/examples/gear.poly

Inputs are Triangle .poly/.node files (2D), and closed surfaces as .off, .stl, .ply, .obj
or TetGen .poly/.smesh (3D). Outputs are chosen by extension: .vtu or .vtp (open them in
ParaView), .node/.ele (Triangle's format), TetGen's .node/.ele/.face, or Medit's .mesh (3D).

Exit codes:
  0  success
  1  the mesh failed the validators (--check), or selfcheck failed
  2  usage error (unknown option, missing argument, bad number)
  3  input error (missing or malformed file, invalid geometry, refused parameters)
  4  device error (--backend gpu without a usable GPU, out of device or host memory)
  5  internal error (a bug; please report it with the input)
  130  interrupted (Ctrl-C; 143 for SIGTERM)
)";

int exit_code_for(gdr::Status s) {
  switch (s) {
    case gdr::Status::Ok: return kExitOk;
    case gdr::Status::InvalidInput:
    case gdr::Status::SelfIntersectingInput:
    case gdr::Status::IoError: return kExitInput;
    case gdr::Status::NoDevice:
    case gdr::Status::OutOfDeviceMemory: return kExitDevice;
    case gdr::Status::Aborted:
    case gdr::Status::InternalError: return kExitInternal;
  }
  return kExitInternal;
}

int dispatch(const std::vector<std::string>& argv) {
  if (argv.empty()) {
    std::fputs(kHelp, stderr);
    return kExitUsage;
  }
  const std::string& cmd = argv[0];
  const std::vector<std::string> rest(argv.begin() + 1, argv.end());
  if (cmd == "-h" || cmd == "--help" || cmd == "help") {
    if (!rest.empty() && rest[0] != "-h" && rest[0] != "--help")
      return dispatch({rest[0], "--help"});
    std::fputs(kHelp, stdout);
    return kExitOk;
  }
  if (cmd == "-V" || cmd == "--version" || cmd == "version") {
    std::printf("gdr %s (%s)\n", version(), build_summary().c_str());
    return kExitOk;
  }
  if (cmd == "2d") return run_2d(rest);
  if (cmd == "tet") return run_tet(rest);
  if (cmd == "rdt") return run_rdt(rest);
  if (cmd == "info") return run_info(rest);
  if (cmd == "selfcheck") return run_selfcheck(rest);
  throw UsageError("", "unknown command '" + cmd + "'");
}

}  // namespace

int main(int argc, char** argv) {
  gdr::cli::settle_process(argv);
  std::vector<std::string> args(argv + 1, argv + argc);
  try {
    return dispatch(args);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "gdr: error: %s\n", e.what());
    const std::string help = e.command().empty() ? "gdr --help" : "gdr " + e.command() + " --help";
    std::fprintf(stderr, "Try '%s' for usage.\n", help.c_str());
    return kExitUsage;
  } catch (const gdr::Error& e) {
    std::fprintf(stderr, "gdr: error: %s\n", e.what());
    return exit_code_for(e.status());
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "gdr: error: out of memory\n");
    return kExitDevice;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gdr: error: internal error: %s\n", e.what());
    return kExitInternal;
  }
}
