// Whether a PSLG needs cleaning (input.cpp, clean_input): duplicate points, repeated
// segments, segments that cross, overlap or touch another's interior, points on a segment's
// interior. One exact pass in the engine's space, for large inputs on the GPU (issue 14: the
// host's checks took 0.13-0.19 s of a 1M-segment run on the H100 machine). It answers only
// yes or no: an input that needs cleaning takes the host's path, which names and mends
// what it finds. The same tests as the host's (the same grid of cells, the same exact
// predicates), so both paths agree on which inputs are clean.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "exec/algorithms.h"
#include "gdr/pslg.h"
#include "predicates/predicates.h"

namespace gdr::r2d {
namespace checks {

using exec::u64;

// Doubles as unsigned keys in the same order (-0 as 0, so that they sort together).
GDR_HD_INLINE u64 sortable(double v) {
  if (v == 0) v = 0;
  u64 b;
  memcpy(&b, &v, sizeof b);
  return (b >> 63) ? ~b : b | (u64(1) << 63);
}

GDR_HD_INLINE bool strictly_between(const double* a, const double* b, const double* c) {
  if (a[0] != b[0]) return (a[0] < c[0] && c[0] < b[0]) || (b[0] < c[0] && c[0] < a[0]);
  return (a[1] < c[1] && c[1] < b[1]) || (b[1] < c[1] && c[1] < a[1]);
}

GDR_HD_INLINE int sgn(double v) { return (v > 0) - (v < 0); }

// Do segments ab and cd (point numbers) cross, overlap, or does an end of one lie on the
// other's interior? (input.cpp's conflict(), any kind.)
GDR_HD_INLINE bool conflict(const double* P, int a, int b, int c, int d) {
  const double *pa = P + 2 * a, *pb = P + 2 * b, *pc = P + 2 * c, *pd = P + 2 * d;
  const int o1 = sgn(pred::orient2d(pa, pb, pc)), o2 = sgn(pred::orient2d(pa, pb, pd));
  if (o1 == 0 && o2 == 0) {
    const bool same = (a == c && b == d) || (a == d && b == c);
    return strictly_between(pa, pb, pc) || strictly_between(pa, pb, pd) ||
           strictly_between(pc, pd, pa) || strictly_between(pc, pd, pb) || same;
  }
  const int o3 = sgn(pred::orient2d(pc, pd, pa)), o4 = sgn(pred::orient2d(pc, pd, pb));
  if (o1 * o2 < 0 && o3 * o4 < 0) return true;
  return (o1 == 0 && c != a && c != b && strictly_between(pa, pb, pc)) ||
         (o2 == 0 && d != a && d != b && strictly_between(pa, pb, pd)) ||
         (o3 == 0 && a != c && a != d && strictly_between(pc, pd, pa)) ||
         (o4 == 0 && b != c && b != d && strictly_between(pc, pd, pb));
}

// The uniform grid of input.cpp's find_segment_conflicts: about one segment per cell over
// the segments' bounding box; a segment goes into every cell its bounding box covers.
struct Grid {
  double x0, y0, h;
  int g;
  GDR_HD int cell(double v, double o) const {
    const int c = static_cast<int>((v - o) / h);
    return c < 0 ? 0 : (c > g - 1 ? g - 1 : c);
  }
  template <class F>
  GDR_HD void for_cells(const double* P, int a, int b, F f) const {
    const double *pa = P + 2 * a, *pb = P + 2 * b;
    const int cx0 = cell(fmin(pa[0], pb[0]), x0), cx1 = cell(fmax(pa[0], pb[0]), x0);
    const int cy0 = cell(fmin(pa[1], pb[1]), y0), cy1 = cell(fmax(pa[1], pb[1]), y0);
    for (int cy = cy0; cy <= cy1; ++cy)
      for (int cx = cx0; cx <= cx1; ++cx) f(cy * g + cx);
  }
};

}  // namespace checks

template <class Space>
bool input_is_clean(const std::vector<Point2>& points, const std::vector<std::array<int, 2>>& segments) {
  using Ops = exec::Ops<Space>;
  using exec::u64;
  const std::size_t n = points.size(), ns = segments.size();
  exec::Buffer<Space, double> xy_buf;
  xy_buf.upload(&points.data()->x, 2 * n);
  exec::Buffer<Space, int> seg_buf;
  seg_buf.upload(segments.data()->data(), 2 * ns);
  exec::Buffer<Space, int> found(1);
  found.zero();
  const double* P = xy_buf.data();
  const int* S = seg_buf.data();
  int* bad = found.data();

  // Duplicate points: ordered by (x, y) with two stable sorts, then neighbours compared.
  {
    exec::Buffer<Space, u64> key(n);
    exec::Buffer<Space, int> order(n);
    u64* k = key.data();
    int* o = order.data();
    Ops::for_each(n, [=] GDR_HD(long long i) { k[i] = checks::sortable(P[2 * i + 1]), o[i] = int(i); });
    Ops::sort_pairs(k, o, n);
    Ops::for_each(n, [=] GDR_HD(long long i) { k[i] = checks::sortable(P[2 * o[i]]); });
    Ops::sort_pairs(k, o, n);
    Ops::for_each(n, [=] GDR_HD(long long i) {
      if (i > 0 && P[2 * o[i]] == P[2 * o[i - 1]] && P[2 * o[i] + 1] == P[2 * o[i - 1] + 1]) *bad = 1;
    });
  }
  // Repeated segments: ordered by their ends.
  {
    exec::Buffer<Space, u64> key(ns);
    exec::Buffer<Space, int> order(ns);
    u64* k = key.data();
    int* o = order.data();
    Ops::for_each(ns, [=] GDR_HD(long long s) {
      const int a = S[2 * s], b = S[2 * s + 1];
      k[s] = (u64(a < b ? a : b) << 32) | u64(a < b ? b : a);
      o[s] = int(s);
    });
    Ops::sort_pairs(k, o, ns);
    Ops::for_each(ns, [=] GDR_HD(long long i) {
      if (i > 0 && k[i] == k[i - 1]) *bad = 1;
    });
  }
  if (found.get(0)) return false;
  if (ns < 2) return true;

  // Crossings, overlaps, touching ends and points on segments, cell by cell.
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const auto& s : segments)
    for (const int v : s) {
      x0 = std::min(x0, points[v].x), x1 = std::max(x1, points[v].x);
      y0 = std::min(y0, points[v].y), y1 = std::max(y1, points[v].y);
    }
  const int g = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(ns))), 1, 2048);
  const double w = std::max(x1 - x0, y1 - y0);
  const checks::Grid grid{x0, y0, w > 0 ? w / g : 1.0, g};
  const std::size_t ncells = static_cast<std::size_t>(g) * g;
  // Segments per cell, then points that end no segment per cell (they may lie on one).
  exec::Buffer<Space, int> seg_begin(ncells + 1), pt_begin(ncells + 1), is_end(n);
  seg_begin.zero();
  pt_begin.zero();
  is_end.zero();
  int *sb = seg_begin.data(), *pb = pt_begin.data(), *end = is_end.data();
  Ops::for_each(ns, [=] GDR_HD(long long s) {
    end[S[2 * s]] = end[S[2 * s + 1]] = 1;
    grid.for_cells(P, S[2 * s], S[2 * s + 1], [&](int c) { exec::atomic_add(&sb[c], 1); });
  });
  const auto loose_cell = [=] GDR_HD(long long v) -> int {
    const double x = P[2 * v], y = P[2 * v + 1];
    if (end[v] || !(x >= x0 && x <= x1 && y >= y0 && y <= y1)) return -1;
    return grid.cell(y, y0) * grid.g + grid.cell(x, x0);
  };
  Ops::for_each(n, [=] GDR_HD(long long v) {
    const int c = loose_cell(v);
    if (c >= 0) exec::atomic_add(&pb[c], 1);
  });
  const std::size_t seg_entries = static_cast<std::size_t>(Ops::exclusive_scan(sb, sb, ncells + 1));
  const std::size_t pt_entries = static_cast<std::size_t>(Ops::exclusive_scan(pb, pb, ncells + 1));
  exec::Buffer<Space, int> seg_fill(ncells), pt_fill(ncells), in_cell(seg_entries), pt_in_cell(pt_entries);
  int *sf = seg_fill.data(), *pf = pt_fill.data(), *ic = in_cell.data(), *pc = pt_in_cell.data();
  Ops::for_each(ncells, [=] GDR_HD(long long c) { sf[c] = sb[c], pf[c] = pb[c]; });
  Ops::for_each(ns, [=] GDR_HD(long long s) {
    grid.for_cells(P, S[2 * s], S[2 * s + 1],
                   [&](int c) { ic[exec::atomic_add(&sf[c], 1)] = static_cast<int>(s); });
  });
  Ops::for_each(n, [=] GDR_HD(long long v) {
    const int c = loose_cell(v);
    if (c >= 0) pc[exec::atomic_add(&pf[c], 1)] = static_cast<int>(v);
  });
  Ops::for_each(ncells, [=] GDR_HD(long long c) {
    for (int i = sb[c]; i < sb[c + 1] && !*bad; ++i) {
      const int s = ic[i];
      for (int j = i + 1; j < sb[c + 1]; ++j) {
        const int t = ic[j];
        if (checks::conflict(P, S[2 * s], S[2 * s + 1], S[2 * t], S[2 * t + 1])) *bad = 1;
      }
      for (int k = pb[c]; k < pb[c + 1]; ++k) {
        const double* p = P + 2 * pc[k];
        const double *a = P + 2 * S[2 * s], *b = P + 2 * S[2 * s + 1];
        if (pred::orient2d(a, b, p) == 0 && checks::strictly_between(a, b, p)) *bad = 1;
      }
    }
  });
  return !found.get(0);
}

}  // namespace gdr::r2d
