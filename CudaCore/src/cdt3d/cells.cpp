// Cells of a closed triangle set and the domain they make (see Plc in cdt3d.h).
//
// Each triangle has two sides. Around every edge, the triangles are sorted by angle (exact
// orient3d); two consecutive ones face the same wedge of space, so their sides facing it are
// glued. The glued classes of sides are closed surfaces, each facing one cell. Seen with
// normals into its cell, a surface has negative signed volume when the cell is inside it
// (the cell's outer boundary) and positive when the cell is outside it (the outside of a
// connected piece of the surface). So every negative surface is one bounded cell; the
// positive surface of a connected piece faces the innermost cell that contains the piece,
// found by a ray-parity test (exact, with a symbolic perturbation) against the cells'
// outer boundaries. Then the cells' depth (least number of surface crossings from the
// outside) and the seeds decide the domain.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <queue>

#include "cdt3d/geometry.h"
#include "cdt3d/internal.h"
#include "gdr/error.h"

namespace gdr::cdt3d {
namespace {

struct Bounds {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void add(const Point3& p) {
    const double* c = geom::xyz(p);
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], c[d]);
      hi[d] = std::max(hi[d], c[d]);
    }
  }
  bool contains(const Point3& p) const {
    const double* c = geom::xyz(p);
    for (int d = 0; d < 3; ++d)
      if (c[d] < lo[d] || c[d] > hi[d]) return false;
    return true;
  }
};

std::string point_text(const Point3& p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.17g, %.17g, %.17g)", p.x, p.y, p.z);
  return buf;
}

}  // namespace

void classify_cells(Plc& plc, const EdgeTable& edges, const std::vector<int>& input_triangle,
                    const Callbacks& callbacks) {
  const auto& P = plc.points;
  const auto& T = plc.triangles;
  const int nt = static_cast<int>(T.size());

  // 1. Glue sides around edges. Side 2t is the front of t (its normal side), 2t+1 the back.
  UnionFind sides(2 * static_cast<std::size_t>(nt));
  UnionFind pieces(nt);  // connected pieces of the surface (through edges)
  std::vector<int> order;
  for (int k = 0; k < edges.size(); ++k) {
    const int m = edges.count(k);
    if (m < 2) continue;  // open edges were refused before
    const int a = edges.edge[k][0], b = edges.edge[k][1];
    const int* tris = &edges.tri[edges.start[k]];
    auto apex = [&](int t) { return T[t][0] + T[t][1] + T[t][2] - a - b; };
    // Does t run a -> b? Then its normal turns toward increasing angle about a -> b.
    auto forward = [&](int t) {
      for (int i = 0; i < 3; ++i)
        if (T[t][i] == a) return T[t][(i + 1) % 3] == b;
      return false;
    };
    order.assign(tris, tris + m);
    if (m > 2) {
      // Angle about the axis a -> b from the first apex r: quarter 0 is r's half-plane,
      // 1 the half turn after it, 2 the opposite half-plane, 3 the rest.
      const int r = apex(order[0]);
      const int axis = geom::projection_axis(P[a], P[b], P[r]);
      auto quarter = [&](int t) {
        const int c = apex(t);
        if (c == r) return 0;
        const int s = geom::orient3d(P[a], P[b], P[r], P[c]);
        if (s < 0) return 1;
        if (s > 0) return 3;
        return geom::orient2d(axis, P[a], P[b], P[r]) == geom::orient2d(axis, P[a], P[b], P[c]) ? 0 : 2;
      };
      std::sort(order.begin(), order.end(), [&](int t1, int t2) {
        const int q1 = quarter(t1), q2 = quarter(t2);
        if (q1 != q2) return q1 < q2;
        if (q1 == 0 || q1 == 2) return false;  // coplanar ties cannot happen without overlap
        return geom::orient3d(P[a], P[b], P[apex(t1)], P[apex(t2)]) < 0;
      });
    }
    for (int i = 0; i < m; ++i) {
      const int t1 = order[i], t2 = order[(i + 1) % m];
      // The wedge from t1 to t2: t1's side toward increasing angle, t2's toward decreasing.
      const int s1 = 2 * t1 + (forward(t1) ? 0 : 1);
      const int s2 = 2 * t2 + (forward(t2) ? 1 : 0);
      sides.unite(s1, s2);
      pieces.unite(t1, t2);
    }
  }

  // 2. Surfaces (glued classes), their signed volumes (normals into their cell), bounds,
  // and the triangles they hold.
  std::vector<int> surface_of(2 * static_cast<std::size_t>(nt));
  int ns = 0;
  {
    std::vector<int> id(2 * static_cast<std::size_t>(nt), -1);
    for (int s = 0; s < 2 * nt; ++s) {
      const int root = sides.find(s);
      if (id[root] < 0) id[root] = ns++;
      surface_of[s] = id[root];
    }
  }
  Bounds all;
  for (const auto& p : P) all.add(p);
  const Point3 o{0.5 * (all.lo[0] + all.hi[0]), 0.5 * (all.lo[1] + all.hi[1]), 0.5 * (all.lo[2] + all.hi[2])};
  std::vector<double> volume(ns, 0);
  std::vector<Bounds> bounds(ns);
  std::vector<int> piece(ns, -1);
  std::vector<int> side_start(ns + 1, 0), side_list(2 * static_cast<std::size_t>(nt));
  for (int t = 0; t < nt; ++t) {
    const Point3 &a = P[T[t][0]], &b = P[T[t][1]], &c = P[T[t][2]];
    const double ax = a.x - o.x, ay = a.y - o.y, az = a.z - o.z;
    const double bx = b.x - o.x, by = b.y - o.y, bz = b.z - o.z;
    const double cx = c.x - o.x, cy = c.y - o.y, cz = c.z - o.z;
    const double v = (ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx)) / 6;
    for (int k = 0; k < 2; ++k) {
      const int s = surface_of[2 * t + k];
      volume[s] += k == 0 ? v : -v;
      for (int i = 0; i < 3; ++i) bounds[s].add(P[T[t][i]]);
      piece[s] = pieces.find(t);
      ++side_start[s + 1];
    }
  }
  for (int s = 0; s < ns; ++s) side_start[s + 1] += side_start[s];
  {
    std::vector<int> fill(side_start.begin(), side_start.end() - 1);
    for (int x = 0; x < 2 * nt; ++x) side_list[fill[surface_of[x]]++] = x;
  }

  // 3. Outer surfaces (positive: they face the outside of their piece) and cells (negative).
  // Cell 0 is the unbounded outside.
  std::vector<int> cell_of_surface(ns, -1);
  std::vector<int> cell_surface = {-1};
  std::vector<std::vector<int>> outer_of_piece(nt);
  for (int s = 0; s < ns; ++s) {
    if (volume[s] > 0) {
      outer_of_piece[piece[s]].push_back(s);
    } else {
      cell_of_surface[s] = static_cast<int>(cell_surface.size());
      cell_surface.push_back(s);
    }
  }
  const int ncells = static_cast<int>(cell_surface.size());

  // Ray parity of p against surface s (counting triangles with one side on s).
  auto inside = [&](const Point3& p, int s) {
    int crossings = 0;
    for (int i = side_start[s]; i < side_start[s + 1]; ++i) {
      const int t = side_list[i] / 2;
      if (surface_of[2 * t] == surface_of[2 * t + 1]) continue;  // both sides: cancels
      const Point3 &a = P[T[t][0]], &b = P[T[t][1]], &c = P[T[t][2]];
      if (std::max({a.x, b.x, c.x}) < p.x) continue;
      if (std::min({a.y, b.y, c.y}) > p.y || std::max({a.y, b.y, c.y}) < p.y) continue;
      if (std::min({a.z, b.z, c.z}) > p.z || std::max({a.z, b.z, c.z}) < p.z) continue;
      crossings += geom::ray_crosses(p, a, b, c) == 1;
    }
    return crossings % 2 == 1;
  };
  // Triangles at each vertex, to tell whether a probe lies on a surface (built only when
  // there are several pieces to place).
  std::vector<int> vt_start, vt_list;
  int npieces = 0;
  for (int pc = 0; pc < nt; ++pc) npieces += !outer_of_piece[pc].empty();
  if (npieces > 1) {
    vt_start.assign(P.size() + 1, 0);
    for (const auto& t : T)
      for (int v : t) ++vt_start[v + 1];
    for (std::size_t v = 0; v < P.size(); ++v) vt_start[v + 1] += vt_start[v];
    vt_list.resize(3 * static_cast<std::size_t>(nt));
    std::vector<int> fill(vt_start.begin(), vt_start.end() - 1);
    for (int t = 0; t < nt; ++t)
      for (int v : T[t]) vt_list[fill[v]++] = t;
  }
  auto on_surface = [&](int v, int s) {
    for (int i = vt_start[v]; i < vt_start[v + 1]; ++i)
      if (surface_of[2 * vt_list[i]] == s || surface_of[2 * vt_list[i] + 1] == s) return true;
    return false;
  };
  // The innermost cell holding the probe (0: outside). The probe is `point` when given (a
  // seed, never on the surface), else the first of the vertices `probes` not on the cell's
  // boundary. Cells of piece `skip_piece` are not candidates.
  auto innermost_cell = [&](const std::vector<int>& probes, const Point3* point, int skip_piece) {
    int best = 0;
    for (int cell = 1; cell < ncells; ++cell) {
      const int s = cell_surface[cell];
      if (piece[s] == skip_piece) continue;
      if (best != 0 && -volume[s] >= -volume[cell_surface[best]]) continue;  // not inner
      const Point3* p = point;
      for (std::size_t i = 0; !p && i < probes.size(); ++i)
        if (!on_surface(probes[i], s)) p = &P[probes[i]];
      if (p && bounds[s].contains(*p) && inside(*p, s)) best = cell;
    }
    return best;
  };

  // 4. The cell each piece sits in, then every side's cell.
  std::vector<int> container(nt, 0);
  for (int pc = 0; pc < nt; ++pc) {
    if (outer_of_piece[pc].empty()) continue;
    std::vector<int> probes;
    for (int s : outer_of_piece[pc]) {
      for (int i = side_start[s]; i < side_start[s + 1] && probes.size() < 64; ++i)
        for (int v : T[side_list[i] / 2]) probes.push_back(v);
    }
    std::sort(probes.begin(), probes.end());
    probes.erase(std::unique(probes.begin(), probes.end()), probes.end());
    container[pc] = innermost_cell(probes, nullptr, pc);
  }
  plc.triangle_cell.assign(nt, {0, 0});
  for (int t = 0; t < nt; ++t)
    for (int k = 0; k < 2; ++k) {
      const int s = surface_of[2 * t + k];
      plc.triangle_cell[t][k] = cell_of_surface[s] >= 0 ? cell_of_surface[s] : container[piece[s]];
    }

  // 5. Cell volumes: inside the outer boundary, less the pieces sitting in the cell.
  plc.cell_volume.assign(ncells, 0);
  for (int cell = 1; cell < ncells; ++cell) plc.cell_volume[cell] = -volume[cell_surface[cell]];
  for (int pc = 0; pc < nt; ++pc)
    for (int s : outer_of_piece[pc])
      if (container[pc] != 0) plc.cell_volume[container[pc]] -= volume[s];

  // 6. Depth: least number of triangles crossed from the outside.
  std::vector<std::vector<int>> adjacent(ncells);
  for (int t = 0; t < nt; ++t) {
    const int c0 = plc.triangle_cell[t][0], c1 = plc.triangle_cell[t][1];
    if (c0 == c1) continue;
    adjacent[c0].push_back(c1);
    adjacent[c1].push_back(c0);
  }
  std::vector<int> depth(ncells, -1);
  std::queue<int> queue;
  depth[0] = 0;
  queue.push(0);
  while (!queue.empty()) {
    const int c = queue.front();
    queue.pop();
    for (int d : adjacent[c])
      if (depth[d] < 0) {
        depth[d] = depth[c] + 1;
        queue.push(d);
      }
  }

  // 7. Seeds: never on the surface; each marks the innermost cell holding it.
  auto seed_cell = [&](const Point3& p, const std::string& what) {
    for (int t = 0; t < nt; ++t) {
      const Point3 &a = P[T[t][0]], &b = P[T[t][1]], &c = P[T[t][2]];
      if (p.x < std::min({a.x, b.x, c.x}) || p.x > std::max({a.x, b.x, c.x})) continue;
      if (p.y < std::min({a.y, b.y, c.y}) || p.y > std::max({a.y, b.y, c.y})) continue;
      if (p.z < std::min({a.z, b.z, c.z}) || p.z > std::max({a.z, b.z, c.z})) continue;
      if (geom::point_on_triangle(p, a, b, c))
        throw Error(Status::InvalidInput, what + " " + point_text(p) + " lies on the surface (triangle " +
                                              std::to_string(input_triangle[t]) + ")");
    }
    return innermost_cell({}, &p, -1);
  };
  auto warn = [&](const std::string& m) {
    if (callbacks.warning) callbacks.warning(m);
  };
  std::vector<char> hole(ncells, 0);
  for (std::size_t i = 0; i < plc.holes.size(); ++i) {
    const int cell = seed_cell(plc.holes[i], "hole seed " + std::to_string(i));
    if (cell == 0) warn("hole seed " + std::to_string(i) + " lies outside the surface: ignored");
    hole[cell] = 1;
  }
  plc.cell_region.assign(ncells, -1);
  for (std::size_t i = 0; i < plc.regions.size(); ++i) {
    const std::string what = "region seed " + std::to_string(i);
    const int cell = seed_cell(plc.regions[i].point, what);
    if (cell == 0) {
      warn(what + " lies outside the surface: ignored");
    } else if (hole[cell]) {
      warn(what + " lies in a hole: ignored");
    } else if (plc.cell_region[cell] >= 0) {
      warn(what + " lies in the same region as region seed " + std::to_string(plc.cell_region[cell]) +
           ": ignored");
    } else {
      plc.cell_region[cell] = static_cast<int>(i);
    }
  }

  // 8. The domain.
  plc.cell_in_domain.assign(ncells, 0);
  plc.volume = 0;
  for (int cell = 1; cell < ncells; ++cell) {
    plc.cell_in_domain[cell] = !hole[cell] && (depth[cell] % 2 == 1 || plc.cell_region[cell] >= 0);
    if (plc.cell_in_domain[cell]) plc.volume += plc.cell_volume[cell];
  }
}

}  // namespace gdr::cdt3d
