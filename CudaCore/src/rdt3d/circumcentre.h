// Circumcentres of tetrahedra for gDP3d's Voronoi duals, accurate on nearly flat ones.
//
// Restricted facets are decided by where the Voronoi edges (between circumcentres) meet the
// surface. Points on a planar part of the surface are rounded off its plane, so refinement
// makes slivers there: four nearly coplanar, nearly cocircular surface points, whose
// circumcentre in plain double arithmetic is noise (numerator and denominator both cancel).
// The duals of their faces then cross the surface at random and the restricted surface
// folds. Such tetrahedra get their circumcentre in double-double arithmetic (error-free
// differences and products, about 32 digits), enough for the tiny volume they have.
#pragma once
#include <cmath>

#include "exec/hd.h"
#include "mesh3d/mesh3d.h"
#include "predicates/expansion.h"

namespace gdr::rdt3d {

// A double-double number: hi + lo, |lo| <= ulp(hi) / 2.
struct DD {
  double hi = 0, lo = 0;
};

GDR_HD_INLINE DD dd_diff(double a, double b) {
  DD r;
  pred::detail::two_diff(a, b, r.hi, r.lo);
  return r;
}

GDR_HD_INLINE DD dd_add(DD x, DD y) {
  DD r;
  double e;
  pred::detail::two_sum(x.hi, y.hi, r.hi, e);
  e += x.lo + y.lo;
  pred::detail::two_sum(r.hi, e, r.hi, r.lo);
  return r;
}

GDR_HD_INLINE DD dd_mul(DD x, DD y) {
  DD r;
  double e;
  pred::detail::two_product(x.hi, y.hi, r.hi, e);
  e += x.hi * y.lo + x.lo * y.hi;
  pred::detail::two_sum(r.hi, e, r.hi, r.lo);
  return r;
}

GDR_HD_INLINE DD dd_neg(DD x) { return DD{-x.hi, -x.lo}; }

GDR_HD_INLINE void dd_cross(const DD* u, const DD* v, DD* w) {
  w[0] = dd_add(dd_mul(u[1], v[2]), dd_neg(dd_mul(u[2], v[1])));
  w[1] = dd_add(dd_mul(u[2], v[0]), dd_neg(dd_mul(u[0], v[2])));
  w[2] = dd_add(dd_mul(u[0], v[1]), dd_neg(dd_mul(u[1], v[0])));
}

GDR_HD_INLINE DD dd_dot(const DD* u, const DD* v) {
  return dd_add(dd_add(dd_mul(u[0], v[0]), dd_mul(u[1], v[1])), dd_mul(u[2], v[2]));
}

// Circumcentre of abcd (m3d::tet_circumcenter's formula); false when it is flat or the
// centre is not representable.
GDR_HD_INLINE bool accurate_tet_circumcenter(const double* a, const double* b, const double* c,
                                             const double* d, double* out) {
  const double l2 = fmax(m3d::dist2(a, b), fmax(m3d::dist2(a, c), m3d::dist2(a, d)));  // longest from a
  // Plain arithmetic is accurate unless the volume is tiny against the edges.
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ad[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  double n[3];
  m3d::cross3(ac, ad, n);
  if (fabs(m3d::dot3(ab, n)) > 1e-4 * l2 * sqrt(l2)) return m3d::tet_circumcenter(a, b, c, d, out);
  DD u[3], v[3], w[3], cd[3], db[3], bc[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = dd_diff(b[k], a[k]);
    v[k] = dd_diff(c[k], a[k]);
    w[k] = dd_diff(d[k], a[k]);
  }
  dd_cross(v, w, cd);
  dd_cross(w, u, db);
  dd_cross(u, v, bc);
  const DD den = dd_dot(u, cd);
  const double den_value = 2 * (den.hi + den.lo);
  if (!(den_value != 0.0)) return false;
  const DD la = dd_dot(u, u), lc = dd_dot(v, v), ld = dd_dot(w, w);
  for (int k = 0; k < 3; ++k) {
    const DD num = dd_add(dd_add(dd_mul(la, cd[k]), dd_mul(lc, db[k])), dd_mul(ld, bc[k]));
    out[k] = a[k] + (num.hi + num.lo) / den_value;
  }
  return out[0] == out[0] && out[1] == out[1] && out[2] == out[2] && fabs(out[0]) < 1e300 &&
         fabs(out[1]) < 1e300 && fabs(out[2]) < 1e300;
}

}  // namespace gdr::rdt3d
