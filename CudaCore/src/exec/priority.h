// Atomic priority marking (the paper's S3 filter): many work items compete for mesh
// elements; each raises the element's mark to itself if its priority is higher and keeps the
// element only if its mark survives. Priority = [class:2][size:30][id:32].
//
// A mark is 32 bits: the number of the item holding it plus one (0 = free), not the 64-bit
// priority itself, which saves 4 bytes per mesh element; comparisons read the holder's
// priority through `prio_of(item)`. Ties (equal priorities) are broken by item number, so
// every mark ends with the single highest item of its competitors.
#pragma once
#include <cmath>
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

// The size key of a priority: sizes rounded down to a power of two, so that elements of
// about the same size rank by their (shuffled) ids.
GDR_HD_INLINE float size_class(double size) {
  if (!(size > 0) || !(size < 1e38)) return size > 0 ? 1e38f : 0.0f;
  return static_cast<float>(exp2(floor(log2(size))));
}

// A bijection of 32 bits that looks random: ids shuffled by a salt per iteration give
// pseudo-random order among equals.
GDR_HD_INLINE unsigned shuffle_id(unsigned x, unsigned salt) {
  x ^= salt;
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

GDR_HD_INLINE u64 make_priority(unsigned klass, float size, unsigned id) {
  return (u64(klass & 3u) << 62) | (u64(size_key(size) & 0x3fffffffu) << 32) | u64(id);
}

GDR_HD_INLINE unsigned priority_id(u64 p) { return unsigned(p & 0xffffffffu); }

// Does item `other` outrank item `me` of priority p?
template <class PrioOf>
GDR_HD_INLINE bool outranks(int other, int me, u64 p, const PrioOf& prio_of) {
  const u64 q = prio_of(other);
  return q > p || (q == p && other > me);
}

// Raises the mark `slot` to item `me` (priority p) unless a higher item holds it. Returns
// the previous mark (holder + 1, 0 = free); it equals me + 1 if `me` held it already.
template <class PrioOf>
GDR_HD_INLINE int raise_mark(int* slot, int me, u64 p, const PrioOf& prio_of) {
  int old = volatile_load(slot);
  for (;;) {
    if (old == me + 1 || (old != 0 && outranks(old - 1, me, p, prio_of))) return old;
    const int seen = atomic_cas(slot, old, me + 1);
    if (seen == old) return old;
    old = seen;
  }
}

// Claims `slot` for item `me`. Returns +1 if `me` took it, 0 if `me` held it already, -1 if
// a higher item holds it (`me` has lost this element).
template <class PrioOf>
GDR_HD_INLINE int claim(int* slot, int me, u64 p, const PrioOf& prio_of) {
  const int old = raise_mark(slot, me, p, prio_of);
  if (old == me + 1) return 0;
  return (old == 0 || !outranks(old - 1, me, p, prio_of)) ? 1 : -1;
}

// Is the mark held by an item that outranks `me`?
template <class PrioOf>
GDR_HD_INLINE bool held_above(int mark, int me, u64 p, const PrioOf& prio_of) {
  return mark != 0 && mark != me + 1 && outranks(mark - 1, me, p, prio_of);
}

}  // namespace gdr::exec
