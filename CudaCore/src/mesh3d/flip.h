// Sliver removal by edge flips, after smoothing (mesh3d/smooth.h), for the slivers smoothing
// cannot reach: those whose four corners lie on the surface (TetGen's -O flips them too).
// A sliver's four corners are nearly coplanar; two of its edges are the diagonals of that
// near-quadrilateral. Where such an edge cd has three to five tetrahedra around it, none of
// their faces at cd a subface and cd no subsegment, they are replaced by the tetrahedra that
// join c and d to a triangulation of the ring of vertices around cd (3-2, 4-4 and 5-6 flips;
// the best triangulation) when every new tetrahedron is positive by exact orient3d
// (then they tile the same polyhedron, so the mesh stays valid and conforming and its volume
// the same), their least dihedral sine is above the old ones', and each meets the mesher's
// bounds if all the old ones did. The mesh is no longer Delaunay there, as after smoothing.
//
// In parallel rounds, as the smoothing: each sliver plans a flip, claims the tetrahedra
// around the edge and their neighbours across the faces that stay (whose links the flip
// rewrites) with random priorities, and those that hold all their claims flip.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "mesh3d/mesh3d.h"
#include "mesh3d/smooth.h"

namespace gdr::m3d {

// The tetrahedra around edge cd of t, into ring[0..most), and the vertices around it off it
// in the same order, into rv (tetrahedron i holds rv[i] and rv[i+1], cyclically): their
// count, or -1 where the walk meets the boundary or a subface, or there are more than `most`.
GDR_HD_INLINE int tets_around_edge(const TetView& m, int t, int c, int d, int* ring, int* rv, int most) {
  const int* q = m.tv + 4 * t;
  int x = -1;  // a corner of the current tetrahedron off cd: leave through the face opposite it
  for (int k = 0; k < 4 && x < 0; ++k)
    if (q[k] != c && q[k] != d) x = q[k];
  int n = 0, cur = t;
  do {
    if (n == most) return -1;
    ring[n] = cur;
    rv[n++] = x;
    const int f = corner_of(m, cur, x);
    if (m.tsub[4 * cur + f] >= 0 || m.tn[4 * cur + f] < 0) return -1;
    const int* w = m.tv + 4 * cur;
    int y = -1;  // the shared face is (c, d, y)
    for (int k = 0; k < 4; ++k)
      if (w[k] != c && w[k] != d && w[k] != x) y = w[k];
    cur = m.tn[4 * cur + f] >> 2;
    x = y;
  } while (cur != t);
  return n;
}

// A planned edge removal: edge cd of tetrahedron ring[0], the n = 3, 4 or 5 tetrahedra around
// it and the vertices around it (tets_around_edge), and the triangulation of that ring: the
// fan from rv[apex] (for n <= 5 every triangulation is a fan). Its triangles, each with c and
// with d, make the 2 (n - 2) new tetrahedra: into the old ones' slots, and for n = 5 one more,
// ring[5], given when the flip is carried out.
struct EdgeFlip {
  int c = -1, d = -1, n = 0, apex = 0;
  bool swap = false;
  int ring[6], rv[5];
  GDR_HD int slot(int i) const { return i < n ? ring[i] : ring[5]; }
};

// New tetrahedron i (0 <= i < 2 (n - 2)) of a plan: fan triangle i / 2 with c (even i) or
// d (odd i). The triangles follow the ring's turn, so one order (`swap` or not) puts c on
// the positive side of all of them when the flip is valid.
GDR_HD_INLINE void new_tet(const EdgeFlip& f, int i, int* v) {
  const int j = i / 2 + 1;
  int a = f.rv[f.apex], b = f.rv[(f.apex + j) % f.n];
  const int e = f.rv[(f.apex + j + 1) % f.n];
  if (f.swap != (i % 2 == 1)) {  // d's tetrahedra take the other order
    const int s = a;
    a = b;
    b = s;
  }
  v[0] = a;
  v[1] = b;
  v[2] = e;
  v[3] = i % 2 ? f.d : f.c;
}

// Whether removing edge cd of tetrahedron t is allowed and raises the least dihedral sine
// there (see above); `f` gets the plan (the best fan). Reads only the tetrahedra around cd.
template <class Bound>
GDR_HD_INLINE bool plan_edge_flip(const TetView& m, int t, int c, int d, const Bound& bound, EdgeFlip& f) {
  f.c = c;
  f.d = d;
  f.n = tets_around_edge(m, t, c, d, f.ring, f.rv, 5);
  if (f.n < 3 || is_subseg(m, t, c, d)) return false;
  double old_least = 1;
  bool old_good = true;
  for (int i = 0; i < f.n; ++i) {
    const int* w = m.tv + 4 * f.ring[i];
    const double* p[4] = {pt(m, w[0]), pt(m, w[1]), pt(m, w[2]), pt(m, w[3])};
    old_least = fmin(old_least, min_dihedral_sine(p[0], p[1], p[2], p[3]));
    old_good = old_good && bound(m, f.ring[i], p);
    if (m.tregion && m.tregion[f.ring[i]] != m.tregion[t]) return false;
  }
  // Each fan (one for three tetrahedra, two distinct ones for four, five for five) whose new
  // tetrahedra are all positive (exact orient3d: then they fill what the old ones did) and
  // meet the bounds the old ones met; the one with the largest least sine, if above the old.
  double best = old_least;
  int best_apex = -1;
  for (int apex = 0; apex < (f.n == 3 ? 1 : (f.n == 4 ? 2 : 5)); ++apex) {
    f.apex = apex;
    f.swap = pred::orient3d(pt(m, f.rv[apex]), pt(m, f.rv[(apex + 1) % f.n]), pt(m, f.rv[(apex + 2) % f.n]),
                            pt(m, c)) < 0;
    double least = 1;
    bool ok = true;
    for (int i = 0; i < 2 * (f.n - 2) && ok; ++i) {
      int v[4];
      new_tet(f, i, v);
      const double* p[4] = {pt(m, v[0]), pt(m, v[1]), pt(m, v[2]), pt(m, v[3])};
      ok = pred::orient3d(p[0], p[1], p[2], p[3]) > 0 && (!old_good || bound(m, t, p));
      least = fmin(least, min_dihedral_sine(p[0], p[1], p[2], p[3]));
    }
    if (ok && least > best) {
      best = least;
      best_apex = apex;
    }
  }
  if (best_apex < 0) return false;
  f.apex = best_apex;
  f.swap = pred::orient3d(pt(m, f.rv[f.apex]), pt(m, f.rv[(f.apex + 1) % f.n]), pt(m, f.rv[(f.apex + 2) % f.n]),
                          pt(m, c)) < 0;
  return true;
}

// Carries out a planned flip: the slots take the new tetrahedra (2 of 3, the third dying; 4 of
// 4; 5 of 5 and ring[5]).
GDR_HD_INLINE void apply_edge_flip(const TetView& m, const EdgeFlip& f) {
  const int c = f.c, d = f.d, n = f.n, nnew = 2 * (n - 2);
  // The faces on the union's boundary: each old tetrahedron's faces opposite c and d, with
  // their neighbour and subface; and the subsegment bits of the edges that stay.
  int ofv[10][3], otn[10], osub[10], no = 0;
  int segs[30][2], ns = 0;
  for (int i = 0; i < n; ++i) {
    const int u = f.ring[i];
    const int* w = m.tv + 4 * u;
    for (int k = 0; k < 4; ++k) {
      if (w[k] != c && w[k] != d) continue;
      for (int j = 0; j < 3; ++j) ofv[no][j] = w[face_corner(k, j)];
      otn[no] = m.tn[4 * u + k];
      osub[no] = m.tsub[4 * u + k];
      ++no;
    }
    for (int e = 0; e < 6; ++e)
      if (is_subseg_edge(m, u, e) && ns < 30) {
        segs[ns][0] = w[edge_corner(e, 0)];
        segs[ns][1] = w[edge_corner(e, 1)];
        ++ns;
      }
  }
  const int region = m.tregion ? m.tregion[f.ring[0]] : 0;
  int nv[6][4];
  for (int i = 0; i < nnew; ++i) new_tet(f, i, nv[i]);
  for (int i = nnew; i < n; ++i) m.tflag[f.ring[i]] = kDead;
  for (int i = 0; i < nnew; ++i) {
    const int u = f.slot(i);
    int* w = m.tv + 4 * u;
    for (int j = 0; j < 4; ++j) w[j] = nv[i][j];
    int flag = 0;
    for (int e = 0; e < 6; ++e) {
      const int a = w[edge_corner(e, 0)], b = w[edge_corner(e, 1)];
      for (int s = 0; s < ns; ++s)
        if ((segs[s][0] == a && segs[s][1] == b) || (segs[s][0] == b && segs[s][1] == a)) flag |= kSeg0 << e;
    }
    m.tflag[u] = flag;
    if (m.tregion) m.tregion[u] = region;
  }
  // Faces: one on the union's boundary takes the old face's neighbour and subface (and they
  // point back); one between two new tetrahedra links them.
  for (int i = 0; i < nnew; ++i) {
    const int u = f.slot(i);
    const int* w = m.tv + 4 * u;
    for (int k = 0; k < 4; ++k) {
      const int a = w[face_corner(k, 0)], b = w[face_corner(k, 1)], e = w[face_corner(k, 2)];
      auto same = [&](const int* x) {
        int hits = 0;
        for (int j = 0; j < 3; ++j) hits += x[j] == a || x[j] == b || x[j] == e;
        return hits == 3;
      };
      bool outer = false;
      for (int o = 0; o < no && !outer; ++o) {
        if (!same(ofv[o])) continue;
        outer = true;
        m.tn[4 * u + k] = otn[o];
        m.tsub[4 * u + k] = osub[o];
        if (otn[o] >= 0) m.tn[otn[o]] = 4 * u + k;
        if (osub[o] >= 0) {
          // The subface's side that named the old tetrahedron now names the new one.
          for (int side = 0; side < 2; ++side) {
            const int tf = m.st[2 * osub[o] + side];
            if (tf < 0) continue;
            for (int r = 0; r < n; ++r)
              if ((tf >> 2) == f.ring[r]) m.st[2 * osub[o] + side] = 4 * u + k;
          }
        }
      }
      if (outer) continue;
      m.tsub[4 * u + k] = -1;
      for (int i2 = 0; i2 < nnew; ++i2) {
        if (i2 == i) continue;
        for (int k2 = 0; k2 < 4; ++k2) {
          const int fv[3] = {nv[i2][face_corner(k2, 0)], nv[i2][face_corner(k2, 1)], nv[i2][face_corner(k2, 2)]};
          if (same(fv)) m.tn[4 * u + k] = 4 * f.slot(i2) + k2;
        }
      }
    }
  }
}

// The planned flip of tetrahedron t (below the target): its edges by dihedral angle,
// largest first (cosine -n1.n2 / (|n1| |n2|) for the outward normals of the two faces at
// the edge), the first that may flip.
template <class Bound>
GDR_HD_INLINE bool plan_sliver_flip(const TetView& m, int t, const Bound& bound, EdgeFlip& f) {
  const int* q = m.tv + 4 * t;
  const double* p[4] = {pt(m, q[0]), pt(m, q[1]), pt(m, q[2]), pt(m, q[3])};
  double cosv[6];
  for (int e = 0; e < 6; ++e) {
    const int i = edge_corner(e, 0), j = edge_corner(e, 1);
    int fc[2], k = 0;
    for (int r = 0; r < 4; ++r)
      if (r != i && r != j) fc[k++] = r;
    double nrm[2][3];
    for (int s = 0; s < 2; ++s) {
      const double* x = p[face_corner(fc[s], 0)];
      const double* y = p[face_corner(fc[s], 1)];
      const double* z = p[face_corner(fc[s], 2)];
      const double u[3] = {y[0] - x[0], y[1] - x[1], y[2] - x[2]};
      const double w[3] = {z[0] - x[0], z[1] - x[1], z[2] - x[2]};
      cross3(u, w, nrm[s]);
    }
    const double den = sqrt(dot3(nrm[0], nrm[0]) * dot3(nrm[1], nrm[1]));
    cosv[e] = den > 0 ? -dot3(nrm[0], nrm[1]) / den : 0.0;
  }
  for (int tries = 0; tries < 6; ++tries) {
    int best = -1;
    for (int e = 0; e < 6; ++e)
      if (cosv[e] < 2 && (best < 0 || cosv[e] < cosv[best])) best = e;
    cosv[best] = 3;  // tried
    if (plan_edge_flip(m, t, q[edge_corner(best, 0)], q[edge_corner(best, 1)], bound, f)) return true;
  }
  return false;
}

// The tetrahedra a planned flip writes: its own and their neighbours across the faces that
// stay. Returns their number (at most 15).
GDR_HD_INLINE int flip_footprint(const TetView& m, const EdgeFlip& f, int* out) {
  int n = 0;
  for (int i = 0; i < f.n; ++i) out[n++] = f.ring[i];
  for (int i = 0; i < f.n; ++i) {
    const int* w = m.tv + 4 * f.ring[i];
    for (int k = 0; k < 4; ++k) {
      if (w[k] != f.c && w[k] != f.d) continue;
      const int nb = m.tn[4 * f.ring[i] + k];
      if (nb >= 0) out[n++] = nb >> 2;
    }
  }
  return n;
}

// Is tetrahedron t alive with a least dihedral sine below the target?
GDR_HD_INLINE bool is_sliver(const TetView& m, int t, double target) {
  if (m.tflag[t] & kDead) return false;
  const int* q = m.tv + 4 * t;
  return min_dihedral_sine(pt(m, q[0]), pt(m, q[1]), pt(m, q[2]), pt(m, q[3])) < target;
}

// How many live tetrahedra have a least dihedral sine below the target, and the least sine.
template <class Space>
long long count_slivers(DeviceTetMesh<Space>& mesh, double target, double& least) {
  using Ops = exec::Ops<Space>;
  exec::Buffer<Space, int> flag;
  exec::Buffer<Space, exec::u64> lowest(1);
  flag.resize_discard(mesh.ntet);
  lowest.zero();
  int* fl = flag.data();
  exec::u64* lo = lowest.data();
  const TetView m = mesh.view();
  Ops::for_each(mesh.ntet, [=] GDR_HD(long long t) {
    fl[t] = 0;
    if (m.tflag[t] & kDead) return;
    const int* q = m.tv + 4 * t;
    const double s = min_dihedral_sine(pt(m, q[0]), pt(m, q[1]), pt(m, q[2]), pt(m, q[3]));
    const exec::u64 key = ~exec::bits_of(s > 0 ? s : 0.0);
    if (key > exec::volatile_load(lo)) exec::atomic_max(lo, key);
    fl[t] = s < target;
  });
  const exec::u64 b = ~lowest.get(0);
  std::memcpy(&least, &b, sizeof b);
  if (lowest.get(0) == 0) least = 1;
  return Ops::exclusive_scan(fl, fl, mesh.ntet);
}

// The flip pass over the tetrahedra whose least dihedral sine is below the target, in
// rounds until one flips nothing (at most max_rounds). `mesh` may hold dead tetrahedra; its
// marks are used and left zero. Returns the flips made.
template <class Space, class Bound>
long long flip_slivers(DeviceTetMesh<Space>& mesh, double target, const Bound& bound, int max_rounds = 8) {
  using Ops = exec::Ops<Space>;
  exec::Buffer<Space, int> cands, next, scratch, won;
  exec::Buffer<Space, EdgeFlip> plans;
  long long total = 0;
  mesh.mark.zero();
  // The first round's candidates from the whole mesh; later ones from the last round's that
  // are still slivers and the tetrahedra its flips made.
  std::size_t nc;
  {
    const TetView m = mesh.view();
    nc = exec::compact_indices<Space>(mesh.ntet, [=] GDR_HD(long long t) { return is_sliver(m, static_cast<int>(t), target); },
                                      cands, scratch);
  }
  for (int round = 0; round < max_rounds && nc > 0; ++round) {
    const TetView m = mesh.view();
    plans.resize_discard(nc);
    won.resize_discard(nc);
    const int* cv = cands.data();
    EdgeFlip* pl = plans.data();
    int* wn = won.data();
    const ShuffledPriority prio_of{cv, 0x85ebca6bu * static_cast<unsigned>(round + 1)};
    Ops::for_each(nc, [=] GDR_HD(long long j) {
      const int me = static_cast<int>(j);
      wn[j] = 0;
      if (!plan_sliver_flip(m, cv[j], bound, pl[j])) {
        pl[j].c = -1;
        return;
      }
      int foot[15];
      const int n = flip_footprint(m, pl[j], foot);
      for (int i = 0; i < n; ++i)
        if (exec::claim(&m.mark[foot[i]], me, prio_of(me), prio_of) < 0) return;
    });
    Ops::for_each(nc, [=] GDR_HD(long long j) {
      if (pl[j].c < 0) return;
      int foot[15];
      const int n = flip_footprint(m, pl[j], foot);
      for (int i = 0; i < n; ++i)
        if (m.mark[foot[i]] != static_cast<int>(j) + 1) return;
      wn[j] = 1;
    });
    // A flip of five tetrahedra makes six: the sixth goes after the last tetrahedron.
    next.resize_discard(nc);
    int* ex = next.data();
    Ops::for_each(nc, [=] GDR_HD(long long j) { ex[j] = wn[j] && pl[j].n == 5; });
    const int extra = static_cast<int>(Ops::exclusive_scan(ex, ex, nc));
    const int first = mesh.ntet;
    if (extra > 0) {
      mesh.reserve(first + extra, mesh.nsub, mesh.npts);
      Ops::for_each(nc, [=] GDR_HD(long long j) {
        if (wn[j] && pl[j].n == 5) pl[j].ring[5] = first + ex[j];
      });
      mesh.ntet = first + extra;
    }
    const TetView mm = mesh.view();
    // Winners flip: each writes only the tetrahedra it holds (and the subfaces between them
    // and the outside, and its new slot), so no two flips touch the same element.
    Ops::for_each(nc, [=] GDR_HD(long long j) {
      if (wn[j]) apply_edge_flip(mm, pl[j]);
    });
    mesh.mark.zero();
    // Next candidates: per old candidate, itself or, for a winner, the new tetrahedra (its own
    // slot, ring[0], is the first), each if still below the target.
    next.resize_discard(6 * nc);
    int* nx = next.data();
    Ops::for_each(nc, [=] GDR_HD(long long j) {
      for (int r = 0; r < 6; ++r) {
        const int a = wn[j] ? (r < 2 * (pl[j].n - 2) ? pl[j].slot(r) : -1) : (r == 0 ? cv[j] : -1);
        nx[6 * j + r] = a >= 0 && is_sliver(mm, a, target) ? a : -1;
      }
    });
    const long long flipped = Ops::exclusive_scan(wn, wn, nc);
    total += flipped;
    if (std::getenv("GDR_TRACE"))
      std::fprintf(stderr, "gdr-trace flips round %d: %zu candidates, %lld flipped\n", round + 1, nc, flipped);
    // Stuck, or nearly (as the smoothing's rounds).
    if (flipped * 50 < static_cast<long long>(nc)) break;
    const int* nxc = nx;
    nc = exec::compact_indices<Space>(
        6 * static_cast<long long>(nc), [=] GDR_HD(long long i) { return nxc[i] >= 0; }, scratch, won);
    cands.resize_discard(nc);
    int* cw = cands.data();
    const int* idx = scratch.data();
    Ops::for_each(nc, [=] GDR_HD(long long i) { cw[i] = nxc[idx[i]]; });
  }
  return total;
}

}  // namespace gdr::m3d
