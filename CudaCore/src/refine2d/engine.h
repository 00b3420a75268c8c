// gDP2d refinement loop (paper Algorithm 1), written once for any execution space.
// engine_cpu.cpp instantiates it for OpenMP, engine_cuda.cu for CUDA.
#pragma once
#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "exec/algorithms.h"
#include "exec/phase_clock.h"
#include "gdr/progress.h"
#include "gdr/refine2d.h"
#include "refine2d/kernels.h"
#include "refine2d/mesh2d.h"

namespace gdr::r2d {

// The paper's design strategies and three of ours, each of which can be switched off to measure
// what it buys (benchmarks only: GDR_DISABLE, see refine2d.cpp).
struct Strategies {
  bool compaction = true;    // S1: compact dead triangles during refinement, not only at the end
  bool filtering = true;     // S3: one splitting point per triangle before growing cavities
  bool irregular = true;     // S4: encroached subsegments and bad triangles in one list
  bool deferment = true;     // S5: defer cavities still growing after a few rounds
  bool touching = true;      // cavities that touch go in together when the mesh stays Delaunay
  bool block_rounds = true;  // small ExpandList windows run their rounds inside one GPU block
  bool grid_rounds = true;   // large ExpandList windows run their rounds in one grid-wide launch
  bool worst_first = true;   // triangles bad by shape alone smallest first, not larger first
  bool graded = true;        // bad triangles wait for much smaller bad triangles nearby
  bool work_list = true;     // CPU: collect from the last list and the changed triangles
  bool cdt_assembly = true;  // the parallel CDT assembled where it ran (cdt_assembly.h), not on the host
  bool one_at_a_time = true; // CPU on few threads: points inserted one at a time (Engine::one_at_a_time)
  bool petal_sinks = true;   // off-centres: larger empty circles in the petal first (kernels.h, move_to_petal_sink)
};

struct EngineParams {
  Criteria criteria;
  std::vector<double> region_area2;  // Criteria::region_area2 on the host (empty: none)
  long long max_steiner = -1;  // -1: unlimited
  bool one_at_a_time = false;  // CPU on few threads: Engine::one_at_a_time instead of the parallel iteration
  int max_iterations = 100000;
  Strategies strategies;
};

struct EngineResult {
  int iterations = 0;
  long long inserted = 0;
  bool cap_reached = false;
  bool stalled = false;
  std::size_t stuck = 0;  // when stalled: bad triangles and encroached subsegments left
  // Stalled because most of the mesh is bad next to small input angles (see
  // Engine::small_angle_cascade): `stuck` counts those triangles, `live` all of them.
  bool small_angle_cascade = false;
  std::size_t live = 0;
  bool slow_cascade = false;  // stalled by Engine::slow_cascade: `stuck` bad elements left
  bool starved = false;       // stalled by Engine::starved: `stuck` bad elements left
  std::size_t peak_bytes = 0;
  std::vector<PhaseTime> phases;
};

// Uploads `mesh`, refines it and downloads the result into `out`.
template <class Space>
EngineResult refine_mesh(const HostMesh& mesh, MeshResult& out, const EngineParams& params,
                         const Callbacks& cb);

namespace detail {

// In-place compaction: live triangles from the tail move into the dead slots of the head,
// so no second copy of the mesh is ever held (device memory per element). `renumber` is
// given the move (MoveTriangles::destination) to renumber other references to triangles.
struct NoTriangleRefs {
  void operator()(const MoveTriangles&) const {}
};
template <class Space, class Renumber = NoTriangleRefs>
void compact_triangles(DeviceMesh<Space>& dm, Renumber renumber = {}) {
  using Ops = exec::Ops<Space>;
  const int n = dm.ntri;
  int* rank = dm.aux.data();  // free between iterations
  const int* flag = dm.tflag.data();
  Ops::for_each(n, [=] GDR_HD(long long t) { rank[t] = (flag[t] & kDead) ? 0 : 1; });
  const int live = static_cast<int>(Ops::exclusive_scan(rank, rank, n));
  exec::Buffer<Space, int> holes(std::size_t(n - live) + 1);
  int* hole = holes.data();
  Ops::for_each(live, [=] GDR_HD(long long t) {
    if (flag[t] & kDead) hole[t - rank[t]] = static_cast<int>(t);
  });
  const int base = live < n ? dm.aux.get(live) : live;  // live triangles in the head
  Ops::for_each(n - live, MoveTriangles{dm.view(), hole, live, base});
  Ops::for_each(n - live, FixBackLinks{dm.view(), hole, live, base});
  renumber(MoveTriangles{dm.view(), hole, live, base});
  dm.ntri = live;
  dm.tv.resize(3 * std::size_t(live));
  dm.tn.resize(3 * std::size_t(live));
  dm.tflag.resize(live);
  dm.mark.resize(live);
  dm.aux.resize(live);
}

}  // namespace detail

// One refinement run. run() is the paper's Algorithm 1; each method is one of its lines.
// (Public members only: nvcc's device lambdas may not live in private member functions.)
template <class Space>
struct Engine {
  using Ops = exec::Ops<Space>;
  template <class T>
  using Buf = exec::Buffer<Space, T>;

  const EngineParams& params;
  const Callbacks& cb;
  EngineResult res;
  exec::PhaseClock clock{res.phases};
  DeviceMesh<Space> dm;
  Buf<int> list, work, failed, point_id, count, error;
  Buf<Candidate> cand_all, cand;  // all splitting points, then the filtered ones
  Buf<CavityTuple> tuples;
  bool allow_deferment = true;
  long long dead = 0;  // dead triangles since the last compaction
  int rounds = 0;      // ExpandList rounds of the last cavity phase
  // At most this many bad elements compete in the next iteration (located, filtered, grown):
  // lowered when few of the last competitors won, raised again as more win (see contention()).
  std::size_t compete_cap = SIZE_MAX;
  u64 compete_below = u64(1) << 32;  // the random-id threshold of this iteration's cap
  const bool trace = std::getenv("GDR_TRACE") != nullptr;  // one line per iteration on stderr

  Buf<double> region_bounds;
  Criteria crit;  // params.criteria with its region bounds in the run's memory

  Engine(const EngineParams& p, const Callbacks& c) : params(p), cb(c), crit(p.criteria) {
    if (!p.region_area2.empty()) {
      region_bounds.upload(p.region_area2);
      crit.region_area2 = region_bounds.data();
    }
  }

  bool has_regions = false;

  void run(const HostMesh& host, MeshResult& out) {
    has_regions = !host.tregion.empty();
    exec::memory_counter<Space>().peak = exec::memory_counter<Space>().current;
    const std::size_t mem_base = exec::memory_counter<Space>().current;
    dm.upload(host);
    clock.template stop<Space>("upload");
    refine(mem_base, out);
  }
  // A mesh already in the engine's memory (cdt_assembly.h: the CDT assembled there).
  void run(DeviceMesh<Space>&& mesh, bool regions, MeshResult& out) {
    has_regions = regions;
    dm = std::move(mesh);
    exec::memory_counter<Space>().peak = exec::memory_counter<Space>().current;
    refine(exec::memory_counter<Space>().current - dm.bytes(), out);
  }

  void refine(std::size_t mem_base, MeshResult& out) {
    error.resize_discard(1);
    error.zero();
    int idle = 0;
    for (int iter = 0; iter < params.max_iterations; ++iter) {
      if (cb.abort && cb.abort()) throw Error(Status::Aborted, "refinement aborted by the caller");
      clock.restart();
      const std::size_t nl = collect();                 // line 3
      if (nl == 0) break;                               // line 9
      res.iterations = iter + 1;
      std::size_t ns = 0;
      long long won = 0;
      if (params.one_at_a_time && !handed_over && iter < kOneAtATimeSweeps) {
        won = one_at_a_time(nl, iter);                  // lines 4-8, a point at a time
      } else {
        compute_splitting_points(nl, iter);             // lines 5-6
        ns = filter(nl);                                // line 7 (S3)
        grow_cavities(ns);                              // line 7 (S2, S5)
        won = verify_and_number(ns);
        contention(ns, won);
        if (won > 0) insert(ns, won);                   // line 8
      }
      graded_now = won > 0;
      if (won > 0) {
        idle = 0;
      } else if (++idle >= 3) {
        res.stalled = true;
        res.stuck = nl;
        break;
      }
      if (cb.progress)
        cb.progress(0.0, "iteration " + std::to_string(iter + 1) + ": " + std::to_string(nl) +
                             " bad elements, " + std::to_string(won) + " points inserted");
      if (trace)
        std::fprintf(stderr,
                     "gdr-trace iter %d: triangles %d, bad %zu, candidates %zu, won %lld, "
                     "rounds %d, tuples %zu, MB %.1f (peak %.1f)\n",
                     iter + 1, dm.ntri, nl, ns, won, rounds, tuples.size(),
                     exec::memory_counter<Space>().current / 1048576.0,
                     exec::memory_counter<Space>().peak / 1048576.0);
      if (res.cap_reached) break;
      if (won > 0 && small_angle_cascade()) break;
      if (slow_cascade(iter + 1, nl)) break;
      if (starved(iter, nl, won)) break;
    }
    download(out);
    res.peak_bytes = exec::memory_counter<Space>().peak - mem_base;
  }

  // Small-angle cascade (issue 9): in a needle whose long sides meet at 1e-21 rad (a base
  // 1e-6 wide under an apex 1e15 away), every triangle is a sliver between the sides, bad but
  // left by the small-angle rule, and refinement only adds more: 1M points, all of them in
  // such triangles, before the automatic cap stopped it (10-20 s on 2 cores). Each time the
  // mesh has doubled beyond 2^17 triangles, the triangles left bad next to small input angles
  // are counted; when they are most of the mesh, refinement stops (a stall: the mesh is valid
  // and the bad triangles are reported). Meshes of inputs with small angles keep them near
  // those angles: 0.1-0.4% of the maps' triangles, 5% of the fans' of fuzz2d.
  static constexpr int kCascadeCheckFrom = 1 << 17;
  int next_cascade_check = kCascadeCheckFrom;
  bool small_angle_cascade() {
    if (dm.ntri < next_cascade_check || params.criteria.sin2_min_angle <= 0) return false;
    next_cascade_check = 2 * dm.ntri;
    const MeshView mv = dm.view();
    const Criteria criteria = crit;
    int* cnt = dm.aux.data();  // free between iterations
    Ops::for_each(dm.ntri, [=] GDR_HD(long long t) {
      const int f = mv.tflag[t];
      cnt[t] = (f & kDead) ? 0 : (classify_triangle(mv, static_cast<int>(t), criteria) == kBadProtected ? 2 : 1);
    });
    // Live triangles and protected ones in one scan: 1 per live triangle, 2 per protected.
    const long long sum = Ops::exclusive_scan(cnt, cnt, dm.ntri);
    Ops::for_each(dm.ntri, [=] GDR_HD(long long t) { cnt[t] = (mv.tflag[t] & kDead) ? 0 : 1; });
    const long long live = Ops::exclusive_scan(cnt, cnt, dm.ntri);
    const long long protected_bad = sum - live;
    clock.template stop<Space>("collect");
    if (trace)
      std::fprintf(stderr, "gdr-trace small-angle check: %lld of %lld triangles bad next to small angles\n",
                   protected_bad, live);
    if (2 * protected_bad <= live) return false;
    res.stalled = res.small_angle_cascade = true;
    res.stuck = static_cast<std::size_t>(protected_bad);
    res.live = static_cast<std::size_t>(live);
    return true;
  }

  // Slow cascades (issue 9): segments from one vertex at 1e-12 rad whose ends lie 1e-12
  // apart, at 33 degrees with diametral circles, kept about 100 elements bad for thousands
  // of iterations, 50 points each (400k triangles after 3,900 iterations, minutes on 2
  // cores, far below the automatic cap). Refinement that converges halves its bad elements
  // again and again; the runs measured end within 100-610 iterations (the maps at 20-30
  // degrees within 110, fuzz2d's fans at 33 within 610). From iteration 1024 on, after two
  // windows of 256 iterations in a row whose fewest bad elements are more than half of the
  // window before's, refinement stops (a stall: the mesh is valid).
  static constexpr int kCascadeWindow = 256, kCascadeFrom = 1024;
  std::size_t window_min = SIZE_MAX, last_window_min = SIZE_MAX;
  int flat_windows = 0;
  bool slow_cascade(int iterations, std::size_t nl) {
    window_min = std::min(window_min, nl);
    if (iterations % kCascadeWindow) return false;
    flat_windows = iterations > kCascadeFrom && 2 * window_min > last_window_min ? flat_windows + 1 : 0;
    last_window_min = window_min;
    window_min = SIZE_MAX;
    if (flat_windows < 2) return false;
    res.stalled = res.slow_cascade = true;
    res.stuck = nl;
    return true;
  }

  // Starved cascades: four segments from one vertex at 1e-15 to 3e-7 rad (fuzz2d seed
  // 43001194) kept 1.7M elements bad while 2-6 points went in per iteration, 0.15 s each on
  // two cores: the slow-cascade rule would have waited 1,536 iterations. When over the last
  // 32 iterations the points inserted are under a hundredth of the fewest bad elements and
  // those did not shrink by a fiftieth, refinement stops (a stall: the mesh is valid).
  // Refinement that converges inserts a large share of its backlog each iteration.
  static constexpr int kStarveWindow = 32;
  std::size_t starve_nl[kStarveWindow] = {};
  long long starve_won[kStarveWindow] = {};
  bool starved(int iter, std::size_t nl, long long won) {
    const int k = iter % kStarveWindow;
    const std::size_t oldest = starve_nl[k];  // kStarveWindow iterations ago, once filled
    starve_nl[k] = nl;
    starve_won[k] = won;
    if (iter < kStarveWindow) return false;
    std::size_t fewest = nl;
    long long inserted = 0;
    for (int j = 0; j < kStarveWindow; ++j) {
      fewest = std::min(fewest, starve_nl[j]);
      inserted += starve_won[j];
    }
    if (100 * inserted >= static_cast<long long>(fewest) || 50 * nl <= 49 * oldest) return false;
    res.stalled = res.starved = true;
    res.stuck = nl;
    return true;
  }

  // Line 3: encroached subsegments and bad triangles in one list (S1, S4). Each triangle
  // keeps a 4-bit mask in its flags and its entry count in aux; the in-place scan of the
  // counts places the entries (t*4 + slot), so collecting needs no arrays of its own.
  std::size_t collect() {
    std::size_t nl = 0;
    const bool listed = collect_listed(nl);
    if (!listed) {
      Ops::for_each(dm.ntri, CollectMask{dm.view(), crit});
      int* cnt = dm.aux.data();
      nl = static_cast<std::size_t>(Ops::exclusive_scan(cnt, cnt, dm.ntri));
      list.resize_discard(nl);
      if (nl) Ops::for_each(dm.ntri, ExpandElements{dm.view(), list.data()});
    }
    if constexpr (!Ops::is_gpu)
      if (params.strategies.work_list) watch_list(nl);
    clock.template stop<Space>(listed ? "collect, listed" : "collect");
    return nl;
  }

  // The CPU's work list. Late iterations split a few hundred elements of a mesh of millions:
  // one thread spent a quarter of its refinement of the generated 1M-segment map in 74 such
  // iterations of 86, mostly in passes over the whole mesh. A triangle's elements are all
  // in its flags and can only appear when it is new or when an edge of it is flagged for
  // splitting (logged: TouchLog), so the triangles of the last list, the new ones (appended
  // since: [listed_below, ntri)) and the logged ones hold every element. Sorted, they give
  // the same list as the whole-mesh scan, in the same order: the same mesh (one thread:
  // the generated 1M-segment map's collect 2.05 -> 0.75 s of 15 s). The GPU scans the whole
  // mesh (three launches).
  Buf<int> watch, pending, touched, touched_n;
  int listed_below = 0;  // 0: scan the whole mesh next (first iteration, after compaction)
  TouchLog touch_log() {
    if (Ops::is_gpu || !listed_below) return {};  // the next collect scans the whole mesh
    return {touched.data(), touched_n.data(), static_cast<int>(touched.size())};
  }
  bool collect_listed(std::size_t& nl) {
    if constexpr (Ops::is_gpu) {
      return false;
    } else {
      const std::size_t nw = watch.size(), nnew = dm.ntri - listed_below;
      const std::size_t nt = listed_below ? static_cast<std::size_t>(touched_n.get(0)) : 0;
      const std::size_t n = nw + nnew + nt;
      // Past an eighth of the mesh the scan costs less than the sort.
      if (!listed_below || nt > touched.size() || 8 * n > static_cast<std::size_t>(dm.ntri)) return false;
      pending.resize_discard(n);
      int* p = pending.data();
      std::copy(watch.data(), watch.data() + nw, p);
      for (std::size_t i = 0; i < nnew; ++i) p[nw + i] = listed_below + static_cast<int>(i);
      std::copy(touched.data(), touched.data() + nt, p + nw + nnew);
      std::sort(p + nw + nnew, p + n);
      std::inplace_merge(p, p + nw + nnew, p + n);
      const std::size_t m = static_cast<std::size_t>(std::unique(p, p + n) - p);
      count.resize_discard(m);
      int* cnt = count.data();
      Ops::for_each(m, CollectMaskAt{dm.view(), crit, p, cnt});
      nl = static_cast<std::size_t>(Ops::exclusive_scan(cnt, cnt, m));
      list.resize_discard(nl);
      if (nl) Ops::for_each(m, ExpandElementsAt{dm.view(), p, cnt, list.data()});
      return true;
    }
  }
  // The triangles of the list, once each, and a fresh log for this iteration's touches;
  // nothing while the list is long (the next collect scans the whole mesh anyway).
  void watch_list(std::size_t nl) {
    listed_below = 0;
    watch.resize_discard(0);
    if (8 * nl > static_cast<std::size_t>(dm.ntri)) return;
    const int* l = list.data();
    const std::size_t nw = exec::compact_indices<Space>(
        nl, [=] GDR_HD(long long j) { return j == 0 || (l[j] >> 2) != (l[j - 1] >> 2); }, watch, count);
    int* w = watch.data();
    Ops::for_each(nw, [=] GDR_HD(long long i) { w[i] = l[w[i]] >> 2; });
    listed_below = dm.ntri;
    touched.resize_discard(2 * nl + 4096);
    touched_n.resize_discard(1);
    touched_n.zero();
  }

  // Lines 5-6: splitting points, priorities, point location. Under a competition cap, only
  // a random share of the bad elements (by the random id of their priority) is located.
  // Walks longer than kShortWalk steps are few in most meshes; where many points are far from
  // their triangles (all n triangles of cocircular points propose the same centre, and walk
  // to it across the mesh: 2.6 s of 6 for 79k points), they are far from winning too, and
  // only a random share of them, at most kMinCompete or ntri/64, walks on.
  static constexpr int kShortWalk = 64;
  void compute_splitting_points(std::size_t nl, int iter) {
    cand_all.resize_discard(nl);
    compete_below = compete_cap >= nl
                        ? u64(1) << 32
                        : static_cast<u64>(static_cast<double>(compete_cap) / nl * 4294967296.0);
    ComputeSplittingPoints step{dm.view(),
                                crit,
                                list.data(),
                                cand_all.data(),
                                0x9e3779b9u * static_cast<unsigned>(iter + 1),
                                params.strategies.worst_first,
                                compete_below,
                                kShortWalk,
                                false,
                                0,
                                near_levels(nl),
                                touch_log()};
    Ops::for_each(nl, step);
    const Candidate* ca = cand_all.data();
    const std::size_t nfar = exec::compact_indices<Space>(
        nl, [=] GDR_HD(long long j) { return ca[j].kind == kFarWalk; }, work, count);
    if (nfar) {
      const double far_cap = std::max<double>(kMinCompete, dm.ntri / 64.0);
      step.far_only = true;
      step.max_steps = params.criteria.step_limit;
      step.far_below = nfar <= far_cap ? u64(1) << 32
                                       : static_cast<u64>(far_cap / nfar * compete_below);
      Ops::for_each(nl, step);
    }
    clock.template stop<Space>("split+locate");
  }

  // Graded order (kernels.h, kGradeWindowShape): the least level of the triangles bad by
  // their shape within kGradeHops of each triangle, in aux. Hops go from a frontier while it
  // is small (late iterations: few bad triangles in a large mesh; on the CPU 25-35% less
  // refinement time on the maps), then over the whole mesh (mark as the second buffer; aux
  // and mark are free until the filter). The GPU never waits for a frontier's size (reading
  // it back each hop cost 0.25 ms per iteration on the maps): each hop is launched over a
  // bound of it and reads the size on the device, and so are the passes over the whole mesh,
  // which do nothing where the frontiers did all the hops. Off for one iteration after one
  // that inserted nothing, so that a bad triangle that cannot be split never holds its
  // neighbours back for good.
  static constexpr int kGradeHops = 6;
  bool graded_now = true;
  Buf<LevelAt> front, pushed;
  Buf<int> front_size;
  const int* near_levels(std::size_t nl) {
    if (!params.strategies.graded || !graded_now) return nullptr;
    int* const level = dm.aux.data();
    Ops::for_each(dm.ntri, [=] GDR_HD(long long t) { level[t] = kNoLevel; });
    const int cap = std::max(1024, dm.ntri / 8);
    front_size.resize_discard(kGradeHops);
    front_size.zero();
    const Frontiers fr{front_size.data(), cap};
    int done = -1;  // hops done in full; -1: on the device
    if constexpr (Ops::is_gpu) {
      front.resize_discard(cap);
      pushed.resize_discard(cap);
      Ops::for_each(nl, SeedLevels{dm.view(), crit, list.data(), level, front.data(), fr});
      std::size_t bound = std::min<std::size_t>(nl, cap);
      for (int hop = 1; hop <= kGradeHops; ++hop) {
        Ops::for_each(bound, PushLevels{dm.view(), front.data(), pushed.data(), level, fr, hop, kGradeHops});
        front.swap(pushed);
        bound = std::min<std::size_t>(3 * bound, cap);
      }
    } else {
      done = hops_by_compaction(nl, level, cap);
    }
    front.release();
    pushed.release();
    if (done == kGradeHops) return level;
    int* const other = dm.mark.data();
    for (int pass = std::max(done, 0); pass < kGradeHops; ++pass)
      Ops::for_each(dm.ntri, SpreadLevels{dm.view(), level, other, fr, pass, kGradeHops});
    Ops::for_each(dm.ntri, TakeSpreadLevels{level, other, fr, kGradeHops});
    return level;
  }

  // The CPU's hops: each frontier written to fixed slots (three per entry) and compacted.
  // Appending to one counter shared by all threads did not scale: PushLevels took 4.5% of one
  // thread's refinement of the generated 1M-segment map and 10.6% of two threads'; on 16
  // threads split+locate ran 3x faster than on one, the other phases 11-15x. The levels are
  // the same (the least within the hops does not depend on the order of the atomics), and on
  // one thread so are the frontiers and their order. Returns the hops done in full and writes
  // frontier sizes that say so, for the passes (Frontiers::hops_done).
  int hops_by_compaction(std::size_t nl, int* level, int cap) {
    const MeshView mv = dm.view();
    const Criteria c = crit;
    const int* lst = list.data();
    front.resize_discard(nl);
    LevelAt* seed = front.data();
    Ops::for_each(nl, [=] GDR_HD(long long j) {
      const int e = lst[j], l = seed_level(mv, c, e);
      seed[j] = LevelAt{-1, 0};
      if (l == kNoLevel) return;
      level[e >> 2] = l;
      seed[j] = LevelAt{e >> 2, l};
    });
    const auto entry = [] GDR_HD(const LevelAt& f) { return f.tri >= 0; };
    std::size_t n = exec::keep_if(front, entry, work);
    int done = 0;
    for (int hop = 1; hop <= kGradeHops; ++hop) {
      if (n == 0) return kGradeHops;  // nothing left to pass on
      if (n > static_cast<std::size_t>(cap)) break;  // overfull: the passes take over
      pushed.resize_discard(3 * n);
      const LevelAt* in = front.data();
      LevelAt* out = pushed.data();
      const bool last = hop == kGradeHops;
      Ops::for_each(n, [=] GDR_HD(long long i) {
        const LevelAt f = in[i];
        for (int k = 0; k < 3; ++k) {
          const int nb = mv.tn[3 * f.tri + k];
          const bool lowered = nb >= 0 && f.level < exec::atomic_min(&level[nb / 3], f.level);
          out[3 * i + k] = lowered && !last ? LevelAt{nb / 3, f.level} : LevelAt{-1, 0};
        }
      });
      done = hop;
      front.swap(pushed);
      n = last ? 0 : exec::keep_if(front, entry, work);
    }
    int* size = front_size.data();  // host memory
    if (done < kGradeHops) size[done] = cap + 1;
    return done;
  }

  // Line 7, first part (S3): one splitting point per triangle, by priority marks.
  // When far more elements are bad than can win at once (the first iterations on a coarse
  // CDT), only a random share of them competes, at most a quarter of the triangle count:
  // the rest would mostly lose anyway, after growing cavities that cost time and memory.
  std::size_t filter(std::size_t nl) {
    dm.mark.zero();
    const Strategies& sg = params.strategies;
    const Candidate* ca = cand_all.data();
    const int* mk = dm.mark.data();
    // Without S4, subsegments are split in iterations of their own, before any triangle.
    std::size_t pool = nl;
    bool segments_only = false;
    if (!sg.irregular) {
      const std::size_t nseg = exec::compact_indices<Space>(
          nl, [=] GDR_HD(long long j) { return ca[j].kind == 0; }, list, count);
      segments_only = nseg > 0;
      if (segments_only) pool = nseg;
    }
    const double share = std::min(1.0, (dm.ntri / 4.0 + 4096.0) / static_cast<double>(pool));
    const u64 keep_below = std::min(compete_below, static_cast<u64>(share * 4294967296.0));
    if (sg.filtering)
      Ops::for_each(nl, ClaimStart{dm.view(), cand_all.data(), keep_below, segments_only});
    const bool filtering = sg.filtering;
    const std::size_t ns = exec::compact_indices<Space>(
        nl,
        [=] GDR_HD(long long j) {
          const Candidate& c = ca[j];
          if (c.kind < 0 || (segments_only && c.kind != 0)) return false;
          return filtering ? mk[c.start] == j + 1 : exec::priority_id(c.prio) < keep_below;
        },
        list, count);
    cand.resize_discard(ns);
    Candidate* cs = cand.data();
    const int* sel = list.data();
    Ops::for_each(ns, [=] GDR_HD(long long j) { cs[j] = ca[sel[j]]; });
    cand_all.release();  // device memory: only the survivors are needed from here on
    list.release();
    dm.mark.zero();  // survivors now claim their cavities from scratch
    clock.template stop<Space>("filter");
    return ns;
  }

  // Line 7, second part: cavities by ExpandList (S2), stragglers deferred (S5). Starts from
  // the triangle holding the point or, for a subsegment, the one on the point's side of it
  // (split_start).
  void grow_cavities(std::size_t ns) {
    failed.resize_discard(ns);
    failed.zero();
    const Candidate* cs = cand.data();
    const MeshView mv = dm.view();
    tuples.resize_discard(ns);
    CavityTuple* tp = tuples.data();
    Ops::for_each(ns, [=] GDR_HD(long long j) {
      const Candidate& c = cs[j];
      tp[j] = CavityTuple{static_cast<int>(j), c.kind == 0 ? split_start(mv, c) : c.start, kForceIn};
    });
    exec::ExpandListLimits lim;
    // Under a competition cap (contention()) big cavities are the rule, not stragglers: a
    // deferred iteration would only throw away the growth of the few points that can win.
    if (allow_deferment && params.strategies.deferment && compete_cap == SIZE_MAX) {
      lim.defer_after_rounds = 16;
      lim.defer_below = ns / 64 + 32;
    }
    lim.block_rounds = params.strategies.block_rounds;
    lim.grid_rounds = params.strategies.grid_rounds;
    const exec::ExpandListResult er = exec::expand_list<Space, 3>(
        tuples, ns, GrowCavity{dm.view(), cand.data(), failed.data(), params.criteria.lens_cos2, touch_log()},
        lim);
    // Deferred cavities must finish next time, or big ones would block their neighbourhood
    // forever. Points whose cavity is still growing give up this iteration.
    allow_deferment = !er.deferred();
    rounds = er.rounds;
    if (er.deferred()) {
      CavityTuple* pend = tuples.data() + er.pending_begin;
      int* f = failed.data();
      Ops::for_each(er.size - er.pending_begin, [=] GDR_HD(long long i) { f[pend[i].pt] = 1; });
    }
    tuples.resize(er.size);
    clock.template stop<Space>("cavity");
  }

  // Surviving marks and exact checks decide the winners; they get vertex numbers. The
  // Steiner cap may drop any of them: a dropped point's cavity stays as it was, and its
  // triangles lie outside the circles of the neighbouring winners. Returns how many won.
  long long verify_and_number(std::size_t ns) {
    const std::size_t nt = tuples.size();
    Ops::for_each(nt, VerifyClaims{dm.view(), cand.data(), tuples.data(), failed.data(),
                                   params.strategies.touching});
    Ops::for_each(nt, SetInCavity{dm.view(), cand.data(), tuples.data(), failed.data(), 1});
    Ops::for_each(nt, CheckCavity{dm.view(), cand.data(), tuples.data(), failed.data()});
    Ops::for_each(nt, SetInCavity{dm.view(), cand.data(), tuples.data(), failed.data(), 0});
    point_id.resize_discard(ns);
    const int* fc = failed.data();
    int* pid = point_id.data();
    Ops::for_each(ns, [=] GDR_HD(long long j) { pid[j] = fc[j] ? 0 : 1; });
    long long won = Ops::exclusive_scan(pid, pid, ns);
    if (params.max_steiner >= 0 && res.inserted + won > params.max_steiner) {
      const int keep = static_cast<int>(params.max_steiner - res.inserted);
      int* f = failed.data();
      Ops::for_each(ns, [=] GDR_HD(long long j) {
        if (!f[j] && pid[j] >= keep) f[j] = 1;
      });
      Ops::for_each(nt, SetInCavity{dm.view(), cand.data(), tuples.data(), failed.data(), 0});
      won = keep;
      res.cap_reached = true;
    }
    clock.template stop<Space>("verify");
    return won;
  }

  // Contention: when few competitors win, most grew cavities (and walked to their points)
  // for nothing. Cocircular inputs are the extreme: after the centre goes in, the mesh is a
  // fan of n slivers whose circumcircles each hold the points of the slivers within about
  // 60 degrees, so only a handful of the n candidates can win an iteration, each after
  // growing a cavity of n/3 triangles, and losers walk and grow too: quadratic work per
  // iteration (a 100k-point circle took 48 s on 2 cores). When fewer than 1 in 16 won, the
  // next iteration lets only 16 times as many compete as won (at least kMinCompete, a random
  // share, so the winners are as spread as before); while at least 1 in 16 wins, the cap
  // grows fourfold per iteration, back to no cap. Inputs where many win are never capped.
  static constexpr std::size_t kMinCompete = 1024;
  void contention(std::size_t ns, long long won) {
    if (static_cast<std::size_t>(won) * 16 < ns)
      compete_cap = std::max<std::size_t>(kMinCompete, 16 * static_cast<std::size_t>(won));
    else if (compete_cap != SIZE_MAX)
      compete_cap = compete_cap > SIZE_MAX / 4 ? SIZE_MAX : 4 * compete_cap;
  }

  // One point at a time (the CPU on up to 4 threads, issue 14). The parallel iteration computes
  // a point for every bad element and grows a cavity for every candidate, but only the points
  // whose cavities win go in: on one thread, the generated 1M-segment map's 508k Steiner
  // points cost 4.9M splitting points and walks and 2.6M cavities over 81 iterations (16 s).
  // Here the elements wait in one priority queue (key(): subsegments first, larger first;
  // then triangles too big for the size bounds, larger first; then those bad by their shape,
  // smallest first, which the parallel iteration's graded order only approximates): the
  // first gets its point, the point goes in at once (the same kernels, on one candidate and
  // its own tuples), and the elements of its new triangles join the queue. A free point
  // that encroaches a subsegment flags it, as in the parallel iteration, and the subsegment
  // joins the queue ahead of the rest; the triangle waits for the next sweep.
  // A sweep ends when the queue is empty or the mesh has doubled (and grown by kSweepGrowth
  // triangles), so that the cascade checks run between sweeps; a sweep whose points for
  // subsegments and bad shapes outnumber 8 times its listed elements and points for size,
  // plus 1024, is a cascade, and the parallel iteration's graded order takes over, as it
  // does after kOneAtATimeSweeps sweeps. Returns the points inserted.
  static constexpr int kOneAtATimeSweeps = 8, kSweepGrowth = 1 << 16;
  bool handed_over = false;
  // The queue: a first-come-first-served bucket per key, the highest key first. Keys take a
  // few hundred values at a time, so buckets cost less than a heap of the elements (whose
  // pops were 5% of one thread's run on the 1M map); the order is the same.
  struct Bucket {
    std::vector<int> e;  // elements: triangle * 4 + slot
    std::size_t head = 0;
  };
  std::map<unsigned, Bucket> queue;
  std::size_t waiting = 0;
  unsigned salt = 0;
  // The queue's key: the element's priority class and size (first come first served among
  // equals; kernels.h, shape_class).
  static unsigned key(u64 prio) { return static_cast<unsigned>(prio >> 32); }
  void enqueue(u64 prio, int e) {
    queue[key(prio)].e.push_back(e);
    ++waiting;
  }
  bool dequeue(int& e) {
    if (queue.empty()) return false;
    const auto last = std::prev(queue.end());
    Bucket& b = last->second;
    e = b.e[b.head++];
    if (b.head == b.e.size()) queue.erase(last);
    --waiting;
    return true;
  }
  // Element e's priority (false: it has no splitting point), its point computed only where
  // the order needs its size.
  bool element_priority(const MeshView& mv, int e, u64& prio) const {
    if ((e & 3) == 3 && params.strategies.worst_first && !too_big(mv, e >> 2, crit)) {
      prio = exec::make_priority(kClassShape, shape_class(mv, e >> 2), 0);
      return true;
    }
    Candidate c{};
    ComputeSplittingPoints{mv, crit, &e, &c, salt, params.strategies.worst_first, u64(1) << 32, 0, false, 0,
                           nullptr, {}}(0);
    prio = c.prio;
    return c.kind != -1;
  }
  // The elements of triangle t (slots in `slots`), queued with their priorities.
  void enqueue_elements(const MeshView& mv, int t, int slots) {
    if (!collect_count(mv, crit, t)) return;
    const int mask = collect_mask(mv.tflag[t]) & slots;
    for (int k = 0; k < 4; ++k) {
      if (!(mask & (1 << k))) continue;
      u64 prio;
      if (element_priority(mv, 4 * t + k, prio)) enqueue(prio, 4 * t + k);
    }
  }
  std::vector<CavityTuple> seq_tuples;  // insert_one's scratch
  std::vector<int> seq_base;
  long long one_at_a_time(std::size_t nl, int iter) {
    if constexpr (Ops::is_gpu) {
      return 0;
    } else {
      salt = 0x9e3779b9u * static_cast<unsigned>(iter + 1);
      // The listed elements' priorities, all threads.
      cand_all.resize_discard(nl);
      {
        Candidate* ca = cand_all.data();
        const int* lst = list.data();
        const MeshView mv = dm.view();
        Ops::for_each(nl, [&, ca, lst, mv](long long j) { ca[j].kind = element_priority(mv, lst[j], ca[j].prio) ? 1 : -1; });
      }
      queue.clear();
      waiting = 0;
      const Candidate* ca = cand_all.data();
      const int* lst = list.data();
      for (std::size_t j = 0; j < nl; ++j)
        if (ca[j].kind != -1) enqueue(ca[j].prio, lst[j]);
      cand_all.release();
      dm.mark.zero();  // each point claims its cavity from clean marks and clears them after
      clock.template stop<Space>("split+locate");
      long long won = 0, sized = 0;  // points inserted, those for triangles too big
      const int grown = 2 * dm.ntri + kSweepGrowth;  // the sweep ends once the mesh is this large
      // About what the listed elements' points make (2.5 new triangles per element on the
      // maps); more grows by sixteenths.
      const double room = dm.ntri + 3.0 * static_cast<double>(nl) + 4096;
      dm.reserve_room(static_cast<int>(std::min<double>(room, grown)), dm.npts + static_cast<int>(std::min<double>(nl, grown)));
      int touched_ids[4];
      int touched_count = 0;
      const TouchLog mine{touched_ids, &touched_count, 4};
      int e = 0;
      for (long long popped = 1; dm.ntri < grown && dequeue(e); ++popped) {
        if ((popped & 4095) == 0) {
          if (cb.abort && cb.abort()) throw Error(Status::Aborted, "refinement aborted by the caller");
          // Often enough for ParaView, which handles its abort button only when progress
          // comes (every 524,288 elements it took 4-10 s to stop a 7M-point run).
          if (cb.progress && (popped & 65535) == 0)
            cb.progress(0.0, "iteration " + std::to_string(iter + 1) + ": " + std::to_string(won) +
                                 " points inserted, " + std::to_string(waiting) + " bad elements waiting");
        }
        if (params.max_steiner >= 0 && res.inserted >= params.max_steiner) {
          res.cap_reached = true;
          break;
        }
        const int t = e >> 2;
        MeshView mv = dm.view();
        // Gone, or no longer an element (a subsegment split from its other side): skip.
        if (!(collect_count(mv, crit, t) && (collect_mask(mv.tflag[t]) & (1 << (e & 3))))) continue;
        Candidate c{};
        touched_count = 0;
        ComputeSplittingPoints{mv, crit, &e, &c, salt, params.strategies.worst_first, u64(1) << 32,
                               params.criteria.step_limit, false, 0, nullptr, mine}(0);
        const int old_ntri = dm.ntri;
        const int in = c.kind < 0 ? 0 : insert_one(c, mine);
        won += in;
        if ((c.prio >> 62) == kClassTriangle) sized += in;
        else if (won - sized > 8 * (static_cast<long long>(nl) + sized) + 1024) {
          handed_over = true;  // a cascade: the parallel iteration's graded order takes over
          break;
        }
        mv = dm.view();
        for (int i = 0; i < std::min(touched_count, 4); ++i) {  // flagged subsegments first
          touch_log().add(touched_ids[i]);
          enqueue_elements(mv, touched_ids[i], 7);
        }
        for (int nt = old_ntri; nt < dm.ntri; ++nt) enqueue_elements(mv, nt, 15);
      }
      queue.clear();
      clock.template stop<Space>("one at a time");
      if (error.get(0)) throw Error(Status::InternalError, "gDP2d: broken cavity while linking new triangles");
      if (params.strategies.compaction && 10 * dead > dm.ntri) {
        detail::compact_triangles(dm);
        dead = 0;
        listed_below = 0;  // renumbered: the work list no longer names the triangles
      }
      clock.template stop<Space>("compact");
      return won;
    }
  }

  // Algorithm 1's lines 7-8 for one candidate: its cavity grown, checked and remeshed by the
  // parallel iteration's kernels (it is point 0 of its own tuples; marks are cleared after).
  int insert_one(const Candidate& c, const TouchLog& touched) {
    std::vector<CavityTuple>& tp = seq_tuples;
    tp.clear();
    MeshView mv = dm.view();
    int failed = 0;
    tp.push_back(CavityTuple{0, c.kind == 0 ? split_start(mv, c) : c.start, kForceIn});
    const GrowCavity grow{mv, &c, &failed, params.criteria.lens_cos2, touched};
    for (std::size_t i = 0; i < tp.size() && !failed; ++i) {
      CavityTuple out[3];
      const int n = grow(static_cast<long long>(i), tp[i], out);
      tp.insert(tp.end(), out, out + n);
    }
    const auto clear_marks = [&] {
      for (const CavityTuple& h : tp) mv.mark[h.tri] = 0;
    };
    if (failed) {
      clear_marks();
      return 0;
    }
    const long long nt = static_cast<long long>(tp.size());
    const CavityTuple* th = tp.data();
    for (long long i = 0; i < nt; ++i) SetInCavity{mv, &c, th, &failed, 1}(i);
    for (long long i = 0; i < nt; ++i) CheckCavity{mv, &c, th, &failed}(i);
    if (failed) {
      for (long long i = 0; i < nt; ++i) SetInCavity{mv, &c, th, &failed, 0}(i);
      clear_marks();
      return 0;
    }
    seq_base.resize(tp.size());
    for (long long i = 0; i < nt; ++i) CountFanEdges{mv, &c, th, &failed, seq_base.data()}(i);
    int new_tris = 0;
    for (int& b : seq_base) {
      const int n = b;
      b = new_tris;
      new_tris += n;
    }
    const int old_ntri = dm.ntri, pid = dm.npts;
    // Past the room reserved, grow by halves: growing a few triangles at a time by sixteenths
    // (the parallel iteration's rule, for device memory) copied every array about 17 times
    // over (copies were a fifth of the counties map's profile on one thread; now a tenth).
    if (3 * std::size_t(old_ntri + new_tris) > dm.tv.capacity() || 2 * std::size_t(pid + 1) > dm.xy.capacity())
      dm.reserve_room(old_ntri + new_tris + old_ntri / 2, pid + 1 + pid / 2);
    dm.reserve(old_ntri + new_tris, pid + 1);
    dm.ntri = old_ntri + new_tris;
    dm.npts = pid + 1;
    mv = dm.view();
    for (long long i = 0; i < nt; ++i) StoreSlotBase{mv, th, &failed, seq_base.data()}(i);
    for (long long i = 0; i < nt; ++i) CreateFan{mv, &c, th, &failed, &pid, old_ntri}(i);
    for (long long i = 0; i < nt; ++i) LinkFan{mv, &c, th, &failed, old_ntri, error.data()}(i);
    for (long long i = 0; i < nt; ++i) KillCavity{mv, th, &failed}(i);
    WritePoints{mv, &c, &failed, &pid}(0);
    clear_marks();
    res.inserted += 1;
    dead += std::max(0, new_tris - 2);
    return 1;
  }

  // Line 8: remesh each winning cavity as a fan from its point, then compact (S1) once a
  // tenth of the triangles are dead (a cavity of k triangles leaves k dead, k+2 new): dead
  // slots are device memory per element.
  void insert(std::size_t ns, long long won) {
    const std::size_t nt = tuples.size();
    // Each cavity triangle gives at most 3 new ones, and triangle numbers (times 3, in the
    // neighbour links) are ints: refuse clearly rather than let a count wrap.
    if (3.0 * static_cast<double>(nt) + dm.ntri > static_cast<double>(INT_MAX / 3))
      throw Error(Status::InvalidInput,
                  "gDP2d: one iteration's cavities hold " + std::to_string(nt) +
                      " triangles on a mesh of " + std::to_string(dm.ntri) +
                      ": beyond the engine's 32-bit triangle numbers");
    count.resize_discard(nt);
    Ops::for_each(nt, CountFanEdges{dm.view(), cand.data(), tuples.data(), failed.data(), count.data()});
    const int new_tris = static_cast<int>(Ops::exclusive_scan(count.data(), count.data(), nt));
    Ops::for_each(nt, StoreSlotBase{dm.view(), tuples.data(), failed.data(), count.data()});
    const int old_ntri = dm.ntri, old_npts = dm.npts;
    dm.reserve(old_ntri + new_tris, old_npts + static_cast<int>(won));
    dm.ntri = old_ntri + new_tris;
    dm.npts = old_npts + static_cast<int>(won);
    int* pid = point_id.data();
    Ops::for_each(ns, [=] GDR_HD(long long j) { pid[j] += old_npts; });
    const MeshView mv = dm.view();
    Ops::for_each(nt, CreateFan{mv, cand.data(), tuples.data(), failed.data(), pid, old_ntri});
    Ops::for_each(nt, LinkFan{mv, cand.data(), tuples.data(), failed.data(), old_ntri, error.data()});
    Ops::for_each(nt, KillCavity{mv, tuples.data(), failed.data()});
    Ops::for_each(ns, WritePoints{mv, cand.data(), failed.data(), pid});
    if (error.get(0)) throw Error(Status::InternalError, "gDP2d: broken cavity while linking new triangles");
    res.inserted += won;
    clock.template stop<Space>("insert");
    dead += std::max<long long>(0, new_tris - 2 * won);
    if (params.strategies.compaction && 10 * dead > dm.ntri) {
      detail::compact_triangles(dm);
      dead = 0;
      listed_below = 0;  // renumbered: the work list no longer names the triangles
    }
    clock.template stop<Space>("compact");
  }

  // The final mesh, live triangles only, with its subsegments (each once, from the side with
  // the smaller edge code) and its bad triangles listed on the device: the host needs neither
  // neighbour nor segment links, so they are not copied.
  void download(MeshResult& out) {
    clock.restart();
    auto t0 = std::chrono::steady_clock::now();
    auto stamp = [&](const char* what) {  // sub-phases, for GDR_TRACE
      if (!trace) return;
      Ops::synchronize();
      const auto now = std::chrono::steady_clock::now();
      std::fprintf(stderr, "gdr-trace download %s: %.4f s\n", what,
                   std::chrono::duration<double>(now - t0).count());
      t0 = now;
    };
    detail::compact_triangles(dm);
    stamp("compact");
    const MeshView mv = dm.view();
    const Criteria criteria = crit;  // by value into the kernel below
    int* cnt = dm.aux.data();
    Ops::for_each(dm.ntri, [=] GDR_HD(long long t) {
      int n = 0;
      for (int i = 0; i < 3; ++i) {
        const int nb = mv.tn[3 * t + i];
        n += is_subseg(mv, static_cast<int>(t), i) && (nb < 0 || nb > 3 * t + i);
      }
      cnt[t] = n;
    });
    const std::size_t nsub = static_cast<std::size_t>(Ops::exclusive_scan(cnt, cnt, dm.ntri));
    work.resize_discard(4 * nsub);
    int* sub = work.data();
    Ops::for_each(dm.ntri, [=] GDR_HD(long long t) {
      int o = 4 * cnt[t];
      for (int i = 0; i < 3; ++i) {
        const int nb = mv.tn[3 * t + i];
        if (!is_subseg(mv, static_cast<int>(t), i) || (nb >= 0 && nb < 3 * t + i)) continue;
        const int a = mv.tv[3 * t + next3(i)], b = mv.tv[3 * t + prev3(i)];
        sub[o++] = a;
        sub[o++] = b;
        sub[o++] = segment_of(mv, a, b);
        sub[o++] = nb < 0;  // on the mesh boundary: one triangle
      }
    });
    stamp("subsegment list");
    work.to_host(out.subseg);
    stamp("subsegment copy");
    if (!params.region_area2.empty() || has_regions) {  // before classify overwrites the flags
      work.resize_discard(dm.ntri);
      int* region = work.data();
      Ops::for_each(dm.ntri, [=] GDR_HD(long long t) { region[t] = mv.tflag[t] >> kRegionShift; });
      work.to_host(out.tregion);
    }
    // The mesh's area and the least sin^2 of an angle, for refine_2d's statistics (a pass
    // of the host over 16M triangles took 0.1-0.2 s). Only a smaller sin^2 takes the atomic.
    {
      Buf<double> area2(dm.ntri);
      Buf<u64> least(1);  // ~bits of the least sin^2 so far
      least.zero();
      double* ar = area2.data();
      u64* lst = least.data();
      Ops::for_each(dm.ntri, [=] GDR_HD(long long t) {
        double a2, s2;
        triangle_measures(mv, static_cast<int>(t), a2, s2);
        ar[t] = a2;
        const u64 key = ~bits_of(s2);
        if (key > exec::volatile_load(lst)) exec::atomic_max(lst, key);
      });
      out.area = 0.5 * Ops::exclusive_scan(ar, ar, dm.ntri);
      const u64 b = ~least.get(0);
      std::memcpy(&out.min_sin2, &b, sizeof b);
      if (dm.ntri == 0) out.min_sin2 = 1.0;
    }
    stamp("area and angles");
    Ops::for_each(dm.ntri, [=] GDR_HD(long long t) {
      mv.tflag[t] = classify_triangle(mv, static_cast<int>(t), criteria);
    });
    const int* cls = dm.tflag.data();
    const std::size_t nbad = exec::compact_indices<Space>(
        dm.ntri, [=] GDR_HD(long long t) { return cls[t] != kGood; }, list, dm.aux);
    int* bad = list.data();
    Ops::for_each(nbad, [=] GDR_HD(long long i) {
      bad[i] = 2 * bad[i] + (cls[bad[i]] == kBadProtected);
    });
    list.to_host(out.bad);
    stamp("bad triangles");
    dm.xy.resize(2 * std::size_t(dm.npts));
    dm.ptype.resize(dm.npts);
    dm.xy.to_host(out.xy);
    stamp("point copy");
    out.ptype.resize(dm.npts);
    static_assert(sizeof(PointType) == sizeof(std::uint8_t) && sizeof(out.tv[0]) == 3 * sizeof(int));
    dm.ptype.download(reinterpret_cast<std::uint8_t*>(out.ptype.data()), dm.npts);
    out.tv.resize(dm.ntri);
    dm.tv.download(reinterpret_cast<int*>(out.tv.data()), 3 * std::size_t(dm.ntri));
    stamp("triangle copy");
    clock.template stop<Space>("download");
  }
};

template <class Space>
EngineResult refine_mesh(const HostMesh& host, MeshResult& out, const EngineParams& params,
                         const Callbacks& cb) {
  Engine<Space> engine(params, cb);
  engine.run(host, out);
  return engine.res;
}

template <class Space>
EngineResult refine_mesh(DeviceMesh<Space>&& mesh, bool regions, MeshResult& out,
                         const EngineParams& params, const Callbacks& cb) {
  Engine<Space> engine(params, cb);
  engine.run(std::move(mesh), regions, out);
  return engine.res;
}

}  // namespace gdr::r2d
