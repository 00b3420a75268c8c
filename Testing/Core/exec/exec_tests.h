// Unit tests of the execution layer (CudaCore/src/exec), written once as templates on the
// execution space. exec_cpu.cpp instantiates them for exec::Cpu (OpenMP) and exec_cuda.cu
// for exec::Cuda. Every check compares against a serial reference on the host, on random
// data, for sizes that include 0, 1, the OpenMP thresholds (4096 for for_each, 16384 for
// the scan) and about 1e6.
//
// Include exec/cpu.h or exec/cuda.cuh before this header.
#pragma once
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "exec/algorithms.h"
#include "exec/buffer.h"
#include "exec/hd.h"
#include "exec/priority.h"
#include "exec/space.h"

namespace gdr::exec_test {

using exec::Buffer;
using exec::Ops;
using exec::u64;

// Sizes around the OpenMP thresholds and one large size.
inline std::vector<std::size_t> test_sizes() {
  return {0, 1, 2, 3, 100, 4095, 4096, 4097, 16383, 16384, 16385, 65537, 1000003};
}

// Index of the first difference of two arrays (or of their sizes), -1 when equal. Used
// instead of comparing whole vectors so that a failure prints one element, not a million.
template <class T>
long long first_mismatch(const std::vector<T>& a, const std::vector<T>& b) {
  const std::size_t n = std::min(a.size(), b.size());
  for (std::size_t i = 0; i < n; ++i)
    if (!(a[i] == b[i])) return static_cast<long long>(i);
  if (a.size() != b.size()) return static_cast<long long>(n);
  return -1;
}

// A deterministic integer hash (host and device).
GDR_HD_INLINE unsigned mix32(unsigned x) {
  x ^= x >> 16;
  x *= 0x7feb352du;
  x ^= x >> 15;
  x *= 0x846ca68bu;
  x ^= x >> 16;
  return x;
}

// ---------------------------------------------------------------------------------------
// fill / iota / for_each

template <class Space>
void check_fill_iota() {
  for (std::size_t n : test_sizes()) {
    SCOPED_TRACE("n = " + std::to_string(n));
    Buffer<Space, int> a(n);
    exec::iota<Space>(a.data(), n, 7);
    std::vector<int> h = a.to_host();
    ASSERT_EQ(h.size(), n);
    long long bad = -1;
    for (std::size_t i = 0; i < n && bad < 0; ++i)
      if (h[i] != 7 + static_cast<int>(i)) bad = static_cast<long long>(i);
    EXPECT_EQ(bad, -1) << "iota wrong at this index";

    Buffer<Space, double> d(n);
    exec::fill<Space>(d.data(), n, 2.5);
    std::vector<double> hd = d.to_host();
    EXPECT_EQ(std::count(hd.begin(), hd.end(), 2.5), static_cast<long long>(n));

    // for_each visits each index exactly once: every index adds one to its own cell and
    // one to a shared counter.
    Buffer<Space, int> hits(n);
    hits.zero();
    Buffer<Space, int> total(1);
    total.zero();
    int* hp = hits.data();
    int* tp = total.data();
    Ops<Space>::for_each(n, [=] GDR_HD(long long i) {
      exec::atomic_add(hp + i, 1);
      exec::atomic_add(tp, 1);
    });
    std::vector<int> hh = hits.to_host();
    EXPECT_EQ(std::count(hh.begin(), hh.end(), 1), static_cast<long long>(n));
    EXPECT_EQ(total.get(0), static_cast<int>(n));
  }
}

// ---------------------------------------------------------------------------------------
// exclusive_scan, out of place and in place

template <class Space, class T>
void check_scan_type(T max_value, unsigned seed) {
  std::mt19937_64 rng(seed);
  for (std::size_t n : test_sizes()) {
    SCOPED_TRACE("n = " + std::to_string(n) + ", sizeof(T) = " + std::to_string(sizeof(T)));
    std::vector<T> in(n);
    std::uniform_int_distribution<long long> dist(0, static_cast<long long>(max_value));
    for (auto& v : in) v = static_cast<T>(dist(rng));
    if (n > 10) in[n / 2] = 0;  // zeros inside runs
    std::vector<T> ref(n);
    T run = 0;
    for (std::size_t i = 0; i < n; ++i) {
      ref[i] = run;
      run += in[i];
    }

    Buffer<Space, T> din, dout(n);
    din.upload(in);
    const T total = Ops<Space>::exclusive_scan(din.data(), dout.data(), n);
    EXPECT_EQ(total, run);
    EXPECT_EQ(first_mismatch(dout.to_host(), ref), -1) << "out-of-place scan differs";
    EXPECT_EQ(first_mismatch(din.to_host(), in), -1) << "out-of-place scan changed its input";

    // In place: in and out alias.
    const T total2 = Ops<Space>::exclusive_scan(din.data(), din.data(), n);
    EXPECT_EQ(total2, run);
    EXPECT_EQ(first_mismatch(din.to_host(), ref), -1) << "in-place scan differs";
  }
}

template <class Space>
void check_exclusive_scan() {
  check_scan_type<Space, int>(9, 1);
  check_scan_type<Space, long long>(1ll << 40, 2);
  check_scan_type<Space, u64>(1ull << 40, 3);
  check_scan_type<Space, std::size_t>(3, 4);
}

// sort_pairs: by key, stable (equal keys keep their values' order), on many equal keys.
template <class Space>
void check_sort_pairs() {
  std::mt19937 rng(5);
  for (const std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(1000), std::size_t(300000)}) {
    std::vector<u64> keys(n);
    std::vector<int> values(n);
    for (std::size_t i = 0; i < n; ++i) {
      keys[i] = (rng() % 64) << 58 | (rng() % 3);  // high and low bits, many ties
      values[i] = static_cast<int>(i);
    }
    std::vector<std::pair<u64, int>> ref(n);
    for (std::size_t i = 0; i < n; ++i) ref[i] = {keys[i], values[i]};
    std::stable_sort(ref.begin(), ref.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    Buffer<Space, u64> k;
    Buffer<Space, int> v;
    k.upload(keys);
    v.upload(values);
    Ops<Space>::sort_pairs(k.data(), v.data(), n);
    const std::vector<u64> ks = k.to_host();
    const std::vector<int> vs = v.to_host();
    for (std::size_t i = 0; i < n; ++i) {
      ASSERT_EQ(ks[i], ref[i].first) << "n " << n << " at " << i;
      ASSERT_EQ(vs[i], ref[i].second) << "n " << n << " at " << i << ": not stable";
    }
  }
}

// ---------------------------------------------------------------------------------------
// compact_indices (S1)

template <class Space>
void check_compaction() {
  std::mt19937 rng(11);
  const double densities[] = {0.0, 0.01, 0.5, 0.97, 1.0};
  // One scratch for all calls, as the engine reuses its own: stale offsets from a bigger
  // earlier call must not leak into a later one.
  Buffer<Space, int> scratch(3);
  exec::fill<Space>(scratch.data(), 3, 9);
  for (std::size_t n : test_sizes()) {
    for (double p : densities) {
      SCOPED_TRACE("n = " + std::to_string(n) + ", density = " + std::to_string(p));
      std::vector<int> flags(n);
      std::bernoulli_distribution coin(p);
      for (auto& f : flags) f = coin(rng) ? 1 + static_cast<int>(rng() % 5) : 0;
      std::vector<int> ref;
      for (std::size_t i = 0; i < n; ++i)
        if (flags[i]) ref.push_back(static_cast<int>(i));

      Buffer<Space, int> dflags;
      dflags.upload(flags);
      const int* f = dflags.data();
      Buffer<Space, int> out(7);  // stale contents and size must not leak into the result
      exec::fill<Space>(out.data(), 7, -5);
      const std::size_t m =
          exec::compact_indices<Space>(n, [=] GDR_HD(long long i) { return f[i] != 0; }, out,
                                       scratch);
      EXPECT_EQ(m, ref.size());
      EXPECT_EQ(out.size(), ref.size());
      EXPECT_EQ(first_mismatch(out.to_host(), ref), -1) << "compacted indices differ (order or content)";
      EXPECT_EQ(first_mismatch(dflags.to_host(), flags), -1) << "compaction changed the flags";
    }
    // A predicate of the index alone.
    {
      SCOPED_TRACE("n = " + std::to_string(n) + ", every third");
      Buffer<Space, int> out;
      const std::size_t m =
          exec::compact_indices<Space>(n, [=] GDR_HD(long long i) { return i % 3 == 1; }, out,
                                       scratch);
      std::vector<int> ref;
      for (std::size_t i = 1; i < n; i += 3) ref.push_back(static_cast<int>(i));
      EXPECT_EQ(m, ref.size());
      EXPECT_EQ(first_mismatch(out.to_host(), ref), -1);
    }
  }
}

// ---------------------------------------------------------------------------------------
// Buffer

struct Rec {
  int a;
  float b;
  long long c;
  bool operator==(const Rec& o) const { return a == o.a && b == o.b && c == o.c; }
};

template <class Space>
void check_buffer() {
  std::mt19937 rng(5);
  // Upload / download / to_host round trip, get / set, partial download with offset.
  for (std::size_t n : test_sizes()) {
    SCOPED_TRACE("n = " + std::to_string(n));
    std::vector<Rec> h(n);
    for (std::size_t i = 0; i < n; ++i)
      h[i] = Rec{static_cast<int>(rng()), static_cast<float>(i) * 0.5f, static_cast<long long>(rng()) << 20};
    Buffer<Space, Rec> b;
    EXPECT_TRUE(b.empty());
    b.upload(h);
    EXPECT_EQ(b.size(), n);
    EXPECT_GE(b.capacity(), n);
    EXPECT_EQ(first_mismatch(b.to_host(), h), -1) << "upload/to_host round trip";
    if (n >= 3) {
      std::vector<Rec> part(n - 2);
      b.download(part.data(), n - 2, 1);
      EXPECT_EQ(first_mismatch(part, std::vector<Rec>(h.begin() + 1, h.end() - 1)), -1)
          << "download with offset";
      const Rec r{-1, -2.0f, -3};
      b.set(n / 2, r);
      EXPECT_EQ(b.get(n / 2), r);
      EXPECT_EQ(b.get(n / 2 - 1), h[n / 2 - 1]);
      EXPECT_EQ(b.get(n / 2 + 1), h[n / 2 + 1]);
    }
    // upload of a smaller array into a used buffer: size follows, contents new.
    std::vector<Rec> small(n / 3, Rec{1, 2.0f, 3});
    b.upload(small);
    EXPECT_EQ(b.size(), small.size());
    EXPECT_EQ(first_mismatch(b.to_host(), small), -1);
  }

  // Growing by resize keeps contents: grow in irregular steps to 1e6, writing each new tail
  // with a kernel, so that the buffer reallocates many times.
  {
    Buffer<Space, int> b;
    std::size_t size = 0;
    const std::size_t steps[] = {1, 0, 3, 4096, 1, 10000, 70000, 5, 400000, 600000};
    for (std::size_t s : steps) {
      const std::size_t old = size;
      size += s;
      const std::size_t cap_before = b.capacity();
      b.resize(size);
      EXPECT_EQ(b.size(), size);
      EXPECT_GE(b.capacity(), size);
      if (size > cap_before) EXPECT_GE(b.capacity(), cap_before + cap_before / 16) << "growth not geometric";
      int* p = b.data();
      Ops<Space>::for_each(s, [=] GDR_HD(long long i) {
        const long long k = static_cast<long long>(old) + i;
        p[k] = static_cast<int>(mix32(static_cast<unsigned>(k)));
      });
    }
    std::vector<int> ref(size);
    for (std::size_t k = 0; k < size; ++k) ref[k] = static_cast<int>(mix32(static_cast<unsigned>(k)));
    EXPECT_EQ(first_mismatch(b.to_host(), ref), -1) << "resize lost contents";

    // Shrinking by resize keeps the prefix and the capacity; growing back within the
    // capacity keeps the prefix.
    const std::size_t cap = b.capacity();
    b.resize(1000);
    EXPECT_EQ(b.size(), 1000u);
    EXPECT_EQ(b.capacity(), cap);
    b.resize(5000);
    std::vector<int> back = b.to_host();
    EXPECT_EQ(first_mismatch(std::vector<int>(back.begin(), back.begin() + 1000),
                             std::vector<int>(ref.begin(), ref.begin() + 1000)),
              -1);

    // shrink_to: exact capacity, prefix kept.
    b.shrink_to(777);
    EXPECT_EQ(b.size(), 777u);
    EXPECT_EQ(b.capacity(), 777u);
    EXPECT_EQ(first_mismatch(b.to_host(), std::vector<int>(ref.begin(), ref.begin() + 777)), -1)
        << "shrink_to lost contents";
    // shrink_to beyond the capacity grows like resize and keeps contents.
    b.shrink_to(2000);
    EXPECT_EQ(b.size(), 2000u);
    EXPECT_GE(b.capacity(), 2000u);
    std::vector<int> grown = b.to_host();
    EXPECT_EQ(first_mismatch(std::vector<int>(grown.begin(), grown.begin() + 777),
                             std::vector<int>(ref.begin(), ref.begin() + 777)),
              -1);
    b.shrink_to(0);
    EXPECT_EQ(b.size(), 0u);
    EXPECT_TRUE(b.empty());
    b.resize(3);  // usable after shrinking to nothing
    b.set(2, 42);
    EXPECT_EQ(b.get(2), 42);
  }

  // resize_discard, zero, moves, release.
  {
    Buffer<Space, int> a(10);
    exec::iota<Space>(a.data(), 10, 100);
    a.resize_discard(4);
    EXPECT_EQ(a.size(), 4u);
    EXPECT_EQ(a.capacity(), 10u);
    a.resize_discard(50);
    EXPECT_EQ(a.size(), 50u);
    a.zero();
    std::vector<int> z = a.to_host();
    EXPECT_EQ(std::count(z.begin(), z.end(), 0), 50);

    exec::iota<Space>(a.data(), 50, 1);
    const int* pa = a.data();
    Buffer<Space, int> moved(std::move(a));
    EXPECT_EQ(moved.data(), pa);
    EXPECT_EQ(moved.size(), 50u);
    EXPECT_EQ(moved.get(49), 50);
    Buffer<Space, int> other(3);
    other = std::move(moved);
    EXPECT_EQ(other.size(), 50u);
    EXPECT_EQ(other.get(0), 1);
    other.release();
    EXPECT_EQ(other.size(), 0u);
    EXPECT_EQ(other.capacity(), 0u);
    EXPECT_EQ(other.data(), nullptr);
    std::vector<int> none = other.to_host();
    EXPECT_TRUE(none.empty());
  }
}

// ---------------------------------------------------------------------------------------
// Atomic priority marking (S3)

struct PrioInput {
  unsigned klass;
  float size;
  unsigned id;
};

template <class Space>
void check_priority() {
  // claim() return codes on one slot, through the space's own kernels. Items 0..3 with
  // priorities p1, p0 (lower class), p2 (same class and size as p1, larger id), and p1 again
  // (an exact tie with item 0, broken by the item number).
  {
    Buffer<Space, int> slot(1);
    slot.zero();
    Buffer<Space, int> res(7);
    const u64 p1 = exec::make_priority(1, 2.0f, 10);
    const u64 p0 = exec::make_priority(0, 100.0f, 99);
    const u64 p2 = exec::make_priority(1, 2.0f, 11);
    Buffer<Space, u64> prio;
    prio.upload(std::vector<u64>{p1, p0, p2, p1});
    int* s = slot.data();
    int* r = res.data();
    const u64* pr = prio.data();
    auto prio_of = [=] GDR_HD(int k) { return pr[k]; };
    Ops<Space>::for_each(1, [=] GDR_HD(long long) {
      r[0] = exec::claim(s, 0, p1, prio_of);  // first: takes it
      r[1] = exec::claim(s, 0, p1, prio_of);  // again: already holds it
      r[2] = exec::claim(s, 1, p0, prio_of);  // lower class: loses
      r[3] = exec::claim(s, 2, p2, prio_of);  // same class and size, larger id: takes it
      r[4] = exec::claim(s, 0, p1, prio_of);  // now lower
      r[5] = exec::held_above(*s, 0, p1, prio_of) ? 1 : 0;
      r[6] = exec::held_above(*s, 2, p2, prio_of) ? 1 : 0;  // its own mark
    });
    const std::vector<int> got = res.to_host();
    EXPECT_EQ(got, (std::vector<int>{1, 0, -1, 1, -1, 1, 0}));
    EXPECT_EQ(slot.get(0), 3) << "the mark names item 2 (plus one)";
    EXPECT_EQ(exec::priority_id(p2), 11u);
    // Equal priorities: the larger item number wins, whichever comes first.
    Ops<Space>::for_each(1, [=] GDR_HD(long long) {
      *s = 0;
      r[0] = exec::claim(s, 3, p1, prio_of);
      r[1] = exec::claim(s, 0, p1, prio_of);
      r[2] = exec::claim(s, 0, p1, prio_of);
    });
    EXPECT_EQ(res.to_host()[0], 1);
    EXPECT_EQ(res.to_host()[1], -1);
    EXPECT_EQ(slot.get(0), 4);
  }

  // make_priority: the space computes the same keys as the host, and the order of keys is
  // lexicographic in (class, size, id), with equal sizes compared by id.
  {
    std::mt19937 rng(17);
    const std::size_t n = 200000;
    std::vector<PrioInput> in(n);
    const float sizes[] = {0.0f, -1.0f, 1e-30f, 1e-3f, 0.5f, 1.0f, 1.0000001f, 3.0f, 1e30f,
                           std::numeric_limits<float>::max(), std::numeric_limits<float>::infinity(),
                           std::numeric_limits<float>::quiet_NaN(), std::numeric_limits<float>::denorm_min()};
    std::uniform_real_distribution<float> ureal(0.0f, 1000.0f);
    for (auto& x : in) {
      x.klass = rng() % 4;
      x.size = (rng() % 3 == 0) ? sizes[rng() % (sizeof(sizes) / sizeof(sizes[0]))] : ureal(rng);
      x.id = static_cast<unsigned>(rng());
    }
    Buffer<Space, PrioInput> din;
    din.upload(in);
    Buffer<Space, u64> dp(n);
    const PrioInput* ip = din.data();
    u64* pp = dp.data();
    Ops<Space>::for_each(n, [=] GDR_HD(long long i) {
      pp[i] = exec::make_priority(ip[i].klass, ip[i].size, ip[i].id);
    });
    const std::vector<u64> pr = dp.to_host();
    long long mismatch = -1;
    for (std::size_t i = 0; i < n && mismatch < 0; ++i)
      if (pr[i] != exec::make_priority(in[i].klass, in[i].size, in[i].id)) mismatch = static_cast<long long>(i);
    EXPECT_EQ(mismatch, -1) << "space and host compute different priorities";

    auto eff_size = [](float s) { return (s > 0.0f) ? s : 0.0f; };  // NaN, <= 0 -> 0
    long long order_errors = 0, id_errors = 0;
    for (std::size_t k = 0; k + 1 < n; ++k) {
      const PrioInput& a = in[k];
      const PrioInput& b = in[k + 1];
      const u64 pa = pr[k], pb = pr[k + 1];
      if (exec::priority_id(pa) != a.id) ++id_errors;
      if (a.klass != b.klass) {
        if ((a.klass < b.klass) != (pa < pb)) ++order_errors;
      } else if (eff_size(a.size) != eff_size(b.size)) {
        // Monotone in size: a strictly larger size never gives a smaller key, and sizes
        // that differ by more than a relative 1e-6 give different keys (denormals may share
        // the key of 0: one mantissa bit is dropped).
        const float sa = eff_size(a.size), sb = eff_size(b.size);
        const float lo = std::min(sa, sb), hi = std::max(sa, sb);
        const u64 plo = sa < sb ? pa : pb, phi = sa < sb ? pb : pa;
        const unsigned klo = exec::size_key(lo), khi = exec::size_key(hi);
        if (klo > khi) ++order_errors;
        if (hi >= std::numeric_limits<float>::min() && hi > lo * (1.0f + 1e-6f) && !(plo < phi))
          ++order_errors;
        if (klo == khi && ((a.id < b.id) != (pa < pb)) && a.id != b.id) ++order_errors;
      } else if (a.id != b.id) {
        if ((a.id < b.id) != (pa < pb)) ++order_errors;
      }
    }
    EXPECT_EQ(order_errors, 0);
    EXPECT_EQ(id_errors, 0);
    // Keys fit in 30 bits and ids never bleed into size or class.
    EXPECT_LE(exec::size_key(std::numeric_limits<float>::infinity()), 0x3fffffffu);
    EXPECT_EQ(exec::size_key(0.0f), 0u);
    EXPECT_EQ(exec::size_key(-3.0f), 0u);
    EXPECT_EQ(exec::size_key(std::numeric_limits<float>::quiet_NaN()), 0u);
    EXPECT_GT(exec::size_key(std::numeric_limits<float>::min()), 0u);
    EXPECT_LT(exec::make_priority(0, std::numeric_limits<float>::infinity(), 0xffffffffu),
              exec::make_priority(1, 0.0f, 0u));
    EXPECT_LT(exec::make_priority(2, 1.0f, 0xffffffffu), exec::make_priority(2, 2.0f, 0u));
    EXPECT_EQ(exec::make_priority(7, 1.0f, 5), exec::make_priority(3, 1.0f, 5)) << "class is 2 bits";
  }

  // Many items compete for few slots with random priorities: after one marking pass each
  // slot holds exactly the maximum of its competitors; a second pass tells each item
  // whether it won (0) or lost (-1).
  const std::size_t item_counts[] = {1, 4095, 4096, 100000, 1000003};
  const std::size_t slot_counts[] = {1, 7, 1000};
  std::mt19937 rng(23);
  for (std::size_t n : item_counts) {
    for (std::size_t ns : slot_counts) {
      SCOPED_TRACE("items = " + std::to_string(n) + ", slots = " + std::to_string(ns));
      std::vector<int> target(n);
      std::vector<PrioInput> in(n);
      std::uniform_real_distribution<float> ureal(0.0f, 4.0f);
      for (std::size_t i = 0; i < n; ++i) {
        target[i] = static_cast<int>(rng() % ns);
        // Few classes and a coarse set of sizes: the id must break most ties.
        in[i] = PrioInput{static_cast<unsigned>(rng() % 3), std::floor(ureal(rng)),
                          static_cast<unsigned>(i + 1)};
      }
      Buffer<Space, int> dt;
      dt.upload(target);
      Buffer<Space, PrioInput> din;
      din.upload(in);
      Buffer<Space, int> slots(ns);
      slots.zero();
      Buffer<Space, u64> prio(n);
      Buffer<Space, int> res1(n), res2(n);
      const int* t = dt.data();
      const PrioInput* ip = din.data();
      int* sl = slots.data();
      u64* pr = prio.data();
      int* r1 = res1.data();
      int* r2 = res2.data();
      Ops<Space>::for_each(n, [=] GDR_HD(long long i) {
        pr[i] = exec::make_priority(ip[i].klass, ip[i].size, ip[i].id);
      });
      auto prio_of = [=] GDR_HD(int k) { return pr[k]; };
      Ops<Space>::for_each(n, [=] GDR_HD(long long i) {
        r1[i] = exec::claim(sl + t[i], static_cast<int>(i), pr[i], prio_of);
      });
      Ops<Space>::for_each(n, [=] GDR_HD(long long i) {
        r2[i] = exec::claim(sl + t[i], static_cast<int>(i), pr[i], prio_of);
      });
      const std::vector<int> got = slots.to_host();
      const std::vector<int> h1 = res1.to_host(), h2 = res2.to_host();

      std::vector<u64> best(ns, 0);
      std::vector<long long> winner(ns, -1);
      for (std::size_t i = 0; i < n; ++i) {
        const u64 p = exec::make_priority(in[i].klass, in[i].size, in[i].id);
        if (p > best[target[i]]) {
          best[target[i]] = p;
          winner[target[i]] = static_cast<long long>(i);
        }
      }
      std::vector<int> expect(ns, 0);
      for (std::size_t k = 0; k < ns; ++k) expect[k] = static_cast<int>(winner[k] + 1);
      EXPECT_EQ(first_mismatch(got, expect), -1) << "a slot does not hold the highest item";
      long long bad1 = 0, bad2 = 0, zeros = 0;
      std::vector<int> survivors(ns, 0);
      for (std::size_t i = 0; i < n; ++i) {
        const bool won = winner[target[i]] == static_cast<long long>(i);
        if (won && h1[i] != 1) ++bad1;    // the maximum always found a lower value first
        if (h1[i] == 0 || (h1[i] == -1 && won)) ++bad1;
        if (h2[i] != (won ? 0 : -1)) ++bad2;
        if (h2[i] == 0) ++zeros;
        if (got[target[i]] == static_cast<int>(i) + 1) ++survivors[target[i]];
      }
      EXPECT_EQ(bad1, 0) << "wrong claim() results in the marking pass";
      EXPECT_EQ(bad2, 0) << "wrong claim() results in the checking pass";
      long long used = 0;
      for (std::size_t k = 0; k < ns; ++k) {
        if (winner[k] >= 0) {
          ++used;
          EXPECT_EQ(survivors[k], 1) << "slot " << k;
        }
      }
      EXPECT_EQ(zeros, used) << "exactly one survivor per contested slot";
    }
  }
}

// ---------------------------------------------------------------------------------------
// Atomics under contention

template <class Space>
void check_atomics() {
  const std::size_t sizes[] = {1, 4097, 1000003};
  std::mt19937 rng(31);
  for (std::size_t n : sizes) {
    SCOPED_TRACE("n = " + std::to_string(n));
    const int C = 3;    // int counters
    const int W = 5;    // or-words
    Buffer<Space, int> cnt(C), words(W), oldc(n), mn(2);
    Buffer<Space, u64> sum(1), mx(1);
    cnt.zero();
    words.zero();
    sum.zero();
    mx.zero();
    mn.upload(std::vector<int>{std::numeric_limits<int>::max(), 0});
    std::vector<int> vals(n);
    std::vector<u64> big(n);
    for (std::size_t i = 0; i < n; ++i) {
      vals[i] = static_cast<int>(rng() % 2000001) - 1000000;
      big[i] = (static_cast<u64>(rng()) << 32) | rng();
    }
    Buffer<Space, int> dv;
    dv.upload(vals);
    Buffer<Space, u64> db;
    db.upload(big);
    int* c = cnt.data();
    int* w = words.data();
    int* o = oldc.data();
    int* m = mn.data();
    u64* s = sum.data();
    u64* x = mx.data();
    const int* v = dv.data();
    const u64* bg = db.data();
    Ops<Space>::for_each(n, [=] GDR_HD(long long i) {
      o[i] = exec::atomic_add(c + i % C, 1);
      exec::atomic_add(s, static_cast<u64>(i) * 3u + 1u);
      exec::atomic_or(w + i % W, 1 << ((i / W) % 31));
      exec::atomic_min(m, v[i]);
      exec::atomic_min(m + 1, -v[i]);
      exec::atomic_max(x, bg[i]);
    });
    // Counters: every value 0..count-1 handed out exactly once per counter.
    const std::vector<int> hc = cnt.to_host(), ho = oldc.to_host();
    std::vector<std::vector<int>> seen(C);
    for (std::size_t i = 0; i < n; ++i) seen[i % C].push_back(ho[i]);
    for (int k = 0; k < C; ++k) {
      EXPECT_EQ(hc[k], static_cast<int>(seen[k].size())) << "counter " << k;
      std::sort(seen[k].begin(), seen[k].end());
      long long bad = -1;
      for (std::size_t j = 0; j < seen[k].size() && bad < 0; ++j)
        if (seen[k][j] != static_cast<int>(j)) bad = static_cast<long long>(j);
      EXPECT_EQ(bad, -1) << "atomic_add returned a duplicate or missing old value, counter " << k;
    }
    u64 ref_sum = 0;
    std::vector<int> ref_words(W, 0);
    int ref_min = std::numeric_limits<int>::max(), ref_min2 = 0;
    u64 ref_max = 0;
    for (std::size_t i = 0; i < n; ++i) {
      ref_sum += static_cast<u64>(i) * 3u + 1u;
      ref_words[i % W] |= 1 << ((i / W) % 31);
      ref_min = std::min(ref_min, vals[i]);
      ref_min2 = std::min(ref_min2, -vals[i]);
      ref_max = std::max(ref_max, big[i]);
    }
    EXPECT_EQ(sum.get(0), ref_sum);
    EXPECT_EQ(words.to_host(), ref_words);
    EXPECT_EQ(mn.get(0), ref_min);
    EXPECT_EQ(mn.get(1), ref_min2);
    EXPECT_EQ(mx.get(0), ref_max);

    // atomic_max as a race detector: values rise with i, so both threads keep raising the
    // same slots. A raise replaces the old value for good, so among the items that raised
    // a slot (old < v) no two may report the same old value, and every old value is 0 or
    // one of the slot's values.
    const int S = 2;
    Buffer<Space, u64> ms(S), mold(n);
    ms.zero();
    u64* msp = ms.data();
    u64* mo = mold.data();
    Ops<Space>::for_each(n, [=] GDR_HD(long long i) {
      mo[i] = exec::atomic_max(msp + i % S, static_cast<u64>(i) + 1);
    });
    const std::vector<u64> hmo = mold.to_host();
    std::vector<std::vector<u64>> raised(S);
    long long foreign = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const u64 v = i + 1;
      if (hmo[i] != 0 && ((hmo[i] - 1) % S != i % S || hmo[i] > n)) ++foreign;
      if (hmo[i] < v) raised[i % S].push_back(hmo[i]);
    }
    EXPECT_EQ(foreign, 0) << "atomic_max returned a value never stored in the slot";
    for (int k = 0; k < S && static_cast<std::size_t>(k) < n; ++k) {
      std::sort(raised[k].begin(), raised[k].end());
      EXPECT_TRUE(std::adjacent_find(raised[k].begin(), raised[k].end()) == raised[k].end())
          << "two raises of slot " << k << " replaced the same value: atomic_max lost an update";
      EXPECT_EQ(ms.get(k), n - (n - 1 - k) % S) << "slot " << k;
    }
  }

  // Return values of atomic_or / atomic_min / atomic_max / atomic_add on one thread (on
  // space memory: GPU atomics need global memory).
  {
    Buffer<Space, int> r(6), cell(2);
    Buffer<Space, u64> r64(3), cell64(1);
    cell.upload(std::vector<int>{5, 10});
    cell64.upload(std::vector<u64>{100});
    int* rp = r.data();
    int* a = cell.data();
    int* b = cell.data() + 1;
    u64* qp = r64.data();
    u64* q = cell64.data();
    Ops<Space>::for_each(1, [=] GDR_HD(long long) {
      rp[0] = exec::atomic_or(a, 2);     // 5
      rp[1] = *a;                        // 7
      rp[2] = exec::atomic_min(b, 20);   // 10, unchanged
      rp[3] = exec::atomic_min(b, -4);   // 10
      rp[4] = *b;                        // -4
      rp[5] = exec::atomic_add(b, 6);    // -4
      qp[0] = exec::atomic_max(q, 50);      // 100, unchanged
      qp[1] = exec::atomic_max(q, ~0ull);   // 100
      qp[2] = *q;                           // all ones
    });
    EXPECT_EQ(r.to_host(), (std::vector<int>{5, 7, 10, 10, -4, -4}));
    EXPECT_EQ(r64.to_host(), (std::vector<u64>{100, 100, ~0ull}));
    EXPECT_EQ(cell.get(1), 2);
  }
}

// ---------------------------------------------------------------------------------------
// expand_list (Algorithm 4): tree expansion against a serial reference, deferment limits,
// and a BFS over a random graph with atomic visit marks.

struct Node {
  int depth;
  unsigned key;
  long long parent;  // index in H of the tuple that spawned this one (-1 for roots)
  int nchild;        // written by the step into the processed tuple
  bool operator==(const Node& o) const {
    return depth == o.depth && key == o.key && parent == o.parent && nchild == o.nchild;
  }
};

constexpr int kTreeK = 4;

// Children of a tree node: between 0 and kTreeK, fewer near `max_depth`, none at it.
GDR_HD_INLINE int tree_children(const Node& h, int max_depth, Node* out, long long index) {
  if (h.depth >= max_depth) return 0;
  const int c = static_cast<int>(mix32(h.key) % (kTreeK + 1));
  for (int k = 0; k < c; ++k)
    out[k] = Node{h.depth + 1, mix32(h.key * 31u + static_cast<unsigned>(k) + 1u), index, -1};
  return c;
}

// Serial Algorithm 4 with the same limits.
inline exec::ExpandListResult serial_expand(std::vector<Node>& H, std::size_t initial, int max_depth,
                                            const exec::ExpandListLimits& lim) {
  exec::ExpandListResult r;
  H.resize(initial);
  std::size_t left = 0, right = initial;
  while (left < right) {
    if (r.rounds >= lim.max_rounds ||
        (r.rounds >= lim.defer_after_rounds && right - left < lim.defer_below))
      break;
    std::size_t added = 0;
    for (std::size_t j = left; j < right; ++j) {
      Node out[kTreeK];
      const int c = tree_children(H[j], max_depth, out, static_cast<long long>(j));
      H[j].nchild = c;
      for (int k = 0; k < c; ++k) H.push_back(out[k]);
      added += c;
    }
    ++r.rounds;
    left = right;
    right += added;
  }
  r.size = right;
  r.pending_begin = left;
  return r;
}

template <class Space>
void run_tree_case(std::size_t roots, std::size_t extra, int max_depth, const exec::ExpandListLimits& lim,
                   bool expect_deferred, const char* what) {
  SCOPED_TRACE(std::string(what) + ": roots = " + std::to_string(roots) +
               ", depth = " + std::to_string(max_depth));
  std::vector<Node> init(roots + extra);
  for (std::size_t j = 0; j < init.size(); ++j)
    init[j] = Node{0, mix32(static_cast<unsigned>(j) * 977u + 3u), -1, -1};
  std::vector<Node> ref = init;
  const exec::ExpandListResult rr = serial_expand(ref, roots, max_depth, lim);

  Buffer<Space, Node> H;
  H.upload(init);  // `extra` tuples beyond `initial` must be ignored
  const int md = max_depth;
  const exec::ExpandListResult r = exec::expand_list<Space, kTreeK>(
      H, roots,
      [=] GDR_HD(long long i, Node& h, Node* out) -> int {
        const int c = tree_children(h, md, out, i);
        h.nchild = c;
        return c;
      },
      lim);
  EXPECT_EQ(r.rounds, rr.rounds);
  EXPECT_EQ(r.size, rr.size);
  EXPECT_EQ(r.pending_begin, rr.pending_begin);
  EXPECT_EQ(r.deferred(), expect_deferred);
  EXPECT_EQ(rr.deferred(), expect_deferred) << "the test case does not exercise what it says";
  EXPECT_EQ(H.size(), r.size);
  const std::vector<Node> got = H.to_host();
  if (!exec::Ops<Space>::is_gpu) {
    // Positions are reserved by a prefix sum, so the order is the serial one exactly.
    EXPECT_EQ(first_mismatch(got, ref), -1) << "H differs from the serial expansion";
  } else {
    // On the GPU large windows append per block in any order: every tuple's parent is a
    // tuple of the round before that spawns it, and every tuple has as many children in H
    // as its step said.
    std::vector<int> children(got.size(), 0);
    long long bad = 0;
    for (std::size_t j = 0; j < got.size(); ++j) {
      const Node& h = got[j];
      if (h.parent < 0) continue;
      if (h.parent >= static_cast<long long>(j) || got[h.parent].depth + 1 != h.depth) {
        ++bad;
        continue;
      }
      ++children[h.parent];
      Node out[kTreeK];
      const int c = tree_children(got[h.parent], max_depth, out, h.parent);
      bool spawned = false;
      for (int k = 0; k < c; ++k) spawned = spawned || (out[k].key == h.key && out[k].depth == h.depth);
      bad += !spawned;
    }
    for (std::size_t j = 0; j < r.pending_begin; ++j) bad += got[j].nchild != children[j];
    EXPECT_EQ(bad, 0) << "parent links in H do not match the expansion";
  }
  // And, independently of the order, the same multiset of tuples.
  auto key_of = [](const Node& a) { return (static_cast<u64>(a.depth) << 32) | a.key; };
  std::vector<u64> ka, kb;
  for (const Node& a : got) ka.push_back(key_of(a));
  for (const Node& a : ref) kb.push_back(key_of(a));
  std::sort(ka.begin(), ka.end());
  std::sort(kb.begin(), kb.end());
  EXPECT_EQ(first_mismatch(ka, kb), -1) << "H holds a different multiset of tuples";
  // The pending window is untouched by any step.
  long long touched = 0;
  for (std::size_t j = r.pending_begin; j < got.size(); ++j)
    if (got[j].nchild != -1) ++touched;
  EXPECT_EQ(touched, 0);
}

struct Visit {
  int v;
  int d;
};

template <class Space>
void check_bfs(int nv, int seed) {
  SCOPED_TRACE("BFS on " + std::to_string(nv) + " vertices");
  constexpr int K = 3;
  std::mt19937 rng(seed);
  std::vector<int> adj(static_cast<std::size_t>(nv) * K, -1);
  for (int v = 0; v < nv; ++v) {
    const int deg = static_cast<int>(rng() % (K + 1));
    for (int k = 0; k < deg; ++k) adj[static_cast<std::size_t>(v) * K + k] = static_cast<int>(rng() % nv);
  }
  // Serial BFS from vertex 0.
  std::vector<int> dist(nv, -1);
  std::vector<int> queue{0};
  dist[0] = 0;
  for (std::size_t q = 0; q < queue.size(); ++q) {
    const int v = queue[q];
    for (int k = 0; k < K; ++k) {
      const int w = adj[static_cast<std::size_t>(v) * K + k];
      if (w >= 0 && dist[w] < 0) {
        dist[w] = dist[v] + 1;
        queue.push_back(w);
      }
    }
  }
  const int maxd = *std::max_element(dist.begin(), dist.end());

  Buffer<Space, int> dadj, vis(nv);
  dadj.upload(adj);
  vis.zero();
  vis.set(0, 1);
  Buffer<Space, Visit> H;
  H.upload(std::vector<Visit>{Visit{0, 0}});
  const int* a = dadj.data();
  int* mark = vis.data();
  const exec::ExpandListResult r = exec::expand_list<Space, K>(
      H, 1, [=] GDR_HD(long long, Visit& h, Visit* out) -> int {
        int c = 0;
        for (int k = 0; k < K; ++k) {
          const int w = a[static_cast<long long>(h.v) * K + k];
          if (w >= 0 && exec::atomic_or(mark + w, 1) == 0) out[c++] = Visit{w, h.d + 1};
        }
        return c;
      });
  EXPECT_EQ(r.rounds, maxd + 1);
  EXPECT_EQ(r.size, queue.size());
  EXPECT_FALSE(r.deferred());
  const std::vector<Visit> got = H.to_host();
  ASSERT_EQ(got.size(), queue.size());
  std::vector<int> seen(nv, 0);
  long long wrong_depth = 0, dup = 0, order = 0;
  for (std::size_t j = 0; j < got.size(); ++j) {
    const Visit& t = got[j];
    ASSERT_TRUE(t.v >= 0 && t.v < nv);
    if (seen[t.v]++) ++dup;
    if (t.d != dist[t.v]) ++wrong_depth;
    if (j && got[j - 1].d > t.d) ++order;
  }
  EXPECT_EQ(dup, 0) << "a vertex was visited twice";
  EXPECT_EQ(wrong_depth, 0) << "a tuple's round differs from its BFS distance";
  EXPECT_EQ(order, 0) << "windows are not in round order";
  long long missing = 0;
  for (int v = 0; v < nv; ++v)
    if ((dist[v] >= 0) != (seen[v] == 1)) ++missing;
  EXPECT_EQ(missing, 0) << "visited set differs from the reachable set";
}

template <class Space>
void check_expand_list() {
  exec::ExpandListLimits none;
  run_tree_case<Space>(0, 0, 5, none, false, "empty");
  run_tree_case<Space>(1, 0, 0, none, false, "single leaf");
  run_tree_case<Space>(1, 3, 6, none, false, "one root, extra tuples after initial");
  run_tree_case<Space>(3, 0, 12, none, false, "small tree");
  run_tree_case<Space>(5000, 0, 8, none, false, "many roots");
  run_tree_case<Space>(8, 0, 15, none, false, "large tree");
  // Windows of tens of thousands of tuples (the GPU runs their rounds across the grid).
  run_tree_case<Space>(30000, 0, 5, none, false, "large windows");

  exec::ExpandListLimits two;
  two.max_rounds = 2;
  run_tree_case<Space>(100, 0, 10, two, true, "max_rounds = 2");
  run_tree_case<Space>(30000, 0, 10, two, true, "max_rounds = 2, large windows");
  exec::ExpandListLimits zero;
  zero.max_rounds = 0;
  run_tree_case<Space>(100, 0, 10, zero, true, "max_rounds = 0");
  exec::ExpandListLimits late;
  late.max_rounds = 11;  // the tree is done after 11 rounds: nothing left to defer
  run_tree_case<Space>(100, 0, 10, late, false, "max_rounds = rounds needed");

  // S5 deferment: from round 3 on, stop when the window has fewer than `defer_below`
  // tuples. A huge threshold stops right at round 3; a small one only when the window
  // shrinks below it (here never: the tree grows), a threshold of 0 never.
  exec::ExpandListLimits defer;
  defer.defer_after_rounds = 3;
  defer.defer_below = std::size_t(1) << 40;
  run_tree_case<Space>(100, 0, 10, defer, true, "defer after 3 rounds, any window");
  run_tree_case<Space>(30000, 0, 10, defer, true, "defer after 3 rounds, large windows");
  defer.defer_below = 0;
  run_tree_case<Space>(100, 0, 10, defer, false, "defer_below = 0");
  // One root: the window starts at 1 tuple; it is deferred at the first round >= 2 where
  // it has fewer than 40 tuples.
  defer.defer_after_rounds = 2;
  defer.defer_below = 40;
  run_tree_case<Space>(1, 0, 14, defer, true, "defer small window after 2 rounds");

  check_bfs<Space>(1, 3);
  check_bfs<Space>(2000, 4);
  check_bfs<Space>(300000, 5);
}

// ---------------------------------------------------------------------------------------
// memory_counter

template <class Space>
void check_memory_counter() {
  exec::MemoryCounter plain;
  plain.add(100);
  plain.add(50);
  plain.sub(120);
  plain.add(10);
  EXPECT_EQ(plain.current, 40u);
  EXPECT_EQ(plain.peak, 150u);

  exec::MemoryCounter& mc = exec::memory_counter<Space>();
  Ops<Space>::synchronize();
  const std::size_t c0 = mc.current;
  mc.peak = mc.current;  // reset, as a run does
  std::size_t da = 0, db = 0;
  {
    Buffer<Space, int> a(1u << 20);
    da = mc.current - c0;
    EXPECT_GE(da, (1u << 20) * sizeof(int));
    EXPECT_LE(da, 2 * (1u << 20) * sizeof(int) + 4096);
    Buffer<Space, double> b(3u << 18);
    db = mc.current - c0 - da;
    EXPECT_GE(db, (3u << 18) * sizeof(double));
    EXPECT_EQ(mc.peak, c0 + da + db);
    a.release();
    EXPECT_EQ(mc.current, c0 + db);
    EXPECT_EQ(mc.peak, c0 + da + db) << "release lowered the peak";
    Buffer<Space, char> c(1000);
    EXPECT_GT(mc.current, c0 + db);
    EXPECT_EQ(mc.peak, c0 + da + db);
  }
  EXPECT_EQ(mc.current, c0) << "destructors did not return what they took";
  EXPECT_EQ(mc.peak, c0 + da + db);

  // Growth by resize holds old and new storage at once: the peak must show it.
  mc.peak = mc.current;
  {
    Buffer<Space, int> g(1u << 20);
    const std::size_t old_bytes = mc.current - c0;
    g.resize(3u << 20);
    const std::size_t new_bytes = mc.current - c0;
    EXPECT_GE(new_bytes, (3u << 20) * sizeof(int));
    EXPECT_EQ(mc.peak, c0 + old_bytes + new_bytes) << "peak misses the transient copy of resize";
    g.shrink_to(10);
    EXPECT_LT(mc.current - c0, new_bytes);
  }
  EXPECT_EQ(mc.current, c0);

  // Scratch allocated inside the algorithms is returned too.
  {
    Buffer<Space, int> out, scratch;
    exec::compact_indices<Space>(100000, [=] GDR_HD(long long i) { return (i & 1) != 0; }, out,
                                 scratch);
    Buffer<Space, int> v(50000);
    v.zero();
    Ops<Space>::exclusive_scan(v.data(), v.data(), v.size());
  }
  Ops<Space>::synchronize();
  EXPECT_EQ(mc.current, c0) << "an algorithm leaked scratch memory";
}

}  // namespace gdr::exec_test

// One TEST per check; GUARD is a statement run first (e.g. a GTEST_SKIP without a device).
#define GDR_EXEC_TESTS(SUITE, SPACE, GUARD)                                         \
  TEST(SUITE, FillIotaForEach) { GUARD; gdr::exec_test::check_fill_iota<SPACE>(); } \
  TEST(SUITE, ExclusiveScan) { GUARD; gdr::exec_test::check_exclusive_scan<SPACE>(); } \
  TEST(SUITE, SortPairs) { GUARD; gdr::exec_test::check_sort_pairs<SPACE>(); }     \
  TEST(SUITE, CompactIndices) { GUARD; gdr::exec_test::check_compaction<SPACE>(); } \
  TEST(SUITE, Buffer) { GUARD; gdr::exec_test::check_buffer<SPACE>(); }             \
  TEST(SUITE, PriorityMarking) { GUARD; gdr::exec_test::check_priority<SPACE>(); }  \
  TEST(SUITE, AtomicsUnderContention) { GUARD; gdr::exec_test::check_atomics<SPACE>(); } \
  TEST(SUITE, ExpandList) { GUARD; gdr::exec_test::check_expand_list<SPACE>(); }    \
  TEST(SUITE, MemoryCounter) { GUARD; gdr::exec_test::check_memory_counter<SPACE>(); }
