#include "build_info.h"

namespace gdr::cli {

const char* version() { return GDR_VERSION; }

bool built_with_cuda() {
#if defined(GDR_HAVE_CUDA)
  return true;
#else
  return false;
#endif
}

std::string build_summary() {
  std::string s = GDR_BUILD_TYPE;
  if (s.empty()) s = "default build type";
#if defined(__clang__)
  s += ", Clang " __clang_version__;
#elif defined(__GNUC__)
  s += ", GCC " __VERSION__;
#endif
  if (built_with_cuda())
    s += std::string(", CUDA backend (sm_") + GDR_CUDA_ARCHS + ")";
  else
    s += ", no CUDA backend (CPU only)";
  s += ", OpenMP CPU backend";
  return s;
}

}  // namespace gdr::cli
