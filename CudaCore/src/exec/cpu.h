// The CPU execution space: OpenMP threads over host memory. Compiled by the host compiler.
#pragma once
#include <omp.h>
#include <sys/mman.h>

#include <parallel/algorithm>
#include <cstdlib>
#include <cstring>
#include <map>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include "exec/space.h"
#include "gdr/error.h"

namespace gdr::exec {

template <>
struct Ops<Cpu> {
  static constexpr bool is_gpu = false;
  static constexpr std::ptrdiff_t serial_below = 4096;  // OpenMP start-up costs more below this

  // Allocations are cached by power-of-two size class: phases allocate scratch arrays every
  // iteration, and fresh pages from the OS would cost a page fault each. The memory counter
  // counts the bytes asked for, as on the GPU.
  static std::size_t size_class(std::size_t bytes) {
    std::size_t c = 4096;
    while (c < bytes) c <<= 1;
    return c;
  }
  struct Pool {
    std::mutex lock;
    std::multimap<std::size_t, void*> free_blocks;
    ~Pool() {
      for (auto& b : free_blocks) std::free(b.second);
    }
  };
  static Pool& pool() {
    static Pool p;
    return p;
  }
  static constexpr std::size_t kHugePage = std::size_t(2) << 20;
  static void* allocate(std::size_t bytes) {
    const std::size_t c = size_class(bytes);
    {
      std::lock_guard<std::mutex> g(pool().lock);
      auto it = pool().free_blocks.find(c);
      if (it != pool().free_blocks.end()) {
        void* p = it->second;
        pool().free_blocks.erase(it);
        memory_counter<Cpu>().add(bytes);
        return p;
      }
    }
    // Large blocks on 2 MiB pages where the kernel gives them on request (transparent huge
    // pages in "madvise" mode, the usual default): with a 4 KiB page fault per first touch,
    // one thread's 2D refinement of a 1M-segment map took 3.5-4.9 s against 2.8-4.1 s
    // (Benchmarks/RESULTS.md, 2026-12-07, host memory on huge pages).
    void* p = std::aligned_alloc(c >= kHugePage ? kHugePage : 64, c);
#ifdef MADV_HUGEPAGE
    if (p && c >= kHugePage) madvise(p, c, MADV_HUGEPAGE);
#endif
    if (!p)
      throw Error(Status::OutOfDeviceMemory,
                  "out of host memory allocating " + std::to_string(bytes) + " bytes");
    memory_counter<Cpu>().add(bytes);
    return p;
  }
  static void deallocate(void* p, std::size_t bytes) {
    const std::size_t c = size_class(bytes);
    std::lock_guard<std::mutex> g(pool().lock);
    pool().free_blocks.emplace(c, p);
    memory_counter<Cpu>().sub(bytes);
  }
  // Returns cached blocks to the system (end of a run).
  static void trim() {
    std::lock_guard<std::mutex> g(pool().lock);
    for (auto& b : pool().free_blocks) std::free(b.second);
    pool().free_blocks.clear();
  }
  static void copy_to_space(void* dst, const void* src, std::size_t bytes) {
    std::memcpy(dst, src, bytes);
  }
  // Large copies and fills by all threads: one thread does not reach the memory's bandwidth,
  // and results land in fresh host memory, whose page faults of first touch cost as much as
  // the copy. (The 2D engine clears its marks, 4 bytes a triangle, twice an iteration.)
  static constexpr std::size_t kParallelBytes = std::size_t(4) << 20;
  template <class Part>
  static void by_parts(std::size_t bytes, Part part) {
    const long long parts = 64;
#pragma omp parallel for
    for (long long p = 0; p < parts; ++p) part(bytes * p / parts, bytes * (p + 1) / parts);
  }
  static void copy_to_host(void* dst, const void* src, std::size_t bytes) {
    if (bytes < kParallelBytes) {
      std::memcpy(dst, src, bytes);
      return;
    }
    by_parts(bytes, [=](std::size_t b, std::size_t e) {
      std::memcpy(static_cast<char*>(dst) + b, static_cast<const char*>(src) + b, e - b);
    });
  }
  static void copy_d2d(void* dst, const void* src, std::size_t bytes) { copy_to_host(dst, src, bytes); }
  static void zero(void* p, std::size_t bytes) {
    if (bytes < kParallelBytes) {
      std::memset(p, 0, bytes);
      return;
    }
    by_parts(bytes, [=](std::size_t b, std::size_t e) { std::memset(static_cast<char*>(p) + b, 0, e - b); });
  }
  static void synchronize() {}

  template <class F>
  static void for_each(std::size_t n, F f) {
    const std::ptrdiff_t m = static_cast<std::ptrdiff_t>(n);
    if (m < serial_below) {
      for (std::ptrdiff_t i = 0; i < m; ++i) f(i);
      return;
    }
#pragma omp parallel for schedule(dynamic, 1024)
    for (std::ptrdiff_t i = 0; i < m; ++i) f(i);
  }

  // For items that each cost far more than a few memory accesses (ExpandList's steps run exact
  // predicates): a team from a few hundred items on, in small chunks. The tails of 3D
  // refinement grow a few hundred large cavities in rounds of 1-4k tuples, which for_each ran
  // on one thread (the boat at B = 1.4: the cavity phase 11.4 s on one thread, 6.2 s on 16).
  template <class F>
  static void for_each_heavy(std::size_t n, F f) {
    const std::ptrdiff_t m = static_cast<std::ptrdiff_t>(n);
    if (m < 256) {
      for (std::ptrdiff_t i = 0; i < m; ++i) f(i);
      return;
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (std::ptrdiff_t i = 0; i < m; ++i) f(i);
  }

  // Stable sort of (key, value) pairs by key.
  static void sort_pairs(unsigned long long* keys, int* values, std::size_t n) {
    std::vector<std::pair<unsigned long long, int>> kv(n);
    const std::ptrdiff_t m = static_cast<std::ptrdiff_t>(n);
#pragma omp parallel for if (m > serial_below)
    for (std::ptrdiff_t i = 0; i < m; ++i) kv[i] = {keys[i], values[i]};
    __gnu_parallel::stable_sort(kv.begin(), kv.end(),
                                [](const auto& a, const auto& b) { return a.first < b.first; });
#pragma omp parallel for if (m > serial_below)
    for (std::ptrdiff_t i = 0; i < m; ++i) keys[i] = kv[i].first, values[i] = kv[i].second;
  }

  // out[i] = sum(in[0..i)); returns the total. `in` and `out` may alias.
  template <class T>
  static T exclusive_scan(const T* in, T* out, std::size_t n) {
    const std::ptrdiff_t m = static_cast<std::ptrdiff_t>(n);
    if (m < 4 * serial_below) {
      T run = T(0);
      for (std::ptrdiff_t i = 0; i < m; ++i) {
        T v = in[i];
        out[i] = run;
        run += v;
      }
      return run;
    }
    const int nt = omp_get_max_threads();
    std::vector<T> partial(nt + 1, T(0));
    int team = 1;
#pragma omp parallel num_threads(nt)
    {
      // The team may be smaller than asked (nested region, dynamic threads): split by
      // the team actually granted, or some chunks would never be scanned.
      const int nth = omp_get_num_threads();
      const int t = omp_get_thread_num();
      const std::ptrdiff_t lo = m * t / nth, hi = m * (t + 1) / nth;
      T s = T(0);
      for (std::ptrdiff_t i = lo; i < hi; ++i) s += in[i];
      partial[t + 1] = s;
#pragma omp barrier
#pragma omp single
      {
        team = nth;
        for (int k = 0; k < nth; ++k) partial[k + 1] += partial[k];
      }
      T run = partial[t];
      for (std::ptrdiff_t i = lo; i < hi; ++i) {
        T v = in[i];
        out[i] = run;
        run += v;
      }
    }
    return partial[team];
  }
};

}  // namespace gdr::exec
