// gDP3d refinement loop (paper Algorithm 5), written once for any execution space.
// engine_cpu.cpp instantiates it for OpenMP, engine_cuda.cu for CUDA.
//
// What is gDP3d's own lives here and in kernels.h: restricted facets and interior
// tetrahedra, the facet and cell criteria, splitting points. Filtering (S3), cavities by
// ExpandList with deferment (S2, S5), insertion and compaction (S1) are the steps gQM3d runs
// too: this engine drives them through a qm3d::Engine on the same device mesh rather than a
// copy of them.
#pragma once
#include <algorithm>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "mesh3d/smooth.h"
#include "mesh3d/stall.h"
#include "qm3d/engine.h"
#include "rdt3d/kernels.h"

namespace gdr::rdt3d {

struct EngineParams {
  Criteria criteria;
  qm3d::EngineParams insertion;  // strategies, Steiner cap (max_steiner), iteration cap
  // Sliver removal after refinement, on the tetrahedra inside the surface (mesh3d/smooth.h,
  // kernels.h InteriorCells): stars with a dihedral angle whose sine is below this are
  // smoothed; 0: none.
  double sliver_sin = 0;
  bool manifold = true;  // refine where the surface is not a manifold (Criteria::manifold)
  double domain_six_volume = 0;  // six times the volume the input encloses (stall detector)
};

struct EngineResult {
  int iterations = 0;
  long long inserted = 0;
  bool cap_reached = false;
  bool stalled = false;
  long long manifold_splits = 0;  // facets split by the manifold criterion
  long long non_manifold = 0;     // surface facets at a non-manifold edge or vertex at the end
  long long lost_features = 0;    // feature subsegments that no surface facet holds, at the end
  m3d::SmoothResult slivers;
  std::size_t peak_bytes = 0;
  std::vector<PhaseTime> phases;
};

// The final triangulation (live tetrahedra, compacted), with this mesher's flags.
struct MeshResult {
  std::vector<double> xyz;
  // The points before the sliver pass, where it moved some (else empty): the restricted
  // facets' measures (their duals' circumcentres) are those of the refined triangulation.
  std::vector<double> xyz_refined;
  std::vector<std::uint8_t> ptype;
  std::vector<int> tv, tn, tflag;
  int tets() const { return static_cast<int>(tv.size() / 4); }
};

// The input surface on the host, for the AABB tree.
struct SurfaceInput {
  std::vector<double> xyz;
  std::vector<int> tri;
  HostAabb tree;
  AabbView view() const {
    return AabbView{xyz.data(), tri.data(), tree.order.data(), tree.box.data(), tree.kids.data(),
                    static_cast<int>(tree.kids.size() / 2)};
  }
};

template <class Space>
EngineResult refine_restricted(const m3d::HostTetMesh& mesh, const SurfaceInput& surface,
                               MeshResult& out, const EngineParams& params, const Callbacks& cb);

template <class Space>
struct Engine {
  using Ops = exec::Ops<Space>;
  template <class T>
  using Buf = exec::Buffer<Space, T>;

  const EngineParams& params;
  const Callbacks& cb;
  qm3d::Engine<Space> core;  // the device mesh and the shared insertion steps
  EngineResult res;
  Buf<double> sxyz, sbox;
  Buf<int> stri, sorder, skids;
  Buf<int> deg, counts;  // the manifold criterion's facets per vertex and tallies
  Buf<int> stamp;        // per point: the manifold check due to look at it (MarkNonManifold)
  int epoch = 1;         // the next manifold check's number
  AabbView tree{};
  bool stagnant = false;
  bool features = false;  // the mesh has feature subsegments
  const bool trace = std::getenv("GDR_TRACE") != nullptr;
  m3d::StallDetector stall{true};  // turnover counts as progress (mesh3d/stall.h)
  // Each round refines the facets where the surface pinches; they shrink to the criterion's
  // floor (Criteria::manifold_min2), so the rounds end. The bound is a guard.
  static constexpr int kManifoldRounds = 200;
  int manifold_rounds = 0;
  // collect(): the mesh size at the last collect (-1: renumbered since), the tetrahedra it
  // listed, and the scratch of the collects between full scans.
  static constexpr int kFullEvery = 16;
  int collected_ntet = -1, since_full = 0;
  bool last_collect_full = true;
  Buf<int> prev_tets, cands, cand_keep, cand_scratch, first;
  Buf<exec::u64> cand_keys;
  const bool check_collect = std::getenv("GDR_CHECK_COLLECT") != nullptr;

  Engine(const EngineParams& p, const Callbacks& c) : params(p), cb(c), core(p.insertion, c) {}

  void run(const m3d::HostTetMesh& host, const SurfaceInput& surface, MeshResult& out) {
    exec::memory_counter<Space>().peak = exec::memory_counter<Space>().current;
    const std::size_t mem_base = exec::memory_counter<Space>().current;
    auto& dm = core.dm;
    dm.upload(host);
    features = host.segments() > 0;
    core.counters.resize_discard(decltype(core)::kCounters);
    core.counters.zero();
    sxyz.upload(surface.xyz);
    stri.upload(surface.tri);
    sorder.upload(surface.tree.order);
    sbox.upload(surface.tree.box);
    skids.upload(surface.tree.kids);
    tree = AabbView{sxyz.data(), stri.data(), sorder.data(), sbox.data(), skids.data(),
                    static_cast<int>(surface.tree.kids.size() / 2)};
    core.clock.template stop<Space>("upload");
    classify();
    int idle = 0;
    std::size_t backlog = ~std::size_t(0);
    for (int iter = 0; iter < params.insertion.max_iterations; ++iter) {
      core.check_abort();
      core.clock.restart();
      std::size_t nl = collect();  // line 4: bad facets and bad tetrahedra, one list
      if (nl == 0 && !last_collect_full) nl = collect(true);  // nothing left: make sure
      // The manifold criterion, once every facet and cell meets the others (as CGAL's).
      if (nl == 0 && params.manifold && manifold_rounds < kManifoldRounds && non_manifold(true) > 0) {
        ++manifold_rounds;
        stall.restart();
        nl = collect(true);  // the rounds mark facets anywhere
      }
      if (nl == 0) break;
      const double bad = bad_cell_volume(nl);  // before insertion moves the listed cells
      res.iterations = iter + 1;
      compute_splitting_points(nl, iter);     // line 5
      const std::size_t ns = core.filter(nl);  // S3
      core.grow_cavities(ns);                 // lines 6-7 (S2, S5)
      core.check_abort();
      refuse_cavities();
      const long long won = core.verify_and_number(ns);
      stagnant = !stagnant && won * 50 < static_cast<long long>(ns);
      core.stagnant = stagnant;
      if (won > 0) {
        core.insert(ns, won);  // line 8
        mark_surface_points(ns);
        classify();            // line 9: reclassify the new facets and tetrahedra
      }
      // Idle: nothing inserted, and nothing left as an exception either.
      idle = won > 0 || nl < backlog ? 0 : idle + 1;
      backlog = nl;
      if (idle >= 8) {
        res.stalled = true;
        break;
      }
      // mesh3d/stall.h, as gQM3d: while over 5% of the domain is in bad cells (the interior
      // still made of few large cells), their shrinking volume is progress, even when few
      // points go in per iteration (spot at 2M cells inserted 216 points at its 71st).
      if (stall.stalled(nl, dm.npts, bad > 0.05 * params.domain_six_volume ? bad : 0.0)) {
        res.stalled = true;
        break;
      }
      if (cb.progress)
        cb.progress(0.0, "iteration " + std::to_string(iter + 1) + ": " + std::to_string(nl) +
                             " elements to split, " + std::to_string(won) + " points inserted");
      if (trace)
        std::fprintf(stderr,
                     "gdr-trace rdt iter %d: tets %d, points %d, elements %zu, candidates %zu, won %lld, "
                     "tuples %zu, rounds %d, lost/encroach/touch/star/defer/cap/delaunay %s\n",
                     iter + 1, dm.ntet, dm.npts, nl, ns, won, core.tuples.size(), core.rounds,
                     core.failure_counts().c_str());
      if (core.res.cap_reached) break;
    }
    res.inserted = core.res.inserted;
    res.cap_reached = core.res.cap_reached;
    res.non_manifold = non_manifold(false);
    if (features) {
      counts.resize_discard(1);
      counts.zero();
      Ops::for_each(dm.ntet, CountLostFeatures{dm.view(), params.criteria, counts.data()});
      int n = 0;
      counts.download(&n, 1);
      res.lost_features = n;
    }
    if (params.sliver_sin > 0 && params.criteria.volume) {
      core.check_abort();
      core.clock.restart();
      out.xyz_refined.resize(3 * std::size_t(dm.npts));
      dm.xyz.download(out.xyz_refined.data(), out.xyz_refined.size());
      res.slivers = m3d::smooth_slivers(dm, m3d::SmoothParams{params.sliver_sin}, MeetsCellCriteria{params.criteria},
                                        InteriorCells{});
      if (res.slivers.moves == 0) out.xyz_refined.clear();
      core.clock.template stop<Space>("slivers");
    }
    download(out);
    res.phases = core.res.phases;
    if (trace)
      for (const PhaseTime& p : res.phases) std::fprintf(stderr, "gdr-trace rdt phase %s: %.3f s\n", p.name.c_str(), p.seconds);
    res.peak_bytes = exec::memory_counter<Space>().peak - mem_base;
  }

  // Line 9: restricted faces and interior flags of the new tetrahedra (kFresh).
  void classify() {
    const m3d::TetView mv = core.dm.view();
    // Only the new tetrahedra need looking at: those of the last insertion, or all after a
    // compaction or the upload (two scans of the whole mesh per iteration were about 6% of
    // the refinement of a 650k-tetrahedron slab on two CPU threads).
    const int from = core.fresh_from, n = core.dm.ntet - from;
    if (from == 0) collected_ntet = -1;  // compacted (or uploaded): renumbered
    const ClassifyFresh classify_one{mv, tree, params.criteria};
    Ops::for_each(n, [=] GDR_HD(long long i) { classify_one(from + i); });
    if (params.manifold) stamp.resize(core.dm.npts);  // new points: all corners of new tetrahedra
    const ClearFresh clear_one{mv, params.manifold ? stamp.data() : nullptr, epoch};
    Ops::for_each(n, [=] GDR_HD(long long i) { clear_one(from + i); });
    core.fresh_from = core.dm.ntet;
    core.clock.template stop<Space>("classify");
  }

  // The manifold criterion: the facets at non-manifold edges and vertices of the surface are
  // marked for splitting (mark) or counted. Returns how many were marked, or counted.
  long long non_manifold(bool mark) {
    auto& dm = core.dm;
    deg.resize_discard(dm.npts);
    deg.zero();
    counts.resize_discard(2);
    counts.zero();
    const m3d::TetView mv = dm.view();
    Ops::for_each(dm.ntet, CountSurfaceFacets{mv, params.criteria, deg.data()});
    // Each check with `mark` looks only where the surface changed since the last (stamps).
    Ops::for_each(dm.ntet, MarkNonManifold{mv, params.criteria, deg.data(), counts.data(), mark,
                                           mark ? stamp.data() : nullptr, epoch});
    if (mark) ++epoch;
    int n[2];
    counts.download(n, 2);
    deg.release();
    core.clock.template stop<Space>("manifold");
    if (trace)
      std::fprintf(stderr, "gdr-trace rdt manifold: %d facets at non-manifold edges or vertices, %d marked\n", n[0],
                   n[1]);
    if (!mark) return n[0];
    res.manifold_splits += n[1];
    return n[1];
  }

  // Six times the volume of the bad cells in the list (rounded: a measure of progress only).
  double bad_cell_volume(std::size_t nl) {
    if (!params.criteria.volume || nl == 0) return 0.0;
    const int* l = core.list.data();
    return core.six_volume(static_cast<int>(nl), [=] GDR_HD(int j) { return (l[j] & 15) == kSlotCell; }, l);
  }

  // The elements to split, from a scan of every tetrahedron, or (most iterations) only of
  // those whose elements can have changed since the last collect: the tetrahedra it listed,
  // the new ones and their neighbours (whose shared facet a new tetrahedron classified), and
  // the cavities' (where refusals mark facets and edges to split). Other kernels mark
  // elements elsewhere now and then (a walk's exit face); a full scan every kFullEvery
  // iterations, and before refinement ends, picks those up. Full scans were a third of the
  // refinement of a 650k-tetrahedron slab on one CPU thread (1,416 iterations). On the GPU a
  // full scan is a few tenths of a millisecond: it keeps them.
  std::size_t collect(bool force_full = false) {
    auto& dm = core.dm;
    const bool full = Ops::is_gpu || force_full || collected_ntet < 0 || ++since_full >= kFullEvery ||
                      prev_tets.size() > static_cast<std::size_t>(dm.ntet) / 8;
    std::size_t nl;
    if (full) {
      since_full = 0;
      Ops::for_each(dm.ntet, CountBad{dm.view(), params.criteria});
      int* cnt = dm.aux.data();
      nl = static_cast<std::size_t>(Ops::exclusive_scan(cnt, cnt, dm.ntet));
      core.list.resize_discard(nl);
      if (nl)
        Ops::for_each(dm.ntet, ListBad{dm.view(), params.criteria, core.list.data(), static_cast<int>(nl)});
    } else {
      nl = collect_changed();
      if (check_collect) compare_with_full_scan(nl);
    }
    last_collect_full = full;
    collected_ntet = dm.ntet;
    if (Ops::is_gpu) {
      core.clock.template stop<Space>("collect");
      return nl;
    }
    // The listed tetrahedra, for the next collect (the list itself is scratch until then).
    const int* l = core.list.data();
    const std::size_t n = nl;
    Buf<int>& tmp = cand_scratch;
    const std::size_t np = exec::compact_indices<Space>(
        n, [=] GDR_HD(long long j) { return j == 0 || (l[j] >> 4) != (l[j - 1] >> 4); }, prev_tets, tmp);
    int* pt = prev_tets.data();
    Ops::for_each(np, [=] GDR_HD(long long k) { pt[k] = l[pt[k]] >> 4; });
    core.clock.template stop<Space>("collect");
    return nl;
  }

  // Debugging and tests (GDR_CHECK_COLLECT): the list of the last collect_changed against a
  // full scan's: an InternalError where they differ (an element missed, or out of order).
  void compare_with_full_scan(std::size_t nl) {
    auto& dm = core.dm;
    const std::vector<int> changed = core.list.to_host();
    Ops::for_each(dm.ntet, CountBad{dm.view(), params.criteria});
    int* cnt = dm.aux.data();
    const std::size_t nf = static_cast<std::size_t>(Ops::exclusive_scan(cnt, cnt, dm.ntet));
    Buf<int> full;
    full.resize_discard(nf);
    if (nf) Ops::for_each(dm.ntet, ListBad{dm.view(), params.criteria, full.data(), static_cast<int>(nf)});
    if (full.to_host() != changed)
      throw Error(Status::InternalError, "gDP3d: the collect of changed tetrahedra listed " + std::to_string(nl) +
                                             " elements, a full scan " + std::to_string(nf) + " (or in another order)");
  }

  std::size_t collect_changed() {
    auto& dm = core.dm;
    const m3d::TetView mv = dm.view();
    const int from = collected_ntet, nnew = dm.ntet - from;
    const std::size_t np = prev_tets.size(), nt = core.tuples.size();
    const std::size_t nc = np + 5 * static_cast<std::size_t>(nnew) + nt;
    cands.resize_discard(nc);
    int* c = cands.data();
    const int* pt = prev_tets.data();
    const m3d::CavityTuple* tp = core.tuples.data();
    Ops::for_each(np, [=] GDR_HD(long long k) { c[k] = pt[k]; });
    Ops::for_each(nnew, [=] GDR_HD(long long k) {
      const int t = from + static_cast<int>(k);
      int* o = c + np + 5 * k;
      o[0] = t;
      for (int f = 0; f < 4; ++f) {
        const int nb = mv.tn[4 * t + f];
        o[1 + f] = nb < 0 ? -1 : nb >> 2;
      }
    });
    Ops::for_each(nt, [=] GDR_HD(long long k) {
      c[np + 5 * static_cast<std::size_t>(nnew) + k] = m3d::is_sub_tuple(tp[k]) ? -1 : tp[k].elem;
    });
    // Each tetrahedron once, at its first place (deterministic): first[t] holds the least
    // place naming t during this collect, INT_MAX otherwise.
    if (first.size() < static_cast<std::size_t>(dm.ntet)) {
      const std::size_t old = first.size();
      first.resize(dm.ntet);
      int* fr = first.data();
      Ops::for_each(dm.ntet - old, [=] GDR_HD(long long k) { fr[old + k] = INT_MAX; });
    }
    int* fr = first.data();
    Ops::for_each(nc, [=] GDR_HD(long long k) {
      if (c[k] >= 0) exec::atomic_min(&fr[c[k]], static_cast<int>(k));
    });
    Buf<int>& keep = cand_keep;
    const std::size_t nk = exec::compact_indices<Space>(
        nc, [=] GDR_HD(long long k) { return c[k] >= 0 && fr[c[k]] == static_cast<int>(k); }, keep, cand_scratch);
    int* kp = keep.data();
    Ops::for_each(nk, [=] GDR_HD(long long k) { kp[k] = c[kp[k]]; });
    Ops::for_each(nk, [=] GDR_HD(long long k) { fr[kp[k]] = INT_MAX; });
    // In the order of a full scan (by tetrahedron), so that the list and what follows from
    // it (the shuffled priorities) are the same as the full scan's.
    cand_keys.resize_discard(nk);
    exec::u64* key = cand_keys.data();
    Ops::for_each(nk, [=] GDR_HD(long long k) { key[k] = static_cast<exec::u64>(kp[k]); });
    if (nk > 1) Ops::sort_pairs(key, kp, nk);
    // CountBad and ListBad over the kept tetrahedra.
    cand_scratch.resize_discard(nk);
    int* cnt = cand_scratch.data();
    const Criteria crit = params.criteria;
    Ops::for_each(nk, [=] GDR_HD(long long k) { cnt[k] = mask_entries(collect_mask(mv, crit, kp[k])); });
    const std::size_t nl = static_cast<std::size_t>(Ops::exclusive_scan(cnt, cnt, nk));
    core.list.resize_discard(nl);
    int* list = core.list.data();
    Ops::for_each(nk, [=] GDR_HD(long long k) { list_entries(collect_mask(mv, crit, kp[k]), kp[k], list + cnt[k]); });
    return nl;
  }

  // As gQM3d: when far more elements are bad than can win at once, a random share competes.
  void compute_splitting_points(std::size_t nl, int iter) {
    const double share = std::min(1.0, (core.dm.ntet / 4.0 + 4096.0) / static_cast<double>(nl));
    core.keep_below = static_cast<u64>(share * 4294967296.0);
    core.cand_all.resize_discard(nl);
    Ops::for_each(nl, ComputeSplittingPoints{core.dm.view(), tree, params.criteria, core.list.data(),
                                             core.cand_all.data(), 0x9e3779b9u * static_cast<unsigned>(iter + 1),
                                             core.keep_below, stagnant});
    core.clock.template stop<Space>("split+locate");
  }

  // The cavities that grew are refused where they would take a feature away (KeepFeatures)
  // or spoil a restricted facet (RefuseEncroachingCells).
  void refuse_cavities() {
    const m3d::TetView mv = core.dm.view();
    const std::size_t nt = core.tuples.size();
    if (features)
      Ops::for_each(nt, KeepFeatures{mv, params.criteria, core.cand.data(), core.tuples.data(), core.failed.data()});
    if (params.criteria.volume)
      Ops::for_each(nt, RefuseEncroachingCells{mv, tree, params.criteria, core.cand.data(),
                                               core.tuples.data(), core.failed.data()});
    // The cavities of the points refused here are no longer inserted.
    Ops::for_each(nt, m3d::SetInCavity{mv, core.tuples.data(), core.failed.data(), 0});
    core.clock.template stop<Space>("refuse");
  }

  // Inserted surface centres are surface points (kFacetPoint); the engine wrote kFreePoint.
  void mark_surface_points(std::size_t ns) {
    const m3d::TetView mv = core.dm.view();
    const Candidate* cs = core.cand.data();
    const int* fl = core.failed.data();
    const int* pid = core.point_id.data();
    Ops::for_each(ns, [=] GDR_HD(long long j) {
      if (!fl[j] && cs[j].kind == m3d::kFreeSplit && cs[j].a == kSurfacePoint) mv.ptype[pid[j]] = m3d::kFacetPoint;
    });
  }

  void download(MeshResult& out) {
    core.clock.restart();
    auto& dm = core.dm;
    m3d::compact(dm);
    out.xyz.resize(3 * std::size_t(dm.npts));
    dm.xyz.download(out.xyz.data(), out.xyz.size());
    out.ptype.resize(dm.npts);
    dm.ptype.download(out.ptype.data(), out.ptype.size());
    out.tv.resize(4 * std::size_t(dm.ntet));
    dm.tv.download(out.tv.data(), out.tv.size());
    out.tn.resize(4 * std::size_t(dm.ntet));
    dm.tn.download(out.tn.data(), out.tn.size());
    out.tflag.resize(dm.ntet);
    dm.tflag.download(out.tflag.data(), out.tflag.size());
    core.clock.template stop<Space>("download");
  }
};

template <class Space>
EngineResult refine_restricted(const m3d::HostTetMesh& mesh, const SurfaceInput& surface,
                               MeshResult& out, const EngineParams& params, const Callbacks& cb) {
  Engine<Space> engine(params, cb);
  engine.run(mesh, surface, out);
  return engine.res;
}

}  // namespace gdr::rdt3d
