// Host+device portability: one macro and a few atomics, so that kernels are written once
// and compiled by nvcc for the GPU and by g++ (OpenMP) for the CPU.
#pragma once
#include <cstdint>
#include <cstring>

#if defined(__CUDACC__)
#define GDR_HD __host__ __device__
#define GDR_HD_INLINE __host__ __device__ __forceinline__
#else
#define GDR_HD
#define GDR_HD_INLINE inline
#endif

namespace gdr::exec {

using u64 = unsigned long long;

// Atomically raises *addr to at least v; returns the previous value.
GDR_HD_INLINE u64 atomic_max(u64* addr, u64 v) {
#if defined(__CUDA_ARCH__)
  return atomicMax(addr, v);
#else
  u64 old = __atomic_load_n(addr, __ATOMIC_RELAXED);
  while (old < v && !__atomic_compare_exchange_n(addr, &old, v, true, __ATOMIC_RELAXED,
                                                 __ATOMIC_RELAXED)) {
  }
  return old;
#endif
}

GDR_HD_INLINE int atomic_add(int* addr, int v) {
#if defined(__CUDA_ARCH__)
  return atomicAdd(addr, v);
#else
  return __atomic_fetch_add(addr, v, __ATOMIC_RELAXED);
#endif
}

GDR_HD_INLINE u64 atomic_add(u64* addr, u64 v) {
#if defined(__CUDA_ARCH__)
  return atomicAdd(addr, v);
#else
  return __atomic_fetch_add(addr, v, __ATOMIC_RELAXED);
#endif
}

GDR_HD_INLINE int atomic_or(int* addr, int v) {
#if defined(__CUDA_ARCH__)
  return atomicOr(addr, v);
#else
  return __atomic_fetch_or(addr, v, __ATOMIC_RELAXED);
#endif
}

GDR_HD_INLINE int atomic_and(int* addr, int v) {
#if defined(__CUDA_ARCH__)
  return atomicAnd(addr, v);
#else
  return __atomic_fetch_and(addr, v, __ATOMIC_RELAXED);
#endif
}

// Compare-and-swap; returns the value found (== expected when the swap happened).
GDR_HD_INLINE int atomic_cas(int* addr, int expected, int desired) {
#if defined(__CUDA_ARCH__)
  return atomicCAS(addr, expected, desired);
#else
  __atomic_compare_exchange_n(addr, &expected, desired, false, __ATOMIC_RELAXED, __ATOMIC_RELAXED);
  return expected;
#endif
}

GDR_HD_INLINE int atomic_min(int* addr, int v) {
#if defined(__CUDA_ARCH__)
  return atomicMin(addr, v);
#else
  int old = __atomic_load_n(addr, __ATOMIC_RELAXED);
  while (old > v && !__atomic_compare_exchange_n(addr, &old, v, true, __ATOMIC_RELAXED,
                                                 __ATOMIC_RELAXED)) {
  }
  return old;
#endif
}

GDR_HD_INLINE int atomic_max(int* addr, int v) {
#if defined(__CUDA_ARCH__)
  return atomicMax(addr, v);
#else
  int old = __atomic_load_n(addr, __ATOMIC_RELAXED);
  while (old < v && !__atomic_compare_exchange_n(addr, &old, v, true, __ATOMIC_RELAXED,
                                                 __ATOMIC_RELAXED)) {
  }
  return old;
#endif
}

// Relaxed load that the compiler may not cache (values other threads change with atomics).
template <class T>
GDR_HD_INLINE T volatile_load(const T* addr) {
  return *static_cast<const volatile T*>(addr);
}

// The bits of a double: for values >= 0 their order is the values' order (so atomic_max of
// ~bits_of(v) keeps the least v).
GDR_HD_INLINE u64 bits_of(double v) {
#if defined(__CUDA_ARCH__)
  return static_cast<u64>(__double_as_longlong(v));
#else
  u64 b;
  std::memcpy(&b, &v, sizeof b);
  return b;
#endif
}

template <class T>
GDR_HD_INLINE void swap(T& a, T& b) {
  T t = a;
  a = b;
  b = t;
}

}  // namespace gdr::exec
