// The execution-layer tests on the CPU space (OpenMP), plus CPU-only checks.
#include <omp.h>

#include "exec/cpu.h"
#include "exec_tests.h"

GDR_EXEC_TESTS(ExecCpu, gdr::exec::Cpu, (void)0)

namespace gdr::exec_test {
namespace {

// The pool hands freed blocks back by size class and trim() empties it; the memory counter
// counts the bytes asked for (as on the GPU), not the size classes.
TEST(ExecCpu, PoolReuseAndTrim) {
  using C = exec::Ops<exec::Cpu>;
  EXPECT_EQ(C::size_class(0), 4096u);
  EXPECT_EQ(C::size_class(4096), 4096u);
  EXPECT_EQ(C::size_class(4097), 8192u);
  EXPECT_EQ(C::size_class((1u << 20) + 1), 2u << 20);
  exec::MemoryCounter& mc = exec::memory_counter<exec::Cpu>();
  C::trim();  // an empty pool: the next free block of the class is the one freed below
  const std::size_t c0 = mc.current;
  void* p = C::allocate(5000);
  EXPECT_EQ(mc.current, c0 + 5000);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % 64, 0u);
  C::deallocate(p, 5000);
  EXPECT_EQ(mc.current, c0);
  void* q = C::allocate(8000);  // same class: the cached block comes back
  EXPECT_EQ(q, p);
  C::deallocate(q, 8000);
  C::trim();
  void* r = C::allocate(100);
  C::deallocate(r, 100);
  EXPECT_EQ(mc.current, c0);
}

// The scan must be right whatever team size OpenMP actually grants, e.g. when it is called
// from inside a parallel region (the inner region then runs on one thread) or with dynamic
// thread adjustment.
TEST(ExecCpu, ExclusiveScanInsideParallelRegion) {
  const std::size_t n = 100000;
  std::vector<long long> in(n), ref(n);
  long long run = 0;
  for (std::size_t i = 0; i < n; ++i) {
    in[i] = static_cast<long long>(mix32(static_cast<unsigned>(i)) % 100);
    ref[i] = run;
    run += in[i];
  }
  std::vector<long long> out(n, -1);
  long long total = -1;
#pragma omp parallel num_threads(2)
  {
#pragma omp single
    total = exec::Ops<exec::Cpu>::exclusive_scan(in.data(), out.data(), n);
  }
  EXPECT_EQ(total, run);
  EXPECT_EQ(first_mismatch(out, ref), -1);
}

}  // namespace
}  // namespace gdr::exec_test
