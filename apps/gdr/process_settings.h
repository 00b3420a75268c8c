// Settings that libgomp and glibc read only when a process starts: gdr (and gdr_bench, which
// measures what gdr does) set them and start again, unless the user chose their own.
#pragma once
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>

namespace gdr::cli {

// GLIBC_TUNABLES as the user started us (baselines run by gdr_bench get it back).
inline constexpr const char* kUserTunables = "GDR_USER_GLIBC_TUNABLES";

// - OpenMP's threads spin at every barrier before they sleep. Where other work shares the
//   cores they spin while the thread they wait for is not running: two runs of 16 threads at
//   once on 16 cores refined the counties map in 30 s each, against 0.2 s alone (libgomp's
//   default; 2.2 s with a spin of 10,000, 0.6 s with passive waiting, which costs 1.4-1.7x on
//   free cores; Benchmarks/RESULTS.md, sixty-third and sixty-fourth runs): a short spin.
// - Large allocations on transparent huge pages (glibc.malloc.hugetlb=1; the kernel's usual
//   "madvise" mode gives them only on request): a 4 KiB page fault at each first touch was a
//   quarter of one thread's 2D run of a 1M-segment map, reading and writing included
//   (Benchmarks/RESULTS.md, 2026-12-07, host memory on huge pages).
inline void settle_process(char** argv) {
  const auto chosen = [](const char* name) {
    const char* v = std::getenv(name);
    return v && *v;
  };
  bool changed = false;
  if (!chosen("OMP_WAIT_POLICY") && !chosen("GOMP_SPINCOUNT"))
    changed |= setenv("GOMP_SPINCOUNT", "10000", 1) == 0;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (!chosen(kUserTunables) && !(tunables && std::strstr(tunables, "glibc.malloc.hugetlb"))) {
    const std::string user = tunables ? tunables : "";
    const std::string ours = user.empty() ? "glibc.malloc.hugetlb=1" : user + ":glibc.malloc.hugetlb=1";
    if (setenv(kUserTunables, user.empty() ? "-" : user.c_str(), 1) == 0 &&
        setenv("GLIBC_TUNABLES", ours.c_str(), 1) == 0)
      changed = true;
  }
  if (changed) execv("/proc/self/exe", argv);  // returns only if it failed: go on as we are
}

// In a child about to run another program: GLIBC_TUNABLES as the user had it.
inline void restore_user_tunables() {
  const char* user = std::getenv(kUserTunables);
  if (!user || !*user) return;
  if (std::strcmp(user, "-") == 0) unsetenv("GLIBC_TUNABLES");
  else setenv("GLIBC_TUNABLES", user, 1);
  unsetenv(kUserTunables);
}

}  // namespace gdr::cli
