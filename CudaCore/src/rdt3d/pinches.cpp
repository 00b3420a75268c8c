// Pinches undone by relabelling tetrahedra (see pinches.h).
#include "rdt3d/pinches.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "mesh3d/host_mesh.h"

namespace gdr::rdt3d {
namespace {

struct Pinches {
  const double* xyz;
  const int* tv;
  const int* tn;
  int* flag;
  int inside_bit;
  std::vector<int> first, star;  // the tetrahedra at each vertex (CSR)
  std::vector<char> movable, frozen;

  bool in(int t) const { return (flag[t] & inside_bit) != 0; }
  void set(int t, bool inside) { flag[t] = inside ? (flag[t] | inside_bit) : (flag[t] & ~inside_bit); }

  double volume(int t) const {
    const double* p[4];
    for (int k = 0; k < 4; ++k) p[k] = xyz + 3 * static_cast<std::size_t>(tv[4 * t + k]);
    double u[3], v[3], w[3];
    for (int k = 0; k < 3; ++k) {
      u[k] = p[1][k] - p[0][k];
      v[k] = p[2][k] - p[0][k];
      w[k] = p[3][k] - p[0][k];
    }
    return std::fabs(u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
                     u[2] * (v[0] * w[1] - v[1] * w[0])) / 6;
  }

  // The tetrahedra around vertex a (b < 0) or edge ab, in increasing order (star is sorted).
  void place(int a, int b, std::vector<int>& ts) const {
    ts.clear();
    for (int k = first[a]; k < first[a + 1]; ++k) {
      const int t = star[k];
      if (b < 0 || std::find(tv + 4 * t, tv + 4 * t + 4, b) != tv + 4 * t + 4) ts.push_back(t);
    }
  }

  // Surface facets at edge ab (faces through it between the two sides; the hull is outside).
  int facets_at_edge(int a, int b) const {
    int twice = 0;
    for (int k = first[a]; k < first[a + 1]; ++k) {
      const int t = star[k];
      if (std::find(tv + 4 * t, tv + 4 * t + 4, b) == tv + 4 * t + 4) continue;
      for (int f = 0; f < 4; ++f) {
        const int opposite = tv[4 * t + f];
        if (opposite == a || opposite == b) continue;
        const int nb = tn[4 * t + f];
        const bool other = nb >= 0 && in(nb >> 2);
        if (in(t) != other) twice += nb >= 0 ? 1 : 2;  // seen from both sides, or once on the hull
      }
    }
    return twice / 2;
  }

  // Groups of the place's tetrahedra on each side, joined across faces through a (and b):
  // group[i] for ts[i], and the number of groups inside and outside.
  void groups(int a, int b, const std::vector<int>& ts, std::vector<int>& group, int& n_in, int& n_out) const {
    const int n = static_cast<int>(ts.size());
    group.resize(n);
    std::iota(group.begin(), group.end(), 0);
    auto root = [&](int i) {
      while (group[i] != i) i = group[i] = group[group[i]];
      return i;
    };
    // ts is sorted (place): the neighbour across a face through a (and b) is in it.
    for (int i = 0; i < n; ++i) {
      const int t = ts[i];
      for (int f = 0; f < 4; ++f) {
        const int opposite = tv[4 * t + f];  // face f holds the other three corners
        if (opposite == a || opposite == b || tn[4 * t + f] < 0) continue;
        const int u = tn[4 * t + f] >> 2;
        if (in(u) != in(t)) continue;
        const auto it = std::lower_bound(ts.begin(), ts.end(), u);
        if (it != ts.end() && *it == u) group[root(i)] = root(static_cast<int>(it - ts.begin()));
      }
    }
    n_in = n_out = 0;
    for (int i = 0; i < n; ++i)
      if (root(i) == i) (in(ts[i]) ? n_in : n_out) += 1;
    for (int i = 0; i < n; ++i) group[i] = root(i);
  }

  bool manifold(int a, int b, std::vector<int>& ts, std::vector<int>& group) const {
    place(a, b, ts);
    int n_in, n_out;
    groups(a, b, ts, group, n_in, n_out);
    return n_in <= 1 && n_out <= 1;
  }

  // Makes the place manifold; the tetrahedra that change side are appended to `moved`.
  void mend(int a, int b, std::vector<int>& ts, std::vector<int>& group, std::vector<int>& moved) {
    if (manifold(a, b, ts, group)) return;
    const int n = static_cast<int>(ts.size());
    // Per group: volume and whether it may change side.
    std::vector<double> gvol(n, 0);
    std::vector<char> gfree(n, 1);
    for (int i = 0; i < n; ++i) {
      gvol[group[i]] += volume(ts[i]);
      if (!movable[ts[i]] || frozen[ts[i]]) gfree[group[i]] = 0;
    }
    // Per side: keep its largest group, move the others; the cost is their volume.
    double cost[2] = {0, 0};
    int keep[2] = {-1, -1}, count[2] = {0, 0};
    bool possible[2] = {true, true};
    for (int side = 0; side < 2; ++side) {
      for (int i = 0; i < n; ++i)
        if (group[i] == i && in(ts[i]) == (side == 1)) {
          ++count[side];
          if (keep[side] < 0 || gvol[i] > gvol[keep[side]]) keep[side] = i;
        }
      for (int i = 0; i < n; ++i)
        if (group[i] == i && in(ts[i]) == (side == 1) && i != keep[side]) {
          cost[side] += gvol[i];
          possible[side] = possible[side] && gfree[i];
        }
      possible[side] = possible[side] && count[side] > 1;
    }
    const auto move = [&](int i) {
      if (frozen[ts[i]]) return;
      set(ts[i], !in(ts[i]));
      frozen[ts[i]] = 1;
      moved.push_back(ts[i]);
    };
    int side;  // the side whose extra groups move
    if (possible[0] || possible[1]) {
      side = possible[0] && possible[1] ? (cost[1] <= cost[0] ? 1 : 0) : (possible[1] ? 1 : 0);
      for (int i = 0; i < n; ++i)
        if (in(ts[i]) == (side == 1) && group[i] != keep[side] && movable[ts[i]]) move(i);
    } else {  // the whole star to the side of most volume, where its tetrahedra may move
      double vol[2] = {0, 0};
      for (int i = 0; i < n; ++i) vol[in(ts[i]) ? 1 : 0] += volume(ts[i]);
      const bool inside = vol[1] >= vol[0];
      for (int i = 0; i < n; ++i)
        if (in(ts[i]) != inside && movable[ts[i]]) {
          set(ts[i], inside);
          moved.push_back(ts[i]);
        }
    }
  }
};

}  // namespace

PinchRepair undo_pinches(const double* xyz, const std::uint8_t* ptype, int npts, const int* tv, const int* tn,
                         int* flag, int ntet, int inside_bit, int fixed_bits, int max_rounds) {
  Pinches p{xyz, tv, tn, flag, inside_bit, {}, {}, {}, {}};
  p.first.assign(npts + 1, 0);
  for (int k = 0; k < 4 * ntet; ++k) ++p.first[tv[k] + 1];
  for (int v = 0; v < npts; ++v) p.first[v + 1] += p.first[v];
  p.star.resize(4 * static_cast<std::size_t>(ntet));
  {
    std::vector<int> at(p.first.begin(), p.first.end() - 1);
    for (int k = 0; k < 4 * ntet; ++k) p.star[at[tv[k]]++] = k / 4;
  }
  p.movable.assign(ntet, 1);
  p.frozen.assign(ntet, 0);
  for (int t = 0; t < ntet; ++t) {
    if (flag[t] & fixed_bits) p.movable[t] = 0;
    for (int k = 0; k < 4; ++k)
      if (tn[4 * t + k] < 0 || ptype[tv[4 * t + k]] == m3d::kFreePoint) p.movable[t] = 0;
  }

  // Surface vertices: a tetrahedron inside and one outside (the hull counts as outside).
  auto on_surface = [&](int v) {
    bool seen[2] = {false, false};
    for (int k = p.first[v]; k < p.first[v + 1]; ++k) seen[p.in(p.star[k])] = true;
    return seen[0] && seen[1];
  };
  // Places to look at: the surface vertices among `vertices`, and the edges between them.
  std::vector<int> ts, group, moved;
  auto look = [&](const std::vector<int>& vertices, bool mend, std::vector<int>* bad) {
    long long left = 0;
    for (const int a : vertices) {
      if (!on_surface(a)) continue;
      if (mend) p.mend(a, -1, ts, group, moved);
      if (!p.manifold(a, -1, ts, group)) {
        ++left;
        if (bad) bad->push_back(a);
      }
      // Edges from a to surface vertices b > a, each once.
      std::vector<int> others;
      for (int k = p.first[a]; k < p.first[a + 1]; ++k)
        for (int q = 0; q < 4; ++q) {
          const int b = tv[4 * p.star[k] + q];
          if (b > a) others.push_back(b);
        }
      std::sort(others.begin(), others.end());
      others.erase(std::unique(others.begin(), others.end()), others.end());
      for (const int b : others) {
        const int facets = p.facets_at_edge(a, b);
        if (facets == 2 || facets == 0) continue;  // manifold there
        if (mend) p.mend(a, b, ts, group, moved);
        if (!p.manifold(a, b, ts, group)) {
          ++left;
          if (bad) {
            bad->push_back(a);
            bad->push_back(b);
          }
        }
      }
    }
    return left;
  };

  // The corners of the faces between the two sides: where pinches can be.
  auto surface_vertices = [&] {
    std::vector<char> on(npts, 0);
    for (int t = 0; t < ntet; ++t)
      for (int f = 0; f < 4; ++f) {
        const int nb = tn[4 * t + f];
        if (p.in(t) == (nb >= 0 && p.in(nb >> 2))) continue;
        for (int k = 0; k < 4; ++k)
          if (k != f) on[tv[4 * t + k]] = 1;
      }
    std::vector<int> list;
    for (int v = 0; v < npts; ++v)
      if (on[v]) list.push_back(v);
    return list;
  };
  PinchRepair r;
  r.moved.assign(ntet, 0);
  std::vector<int> vertices = surface_vertices();
  for (r.rounds = 0; r.rounds < max_rounds; ++r.rounds) {
    moved.clear();
    const long long left = look(vertices, true, nullptr);
    r.relabelled += static_cast<long long>(moved.size());
    for (const int t : moved) r.moved[t] = 1;
    if (moved.empty() || left == 0) break;
    // Next round: the vertices of what moved and their neighbours' (whose edges and stars changed).
    vertices.clear();
    for (const int t : moved)
      for (int k = 0; k < 4; ++k) {
        const int v = tv[4 * t + k];
        for (int j = p.first[v]; j < p.first[v + 1]; ++j)
          for (int q = 0; q < 4; ++q) vertices.push_back(tv[4 * p.star[j] + q]);
      }
    std::sort(vertices.begin(), vertices.end());
    vertices.erase(std::unique(vertices.begin(), vertices.end()), vertices.end());
  }
  r.places_left = look(surface_vertices(), false, &r.left_at);
  std::sort(r.left_at.begin(), r.left_at.end());
  r.left_at.erase(std::unique(r.left_at.begin(), r.left_at.end()), r.left_at.end());
  return r;
}

}  // namespace gdr::rdt3d
