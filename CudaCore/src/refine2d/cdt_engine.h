// Parallel constrained Delaunay triangulation (issue 14), written once for any execution
// space like the refinement engine (engine.h), whose point insertion it reuses:
//   1. Delaunay triangulation of the points inside a bounding triangle, by rounds of
//      parallel Bowyer-Watson insertion: every triangle that holds points still to insert
//      proposes one of them, cavities are grown, filtered by priority marks and remeshed as
//      in refinement, and the points of the dead triangles walk to their new ones.
//   2. The convex hull's edges (when the hull is meshed) join the segments.
//   3. Missing segments are recovered in parallel: each claims the triangles its open
//      segment crosses and their neighbours; the winners replace those triangles by the
//      constrained Delaunay triangulations of the two pseudo-polygons on either side of the
//      segment (Anglada's insertion), which keeps the whole triangulation constrained
//      Delaunay. Losers retry in the next round.
// Exact predicates decide everything. Points are never moved or added.
#pragma once
#include <algorithm>
#include <climits>
#include <string>
#include <vector>

#include "exec/algorithms.h"
#include "exec/phase_clock.h"
#include "refine2d/cdt_kernels.h"
#include "refine2d/engine.h"

namespace gdr::r2d {

// What the device part hands back: every triangle, those at the bounding triangle's three
// vertices (numbered n, n+1, n+2) included; tseg[3t+e] is the segment on edge e or -1.
struct RawCdt {
  exec::HostVector<int> tv, tn, tseg;
  std::vector<PhaseTime> phases;
};

// The convex hull's edges as segments (2 per edge, counter-clockwise, collinear points kept
// as vertices), from the points adjacent to the bounding triangle (cdt_parallel.cpp).
std::vector<int> hull_segments(const double* xy, std::vector<int> candidates);

// An edge that two segments share (an input segment on the convex hull is a hull segment
// too) keeps the smaller number, the input's, whichever marks it last.
GDR_HD inline void claim_edge(int* ts, long long e, int s) {
  int cur = exec::volatile_load(&ts[e]);
  while (cur < 0 || cur > s) {
    const int seen = exec::atomic_cas(&ts[e], cur, s);
    if (seen == cur) return;
    cur = seen;
  }
}

// Compaction during point insertion: each point's triangle follows its move.
struct RenumberLocations {
  MoveTriangles move;
  const int* pending;
  int* loc;
  GDR_HD void operator()(long long j) const { loc[pending[j]] = move.destination(loc[pending[j]]); }
};
template <class Space>
struct FollowMoves {
  std::size_t np;
  const int* pending;
  int* loc;
  void operator()(const MoveTriangles& move) const {
    exec::Ops<Space>::for_each(np, RenumberLocations{move, pending, loc});
  }
};

template <class Space>
struct ParallelCdt {
  using Ops = exec::Ops<Space>;
  template <class T>
  using Buf = exec::Buffer<Space, T>;

  RawCdt res;
  exec::PhaseClock clock{res.phases};
  DeviceMesh<Space> dm;
  Buf<int> loc, pending, sel, failed, point_id, count, list, anchor, error, done;
  Buf<Candidate> cand_all, cand;
  Buf<CavityTuple> tuples;
  int n = 0;  // input points; n, n+1, n+2 bound them

  // Step 1. xy: the n points, then the bounding triangle's three corners.
  void triangulate_points(const std::vector<double>& xy) {
    n = static_cast<int>(xy.size() / 2) - 3;
    dm.npts = n + 3;
    dm.xy.upload(xy);
    dm.ptype.resize_discard(n + 3);
    exec::fill<Space>(dm.ptype.data(), n + 3, std::uint8_t(kInputPoint));
    dm.pseg.resize_discard(n + 3);
    exec::fill<Space>(dm.pseg.data(), n + 3, -1);
    dm.ntri = 1;
    const int corners[3] = {n, n + 1, n + 2}, none[3] = {-1, -1, -1}, zero = 0;
    dm.tv.upload(corners, 3);
    dm.tn.upload(none, 3);
    dm.tflag.resize_discard(1);
    dm.mark.resize_discard(1);
    dm.aux.resize_discard(1);
    dm.tflag.set(0, zero);
    dm.mark.set(0, zero);
    dm.reserve(2 * n + 16, n + 3);  // about the final count; compaction keeps it near that
    error.resize_discard(1);
    error.zero();
    loc.resize_discard(n);
    loc.zero();
    pending.resize_discard(n);
    exec::iota<Space>(pending.data(), n);
    std::size_t np = n;
    clock.template stop<Space>("dt setup");
    while (np > 0) {
      if (insertion_round(np) <= 0 || error.get(0))
        throw Error(Status::InternalError, "parallel CDT: point insertion made no progress");
      np = next_pending(np);
      if (4 * dead > dm.ntri || np == 0) {  // compaction (S1): loc follows the moves
        detail::compact_triangles(dm, FollowMoves<Space>{np, pending.data(), loc.data()});
        dead = 0;
      }
      clock.template stop<Space>("dt compact");
    }
  }

  long long dead = 0;  // dead triangles since the last compaction

  // One round: candidates, one per triangle, cavities, winners, fans, relocation.
  long long insertion_round(std::size_t np) {
    cand_all.resize_discard(np);
    Ops::for_each(np, MakePointCandidates{dm.xy.data(), pending.data(), loc.data(), cand_all.data()});
    dm.mark.zero();
    Ops::for_each(np, ClaimStart{dm.view(), cand_all.data(), u64(1) << 32, false});
    const Candidate* ca = cand_all.data();
    const int* mk = dm.mark.data();
    const std::size_t ns = exec::compact_indices<Space>(
        np, [=] GDR_HD(long long j) { return mk[ca[j].start] == j + 1; }, sel, count);
    cand.resize_discard(ns);
    Candidate* cs = cand.data();
    const int* sl = sel.data();
    Ops::for_each(ns, [=] GDR_HD(long long k) { cs[k] = ca[sl[k]]; });
    dm.mark.zero();
    clock.template stop<Space>("dt filter");

    failed.resize_discard(ns);
    failed.zero();
    tuples.resize_discard(ns);
    CavityTuple* tp = tuples.data();
    Ops::for_each(ns, [=] GDR_HD(long long k) { tp[k] = CavityTuple{static_cast<int>(k), cs[k].start, kForceIn}; });
    const exec::ExpandListResult er =
        exec::expand_list<Space, 3>(tuples, ns, GrowCavity{dm.view(), cand.data(), failed.data(), 0.0});
    tuples.resize(er.size);
    const std::size_t nt = tuples.size();
    Ops::for_each(nt, VerifyClaims{dm.view(), cand.data(), tuples.data(), failed.data(), true});
    Ops::for_each(nt, SetInCavity{dm.view(), cand.data(), tuples.data(), failed.data(), 1});
    Ops::for_each(nt, CheckCavity{dm.view(), cand.data(), tuples.data(), failed.data()});
    Ops::for_each(nt, SetInCavity{dm.view(), cand.data(), tuples.data(), failed.data(), 0});
    clock.template stop<Space>("dt cavity");

    // Fans: the engine's insertion, with each winner keeping its input number.
    count.resize_discard(nt);
    Ops::for_each(nt, CountFanEdges{dm.view(), cand.data(), tuples.data(), failed.data(), count.data()});
    const int new_tris = static_cast<int>(Ops::exclusive_scan(count.data(), count.data(), nt));
    Ops::for_each(nt, StoreSlotBase{dm.view(), tuples.data(), failed.data(), count.data()});
    const int old_ntri = dm.ntri;
    dm.reserve(old_ntri + new_tris, dm.npts);
    dm.ntri = old_ntri + new_tris;
    point_id.resize_discard(ns);
    anchor.resize_discard(ns);
    int* pid = point_id.data();
    int* anc = anchor.data();
    const int* pend = pending.data();
    const int* fl = failed.data();
    Ops::for_each(ns, [=] GDR_HD(long long k) {
      pid[k] = pend[sl[k]];
      anc[k] = INT_MAX;
    });
    const MeshView mv = dm.view();
    Ops::for_each(nt, CreateFan{mv, cand.data(), tuples.data(), failed.data(), pid, old_ntri});
    Ops::for_each(nt, LinkFan{mv, cand.data(), tuples.data(), failed.data(), old_ntri, error.data()});
    const CavityTuple* tc = tuples.data();
    const int* base = count.data();
    const long long ntl = static_cast<long long>(nt);
    Ops::for_each(nt, [=] GDR_HD(long long i) {
      const CavityTuple& h = tc[i];
      if (h.state != kTupleCavity || fl[h.pt]) return;
      const int end = i + 1 < ntl ? base[i + 1] : new_tris;
      if (end > base[i]) exec::atomic_min(&anc[h.pt], old_ntri + base[i]);
    });
    Ops::for_each(nt, KillCavity{mv, tuples.data(), failed.data()});
    done.resize_discard(np);
    done.zero();
    int* dn = done.data();
    Ops::for_each(ns, [=] GDR_HD(long long k) {
      if (!fl[k]) dn[sl[k]] = 1;
    });
    long long won = 0;
    {
      int* w = point_id.data();  // reused: winners count
      Ops::for_each(ns, [=] GDR_HD(long long k) { w[k] = fl[k] ? 0 : 1; });
      won = Ops::exclusive_scan(w, w, ns);
    }
    clock.template stop<Space>("dt insert");
    Ops::for_each(np, Relocate{mv, pending.data(), done.data(), loc.data(), anchor.data(), error.data()});
    clock.template stop<Space>("dt relocate");
    dead += new_tris - 2 * won;  // a cavity of k triangles leaves k dead for k + 2 new
    return won;
  }

  // The points still to insert, in their old order.
  std::size_t next_pending(std::size_t np) {
    const int* dn = done.data();
    const std::size_t left = exec::compact_indices<Space>(
        np, [=] GDR_HD(long long j) { return !dn[j]; }, list, count);
    Buf<int> next(left);
    int* nx = next.data();
    const int* pd = pending.data();
    const int* li = list.data();
    Ops::for_each(left, [=] GDR_HD(long long j) { nx[j] = pd[li[j]]; });
    pending.swap(next);
    return left;
  }

  // Step 2's input: the points joined to the bounding triangle (every hull vertex is).
  std::vector<int> hull_candidates() {
    Buf<int> near(n);
    near.zero();
    int* nr = near.data();
    const MeshView mv = dm.view();
    const int nn = n;
    Ops::for_each(dm.ntri, [=] GDR_HD(long long t) {
      const int* v = mv.tv + 3 * t;
      if (v[0] < nn && v[1] < nn && v[2] < nn) return;
      for (int i = 0; i < 3; ++i)
        if (v[i] < nn) nr[v[i]] = 1;
    });
    exec::compact_indices<Space>(n, [=] GDR_HD(long long p) { return nr[p] != 0; }, list, count);
    return list.to_host();
  }

  Buf<int> seg, tseg, vt, miss, start, tri_count, slots, scratch;

  // Everything but the triangulation (dm) and its segment marks (tseg), once done.
  void release_scratch() {
    for (Buf<int>* b : {&loc, &pending, &sel, &failed, &point_id, &count, &list, &anchor, &error, &done,
                        &seg, &vt, &miss, &start, &tri_count, &slots, &scratch})
      b->release();
    for (Buf<int>* b : {&dm.tflag, &dm.mark, &dm.aux}) b->release();
    cand_all.release();
    cand.release();
    tuples.release();
  }

  // Step 3: every segment (2 per segment: point numbers) becomes an edge of the mesh.
  void recover_segments(const std::vector<int>& segments) {
    const int ns = static_cast<int>(segments.size() / 2);
    seg.upload(segments);
    tseg.resize_discard(3 * std::size_t(dm.ntri));
    exec::fill<Space>(tseg.data(), tseg.size(), -1);
    miss.resize_discard(ns);
    exec::iota<Space>(miss.data(), ns);
    std::size_t nm = ns;
    int rounds = 0;
    while (nm > 0) {
      find_segments(nm);  // present ones are marked and dropped; start codes for the rest
      nm = drop_marked(nm);
      clock.template stop<Space>("segments find");
      if (nm == 0) break;
      if (++rounds > 1000000)
        throw Error(Status::InternalError, "parallel CDT: segment recovery made no progress");
      recovery_round(nm);
    }
    check_links();
  }

  // Every link must be mutual, between the same two vertices, with the same segment mark on
  // both sides. A spike in a chain (InsertSegment) used to leave links to reused slots,
  // after which the exterior flooded through them (fuzz2d seed 51; long segments through a
  // cloud): should any such defect remain, the CDT is refused and refine_2d builds CGAL's,
  // with a warning.
  void check_links() {
    const MeshView mv = dm.view();
    const int* ts = tseg.size() >= 3 * std::size_t(dm.ntri) ? tseg.data() : nullptr;
    int* err = error.data();
    error.zero();
    Ops::for_each(3 * std::size_t(dm.ntri), [=] GDR_HD(long long e) {
      const int nb = mv.tn[e];
      if (nb < 0) return;
      const long long t = e / 3, u = nb / 3;
      const int i = static_cast<int>(e % 3), j = nb % 3;
      if (mv.tn[nb] != e || (ts && ts[nb] != ts[e]) || mv.tv[3 * t + next3(i)] != mv.tv[3 * u + prev3(j)] ||
          mv.tv[3 * t + prev3(i)] != mv.tv[3 * u + next3(j)])
        *err = 1;
    });
    if (error.get(0))
      throw Error(Status::InternalError, "parallel CDT: inconsistent triangle links after segment recovery");
  }

  // Per listed segment: done (its edge is there: marked now) or its start code.
  void find_segments(std::size_t nm) {
    vt.resize_discard(n);
    exec::fill<Space>(vt.data(), n, INT_MAX);
    int* v = vt.data();
    const MeshView mv = dm.view();
    const int nn = n;
    Ops::for_each(dm.ntri, [=] GDR_HD(long long t) {
      for (int i = 0; i < 3; ++i)
        if (mv.tv[3 * t + i] < nn) exec::atomic_min(&v[mv.tv[3 * t + i]], static_cast<int>(t));
    });
    start.resize_discard(nm);
    int* st = start.data();
    const int* ms = miss.data();
    const int* sg = seg.data();
    int* ts = tseg.data();
    int* err = error.data();
    Ops::for_each(nm, [=] GDR_HD(long long r) {
      const int s = ms[r];
      const int a = sg[2 * s], b = sg[2 * s + 1];
      const long long code = segment_start(mv, v[a], a, b);
      if (code <= -2) {  // present: mark both sides
        const long long c = -2 - code;
        claim_edge(ts, c, s);
        const int nb = mv.tn[c];
        if (nb >= 0) claim_edge(ts, nb, s);
        st[r] = -1;
      } else if (code == -1) {
        *err = 2 + s;  // a point on the segment
        st[r] = -1;
      } else {
        st[r] = static_cast<int>(code);
      }
    });
    const int e = error.get(0);
    if (e >= 2)
      throw Error(Status::SelfIntersectingInput,
                  "parallel CDT: a point lies on the interior of segment " + std::to_string(e - 2));
  }

  std::size_t drop_marked(std::size_t nm) {
    const int* st = start.data();
    const std::size_t left = exec::compact_indices<Space>(
        nm, [=] GDR_HD(long long r) { return st[r] >= 0; }, list, count);
    Buf<int> m2(left), s2(left);
    int* a = m2.data();
    int* b = s2.data();
    const int* ms = miss.data();
    const int* li = list.data();
    Ops::for_each(left, [=] GDR_HD(long long r) {
      a[r] = ms[li[r]];
      b[r] = st[li[r]];
    });
    miss.swap(m2);
    start.swap(s2);
    return left;
  }

  void recovery_round(std::size_t nm) {
    const MeshView mv = dm.view();
    const int* ms = miss.data();
    const int* sg = seg.data();
    const int* st = start.data();
    const int* ts = tseg.data();
    int* err = error.data();
    // Triangles crossed, then their offsets.
    tri_count.resize_discard(nm + 1);
    int* tc = tri_count.data();
    Ops::for_each(nm, [=] GDR_HD(long long r) {
      const int b = sg[2 * ms[r] + 1];
      const int k = walk_segment(mv, ts, st[r], b, INT_MAX / 8, [](int, int, int) {});
      if (k < 0) *err = k == -1 ? 2 + ms[r] : (k == -2 ? -(2 + ms[r]) : 1);
      tc[r] = k < 0 ? 0 : k;
    });
    const int e = error.get(0);
    if (e >= 2)
      throw Error(Status::SelfIntersectingInput,
                  "parallel CDT: a point lies on the interior of segment " + std::to_string(e - 2));
    if (e <= -2)
      throw Error(Status::SelfIntersectingInput,
                  "parallel CDT: segment " + std::to_string(-e - 2) + " crosses another segment");
    if (e) throw Error(Status::InternalError, "parallel CDT: a segment walk failed");
    Ops::for_each(1, [=] GDR_HD(long long) { tc[nm] = 0; });
    const long long total = Ops::exclusive_scan(tc, tc, nm + 1);
    slots.resize_discard(total);
    scratch.resize_discard(9 * total + 12 * nm);
    // Claims: the crossed triangles and their neighbours outside, highest segment wins.
    dm.mark.zero();
    const ShuffledPrio prio{ms};
    Ops::for_each(nm, [=] GDR_HD(long long r) {
      const int me = static_cast<int>(r);
      const u64 p = prio(me);
      const int b = sg[2 * ms[r] + 1];
      walk_segment(mv, ts, st[r], b, INT_MAX / 8, [&](int t, int le, int re) {
        exec::raise_mark(&mv.mark[t], me, p, prio);
        const int sides[2] = {le, re};
        for (int k : sides) {
          const int o = k >= 0 ? mv.tn[3 * t + k] : -1;
          if (o >= 0) exec::raise_mark(&mv.mark[o / 3], me, p, prio);
        }
      });
    });
    failed.resize_discard(nm);
    int* fl = failed.data();
    Ops::for_each(nm, [=] GDR_HD(long long r) {
      const int me = static_cast<int>(r) + 1;
      const int b = sg[2 * ms[r] + 1];
      bool lost = false;
      walk_segment(mv, ts, st[r], b, INT_MAX / 8, [&](int t, int le, int re) {
        lost = lost || mv.mark[t] != me;
        const int sides[2] = {le, re};
        for (int k : sides) {
          const int o = k >= 0 ? mv.tn[3 * t + k] : -1;
          if (o >= 0) lost = lost || mv.mark[o / 3] != me;
        }
      });
      fl[r] = lost;
    });
    clock.template stop<Space>("segments claim");
    Ops::for_each(nm, InsertSegment{mv, tseg.data(), ms, sg, st, fl, tc, slots.data(),
                                    scratch.data(), err});
    if (error.get(0)) throw Error(Status::InternalError, "parallel CDT: a pseudo-polygon could not be triangulated");
    clock.template stop<Space>("segments insert");
  }

  // Retriangulates the region of a winning segment: its crossed triangles' slots get the
  // constrained Delaunay triangulations of the pseudo-polygons on either side.
  struct InsertSegment {
    MeshView m;
    int* tseg;
    const int* miss;
    const int* seg;
    const int* start;
    const int* failed;
    const int* off;
    int* slots;
    int* scratch;
    int* error;
    GDR_HD void operator()(long long rr) const {
      const int r = static_cast<int>(rr);
      if (failed[r]) return;
      const int s = miss[r];
      const int a = seg[2 * s], b = seg[2 * s + 1];
      const int k = off[r + 1] - off[r];
      int* slot = slots + off[r];
      // Chains (a, ..., b) on each side, the outer link and segment of each chain edge, and
      // a stack of intervals: 9k + 11 ints of the region's 9k + 12.
      int* L = scratch + 9 * off[r] + 12 * r;  // k + 2 vertices at most per side
      int* R = L + (k + 2);
      int* Lo = R + (k + 2);                    // (outer, segment) per chain edge
      int* Ro = Lo + 2 * (k + 1);
      int* stack = Ro + 2 * (k + 1);            // (lo, hi, parent edge code), k + 1 at most
      int nl = 0, nr = 0, nslot = 0;
      L[0] = R[0] = a;
      walk_segment(m, tseg, start[r], b, k + 1, [&](int t, int le, int re) {
        slot[nslot++] = t;
        if (le >= 0) {
          Lo[2 * nl] = m.tn[3 * t + le];
          Lo[2 * nl + 1] = tseg[3 * t + le];
          L[++nl] = m.tv[3 * t + next3(le)];
        }
        if (re >= 0) {
          Ro[2 * nr] = m.tn[3 * t + re];
          Ro[2 * nr + 1] = tseg[3 * t + re];
          R[++nr] = m.tv[3 * t + prev3(re)];
        }
      });
      // A vertex beside the segment whose whole star is crossed (a point 1e-12 off it) puts
      // a spike u, v, u into its side's chain: the chain edges (u, v) and (v, u) then face
      // each other across crossed triangles, not outer ones. They are marked (-2) and linked
      // to each other once their new triangles exist.
      for (int side = 0; side < 2; ++side) {
        int* out = side == 0 ? Lo : Ro;
        const int last = side == 0 ? nl : nr;
        for (int j = 0; j < last; ++j)
          for (int q = 0; q < k && out[2 * j] >= 0; ++q)
            if (out[2 * j] / 3 == slot[q]) out[2 * j] = -2;
      }
      // nl + nr == k + 2 (both chains end at b); each side has nl - 1 and nr - 1 triangles.
      int used = 0;
      int root[2];
      for (int side = 0; side < 2; ++side) {
        const int* V = side == 0 ? L : R;
        int* out = side == 0 ? Lo : Ro;
        const int last = side == 0 ? nl : nr;
        stack[0] = 0, stack[1] = last, stack[2] = -1;
        int depth = 1;
        while (depth > 0) {
          --depth;
          const int lo = stack[3 * depth], hi = stack[3 * depth + 1], parent = stack[3 * depth + 2];
          const int q = empty_circle_apex(m, V, lo, hi);
          if (used >= k) {
            *error = 1;
            return;
          }
          const int t = slot[used++];
          const double o = pred::orient2d(pt(m, V[lo]), pt(m, V[hi]), pt(m, V[q]));
          if (o == 0) {
            *error = 1;
            return;
          }
          // Counter-clockwise (x, y, V[q]) with base (x, y) as edge 2.
          const int x = o > 0 ? V[lo] : V[hi], y = o > 0 ? V[hi] : V[lo];
          m.tv[3 * t] = x;
          m.tv[3 * t + 1] = y;
          m.tv[3 * t + 2] = V[q];
          // Edge 2: the base. Edge opposite V[lo]: (V[hi], V[q]); opposite V[hi]: (V[q], V[lo]).
          const int e_lo = o > 0 ? 1 : 0;  // the edge (V[lo], V[q])
          const int e_hi = o > 0 ? 0 : 1;  // the edge (V[q], V[hi])
          if (parent < 0) {
            root[side] = 3 * t + 2;
            tseg[3 * t + 2] = s;
          } else {
            m.tn[3 * t + 2] = parent;
            m.tn[parent] = 3 * t + 2;
            tseg[3 * t + 2] = -1;
          }
          const int ends[2][3] = {{lo, q, e_lo}, {q, hi, e_hi}};
          for (const auto& iv : ends) {
            const int i0 = iv[0], i1 = iv[1], ed = iv[2];
            if (i1 == i0 + 1) {  // a chain edge: link outwards
              const int ol = out[2 * i0];
              if (ol == -2) {  // a spike's: linked below, meanwhile its new edge is kept
                m.tn[3 * t + ed] = -1;
                out[2 * i0] = -3 - (3 * t + ed);
              } else {
                m.tn[3 * t + ed] = ol;
                if (ol >= 0) m.tn[ol] = 3 * t + ed;
              }
              tseg[3 * t + ed] = out[2 * i0 + 1];
            } else {  // an inner edge: the triangle beyond links back when it is made
              tseg[3 * t + ed] = -1;
              stack[3 * depth] = i0;
              stack[3 * depth + 1] = i1;
              stack[3 * depth + 2] = 3 * t + ed;
              ++depth;
            }
          }
        }
      }
      if (used != k) {
        *error = 1;
        return;
      }
      m.tn[root[0]] = root[1];
      m.tn[root[1]] = root[0];
      // The spikes' chain edges, (u, v) with (v, u) of the same side.
      for (int side = 0; side < 2; ++side) {
        const int* V = side == 0 ? L : R;
        int* out = side == 0 ? Lo : Ro;
        const int last = side == 0 ? nl : nr;
        for (int j = 0; j < last; ++j) {
          if (out[2 * j] > -3) continue;
          int partner = -1;
          for (int j2 = 0; j2 < last && partner < 0; ++j2)
            if (j2 != j && out[2 * j2] <= -3 && V[j2] == V[j + 1] && V[j2 + 1] == V[j]) partner = j2;
          if (partner < 0) {
            *error = 1;
            return;
          }
          const int e1 = -3 - out[2 * j], e2 = -3 - out[2 * partner];
          m.tn[e1] = e2;
          m.tn[e2] = e1;
          out[2 * j] = out[2 * partner] = -1;
        }
      }
    }
  };

  void download(RawCdt& out) {
    dm.tv.to_host(out.tv);
    dm.tn.to_host(out.tn);
    tseg.to_host(out.tseg);
    clock.template stop<Space>("cdt download");
  }
};

}  // namespace gdr::r2d
