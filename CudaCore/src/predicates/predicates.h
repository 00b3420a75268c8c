// Robust geometric predicates for host and device (docs/predicates.md has the derivations).
//
// Each predicate runs in two stages: a floating-point evaluation certified by a static
// permanent-based error bound (stage 1), and, only when that cannot certify the sign, an exact
// evaluation with floating-point expansions (stage 2). The returned value always has the exact
// sign of the determinant; its magnitude is an approximation. The *_sos variants break exact
// ties with a symbolic perturbation ordered by global vertex index.
//
// Points are `const double*` with 2 or 3 coordinates. Exactness holds while every nonzero
// coordinate magnitude lies in the range documented per predicate in docs/predicates.md
// (e.g. [2^-162, 2^202] for insphere); outside it a product may overflow or underflow.
#pragma once
#include "predicates/expansion.h"

namespace gdr::pred {

namespace detail {

constexpr double kEps = 0x1p-53;  // half an ulp of 1: the unit roundoff of round-to-nearest

GDR_HD_INLINE void report(int* stage, int s) {
  if (stage) *stage = s;
}

// True when the rounded value `det` has a certified sign given the absolute error bound.
GDR_HD_INLINE bool certified(double det, double bound) { return det > bound || -det > bound; }

// det [[px,py,1],[qx,qy,1],[rx,ry,1]] exactly (at most 12 components).
GDR_HD_INLINE int orient2d_raw(const double* p, const double* q, const double* r, double* h) {
  double pq[4], qr[4], rp[4], t[8];
  const int n1 = cross2(p[0], p[1], q[0], q[1], pq);
  const int n2 = cross2(q[0], q[1], r[0], r[1], qr);
  const int n3 = cross2(r[0], r[1], p[0], p[1], rp);
  const int n12 = expansion_sum(n1, pq, n2, qr, t);
  return expansion_sum(n12, t, n3, rp, h);
}

// det of rows (x, y, z, 1) of p, q, r, s exactly (at most 96 components), expanded along z.
GDR_HD_INLINE int orient3d_raw(const double* p, const double* q, const double* r, const double* s,
                               double* h) {
  const double* pts[4] = {p, q, r, s};
  double o[12], t[24];
  int len = 0;
  for (int i = 0; i < 4; ++i) {
    if (pts[i][2] == 0.0) continue;  // the term vanishes
    const double* rest[3];
    for (int j = 0, k = 0; j < 4; ++j)
      if (j != i) rest[k++] = pts[j];
    const int on = orient2d_raw(rest[0], rest[1], rest[2], o);
    const int tn = scale_expansion(on, o, (i % 2 == 0) ? pts[i][2] : -pts[i][2], t);
    accumulate(h, len, tn, t);
  }
  if (len == 0) h[len++] = 0.0;
  return len;
}

// acc += sgn * |p|^2 * e, one squared coordinate at a time (each term at most 4 * elen long).
GDR_HD_INLINE void accumulate_lifted(double* acc, int& len, const double* p, int dim, int sgn,
                                     int elen, const double* e, double* t1, double* t2) {
  for (int k = 0; k < dim; ++k) {
    const int n1 = scale_expansion(elen, e, p[k], t1);
    const int n2 = scale_expansion(n1, t1, sgn > 0 ? p[k] : -p[k], t2);
    accumulate(acc, len, n2, t2);
  }
}

GDR_HD inline double orient2d_exact(const double* a, const double* b, const double* c) {
  double h[12];
  const int n = orient2d_raw(a, b, c, h);
  return most_significant(n, h);
}

GDR_HD inline double orient3d_exact(const double* a, const double* b, const double* c,
                                    const double* d) {
  double h[96];
  const int n = orient3d_raw(a, b, c, d, h);
  return most_significant(n, h);
}

// det of rows (x, y, x^2+y^2, 1), expanded along the lift column: 4 terms of 2 * 48 components.
GDR_HD inline double incircle_exact(const double* a, const double* b, const double* c,
                                    const double* d) {
  const double* pts[4] = {a, b, c, d};
  double acc[384], o[12], t1[24], t2[48];
  int len = 0;
  for (int i = 0; i < 4; ++i) {
    const double* rest[3];
    for (int j = 0, k = 0; j < 4; ++j)
      if (j != i) rest[k++] = pts[j];
    if (pts[i][0] == 0.0 && pts[i][1] == 0.0) continue;  // zero lift: no term
    const int on = orient2d_raw(rest[0], rest[1], rest[2], o);
    accumulate_lifted(acc, len, pts[i], 2, (i % 2 == 0) ? 1 : -1, on, o, t1, t2);
  }
  return most_significant(len, acc);
}

// det of rows (x, y, z, x^2+y^2+z^2, 1), expanded along the lift column:
// 5 terms of 3 * 384 components, so the accumulator needs 5760.
GDR_HD inline double insphere_exact(const double* a, const double* b, const double* c,
                                    const double* d, const double* e) {
  const double* pts[5] = {a, b, c, d, e};
  double acc[5760], o[96], t1[192], t2[384];
  int len = 0;
  for (int i = 0; i < 5; ++i) {
    const double* rest[4];
    for (int j = 0, k = 0; j < 5; ++j)
      if (j != i) rest[k++] = pts[j];
    if (pts[i][0] == 0.0 && pts[i][1] == 0.0 && pts[i][2] == 0.0) continue;  // zero lift
    const int on = orient3d_raw(rest[0], rest[1], rest[2], rest[3], o);
    accumulate_lifted(acc, len, pts[i], 3, (i % 2 == 0) ? -1 : 1, on, o, t1, t2);
  }
  return most_significant(len, acc);
}

// The determinants are translation invariant: when every coordinate difference to the last
// point is exact (common for nearby or lattice points), evaluating on the differences, with the
// last point at the origin, gives shorter expansions. Returns false when a difference rounds.
template <int N>
GDR_HD_INLINE bool translate_exactly(const double* const* pts, int dim, double (*out)[3]) {
  for (int i = 0; i < N; ++i)
    for (int k = 0; k < dim; ++k) {
      double x, y;
      two_diff(pts[i][k], pts[N - 1][k], x, y);
      if (y != 0.0) return false;
      out[i][k] = x;
    }
  return true;
}

GDR_HD inline double orient2d_stage2(const double* a, const double* b, const double* c) {
  const double* p[3] = {a, b, c};
  double t[3][3];
  if (translate_exactly<3>(p, 2, t)) return orient2d_exact(t[0], t[1], t[2]);
  return orient2d_exact(a, b, c);
}

GDR_HD inline double incircle_stage2(const double* a, const double* b, const double* c,
                                     const double* d) {
  const double* p[4] = {a, b, c, d};
  double t[4][3];
  if (translate_exactly<4>(p, 2, t)) return incircle_exact(t[0], t[1], t[2], t[3]);
  return incircle_exact(a, b, c, d);
}

GDR_HD inline double orient3d_stage2(const double* a, const double* b, const double* c,
                                     const double* d) {
  const double* p[4] = {a, b, c, d};
  double t[4][3];
  if (translate_exactly<4>(p, 3, t)) return orient3d_exact(t[0], t[1], t[2], t[3]);
  return orient3d_exact(a, b, c, d);
}

GDR_HD inline double insphere_stage2(const double* a, const double* b, const double* c,
                                     const double* d, const double* e) {
  const double* p[5] = {a, b, c, d, e};
  double t[5][3];
  if (translate_exactly<5>(p, 3, t)) return insphere_exact(t[0], t[1], t[2], t[3], t[4]);
  return insphere_exact(a, b, c, d, e);
}

// -(a-p).(b-p) exactly; each coordinate difference is first made exact as a 2-component
// expansion, so each coordinate contributes at most 8 components.
GDR_HD inline int diametral_exact(const double* a, const double* b, const double* p, int dim) {
  double acc[24], t1[4], t2[4], t[8];
  int len = 0;
  for (int k = 0; k < dim; ++k) {
    double u[2], v[2];
    two_diff(a[k], p[k], u[1], u[0]);
    two_diff(b[k], p[k], v[1], v[0]);
    const int n1 = scale_expansion(2, u, -v[1], t1);
    const int n2 = scale_expansion(2, u, -v[0], t2);
    const int n = expansion_sum(n1, t1, n2, t2, t);
    accumulate(acc, len, n, t);
  }
  return sign_of(most_significant(len, acc));
}

// Sign of the k x k minor (rows, cols ascending) of the homogeneous matrix whose row i is
// (pts[i][0..dim), [|pts[i]|^2 if lifted], 1), by the permutation expansion (k <= 4).
GDR_HD inline int minor_sign(const double* const* pts, int dim, bool lifted, const int* rows,
                             const int* cols, int k) {
  const int lift_col = lifted ? dim : -1;
  double acc[1152], ta[48], tb[48];
  int len = 0;
  int total = 1;
  for (int i = 0; i < k; ++i) total *= k;
  for (int code = 0; code < total; ++code) {
    int perm[4];
    int used = 0;
    bool is_perm = true;
    for (int t = 0, c = code; t < k; ++t, c /= k) {
      perm[t] = c % k;
      if (used & (1 << perm[t])) is_perm = false;
      used |= 1 << perm[t];
    }
    if (!is_perm) continue;
    int inversions = 0;
    for (int s = 0; s < k; ++s)
      for (int t = s + 1; t < k; ++t) inversions += perm[s] > perm[t];
    double* term = ta;
    double* spare = tb;
    int n = 1;
    term[0] = 1.0;
    for (int t = 0; t < k; ++t)
      if (cols[perm[t]] == lift_col) n = lift(pts[rows[t]], dim, term);
    bool zero = term[n - 1] == 0.0;
    for (int t = 0; t < k && !zero; ++t) {
      const int c = cols[perm[t]];
      if (c >= dim) continue;  // the lift (handled above) or the constant 1
      const double v = pts[rows[t]][c];
      if (v == 0.0) {
        zero = true;
      } else {
        n = scale_expansion(n, term, v, spare);
        exec::swap(term, spare);
      }
    }
    if (zero) continue;
    if (inversions % 2 == 1) negate(n, term);
    accumulate(acc, len, n, term);
  }
  return sign_of(most_significant(len, acc));
}

// Simulation of Simplicity on the homogeneous matrix of N points (N = perturbed columns + 1).
// Entry (r, j) of the rows sorted by index gets +eps^(2^(r*delta + delta-1-j)); the sign of the
// perturbed determinant is that of the first nonzero coefficient in increasing order of the
// exponent, i.e. of the subset bit mask. `plain` is the exact sign of the unperturbed one.
template <int N>
GDR_HD inline int sos_sign(const double* const* pts_in, const int* idx_in, int dim, bool lifted,
                           int plain) {
  if (plain != 0) return plain;
  const double* pts[N];
  int idx[N];
  for (int i = 0; i < N; ++i) {
    pts[i] = pts_in[i];
    idx[i] = idx_in[i];
  }
  int parity = 1;
  for (int i = 1; i < N; ++i)
    for (int j = i; j > 0 && idx[j - 1] > idx[j]; --j) {
      exec::swap(idx[j - 1], idx[j]);
      exec::swap(pts[j - 1], pts[j]);
      parity = -parity;
    }
  for (int i = 1; i < N; ++i)
    if (idx[i] == idx[i - 1]) return 0;  // the same vertex twice: a true degeneracy
  const int delta = N - 1;
  const int nbits = N * delta;
  for (unsigned mask = 1; mask < (1u << nbits); ++mask) {
    int rows_used = 0, cols_used = 0, sign_sum = 0, count = 0;
    int seq[N];
    bool valid = true;
    for (int bit = 0; bit < nbits && valid; ++bit) {
      if (!((mask >> bit) & 1u)) continue;
      const int r = bit / delta;
      const int j = delta - 1 - bit % delta;
      if (((rows_used >> r) & 1) || ((cols_used >> j) & 1)) valid = false;
      rows_used |= 1 << r;
      cols_used |= 1 << j;
      sign_sum += r + j;
      seq[count++] = j;  // bits ascend with the row, so seq lists columns in row order
    }
    if (!valid) continue;
    for (int s = 0; s < count; ++s)
      for (int t = s + 1; t < count; ++t) sign_sum += seq[s] > seq[t];
    int rows[N], cols[N];
    int k = 0, kc = 0;
    for (int r = 0; r < N; ++r)
      if (!((rows_used >> r) & 1)) rows[k++] = r;
    for (int c = 0; c <= delta; ++c)
      if (!((cols_used >> c) & 1)) cols[kc++] = c;
    const int s = minor_sign(pts, dim, lifted, rows, cols, k);
    if (s != 0) return (sign_sum % 2 == 0 ? parity : -parity) * s;
  }
  return 0;  // not reached: the mask removing every perturbed column leaves the minor (1)
}

}  // namespace detail

// ---- orient2d: det [[ax-cx, ay-cy], [bx-cx, by-cy]]; > 0 iff a, b, c counter-clockwise.
namespace detail {
GDR_HD_INLINE bool orient2d_filter(const double* a, const double* b, const double* c, double& det) {
  const double acx = sub(a[0], c[0]), bcx = sub(b[0], c[0]);
  const double acy = sub(a[1], c[1]), bcy = sub(b[1], c[1]);
  const double left = mul(acx, bcy), right = mul(acy, bcx);
  det = sub(left, right);
  const double bound = (3.0 + 16.0 * kEps) * kEps * (mag(left) + mag(right));
  return certified(det, bound);
}
}  // namespace detail

GDR_HD_INLINE double orient2d(const double* a, const double* b, const double* c, int* stage) {
  double det;
  if (detail::orient2d_filter(a, b, c, det)) {
    detail::report(stage, 1);
    return det;
  }
  detail::report(stage, 2);
  return detail::orient2d_stage2(a, b, c);
}

// Stage 1 only: the determinant when its sign is certified, else 0.0 (uncertain).
GDR_HD_INLINE double orient2d_filtered(const double* a, const double* b, const double* c) {
  double det;
  return detail::orient2d_filter(a, b, c, det) ? det : 0.0;
}

GDR_HD_INLINE double orient2d(const double* a, const double* b, const double* c) {
  return orient2d(a, b, c, nullptr);
}

// ---- incircle: > 0 iff d lies strictly inside the circle through counter-clockwise a, b, c.
namespace detail {
GDR_HD_INLINE bool incircle_filter(const double* a, const double* b, const double* c, const double* d, double& det) {
  const double adx = sub(a[0], d[0]), ady = sub(a[1], d[1]);
  const double bdx = sub(b[0], d[0]), bdy = sub(b[1], d[1]);
  const double cdx = sub(c[0], d[0]), cdy = sub(c[1], d[1]);
  const double bc1 = mul(bdx, cdy), bc2 = mul(cdx, bdy);
  const double ca1 = mul(cdx, ady), ca2 = mul(adx, cdy);
  const double ab1 = mul(adx, bdy), ab2 = mul(bdx, ady);
  const double alift = add(mul(adx, adx), mul(ady, ady));
  const double blift = add(mul(bdx, bdx), mul(bdy, bdy));
  const double clift = add(mul(cdx, cdx), mul(cdy, cdy));
  det = add(add(mul(alift, sub(bc1, bc2)), mul(blift, sub(ca1, ca2))),
                         mul(clift, sub(ab1, ab2)));
  const double permanent = add(add(mul(add(mag(bc1), mag(bc2)), alift),
                                   mul(add(mag(ca1), mag(ca2)), blift)),
                               mul(add(mag(ab1), mag(ab2)), clift));
  const double bound = (10.0 + 96.0 * kEps) * kEps * permanent;
  return certified(det, bound);
}
}  // namespace detail

GDR_HD_INLINE double incircle(const double* a, const double* b, const double* c, const double* d, int* stage) {
  double det;
  if (detail::incircle_filter(a, b, c, d, det)) {
    detail::report(stage, 1);
    return det;
  }
  detail::report(stage, 2);
  return detail::incircle_stage2(a, b, c, d);
}

// Stage 1 only: the determinant when its sign is certified, else 0.0 (uncertain).
GDR_HD_INLINE double incircle_filtered(const double* a, const double* b, const double* c, const double* d) {
  double det;
  return detail::incircle_filter(a, b, c, d, det) ? det : 0.0;
}

GDR_HD_INLINE double incircle(const double* a, const double* b, const double* c,
                              const double* d) {
  return incircle(a, b, c, d, nullptr);
}

// ---- orient3d: det [a-d; b-d; c-d]; > 0 iff d lies below the plane of a, b, c, where a, b, c
// appear counter-clockwise when seen from above.
namespace detail {
GDR_HD_INLINE bool orient3d_filter(const double* a, const double* b, const double* c, const double* d, double& det) {
  const double adx = sub(a[0], d[0]), ady = sub(a[1], d[1]), adz = sub(a[2], d[2]);
  const double bdx = sub(b[0], d[0]), bdy = sub(b[1], d[1]), bdz = sub(b[2], d[2]);
  const double cdx = sub(c[0], d[0]), cdy = sub(c[1], d[1]), cdz = sub(c[2], d[2]);
  const double bc1 = mul(bdx, cdy), bc2 = mul(cdx, bdy);
  const double ca1 = mul(cdx, ady), ca2 = mul(adx, cdy);
  const double ab1 = mul(adx, bdy), ab2 = mul(bdx, ady);
  det = add(add(mul(adz, sub(bc1, bc2)), mul(bdz, sub(ca1, ca2))),
                         mul(cdz, sub(ab1, ab2)));
  const double permanent = add(add(mul(add(mag(bc1), mag(bc2)), mag(adz)),
                                   mul(add(mag(ca1), mag(ca2)), mag(bdz))),
                               mul(add(mag(ab1), mag(ab2)), mag(cdz)));
  const double bound = (7.0 + 56.0 * kEps) * kEps * permanent;
  return certified(det, bound);
}
}  // namespace detail

GDR_HD_INLINE double orient3d(const double* a, const double* b, const double* c, const double* d, int* stage) {
  double det;
  if (detail::orient3d_filter(a, b, c, d, det)) {
    detail::report(stage, 1);
    return det;
  }
  detail::report(stage, 2);
  return detail::orient3d_stage2(a, b, c, d);
}

// Stage 1 only: the determinant when its sign is certified, else 0.0 (uncertain).
GDR_HD_INLINE double orient3d_filtered(const double* a, const double* b, const double* c, const double* d) {
  double det;
  return detail::orient3d_filter(a, b, c, d, det) ? det : 0.0;
}

GDR_HD_INLINE double orient3d(const double* a, const double* b, const double* c,
                              const double* d) {
  return orient3d(a, b, c, d, nullptr);
}

// ---- insphere: > 0 iff e lies strictly inside the sphere through a, b, c, d, given
// orient3d(a, b, c, d) > 0 (the sign flips with that orientation).
namespace detail {
GDR_HD_INLINE bool insphere_filter(const double* a, const double* b, const double* c, const double* d, const double* e, double& det) {
  const double aex = sub(a[0], e[0]), aey = sub(a[1], e[1]), aez = sub(a[2], e[2]);
  const double bex = sub(b[0], e[0]), bey = sub(b[1], e[1]), bez = sub(b[2], e[2]);
  const double cex = sub(c[0], e[0]), cey = sub(c[1], e[1]), cez = sub(c[2], e[2]);
  const double dex = sub(d[0], e[0]), dey = sub(d[1], e[1]), dez = sub(d[2], e[2]);
  // 2x2 minors of the xy columns, each as its two products (p, q): minor = p - q.
  const double abp = mul(aex, bey), abq = mul(bex, aey);
  const double bcp = mul(bex, cey), bcq = mul(cex, bey);
  const double cdp = mul(cex, dey), cdq = mul(dex, cey);
  const double dap = mul(dex, aey), daq = mul(aex, dey);
  const double acp = mul(aex, cey), acq = mul(cex, aey);
  const double bdp = mul(bex, dey), bdq = mul(dex, bey);
  const double ab = sub(abp, abq), bc = sub(bcp, bcq), cd = sub(cdp, cdq);
  const double da = sub(dap, daq), ac = sub(acp, acq), bd = sub(bdp, bdq);
  // 3x3 minors (xyz of three rows) and their permanents.
  const double abc = add(sub(mul(aez, bc), mul(bez, ac)), mul(cez, ab));
  const double bcd = add(sub(mul(bez, cd), mul(cez, bd)), mul(dez, bc));
  const double cda = add(add(mul(cez, da), mul(dez, ac)), mul(aez, cd));
  const double dab = add(add(mul(dez, ab), mul(aez, bd)), mul(bez, da));
  const double abcp = add(add(mul(mag(aez), add(mag(bcp), mag(bcq))),
                              mul(mag(bez), add(mag(acp), mag(acq)))),
                          mul(mag(cez), add(mag(abp), mag(abq))));
  const double bcdp = add(add(mul(mag(bez), add(mag(cdp), mag(cdq))),
                              mul(mag(cez), add(mag(bdp), mag(bdq)))),
                          mul(mag(dez), add(mag(bcp), mag(bcq))));
  const double cdap = add(add(mul(mag(cez), add(mag(dap), mag(daq))),
                              mul(mag(dez), add(mag(acp), mag(acq)))),
                          mul(mag(aez), add(mag(cdp), mag(cdq))));
  const double dabp = add(add(mul(mag(dez), add(mag(abp), mag(abq))),
                              mul(mag(aez), add(mag(bdp), mag(bdq)))),
                          mul(mag(bez), add(mag(dap), mag(daq))));
  const double alift = add(add(mul(aex, aex), mul(aey, aey)), mul(aez, aez));
  const double blift = add(add(mul(bex, bex), mul(bey, bey)), mul(bez, bez));
  const double clift = add(add(mul(cex, cex), mul(cey, cey)), mul(cez, cez));
  const double dlift = add(add(mul(dex, dex), mul(dey, dey)), mul(dez, dez));
  det = add(sub(mul(dlift, abc), mul(clift, dab)),
                         sub(mul(blift, cda), mul(alift, bcd)));
  const double permanent = add(add(mul(dlift, abcp), mul(clift, dabp)),
                               add(mul(blift, cdap), mul(alift, bcdp)));
  const double bound = (16.0 + 224.0 * kEps) * kEps * permanent;
  return certified(det, bound);
}
}  // namespace detail

GDR_HD_INLINE double insphere(const double* a, const double* b, const double* c, const double* d, const double* e, int* stage) {
  double det;
  if (detail::insphere_filter(a, b, c, d, e, det)) {
    detail::report(stage, 1);
    return det;
  }
  detail::report(stage, 2);
  return detail::insphere_stage2(a, b, c, d, e);
}

// Stage 1 only: the determinant when its sign is certified, else 0.0 (uncertain).
GDR_HD_INLINE double insphere_filtered(const double* a, const double* b, const double* c, const double* d, const double* e) {
  double det;
  return detail::insphere_filter(a, b, c, d, e, det) ? det : 0.0;
}

GDR_HD_INLINE double insphere(const double* a, const double* b, const double* c, const double* d,
                              const double* e) {
  return insphere(a, b, c, d, e, nullptr);
}

// ---- Diametral balls (Ruppert / Shewchuk encroachment): sign of -(a-p).(b-p):
// +1 strictly inside the circle (sphere) with diameter ab, 0 on it, -1 outside.
GDR_HD_INLINE int in_diametral_circle(const double* a, const double* b, const double* p,
                                      int* stage) {
  using namespace detail;
  const double tx = mul(sub(a[0], p[0]), sub(b[0], p[0]));
  const double ty = mul(sub(a[1], p[1]), sub(b[1], p[1]));
  const double dot = add(tx, ty);
  const double bound = (3.0 + 16.0 * kEps) * kEps * (mag(tx) + mag(ty));
  if (certified(dot, bound)) {
    report(stage, 1);
    return dot < 0.0 ? 1 : -1;
  }
  report(stage, 2);
  return diametral_exact(a, b, p, 2);
}

GDR_HD_INLINE int in_diametral_circle(const double* a, const double* b, const double* p) {
  return in_diametral_circle(a, b, p, nullptr);
}

GDR_HD_INLINE int in_diametral_sphere(const double* a, const double* b, const double* p,
                                      int* stage) {
  using namespace detail;
  const double tx = mul(sub(a[0], p[0]), sub(b[0], p[0]));
  const double ty = mul(sub(a[1], p[1]), sub(b[1], p[1]));
  const double tz = mul(sub(a[2], p[2]), sub(b[2], p[2]));
  const double dot = add(add(tx, ty), tz);
  const double bound = (5.0 + 64.0 * kEps) * kEps * (mag(tx) + mag(ty) + mag(tz));
  if (certified(dot, bound)) {
    report(stage, 1);
    return dot < 0.0 ? 1 : -1;
  }
  report(stage, 2);
  return diametral_exact(a, b, p, 3);
}

GDR_HD_INLINE int in_diametral_sphere(const double* a, const double* b, const double* p) {
  return in_diametral_sphere(a, b, p, nullptr);
}

// ---- Symbolic perturbation: exact sign of the predicate on points perturbed by infinitesimals
// ordered by global vertex index (docs/predicates.md). Nonzero unless two indices are equal.
GDR_HD_INLINE int orient2d_sos(const double* a, const double* b, const double* c, int ia, int ib,
                               int ic) {
  const double* pts[3] = {a, b, c};
  const int idx[3] = {ia, ib, ic};
  return detail::sos_sign<3>(pts, idx, 2, false, detail::sign_of(orient2d(a, b, c)));
}

GDR_HD_INLINE int incircle_sos(const double* a, const double* b, const double* c, const double* d,
                               int ia, int ib, int ic, int id) {
  const double* pts[4] = {a, b, c, d};
  const int idx[4] = {ia, ib, ic, id};
  return detail::sos_sign<4>(pts, idx, 2, true, detail::sign_of(incircle(a, b, c, d)));
}

GDR_HD_INLINE int orient3d_sos(const double* a, const double* b, const double* c, const double* d,
                               int ia, int ib, int ic, int id) {
  const double* pts[4] = {a, b, c, d};
  const int idx[4] = {ia, ib, ic, id};
  return detail::sos_sign<4>(pts, idx, 3, false, detail::sign_of(orient3d(a, b, c, d)));
}

GDR_HD_INLINE int insphere_sos(const double* a, const double* b, const double* c, const double* d,
                               const double* e, int ia, int ib, int ic, int id, int ie) {
  const double* pts[5] = {a, b, c, d, e};
  const int idx[5] = {ia, ib, ic, id, ie};
  return detail::sos_sign<5>(pts, idx, 3, true, detail::sign_of(insphere(a, b, c, d, e)));
}

}  // namespace gdr::pred
