// The per-element work of the parallel constrained Delaunay triangulation (cdt_engine.h),
// written once as host+device functors like the refinement's kernels.h, whose insertion
// phases it reuses for the points.
#pragma once
#include "refine2d/kernels.h"

namespace gdr::r2d {

// Priority of item k among competitors for triangles (points of one round, segments of one
// recovery round): a fixed shuffle of its number, so that winners are spread in space and
// the result does not depend on thread timing.
struct ShuffledPrio {
  const int* id;  // the item's own number (point or segment); null: k itself
  GDR_HD_INLINE u64 operator()(int k) const {
    return exec::shuffle_id(static_cast<unsigned>(id ? id[k] : k), 0x2545f491u);
  }
};

// Visibility walk from triangle t to the triangle holding p (on its boundary counts); the
// first edge tried rotates with the step, so that ties cannot cycle. -1 after max_steps.
GDR_HD_INLINE int walk_to(const MeshView& m, int t, const double* p, int max_steps) {
  for (int step = 0; step < max_steps; ++step) {
    int exit = -1;
    for (int i0 = 0; i0 < 3; ++i0) {
      const int i = (i0 + step) % 3;
      if (pred::orient2d(pt(m, m.tv[3 * t + next3(i)]), pt(m, m.tv[3 * t + prev3(i)]), p) < 0) {
        exit = i;
        break;
      }
    }
    if (exit < 0) return t;
    const int nb = m.tn[3 * t + exit];
    if (nb < 0) return -1;  // outside the bounding triangle: cannot happen
    t = nb / 3;
  }
  return -1;
}

// One candidate per point still to insert, located in triangle loc[p].
struct MakePointCandidates {
  const double* xy;
  const int* pending;
  const int* loc;
  Candidate* cand;
  GDR_HD void operator()(long long j) const {
    const int p = pending[j];
    Candidate& c = cand[j];
    c.x = xy[2 * p];
    c.y = xy[2 * p + 1];
    c.prio = ShuffledPrio{nullptr}(p);
    c.start = loc[p];
    c.kind = 1;
    c.ek = -1;
  }
};

// After an insertion round: a point still to insert whose triangle died walks from a new
// triangle of the cavity that took it (the cavity's region is covered by its fan).
struct Relocate {
  MeshView m;
  const int* pending;
  const int* done;    // per pending entry: inserted this round
  int* loc;
  const int* anchor;  // per winner: one of its new triangles
  int* error;
  GDR_HD void operator()(long long j) const {
    if (done[j]) return;
    const int p = pending[j];
    const int t = loc[p];
    if (!(m.tflag[t] & kDead)) return;
    const int u = walk_to(m, anchor[m.mark[t] - 1], m.xy + 2 * p, 1 << 24);  // the winner's
    if (u < 0) *error = 1;
    else loc[p] = u;
  }
};

// ---------------------------------------------------------------------------------------
// Segment recovery. tseg[3t+e] is the segment on edge e of triangle t, or -1.

// The triangle around vertex a (position i in it) whose angle at a holds the direction of
// b, found by rotating around a from triangle t. Returns the edge code 3t+i, or:
//   -2 - c  if b is already joined to a (edge code c of the edge ab),
//   -1      if a vertex lies on the open segment ab (or the rotation failed).
GDR_HD_INLINE long long segment_start(const MeshView& m, int t, int a, int b) {
  const double* pa = pt(m, a);
  const double* pb = pt(m, b);
  int i = m.tv[3 * t] == a ? 0 : (m.tv[3 * t + 1] == a ? 1 : 2);
  for (int guard = 0; guard < 1 << 20; ++guard) {
    const int u = m.tv[3 * t + next3(i)], w = m.tv[3 * t + prev3(i)];
    if (u == b) return -2 - (3LL * t + prev3(i));
    if (w == b) return -2 - (3LL * t + next3(i));
    const double ou = pred::orient2d(pa, pt(m, u), pb);
    const double ow = pred::orient2d(pa, pb, pt(m, w));
    if (ou == 0 && (pt(m, u)[0] - pa[0]) * (pb[0] - pa[0]) + (pt(m, u)[1] - pa[1]) * (pb[1] - pa[1]) > 0)
      return -1;  // u on the ray from a through b, before b (b is no neighbour of a)
    if (ou > 0 && ow > 0) return 3LL * t + i;
    // Rotate counter-clockwise around a: across edge (a, w), which is edge next3(i).
    const int nb = m.tn[3 * t + next3(i)];
    if (nb < 0) return -1;  // a on the bounding triangle: not an input vertex
    t = nb / 3;
    i = m.tv[3 * t] == a ? 0 : (m.tv[3 * t + 1] == a ? 1 : 2);
  }
  return -1;
}

// Walks the triangles that the open segment ab crosses, from the start found by
// segment_start (edge code `start`: triangle and a's position). Calls visit(t, left_edge,
// right_edge, left_vertex_new) for each: the region's boundary edges of t on each side of ab
// (-1 if none) in walking order. Returns the number of triangles, or -1 if a vertex lies on
// ab, -2 if ab crosses a segment.
template <class Visit>
GDR_HD_INLINE int walk_segment(const MeshView& m, const int* tseg, long long start, int b,
                               int max_tris, Visit visit) {
  int t = static_cast<int>(start / 3);
  const int i = static_cast<int>(start % 3);
  const double* pa = pt(m, m.tv[3 * t + i]);
  const double* pb = pt(m, b);
  // First triangle (a, u, w): u right of ab, w left; it exits across edge i.
  visit(t, next3(i), prev3(i));
  int exit = i;
  for (int n = 1; n < max_tris; ++n) {
    if (tseg[3 * t + exit] >= 0) return -2;
    const int code = m.tn[3 * t + exit];
    if (code < 0) return -2;  // cannot happen inside the bounding triangle
    t = code / 3;
    const int e = code % 3;
    const int v = m.tv[3 * t + e];  // apex across the entry edge (x left, y right of ab)
    if (v == b) {
      visit(t, prev3(e), next3(e));
      return n + 1;
    }
    const double o = pred::orient2d(pa, pb, pt(m, v));
    if (o == 0) return -1;
    if (o > 0) {  // v left: edge (v, x) bounds the left side, ab leaves across (y, v)
      visit(t, prev3(e), -1);
      exit = next3(e);
    } else {      // v right: edge (y, v) bounds the right side, ab leaves across (v, x)
      visit(t, -1, next3(e));
      exit = prev3(e);
    }
  }
  return -3;  // longer than max_tris
}

// Lower-left on a pencil of circles: the chain vertex c of V[lo+1 .. hi-1] whose circle
// through V[lo], V[hi] holds none of the others (all lie on one side of that base).
GDR_HD_INLINE int empty_circle_apex(const MeshView& m, const int* V, int lo, int hi) {
  int c = lo + 1;
  const double* a = pt(m, V[lo]);
  const double* b = pt(m, V[hi]);
  const bool ccw = pred::orient2d(a, b, pt(m, V[c])) > 0;
  for (int k = lo + 2; k < hi; ++k) {
    const double s = ccw ? pred::incircle(a, b, pt(m, V[c]), pt(m, V[k]))
                         : pred::incircle(b, a, pt(m, V[c]), pt(m, V[k]));
    if (s > 0) c = k;
  }
  return c;
}

}  // namespace gdr::r2d
