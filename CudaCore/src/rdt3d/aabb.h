// The input surface for gDP3d's geometric queries: an axis-aligned bounding-box tree over its
// triangles (built on the host, traversed by host+device code), exact segment-triangle tests
// and the inside/outside test of a point (ray parity).
//
// Every decision is made with exact orientation tests on the given points (segment ends are
// rounded constructions such as circumcentres; the decision is exact for those coordinates).
// Box tests only prune: boxes are widened by a relative 2^-30 of the scene so that a rounded
// slab test never drops a triangle the exact tests would keep. Intersection points are
// rounded constructions.
#pragma once
#include <cmath>
#include <vector>

#include "exec/hd.h"
#include "predicates/predicates.h"

namespace gdr::rdt3d {

// Node k: box[6k..6k+5] = (min x, y, z, max x, y, z); kids[2k] = left child and kids[2k+1] =
// right child for an inner node; a leaf has kids[2k] = -1 - first and kids[2k+1] = count of
// its triangles in `order`. Node 0 is the root.
struct AabbView {
  const double* xyz;  // surface points, 3 per point
  const int* tri;     // 3 per triangle
  const int* order;   // triangles by leaf
  const double* box;
  const int* kids;
  int nodes;
};

struct HostAabb {
  std::vector<double> box;
  std::vector<int> kids, order;
};

// Median split on the longest axis of the centroids' box, leaves of at most 4 triangles;
// nodes in pre-order (a subtree's nodes follow its root), subtrees built in parallel.
HostAabb build_aabb(const std::vector<double>& xyz, const std::vector<int>& tri);

GDR_HD_INLINE bool segment_meets_box(const double* box, const double* p, const double* q) {
  double t0 = 0, t1 = 1;
  for (int k = 0; k < 3; ++k) {
    const double d = q[k] - p[k];
    const double lo = box[k], hi = box[3 + k];
    if (d == 0) {
      if (p[k] < lo || p[k] > hi) return false;
      continue;
    }
    double a = (lo - p[k]) / d, b = (hi - p[k]) / d;
    if (a > b) {
      const double s = a;
      a = b;
      b = s;
    }
    t0 = a > t0 ? a : t0;
    t1 = b < t1 ? b : t1;
    if (t0 > t1) return false;
  }
  return true;
}

// How segment pq meets triangle abc, exactly: kMiss, kCross (the open segment crosses the
// triangle's interior, neither end on its plane), or kTouch (any other contact: an end on
// the plane, or the segment through an edge or a corner). Coplanar contact is kTouch.
enum : int { kMiss = 0, kCross = 1, kTouch = 2 };

GDR_HD_INLINE int segment_triangle(const double* p, const double* q, const double* a,
                                   const double* b, const double* c) {
  const double sp = pred::orient3d(a, b, c, p), sq = pred::orient3d(a, b, c, q);
  if ((sp > 0 && sq > 0) || (sp < 0 && sq < 0)) return kMiss;
  if (sp == 0 && sq == 0) {
    // Coplanar: contact only matters for degeneracy detection; report a touch when the
    // segment's box meets the triangle's (conservative).
    for (int k = 0; k < 3; ++k) {
      const double lo = fmin(a[k], fmin(b[k], c[k])), hi = fmax(a[k], fmax(b[k], c[k]));
      if (fmax(p[k], q[k]) < lo || fmin(p[k], q[k]) > hi) return kMiss;
    }
    return kTouch;
  }
  const double o1 = pred::orient3d(p, q, a, b), o2 = pred::orient3d(p, q, b, c),
               o3 = pred::orient3d(p, q, c, a);
  const bool pos = o1 >= 0 && o2 >= 0 && o3 >= 0, neg = o1 <= 0 && o2 <= 0 && o3 <= 0;
  if (!pos && !neg) return kMiss;
  if (sp == 0 || sq == 0 || o1 == 0 || o2 == 0 || o3 == 0) return kTouch;
  return kCross;
}

// The point where segment pq meets the plane of abc (rounded), for p and q on its two sides.
GDR_HD_INLINE void segment_plane_point(const double* p, const double* q, const double* a,
                                       const double* b, const double* c, double* out) {
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double dp = n[0] * (p[0] - a[0]) + n[1] * (p[1] - a[1]) + n[2] * (p[2] - a[2]);
  const double dq = n[0] * (q[0] - a[0]) + n[1] * (q[1] - a[1]) + n[2] * (q[2] - a[2]);
  double t = dp != dq ? dp / (dp - dq) : 0.5;
  t = t < 0 ? 0 : (t > 1 ? 1 : t);
  for (int k = 0; k < 3; ++k) out[k] = p[k] + t * (q[k] - p[k]);
}

// Visits every triangle whose widened box the segment pq meets: visit(triangle) returns
// false to stop. Depth-first with a fixed stack (the tree's depth is about log2(n / 4) + 2).
template <class Visit>
GDR_HD_INLINE void for_triangles_near_segment(const AabbView& t, const double* p, const double* q,
                                              Visit&& visit) {
  if (t.nodes == 0) return;
  int stack[64];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int k = stack[--top];
    if (!segment_meets_box(t.box + 6 * k, p, q)) continue;
    const int l = t.kids[2 * k], r = t.kids[2 * k + 1];
    if (l < 0) {
      for (int i = -1 - l; i < -1 - l + r; ++i)
        if (!visit(t.order[i])) return;
    } else if (top + 2 <= 64) {
      stack[top++] = r;
      stack[top++] = l;
    }
  }
}

GDR_HD_INLINE const double* corner(const AabbView& t, int tri, int k) {
  return t.xyz + 3 * t.tri[3 * tri + k];
}

// Does segment pq meet the surface (any contact)?
GDR_HD_INLINE bool segment_meets_surface(const AabbView& t, const double* p, const double* q) {
  bool hit = false;
  for_triangles_near_segment(t, p, q, [&](int tri) {
    hit = segment_triangle(p, q, corner(t, tri, 0), corner(t, tri, 1), corner(t, tri, 2)) != kMiss;
    return !hit;
  });
  return hit;
}

// How a segment meets the surface: proper crossings, and whether any contact was degenerate.
struct SegmentContacts {
  int crossings = 0;
  bool touch = false;
};

// The point of segment pq on the surface that is farthest from `far_from` (the surface
// centre of a restricted facet whose corner is far_from: the centre of its largest surface
// Delaunay ball), and the triangle it lies on. False when pq does not meet the surface.
// Ties between triangles go to the lower triangle index, so the answer does not depend on
// the traversal order. `contacts` (optional) counts the crossings on the way.
GDR_HD_INLINE bool surface_point_on_segment(const AabbView& t, const double* p, const double* q,
                                            const double* far_from, double* out, int* out_tri,
                                            SegmentContacts* contacts = nullptr) {
  double best = -1;
  int best_tri = -1;
  for_triangles_near_segment(t, p, q, [&](int tri) {
    const double *a = corner(t, tri, 0), *b = corner(t, tri, 1), *c = corner(t, tri, 2);
    const int r = segment_triangle(p, q, a, b, c);
    if (r == kMiss) return true;
    if (contacts) {
      contacts->crossings += r == kCross;
      contacts->touch = contacts->touch || r == kTouch;
    }
    double x[3];
    if (pred::orient3d(a, b, c, p) == 0 && pred::orient3d(a, b, c, q) == 0) {
      // Segment in the triangle's plane: its end nearer the triangle's centroid stands in.
      const double g[3] = {(a[0] + b[0] + c[0]) / 3, (a[1] + b[1] + c[1]) / 3, (a[2] + b[2] + c[2]) / 3};
      const double dp = (p[0] - g[0]) * (p[0] - g[0]) + (p[1] - g[1]) * (p[1] - g[1]) + (p[2] - g[2]) * (p[2] - g[2]);
      const double dq = (q[0] - g[0]) * (q[0] - g[0]) + (q[1] - g[1]) * (q[1] - g[1]) + (q[2] - g[2]) * (q[2] - g[2]);
      for (int k = 0; k < 3; ++k) x[k] = dp <= dq ? p[k] : q[k];
    } else {
      segment_plane_point(p, q, a, b, c, x);
    }
    const double d = (x[0] - far_from[0]) * (x[0] - far_from[0]) + (x[1] - far_from[1]) * (x[1] - far_from[1]) +
                     (x[2] - far_from[2]) * (x[2] - far_from[2]);
    if (d > best || (d == best && tri < best_tri)) {
      best = d;
      best_tri = tri;
      for (int k = 0; k < 3; ++k) out[k] = x[k];
    }
    return true;
  });
  if (out_tri) *out_tri = best_tri;
  return best_tri >= 0;
}

// Is p inside the closed surface? Parity of the crossings of a segment from p to a point
// beyond the surface's box (`reach`: longer than any distance from p out of the box). A
// segment with a degenerate contact (through an edge or corner, or an end on a triangle's
// plane) is not counted: the next of eight fixed directions is tried. p on the surface, where
// every direction is degenerate, counts as outside.
GDR_HD_INLINE bool inside_surface(const AabbView& t, const double* p, double reach) {
  // Directions without symmetry with respect to the axes (inputs are often axis aligned).
  const double dirs[8][3] = {{0.5377, 0.8622, 0.0303},  {-0.7254, 0.3188, 0.6102},
                             {0.1839, -0.9307, 0.3160}, {-0.2050, -0.1241, -0.9709},
                             {0.8884, -0.3008, -0.3469}, {-0.6565, -0.7297, 0.1912},
                             {0.3426, 0.5784, -0.7403},  {-0.9280, 0.2120, -0.3061}};
  if (t.nodes == 0) return false;
  for (int k = 0; k < 3; ++k)
    if (!(p[k] >= t.box[k] && p[k] <= t.box[3 + k])) return false;  // outside the surface's box
  for (int d = 0; d < 8; ++d) {
    const double q[3] = {p[0] + reach * dirs[d][0], p[1] + reach * dirs[d][1], p[2] + reach * dirs[d][2]};
    int crossings = 0;
    bool degenerate = false;
    for_triangles_near_segment(t, p, q, [&](int tri) {
      const int r = segment_triangle(p, q, corner(t, tri, 0), corner(t, tri, 1), corner(t, tri, 2));
      if (r == kTouch) degenerate = true;
      crossings += r == kCross;
      return !degenerate;
    });
    if (!degenerate) return (crossings & 1) != 0;
  }
  return false;
}

}  // namespace gdr::rdt3d
