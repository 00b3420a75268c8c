// The parallel CDT's host side (cdt_engine.h does the rest on the device or the CPU
// threads), and the conversion of any CDT's triangles into the engine's HostMesh, shared
// with the CGAL path.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "predicates/predicates.h"
#include "common/trace.h"
#include "refine2d/cdt_engine.h"
#include "refine2d/engine_dispatch.h"
#include "refine2d/input.h"

namespace gdr::r2d {

std::vector<int> hull_segments(const double* xy, std::vector<int> c) {
  // Andrew's monotone chain over the candidates, keeping collinear points as vertices: a
  // hull edge through a point would be a segment through a vertex.
  auto P = [&](int v) { return xy + 2 * v; };
  std::sort(c.begin(), c.end(), [&](int a, int b) {
    return P(a)[0] < P(b)[0] || (P(a)[0] == P(b)[0] && P(a)[1] < P(b)[1]);
  });
  std::vector<int> h;
  for (int pass = 0; pass < 2; ++pass) {
    const std::size_t floor = h.size();
    for (std::size_t k = 0; k < c.size(); ++k) {
      const int v = pass == 0 ? c[k] : c[c.size() - 1 - k];
      while (h.size() >= floor + 2 && pred::orient2d(P(h[h.size() - 2]), P(h.back()), P(v)) < 0)
        h.pop_back();
      h.push_back(v);
    }
    h.pop_back();  // the last point starts the other chain
  }
  std::vector<int> segs;
  for (std::size_t i = 0; i < h.size(); ++i) {
    segs.push_back(h[i]);
    segs.push_back(h[(i + 1) % h.size()]);
  }
  return segs;
}

namespace {

// The triangle holding p (its boundary counts): a walk with a rotating first edge, then a
// scan of all triangles if the walk is long (a constrained triangulation can trap walks).
// -1 if none holds it.
int locate(const exec::HostVector<int>& tv, const exec::HostVector<int>& tn, const double* xy, const Point2& q) {
  const double p[2] = {q.x, q.y};
  const int nt = static_cast<int>(tv.size() / 3);
  auto inside = [&](int t, int& exit, int step) {
    exit = -1;
    for (int i0 = 0; i0 < 3; ++i0) {
      const int i = (i0 + step) % 3;
      if (pred::orient2d(xy + 2 * tv[3 * t + (i + 1) % 3], xy + 2 * tv[3 * t + (i + 2) % 3], p) < 0) {
        exit = i;
        return false;
      }
    }
    return true;
  };
  int t = 0, exit = -1;
  for (int step = 0; nt > 0 && step < 100000; ++step) {
    if (inside(t, exit, step)) return t;
    const int nb = tn[3 * t + exit];
    if (nb < 0) break;
    t = nb / 3;
  }
  for (t = 0; t < nt; ++t)
    if (inside(t, exit, 0)) return t;
  return -1;
}

}  // namespace

// With the convex hull kept (-c), points that lie within rounding of a hull edge, but not on
// it, leave slivers between the edge and them that no angle bound can mesh: a map turned by
// a few degrees, whose straight border points were rounded off their line (by 1e-17 to 1e-15
// of the edge's length there; up to 1e-11 where coordinates are large next to the edges),
// was refused for asking 1e12-1e15 Steiner points, and Triangle 1.6 ran out of 16 GB on it.
// A boundary triangle on a hull edge whose apex lies within kHullSliver of the edge's length
// from it (an angle below 1e-9 radians, which no refinement could mend) is left out, so the
// apex joins the boundary (the domain loses that sliver), and so on for the triangles that
// come to the boundary. Points rounded just outside the line become hull vertices instead,
// and the flat triangles between them stay (README, Known limits).
void peel_hull_slivers(const CleanPslg& g, const CdtTriangles& c, std::vector<char>& outside) {
  const int ninput = static_cast<int>(g.segments.size());
  const int nt = static_cast<int>(c.tv.size() / 3);
  const int n = static_cast<int>(g.points.size());
  auto boundary_hull_edge = [&](int t, int i) {
    const int nb = c.tn[3 * t + i], s = c.tseg[3 * t + i];
    return (nb < 0 || outside[nb / 3]) && (s < 0 || s >= ninput);
  };
  auto sliver = [&](int t) {
    for (int i = 0; i < 3; ++i) {
      if (!boundary_hull_edge(t, i)) continue;
      const int v = c.tv[3 * t + i], p = c.tv[3 * t + (i + 1) % 3], q = c.tv[3 * t + (i + 2) % 3];
      if (v >= n || p >= n || q >= n) continue;  // the parallel CDT's bounding triangle
      const Point2 &P = g.points[p], &Q = g.points[q], &V = g.points[v];
      const double ux = Q.x - P.x, uy = Q.y - P.y, wx = V.x - P.x, wy = V.y - P.y;
      const double len2 = ux * ux + uy * uy, along = ux * wx + uy * wy;
      if (std::fabs(ux * wy - uy * wx) <= kHullSliver * len2 && along > 0 && along < len2) return true;
    }
    return false;
  };
  // Never at the cost of an input segment or point: each input segment keeps a triangle on
  // one side and each point one triangle (collinear points with one just off their line, whose
  // slivers run between input segments, kept them only so).
  std::vector<int> kept_at;  // per point: kept triangles
  auto keeps_input = [&](int t) {
    for (int i = 0; i < 3; ++i) {
      if (kept_at[c.tv[3 * t + i]] <= 1) return false;
      const int s = c.tseg[3 * t + i], nb = c.tn[3 * t + i];
      if (s >= 0 && s < ninput && (nb < 0 || outside[nb / 3])) return false;
    }
    return true;
  };
  std::vector<int> stack;
  for (int t = 0; t < nt; ++t)
    if (!outside[t] && sliver(t)) stack.push_back(t);
  if (stack.empty()) return;
  kept_at.assign(n + 3, 0);
  for (int t = 0; t < nt; ++t)
    if (!outside[t])
      for (int i = 0; i < 3; ++i) ++kept_at[c.tv[3 * t + i]];
  while (!stack.empty()) {
    const int t = stack.back();
    stack.pop_back();
    if (outside[t] || !sliver(t) || !keeps_input(t)) continue;
    outside[t] = 1;
    for (int i = 0; i < 3; ++i) --kept_at[c.tv[3 * t + i]];
    for (int i = 0; i < 3; ++i)
      if (c.tn[3 * t + i] >= 0 && !outside[c.tn[3 * t + i] / 3]) stack.push_back(c.tn[3 * t + i] / 3);
  }
}

void throw_empty_domain() {
  throw Error(Status::InvalidInput,
              "no triangles are left after removing the exterior and the holes (are the "
              "boundary segments closed, and are the hole points inside them?)");
}

HostMesh assemble_cdt(const CleanPslg& g, CdtTriangles c) {
  const int n = static_cast<int>(g.points.size());
  const int nt_all = static_cast<int>(c.tv.size() / 3);
  const int ninput = static_cast<int>(g.segments.size());
  TraceSteps step("CDT assembly");
  // Outside: flood from the seeds without crossing a segment.
  std::vector<char> outside(nt_all, 0);
  std::vector<int> stack = c.exterior_seeds;
  for (int t : c.hole_tris)
    if (t >= 0) stack.push_back(t);
  while (!stack.empty()) {
    const int t = stack.back();
    stack.pop_back();
    if (outside[t]) continue;
    outside[t] = 1;
    for (int i = 0; i < 3; ++i)
      if (c.tseg[3 * t + i] < 0 && c.tn[3 * t + i] >= 0 && !outside[c.tn[3 * t + i] / 3])
        stack.push_back(c.tn[3 * t + i] / 3);
  }
  step("exterior flood");
  peel_hull_slivers(g, c, outside);
  step("hull slivers");
  // Kept triangles numbered in order (a scan), then copied and relinked in parallel.
  std::vector<int> id(nt_all, -1);
  int nt = 0;
  for (int t = 0; t < nt_all; ++t)
    if (!outside[t]) id[t] = nt++;
  if (nt == 0) throw_empty_domain();

  step("numbering");
  HostMesh m;
  m.xy.resize(2 * std::size_t(n));
  m.ptype.resize(n);
  m.pseg.resize(n);
  m.seg.resize(2 * std::size_t(ninput));
  m.tv.resize(3 * std::size_t(nt));
  m.tn.resize(3 * std::size_t(nt));
  m.ts.resize(3 * std::size_t(nt));
  m.input_segments = ninput;
#pragma omp parallel
  {
#pragma omp for nowait
    for (int i = 0; i < n; ++i) {
      m.xy[2 * i] = g.points[i].x;
      m.xy[2 * i + 1] = g.points[i].y;
      m.ptype[i] = kInputPoint;
      m.pseg[i] = -1;
    }
#pragma omp for nowait
    for (int k = 0; k < ninput; ++k) {
      m.seg[2 * k] = g.segments[k][0];
      m.seg[2 * k + 1] = g.segments[k][1];
    }
    // Segment of each edge: an input segment's number, -2 for a domain-boundary edge that is
    // none (numbered below), else -1.
#pragma omp for
    for (int t = 0; t < nt_all; ++t) {
      if (outside[t]) continue;
      const int u = id[t];
      for (int i = 0; i < 3; ++i) {
        m.tv[3 * u + i] = c.tv[3 * t + i];
        const int nb = c.tn[3 * t + i];
        m.tn[3 * u + i] = nb < 0 || outside[nb / 3] ? -1 : 3 * id[nb / 3] + nb % 3;
        const int s = c.tseg[3 * t + i];
        m.ts[3 * u + i] = s >= 0 && s < ninput ? s : (m.tn[3 * u + i] < 0 ? -2 : -1);
      }
    }
  }
  step("copy and relink");
  // Domain-boundary edges that are not input segments become hull segments, numbered after
  // the input's.
  for (int u = 0; u < nt; ++u)
    for (int i = 0; i < 3; ++i)
      if (m.ts[3 * u + i] == -2) {
        m.ts[3 * u + i] = static_cast<int>(m.seg.size() / 2);
        m.seg.insert(m.seg.end(), {m.tv[3 * u + (i + 1) % 3], m.tv[3 * u + (i + 2) % 3]});
      }
  step("hull segments");
  // Regions: from each seed in turn (a later seed wins, as in Triangle), every triangle
  // reachable without crossing a segment gets its number. Seeds outside the domain mark
  // nothing.
  if (!g.regions.empty()) {
    m.tregion.assign(nt, 0);
    std::vector<int> visited(nt, 0);
    for (std::size_t r = 0; r < g.regions.size() && r < c.region_tris.size(); ++r) {
      const int f = c.region_tris[r];
      if (f < 0 || outside[f]) continue;
      const int number = static_cast<int>(r) + 1;
      stack.assign(1, id[f]);
      while (!stack.empty()) {
        const int t = stack.back();
        stack.pop_back();
        if (visited[t] == number) continue;
        visited[t] = number;
        m.tregion[t] = number;
        for (int i = 0; i < 3; ++i)
          if (m.ts[3 * t + i] < 0 && m.tn[3 * t + i] >= 0) stack.push_back(m.tn[3 * t + i] / 3);
      }
    }
  }
  return m;
}

InitialCdt::InitialCdt() = default;
InitialCdt::InitialCdt(InitialCdt&&) noexcept = default;
InitialCdt::~InitialCdt() = default;

InitialCdt initial_cdt_parallel(const CleanPslg& g, bool remove_exterior, bool gpu, bool in_space,
                                std::vector<PhaseTime>* phases) {
  const int n = static_cast<int>(g.points.size());
  std::vector<double> xy(2 * std::size_t(n) + 6);
#pragma omp parallel for
  for (int i = 0; i < n; ++i) {
    xy[2 * i] = g.points[i].x;
    xy[2 * i + 1] = g.points[i].y;
  }
  // The bounding triangle: far beyond the scaled input (|x|, |y| < 2), so that few hull
  // edges are missing from the first triangulation; integers, so the predicates stay exact.
  const double M = std::ldexp(1.0, 40);
  const double corners[6] = {-M, -M, M, -M, 0, M};
  std::copy(corners, corners + 6, xy.begin() + 2 * std::size_t(n));
  std::vector<int> segments(2 * g.segments.size());
  const long long ns = static_cast<long long>(g.segments.size());
#pragma omp parallel for
  for (long long s = 0; s < ns; ++s) segments[2 * s] = g.segments[s][0], segments[2 * s + 1] = g.segments[s][1];
  std::vector<Point2> seeds = g.holes;
  for (const auto& rs : g.regions) seeds.push_back(rs.point);
  const int holes = static_cast<int>(g.holes.size());
  ParallelCdtResult r;
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
#if defined(GDR_HAVE_CUDA)
  if (gpu) r = parallel_cdt_cuda(xy, segments, !remove_exterior, in_space, seeds, holes);
  else
#endif
  {
    (void)gpu;
    r = parallel_cdt_cpu(xy, segments, !remove_exterior, in_space, seeds, holes);
  }
  // Beside the device phases: the whole device call (set-up, transfers and memory handed
  // back included) and the domain's assembly on the host.
  const auto t1 = Clock::now();
  r.phases.push_back({"whole device call", std::chrono::duration<double>(t1 - t0).count()});
  InitialCdt out;
  out.prepared = std::move(r.prepared);
  if (!out.prepared) {
    CdtTriangles c;
    c.tv = std::move(r.raw.tv);
    c.tn = std::move(r.raw.tn);
    c.tseg = std::move(r.raw.tseg);
    // Outside from the start: every triangle at the bounding triangle (the hull segments, or
    // with the exterior removed the input's, stop the flood).
    const int nt = static_cast<int>(c.tv.size() / 3);
    for (int t = 0; t < nt; ++t)
      if (c.tv[3 * t] >= n || c.tv[3 * t + 1] >= n || c.tv[3 * t + 2] >= n) c.exterior_seeds.push_back(t);
    for (const Point2& h : g.holes) c.hole_tris.push_back(locate(c.tv, c.tn, xy.data(), h));
    for (const auto& rs : g.regions) c.region_tris.push_back(locate(c.tv, c.tn, xy.data(), rs.point));
    out.host = assemble_cdt(g, std::move(c));
    r.phases.push_back({"assembly (host)", std::chrono::duration<double>(Clock::now() - t1).count()});
  }
  if (phases) *phases = std::move(r.phases);
  return out;
}

}  // namespace gdr::r2d
