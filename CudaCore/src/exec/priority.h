// Atomic priority marking (the paper's S3 filter): many work items compete for mesh
// elements; each writes its 64-bit priority with atomicMax and keeps the element only if
// its mark survives. Priority = [class:2][size:30][id:32], so ties never happen.
#pragma once
#include <cstring>

#include "exec/hd.h"

namespace gdr::exec {

// Monotone 30-bit key of a non-negative float size (bigger size -> bigger key).
GDR_HD_INLINE unsigned size_key(float size) {
  if (!(size > 0.0f)) return 0u;
  unsigned bits;
#if defined(__CUDA_ARCH__)
  bits = __float_as_uint(size);
#else
  std::memcpy(&bits, &size, sizeof bits);
#endif
  return bits >> 1;  // sign bit is 0: drop one mantissa bit, keep order
}

GDR_HD_INLINE u64 make_priority(unsigned klass, float size, unsigned id) {
  return (u64(klass & 3u) << 62) | (u64(size_key(size) & 0x3fffffffu) << 32) | u64(id);
}

GDR_HD_INLINE unsigned priority_id(u64 p) { return unsigned(p & 0xffffffffu); }

// Claims `slot` for priority p. Returns +1 if p took it first, 0 if p held it already,
// -1 if a higher priority holds it (p has lost this element).
GDR_HD_INLINE int claim(u64* slot, u64 p) {
  u64 old = atomic_max(slot, p);
  if (old < p) return 1;
  if (old == p) return 0;
  return -1;
}

}  // namespace gdr::exec
