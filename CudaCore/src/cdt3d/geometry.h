// Exact tests on input triangles (host only): segment/triangle and triangle/triangle
// intersection that ignores what two triangles legitimately share (a vertex or an edge),
// and a ray-parity test for point-in-closed-surface. Only signs of exact predicates decide.
#pragma once
#include <algorithm>
#include <array>
#include <vector>

#include "gdr/pslg.h"
#include "predicates/predicates.h"

namespace gdr::cdt3d::geom {

inline const double* xyz(const Point3& p) { return &p.x; }

inline int sign(double v) { return (v > 0) - (v < 0); }

inline int orient3d(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return sign(pred::orient3d(xyz(a), xyz(b), xyz(c), xyz(d)));
}

// orient2d of the projection that drops coordinate `axis` (the other two in cyclic order,
// so that every projection keeps a consistent orientation).
inline int orient2d(int axis, const Point3& a, const Point3& b, const Point3& c) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const double pa[2] = {xyz(a)[u], xyz(a)[v]}, pb[2] = {xyz(b)[u], xyz(b)[v]},
               pc[2] = {xyz(c)[u], xyz(c)[v]};
  return sign(pred::orient2d(pa, pb, pc));
}

// A coordinate to drop so that the projection of triangle abc is not degenerate, or -1
// when all three projections are (the triangle has zero area: its corners are collinear).
inline int projection_axis(const Point3& a, const Point3& b, const Point3& c) {
  for (int axis : {2, 0, 1})
    if (orient2d(axis, a, b, c) != 0) return axis;
  return -1;
}

// Closed 2D point-in-triangle in projection `axis` (abc not degenerate there).
inline bool in_triangle_2d(int axis, const Point3& a, const Point3& b, const Point3& c,
                           const Point3& p) {
  const int s = orient2d(axis, a, b, c);
  return s * orient2d(axis, a, b, p) >= 0 && s * orient2d(axis, b, c, p) >= 0 &&
         s * orient2d(axis, c, a, p) >= 0;
}

// Lexicographic order of the projected coordinates; along a line it orders its points.
inline bool lex_less(int axis, const Point3& a, const Point3& b) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  if (xyz(a)[u] != xyz(b)[u]) return xyz(a)[u] < xyz(b)[u];
  return xyz(a)[v] < xyz(b)[v];
}

// Closed 2D segments pq and ab meet (projection `axis`).
inline bool segments_meet_2d(int axis, const Point3& p, const Point3& q, const Point3& a,
                             const Point3& b) {
  const int o1 = orient2d(axis, p, q, a), o2 = orient2d(axis, p, q, b);
  if (o1 * o2 > 0) return false;
  const int o3 = orient2d(axis, a, b, p), o4 = orient2d(axis, a, b, q);
  if (o3 * o4 > 0) return false;
  if (o1 != 0 || o2 != 0 || o3 != 0 || o4 != 0) return true;
  // Collinear: do the two intervals overlap along the line?
  const Point3& lo1 = lex_less(axis, p, q) ? p : q;
  const Point3& hi1 = lex_less(axis, p, q) ? q : p;
  const Point3& lo2 = lex_less(axis, a, b) ? a : b;
  const Point3& hi2 = lex_less(axis, a, b) ? b : a;
  return !lex_less(axis, hi1, lo2) && !lex_less(axis, hi2, lo1);
}

// Closed segment pq meets closed triangle abc (abc not degenerate), given op and oq, the
// signs of orient3d(a, b, c, p) and orient3d(a, b, c, q).
inline bool segment_meets_triangle(const Point3& p, const Point3& q, const Point3& a,
                                   const Point3& b, const Point3& c, int op, int oq) {
  if (op * oq > 0) return false;
  if (op == 0 && oq == 0) {  // coplanar: a 2D question
    const int axis = projection_axis(a, b, c);
    return in_triangle_2d(axis, a, b, c, p) || in_triangle_2d(axis, a, b, c, q) ||
           segments_meet_2d(axis, p, q, a, b) || segments_meet_2d(axis, p, q, b, c) ||
           segments_meet_2d(axis, p, q, c, a);
  }
  // The line through p and q crosses the plane once, on the segment; it passes through
  // the triangle iff it passes on the same side of all three edges.
  const int s1 = orient3d(p, q, a, b), s2 = orient3d(p, q, b, c), s3 = orient3d(p, q, c, a);
  const bool pos = s1 > 0 || s2 > 0 || s3 > 0, neg = s1 < 0 || s2 < 0 || s3 < 0;
  return !(pos && neg);
}

inline bool segment_meets_triangle(const Point3& p, const Point3& q, const Point3& a,
                                   const Point3& b, const Point3& c) {
  return segment_meets_triangle(p, q, a, b, c, orient3d(a, b, c, p), orient3d(a, b, c, q));
}

// x (in the plane of a, d, e) lies in the closed cone at a spanned by d and e.
inline bool in_cone(int axis, const Point3& a, const Point3& d, const Point3& e, const Point3& x) {
  const int s = orient2d(axis, a, d, e);
  return s * orient2d(axis, a, d, x) >= 0 && s * orient2d(axis, a, x, e) >= 0;
}

// Triangles t1 and t2 (vertex ids into pts, each non-degenerate, not the same vertex set)
// meet anywhere other than in what they share: a common vertex or a common edge. Each
// plane orientation is evaluated once: on flat (coplanar) input they take the exact stage.
inline bool triangles_clash(const std::vector<Point3>& pts, std::array<int, 3> t1,
                            std::array<int, 3> t2) {
  int shared = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) shared += t1[i] == t2[j];
  auto P = [&](int v) -> const Point3& { return pts[v]; };
  auto in = [](const std::array<int, 3>& t, int v) { return t[0] == v || t[1] == v || t[2] == v; };
  // Rotate t1 so that its shared vertices come first, and t2 to start with the same ones.
  if (shared > 0) {
    while (!in(t2, t1[0]) || (shared == 2 && !in(t2, t1[1]))) std::rotate(t1.begin(), t1.begin() + 1, t1.end());
    while (t2[0] != t1[0]) std::rotate(t2.begin(), t2.begin() + 1, t2.end());
  }
  const Point3 &a = P(t1[0]), &b = P(t1[1]), &c = P(t1[2]);
  if (shared == 2) {
    // t1 = (a, b, c), t2 holds a, b and apex d. They overlap only if coplanar with c and d
    // on the same side of ab.
    const Point3& d = P(t2[1] == t1[1] ? t2[2] : t2[1]);
    if (orient3d(a, b, c, d) != 0) return false;
    const int axis = projection_axis(a, b, c);
    return orient2d(axis, a, b, c) == orient2d(axis, a, b, d);
  }
  const Point3 &d = P(t2[1]), &e = P(t2[2]);
  if (shared == 1) {
    // t1 = (a, b, c), t2 = (a, d, e). Both other corners of one strictly on one side of the
    // other's plane: they meet only in a.
    const int d1 = orient3d(a, b, c, d), e1 = orient3d(a, b, c, e);
    if (d1 * e1 > 0) return false;
    const int ax1 = projection_axis(a, b, c);
    if (d1 == 0 && e1 == 0) {
      // Coplanar: near a the triangles are their angles at a; they overlap beyond a iff
      // an edge ray of one lies in the other's closed angle.
      return in_cone(ax1, a, d, e, b) || in_cone(ax1, a, d, e, c) || in_cone(ax1, a, b, c, d) ||
             in_cone(ax1, a, b, c, e);
    }
    const int b2 = orient3d(a, d, e, b), c2 = orient3d(a, d, e, c);
    if (b2 * c2 > 0) return false;
    // The intersection lies on the line where the planes meet and starts at a: it is more
    // than a iff its far end is on an opposite edge, or on an edge at a lying in the other
    // triangle's plane.
    if (segment_meets_triangle(b, c, a, d, e, b2, c2) || segment_meets_triangle(d, e, a, b, c, d1, e1)) return true;
    const int ax2 = projection_axis(a, d, e);
    return (b2 == 0 && in_cone(ax2, a, d, e, b)) || (c2 == 0 && in_cone(ax2, a, d, e, c)) ||
           (d1 == 0 && in_cone(ax1, a, b, c, d)) || (e1 == 0 && in_cone(ax1, a, b, c, e));
  }
  // Nothing shared: any contact is a clash.
  const Point3& f = P(t2[0]);
  const int o1[3] = {orient3d(a, b, c, f), orient3d(a, b, c, d), orient3d(a, b, c, e)};
  if ((o1[0] > 0 && o1[1] > 0 && o1[2] > 0) || (o1[0] < 0 && o1[1] < 0 && o1[2] < 0)) return false;
  const int o2[3] = {orient3d(f, d, e, a), orient3d(f, d, e, b), orient3d(f, d, e, c)};
  if ((o2[0] > 0 && o2[1] > 0 && o2[2] > 0) || (o2[0] < 0 && o2[1] < 0 && o2[2] < 0)) return false;
  const Point3* v1[3] = {&a, &b, &c};
  const Point3* v2[3] = {&f, &d, &e};
  for (int k = 0; k < 3; ++k) {
    const int k1 = (k + 1) % 3;
    if (segment_meets_triangle(*v1[k], *v1[k1], f, d, e, o2[k], o2[k1])) return true;
    if (segment_meets_triangle(*v2[k], *v2[k1], a, b, c, o1[k], o1[k1])) return true;
  }
  return false;
}

// Point p lies on closed triangle abc (non-degenerate).
inline bool point_on_triangle(const Point3& p, const Point3& a, const Point3& b, const Point3& c) {
  if (orient3d(a, b, c, p) != 0) return false;
  return in_triangle_2d(projection_axis(a, b, c), a, b, c, p);
}

// Orientation of (u, v, p) in the (y, z) plane with p moved to (p.y + eps, p.z + eps^2):
// never 0 unless u and v project to the same point. Antisymmetric in u, v, so a ray from
// the perturbed p never passes through an edge or a vertex.
inline int orient_yz_perturbed(const Point3& u, const Point3& v, const Point3& p) {
  const int s = orient2d(0, u, v, p);
  if (s != 0) return s;
  if (u.z != v.z) return u.z > v.z ? 1 : -1;
  if (v.y != u.y) return v.y > u.y ? 1 : -1;
  return 0;
}

// Does the ray from p in +x cross triangle abc (p perturbed as above)? Returns 1 or 0, or
// -1 when p lies on the triangle.
inline int ray_crosses(const Point3& p, const Point3& a, const Point3& b, const Point3& c) {
  const int n = orient2d(0, a, b, c);  // sign of the normal's x component
  if (n == 0) return 0;                // seen edge-on: the perturbed ray misses it
  if (orient_yz_perturbed(a, b, p) != n || orient_yz_perturbed(b, c, p) != n ||
      orient_yz_perturbed(c, a, p) != n)
    return 0;
  const int o = orient3d(a, b, c, p);
  if (o == 0) return -1;
  return o == n ? 1 : 0;  // the crossing is ahead of p
}

}  // namespace gdr::cdt3d::geom
