// Execution spaces. Algorithms are templates on a Space; each space supplies Ops<Space>:
//   Cpu  (exec/cpu.h, compiled by g++ with OpenMP)
//   Cuda (exec/cuda.cuh, compiled by nvcc)
// Ops<Space> provides: allocate/deallocate, copies, zero-fill, for_each(n, f),
// exclusive_scan, sort_pairs (stable, by 64-bit key), synchronize. Everything else
// (buffers, compaction, ExpandList) is written once on top of these.
#pragma once
#include <cstddef>

namespace gdr::exec {

struct Cpu {};
struct Cuda {};

template <class Space>
struct Ops;  // specialised per space

// Bytes currently held and the peak, per space, for the stats (reset per run).
struct MemoryCounter {
  std::size_t current = 0;
  std::size_t peak = 0;
  void add(std::size_t b) {
    current += b;
    if (current > peak) peak = current;
  }
  void sub(std::size_t b) { current -= b; }
};

template <class Space>
MemoryCounter& memory_counter() {
  static MemoryCounter counter;
  return counter;
}

}  // namespace gdr::exec
