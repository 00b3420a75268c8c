// gQM3d refinement loop (paper Algorithm 3), written once for any execution space.
// engine_cpu.cpp instantiates it for OpenMP, engine_cuda.cu for CUDA.
#pragma once
#include <algorithm>
#include <chrono>
#include <climits>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "exec/algorithms.h"
#include "exec/host_vector.h"
#include "exec/phase_clock.h"
#include <functional>

#include "gdr/progress.h"
#include "gdr/qm3d.h"
#include "mesh3d/cavity.h"
#include "mesh3d/compact.h"
#include "mesh3d/mesh3d.h"
#include "mesh3d/flip.h"
#include "mesh3d/smooth.h"
#include "mesh3d/stall.h"
#include "qm3d/kernels.h"

namespace gdr::qm3d {

// The paper's design strategies and some of ours, each of which can be switched off to
// measure what it buys (benchmarks only: GDR_DISABLE, see quality_tet_mesh.cpp).
struct Strategies {
  bool compaction = true;    // S1: compact dead elements during refinement, not only at the end
  bool filtering = true;     // S3: one splitting point per tetrahedron before growing cavities
  bool deferment = true;     // S5: defer cavities still growing after a few rounds
  bool touching = true;      // cavities that touch go in together when the mesh stays Delaunay
  bool block_rounds = true;  // small ExpandList windows run their rounds inside one GPU block
  bool grid_rounds = true;   // large ExpandList windows run their rounds in one grid-wide launch
  bool worst_first = true;   // tetrahedra bad by shape alone worst first, not larger first
  bool crowding = true;      // S3: fewer competitors while most of them lose (large cavities)
  bool interior_seeds = true;  // a graded lattice inside goes into the CDT (cdt3d/seeds.cpp)
  bool blocking = true;        // segments whose splits keep failing are left as they are (Engine)
  bool acute_vertices = true;  // protecting balls at acute vertices too (qm3d/features.h)
  bool segment_presplit = true;  // segments that would wait on each other split before the CDT
  bool flips = true;             // the sliver pass flips the slivers it cannot smooth (mesh3d/flip.h)
  bool sleeping = true;          // points that failed for reasons of their own wait for a change
};

struct EngineParams {
  Criteria criteria;
  long long max_steiner = -1;  // -1: unlimited
  int max_iterations = 100000;
  Strategies strategies;
  bool check_links = false;  // tests: check every link of the mesh after each iteration
  // Check every subsegment and subface of the input mesh for encroachment (kernels.h,
  // static_collect_mask); off when refining a mesh that is already refined.
  bool check_input_boundary = true;
  // Sliver removal after refinement (mesh3d/smooth.h): stars with a dihedral angle whose
  // sine is below this are smoothed; 0: none.
  double sliver_sin = 0;
  // Called on the host before each iteration with the live tetrahedra (the CPU backend's
  // thread count follows the mesh: a part estimated small can grow a hundredfold).
  std::function<void(long long tets)> on_iteration;
};

struct EngineResult {
  int iterations = 0;
  long long inserted = 0;
  bool cap_reached = false;
  bool stalled = false;
  long long blocked_segments = 0;  // input segments left unsplit after repeated failures
  long long slept = 0;             // points that fell asleep (Engine::sleep_failed)
  m3d::SmoothResult slivers;
  std::size_t peak_bytes = 0;
  std::vector<PhaseTime> phases;
};

// The final mesh, live elements only, in the forms the facade reports.
struct MeshResult {
  exec::HostVector<double> xyz;          // 3 per point
  exec::HostVector<std::uint8_t> ptype;  // per point
  exec::HostVector<int> tv;              // 4 per tetrahedron
  exec::HostVector<int> tregion;         // per tetrahedron (empty without regions)
  exec::HostVector<int> sv;              // 3 per subface
  exec::HostVector<int> sfacet;          // per subface
  exec::HostVector<int> subseg;          // 3 per subsegment: its two vertices and its segment
  exec::HostVector<int> bad;             // tetrahedra left bad: 2t, or 2t+1 when no point
                                         // could fix it (its split was declined)
  int tets() const { return static_cast<int>(tv.size() / 4); }
  int points() const { return static_cast<int>(ptype.size()); }
};

// `final_mesh` (tests): the refined mesh with all its links, to check or refine again.
template <class Space>
EngineResult refine_mesh(const m3d::HostTetMesh& mesh, MeshResult& out, const EngineParams& params,
                         const Callbacks& cb, m3d::HostTetMesh* final_mesh = nullptr);

// One refinement run. run() is the paper's Algorithm 3; each method is one of its lines.
// (Public members only: nvcc's device lambdas may not live in private member functions.)
template <class Space>
struct Engine {
  using Ops = exec::Ops<Space>;
  template <class T>
  using Buf = exec::Buffer<Space, T>;
  using Tuple = m3d::CavityTuple;

  const EngineParams& params;
  const Callbacks& cb;
  EngineResult res;
  exec::PhaseClock clock{res.phases};
  m3d::DeviceTetMesh<Space> dm;
  Buf<int> list, failed, point_id, count, count2, counters;
  Buf<Candidate> cand_all, cand;  // all splitting points, then the filtered ones
  Buf<Tuple> tuples;
  Buf<double> work_volume;             // six_volume's scratch
  Buf<int> segment_failures;           // per input segment: splits without a star (blocking)
  // Sleeping (sleep_failed): per tetrahedron, its listed elements that sleep (kernels.h
  // asleep); per sleeping element, the elements of its last cavity, watched for changes.
  struct Watch {
    int elem;   // the sleeping element, t * 16 + slot
    int what;   // a tetrahedron of its cavity, or ~s for a subface s of it
    int since;  // the iteration it fell asleep
  };
  Buf<int> sleep;
  Buf<Watch> watch;
  bool slivers_held = false;  // sliver_split_ratio2 in force (compute_splitting_points)
  double domain_volume = 0, bad_volume = 0;  // six times: all tetrahedra at the start, the bad ones now
  long long initial_points = 0;               // in the mesh given to refine
  bool allow_deferment = true;
  // Livelock breaker: after an iteration that inserted almost none of its candidates, the
  // next one ranks them at random within their class (segments, facets, tetrahedra) and
  // defers no cavity, so that points that keep failing (a cavity that touches a failing
  // higher one, a split that must wait) no longer block the same lower ones.
  bool stagnant = false;
  // No point went in for two iterations: room is asked for and made more eagerly
  // (CheckCavity::room_too, ComputeSplittingPoints::centroid_room).
  bool idle_twice = false;
  long long dead_tets = 0, dead_subs = 0;  // since the last compaction
  // The new tetrahedra (kFresh) of the last insertion are those from here on: they are
  // appended, unless a compaction moved them (then 0).
  int fresh_from = 0;
  int rounds = 0;                          // ExpandList rounds of the last cavity phase
  const bool trace = std::getenv("GDR_TRACE") != nullptr;

  // counters: [0] broken link found while remeshing, [1] tetrahedra killed, [2] subfaces killed
  enum { kError = 0, kKilledTets = 1, kKilledSubs = 2, kBlocked = 3, kCounters = 4 };
  static constexpr int kClaimRounds = 8;  // claim rounds per iteration (grow_cavities)
  static constexpr std::size_t kKeepAbove = std::size_t(1) << 16;  // tuples worth compacting
  static constexpr double kFloor = 64;    // competitors at least (crowding)
  m3d::StallDetector stall;
  u64 keep_below = 0;                     // priority ids below this compete this iteration
  double crowd_share = 1.0;               // share of the competitors kept by crowding

  Engine(const EngineParams& p, const Callbacks& c) : params(p), cb(c) {}

  void check_abort() const {
    if (cb.abort && cb.abort()) throw Error(Status::Aborted, "refinement aborted by the caller");
  }

  void run(const m3d::HostTetMesh& host, MeshResult& out) {
    exec::memory_counter<Space>().peak = exec::memory_counter<Space>().current;
    const std::size_t mem_base = exec::memory_counter<Space>().current;
    dm.upload(host);
    domain_volume = six_volume(dm.ntet, [] GDR_HD(int) { return true; });
    stall = m3d::StallDetector(false, 0.05 * domain_volume,
                               params.criteria.max_volume6 == 0 && params.criteria.region_bounds == 0);
    initial_points = dm.npts;
    counters.resize_discard(kCounters);
    counters.zero();
    clock.template stop<Space>("upload");
    int idle = 0;
    for (int iter = 0; iter < params.max_iterations; ++iter) {
      check_abort();
      clock.restart();
      const auto t0 = std::chrono::steady_clock::now();
      const std::vector<PhaseTime> phases_before = trace ? res.phases : std::vector<PhaseTime>{};
      if (params.on_iteration) params.on_iteration(dm.ntet);
      const std::size_t nl = collect(iter == 0 && params.check_input_boundary);  // line 4
      if (nl == 0) break;                               // line 10
      res.iterations = iter + 1;
      if (idle >= 2 && !idle_twice) wake_all();  // their points are made another way now
      idle_twice = idle >= 2;
      compute_splitting_points(nl, iter);               // line 6
      if (params.strategies.blocking && params.strategies.sleeping) count_segment_failures(cand_all.data(), nullptr, nl);
      const std::size_t ns = filter(nl);                // line 7 (S1, S3)
      grow_cavities(ns);                                // line 8 (S2, S3, S5)
      check_abort();  // an iteration of millions of points takes seconds on a few CPU threads
      const long long won = verify_and_number(ns);
      if (params.strategies.blocking) count_segment_failures(cand.data(), failed.data(), ns);
      stagnant = !stagnant && won * 50 < static_cast<long long>(ns);
      adjust_crowding(ns, won);
      if (won > 0) {
        insert(ns, won, iter);                          // line 9
        idle = 0;
      } else {
        sleep_failed(ns, iter, false);
        if (++idle >= 8) {
          res.stalled = true;
          break;
        }
      }
      // The bad volume counts as progress on its own only while it is a large share of the
      // domain (the interior still empty), not in a cascade of ever smaller bad tetrahedra
      // near small input angles, which would otherwise go on shrinking it; later, growth
      // counts only with it shrinking.
      if (stall.stalled(nl, dm.npts, bad_volume)) {
        res.stalled = true;  // mesh3d/stall.h
        break;
      }
      if (cb.progress)
        cb.progress(0.0, "iteration " + std::to_string(iter + 1) + ": " + std::to_string(nl) +
                             " elements to split, " + std::to_string(won) + " points inserted");
      if (trace) {
        Ops::synchronize();
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        std::string phase_ms;  // this iteration's share of each phase
        for (const PhaseTime& p : res.phases) {
          double before = 0;
          for (const PhaseTime& q : phases_before)
            if (q.name == p.name) before = q.seconds;
          if (p.seconds > before) phase_ms += " " + p.name + " " + std::to_string(1e3 * (p.seconds - before));
        }
        std::fprintf(stderr, "gdr-trace phases ms:%s\n", phase_ms.c_str());
        std::fprintf(stderr,
                     "gdr-trace iter %d: ms %.2f, tets %d, subfaces %d, points %d, elements %zu, bad volume %.3g%%, "
                     "candidates %zu, won %lld, rounds %d, tuples %zu, watched %zu, MB %.1f (peak %.1f), "
                     "lost/encroach/touch/star/defer/cap/delaunay %s\n",
                     iter + 1, ms, dm.ntet, dm.nsub, dm.npts, nl, 100 * bad_volume / domain_volume, ns, won, rounds, tuples.size(), watch.size(),
                     exec::memory_counter<Space>().current / 1048576.0,
                     exec::memory_counter<Space>().peak / 1048576.0, failure_counts().c_str());
      }
      if (params.check_links) {
        m3d::compact(dm);
        wake_all();  // the sleepers' tetrahedra and subfaces are numbered anew
        m3d::check_host_mesh(dm.to_host(host.input_points));
      }
      if (res.cap_reached) break;
      // The first iterations' cavities are the largest: their scratch would stay allocated
      // while the mesh grows to its final size (peak device memory per tetrahedron).
      for (auto* b : {&list, &failed, &point_id, &count, &count2}) b->release_if_oversized();
      cand.release_if_oversized();
      tuples.release_if_oversized();
    }
    int host_ctr[kCounters];
    counters.download(host_ctr, kCounters);  // blocked after the last insertion
    res.blocked_segments += host_ctr[kBlocked];
    if (params.sliver_sin > 0) {
      clock.restart();
      res.slivers = m3d::smooth_slivers(dm, m3d::SmoothParams{params.sliver_sin}, MeetsCriteria{params.criteria});
      // Slivers with all four corners on the surface do not move: flips remove those it can.
      if (res.slivers.slivers_after > 0 && params.strategies.flips) {
        res.slivers.flips = m3d::flip_slivers(dm, params.sliver_sin, MeetsCriteria{params.criteria});
        if (res.slivers.flips > 0)
          res.slivers.slivers_after = m3d::count_slivers(dm, params.sliver_sin, res.slivers.min_sine_after);
        if (params.check_links) {
          m3d::compact(dm);
          m3d::check_host_mesh(dm.to_host(host.input_points));
        }
      }
      clock.template stop<Space>("slivers");
    }
    download(out);
    res.peak_bytes = exec::memory_counter<Space>().peak - mem_base;
  }

  // Six times the volume (rounded: a measure of progress only) of the tetrahedra t = of(j)
  // for the j < n with pick(j); of is the identity without a list, else list[j] / 16.
  template <class Pick>
  double six_volume(int n, Pick pick, const int* list = nullptr) {
    if (n == 0) return 0.0;
    work_volume.resize_discard(n);
    double* wv = work_volume.data();
    const m3d::TetView mv = dm.view();
    Ops::for_each(n, [=] GDR_HD(long long j) {
      wv[j] = 0.0;
      if (!pick(static_cast<int>(j))) return;
      const int* v = mv.tv + 4 * (list ? list[j] >> 4 : static_cast<int>(j));
      const double *a = m3d::pt(mv, v[0]), *b = m3d::pt(mv, v[1]), *c = m3d::pt(mv, v[2]), *d = m3d::pt(mv, v[3]);
      const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]},
                   x[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
      wv[j] = fabs(u[0] * (w[1] * x[2] - w[2] * x[1]) - u[1] * (w[0] * x[2] - w[2] * x[0]) +
                   u[2] * (w[0] * x[1] - w[1] * x[0]));
    });
    const double total = Ops::exclusive_scan(wv, wv, n);
    work_volume.release();
    return total;
  }

  // Trace only: why the points that did not go in failed (cavity.h kFail*), and per kind
  // (segment / facet / free) the candidates and the winners.
  std::string failure_counts() const {
    std::vector<int> f(failed.size());
    failed.download(f.data(), f.size());
    std::vector<Candidate> c(cand.size());
    cand.download(c.data(), c.size());
    long long n[m3d::kFailReasons] = {}, kinds[3] = {}, wins[3] = {};
    for (std::size_t j = 0; j < f.size(); ++j) {
      ++n[f[j] >= 0 && f[j] < m3d::kFailReasons ? f[j] : 0];
      if (c[j].kind >= 0 && c[j].kind < 3) {
        ++kinds[c[j].kind];
        wins[c[j].kind] += f[j] == 0;
      }
    }
    std::string s;
    for (int k = 1; k < m3d::kFailReasons; ++k) s += (k > 1 ? "/" : "") + std::to_string(n[k]);
    {
      long long mr = 0, mrw = 0, mrf[m3d::kFailReasons] = {};
      for (std::size_t j = 0; j < f.size(); ++j)
        if (c[j].kind == m3d::kFreeSplit && c[j].ek == m3d::kMakeRoomPoint) {
          ++mr;
          mrw += f[j] == 0;
          ++mrf[f[j] >= 0 && f[j] < m3d::kFailReasons ? f[j] : 0];
        }
      s += ", make-room " + std::to_string(mr) + " won " + std::to_string(mrw) + " fail";
      for (int k = 1; k < m3d::kFailReasons; ++k) s += " " + std::to_string(mrf[k]);
    }
    for (int kd = 0; kd < 3; ++kd) {
      long long nf[m3d::kFailReasons] = {};
      for (std::size_t j = 0; j < f.size(); ++j)
        if (c[j].kind == kd) ++nf[f[j] >= 0 && f[j] < m3d::kFailReasons ? f[j] : 0];
      s += kd == 0 ? ", segment fails" : (kd == 1 ? ", facet fails" : ", free fails");
      for (int k = 1; k < m3d::kFailReasons; ++k) s += " " + std::to_string(nf[k]);
    }
    s += ", seg/facet/free candidates " + std::to_string(kinds[0]) + "/" + std::to_string(kinds[1]) +
         "/" + std::to_string(kinds[2]) + " won " + std::to_string(wins[0]) + "/" +
         std::to_string(wins[1]) + "/" + std::to_string(wins[2]);
    return s;
  }

  // Line 4: encroached subsegments, encroached subfaces and bad tetrahedra in one list (S1,
  // S4). Each tetrahedron keeps an 11-bit mask in its flags and its entry count in aux; the
  // in-place scan of the counts places the entries (t*16 + slot).
  std::size_t collect(bool all) {
    Ops::for_each(dm.ntet, CollectMask{dm.view(), params.criteria, all});
    int* cnt = dm.aux.data();
    const std::size_t nl = static_cast<std::size_t>(Ops::exclusive_scan(cnt, cnt, dm.ntet));
    list.resize_discard(nl);
    if (nl) Ops::for_each(dm.ntet, ExpandElements{dm.view(), list.data(), static_cast<int>(nl)});
    // The bad tetrahedra's volume, for the stall detector.
    const int* l = list.data();
    bad_volume = six_volume(static_cast<int>(nl), [=] GDR_HD(int j) { return (l[j] & 15) == kSlotTet; }, l);
    if (trace && nl) {
      std::vector<int> l(nl);
      list.download(l.data(), nl);
      long long k[3] = {};
      for (int e : l) ++k[(e & 15) >= kSlotEdge0 ? 0 : ((e & 15) >= kSlotFace0 ? 1 : 2)];
      std::fprintf(stderr, "gdr-trace elements: subsegments %lld, subfaces %lld, tets %lld\n", k[0], k[1], k[2]);
    }
    clock.template stop<Space>("collect");
    return nl;
  }

  // Line 6: splitting points, priorities and point location.
  // When far more elements are bad than can win at once (the first iterations), only a
  // random share of them competes, at most a quarter of the tetrahedron count: the others
  // are not even located (the walks to far circumcentres are most of this phase then).
  // About kFloor of them always compete: a share left small by crowding, once only a few
  // elements are left, would otherwise let none compete, and the run stalled (H100: spot at
  // B = 2 stopped with one tetrahedron of 8% of the volume unsplit).
  void compute_splitting_points(std::size_t nl, int iter) {
    const double n = static_cast<double>(nl);
    const double share = std::max(crowd_share * std::min(1.0, (dm.ntet / 4.0 + 4096.0) / n), std::min(1.0, kFloor / n));
    keep_below = static_cast<u64>(share * 4294967296.0);
    cand_all.resize_discard(nl);
    // A dihedral bound has no termination guarantee: the circumcentre of a sliver lies as
    // near its corners as its shortest edge or nearer (0.61 of it for a regular tetrahedron),
    // and the slivers it makes beside the surface ask for smaller points again (spot at 25
    // degrees cascaded to the Steiner cap: 2.5M points, 5% of the volume still bad; TetGen
    // 1.5 ran past 5 minutes). Once the mesh has grown fourfold, slivers are split only where
    // their circumradius is at least their shortest edge, so insertion radii stop shrinking
    // (spot: 22k points, 2.6% bad, 0.45 s on 2 CPU threads); the others are left and counted.
    Criteria crit = params.criteria;
    if (crit.dihedral && dm.npts > 4LL * initial_points) {
      crit.sliver_split_ratio2 = 1.0;
      if (!slivers_held) wake_all();
      slivers_held = true;
    }
    if (params.strategies.sleeping && sleep.size() != static_cast<std::size_t>(dm.ntet)) {  // the first iteration (insert keeps the size)
      wake_all();
      sleep.resize_discard(dm.ntet);
      sleep.zero();
    }
    Ops::for_each(nl, ComputeSplittingPoints{dm.view(), crit, list.data(), cand_all.data(),
                                             0x9e3779b9u * static_cast<unsigned>(iter + 1),
                                             params.strategies.worst_first, stagnant, keep_below,
                                             segment_failures.size() == dm.sharp.size() ? segment_failures.data() : nullptr,
                                             idle_twice, params.strategies.sleeping ? sleep.data() : nullptr});
    clock.template stop<Space>("split+locate");
  }

  // Crowding (S3): while the interior is still empty, cavities span hundreds of tetrahedra
  // and a few dozen of a thousand competitors win; the others lose to them after growing
  // their whole cavity. Next time only about kCrowd losers per winner compete (a random
  // share, so the winners stay spread out); the share grows back as cavities shrink. Points
  // that fail for reasons of their own (a subsegment to split first, no star) do not count.
  // kCrowd 2 against 8 on the H100 (2026-11-24, medians of one): GPU refinement 1.40 -> 0.88
  // s at 1M tetrahedra, 0.35 -> 0.28 s on fandisk; 16 CPU threads 7.5 -> 4.7 s at 1M, 11.6 ->
  // 3.8 s on penguin_hr (B = 2), with 1-6% fewer tetrahedra.
  void adjust_crowding(std::size_t ns, long long won) {
    if (!params.strategies.crowding || ns == 0) return;
    const int* f = failed.data();
    count2.resize_discard(ns);
    int* lost = count2.data();
    Ops::for_each(ns, [=] GDR_HD(long long j) {
      lost[j] = f[j] == m3d::kFailLost || f[j] == m3d::kFailTouch;
    });
    const double contenders = static_cast<double>(won + Ops::exclusive_scan(lost, lost, ns));
    constexpr double kCrowd = 2, kMinShare = 1.0 / 4096;
    const double target = kCrowd * static_cast<double>(won) + kFloor;
    crowd_share = std::clamp(crowd_share * target / std::max(contenders, 1.0), kMinShare, 1.0);
  }

  // Line 7 (S3): one splitting point per neighbourhood, by priority marks, among the random
  // share that competes (compute_splitting_points).
  std::size_t filter(std::size_t nl) {
    dm.mark.zero();
    const Candidate* ca = cand_all.data();
    const u64 keep_below = this->keep_below;
    const bool filtering = params.strategies.filtering;
    if (filtering) Ops::for_each(nl, ClaimStart{dm.view(), ca, keep_below});
    const KeptStart kept{dm.view(), ca, keep_below};
    const std::size_t ns = exec::compact_indices<Space>(
        nl,
        [=] GDR_HD(long long j) {
          const Candidate& c = ca[j];
          if (c.kind < 0) return false;
          return filtering ? kept(j) : exec::priority_id(c.prio) < keep_below;
        },
        list, count);
    cand.resize_discard(ns);
    Candidate* cs = cand.data();
    const int* sel = list.data();
    Ops::for_each(ns, [=] GDR_HD(long long j) { cs[j] = ca[sel[j]]; });
    cand_all.release();  // device memory: only the survivors are needed from here on
    list.release();
    dm.mark.zero();  // survivors now claim their cavities from scratch
    dm.smark.zero();
    clock.template stop<Space>("filter");
    return ns;
  }

  // Line 8, growing (S2, S5): cavities by ExpandList from the tetrahedron holding the point,
  // or, for a point on a facet, from the subface holding it; stragglers are deferred. Then the
  // Delaunay-independent, star-shaped cavities are kept (verify_round). In further rounds the
  // points that only lost a claim grow again, with the winners' elements reserved (their
  // priority raised above all) and the failed points' claims released: a high point that
  // fails for a reason of its own (a cavity that is not star-shaped, a subsegment it must
  // wait for) no longer blocks every lower point around it for the whole iteration.
  void grow_cavities(std::size_t ns) {
    failed.resize_discard(ns);
    failed.zero();
    exec::ExpandListLimits lim;
    if (allow_deferment && !stagnant && params.strategies.deferment) {
      lim.defer_after_rounds = 16;
      lim.defer_below = ns / 64 + 32;
    }
    lim.block_rounds = params.strategies.block_rounds;
    lim.grid_rounds = params.strategies.grid_rounds;
    point_id.resize_discard(ns);
    int* all = point_id.data();  // scratch here: the candidates that grow
    Ops::for_each(ns, [=] GDR_HD(long long j) { all[j] = static_cast<int>(j); });
    const exec::ExpandListResult er = grow(tuples, all, ns, lim);
    // Deferred cavities must finish next time, or big ones would block their neighbourhood
    // forever. Points whose cavity is still growing give up this iteration.
    allow_deferment = !er.deferred();
    rounds = er.rounds;
    verify_round(tuples);
    clock.template stop<Space>("cavity");
    int* f = failed.data();
    Candidate* cs = cand.data();
    for (int round = 1; round < kClaimRounds; ++round) {
      const std::size_t nlost = exec::compact_indices<Space>(
          ns, [=] GDR_HD(long long j) { return f[j] == m3d::kFailLost; }, list, count);
      if (nlost == 0) break;
      // Release the claims of the points that failed, retire the losers' tuples, reserve the
      // winners' elements.
      const m3d::TetView mv = dm.view();
      Tuple* tw = tuples.data();
      Ops::for_each(tuples.size(), [=] GDR_HD(long long i) {
        Tuple& h = tw[i];
        if (!f[h.pt] || m3d::result_of(h) != m3d::kCavity) return;
        int* slot = m3d::is_sub_tuple(h) ? &mv.smark[h.elem] : &mv.mark[h.elem];
        if (*slot == h.pt + 1) *slot = 0;
        if (f[h.pt] == m3d::kFailLost) m3d::set_result(h, m3d::kStale);
      });
      Ops::for_each(ns, [=] GDR_HD(long long j) {
        if (!f[j]) cs[j].prio = ~0ull;
      });
      const int* lost = list.data();
      Ops::for_each(nlost, [=] GDR_HD(long long k) { f[lost[k]] = 0; });
      // From here on only the tuples of cavity elements are read (their points' claims, the
      // winners' remeshing, in order): the rings, the duplicates and the losers' stale
      // tuples, most of a first iteration's millions, go before the regrown cavities are
      // appended, or the appending copy held them twice. That copy was the peak of device
      // memory: on the CPU counter the 1M case at B = 1.4 went from 162 to 140 bytes per
      // tetrahedron on one thread (the same mesh), from 187 to 140 on two; on the H100 from
      // 214 to 141. Only where the tuples are many for the mesh: each compaction allocates,
      // and compacting every round cost the H100 20% of that case's refinement time.
      if (tuples.size() > std::max<std::size_t>(kKeepAbove, static_cast<std::size_t>(dm.ntet) / 2)) {
        exec::keep_if(tuples, [] GDR_HD(const Tuple& h) { return m3d::result_of(h) == m3d::kCavity; }, count);
        count.release();
      }
      Buf<Tuple> more;
      exec::ExpandListLimits again_lim;
      again_lim.block_rounds = params.strategies.block_rounds;
      again_lim.grid_rounds = params.strategies.grid_rounds;
      grow(more, lost, nlost, again_lim);
      verify_round(more);
      const std::size_t before = tuples.size();
      tuples.resize(before + more.size());
      Ops::copy_d2d(tuples.data() + before, more.data(), more.size() * sizeof(Tuple));
      clock.template stop<Space>("cavity");
      const std::size_t again = exec::compact_indices<Space>(
          nlost, [=] GDR_HD(long long k) { return f[lost[k]] == m3d::kFailLost; }, count2, count);
      if (again == nlost) break;  // nobody won or failed on its own: the next round is the same
    }
  }

  // Seeds and grows the cavities of the candidates `which[0..n)` into H.
  exec::ExpandListResult grow(Buf<Tuple>& H, const int* which, std::size_t n,
                              const exec::ExpandListLimits& lim) {
    H.resize_discard(n);
    const Candidate* cs = cand.data();
    Tuple* tp = H.data();
    Ops::for_each(n, [=] GDR_HD(long long k) {
      const int j = which[k];
      const Candidate& c = cs[j];
      tp[k] = c.kind == m3d::kFacetSplit ? Tuple{j, c.sub, m3d::kSubTuple | m3d::kForceIn}
                                         : Tuple{j, c.start, m3d::kForceIn};
    });
    const exec::ExpandListResult er = exec::expand_list<Space, m3d::GrowCavity::K>(
        H, n, m3d::GrowCavity{dm.view(), cand.data(), failed.data()}, lim);
    if (er.deferred()) {
      Tuple* pend = H.data() + er.pending_begin;
      int* f = failed.data();
      Ops::for_each(er.size - er.pending_begin,
                    [=] GDR_HD(long long i) { f[pend[i].pt] = m3d::kFailDeferred; });
    }
    H.resize(er.size);
    return er;
  }

  // Surviving marks and exact checks decide the winners among the tuples of H: claims kept,
  // touching cavities Delaunay across their shared faces, star-shaped, new faces Delaunay.
  void verify_round(Buf<Tuple>& H) {
    const std::size_t nt = H.size();
    const m3d::TetView mv = dm.view();
    Ops::for_each(nt, m3d::VerifyClaims{mv, cand.data(), H.data(), failed.data(),
                                        params.strategies.touching});
    Ops::for_each(nt, m3d::SetInCavity{mv, H.data(), failed.data(), 1});
    Ops::for_each(nt, m3d::MarkFlips{mv, cand.data(), H.data(), failed.data()});
    Ops::for_each(nt, m3d::CheckCavity{mv, cand.data(), H.data(), failed.data(), idle_twice});
    Ops::for_each(nt, m3d::SetInCavity{mv, H.data(), failed.data(), 0});
  }

  // Line 8, filtering done: the winners get vertex numbers. The Steiner cap may drop any of
  // them: a dropped point's cavity stays as it was. Returns how many won.
  long long verify_and_number(std::size_t ns) {
    const std::size_t nt = tuples.size();
    const m3d::TetView mv = dm.view();
    point_id.resize_discard(ns);
    const int* fc = failed.data();
    int* pid = point_id.data();
    Ops::for_each(ns, [=] GDR_HD(long long j) { pid[j] = fc[j] ? 0 : 1; });
    long long won = Ops::exclusive_scan(pid, pid, ns);
    if (params.max_steiner >= 0 && res.inserted + won > params.max_steiner) {
      const int keep = static_cast<int>(params.max_steiner - res.inserted);
      int* f = failed.data();
      Ops::for_each(ns, [=] GDR_HD(long long j) {
        if (!f[j] && pid[j] >= keep) f[j] = m3d::kFailCap;
      });
      Ops::for_each(nt, m3d::SetInCavity{mv, tuples.data(), failed.data(), 0});
      won = keep;
      res.cap_reached = true;
    }
    Ops::for_each(nt, m3d::MarkSubfaceFans{mv, cand.data(), tuples.data(), failed.data()});
    clock.template stop<Space>("verify");
    return won;
  }

  // A subsegment whose split point sees no star, iteration after iteration, lies next to a
  // nearly coplanar facet that the point sees from behind (a scanned surface, where every
  // edge is a segment; TetGen flips there). Only segments whose facets meet nearly flat
  // (kNearlyFlat) are blocked: elsewhere, as between the facets of a CAD part, such failures
  // pass once the mesh around is refined (thingi10k_288351 kept 1.3% of its volume bad when
  // any segment could be blocked). Whatever waits on that split would wait for ever,
  // and refinement around it cascades: the scanned boat at B = 1.4 inserted 140k of its 200k
  // points after its bad volume had stopped falling. After kBlockAfter such failures the
  // segment is treated as sharp (mesh3d.h is_sharp_subseg): it is split no more, and what
  // would encroach it gives up (a protected, reported tetrahedron; a subface left as it is).
  // The candidates cs[0..n) that failed so: with `fl`, those whose failure fl[j] is one of
  // these; without, the sleeping ones that would have (kSleeping).
  static constexpr int kBlockAfter = 8;
  void count_segment_failures(const Candidate* cs, const int* fl, std::size_t n) {
    const std::size_t nseg = dm.sharp.size();
    if (nseg == 0) return;
    if (segment_failures.size() != nseg) {
      segment_failures.resize_discard(nseg);
      segment_failures.zero();
    }
    const m3d::TetView mv = dm.view();
    int* nf = segment_failures.data();
    std::uint8_t* sharp = dm.sharp.data();
    int* blocked = counters.data() + kBlocked;
    Ops::for_each(n, [=] GDR_HD(long long j) {
      if (fl ? cs[j].kind != m3d::kSegmentSplit || (fl[j] != m3d::kFailStar && fl[j] != m3d::kFailDelaunay)
             : cs[j].kind != m3d::kSleeping)
        return;
      const int g = m3d::segment_of(mv, cs[j].a, cs[j].b);
      if (g < 0) return;
      // Counted for every segment: one that keeps failing waits behind the others (its
      // remedy, a subsegment it encroaches, goes first: ComputeSplittingPoints).
      if (exec::atomic_add(&nf[g], 1) + 1 == kBlockAfter && (sharp[g] & m3d::kNearlyFlat)) {
        sharp[g] |= m3d::kSharp;
        exec::atomic_add(blocked, 1);
      }
    });
    clock.template stop<Space>("verify");
  }

  // Line 9: remesh each winning cavity (section 6.5) as a fan of new tetrahedra from its
  // point, and each split subface cavity as a fan of new subfaces; then compact (S1) once a
  // tenth of the elements are dead.
  // `iter` < 0 (gDP3d's driver, whose points have no listed elements): no sleeping.
  void insert(std::size_t ns, long long won, int iter = -1) {
    const std::size_t nt = tuples.size();
    // Faces are numbered 4t + f in 32 bits (tn): a mesh that could pass INT_MAX / 4
    // tetrahedra (about 537 million; an H200 holds that many) stops with an error before any
    // number wraps. A cavity's tuples make at most four new tetrahedra each.
    if (4.0 * static_cast<double>(nt) + dm.ntet > static_cast<double>(INT_MAX / 4))
      throw Error(Status::InvalidInput,
                  "one iteration's cavities hold " + std::to_string(nt) + " elements on a mesh of " +
                      std::to_string(dm.ntet) + " tetrahedra: beyond the engine's 32-bit tetrahedron numbers "
                      "(give larger sizes or a maximum of Steiner points)");
    count.resize_discard(nt);
    count2.resize_discard(nt);
    const Tuple* tp = tuples.data();
    const int* fl = failed.data();
    Ops::for_each(nt, m3d::CountNew{dm.view(), tp, fl, count.data(), count2.data()});
    const int new_tets = static_cast<int>(Ops::exclusive_scan(count.data(), count.data(), nt));
    const int new_subs = static_cast<int>(Ops::exclusive_scan(count2.data(), count2.data(), nt));
    const int old_ntet = dm.ntet, old_nsub = dm.nsub, old_npts = dm.npts;
    fresh_from = old_ntet;
    Ops::for_each(nt, m3d::StoreSlotBase{dm.view(), tp, fl, count.data(), count2.data(), old_ntet, old_nsub});
    count.release();  // one int per tuple each: not held while the mesh arrays grow
    count2.release();
    dm.reserve(old_ntet + new_tets, old_nsub + new_subs, old_npts + static_cast<int>(won));
    dm.ntet = old_ntet + new_tets;
    dm.nsub = old_nsub + new_subs;
    dm.npts = old_npts + static_cast<int>(won);
    int* pid = point_id.data();
    Ops::for_each(ns, [=] GDR_HD(long long j) { pid[j] += old_npts; });
    const m3d::TetView mv = dm.view();
    const Candidate* cs = cand.data();
    Ops::for_each(nt, m3d::CreateSubfaces{mv, tp, fl, pid});
    Ops::for_each(nt, m3d::CreateTets{mv, cs, tp, fl, pid});
    int* ctr = counters.data();
    Ops::for_each(nt, m3d::LinkNew{mv, tp, fl, ctr + kError});
    Ops::for_each(nt, m3d::FinishFlips{mv, tp, fl});
    Ops::for_each(ns, m3d::WritePoints{mv, cs, fl, pid});
    Ops::for_each(nt, [=] GDR_HD(long long i) {
      const Tuple& h = tp[i];
      if (m3d::result_of(h) != m3d::kCavity || fl[h.pt]) return;
      if (m3d::is_sub_tuple(h)) {
        mv.sflag[h.elem] = m3d::kSubDead;
        exec::atomic_add(ctr + kKilledSubs, 1);
      } else {
        mv.tflag[h.elem] = m3d::kDead;
        exec::atomic_add(ctr + kKilledTets, 1);
      }
    });
    int host_ctr[kCounters];
    counters.download(host_ctr, kCounters);
    if (host_ctr[kError])
      throw Error(Status::InternalError, "gQM3d: broken cavity while linking new tetrahedra");
    counters.zero();
    res.inserted += won;
    res.blocked_segments += host_ctr[kBlocked];
    dead_tets += host_ctr[kKilledTets];
    dead_subs += host_ctr[kKilledSubs];
    clock.template stop<Space>("insert");
    sleep_failed(ns, iter, true);
    if (params.strategies.compaction && (10 * dead_tets > dm.ntet || 10 * dead_subs > dm.nsub)) {
      m3d::compact(dm);
      dead_tets = dead_subs = 0;
      fresh_from = 0;
      wake_all();  // the tetrahedra are numbered anew
    }
    clock.template stop<Space>("compact");
  }

  // Sleeping (ours): in the end game of a scanned surface most points fail for reasons of
  // their own (no star, a new tetrahedron not Delaunay, a subsegment encroached) in
  // neighbourhoods that no other point changes, and grew the same cavity to fail again
  // every iteration (boat, B = 1.4: hundreds of iterations of a few hundred such points and
  // a few insertions each). Such a point's element sleeps: it is listed, and counted, but
  // makes no point until an insertion kills a tetrahedron of that cavity or gives one of them
  // a new neighbour (then the same walk and growth could end elsewhere), or kSleepMost
  // iterations have passed (what decides a failure reaches a little beyond the cavity: a
  // walk across a facet, a claim another point held). After this iteration's insertion
  // (`inserted`: the new tetrahedra are those from fresh_from on).
  static constexpr int kSleepMost = 16;
  void sleep_failed(std::size_t ns, int iter, bool inserted) {
    if (!params.strategies.sleeping || iter < 0) return;
    clock.restart();
    const std::size_t old_size = sleep.size();
    if (old_size < static_cast<std::size_t>(dm.ntet)) {
      sleep.resize(dm.ntet);
      int* sl = sleep.data();
      Ops::for_each(dm.ntet - old_size, [=] GDR_HD(long long i) { sl[old_size + i] = 0; });
    }
    const m3d::TetView mv = dm.view();
    const Candidate* cs = cand.data();
    const int* fl = failed.data();
    int* sl = sleep.data();
    // The points that fall asleep: failed for a reason of their own, their element alive
    // and its request for room what it was when the point was made.
    count2.resize_discard(ns);
    int* falls = count2.data();
    Ops::for_each(ns, [=] GDR_HD(long long j) {
      const int f = fl[j], e = cs[j].elem;
      falls[j] = 0;
      if ((f != m3d::kFailStar && f != m3d::kFailDelaunay && f != m3d::kFailEncroach) || e < 0) return;
      const int t = e >> 4, slot = e & 15;
      const bool room = (mv.tflag[t] & m3d::kMakeRoom) != 0;
      if ((mv.tflag[t] & m3d::kDead) || room != (cs[j].room != 0)) return;
      int w = 1 << slot;
      if (slot >= kSlotEdge0 && f != m3d::kFailEncroach) w |= sleep_counts_bit(slot);
      if (slot == kSlotTet && room) w |= kSleptRoom;
      exec::atomic_or(&sl[t], w);
      falls[j] = 1;
    });
    // Their cavities' elements are watched, and their own tetrahedra (a cavity may be empty).
    const Tuple* tp = tuples.data();
    const std::size_t nt = tuples.size();
    const std::size_t nw = exec::compact_indices<Space>(
        nt, [=] GDR_HD(long long i) { return m3d::result_of(tp[i]) == m3d::kCavity && falls[tp[i].pt]; }, list, count);
    const std::size_t nown = exec::compact_indices<Space>(ns, [=] GDR_HD(long long j) { return falls[j] != 0; }, point_id, count);
    res.slept += static_cast<long long>(nown);
    const std::size_t before = watch.size();
    watch.resize(before + nw + nown);
    Watch* wt = watch.data();
    const int* sel = list.data();
    Ops::for_each(nw, [=] GDR_HD(long long k) {
      const Tuple& h = tp[sel[k]];
      wt[before + k] = Watch{cs[h.pt].elem, m3d::is_sub_tuple(h) ? ~h.elem : h.elem, iter};
    });
    const int* own = point_id.data();
    Ops::for_each(nown, [=] GDR_HD(long long k) {
      const int e = cs[own[k]].elem;
      wt[before + nw + k] = Watch{e, e >> 4, iter};
    });
    // Wake the sleepers whose cavity changed in this insertion, or that slept long enough.
    const int fresh = inserted ? fresh_from : dm.ntet;
    const auto changed = [=] GDR_HD(int t) {  // t < 0: no tetrahedron on that side
      if (t < 0) return false;
      if (mv.tflag[t] & m3d::kDead) return true;
      for (int f = 0; f < 4; ++f)
        if (mv.tn[4 * t + f] >= 0 && (mv.tn[4 * t + f] >> 2) >= fresh) return true;
      return false;
    };
    Ops::for_each(watch.size(), [=] GDR_HD(long long i) {
      const Watch w = wt[i];
      const int t = w.elem >> 4, slot = w.elem & 15;
      if (!(sl[t] & (1 << slot))) return;
      bool wake = iter - w.since >= kSleepMost;
      if (!wake && w.what >= 0) wake = changed(w.what);
      if (!wake && w.what < 0) {
        const int s = ~w.what;
        wake = (mv.sflag[s] & m3d::kSubDead) || changed(mv.st[2 * s] >> 2) || changed(mv.st[2 * s + 1] >> 2);
      }
      if (wake) exec::atomic_and(&sl[t], ~sleep_bits(slot));
    });
    exec::keep_if(watch, [=] GDR_HD(const Watch& w) { return (sl[w.elem >> 4] & (1 << (w.elem & 15))) != 0; }, count);
    count.release();
    count2.release();
    clock.template stop<Space>("sleep");
  }

  void wake_all() {
    sleep.zero();
    watch.resize_discard(0);
  }

  // The final mesh, live elements only, with its subsegments (each once, from the least
  // tetrahedron around it) and its bad tetrahedra listed on the device: the host needs no
  // links, so none are copied.
  void download(MeshResult& out) {
    clock.restart();
    m3d::compact(dm);
    const m3d::TetView mv = dm.view();
    const Criteria crit = params.criteria;
    int* cnt = dm.aux.data();
    auto subsegment_here = [=] GDR_HD(int t, int e) {
      if (!m3d::is_subseg_edge(mv, t, e)) return false;
      const int a = mv.tv[4 * t + m3d::edge_corner(e, 0)], b = mv.tv[4 * t + m3d::edge_corner(e, 1)];
      return least_tet_around_edge(mv, t, a, b) == t;
    };
    Ops::for_each(dm.ntet, [=] GDR_HD(long long t) {
      int n = 0;
      for (int e = 0; e < 6; ++e) n += subsegment_here(static_cast<int>(t), e);
      cnt[t] = n;
    });
    const std::size_t nsub = static_cast<std::size_t>(Ops::exclusive_scan(cnt, cnt, dm.ntet));
    list.resize_discard(3 * nsub);
    int* sub = list.data();
    Ops::for_each(dm.ntet, [=] GDR_HD(long long t) {
      int o = 3 * cnt[t];
      for (int e = 0; e < 6; ++e) {
        if (!subsegment_here(static_cast<int>(t), e)) continue;
        const int a = mv.tv[4 * t + m3d::edge_corner(e, 0)], b = mv.tv[4 * t + m3d::edge_corner(e, 1)];
        sub[o++] = a;
        sub[o++] = b;
        sub[o++] = m3d::segment_of(mv, a, b);
      }
    });
    list.to_host(out.subseg);
    Ops::for_each(dm.ntet, [=] GDR_HD(long long t) {
      const int u = static_cast<int>(t);
      cnt[t] = classify_tet(mv, u, crit, tet_shape(mv, u)) != kGood;
    });
    const std::size_t nbad = static_cast<std::size_t>(Ops::exclusive_scan(cnt, cnt, dm.ntet));
    list.resize_discard(nbad);
    int* bad = list.data();
    Ops::for_each(dm.ntet, [=] GDR_HD(long long t) {
      const int next = t + 1 < mv.ntet ? cnt[t + 1] : static_cast<int>(nbad);
      if (next != cnt[t]) bad[cnt[t]] = 2 * static_cast<int>(t) + ((mv.tflag[t] & m3d::kProtected) != 0);
    });
    list.to_host(out.bad);
    dm.xyz.resize(3 * std::size_t(dm.npts));
    dm.ptype.resize(dm.npts);
    dm.xyz.to_host(out.xyz);
    dm.ptype.to_host(out.ptype);
    dm.tv.to_host(out.tv);
    if (dm.regions) dm.tregion.to_host(out.tregion);
    dm.sv.to_host(out.sv);
    dm.sfacet.to_host(out.sfacet);
    clock.template stop<Space>("download");
  }
};

template <class Space>
EngineResult refine_mesh(const m3d::HostTetMesh& host, MeshResult& out, const EngineParams& params,
                         const Callbacks& cb, m3d::HostTetMesh* final_mesh) {
  Engine<Space> engine(params, cb);
  engine.run(host, out);
  if (final_mesh) *final_mesh = engine.dm.to_host(host.input_points);
  return engine.res;
}

}  // namespace gdr::qm3d
