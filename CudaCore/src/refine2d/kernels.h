// The per-element work of gDP2d, written once as host+device functors. Each phase of
// engine.h launches one of these over its work list on the CPU (OpenMP) or the GPU (CUDA).
#pragma once
#include <cmath>
#include <cstring>

#include "exec/hd.h"
#include "exec/priority.h"
#include "predicates/predicates.h"
#include "refine2d/mesh2d.h"

namespace gdr::r2d {

using exec::bits_of;
using exec::u64;

GDR_HD_INLINE int next3(int i) { return i == 2 ? 0 : i + 1; }
GDR_HD_INLINE int prev3(int i) { return i == 0 ? 2 : i - 1; }

// Quality criteria, in forms that avoid square roots and trigonometry in kernels.
struct Criteria {
  double sin2_min_angle = 0;  // sin^2(theta); 0 disables the angle test
  double max_edge2 = 0;       // squared edge bound; 0 = off
  double max_area2 = 0;       // twice the area bound (compared with |cross|); 0 = off
  double offcenter_h = 0;     // off-centres: height over the shortest edge / its length; 0 = circumcentres
  int sink_steps = 0;         // with off-centres: steps towards larger empty circles in the petal (move_to_petal_sink)
  // Encroachment: 0 = diametral circle (Ruppert); else the diametral lens of the points that
  // see the subsegment at an angle whose cosine c has c^2 >= lens_cos2 (c < 0).
  double lens_cos2 = 0;
  // Per region number r > 0 (mesh2d.h, kRegionShift): twice region r's area bound at
  // region_area2[r - 1], 0 = none; null without regional bounds. Device memory of the run.
  const double* region_area2 = nullptr;
  int step_limit = 4096;      // point-location walk bound (deferred beyond it)
  int grid_exp = 1074;        // new coordinates are multiples of 2^-grid_exp (on_grid)
};

// The facade rescales the input so that its coordinates are below 2 and multiples of
// 2^-grid_exp (grid_exp <= 260): every product of four coordinate differences is then a
// multiple of 2^-1040, and the predicates' expansions cannot underflow (docs/predicates.md).
// New points keep that: a coordinate too small to be a multiple of 2^-grid_exp by itself is
// rounded to one (a move of at most 2^-261, below the rounding of any construction near 1).
GDR_HD_INLINE double on_grid(double v, int grid_exp) {
  return fabs(v) < ldexp(1.0, 52 - grid_exp) ? ldexp(rint(ldexp(v, grid_exp)), -grid_exp) : v;
}

GDR_HD_INLINE const double* pt(const MeshView& m, int v) { return m.xy + 2 * v; }

GDR_HD_INLINE bool is_subseg(const MeshView& m, int t, int e) {
  return (m.tflag[t] & (kSubseg0 << e)) != 0;
}

// The segment that subsegment ab lies on: that of a segment point among its endpoints, or,
// between two input vertices, the segment joining them.
GDR_HD_INLINE int segment_of(const MeshView& m, int a, int b) {
  if (m.ptype[a] == kSegmentPoint) return m.pseg[a];
  if (m.ptype[b] == kSegmentPoint) return m.pseg[b];
  for (int k = m.vseg_begin[a]; k < m.vseg_begin[a + 1]; ++k) {
    const int s = m.vseg[k];
    if (m.seg[2 * s] == b || m.seg[2 * s + 1] == b) return s;
  }
  return -1;
}

GDR_HD_INLINE double dist2(const double* a, const double* b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1];
  return dx * dx + dy * dy;
}

// Twice the area of triangle t and the least sin^2 of its angles. The smallest angle faces
// the shortest edge and is at most 60 degrees, where the sine grows: sin^2 = (2 area)^2 / the
// product of the two longer squared edges (no trigonometry per triangle).
GDR_HD_INLINE void triangle_measures(const MeshView& m, int t, double& area2, double& sin2) {
  const double* a = pt(m, m.tv[3 * t]);
  const double* b = pt(m, m.tv[3 * t + 1]);
  const double* c = pt(m, m.tv[3 * t + 2]);
  area2 = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
  const double la = dist2(b, c), lb = dist2(c, a), lc = dist2(a, b);
  const double others = fmax(la * lb, fmax(lb * lc, lc * la));
  sin2 = others > 0 ? area2 * area2 / others : 0.0;
}

// Does p encroach the subsegment ab? Ruppert: strictly inside the diametral circle (exact).
// Lens: inside the diametral lens, i.e. the angle apb is at least arccos(-sqrt(lens_cos2)).
GDR_HD_INLINE bool encroaches(const double* a, const double* b, const double* p, double lens_cos2) {
  if (pred::in_diametral_circle(a, b, p) <= 0) return false;
  if (!(lens_cos2 > 0)) return true;
  const double ax = a[0] - p[0], ay = a[1] - p[1], bx = b[0] - p[0], by = b[1] - p[1];
  const double dot = ax * bx + ay * by;  // negative here
  return dot * dot >= lens_cos2 * (ax * ax + ay * ay) * (bx * bx + by * by);
}

// Classification of a triangle against the criteria.
enum : int { kGood = 0, kBad = 1, kBadProtected = 2 };

// A triangle whose shortest edge joins two segment points lying on different segments
// that share an input vertex, at (nearly) equal distances from it, sits in a small input
// angle: splitting it only cuts the angle again (Ruppert/Shewchuk). It is left bad and
// reported instead. The tolerance is on a quality heuristic, not on topology.
GDR_HD_INLINE bool in_small_angle(const MeshView& m, int p, int q) {
  if (m.ptype[p] != kSegmentPoint || m.ptype[q] != kSegmentPoint) return false;
  const int sp = m.pseg[p], sq = m.pseg[q];
  if (sp == sq || sp < 0 || sq < 0) return false;
  const int p0 = m.seg[2 * sp], p1 = m.seg[2 * sp + 1];
  const int q0 = m.seg[2 * sq], q1 = m.seg[2 * sq + 1];
  int apex = -1;
  if (p0 == q0 || p0 == q1) apex = p0;
  else if (p1 == q0 || p1 == q1) apex = p1;
  if (apex < 0) return false;
  const double dp = sqrt(dist2(pt(m, apex), pt(m, p)));
  const double dq = sqrt(dist2(pt(m, apex), pt(m, q)));
  return fabs(dp - dq) <= 1e-3 * (dp > dq ? dp : dq);
}

// Too big for the size bounds (longest edge, area)?
GDR_HD_INLINE bool too_big(const MeshView& m, int t, const Criteria& c) {
  const double* a = pt(m, m.tv[3 * t]);
  const double* b = pt(m, m.tv[3 * t + 1]);
  const double* d = pt(m, m.tv[3 * t + 2]);
  const double cross = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
  const double lmax = fmax(dist2(b, d), fmax(dist2(d, a), dist2(a, b)));
  double area2 = c.max_area2;
  const int region = m.tflag[t] >> kRegionShift;
  if (c.region_area2 && region > 0) {
    const double r = c.region_area2[region - 1];
    if (r > 0 && (area2 <= 0 || r < area2)) area2 = r;
  }
  return (c.max_edge2 > 0 && lmax > c.max_edge2) || (area2 > 0 && fabs(cross) > area2);
}

GDR_HD_INLINE int classify_triangle(const MeshView& m, int t, const Criteria& c) {
  if (too_big(m, t, c)) return kBad;
  if (c.sin2_min_angle <= 0) return kGood;
  const int v0 = m.tv[3 * t], v1 = m.tv[3 * t + 1], v2 = m.tv[3 * t + 2];
  const double* a = pt(m, v0);
  const double* b = pt(m, v1);
  const double* d = pt(m, v2);
  const double l0 = dist2(b, d), l1 = dist2(d, a), l2 = dist2(a, b);  // edge i opposite vertex i
  const double cross = (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]);
  // min angle < theta  <=>  sin^2(theta) * (product of the two longer squared edges) > cross^2
  int s = 0;
  double lmin = l0;
  if (l1 < lmin) { lmin = l1; s = 1; }
  if (l2 < lmin) { lmin = l2; s = 2; }
  // (The two longer edges' product, not l0 l1 l2 / lmin: a product of six differences
  // could underflow.)
  const double others = s == 0 ? l1 * l2 : (s == 1 ? l0 * l2 : l0 * l1);
  if (!(c.sin2_min_angle * others > cross * cross)) return kGood;
  const int p = m.tv[3 * t + next3(s)], q = m.tv[3 * t + prev3(s)];
  return in_small_angle(m, p, q) ? kBadProtected : kBad;
}

// The shortest edge pq of triangle abd and the corner r across it; returns |pq|^2.
GDR_HD_INLINE double shortest_edge(const double* a, const double* b, const double* d, const double*& p,
                                   const double*& q, const double*& r) {
  const double l0 = dist2(b, d), l1 = dist2(d, a), l2 = dist2(a, b);
  p = b;
  q = d;
  r = a;
  double lmin = l0;
  if (l1 < lmin) { lmin = l1; p = d; q = a; r = b; }
  if (l2 < lmin) { lmin = l2; p = a; q = b; r = d; }
  return lmin;
}

// Moves `out`, the circumcentre of triangle abd, to its off-centre.
GDR_HD_INLINE void move_to_offcenter(const double* a, const double* b, const double* d,
                                     const Criteria& c, double* out) {
  // Off-centre (Ungor): on the bisector of the shortest edge pq, at the height h|pq| where the
  // new triangle pq-o has an apex angle of about theta, when that is nearer than the
  // circumcentre. o is then |pq| / (2 sin(theta/2)) from p and q, 1.9|pq| at 30 degrees: new
  // edges are longer than the bad triangle's shortest, and the mesh grades away from small
  // features. (At the height of the circle of radius |pq| / (2 sin theta) through p and q, new
  // edges were only that long, |pq| at 30 degrees: the smallest features' edge length spread
  // over the whole domain, 9.8M points on a contour map that needs 0.34M.)
  const double *p, *q, *r;
  const double lmin = shortest_edge(a, b, d, p, q, r);
  const double mx = 0.5 * (p[0] + q[0]), my = 0.5 * (p[1] + q[1]);
  const double cx = out[0] - mx, cy = out[1] - my;
  const double cl = sqrt(cx * cx + cy * cy);
  const double h = sqrt(lmin) * c.offcenter_h;
  if (cl > h && cl > 0) {
    out[0] = mx + cx * (h / cl);
    out[1] = my + cy * (h / cl);
  }
}

// Circumcentre of triangle t and its squared radius (false: degenerate).
GDR_HD_INLINE bool circumcentre(const MeshView& m, int t, double* out, double* r2) {
  const double* a = pt(m, m.tv[3 * t]);
  const double* b = pt(m, m.tv[3 * t + 1]);
  const double* d = pt(m, m.tv[3 * t + 2]);
  const double bx = b[0] - a[0], by = b[1] - a[1], dx = d[0] - a[0], dy = d[1] - a[1];
  const double bl = bx * bx + by * by, dl = dx * dx + dy * dy;
  const double den = 2.0 * (bx * dy - by * dx);
  const double ux = (dy * bl - by * dl) / den, uy = (bx * dl - dx * bl) / den;
  *r2 = ux * ux + uy * uy;
  out[0] = a[0] + ux;
  out[1] = a[1] + uy;
  return *r2 < 1e300 && out[0] == out[0] && out[1] == out[1];
}

// Does x encroach a subsegment that is an edge of triangle t?
GDR_HD_INLINE bool encroaches_own_subseg(const MeshView& m, int t, const double* x, const Criteria& c) {
  for (int k = 0; k < 3; ++k)
    if (is_subseg(m, t, k) &&
        encroaches(pt(m, m.tv[3 * t + next3(k)]), pt(m, m.tv[3 * t + prev3(k)]), x, c.lens_cos2))
      return true;
  return false;
}

// Locally optimal Steiner points (Erten and Ungor, "Quality triangulations with locally
// optimal Steiner points", types III and IV): the petal of a bad triangle's shortest edge pq
// is the disk through p and q of radius |pq| / (2 sin theta) on the triangle's side, whose
// points see pq at an angle of at least theta and lie in the triangle's circumcircle. Where
// the circumcentre lies in it, the point goes instead to the centre of a larger empty circle
// in the petal: from the triangle, up to c.sink_steps times, to the neighbour (not across a
// subsegment) whose circumcentre lies in the petal with the largest circumradius above the
// current one, unless it encroaches a subsegment of that neighbour (a point there would only
// split the subsegment: on a gear at 30 degrees, 296 points against 257). The point still
// destroys the bad triangle, and it lies farther from every vertex than the circumcentre, so
// the insertion radius, and with it Ruppert's termination argument, only improves. Fewer
// points: 3-8% on the data set's maps at 20-30 degrees, 6-20% on a generated 1M-segment map
// (GPU, Benchmarks/RESULTS.md, ninety-fourth run). Returns false where the circumcentre is
// outside the petal (the off-centre's case).
GDR_HD_INLINE bool move_to_petal_sink(const MeshView& m, int t, const Criteria& c, double* out,
                                      double r2) {
  const double* a = pt(m, m.tv[3 * t]);
  const double* b = pt(m, m.tv[3 * t + 1]);
  const double* d = pt(m, m.tv[3 * t + 2]);
  const double *p, *q, *r;
  const double lmin = shortest_edge(a, b, d, p, q, r);
  // n: unit normal of pq towards r. The petal's centre is |pq| cot(theta) / 2 above pq.
  const double len = sqrt(lmin);
  double nx = (p[1] - q[1]) / len, ny = (q[0] - p[0]) / len;
  const double mx = 0.5 * (p[0] + q[0]), my = 0.5 * (p[1] + q[1]);
  if ((r[0] - mx) * nx + (r[1] - my) * ny < 0) {
    nx = -nx;
    ny = -ny;
  }
  const double s2 = c.sin2_min_angle, half_cot = 0.5 * len * sqrt((1 - s2) / s2);
  const double pcx = mx + nx * half_cot, pcy = my + ny * half_cot, pr2 = 0.25 * lmin / s2;
  auto in_petal = [&](const double* x) {
    const double dx = x[0] - pcx, dy = x[1] - pcy;
    return dx * dx + dy * dy < pr2 && (x[0] - mx) * nx + (x[1] - my) * ny > 0;
  };
  if (!in_petal(out)) return false;
  int u = t, from = -1;
  for (int step = 0; step < c.sink_steps; ++step) {
    int next = -1;
    double next_c[2], next_r2 = r2;
    for (int e = 0; e < 3; ++e) {
      const int nb = m.tn[3 * u + e];
      if (nb < 0 || nb / 3 == from || is_subseg(m, u, e)) continue;
      double cc[2], rr2;
      if (!circumcentre(m, nb / 3, cc, &rr2) || !(rr2 > next_r2) || !in_petal(cc)) continue;
      if (encroaches_own_subseg(m, nb / 3, cc, c)) continue;
      next = nb / 3;
      next_r2 = rr2;
      next_c[0] = cc[0];
      next_c[1] = cc[1];
    }
    if (next < 0) break;
    from = u;
    u = next;
    r2 = next_r2;
    out[0] = next_c[0];
    out[1] = next_c[1];
  }
  return true;
}

// Circumcentre (or Ungor off-centre, or sink in the petal) of triangle t, and its squared
// circumradius.
GDR_HD_INLINE void splitting_point(const MeshView& m, int t, const Criteria& c, double* out,
                                   double* r2) {
  const double* a = pt(m, m.tv[3 * t]);
  const double* b = pt(m, m.tv[3 * t + 1]);
  const double* d = pt(m, m.tv[3 * t + 2]);
  const bool ok = circumcentre(m, t, out, r2);
  if (c.offcenter_h > 0 && !(ok && c.sink_steps > 0 && move_to_petal_sink(m, t, c, out, *r2)))
    move_to_offcenter(a, b, d, c, out);
  // A near-flat triangle's circumcentre can be 2^480 away: it is brought back to 2^20 from
  // a in the same direction, still far outside the domain (coordinates below 2), so that no
  // predicate on it overflows; the walk towards it ends on a boundary subsegment as before.
  const double far = 0x1p20, vx = out[0] - a[0], vy = out[1] - a[1], v2 = vx * vx + vy * vy;
  if (v2 > far * far) {
    const double f = far / sqrt(v2);
    out[0] = a[0] + vx * f;
    out[1] = a[1] + vy * f;
  }
  out[0] = on_grid(out[0], c.grid_exp);
  out[1] = on_grid(out[1], c.grid_exp);
}

// The cosine of the angle at p between pq and px.
GDR_HD_INLINE double cos_angle(const double* p, const double* q, const double* x) {
  const double ux = q[0] - p[0], uy = q[1] - p[1], vx = x[0] - p[0], vy = x[1] - p[1];
  return (ux * vx + uy * vy) / sqrt((ux * ux + uy * uy) * (vx * vx + vy * vy));
}

// Splitting point of edge k of triangle t, a subsegment ab. Concentric shells (Ruppert,
// Shewchuk): where another subsegment meets ab at an endpoint in a triangle on either side
// (the segments meet at an angle below 180 degrees), split at a power-of-two distance from
// that endpoint (the one with the smaller angle, when both are), so that segments meeting at
// a small angle are cut at matching radii and do not encroach each other forever; elsewhere
// at the midpoint, as Triangle does. (Shells at every input vertex cut all segments
// unevenly: 7-10% more points on segments.) Above 30 degrees, shells from the one input
// vertex among a and b, as before: Triangle's rule left 0.0154% of the world map's area bad
// at 33.5 degrees, against below 0.01%.
GDR_HD_INLINE void segment_split_point(const MeshView& m, int t, int k, const Criteria& c,
                                       double* out) {
  const int va = m.tv[3 * t + next3(k)], vb = m.tv[3 * t + prev3(k)];
  const double* a = pt(m, va);
  const double* b = pt(m, vb);
  bool ia, ib;
  if (c.sin2_min_angle <= 0.25) {
    // Cosines of the smallest angles that other subsegments make with ab at a and at b.
    double ca = -2, cb = -2;
    const double* apex = pt(m, m.tv[3 * t + k]);
    if (is_subseg(m, t, prev3(k))) ca = cos_angle(a, b, apex);
    if (is_subseg(m, t, next3(k))) cb = cos_angle(b, a, apex);
    const int nb = m.tn[3 * t + k];
    if (nb >= 0) {  // in the triangle across ab, edge next3(ku) ends at a, prev3(ku) at b
      const int u = nb / 3, ku = nb % 3;
      const double* apex_u = pt(m, m.tv[3 * u + ku]);
      if (is_subseg(m, u, next3(ku))) ca = fmax(ca, cos_angle(a, b, apex_u));
      if (is_subseg(m, u, prev3(ku))) cb = fmax(cb, cos_angle(b, a, apex_u));
    }
    // Both: from the smaller angle, where the shells must match the other segment's. (From
    // the other end, the segment of sharp_angle.poly with 1.9 degrees at one end and 97 at
    // the other was cut unevenly near the 1.9: 113-182 Steiner points at 25.5-30 degrees,
    // now 82-101; Triangle 93-118.)
    ia = ca > cb;
    ib = cb >= ca && cb > -2;
  } else {
    ia = m.ptype[va] == kInputPoint;
    ib = m.ptype[vb] == kInputPoint;
    if (ia && ib) ia = ib = false;
  }
  double f = 0.5;
  if (ia || ib) {
    const double len = sqrt(dist2(a, b));
    const double d = exp2(floor(log2(0.5 * len) + 0.5));  // nearest power of two to len/2
    f = d / len;
    if (!(f > 0.25 && f < 0.75)) f = 0.5;
    if (ib) f = 1.0 - f;
  }
  out[0] = a[0] + f * (b[0] - a[0]);
  out[1] = a[1] + f * (b[1] - a[1]);
  if (f == 0.5) {  // the exact midpoint where representable, symmetric in a and b
    out[0] = 0.5 * (a[0] + b[0]);
    out[1] = 0.5 * (a[1] + b[1]);
  }
  out[0] = on_grid(out[0], c.grid_exp);
  out[1] = on_grid(out[1], c.grid_exp);
}

// Shells (segment_split_point) cut segments that meet at an input vertex v at matching
// distances from v; a vertex p on one of them sees the subsegment vw of the other, w at the
// same distance from v as p, from just outside its diametral circle, when the angle is
// small: by less than the rounding of p when the angle is 1e-8 rad. Then rounding alone made
// p encroach vw, vw was split at half the distance, which encroached the other subsegment
// at v, and so on down to 1e-71 from v (fuzz2d fan, --mode ruppert). Such a p, on a segment
// at v and at least as far from v as w (less 1e-3, the small-angle rule's tolerance), does
// not count as encroaching vw: with an angle above 2.6 degrees it never lies inside.
GDR_HD_INLINE bool on_matching_shell(const MeshView& m, int a, int b, int p) {
  const int s = segment_of(m, a, b);
  if (s < 0) return false;
  for (int end = 0; end < 2; ++end) {
    const int v = end ? b : a, w = end ? a : b;
    if (m.ptype[v] != kInputPoint || (m.seg[2 * s] != v && m.seg[2 * s + 1] != v)) continue;
    bool shares = false;  // p lies on another segment that ends at v
    if (m.ptype[p] == kSegmentPoint) {
      const int s2 = m.pseg[p];
      shares = s2 >= 0 && s2 != s && (m.seg[2 * s2] == v || m.seg[2 * s2 + 1] == v);
    } else if (m.ptype[p] == kInputPoint) {
      for (int k = m.vseg_begin[p]; k < m.vseg_begin[p + 1] && !shares; ++k) {
        const int s2 = m.vseg[k];
        shares = s2 != s && (m.seg[2 * s2] == v || m.seg[2 * s2 + 1] == v);
      }
    }
    if (shares && dist2(pt(m, v), pt(m, p)) >= (1 - 2e-3) * dist2(pt(m, v), pt(m, w))) return true;
  }
  return false;
}

// ---------------------------------------------------------------------------------------
// Collect (Algorithm 1 line 3, S4): per triangle a 4-bit mask; bits 0-2 are its edges as
// encroached subsegments, bit 3 the triangle itself when it is bad. Whether a triangle is bad
// and whether its apexes encroach its subsegments never change while it lives, so that part
// is computed once, when the triangle is new (kFresh), and kept in its flags; edges flagged
// for splitting since are added each time.
GDR_HD_INLINE int static_collect_mask(const MeshView& m, const Criteria& c, int t) {
  int mask = classify_triangle(m, t, c) == kBad ? 8 : 0;
  for (int k = 0; k < 3; ++k) {
    if (!is_subseg(m, t, k)) continue;
    const int a = m.tv[3 * t + next3(k)], b = m.tv[3 * t + prev3(k)], apex = m.tv[3 * t + k];
    if (encroaches(pt(m, a), pt(m, b), pt(m, apex), c.lens_cos2) && !on_matching_shell(m, a, b, apex))
      mask |= 1 << k;
  }
  return mask;
}

GDR_HD_INLINE int collect_mask(int flags) {
  if (flags & kDead) return 0;
  return ((flags & kCollectBits) >> kCollectShift) | ((flags / kSplitEdge0) & 7);
}

// Triangle t's entry count, its static mask computed first when it is new.
GDR_HD_INLINE int collect_count(const MeshView& m, const Criteria& c, int t) {
  int f = m.tflag[t];
  if ((f & kFresh) && !(f & kDead)) {
    f = (f & ~(kFresh | kCollectBits)) | (static_collect_mask(m, c, t) << kCollectShift);
    m.tflag[t] = f;
  }
  const int mask = collect_mask(f);
  return (mask & 1) + ((mask >> 1) & 1) + ((mask >> 2) & 1) + ((mask >> 3) & 1);
}

GDR_HD_INLINE void write_elements(const MeshView& m, int t, int o, int* list) {
  const int mask = collect_mask(m.tflag[t]);
  for (int k = 0; k < 4; ++k)
    if (mask & (1 << k)) list[o++] = 4 * t + k;
}

// Over the whole mesh: the entry count goes to aux, which the engine scans in place into
// list offsets (no per-triangle arrays beyond the mesh's own).
struct CollectMask {
  MeshView m;
  Criteria c;
  GDR_HD void operator()(long long i) const { m.aux[i] = collect_count(m, c, static_cast<int>(i)); }
};

// Expands the masks into the element list (t*4 + slot) at the scanned offsets.
struct ExpandElements {
  MeshView m;
  int* list;
  GDR_HD void operator()(long long i) const { write_elements(m, static_cast<int>(i), m.aux[i], list); }
};

// The same over a work list of triangles (increasing), with counts and offsets of its own.
struct CollectMaskAt {
  MeshView m;
  Criteria c;
  const int* tris;
  int* cnt;
  GDR_HD void operator()(long long i) const { cnt[i] = collect_count(m, c, tris[i]); }
};

struct ExpandElementsAt {
  MeshView m;
  const int* tris;
  const int* off;
  int* list;
  GDR_HD void operator()(long long i) const { write_elements(m, tris[i], off[i], list); }
};

// Old triangles whose collect mask may have grown since the last collect: those with an edge
// flagged for splitting. (A split subsegment's triangle across, kFresh again, can only lose
// elements: its edge is no longer a subsegment, and whether it is bad depends on its corners
// alone.) The CPU's work-list collect looks at them besides the last list and the new
// triangles (Engine::collect); the GPU scans the whole mesh and logs nothing (ids null).
// Past `cap` the log is full and the next collect scans the whole mesh.
struct TouchLog {
  int* ids = nullptr;
  int* n = nullptr;
  int cap = 0;
  GDR_HD_INLINE void add(int t) const {
    if (!ids) return;
    const int k = exec::atomic_add(n, 1);
    if (k < cap) ids[k] = t;
  }
};

// A splitting point and its claim (the paper's S): kind 0 splits the subsegment that is
// edge ek of triangle `start` (its canonical side), kind 1 is a free point (circumcentre)
// located in triangle `start`. 32 bytes.
struct Candidate {
  double x, y;
  u64 prio;
  int start;
  short kind;  // -1: dropped this iteration
  short ek;
};

// Priority of candidate k, for the 32-bit marks (exec/priority.h).
struct PrioOf {
  const Candidate* cand;
  GDR_HD_INLINE u64 operator()(int k) const { return cand[k].prio; }
};

enum : unsigned { kClassShape = 0, kClassTriangle = 1, kClassWalkSegment = 2, kClassEncroached = 3 };

// Priorities. Subsegments: longer first, but only by factor-of-two size classes; within a
// class the order is a pseudo-random permutation of the candidates. Exact sizes would make
// graded neighbourhoods into long chains where each point loses to its bigger neighbour and
// only one point per chain could be inserted per iteration.
using exec::shuffle_id;
using exec::size_class;

// Triangles: those too big for the size bounds first, larger first by size classes (the
// paper's order); then those bad by their shape alone, smallest first: by the length of their
// shortest edge, in classes of a factor sqrt(2) of its square (shortest_edge_class; one point
// at a time, shape_class), as Triangle's queue orders them (smallest features first, so that
// the points around them are placed before the coarser ones that they would otherwise crowd).
// For shape, larger-first needs more points and cascades sooner above 30 degrees (the world map at 33.5 degrees took 1.3M Steiner points larger-first
// against 345k worst-first by radius-edge ratio); smallest-first needs 3-10% fewer points than
// worst-first at 20-30 degrees (Benchmarks/RESULTS.md, issue 13). For size, a finer order takes
// more iterations (counties at 1M points: 89 against 68 on the H100, 29% slower).
// Above 30 degrees too: worst first by radius-edge ratio took 1.05-2x the points on the maps
// at 33-33.5 degrees, with bad areas alike (below 0.01%). (It was kept there while
// smallest-first cascaded on the world map at 33.5 degrees with Triangle's shells; with the
// shells from input vertices used above 30 degrees it does not.)
// The size level of triangle t: floor(2 log2) of its shortest edge's square (levels a factor
// 2^(1/4) apart in length; -2148 to 2047 for any double l2 > 0).
GDR_HD_INLINE int shortest_edge_level(const MeshView& m, int t) {
  const double* a = pt(m, m.tv[3 * t]);
  const double* b = pt(m, m.tv[3 * t + 1]);
  const double* d = pt(m, m.tv[3 * t + 2]);
  const double l2 = fmin(dist2(a, b), fmin(dist2(b, d), dist2(d, a)));
  return static_cast<int>(floor(2.0 * log2(l2)));
}

// The one-at-a-time queue's order among triangles bad by their shape (Engine::one_at_a_time),
// smaller triangles first: levels a factor 2^(1/8) apart of the shortest edge's square times
// 0.5 plus the square of the sine of the smallest angle (worse shapes a little earlier). One
// point at a time, the parallel iteration's levels of the shortest edge alone (below) took
// 1-8% more points on the maps at 20-30 degrees (generated 1M-segment map at 20 degrees:
// 527,771 against 489,156), the bare edge length once 1.7x as many (a generated 100k-segment
// map at 30 degrees), and an order without levels lost the locality of first come first
// served among equals (one thread: 3.8 s against 2.9 s on the 1M map). In the parallel
// iteration it took 0.1-3.4% fewer points on the maps (the 1M map 492,515 against 508,527)
// but cascaded at tiny input angles (Testing: fan_cascade33.poly, 6,052 points and a stall
// against 1,484), so the parallel iteration keeps shortest_edge_class.
GDR_HD_INLINE float shape_class(const MeshView& m, int t) {
  const double* a = pt(m, m.tv[3 * t]);
  const double* b = pt(m, m.tv[3 * t + 1]);
  const double* d = pt(m, m.tv[3 * t + 2]);
  const double l2 = fmin(dist2(a, b), fmin(dist2(b, d), dist2(d, a)));
  double area2, sin2;
  triangle_measures(m, t, area2, sin2);
  return static_cast<float>(20000.0 - floor(8.0 * log2(l2 * (0.5 + sin2))));  // positive
}

// The parallel iteration's priority size of a triangle bad by its shape: smaller higher.
GDR_HD_INLINE float shortest_edge_class(const MeshView& m, int t) {
  return static_cast<float>(2200 - shortest_edge_level(m, t));  // positive
}

// Graded order (issue 13): a bad triangle waits while a bad triangle more than a window of
// levels smaller lies within a few hops of it (Engine::near_levels). The parallel insertion
// splits every locally first triangle at once; a sequential mesher like Triangle splits the
// smallest first everywhere, and by the time it reaches a coarse triangle the grading around
// the small features has often reshaped or removed it. Splitting the coarse ones early puts
// points where the grading later crowds more points around them: 13% more on the counties
// map at 30 degrees (Benchmarks/RESULTS.md). Only triangles bad by their shape hold others
// back: triangles too big for the size bounds are many and alike, and ordering them among
// themselves took 5x the iterations (counties at 1M points: 312 against 61) for 0.2% fewer
// points. They wait, with a wider window, for the shape-bad ones near them.
constexpr int kGradeWindowShape = 2, kGradeWindowSize = 4;

// A triangle whose level was just lowered, to pass on in the next hop.
struct LevelAt {
  int tri, level;
};

// The frontiers of the hops (Engine::near_levels) are appended to at most `cap` entries,
// their sizes counted on the device (size[h]: entries handed to hop h + 1), so that no hop
// waits for the host. A frontier that outgrew its cap stops the hops; the rest are passes
// over the whole mesh. Hops done in full: those before the first overfull frontier.
struct Frontiers {
  int* size;  // kGradeHops counts, zeroed
  int cap;
  GDR_HD void append(LevelAt* out, int hop, LevelAt f) const {
    const int at = exec::atomic_add(&size[hop], 1);
    if (at < cap) out[at] = f;
  }
  GDR_HD int hops_done(int hops) const {
    for (int h = 0; h < hops; ++h)
      if (size[h] > cap) return h;
    return hops;
  }
};

// Seeds the levels: each triangle bad by its shape its own level (kNoLevel elsewhere, aux
// filled beforehand), and the first frontier.
constexpr int kNoLevel = 1 << 30;
// The level that bad-list entry e seeds: its triangle's, where the triangle is bad by its
// shape (slot 3, not too big for the size bounds); kNoLevel for every other entry.
GDR_HD_INLINE int seed_level(const MeshView& m, const Criteria& c, int e) {
  if ((e & 3) != 3 || too_big(m, e >> 2, c)) return kNoLevel;
  return shortest_edge_level(m, e >> 2);
}
struct SeedLevels {
  MeshView m;
  Criteria c;
  const int* list;
  int* level;
  LevelAt* front;
  Frontiers fr;
  GDR_HD void operator()(long long j) const {
    const int e = list[j], l = seed_level(m, c, e);
    if (l == kNoLevel) return;
    level[e >> 2] = l;
    fr.append(front, 0, LevelAt{e >> 2, l});
  }
};

// Hop `hop` (1-based) from the frontier of the one before: each entry lowers its neighbours'
// levels (atomic min), and those it lowered form the next frontier. Entries carry the level
// they pass on, so that a level lowered twice in one hop still travels one hop per round:
// after k rounds each level is the least within k hops, in any order of the atomics. Launched
// over a bound of the frontier's size; a frontier that overflowed stops this hop and the rest.
struct PushLevels {
  MeshView m;
  const LevelAt* in;
  LevelAt* out;
  int* level;
  Frontiers fr;
  int hop, last;
  GDR_HD void operator()(long long i) const {
    const int n = fr.size[hop - 1];
    if (i >= n || n > fr.cap) return;  // (after an overfull frontier, the next ones are empty)
    const LevelAt f = in[i];
    for (int k = 0; k < 3; ++k) {
      const int nb = m.tn[3 * f.tri + k];
      if (nb >= 0 && f.level < exec::atomic_min(&level[nb / 3], f.level) && hop < last)
        fr.append(out, hop, LevelAt{nb / 3, f.level});
    }
  }
};

// Pass `pass` over the whole mesh, for the hops the frontiers did not do: each live triangle
// takes the smallest level of itself and its neighbours. The passes alternate between the
// levels and a second buffer, starting from the levels at the first pass that runs.
struct SpreadLevels {
  MeshView m;
  int* level;
  int* other;
  Frontiers fr;
  int pass, hops;
  GDR_HD void operator()(long long i) const {
    const int done = fr.hops_done(hops);
    if (pass < done) return;
    const int* in = (pass - done) % 2 ? other : level;
    int* out = (pass - done) % 2 ? level : other;
    const int t = static_cast<int>(i);
    int v = in[t];
    if (!(m.tflag[t] & kDead))
      for (int k = 0; k < 3; ++k) {
        const int nb = m.tn[3 * t + k];
        if (nb >= 0 && in[nb / 3] < v) v = in[nb / 3];
      }
    out[t] = v;
  }
};

// After the passes: where an odd number ran, the result is in the second buffer.
struct TakeSpreadLevels {
  int* level;
  const int* other;
  Frontiers fr;
  int hops;
  GDR_HD void operator()(long long t) const {
    if ((hops - fr.hops_done(hops)) % 2) level[t] = other[t];
  }
};

GDR_HD_INLINE void make_segment_candidate(const MeshView& m, int t, int k, unsigned klass,
                                          unsigned id, const Criteria& c, Candidate& out) {
  const int a = m.tv[3 * t + next3(k)], b = m.tv[3 * t + prev3(k)];
  double p[2];
  segment_split_point(m, t, k, c, p);
  const int nb = m.tn[3 * t + k];
  // The canonical side: both triangles may report the same subsegment.
  if (nb >= 0 && nb / 3 < t) {
    t = nb / 3;
    k = nb % 3;
  }
  out.x = p[0];
  out.y = p[1];
  out.start = t;
  out.ek = static_cast<short>(k);
  out.kind = 0;
  out.prio = exec::make_priority(klass, size_class(dist2(pt(m, a), pt(m, b))), id);
  // A split point that rounds onto an endpoint would duplicate it: leave that subsegment.
  if ((p[0] == pt(m, a)[0] && p[1] == pt(m, a)[1]) || (p[0] == pt(m, b)[0] && p[1] == pt(m, b)[1]))
    out.kind = -1;
}

// A walk that ran out of its short first budget (kind, until the second pass decides).
enum : short { kFarWalk = -2 };

// Splitting points and point location (Algorithm 1 lines 5-6). A walk towards a
// circumcentre that meets a subsegment takes that subsegment's split point instead.
// Walks go in two passes: the first stops after `max_steps` (kFarWalk); the second
// (`far_only`) walks again, up to the step limit, the far ones whose id is below `far_below`.
struct ComputeSplittingPoints {
  MeshView m;
  Criteria c;
  const int* list;
  Candidate* out;
  unsigned salt;  // changes every iteration
  bool worst_first;  // triangles bad by shape smallest first (shortest edge); false: all larger first
  u64 compete_below;  // only elements whose random id is below this (of 2^32) compete
  int max_steps;
  bool far_only;
  u64 far_below;
  const int* near_level;  // graded order: smallest bad level near each triangle (null: off)
  TouchLog touched = {};  // triangles with an edge flagged for splitting
  GDR_HD void operator()(long long j) const {
    const int e = list[j];
    const int t = e >> 2, k = e & 3;
    Candidate& cand = out[j];
    const unsigned id = shuffle_id(static_cast<unsigned>(j), salt);
    if (far_only) {
      if (cand.kind != kFarWalk) return;
      if (id >= far_below) {
        cand.kind = -1;
        return;
      }
    } else if (id >= compete_below) {  // sits this iteration out: no walk
      cand.kind = -1;
      return;
    }
    if (k < 3) {
      make_segment_candidate(m, t, k, kClassEncroached, id, c, cand);
      return;
    }
    if (near_level) {
      const int window = too_big(m, t, c) ? kGradeWindowSize : kGradeWindowShape;
      if (near_level[t] < shortest_edge_level(m, t) - window) {  // waits for smaller ones
        cand.kind = -1;
        return;
      }
    }
    double p[2], r2;
    splitting_point(m, t, c, p, &r2);
    cand.x = p[0];
    cand.y = p[1];
    cand.kind = -1;
    if (!(r2 < 1e300) || p[0] != p[0] || p[1] != p[1]) return;  // degenerate triangle
    // The priority before the walk: the one-at-a-time sweep orders by it without walking.
    if (worst_first && !too_big(m, t, c))
      cand.prio = exec::make_priority(kClassShape, shortest_edge_class(m, t), id);
    else
      cand.prio = exec::make_priority(kClassTriangle, size_class(r2), id);
    int u = t;
    const int steps = max_steps < c.step_limit ? max_steps : c.step_limit;
    for (int step = 0; step < steps; ++step) {
      int exit = -1;
      for (int i0 = 0; i0 < 3; ++i0) {
        const int i = (i0 + step) % 3;  // rotate the first edge tried: no cycling
        const double* a = pt(m, m.tv[3 * u + next3(i)]);
        const double* b = pt(m, m.tv[3 * u + prev3(i)]);
        if (pred::orient2d(a, b, p) < 0) {
          exit = i;
          break;
        }
      }
      if (exit < 0) {  // p is in u (or on its boundary)
        cand.kind = 1;
        cand.start = u;
        cand.ek = -1;
        return;
      }
      if (is_subseg(m, u, exit) || m.tn[3 * u + exit] < 0) {
        if (!is_subseg(m, u, exit)) return;  // outside an unconstrained boundary: cannot happen
        exec::atomic_or(&m.tflag[u], kSplitEdge0 << exit);
        touched.add(u);
        make_segment_candidate(m, u, exit, kClassWalkSegment, id, c, cand);
        return;
      }
      u = m.tn[3 * u + exit] / 3;
    }
    if (steps < c.step_limit) cand.kind = kFarWalk;
  }
};

// Filter (S3): one splitting point per triangle, by atomic priority marks.
// Only candidates whose random id is below `keep_below` (of 2^32) compete, and only
// subsegment splits when `segments_only`.
struct ClaimStart {
  MeshView m;
  const Candidate* cand;
  u64 keep_below;
  bool segments_only;
  GDR_HD void operator()(long long j) const {
    const Candidate& c = cand[j];
    if (c.kind >= 0 && (c.kind == 0 || !segments_only) && exec::priority_id(c.prio) < keep_below)
      exec::raise_mark(&m.mark[c.start], static_cast<int>(j), c.prio, PrioOf{cand});
  }
};

// ---------------------------------------------------------------------------------------
// Cavity growth by ExpandList (Algorithm 4, S2): one tuple = (point, triangle).
enum : int {
  kTupleCavity = 1,  // first claim of a triangle in the point's cavity
  kTupleRing = 2,    // first claim of a triangle just outside it
  kTupleDup = 3,     // already claimed by the same point
  kTupleLost = 4,
  kTupleStale = 5,
};
enum : int { kForceIn = 1, kForceOut = 2 };

struct CavityTuple {
  int pt;     // index into the candidate list
  int tri;
  int state;  // kTuple*; on input: kForce* bits
};

GDR_HD_INLINE bool is_split_edge(const MeshView& m, const Candidate& c, int t, int e) {
  if (c.kind != 0) return false;
  if (t == c.start && e == c.ek) return true;
  return m.tn[3 * c.start + c.ek] == 3 * t + e;
}

// The triangle that a subsegment split's cavity starts from: the one on the split point's
// side of the subsegment. Rounding can put the point a little off the subsegment, outside the
// circle of the triangle across, which then joins the cavity only if its circle holds the
// point (GrowCavity): forced in, it left a non-Delaunay edge from the point to its apex.
GDR_HD_INLINE int split_start(const MeshView& m, const Candidate& c) {
  const int nb = m.tn[3 * c.start + c.ek];
  const double p[2] = {c.x, c.y};
  if (nb < 0 || pred::orient2d(pt(m, m.tv[3 * c.start + next3(c.ek)]),
                               pt(m, m.tv[3 * c.start + prev3(c.ek)]), p) >= 0)
    return c.start;
  return nb / 3;
}

struct GrowCavity {
  MeshView m;
  const Candidate* cand;
  int* failed;
  double lens_cos2;
  TouchLog touched = {};  // triangles with an edge flagged for splitting
  GDR_HD int operator()(long long, CavityTuple& h, CavityTuple* out) const {
    const Candidate& c = cand[h.pt];
    if (exec::volatile_load(&failed[h.pt])) {
      h.state = kTupleStale;
      return 0;
    }
    const int t = h.tri;
    const double p[2] = {c.x, c.y};
    bool in;
    if (h.state & kForceIn) in = true;
    else if (h.state & kForceOut) in = false;
    else
      in = pred::incircle(pt(m, m.tv[3 * t]), pt(m, m.tv[3 * t + 1]), pt(m, m.tv[3 * t + 2]), p) > 0;
    if (!in) {
      // Ring: the triangle stays, only its link to the cavity changes, unless another
      // point's cavity takes it (checked in VerifyClaims).
      h.state = kTupleRing;
      return 0;
    }
    const int r = exec::claim(&m.mark[t], h.pt, c.prio, PrioOf{cand});
    if (r < 0) {
      failed[h.pt] = 1;
      h.state = kTupleLost;
      return 0;
    }
    if (r == 0) {
      h.state = kTupleDup;
      return 0;
    }
    h.state = kTupleCavity;
    int n = 0;
    for (int e = 0; e < 3; ++e) {
      const int nb = m.tn[3 * t + e];
      if (is_split_edge(m, c, t, e)) {
        if (nb >= 0) out[n++] = CavityTuple{h.pt, nb / 3, 0};  // split_start
        continue;
      }
      if (is_subseg(m, t, e)) {
        // Ruppert: a free point that would encroach a subsegment is not inserted; the
        // subsegment is split first (flagged for the next iteration).
        if (c.kind == 1 && encroaches(pt(m, m.tv[3 * t + next3(e)]), pt(m, m.tv[3 * t + prev3(e)]),
                                      p, lens_cos2)) {
          exec::atomic_or(&m.tflag[t], kSplitEdge0 << e);
          touched.add(t);
          failed[h.pt] = 1;
          return n;
        }
        if (nb >= 0) out[n++] = CavityTuple{h.pt, nb / 3, kForceOut};  // keep it untouched
        continue;
      }
      if (nb >= 0) out[n++] = CavityTuple{h.pt, nb / 3, 0};
    }
    return n;
  }
};

// Marks that did not survive mean a higher-priority point overlaps: drop this one. Cavities
// may touch: where our ring triangle lies in a higher point's cavity, both fans meet across
// the shared edges, and both points go in together only if each shared unconstrained edge
// stays locally Delaunay (the other point not inside the circle of our new triangle on it),
// so the mesh stays constrained Delaunay. The paper's cavities need not be independent
// either; its flips repair such edges afterwards. A subsegment split by either point may not
// lie between the two: the side of it that stays (split_start) makes it an ordinary edge,
// which the other fan would keep as a subsegment.
struct VerifyClaims {
  MeshView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  int* failed;
  bool touching;  // false: any contact with a higher cavity drops this point
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (h.state == kTupleCavity && m.mark[h.tri] != h.pt + 1) failed[h.pt] = 1;
    if (h.state != kTupleRing) return;
    const int r = h.tri, other = m.mark[r];
    if (!exec::held_above(other, h.pt, cand[h.pt].prio, PrioOf{cand})) return;
    if (!touching) {
      failed[h.pt] = 1;
      return;
    }
    const double p[2] = {cand[h.pt].x, cand[h.pt].y};
    const double q[2] = {cand[other - 1].x, cand[other - 1].y};
    for (int e = 0; e < 3; ++e) {
      const int nb = m.tn[3 * r + e];
      if (nb < 0 || m.mark[nb / 3] != h.pt + 1) continue;
      if (is_split_edge(m, cand[h.pt], r, e) || is_split_edge(m, cand[other - 1], r, e)) {
        failed[h.pt] = 1;
        return;
      }
      if (is_subseg(m, r, e)) continue;
      const int c = nb / 3, ce = nb % 3;  // our cavity triangle and its edge on r
      if (pred::incircle(pt(m, m.tv[3 * c + next3(ce)]), pt(m, m.tv[3 * c + prev3(ce)]), p, q) > 0)
        failed[h.pt] = 1;
    }
  }
};

struct SetInCavity {
  MeshView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  const int* failed;
  int value;  // 1: set, 0: clear (for points dropped after marking)
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (h.state != kTupleCavity) return;
    if (value && !failed[h.pt]) m.tflag[h.tri] |= kInCavity;
    // Only the owner of the mark may clear: a failed point's tuple can name a triangle that
    // a winner took over.
    if (!value && failed[h.pt] && m.mark[h.tri] == h.pt + 1) m.tflag[h.tri] &= ~kInCavity;
  }
};

// Edge e of cavity triangle t: 0 interior to the cavity, 1 boundary edge that gets a new
// triangle (fan from the point), 2 the split subsegment on the domain boundary (no triangle).
// A split subsegment whose other side stays out of the cavity (split_start) is a fan edge:
// its new triangle is flat, with the two halves as edges and the old subsegment as an
// ordinary one, which is what a flip would make of it.
enum : int { kEdgeInterior = 0, kEdgeFan = 1, kEdgeHullSplit = 2 };

GDR_HD_INLINE int cavity_edge(const MeshView& m, const Candidate& c, int j, int t, int e) {
  const int nb = m.tn[3 * t + e];
  if (nb < 0) return is_split_edge(m, c, t, e) ? kEdgeHullSplit : kEdgeFan;
  if ((m.tflag[nb / 3] & kInCavity) && m.mark[nb / 3] == j + 1) return kEdgeInterior;
  return kEdgeFan;
}

// Last exact checks before anything is written: the fan must be made of positively oriented
// triangles, and no other subsegment may lie inside the cavity.
struct CheckCavity {
  MeshView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  int* failed;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (h.state != kTupleCavity || failed[h.pt]) return;
    const Candidate& c = cand[h.pt];
    const double p[2] = {c.x, c.y};
    const int t = h.tri;
    for (int e = 0; e < 3; ++e) {
      const int k = cavity_edge(m, c, h.pt, t, e);
      if (k == kEdgeInterior) {
        if (is_subseg(m, t, e) && !is_split_edge(m, c, t, e)) failed[h.pt] = 1;
      } else if (k == kEdgeFan) {
        if (pred::orient2d(pt(m, m.tv[3 * t + next3(e)]), pt(m, m.tv[3 * t + prev3(e)]), p) <= 0)
          failed[h.pt] = 1;
      }
    }
  }
};

struct CountFanEdges {
  MeshView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  const int* failed;
  int* count;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    int n = 0;
    if (h.state == kTupleCavity && !failed[h.pt])
      for (int e = 0; e < 3; ++e) n += cavity_edge(m, cand[h.pt], h.pt, h.tri, e) == kEdgeFan;
    count[i] = n;
  }
};

struct StoreSlotBase {
  MeshView m;
  const CavityTuple* tuples;
  const int* failed;
  const int* base;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (h.state == kTupleCavity && !failed[h.pt]) m.aux[h.tri] = base[i];
  }
};

GDR_HD_INLINE int fan_rank(const MeshView& m, const Candidate& c, int j, int t, int e) {
  int r = 0;
  for (int i = 0; i < e; ++i) r += cavity_edge(m, c, j, t, i) == kEdgeFan;
  return r;
}

// Remesh the cavity: one new triangle (x, y, p) per fan edge (x, y), linked to the
// triangle outside the cavity; the links between fan triangles come in LinkFan.
struct CreateFan {
  MeshView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  const int* failed;
  const int* point_id;  // new vertex index of each candidate
  int old_ntri;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (h.state != kTupleCavity || failed[h.pt]) return;
    const Candidate& c = cand[h.pt];
    const int t = h.tri, p = point_id[h.pt];
    int split_a = -1, split_b = -1;
    if (c.kind == 0) {
      split_a = m.tv[3 * c.start + next3(c.ek)];
      split_b = m.tv[3 * c.start + prev3(c.ek)];
    }
    int r = 0;
    for (int e = 0; e < 3; ++e) {
      if (cavity_edge(m, c, h.pt, t, e) != kEdgeFan) continue;
      const int nt = old_ntri + m.aux[t] + r++;
      const int x = m.tv[3 * t + next3(e)], y = m.tv[3 * t + prev3(e)];
      const bool split = is_split_edge(m, c, t, e);  // before the link across changes
      m.tv[3 * nt] = x;
      m.tv[3 * nt + 1] = y;
      m.tv[3 * nt + 2] = p;
      const int outer = m.tn[3 * t + e];
      if (outer >= 0 && (m.tflag[outer / 3] & kInCavity)) {
        // Another winner's cavity is across: link to its new triangle on this edge (it
        // links back the same way).
        const int r = outer / 3, q = m.mark[r] - 1;
        m.tn[3 * nt + 2] = 3 * (old_ntri + m.aux[r] + fan_rank(m, cand[q], q, r, outer % 3)) + 2;
      } else {
        m.tn[3 * nt + 2] = outer;
        if (outer >= 0) m.tn[outer] = 3 * nt + 2;
      }
      m.tn[3 * nt] = -1;
      m.tn[3 * nt + 1] = -1;
      // The fan edge keeps its flags, unless it is the split subsegment (a flat triangle,
      // cavity_edge): then it is an ordinary edge on both sides, and the triangle across
      // collects its elements anew. The edges at p are halves of a split subsegment.
      int flags = 0;
      if (split) {
        exec::atomic_and(&m.tflag[outer / 3], ~((kSubseg0 | kSplitEdge0) << (outer % 3)));
        exec::atomic_or(&m.tflag[outer / 3], kFresh);
      } else {
        if (m.tflag[t] & (kSplitEdge0 << e)) flags |= kSplitEdge0 << 2;
        if (is_subseg(m, t, e)) flags |= kSubseg0 << 2;
      }
      if (y == split_a || y == split_b) flags |= kSubseg0;
      if (x == split_a || x == split_b) flags |= kSubseg0 << 1;
      m.tflag[nt] = flags | kFresh | (m.tflag[t] & (kMaxRegions << kRegionShift));
      m.mark[nt] = 0;
    }
  }
};

struct LinkFan {
  MeshView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  const int* failed;
  int old_ntri;
  int* error;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (h.state != kTupleCavity || failed[h.pt]) return;
    const Candidate& c = cand[h.pt];
    const int t = h.tri;
    int r = 0;
    for (int e = 0; e < 3; ++e) {
      if (cavity_edge(m, c, h.pt, t, e) != kEdgeFan) continue;
      const int nt = old_ntri + m.aux[t] + r++;
      // Rotate around y = end of the fan edge, through the cavity, to the fan edge that
      // starts at y: the next triangle of the fan.
      const int y = m.tv[3 * t + prev3(e)];
      int u = t, k = prev3(e);
      for (int guard = 0;; ++guard) {
        if (guard > m.ntri) {  // a cavity has fewer triangles than the mesh
          *error = 1;
          return;
        }
        const int out_edge = prev3(k);  // edge (y, next vertex) of u
        const int kind = cavity_edge(m, c, h.pt, u, out_edge);
        if (kind == kEdgeFan) {
          const int nt2 = old_ntri + m.aux[u] + fan_rank(m, c, h.pt, u, out_edge);
          m.tn[3 * nt] = 3 * nt2 + 1;
          m.tn[3 * nt2 + 1] = 3 * nt;
          break;
        }
        if (kind == kEdgeHullSplit) break;  // the new hull subsegment (y, p): no neighbour
        const int nb = m.tn[3 * u + out_edge];
        u = nb / 3;
        k = m.tv[3 * u] == y ? 0 : (m.tv[3 * u + 1] == y ? 1 : 2);
      }
    }
  }
};

struct KillCavity {
  MeshView m;
  const CavityTuple* tuples;
  const int* failed;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (h.state == kTupleCavity && !failed[h.pt]) m.tflag[h.tri] = kDead;
  }
};

struct WritePoints {
  MeshView m;
  const Candidate* cand;
  const int* failed;
  const int* point_id;
  GDR_HD void operator()(long long j) const {
    if (failed[j]) return;
    const Candidate& c = cand[j];
    const int p = point_id[j];
    m.xy[2 * p] = c.x;
    m.xy[2 * p + 1] = c.y;
    m.ptype[p] = c.kind == 0 ? kSegmentPoint : kFreePoint;
    // The split subsegment's triangle is dead by now but keeps its vertices until compaction.
    m.pseg[p] = c.kind == 0 ? segment_of(m, m.tv[3 * c.start + next3(c.ek)],
                                         m.tv[3 * c.start + prev3(c.ek)])
                            : -1;
  }
};

// Compaction (S1), in place: the live triangle at tail position live+i moves into the r-th
// dead slot of the head, r being its rank among the tail's live triangles; aux holds the
// exclusive scan of the live flags, and `base` the number of live triangles in the head.
struct MoveTriangles {
  MeshView m;
  const int* hole;
  int live, base;
  GDR_HD int destination(int t) const { return t < live ? t : hole[m.aux[t] - base]; }
  GDR_HD void operator()(long long i) const {
    const int s = live + static_cast<int>(i);
    if (m.tflag[s] & kDead) return;
    const int d = destination(s);
    for (int e = 0; e < 3; ++e) {
      m.tv[3 * d + e] = m.tv[3 * s + e];
      const int nb = m.tn[3 * s + e];
      m.tn[3 * d + e] = nb < 0 ? -1 : 3 * destination(nb / 3) + nb % 3;
    }
    m.tflag[d] = m.tflag[s] & ~kInCavity;
  }
};

// Then every neighbour of a moved triangle points back at its new slot.
struct FixBackLinks {
  MeshView m;
  const int* hole;
  int live, base;
  GDR_HD void operator()(long long i) const {
    const int s = live + static_cast<int>(i);
    if (m.tflag[s] & kDead) return;
    const int d = hole[m.aux[s] - base];
    for (int e = 0; e < 3; ++e) {
      const int nb = m.tn[3 * d + e];
      if (nb >= 0) m.tn[nb] = 3 * d + e;
    }
  }
};

}  // namespace gdr::r2d
