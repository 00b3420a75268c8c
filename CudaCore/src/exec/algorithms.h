// Reusable parallel building blocks on top of Ops<Space>: fill, stream compaction (S1) and
// the tuple-based ExpandList loop (paper, Algorithm 4; S2 regularization, S5 deferment).
#pragma once
#include <algorithm>
#include <cstddef>

#include "exec/buffer.h"
#include "exec/hd.h"

namespace gdr::exec {

template <class Space, class T>
void fill(T* p, std::size_t n, T value) {
  Ops<Space>::for_each(n, [=] GDR_HD(long long i) { p[i] = value; });
}

template <class Space>
void iota(int* p, std::size_t n, int start = 0) {
  Ops<Space>::for_each(n, [=] GDR_HD(long long i) { p[i] = start + static_cast<int>(i); });
}

// Stream compaction: writes, in increasing order, every i in [0,n) with pred(i) != 0 into
// `out` and returns how many. `pred` is a host+device functor of (long long i) -> bool.
// `scratch` (resized to n ints, contents lost) holds the offsets: callers pass a long-lived
// buffer of their own, which saves an allocation (and device memory) per call.
template <class Space, class Pred>
std::size_t compact_indices(std::size_t n, Pred pred, Buffer<Space, int>& out,
                            Buffer<Space, int>& scratch) {
  if (n == 0) {
    out.resize_discard(0);
    return 0;
  }
  scratch.resize_discard(n);
  int* off = scratch.data();
  Ops<Space>::for_each(n, [=] GDR_HD(long long i) { off[i] = pred(i) ? 1 : 0; });
  const std::size_t total = static_cast<std::size_t>(Ops<Space>::exclusive_scan(off, off, n));
  out.resize_discard(total);
  int* o = out.data();
  // Selected items are where the offset steps up (the last one steps up to the total).
  const long long last = static_cast<long long>(n) - 1;
  const int tot = static_cast<int>(total);
  Ops<Space>::for_each(n, [=] GDR_HD(long long i) {
    if ((i < last ? off[i + 1] : tot) != off[i]) o[off[i]] = static_cast<int>(i);
  });
  return total;
}

// Stable compaction of a buffer into one of exactly the size kept: the elements x with
// keep(x), in their order; the old storage is freed. `scratch` (resized to n ints, contents
// lost) holds the offsets. `keep` is a host+device functor of (const T&) -> bool.
template <class Space, class T, class Keep>
std::size_t keep_if(Buffer<Space, T>& buf, Keep keep, Buffer<Space, int>& scratch) {
  const std::size_t n = buf.size();
  if (n == 0) return 0;
  scratch.resize_discard(n);
  int* off = scratch.data();
  const T* in = buf.data();
  Ops<Space>::for_each(n, [=] GDR_HD(long long i) { off[i] = keep(in[i]) ? 1 : 0; });
  const std::size_t total = static_cast<std::size_t>(Ops<Space>::exclusive_scan(off, off, n));
  Buffer<Space, T> kept(total);
  T* o = kept.data();
  const long long last = static_cast<long long>(n) - 1;
  const int tot = static_cast<int>(total);
  Ops<Space>::for_each(n, [=] GDR_HD(long long i) {
    if ((i < last ? off[i + 1] : tot) != off[i]) o[off[i]] = in[i];
  });
  buf.swap(kept);
  return total;
}

struct ExpandListResult {
  int rounds = 0;
  std::size_t size = 0;           // tuples in H at the end (all windows)
  std::size_t pending_begin = 0;  // [pending_begin, size): tuples left unprocessed (deferred)
  bool deferred() const { return pending_begin < size; }
};

struct ExpandListLimits {
  int max_rounds = 1 << 20;       // hard stop; the rest is deferred
  int defer_after_rounds = 1 << 20;  // from this round on, stop when the window is small...
  std::size_t defer_below = 0;    // ...i.e. has fewer tuples than this (S5)
  bool block_rounds = true;       // GPU: small windows run their rounds inside one block
  bool grid_rounds = true;        // GPU: large windows run their rounds in one grid-wide launch
};

// ExpandList (Algorithm 4). H[0, initial) is the first operation window. Each round applies
// step(i, h, out) to every tuple of the window; the step may modify h and writes up to K
// new tuples to out[0..K), returning how many. New tuples are appended to H with positions
// reserved by a prefix sum, and form the next window. Processed tuples stay in H so callers
// can inspect them afterwards (e.g. to verify cavity marks).
template <class Space, int K, class Tuple, class Step>
ExpandListResult expand_list(Buffer<Space, Tuple>& H, std::size_t initial, Step step,
                             const ExpandListLimits& limits = {}) {
  ExpandListResult r;
  std::size_t left = 0, right = initial;
  H.resize(initial);
  Buffer<Space, Tuple> stage;
  Buffer<Space, int> count;
  while (left < right) {
    if (r.rounds >= limits.max_rounds ||
        (r.rounds >= limits.defer_after_rounds && right - left < limits.defer_below))
      break;
    if constexpr (Ops<Space>::is_gpu) {
      // Rounds run on the device without a host round trip: small windows (the long tails of
      // big cavities) inside one block, large ones across the whole GPU.
      constexpr std::size_t kSmallWindow = 4096;
      if (limits.block_rounds && right - left <= kSmallWindow) {
        // Room for the rounds' new tuples: a quarter of H (small problems stay small in
        // memory), at least one round's worth, at most 64k tuples.
        const std::size_t room = std::clamp<std::size_t>(right / 4, K * (right - left),
                                                         std::size_t(1) << 16);
        H.resize(right + room);
        const std::size_t before = left;
        Ops<Space>::template small_rounds<K>(H.data(), left, right, right + room, step, r.rounds,
                                             limits.max_rounds, limits.defer_after_rounds,
                                             limits.defer_below, kSmallWindow);
        H.resize(right);
        if (left != before) continue;  // otherwise no round fitted: one round the normal way
      } else if (limits.grid_rounds) {
        // Room for one round at the most each tuple can add, and for H to grow by a
        // sixteenth (device memory per element): the kernel stops where a round might not fit.
        const std::size_t room = K * (right - left) + right / 16;
        H.resize(right + room);
        const std::size_t before = left;
        const bool ran = Ops<Space>::template grid_rounds<K>(
            H.data(), left, right, right + room, step, r.rounds, limits.max_rounds,
            limits.defer_after_rounds, limits.defer_below, kSmallWindow);
        H.resize(right);
        if (ran && left != before) continue;
      }
    }
    const std::size_t w = right - left;
    stage.resize_discard(w * K);
    count.resize_discard(w);
    Tuple* h = H.data() + left;
    Tuple* st = stage.data();
    int* cnt = count.data();
    const std::size_t base = left;
    Ops<Space>::for_each_heavy(w, [=] GDR_HD(long long j) {
      cnt[j] = step(static_cast<long long>(base) + j, h[j], st + j * K);
    });
    const std::size_t added = static_cast<std::size_t>(Ops<Space>::exclusive_scan(cnt, cnt, w));
    ++r.rounds;
    if (added) {
      H.resize(right + added);
      Tuple* dst = H.data() + right;
      // The scan destroyed the counts: recover each as the difference of offsets.
      const int total = static_cast<int>(added);
      const long long wl = static_cast<long long>(w);
      Ops<Space>::for_each(w, [=] GDR_HD(long long j) {
        const int begin = cnt[j];
        const int end = (j + 1 < wl) ? cnt[j + 1] : total;
        for (int k = begin; k < end; ++k) dst[k] = st[j * K + (k - begin)];
      });
    }
    left = right;
    right += added;
  }
  r.size = right;
  r.pending_begin = left;
  return r;
}

}  // namespace gdr::exec
