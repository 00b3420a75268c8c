// Sliver removal by vertex smoothing, after refinement (beyond the paper; TetGen's -O
// smooths vertices in the same spirit). Delaunay refinement bounds the radius-edge ratio,
// which does not rule out slivers: four nearly cospherical points with good edges and a
// dihedral angle near 0 or 180 degrees.
//
// Each round, every free (interior Steiner) vertex of a tetrahedron whose smallest dihedral
// sine is below the target is a candidate. Candidates claim the tetrahedra of their stars
// with priority marks (exec/priority.h, random priorities); those that hold their whole star
// move, so no tetrahedron changes under two moves at once. A winner climbs the smallest
// dihedral sine of its star: it tries the centre of its link, then steps along the gradient
// of its worst tetrahedron, and keeps a position only if it raises the star's minimum
// without adding slivers to the star (so their number never grows), leaves every
// tetrahedron of the star positive (exact orient3d: the star still tiles the
// same polyhedron, so the mesh stays valid and conforming, its volume unchanged) and every
// one that met the mesher's bounds (`Bound`: radius-edge ratio, volume) meeting them. The mesh is no longer
// Delaunay where vertices moved.
//
// Both 3D meshers run it. `Scope` says which part of the mesh it works on: gQM3d's whole mesh
// (WholeMesh), or gDP3d's tetrahedra inside the surface (rdt3d/kernels.h), whose vertices move
// only when every tetrahedron of their star may change (so that the restricted surface, read
// off the tetrahedra next to it, stays as it was).
#pragma once
#include <cstdio>
#include <cstdlib>

#include "exec/algorithms.h"
#include "exec/priority.h"
#include "mesh3d/mesh3d.h"

namespace gdr::m3d {

struct SmoothParams {
  double target_sin = 0;  // stars holding a dihedral angle whose sine is below this
  int max_rounds = 30;
};

struct SmoothResult {
  long long slivers_before = 0, slivers_after = 0;  // tetrahedra below the target
  double min_sine_before = 1, min_sine_after = 1;   // the least dihedral sine there
  long long moves = 0;                              // vertex moves accepted
  long long flips = 0;                              // edge flips made after (mesh3d/flip.h)
  int rounds = 0;
};

// Smallest sine of the six dihedral angles of abcd: at edge e between faces with normals
// n1, n2 (twice their areas), sin = 6V |e| / (|n1| |n2|). Small for angles near 0 and 180.
GDR_HD_INLINE double min_dihedral_sine(const double* a, const double* b, const double* c,
                                       const double* d) {
  const double* p[4] = {a, b, c, d};
  double nl[4];
  for (int f = 0; f < 4; ++f) {
    const double* x = p[face_corner(f, 0)];
    const double* y = p[face_corner(f, 1)];
    const double* z = p[face_corner(f, 2)];
    const double u[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
    const double w[3] = {z[0] - x[0], z[1] - x[1], z[2] - x[2]};
    double n[3];
    cross3(u, w, n);
    nl[f] = sqrt(dot3(n, n));
  }
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ad[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  double n[3];
  cross3(ac, ad, n);
  const double v6 = fabs(dot3(ab, n));
  double lo = 1.0;
  for (int e = 0; e < 6; ++e) {
    const int i = edge_corner(e, 0), j = edge_corner(e, 1);
    int f[2], k = 0;
    for (int q = 0; q < 4; ++q)
      if (q != i && q != j) f[k++] = q;  // the faces at edge ij are opposite its other corners
    const double den = nl[f[0]] * nl[f[1]];
    const double s = den > 0 ? v6 * sqrt(dist2(p[i], p[j])) / den : 0.0;
    lo = fmin(lo, s);
  }
  return lo;
}

// The tetrahedra around vertex v, from t0 (one of them), through the faces at v. Returns
// their number, or -1 when there are more than kMaxStar or the walk leaves the mesh (v is
// then not a free vertex of a closed star and is not moved).
constexpr int kMaxStar = 128;
GDR_HD_INLINE int vertex_star(const TetView& m, int v, int t0, int* star) {
  int n = 0;
  star[n++] = t0;
  for (int i = 0; i < n; ++i) {
    const int t = star[i];
    const int cv = corner_of(m, t, v);
    for (int f = 0; f < 4; ++f) {
      if (f == cv) continue;
      const int nb = m.tn[4 * t + f];
      if (nb < 0) return -1;
      const int u = nb >> 2;
      bool seen = false;
      for (int k = 0; k < n && !seen; ++k) seen = star[k] == u;
      if (seen) continue;
      if (n == kMaxStar) return -1;
      star[n++] = u;
    }
  }
  return n;
}

// The star's tetrahedra with v at p: the smallest dihedral sine, or -1 if one of them is not
// positive (exact) or no longer meets the bounds it met (good[i]); `below` gets how many of
// them have a sine below the target.
template <class Bound>
struct StarEval {
  const TetView& m;
  const Bound& bound;
  const int* star;
  const bool* good;
  int n, v;
  double target;
  GDR_HD void corners(int i, const double* p, const double** c) const {
    const int* q = m.tv + 4 * star[i];
    for (int k = 0; k < 4; ++k) c[k] = q[k] == v ? p : pt(m, q[k]);
  }
  GDR_HD double operator()(const double* p, int& below) const {
    double lo = 1.0;
    below = 0;
    for (int i = 0; i < n; ++i) {
      const double* c[4];
      corners(i, p, c);
      if (!(pred::orient3d(c[0], c[1], c[2], c[3]) > 0)) return -1.0;
      if (good[i] && !bound(m, star[i], c)) return -1.0;
      const double s = min_dihedral_sine(c[0], c[1], c[2], c[3]);
      lo = fmin(lo, s);
      below += s < target;
    }
    return lo;
  }
  // The smallest dihedral sine of star tetrahedron i with v at p (no other check).
  GDR_HD double one(int i, const double* p) const {
    const double* c[4];
    corners(i, p, c);
    return min_dihedral_sine(c[0], c[1], c[2], c[3]);
  }
};

// Moves v (whose star is star[0..n)) to a better place, if it finds one: one where the star's
// smallest dihedral sine is higher and no more of its tetrahedra are below `target` (so that
// the number of slivers never grows: moves in one round change disjoint stars). Returns
// whether it moved.
template <class Bound>
GDR_HD bool smooth_vertex(const TetView& m, int v, const int* star, int n, const Bound& bound, double target) {
  double best[3] = {m.xyz[3 * v], m.xyz[3 * v + 1], m.xyz[3 * v + 2]};
  bool good[kMaxStar];
  for (int i = 0; i < n; ++i) {
    const int* q = m.tv + 4 * star[i];
    const double* c[4] = {pt(m, q[0]), pt(m, q[1]), pt(m, q[2]), pt(m, q[3])};
    good[i] = bound(m, star[i], c);
  }
  const StarEval<Bound> eval{m, bound, star, good, n, v, target};
  int below0 = 0, below = 0;
  double fbest = eval(best, below0);
  if (fbest < 0) return false;
  // Scale: the shortest edge at v.
  double lmin2 = INFINITY, centre[3] = {0, 0, 0};
  int nc = 0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) {
      const int u = m.tv[4 * star[i] + k];
      if (u == v) continue;
      lmin2 = fmin(lmin2, dist2(best, pt(m, u)));
      for (int d = 0; d < 3; ++d) centre[d] += pt(m, u)[d];
      ++nc;
    }
  for (int d = 0; d < 3; ++d) centre[d] /= nc;
  bool moved = false;
  const double fc = eval(centre, below);
  if (fc > fbest && below <= below0) {
    for (int d = 0; d < 3; ++d) best[d] = centre[d];
    fbest = fc;
    moved = true;
  }
  const double scale = sqrt(lmin2);
  for (int it = 0; it < 12; ++it) {
    int w = 0;  // the worst tetrahedron
    double fw = 2.0;
    for (int i = 0; i < n; ++i) {
      const double s = eval.one(i, best);
      if (s < fw) {
        fw = s;
        w = i;
      }
    }
    // Its gradient by central differences.
    const double h = 1e-4 * scale;
    double g[3];
    for (int d = 0; d < 3; ++d) {
      double q[3] = {best[0], best[1], best[2]};
      q[d] = best[d] + h;
      const double up = eval.one(w, q);
      q[d] = best[d] - h;
      g[d] = (up - eval.one(w, q)) / (2 * h);
    }
    const double gl = sqrt(dot3(g, g));
    if (!(gl > 0)) break;
    double step = 0.25 * scale;
    bool better = false;
    for (int k = 0; k < 10 && !better; ++k, step *= 0.5) {
      const double q[3] = {best[0] + step * g[0] / gl, best[1] + step * g[1] / gl, best[2] + step * g[2] / gl};
      const double f = eval(q, below);
      if (f > fbest && below <= below0) {
        for (int d = 0; d < 3; ++d) best[d] = q[d];
        fbest = f;
        better = true;
      }
    }
    if (!better) break;
    moved = true;
  }
  if (moved)
    for (int d = 0; d < 3; ++d) m.xyz[3 * v + d] = best[d];
  return moved;
}

// Where the pass works. counts(m, t): t is one of the tetrahedra whose slivers are counted
// and removed. in_star(m, t): a vertex whose star holds t may move (a vertex of any tetrahedron
// for which this is false stays where it is). kEverywhere: both are always true.
struct WholeMesh {
  static constexpr bool kEverywhere = true;
  GDR_HD bool counts(const TetView&, int) const { return true; }
  GDR_HD bool in_star(const TetView&, int) const { return true; }
};

// Candidates rank in a random order that changes every round.
struct ShuffledPriority {
  const int* vertex;
  unsigned salt;
  GDR_HD exec::u64 operator()(int j) const {
    return exec::shuffle_id(static_cast<unsigned>(vertex[j]), salt);
  }
};

// The smoothing rounds, on the tetrahedra of `scope`. `mesh` may hold dead tetrahedra
// (skipped); its marks are used and left zero.
template <class Space, class Bound, class Scope = WholeMesh>
SmoothResult smooth_slivers(DeviceTetMesh<Space>& mesh, const SmoothParams& sp, const Bound& bound,
                            const Scope& scope = Scope{}) {
  using Ops = exec::Ops<Space>;
  SmoothResult res;
  exec::Buffer<Space, int> vtet, cands, scratch, moved, pinned;
  exec::Buffer<Space, exec::u64> least(1);  // ~bits of the least dihedral sine counted
  vtet.resize_discard(mesh.npts);
  const double target = sp.target_sin;
  // Vertices of tetrahedra outside the scope's stars stay (their tetrahedra do not change).
  int* pin = nullptr;
  if (!Scope::kEverywhere) {
    pinned.resize_discard(mesh.npts);
    pin = pinned.data();
    exec::fill<Space>(pin, mesh.npts, 0);
    const TetView m = mesh.view();
    Ops::for_each(mesh.ntet, [=] GDR_HD(long long i) {
      const int t = static_cast<int>(i);
      if ((m.tflag[t] & kDead) || scope.in_star(m, t)) return;
      for (int k = 0; k < 4; ++k) exec::atomic_or(&pin[m.tv[4 * t + k]], 1);
    });
  }
  // Also the least sine (min_sine): moves raise their star's least sine, so it never falls.
  double min_sine = 1;
  auto count_slivers = [&]() {
    const TetView m = mesh.view();
    int* vt = vtet.data();
    exec::fill<Space>(vt, mesh.npts, -1);
    scratch.resize_discard(mesh.ntet);
    int* sl = scratch.data();
    const int* pn = pin;
    least.zero();
    exec::u64* lst = least.data();
    Ops::for_each(mesh.ntet, [=] GDR_HD(long long i) {
      const int t = static_cast<int>(i);
      sl[t] = 0;
      if ((m.tflag[t] & kDead) || !scope.counts(m, t)) return;
      const int* q = m.tv + 4 * t;
      const double s = min_dihedral_sine(pt(m, q[0]), pt(m, q[1]), pt(m, q[2]), pt(m, q[3]));
      const exec::u64 key = ~exec::bits_of(s > 0 ? s : 0.0);
      if (key > exec::volatile_load(lst)) exec::atomic_max(lst, key);
      if (!(s < target)) return;
      sl[t] = 1;
      for (int k = 0; k < 4; ++k)
        if (m.ptype[q[k]] == kFreePoint && !(pn && pn[q[k]])) exec::atomic_cas(&vt[q[k]], -1, t);
    });
    const exec::u64 b = ~least.get(0);
    std::memcpy(&min_sine, &b, sizeof b);
    if (least.get(0) == 0) min_sine = 1;  // nothing counted
    return Ops::exclusive_scan(sl, sl, mesh.ntet);
  };
  res.slivers_before = count_slivers();
  res.min_sine_before = min_sine;
  long long slivers = res.slivers_before;
  int stale = 0;  // rounds in a row that removed under 1% of the slivers
  mesh.mark.zero();
  for (int round = 0; round < sp.max_rounds && slivers > 0; ++round) {
    const int* vt = vtet.data();
    const std::size_t nc =
        exec::compact_indices<Space>(mesh.npts, [=] GDR_HD(long long v) { return vt[v] >= 0; }, cands, scratch);
    if (nc == 0) break;
    const TetView m = mesh.view();
    const int* cv = cands.data();
    const ShuffledPriority prio_of{cv, 0x9e3779b9u * static_cast<unsigned>(round + 1)};
    Ops::for_each(nc, [=] GDR_HD(long long j) {
      int star[kMaxStar];
      const int me = static_cast<int>(j);
      const int n = vertex_star(m, cv[j], vt[cv[j]], star);
      for (int i = 0; i < n; ++i)
        if (exec::claim(&m.mark[star[i]], me, prio_of(me), prio_of) < 0) return;
    });
    moved.resize_discard(nc);
    int* mv = moved.data();
    Ops::for_each(nc, [=] GDR_HD(long long j) {
      int star[kMaxStar];
      const int me = static_cast<int>(j);
      mv[j] = 0;
      const int n = vertex_star(m, cv[j], vt[cv[j]], star);
      for (int i = 0; i < n; ++i)
        if (m.mark[star[i]] != me + 1) return;
      if (n > 0) mv[j] = smooth_vertex(m, cv[j], star, n, bound, target) ? 1 : 0;
    });
    mesh.mark.zero();
    const long long nmoved = Ops::exclusive_scan(mv, mv, nc);
    res.moves += nmoved;
    res.rounds = round + 1;
    const long long was = slivers;
    slivers = count_slivers();
    if (std::getenv("GDR_TRACE"))
      std::fprintf(stderr, "gdr-trace slivers round %d: %zu candidates, %lld moved, %lld slivers left\n",
                   round + 1, nc, nmoved, slivers);
    // Stuck, or nearly: the rest are local optima (on the H100 the last rounds of 40 took
    // as long as the first and removed a few slivers each). One round may remove none (a
    // move raises its star's least angle, not always past the target), so two such
    // rounds in a row end it.
    stale = 100 * (was - slivers) < was ? stale + 1 : 0;
    if (nmoved * 50 < static_cast<long long>(nc) || stale == 2) break;
  }
  res.slivers_after = slivers;
  res.min_sine_after = min_sine;
  return res;
}

}  // namespace gdr::m3d
