// Conformity helpers shared by the 2D and 3D validators: finding input points in the mesh by
// exact coordinates, and following an input segment along the mesh's subsegment chain.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

#include "gdr/pslg.h"
#include "validate/incidence.h"

namespace gdr::validate {

inline std::array<double, 3> xyz(const Point2& p) { return {p.x, p.y, 0.0}; }
inline std::array<double, 3> xyz(const Point3& p) { return {p.x, p.y, p.z}; }

struct CoordKey {
  std::array<double, 3> c;
  bool operator==(const CoordKey& o) const { return c == o.c; }
};
struct CoordHash {
  std::size_t operator()(const CoordKey& k) const {
    std::uint64_t h = 0x243F6A8885A308D3ull;
    for (double v : k.c) {
      const double z = v + 0.0;  // -0 and +0 are the same coordinate
      std::uint64_t b;
      std::memcpy(&b, &z, sizeof b);
      h = (h ^ b) * 0x9E3779B97F4A7C15ull;
      h ^= h >> 31;
    }
    return static_cast<std::size_t>(h);
  }
};

// For every input point, the mesh vertex with exactly its coordinates (-1 if none). Input
// duplicates share one representative; `representative[i]` is its index.
template <class P, class A, class B>
std::vector<int> locate_input_points(const std::vector<P, A>& input, const std::vector<P, B>& mesh,
                                     std::vector<int>& representative) {
  std::unordered_map<CoordKey, int, CoordHash> index;
  index.reserve(input.size());
  representative.resize(input.size());
  for (std::size_t i = 0; i < input.size(); ++i)
    representative[i] = index.emplace(CoordKey{xyz(input[i])}, static_cast<int>(i)).first->second;
  std::vector<int> found(input.size(), -1);
  const std::int64_t n = static_cast<std::int64_t>(mesh.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t v = 0; v < n; ++v) {
    const auto it = index.find(CoordKey{xyz(mesh[v])});
    if (it == index.end()) continue;
    // The smallest mesh vertex wins, so the result does not depend on the thread schedule.
    int* slot = &found[it->second];
    int old = __atomic_load_n(slot, __ATOMIC_RELAXED);
    while ((old < 0 || old > v) &&
           !__atomic_compare_exchange_n(slot, &old, static_cast<int>(v), true, __ATOMIC_RELAXED,
                                        __ATOMIC_RELAXED)) {
    }
  }
  return found;
}

// Vertex -> subsegment neighbours (CSR).
struct SubsegmentGraph {
  std::vector<std::size_t> start;
  std::vector<int> next;
  template <class A>
  SubsegmentGraph(std::size_t vertices, const std::vector<std::array<int, 2>, A>& subsegments)
      : start(vertices + 1, 0) {
    auto ok = [&](const std::array<int, 2>& s) {
      return s[0] >= 0 && s[1] >= 0 && static_cast<std::size_t>(s[0]) < vertices &&
             static_cast<std::size_t>(s[1]) < vertices && s[0] != s[1];
    };
    for (const auto& s : subsegments)
      if (ok(s)) ++start[s[0] + 1], ++start[s[1] + 1];
    for (std::size_t v = 0; v < vertices; ++v) start[v + 1] += start[v];
    next.resize(start[vertices]);
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    for (const auto& s : subsegments)
      if (ok(s)) next[fill[s[0]]++] = s[1], next[fill[s[1]]++] = s[0];
  }
};

// The vertices, from a to b, of the path that the edges `chain` form; empty when they do not
// form exactly one simple path from a to b (a gap, a branch, a cycle, an edge elsewhere).
inline std::vector<int> chain_path(const std::vector<std::array<int, 2>>& chain, int a, int b) {
  std::vector<int> verts;
  for (const auto& e : chain) verts.push_back(e[0]), verts.push_back(e[1]);
  std::sort(verts.begin(), verts.end());
  verts.erase(std::unique(verts.begin(), verts.end()), verts.end());
  if (a == b || chain.empty() || verts.size() != chain.size() + 1 ||
      !std::binary_search(verts.begin(), verts.end(), a) ||
      !std::binary_search(verts.begin(), verts.end(), b))
    return {};
  const auto index = [&](int v) {
    return static_cast<std::size_t>(std::lower_bound(verts.begin(), verts.end(), v) - verts.begin());
  };
  std::vector<std::array<int, 2>> next(verts.size(), {-1, -1});
  for (const auto& e : chain)
    for (int k = 0; k < 2; ++k) {
      auto& n = next[index(e[k])];
      if (e[0] == e[1] || n[1] >= 0) return {};  // a loop edge, or a vertex on three edges
      n[n[0] >= 0 ? 1 : 0] = e[1 - k];
    }
  std::vector<int> path{a};
  for (int prev = -1, cur = a; cur != b;) {
    const auto& n = next[index(cur)];
    if ((cur == a) != (n[1] < 0) || path.size() > chain.size()) return {};  // ends on one edge
    const int to = n[0] != prev ? n[0] : n[1];
    prev = cur;
    cur = to;
    path.push_back(cur);
  }
  if (next[index(b)][1] >= 0) return {};
  return path;
}

// How far rounding alone can put a vertex off the segment or plane it was computed on: a
// few units in the last place of the largest coordinate. Near the origin that is far below
// any relative tolerance; for a part far from the origin (a scan in map coordinates, 1e5
// times its size away) the output's own coordinates are that coarse.
template <class P>
double coordinate_slack(const std::vector<P>& points) {
  double m = 0;
  for (const P& p : points)
    for (const double v : xyz(p))
      if (std::isfinite(v)) m = std::max(m, std::fabs(v));
  return m > 0 ? std::ldexp(64.0, std::ilogb(m) - 52) : 0.0;
}

// True when a chain of subsegments leads from mesh vertex a to b, every intermediate vertex
// within `tolerance * |ab| + slack` of segment ab and strictly progressing from a towards b.
// `slack`: the rounding of the coordinates themselves (coordinate_slack). Distances are taken
// on coordinates scaled by a power of two (exact) to about 1: at 1e95 and beyond the squares
// overflowed to infinity, and every vertex passed (a 2D star at 1e156 failed --check only
// when scaled down to 3e5). Where several subsegments qualify, the one nearest the line is
// followed first and the others are tried if it leads nowhere: at 6e11, a hull subsegment
// 0.4 off the segment but within its tolerance was taken for the segment's next piece.
template <class P, class A>
bool follow_segment(const std::vector<P, A>& points, const SubsegmentGraph& graph, int a, int b,
                    double tolerance, double slack = 0) {
  const auto qa = xyz(points[a]), qb = xyz(points[b]);
  double m = 0;
  for (int i = 0; i < 3; ++i) m = std::max({m, std::fabs(qa[i]), std::fabs(qb[i])});
  const int k = m > 0 && std::isfinite(m) ? -std::ilogb(m) : 0;
  const auto scaled = [k](std::array<double, 3> q) {
    for (double& v : q) v = std::ldexp(v, k);
    return q;
  };
  const auto pa = scaled(qa), pb = scaled(qb);
  slack = std::ldexp(slack, k);
  const double d[3] = {pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]};
  const double len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
  const double allowed = tolerance * len2 + slack * std::sqrt(len2);
  // Depth first, progress strictly increasing (so no cycles); the budget, twice the
  // subsegment ends (a chain takes one step per vertex), bounds pathological branching.
  struct Step {
    int v;
    double t;
  };
  // Scratch kept per thread: the validators call this for every segment, in parallel.
  thread_local std::vector<Step> stack;
  thread_local std::vector<std::pair<double, Step>> next;  // (distance squared, step)
  stack.assign(1, Step{a, 0.0});
  for (std::size_t budget = 2 * graph.next.size() + 64; !stack.empty() && budget > 0; --budget) {
    const Step cur = stack.back();
    stack.pop_back();
    next.clear();
    for (std::size_t j = graph.start[cur.v]; j < graph.start[cur.v + 1]; ++j) {
      const int w = graph.next[j];
      if (w == b) return true;
      const auto pw = scaled(xyz(points[w]));
      const double r[3] = {pw[0] - pa[0], pw[1] - pa[1], pw[2] - pa[2]};
      const double t = (r[0] * d[0] + r[1] * d[1] + r[2] * d[2]) / len2;
      if (!(t > cur.t && t < 1)) continue;
      const double cx = r[1] * d[2] - r[2] * d[1], cy = r[2] * d[0] - r[0] * d[2],
                   cz = r[0] * d[1] - r[1] * d[0];
      // |r x d| / |d| is the distance from the line; compare squares to avoid roots.
      const double off2 = cx * cx + cy * cy + cz * cz;
      if (off2 > allowed * allowed) continue;
      next.push_back({off2, Step{w, t}});
    }
    // The nearest to the line last, so that it is popped first.
    std::sort(next.begin(), next.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
    for (const auto& n : next) stack.push_back(n.second);
  }
  return false;
}

}  // namespace gdr::validate
