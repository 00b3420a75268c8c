// Sliver removal by 3-2 flips, after smoothing (mesh3d/smooth.h), for the slivers smoothing
// cannot reach: those whose four corners lie on the surface (TetGen's -O flips them too).
// A sliver's four corners are nearly coplanar; two of its edges are the diagonals of that
// near-quadrilateral. Where such an edge cd has exactly three tetrahedra around it, none of
// its faces a subface and cd no subsegment, the three (cd with ring a, b, e) are replaced by
// the two tetrahedra abec and abed when the segment cd crosses the triangle abe (then the two
// tile the same polyhedron, so the mesh stays valid and conforming and its volume the same),
// their least dihedral sine is above the three's, and each meets the mesher's bounds if all
// three did. The mesh is no longer Delaunay there, as after smoothing.
//
// In parallel rounds, as the smoothing: each sliver plans a flip, claims the three
// tetrahedra and their neighbours across the faces that stay (whose links the flip rewrites)
// with random priorities, and those that hold all their claims flip.
#pragma once
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "mesh3d/mesh3d.h"
#include "mesh3d/smooth.h"

namespace gdr::m3d {

// The tetrahedra around edge cd of t, into ring[0..most): their count, or -1 where the walk
// meets the boundary or a subface, or there are more than `most`.
GDR_HD_INLINE int tets_around_edge(const TetView& m, int t, int c, int d, int* ring, int most) {
  const int* q = m.tv + 4 * t;
  int x = -1;  // a corner of the current tetrahedron off cd: leave through the face opposite it
  for (int k = 0; k < 4 && x < 0; ++k)
    if (q[k] != c && q[k] != d) x = q[k];
  int n = 0, cur = t;
  do {
    if (n == most) return -1;
    ring[n++] = cur;
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

// The three vertices around edge cd off it, in the three tetrahedra `ring`, ordered so that
// c lies on the positive side of their triangle (false: not three).
GDR_HD_INLINE bool ring_vertices(const TetView& m, const int* ring, int c, int d, int* rv) {
  int k = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) {
      const int v = m.tv[4 * ring[i] + j];
      if (v == c || v == d) continue;
      bool seen = false;
      for (int u = 0; u < k; ++u) seen = seen || rv[u] == v;
      if (!seen && k < 3) rv[k++] = v;
    }
  if (k != 3) return false;
  if (pred::orient3d(pt(m, rv[0]), pt(m, rv[1]), pt(m, rv[2]), pt(m, c)) < 0) {
    const int s = rv[0];
    rv[0] = rv[1];
    rv[1] = s;
  }
  return true;
}

// A planned 3-2 flip: the edge cd of tetrahedron ring[0] and the three tetrahedra around it.
struct Flip32 {
  int c = -1, d = -1;
  int ring[3];
};

// Whether the 3-2 flip of edge cd of tetrahedron t is allowed and raises the least dihedral
// sine there (see above); `f` gets the plan. Reads only the three tetrahedra.
template <class Bound>
GDR_HD_INLINE bool plan_flip32(const TetView& m, int t, int c, int d, const Bound& bound, Flip32& f) {
  int* ring = f.ring;
  if (tets_around_edge(m, t, c, d, ring, 3) != 3) return false;
  if (is_subseg(m, t, c, d)) return false;
  int rv[3];
  if (!ring_vertices(m, ring, c, d, rv)) return false;
  const double *A = pt(m, rv[0]), *B = pt(m, rv[1]), *E = pt(m, rv[2]), *C = pt(m, c), *D = pt(m, d);
  // c above abe, d below, and cd through the inside of triangle abe.
  if (!(pred::orient3d(A, B, E, C) > 0 && pred::orient3d(A, B, E, D) < 0)) return false;
  const double s0 = pred::orient3d(C, D, A, B), s1 = pred::orient3d(C, D, B, E), s2 = pred::orient3d(C, D, E, A);
  if (!((s0 > 0 && s1 > 0 && s2 > 0) || (s0 < 0 && s1 < 0 && s2 < 0))) return false;
  // Quality: the least sine must rise, and bounds met before stay met.
  double old_least = 1;
  bool old_good = true;
  for (int i = 0; i < 3; ++i) {
    const int* w = m.tv + 4 * ring[i];
    const double* p[4] = {pt(m, w[0]), pt(m, w[1]), pt(m, w[2]), pt(m, w[3])};
    old_least = fmin(old_least, min_dihedral_sine(p[0], p[1], p[2], p[3]));
    old_good = old_good && bound(m, ring[i], p);
    if (m.tregion && m.tregion[ring[i]] != m.tregion[t]) return false;
  }
  const int nv[2][4] = {{rv[0], rv[1], rv[2], c}, {rv[1], rv[0], rv[2], d}};
  for (int i = 0; i < 2; ++i) {
    const double* p[4] = {pt(m, nv[i][0]), pt(m, nv[i][1]), pt(m, nv[i][2]), pt(m, nv[i][3])};
    if (!(min_dihedral_sine(p[0], p[1], p[2], p[3]) > old_least)) return false;
    if (old_good && !bound(m, ring[i], p)) return false;
  }
  f.c = c;
  f.d = d;
  return true;
}

// Carries out a planned flip: ring[0] and ring[1] take the two new tetrahedra, ring[2] dies.
GDR_HD_INLINE void apply_flip32(const TetView& m, const Flip32& f) {
  const int c = f.c, d = f.d, t = f.ring[0];
  const int* ring = f.ring;
  int rv[3];
  ring_vertices(m, ring, c, d, rv);
  const int nv[2][4] = {{rv[0], rv[1], rv[2], c}, {rv[1], rv[0], rv[2], d}};
  // The faces on the union's boundary: each old tetrahedron's faces opposite c and d, with
  // their neighbour and subface; and the subsegment bits of the edges that stay.
  int ofv[6][3], otn[6], osub[6], no = 0;
  int segs[16][2], ns = 0;
  for (int i = 0; i < 3; ++i) {
    const int u = ring[i];
    const int* w = m.tv + 4 * u;
    for (int f = 0; f < 4; ++f) {
      if (w[f] != c && w[f] != d) continue;
      for (int j = 0; j < 3; ++j) ofv[no][j] = w[face_corner(f, j)];
      otn[no] = m.tn[4 * u + f];
      osub[no] = m.tsub[4 * u + f];
      ++no;
    }
    for (int e = 0; e < 6; ++e)
      if (is_subseg_edge(m, u, e) && ns < 16) {
        segs[ns][0] = w[edge_corner(e, 0)];
        segs[ns][1] = w[edge_corner(e, 1)];
        ++ns;
      }
  }
  const int region = m.tregion ? m.tregion[t] : 0;
  const int slot[2] = {ring[0], ring[1]};
  m.tflag[ring[2]] = kDead;
  for (int i = 0; i < 2; ++i) {
    const int u = slot[i];
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
    for (int f = 0; f < 4; ++f) {
      if (f == 3) {  // the new inner face abe, shared by the two
        m.tn[4 * u + 3] = 4 * slot[1 - i] + 3;
        m.tsub[4 * u + 3] = -1;
        continue;
      }
      const int a = w[face_corner(f, 0)], b = w[face_corner(f, 1)], e = w[face_corner(f, 2)];
      for (int o = 0; o < no; ++o) {
        int hits = 0;
        for (int j = 0; j < 3; ++j) hits += ofv[o][j] == a || ofv[o][j] == b || ofv[o][j] == e;
        if (hits != 3) continue;
        m.tn[4 * u + f] = otn[o];
        m.tsub[4 * u + f] = osub[o];
        if (otn[o] >= 0) m.tn[otn[o]] = 4 * u + f;
        if (osub[o] >= 0) {
          // The subface's side that named this face's old tetrahedron now names the new one.
          const int s = osub[o];
          for (int side = 0; side < 2; ++side) {
            const int tf = m.st[2 * s + side];
            if (tf < 0) continue;
            const int ot = tf >> 2;
            if (ot == ring[0] || ot == ring[1] || ot == ring[2]) m.st[2 * s + side] = 4 * u + f;
          }
        }
        break;
      }
    }
  }
}

// The planned flip of tetrahedron t (below the target): its edges by dihedral angle,
// largest first (cosine -n1.n2 / (|n1| |n2|) for the outward normals of the two faces at
// the edge), the first that may flip.
template <class Bound>
GDR_HD_INLINE bool plan_sliver_flip(const TetView& m, int t, const Bound& bound, Flip32& f) {
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
    if (plan_flip32(m, t, q[edge_corner(best, 0)], q[edge_corner(best, 1)], bound, f)) return true;
  }
  return false;
}

// The tetrahedra a planned flip writes: its three and their neighbours across the faces
// that stay. Returns their number (at most 9).
GDR_HD_INLINE int flip_footprint(const TetView& m, const Flip32& f, int* out) {
  int n = 0;
  for (int i = 0; i < 3; ++i) out[n++] = f.ring[i];
  for (int i = 0; i < 3; ++i) {
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
  exec::Buffer<Space, Flip32> plans;
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
    Flip32* pl = plans.data();
    int* wn = won.data();
    const ShuffledPriority prio_of{cv, 0x85ebca6bu * static_cast<unsigned>(round + 1)};
    Ops::for_each(nc, [=] GDR_HD(long long j) {
      const int me = static_cast<int>(j);
      wn[j] = 0;
      if (!plan_sliver_flip(m, cv[j], bound, pl[j])) {
        pl[j].c = -1;
        return;
      }
      int foot[9];
      const int n = flip_footprint(m, pl[j], foot);
      for (int i = 0; i < n; ++i)
        if (exec::claim(&m.mark[foot[i]], me, prio_of(me), prio_of) < 0) return;
    });
    Ops::for_each(nc, [=] GDR_HD(long long j) {
      if (pl[j].c < 0) return;
      int foot[9];
      const int n = flip_footprint(m, pl[j], foot);
      for (int i = 0; i < n; ++i)
        if (m.mark[foot[i]] != static_cast<int>(j) + 1) return;
      wn[j] = 1;
    });
    // Winners flip: each writes only the tetrahedra it holds (and the subfaces between them
    // and the outside), so no two flips touch the same element.
    Ops::for_each(nc, [=] GDR_HD(long long j) {
      if (wn[j]) apply_flip32(m, pl[j]);
    });
    mesh.mark.zero();
    // Next candidates: per old candidate, itself and, for a winner, the other new tetrahedron
    // (its own slot, ring[0], is the first), each if still below the target.
    next.resize_discard(2 * nc);
    int* nx = next.data();
    Ops::for_each(nc, [=] GDR_HD(long long j) {
      const int a = wn[j] ? pl[j].ring[0] : cv[j];
      nx[2 * j] = is_sliver(m, a, target) ? a : -1;
      nx[2 * j + 1] = wn[j] && is_sliver(m, pl[j].ring[1], target) ? pl[j].ring[1] : -1;
    });
    const long long flipped = Ops::exclusive_scan(wn, wn, nc);
    total += flipped;
    if (std::getenv("GDR_TRACE"))
      std::fprintf(stderr, "gdr-trace flips round %d: %zu candidates, %lld flipped\n", round + 1, nc, flipped);
    // Stuck, or nearly (as the smoothing's rounds).
    if (flipped * 50 < static_cast<long long>(nc)) break;
    const int* nxc = nx;
    nc = exec::compact_indices<Space>(
        2 * static_cast<long long>(nc), [=] GDR_HD(long long i) { return nxc[i] >= 0; }, scratch, won);
    cands.resize_discard(nc);
    int* cw = cands.data();
    const int* idx = scratch.data();
    Ops::for_each(nc, [=] GDR_HD(long long i) { cw[i] = nxc[idx[i]]; });
  }
  return total;
}

}  // namespace gdr::m3d
