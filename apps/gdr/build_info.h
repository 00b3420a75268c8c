// How this gdr binary was built (version, compiler, CUDA), for --version and selfcheck.
#pragma once
#include <string>

namespace gdr::cli {

const char* version();
std::string build_summary();  // one line, e.g. "Release, GCC 12.2.0, CUDA backend (sm_90), ..."
bool built_with_cuda();

}  // namespace gdr::cli
