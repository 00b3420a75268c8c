// Segments split before the CDT where two of them would wait on each other (cdt3d.h,
// split_mutually_encroaching_segments).
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#include "cdt3d/cdt3d.h"
#include "cdt3d/internal.h"
#include "predicates/predicates.h"

namespace gdr::cdt3d {
namespace {

Point3 midpoint(const Point3& a, const Point3& b) {
  return {0.5 * (a.x + b.x), 0.5 * (a.y + b.y), 0.5 * (a.z + b.z)};
}

// The triangles at each edge, by edge_key.
using EdgeTriangles = std::unordered_multimap<std::uint64_t, int>;

// The unit normal of triangle t (its corners' order).
Point3 unit_normal(const Plc& plc, int t) {
  const auto& q = plc.triangles[t];
  const Point3 &a = plc.points[q[0]], &b = plc.points[q[1]], &c = plc.points[q[2]];
  const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
  const Point3 n{uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
  const double l = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
  return {n.x / l, n.y / l, n.z / l};
}

// Does segment b bound a facet that segment a bounds too, turning at b into a facet whose
// plane has a's midpoint strictly outside the domain, at a bend of less than kBend degrees
// (the next face of a polygonal bore)? Then the point splitting a sees that facet's
// subfaces from behind through the material along the shared facet, and each split waits
// for the other. Across a gap (two blocks' facing walls) the material does not join them
// there; at a square step (thingi10k_288351) refinement resolves them, and splitting them
// first only added 11% more tetrahedra.
constexpr double kBend = 60;

bool waits_across_a_bend(const Plc& plc, const EdgeTriangles& by_edge, int a, int b, const Point3& mid_a) {
  const auto tris = [&](int g) {
    std::vector<int> t;
    const auto r = by_edge.equal_range(edge_key(plc.segments[g][0], plc.segments[g][1]));
    for (auto it = r.first; it != r.second; ++it) t.push_back(it->second);
    return t;
  };
  const std::vector<int> ta = tris(a), tb = tris(b);
  const auto facet_of_a = [&](int y) {
    for (const int x : ta)
      if (plc.triangle_facet[x] == plc.triangle_facet[y]) return true;
    return false;
  };
  const double m[3] = {mid_a.x, mid_a.y, mid_a.z};
  const double cos_bend = std::cos(kBend * 3.14159265358979323846 / 180.0);
  for (const int shared : tb) {
    if (!facet_of_a(shared)) continue;
    const Point3 ns = unit_normal(plc, shared);
    for (const int y : tb) {
      if (facet_of_a(y)) continue;
      const bool front_in = plc.cell_in_domain[plc.triangle_cell[y][0]] != 0;
      const bool back_in = plc.cell_in_domain[plc.triangle_cell[y][1]] != 0;
      if (front_in == back_in) continue;  // an internal facet, or none
      const Point3 ny = unit_normal(plc, y);
      if (std::fabs(ns.x * ny.x + ns.y * ny.y + ns.z * ny.z) < cos_bend) continue;
      const auto& r = plc.triangles[y];
      const Point3 &p0 = plc.points[r[0]], &p1 = plc.points[r[1]], &p2 = plc.points[r[2]];
      const double q0[3] = {p0.x, p0.y, p0.z}, q1[3] = {p1.x, p1.y, p1.z}, q2[3] = {p2.x, p2.y, p2.z};
      const double o = pred::orient3d(q0, q1, q2, m);  // < 0: the front side
      if (front_in ? o > 0 : o < 0) return true;
    }
  }
  return false;
}

// Pairs of segments (not nearly flat, sharing no endpoint) each of whose midpoints lies in
// the other's diametral sphere. Their midpoints are then less than half the shorter one's
// length apart: segments are bucketed by length in powers of two, each level's midpoints in
// a grid of cells twice as large as its shortest length (a sorted array of cell keys), and
// each segment looks for partners at least as long as itself in the 8 cells its ball of
// half its length can reach, level by level. With `changed` (the rounds after the first), only pairs with a
// changed segment can be new: those segments alone look, for partners of any length. Pairs
// come sorted, each once, its shorter segment first.
std::vector<std::array<int, 2>> mutually_encroaching(const Plc& plc, const std::vector<char>* changed = nullptr) {
  const std::size_t ns = plc.segments.size();
  std::vector<std::array<int, 2>> pairs;
  // Nearly flat segments are left out: on the boat (a surface of nearly flat triangles) they
  // added 900 points and 5-7% more tetrahedra; a 48-sector bore (7.5-degree bends) stays with
  // the engine's blocking (its bad volume fell from 1-3% to 0 with them, at 17-28% more
  // tetrahedra than without, TetGen's count).
  const auto skip = [&](std::size_t g) { return plc.segment_flat[g] != 0; };
  std::vector<int> level(ns, 0);
  std::vector<Point3> mid(ns);
  std::vector<double> len(ns);
  int lo = 1 << 20, hi = -(1 << 20);
  for (std::size_t g = 0; g < ns; ++g) {
    const Point3 &a = plc.points[plc.segments[g][0]], &b = plc.points[plc.segments[g][1]];
    mid[g] = midpoint(a, b);
    len[g] = std::sqrt((a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y) + (a.z - b.z) * (a.z - b.z));
    int e = 0;
    std::frexp(len[g], &e);  // len in [2^(e-1), 2^e)
    level[g] = e - 1;
    if (!skip(g)) lo = std::min(lo, level[g]), hi = std::max(hi, level[g]);
  }
  if (lo > hi) return pairs;
  // Level l's cells are 2^(l+1) wide: a ball of radius below 2^l around a point reaches
  // only the cell the point lies in and, along each axis, the neighbour on the side of the
  // cell's half it lies in.
  const auto cell_at = [](double v, int l) { return std::floor(v / std::ldexp(1.0, l + 1)); };
  const auto key_of = [](double x, double y, double z) {
    const auto q = [](double v) { return static_cast<std::uint64_t>(static_cast<std::int64_t>(v) & 0x1fffff); };
    return (q(x) << 42) | (q(y) << 21) | q(z);
  };
  const auto key_at = [&](const Point3& p, int l) { return key_of(cell_at(p.x, l), cell_at(p.y, l), cell_at(p.z, l)); };
  // Per level, (cell key, segment) sorted: built by one sort (a hash table of 2.2M
  // segments took 1.2-1.4 s to build, and its lookups waited on memory).
  std::vector<std::vector<std::pair<std::uint64_t, int>>> grid(hi - lo + 1);
  for (std::size_t g = 0; g < ns; ++g)
    if (!skip(g)) grid[level[g] - lo].push_back({key_at(mid[g], level[g]), static_cast<int>(g)});
  for (auto& cells : grid) std::sort(cells.begin(), cells.end());
  // Who looks: every segment, in the order of its cell (neighbours then look up the same
  // cells, in cache), or the changed ones.
  std::vector<int> who;
  if (changed) {
    for (std::size_t g = 0; g < ns; ++g)
      if ((*changed)[g] && !skip(g)) who.push_back(static_cast<int>(g));
  } else {
    for (const auto& cells : grid)
      for (const auto& [k, g] : cells) who.push_back(g);
  }
  const auto xyz = [](const Point3& p) { return std::array<double, 3>{p.x, p.y, p.z}; };
  const auto shorter = [&](int a, int b) { return len[a] < len[b] || (len[a] == len[b] && a < b); };
  const long long n = static_cast<long long>(who.size());
#pragma omp parallel
  {
    std::vector<std::array<int, 2>> mine;
#pragma omp for schedule(dynamic, 4096) nowait
    for (long long i = 0; i < n; ++i) {
      const int a = who[i];
      const int a0 = plc.segments[a][0], a1 = plc.segments[a][1];
      const auto pa0 = xyz(plc.points[a0]), pa1 = xyz(plc.points[a1]), ma = xyz(mid[a]);
      // Partners lie at a's level or above (at any level for a changed segment); a rounded
      // distance well beyond half the shorter length (the midpoints are rounded, by up to an
      // ulp of the coordinates) rules one out before the exact tests.
      const double big = std::max({std::fabs(ma[0]), std::fabs(ma[1]), std::fabs(ma[2]), len[a]});
      for (int l = changed ? lo : level[a]; l <= hi; ++l) {
        const auto& cells = grid[l - lo];
        const double h = std::ldexp(1.0, l + 1);
        const double reach = 0.5 * std::min(len[a], h) * (1 + 1e-9) + 1e-12 * big;
        double c[3], side[3];
        for (int k = 0; k < 3; ++k) {
          c[k] = cell_at(ma[k], l);
          side[k] = ma[k] / h - c[k] < 0.5 ? -1 : 1;
        }
        for (int corner = 0; corner < 8; ++corner) {
          const std::uint64_t k = key_of(c[0] + (corner & 1 ? side[0] : 0), c[1] + (corner & 2 ? side[1] : 0),
                                         c[2] + (corner & 4 ? side[2] : 0));
          auto it = std::lower_bound(cells.begin(), cells.end(), std::make_pair(k, -1));
          for (; it != cells.end() && it->first == k; ++it) {
            const int b = it->second;
            if (b == a) continue;
            // Each pair once: from its shorter segment, or from the changed one that
            // is shorter when both changed.
            if (!changed ? shorter(b, a) : ((*changed)[b] && shorter(b, a))) continue;
            const int b0 = plc.segments[b][0], b1 = plc.segments[b][1];
            if (b0 == a0 || b0 == a1 || b1 == a0 || b1 == a1) continue;
            const Point3& q = mid[b];
            if ((q.x - ma[0]) * (q.x - ma[0]) + (q.y - ma[1]) * (q.y - ma[1]) + (q.z - ma[2]) * (q.z - ma[2]) >
                reach * reach)
              continue;
            const auto pb0 = xyz(plc.points[b0]), pb1 = xyz(plc.points[b1]), mb = xyz(mid[b]);
            if (pred::in_diametral_sphere(pa0.data(), pa1.data(), mb.data()) > 0 &&
                pred::in_diametral_sphere(pb0.data(), pb1.data(), ma.data()) > 0)
              mine.push_back(shorter(a, b) ? std::array<int, 2>{a, b} : std::array<int, 2>{b, a});
          }
        }
      }
    }
#pragma omp critical(gdr_presplit_pairs)
    pairs.insert(pairs.end(), mine.begin(), mine.end());
  }
  std::sort(pairs.begin(), pairs.end());  // the same on any number of threads
  return pairs;
}

}  // namespace

int split_mutually_encroaching_segments(Plc& plc, int max_rounds) {
  int added = 0;
  std::vector<char> changed;  // the segments the last round split or made
  for (int round = 0; round < max_rounds; ++round) {
    const std::vector<std::array<int, 2>> pairs = mutually_encroaching(plc, round > 0 ? &changed : nullptr);
    if (pairs.empty()) break;
    // The triangles beside the segments of those pairs, by their edges: the facets there, and
    // the triangles to split (only these: a scan of 369k triangles has no such pair).
    std::unordered_set<std::uint64_t> involved;
    for (const auto& pr : pairs)
      for (const int g : pr) involved.insert(edge_key(plc.segments[g][0], plc.segments[g][1]));
    EdgeTriangles by_edge;
    for (std::size_t t = 0; t < plc.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const std::uint64_t e = edge_key(plc.triangles[t][k], plc.triangles[t][(k + 1) % 3]);
        if (involved.count(e)) by_edge.emplace(e, static_cast<int>(t));
      }
    const std::size_t ns = plc.segments.size();
    std::vector<char> split(ns, 0);
    for (const auto& [a, b] : pairs) {
      const Point3 ma = midpoint(plc.points[plc.segments[a][0]], plc.points[plc.segments[a][1]]);
      const Point3 mb = midpoint(plc.points[plc.segments[b][0]], plc.points[plc.segments[b][1]]);
      if (waits_across_a_bend(plc, by_edge, a, b, ma) || waits_across_a_bend(plc, by_edge, b, a, mb))
        split[a] = split[b] = 1;
    }
    if (std::find(split.begin(), split.end(), 1) == split.end()) break;
    changed.assign(ns, 0);
    for (std::size_t g = 0; g < ns; ++g) {
      if (!split[g]) continue;
      changed[g] = 1;
      const int a = plc.segments[g][0], b = plc.segments[g][1];
      const int m = static_cast<int>(plc.points.size());
      plc.points.push_back(midpoint(plc.points[a], plc.points[b]));
      ++added;
      plc.segments[g] = {a, m};
      plc.segments.push_back({m, b});
      plc.segment_flat.push_back(plc.segment_flat[g]);
      changed.push_back(1);
      // Each triangle (.., a, b, ..) becomes (a, m, c) and (m, b, c), in its orientation.
      const auto range = by_edge.equal_range(edge_key(a, b));
      std::vector<int> beside;
      for (auto it = range.first; it != range.second; ++it) beside.push_back(it->second);
      for (const int t : beside) {
        const std::array<int, 3> r = plc.triangles[t];
        int k = 0;
        while (k < 3 && !((r[k] == a && r[(k + 1) % 3] == b) || (r[k] == b && r[(k + 1) % 3] == a))) ++k;
        if (k == 3) continue;  // a stale entry: that edge went to the other half
        const int u = r[k], v = r[(k + 1) % 3], w = r[(k + 2) % 3];
        plc.triangles[t] = {u, m, w};
        plc.triangles.push_back({m, v, w});
        plc.triangle_origin.push_back(plc.triangle_origin[t]);
        plc.triangle_facet.push_back(plc.triangle_facet[t]);
        if (!plc.triangle_cell.empty()) plc.triangle_cell.push_back(plc.triangle_cell[t]);
        // The halves' edges, for segments split later in this round.
        by_edge.emplace(edge_key(u, m), t);
        by_edge.emplace(edge_key(m, w), t);
        const int t2 = static_cast<int>(plc.triangles.size()) - 1;
        by_edge.emplace(edge_key(m, v), t2);
        by_edge.emplace(edge_key(m, w), t2);
        by_edge.emplace(edge_key(v, w), t2);
      }
    }
  }
  return added;
}

}  // namespace gdr::cdt3d
