// Floating-point expansion arithmetic (Priest / Shewchuk): a number is held exactly as a sum
// of doubles whose significands do not overlap, ordered by increasing magnitude. Every routine
// here is exact under IEEE double arithmetic with round-to-nearest-even, as long as no product
// overflows or loses bits to underflow (see docs/predicates.md for the coordinate range).
//
// Expansions produced here are strongly nonoverlapping and zero-eliminated; a zero value is the
// one-component expansion {0}. Lengths are always >= 1.
#pragma once
#include <cmath>

#include "exec/hd.h"

#if defined(__FAST_MATH__)
#error "gdr predicates need IEEE semantics: do not compile with -ffast-math"
#endif

namespace gdr::pred::detail {

// Rounded operations that the compiler may not contract into fused multiply-adds: the
// error-free transformations below rely on each product and sum being rounded on its own.
GDR_HD_INLINE double mul(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __dmul_rn(a, b);
#else
  return a * b;
#endif
}

GDR_HD_INLINE double add(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __dadd_rn(a, b);
#else
  return a + b;
#endif
}

GDR_HD_INLINE double sub(double a, double b) {
#if defined(__CUDA_ARCH__)
  return __dsub_rn(a, b);
#else
  return a - b;
#endif
}

GDR_HD_INLINE double fused(double a, double b, double c) {
#if defined(__CUDA_ARCH__)
  return ::fma(a, b, c);
#else
  return std::fma(a, b, c);
#endif
}

GDR_HD_INLINE double mag(double a) { return a < 0.0 ? -a : a; }

// x + y == a + b exactly, x = fl(a + b).
GDR_HD_INLINE void two_sum(double a, double b, double& x, double& y) {
  x = add(a, b);
  const double bv = sub(x, a);
  const double av = sub(x, bv);
  y = add(sub(a, av), sub(b, bv));
}

// x + y == a - b exactly, x = fl(a - b).
GDR_HD_INLINE void two_diff(double a, double b, double& x, double& y) {
  x = sub(a, b);
  const double bv = sub(a, x);
  const double av = add(x, bv);
  y = add(sub(a, av), sub(bv, b));
}

// x + y == a * b exactly, x = fl(a * b); the fused multiply-add yields the rounding error.
GDR_HD_INLINE void two_product(double a, double b, double& x, double& y) {
  x = mul(a, b);
  y = fused(a, b, -x);
}

// h = e + f. h needs room for elen + flen components. Safe in place when e lies at h + flen
// (each write lands strictly below the next unread component of e).
GDR_HD_INLINE int expansion_sum(int elen, const double* e, int flen, const double* f, double* h) {
  int ei = 0, fi = 0, hn = 0;
  double q;
  // Merge by increasing magnitude and carry the running sum q; emit nonzero tails.
  if (mag(e[0]) < mag(f[0])) {
    q = e[ei++];
  } else {
    q = f[fi++];
  }
  while (ei < elen || fi < flen) {
    double g;
    if (fi >= flen || (ei < elen && mag(e[ei]) < mag(f[fi]))) {
      g = e[ei++];
    } else {
      g = f[fi++];
    }
    double s, t;
    two_sum(q, g, s, t);
    q = s;
    if (t != 0.0) h[hn++] = t;
  }
  if (q != 0.0 || hn == 0) h[hn++] = q;
  return hn;
}

// h = b * e. h needs room for 2 * elen components.
GDR_HD_INLINE int scale_expansion(int elen, const double* e, double b, double* h) {
  int hn = 0;
  double q, t;
  two_product(e[0], b, q, t);
  if (t != 0.0) h[hn++] = t;
  for (int i = 1; i < elen; ++i) {
    double p1, p0, s, u;
    two_product(e[i], b, p1, p0);
    two_sum(q, p0, s, u);
    if (u != 0.0) h[hn++] = u;
    two_sum(p1, s, q, u);
    if (u != 0.0) h[hn++] = u;
  }
  if (q != 0.0 || hn == 0) h[hn++] = q;
  return hn;
}

GDR_HD_INLINE void negate(int n, double* e) {
  for (int i = 0; i < n; ++i) e[i] = -e[i];
}

GDR_HD_INLINE void copy(int n, const double* src, double* dst) {
  for (int i = 0; i < n; ++i) dst[i] = src[i];
}

// The largest component carries the sign of the whole (nonoverlapping, zero-eliminated).
GDR_HD_INLINE double most_significant(int n, const double* e) { return n > 0 ? e[n - 1] : 0.0; }

GDR_HD_INLINE int sign_of(double v) { return (v > 0.0) - (v < 0.0); }

// acc += t, in place; len == 0 stands for an empty accumulator. acc needs len + tlen slots.
GDR_HD_INLINE void accumulate(double* acc, int& len, int tlen, const double* t) {
  if (len == 0) {
    copy(tlen, t, acc);
    len = tlen;
    return;
  }
  for (int i = len - 1; i >= 0; --i) acc[i + tlen] = acc[i];
  len = expansion_sum(len, acc + tlen, tlen, t, acc);
}

// {x0*y1 - x1*y0} as an expansion of at most 4 components.
GDR_HD_INLINE int cross2(double x0, double y0, double x1, double y1, double* h) {
  double p[2], q[2];
  two_product(x0, y1, p[1], p[0]);
  two_product(x1, y0, q[1], q[0]);
  q[0] = -q[0];
  q[1] = -q[1];
  return expansion_sum(2, p, 2, q, h);
}

// Exact squared norm of a 2D or 3D point (at most 6 components).
GDR_HD_INLINE int lift(const double* p, int dim, double* h) {
  double s[2], t[4];
  two_product(p[0], p[0], h[1], h[0]);
  two_product(p[1], p[1], s[1], s[0]);
  int n = expansion_sum(2, h, 2, s, t);
  if (dim == 2) {
    copy(n, t, h);
    return n;
  }
  two_product(p[2], p[2], s[1], s[0]);
  return expansion_sum(n, t, 2, s, h);
}

}  // namespace gdr::pred::detail
