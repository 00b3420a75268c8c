// Self-intersection search: triangles binned by their boxes into a uniform grid (one
// counted array), each candidate pair tested once, in the first grid cell both boxes share,
// with the exact test of geometry.h. Cells are processed in parallel.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "cdt3d/geometry.h"
#include "cdt3d/internal.h"

namespace gdr::cdt3d {
namespace {

struct Box {
  double lo[3], hi[3];
};

struct Grid {
  double origin[3] = {0, 0, 0};
  double cell = 1;
  long long n[3] = {1, 1, 1};
  long long cell_of(double v, int axis) const {
    const long long c = static_cast<long long>(std::floor((v - origin[axis]) / cell));
    return std::clamp<long long>(c, 0, n[axis] - 1);
  }
  long long cells() const { return n[0] * n[1] * n[2]; }
};

// Squared distance from p to triangle abc (floating point: a measure, not a predicate).
double point_triangle_dist2(const double* p, const double* a, const double* b, const double* c) {
  double ab[3], ac[3], ap[3];
  for (int d = 0; d < 3; ++d) ab[d] = b[d] - a[d], ac[d] = c[d] - a[d], ap[d] = p[d] - a[d];
  auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  const double d00 = dot(ab, ab), d01 = dot(ab, ac), d11 = dot(ac, ac), d20 = dot(ap, ab), d21 = dot(ap, ac);
  const double den = d00 * d11 - d01 * d01;
  if (den > 0) {
    const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
    if (v >= 0 && w >= 0 && v + w <= 1) {
      double q[3];
      for (int d = 0; d < 3; ++d) q[d] = a[d] + v * ab[d] + w * ac[d] - p[d];
      return dot(q, q);
    }
  }
  // Else the nearest point lies on an edge.
  double best = HUGE_VAL;
  const double* corner[3] = {a, b, c};
  for (int e = 0; e < 3; ++e) {
    const double *u = corner[e], *v = corner[(e + 1) % 3];
    double uv[3], up[3];
    for (int d = 0; d < 3; ++d) uv[d] = v[d] - u[d], up[d] = p[d] - u[d];
    const double len2 = dot(uv, uv);
    const double t = len2 > 0 ? std::clamp(dot(up, uv) / len2, 0.0, 1.0) : 0.0;
    double q[3];
    for (int d = 0; d < 3; ++d) q[d] = u[d] + t * uv[d] - p[d];
    best = std::min(best, dot(q, q));
  }
  return best;
}

// Squared distance between segments pq and rs.
double segment_dist2(const double* p, const double* q, const double* r, const double* s) {
  auto dot = [](const double* u, const double* v) { return u[0] * v[0] + u[1] * v[1] + u[2] * v[2]; };
  double d1[3], d2[3], w[3];
  for (int d = 0; d < 3; ++d) d1[d] = q[d] - p[d], d2[d] = s[d] - r[d], w[d] = p[d] - r[d];
  const double a = dot(d1, d1), e = dot(d2, d2), f = dot(d2, w), c = dot(d1, w), b = dot(d1, d2);
  const double den = a * e - b * b;
  double t1 = den > 0 ? std::clamp((b * f - c * e) / den, 0.0, 1.0) : 0.0;
  double t2 = e > 0 ? (b * t1 + f) / e : 0.0;
  if (t2 < 0 || t2 > 1) {
    t2 = std::clamp(t2, 0.0, 1.0);
    t1 = a > 0 ? std::clamp((b * t2 - c) / a, 0.0, 1.0) : 0.0;
  }
  double x[3];
  for (int d = 0; d < 3; ++d) x[d] = p[d] + t1 * d1[d] - r[d] - t2 * d2[d];
  return dot(x, x);
}

// Whether triangles t1 and t2, sharing no vertex, come within `gap` of each other.
bool triangles_within(const std::vector<Point3>& pts, const std::array<int, 3>& t1, const std::array<int, 3>& t2,
                      double gap) {
  for (int a : t1)
    for (int b : t2)
      if (a == b) return false;  // neighbours: their distance is 0 by design
  const double g2 = gap * gap;
  auto at = [&](int v) { return geom::xyz(pts[v]); };
  for (int k = 0; k < 3; ++k) {
    if (point_triangle_dist2(at(t1[k]), at(t2[0]), at(t2[1]), at(t2[2])) < g2) return true;
    if (point_triangle_dist2(at(t2[k]), at(t1[0]), at(t1[1]), at(t1[2])) < g2) return true;
    for (int m = 0; m < 3; ++m)
      if (segment_dist2(at(t1[k]), at(t1[(k + 1) % 3]), at(t2[m]), at(t2[(m + 1) % 3])) < g2) return true;
  }
  return false;
}

long long find_triangle_pairs(const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& triangles,
                              double gap, std::size_t max_pairs, std::vector<std::array<int, 2>>& pairs) {
  pairs.clear();
  const long long nt = static_cast<long long>(triangles.size());
  if (nt < 2) return 0;
  std::vector<Box> box(nt);
  Box all{{HUGE_VAL, HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
  double extent_sum = 0;
  for (long long t = 0; t < nt; ++t) {
    Box& b = box[t];
    for (int d = 0; d < 3; ++d) {
      b.lo[d] = HUGE_VAL;
      b.hi[d] = -HUGE_VAL;
    }
    for (int k = 0; k < 3; ++k) {
      const double* p = geom::xyz(points[triangles[t][k]]);
      for (int d = 0; d < 3; ++d) {
        b.lo[d] = std::min(b.lo[d], p[d] - gap);
        b.hi[d] = std::max(b.hi[d], p[d] + gap);
      }
    }
    double e = 0;
    for (int d = 0; d < 3; ++d) {
      all.lo[d] = std::min(all.lo[d], b.lo[d]);
      all.hi[d] = std::max(all.hi[d], b.hi[d]);
      e = std::max(e, b.hi[d] - b.lo[d]);
    }
    extent_sum += e;
  }

  // Cells about the size of an average triangle, but at most ~2 cells per triangle and a
  // bounded number of (triangle, cell) entries: long thin triangles would otherwise fill
  // many cells.
  Grid grid;
  double span = 0;
  for (int d = 0; d < 3; ++d) {
    grid.origin[d] = all.lo[d];
    span = std::max(span, all.hi[d] - all.lo[d]);
  }
  grid.cell = std::max(extent_sum / nt, span * 1e-9);
  if (!(grid.cell > 0)) grid.cell = 1;
  std::vector<long long> entry_start;
  for (;;) {
    for (int d = 0; d < 3; ++d)
      grid.n[d] = std::max<long long>(1, static_cast<long long>((all.hi[d] - all.lo[d]) / grid.cell) + 1);
    if (grid.cells() > 2 * nt + 64) {
      grid.cell *= std::cbrt(static_cast<double>(grid.cells()) / (2 * nt + 64)) * 1.01;
      continue;
    }
    long long entries = 0;
    for (long long t = 0; t < nt; ++t) {
      long long c = 1;
      for (int d = 0; d < 3; ++d) c *= grid.cell_of(box[t].hi[d], d) - grid.cell_of(box[t].lo[d], d) + 1;
      entries += c;
    }
    if (entries > 16 * nt + 1024) {
      grid.cell *= 1.5;
      continue;
    }
    break;
  }

  // Each triangle's cell range, then a counted array: cell -> triangles, in increasing
  // order within a cell.
  const long long ncells = grid.cells();
  std::vector<std::array<int, 6>> range(nt);  // lo x, y, z, hi x, y, z
#pragma omp parallel for schedule(static) if (nt > 20000)
  for (long long t = 0; t < nt; ++t)
    for (int d = 0; d < 3; ++d) {
      range[t][d] = static_cast<int>(grid.cell_of(box[t].lo[d], d));
      range[t][3 + d] = static_cast<int>(grid.cell_of(box[t].hi[d], d));
    }
  std::vector<int> count(ncells + 1, 0);
  auto for_cells = [&](long long t, auto&& f) {
    const auto& r = range[t];
    for (long long x = r[0]; x <= r[3]; ++x)
      for (long long y = r[1]; y <= r[4]; ++y)
        for (long long z = r[2]; z <= r[5]; ++z) f((x * grid.n[1] + y) * grid.n[2] + z);
  };
  for (long long t = 0; t < nt; ++t) for_cells(t, [&](long long c) { ++count[c + 1]; });
  for (long long c = 0; c < ncells; ++c) count[c + 1] += count[c];
  std::vector<int> items(count[ncells]);
  {
    std::vector<int> fill(count.begin(), count.end() - 1);
    for (long long t = 0; t < nt; ++t)
      for_cells(t, [&](long long c) { items[fill[c]++] = static_cast<int>(t); });
  }

  auto overlap = [&](int i, int j) {
    for (int d = 0; d < 3; ++d)
      if (box[i].hi[d] < box[j].lo[d] || box[j].hi[d] < box[i].lo[d]) return false;
    return true;
  };
  // The pair is tested in the lowest cell both boxes cover.
  auto first_common_cell = [&](int i, int j) {
    const long long x = std::max(range[i][0], range[j][0]), y = std::max(range[i][1], range[j][1]),
                    z = std::max(range[i][2], range[j][2]);
    return (x * grid.n[1] + y) * grid.n[2] + z;
  };

  const std::size_t keep = std::max<std::size_t>(max_pairs, 1) * 64;  // per thread, before sorting
  long long total = 0;
#pragma omp parallel if (nt > 5000)  // small inputs: thread start-up costs more
  {
    std::vector<std::array<int, 2>> mine;
    long long found = 0;
#pragma omp for schedule(dynamic, 256) nowait
    for (long long c = 0; c < ncells; ++c) {
      for (int a = count[c]; a < count[c + 1]; ++a) {
        const int i = items[a];
        for (int b = a + 1; b < count[c + 1]; ++b) {
          const int j = items[b];
          if (!overlap(i, j) || first_common_cell(i, j) != c) continue;
          if (gap > 0 ? !triangles_within(points, triangles[i], triangles[j], gap)
                      : !geom::triangles_clash(points, triangles[i], triangles[j]))
            continue;
          ++found;
          if (mine.size() < keep) mine.push_back({i, j});
        }
      }
    }
#pragma omp critical
    {
      total += found;
      pairs.insert(pairs.end(), mine.begin(), mine.end());
    }
  }
  std::sort(pairs.begin(), pairs.end());
  if (pairs.size() > max_pairs) pairs.resize(max_pairs);
  return total;
}

}  // namespace

long long find_clashing_triangles(const std::vector<Point3>& points,
                                  const std::vector<std::array<int, 3>>& triangles,
                                  std::size_t max_pairs, std::vector<std::array<int, 2>>& pairs) {
  return find_triangle_pairs(points, triangles, 0, max_pairs, pairs);
}

long long find_close_triangles(const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& triangles,
                               double gap, std::size_t max_pairs, std::vector<std::array<int, 2>>& pairs) {
  return find_triangle_pairs(points, triangles, gap, max_pairs, pairs);
}

EdgeTable build_edges(const std::vector<std::array<int, 3>>& triangles) {
  // Bucket every edge (a < b) by a, then sort each small bucket by (b, triangle): linear
  // work instead of one big sort. In parallel: the buckets filled by atomic counters (their
  // order is then fixed by the sort), the table from per-bucket counts of distinct edges.
  const long long nt = static_cast<long long>(triangles.size());
  const bool parallel = nt > 20000;
  int nv = 0;
#pragma omp parallel for reduction(max : nv) schedule(static) if (parallel)
  for (long long t = 0; t < nt; ++t) nv = std::max({nv, triangles[t][0] + 1, triangles[t][1] + 1, triangles[t][2] + 1});
  std::vector<int> start(nv + 1, 0);
#pragma omp parallel for schedule(static) if (parallel)
  for (long long t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) {
#pragma omp atomic
      ++start[std::min(triangles[t][k], triangles[t][(k + 1) % 3]) + 1];
    }
  for (int v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<std::pair<int, int>> slot(3 * nt);  // (b, triangle) in a's bucket
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
#pragma omp parallel for schedule(static) if (parallel)
    for (long long t = 0; t < nt; ++t)
      for (int k = 0; k < 3; ++k) {
        const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
        int at;
#pragma omp atomic capture
        at = fill[std::min(a, b)]++;
        slot[at] = {std::max(a, b), static_cast<int>(t)};
      }
  }
  std::vector<int> distinct(nv + 1, 0);  // per bucket: its distinct edges, then their offsets
#pragma omp parallel for schedule(dynamic, 1024) if (parallel)
  for (int v = 0; v < nv; ++v) {
    std::sort(slot.begin() + start[v], slot.begin() + start[v + 1]);
    for (int i = start[v]; i < start[v + 1]; ++i) distinct[v + 1] += i == start[v] || slot[i].first != slot[i - 1].first;
  }
  for (int v = 0; v < nv; ++v) distinct[v + 1] += distinct[v];
  EdgeTable table;
  table.tri.resize(slot.size());
  table.edge.resize(distinct[nv]);
  table.start.resize(distinct[nv] + 1);
#pragma omp parallel for schedule(dynamic, 1024) if (parallel)
  for (int a = 0; a < nv; ++a) {
    int k = distinct[a];
    for (int i = start[a]; i < start[a + 1]; ++i) {
      if (i == start[a] || slot[i].first != slot[i - 1].first) {
        table.start[k] = i;
        table.edge[k++] = {a, slot[i].first};
      }
      table.tri[i] = slot[i].second;
    }
  }
  table.start[distinct[nv]] = static_cast<int>(slot.size());
  return table;
}

}  // namespace gdr::cdt3d
