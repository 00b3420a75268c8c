// The parallel CDT's domain assembled where it was computed (issue 14): the exterior taken
// away, the triangles numbered and relinked, the hull segments numbered and the engine's
// mesh built in the space's memory, so that a GPU run's CDT never goes to the host and back
// (download, host assembly and upload took 0.12 s of a 0.52 s run at 1M segments on the
// H200). The same steps as the host's assemble_cdt (cdt_parallel.cpp), which stays for what
// this one leaves to it, slivers at the hull to peel; hole and region seeds are located by
// the same walk and flood the same components. Both give the same mesh, triangle for
// triangle (cdt2d_test).
#pragma once
#include <cstring>
#include <memory>
#include <vector>

#include "common/trace.h"
#include "gdr/error.h"
#include "refine2d/cdt_engine.h"
#include "refine2d/engine_dispatch.h"
#include "refine2d/input.h"
#include "refine2d/thin_parts.h"

namespace gdr::r2d {

namespace detail {

// Union-find over triangles, safe under concurrent unions: a root is hooked under the smaller
// root by compare-and-swap, and finds halve their paths as they go (a benign race).
GDR_HD inline int find_root(int* parent, int x) {
  for (;;) {
    const int p = exec::volatile_load(&parent[x]);
    if (p == x) return x;
    const int g = exec::volatile_load(&parent[p]);
    if (g != p) parent[x] = g;
    x = g;
  }
}
GDR_HD inline void unite(int* parent, int a, int b) {
  for (;;) {
    a = find_root(parent, a);
    b = find_root(parent, b);
    if (a == b) return;
    if (a > b) {
      const int t = a;
      a = b;
      b = t;
    }
    if (exec::atomic_cas(&parent[b], b, a) == b) return;
  }
}

// A positive double's bits, which order as the doubles do.
GDR_HD inline exec::u64 positive_bits(double d) {
#if defined(__CUDA_ARCH__)
  return static_cast<exec::u64>(__double_as_longlong(d));
#else
  exec::u64 b;
  std::memcpy(&b, &d, sizeof b);
  return b;
#endif
}

}  // namespace detail

template <class Space>
struct AssembledCdt {
  DeviceMesh<Space> dm;           // the engine's mesh
  exec::Buffer<Space, int> ts;    // per triangle edge: its segment or -1 (mesh2d.h)
  int input_segments = 0;
  bool regions = false;           // region numbers in the flags (kRegionShift)
};

// Assembles `cdt` (its segments: `input` then hull segments) into `out`. False, with `cdt`
// untouched, where a hull edge has a sliver to peel (the host does that).
template <class Space>
bool assemble_in_space(ParallelCdt<Space>& cdt, const std::vector<int>& input,
                       const std::vector<Point2>& seeds, int holes, AssembledCdt<Space>& out) {
  using Ops = exec::Ops<Space>;
  using Buf = exec::Buffer<Space, int>;
  const int n = cdt.n, nt_all = cdt.dm.ntri, ninput = static_cast<int>(input.size() / 2);
  const int* tv = cdt.dm.tv.data();
  const int* tn = cdt.dm.tn.data();
  const int* tseg = cdt.tseg.data();
  const double* xy = cdt.dm.xy.data();
  TraceSteps trace("CDT assembly in the space");
  const auto step = [&](const char* what) {  // waits for the device only when tracing
    if (!trace.on()) return;
    Ops::synchronize();
    trace(what);
  };
  // Outside: the components (across edges that are no segment) of the triangles at the
  // bounding triangle.
  Buf parent(nt_all), outside(nt_all);
  int* par = parent.data();
  int* out_flag = outside.data();
  exec::iota<Space>(par, nt_all);
  outside.zero();
  Ops::for_each(nt_all, [=] GDR_HD(long long t) {
    for (int i = 0; i < 3; ++i) {
      const int nb = tn[3 * t + i];
      if (tseg[3 * t + i] < 0 && nb >= 0 && nb / 3 > t) detail::unite(par, static_cast<int>(t), nb / 3);
    }
  });
  Ops::for_each(nt_all, [=] GDR_HD(long long t) {
    if (tv[3 * t] >= n || tv[3 * t + 1] >= n || tv[3 * t + 2] >= n)
      out_flag[detail::find_root(par, static_cast<int>(t))] = 1;
  });
  // Hole seeds empty their components; region seeds number theirs, a later seed winning (as
  // Triangle does). Each is located by the host's walk (from triangle 0, walk_to), else by a
  // scan of all triangles.
  const int nseeds = static_cast<int>(seeds.size()), nregions = nseeds - holes;
  Buf comp_region(nregions > 0 ? nt_all : 0);
  int* creg = comp_region.data();
  if (nseeds > 0) {
    std::vector<double> sxy;
    for (const Point2& p : seeds) sxy.insert(sxy.end(), {p.x, p.y});
    exec::Buffer<Space, double> seed_xy;
    seed_xy.upload(sxy);
    Buf seed_tri(nseeds), walked(nseeds), missed(1);
    missed.zero();
    const double* sp = seed_xy.data();
    int* st = seed_tri.data();
    int* wk = walked.data();
    int* ms = missed.data();
    const MeshView mv = cdt.dm.view();
    Ops::for_each(nseeds, [=] GDR_HD(long long k) {
      const int t = nt_all > 0 ? walk_to(mv, 0, sp + 2 * k, 100000) : -1;
      wk[k] = t >= 0;
      st[k] = t >= 0 ? t : INT_MAX;
      if (t < 0) *ms = 1;
    });
    if (missed.get(0))  // the first triangle that holds it
      Ops::for_each(nt_all, [=] GDR_HD(long long t) {
        for (int k = 0; k < nseeds; ++k) {
          if (wk[k] || exec::volatile_load(&st[k]) <= t) continue;
          bool inside = true;
          for (int i = 0; i < 3 && inside; ++i)
            inside = pred::orient2d(xy + 2 * tv[3 * t + (i + 1) % 3], xy + 2 * tv[3 * t + (i + 2) % 3], sp + 2 * k) >= 0;
          if (inside) exec::atomic_min(&st[k], static_cast<int>(t));
        }
      });
    if (nregions > 0) comp_region.zero();
    Ops::for_each(nseeds, [=] GDR_HD(long long k) {
      if (st[k] == INT_MAX) return;  // in no triangle
      const int r = detail::find_root(par, st[k]);
      if (k < holes) out_flag[r] = 1;
      else exec::atomic_max(&creg[r], static_cast<int>(k - holes) + 1);
    });
  }
  Buf gone(nt_all), region(creg ? nt_all : 0);  // per triangle: outside; its region number
  int* gn = gone.data();
  int* rgw = region.data();
  Ops::for_each(nt_all, [=] GDR_HD(long long t) {
    const int r = detail::find_root(par, static_cast<int>(t));
    gn[t] = out_flag[r];
    if (rgw) rgw[t] = creg[r];
  });
  parent.release();
  outside.release();
  comp_region.release();
  const int* rg = region.data();
  const auto is_out = [=] GDR_HD(int t) { return gn[t] != 0; };
  // Slivers at the hull (peel_hull_slivers' test): left to the host.
  Buf sliver(1);
  sliver.zero();
  int* sl = sliver.data();
  Ops::for_each(nt_all, [=] GDR_HD(long long t) {
    if (is_out(static_cast<int>(t))) return;
    for (int i = 0; i < 3; ++i) {
      const int nb = tn[3 * t + i], s = tseg[3 * t + i];
      if (!((nb < 0 || is_out(nb / 3)) && (s < 0 || s >= ninput))) continue;
      const int v = tv[3 * t + i], p = tv[3 * t + (i + 1) % 3], q = tv[3 * t + (i + 2) % 3];
      if (v >= n || p >= n || q >= n) continue;
      const double ux = xy[2 * q] - xy[2 * p], uy = xy[2 * q + 1] - xy[2 * p + 1];
      const double wx = xy[2 * v] - xy[2 * p], wy = xy[2 * v + 1] - xy[2 * p + 1];
      const double len2 = ux * ux + uy * uy, along = ux * wx + uy * wy;
      if (fabs(ux * wy - uy * wx) <= kHullSliver * len2 && along > 0 && along < len2) *sl = 1;
    }
  });
  step("exterior");
  if (sliver.get(0)) return false;
  step("hull slivers");

  // Kept triangles numbered in order (a scan), then copied and relinked.
  Buf id(nt_all);
  int* ids = id.data();
  Ops::for_each(nt_all, [=] GDR_HD(long long t) { ids[t] = is_out(static_cast<int>(t)) ? 0 : 1; });
  const int nt = static_cast<int>(Ops::exclusive_scan(ids, ids, nt_all));
  if (nt == 0) throw_empty_domain();
  DeviceMesh<Space>& dm = out.dm;
  dm.tv.resize_discard(3 * std::size_t(nt));
  dm.tn.resize_discard(3 * std::size_t(nt));
  out.ts.resize_discard(3 * std::size_t(nt));
  int* tv2 = dm.tv.data();
  int* tn2 = dm.tn.data();
  int* ts2 = out.ts.data();
  Ops::for_each(nt_all, [=] GDR_HD(long long t) {
    if (is_out(static_cast<int>(t))) return;
    const int u = ids[t];
    for (int i = 0; i < 3; ++i) {
      tv2[3 * u + i] = tv[3 * t + i];
      const int nb = tn[3 * t + i];
      tn2[3 * u + i] = nb < 0 || is_out(nb / 3) ? -1 : 3 * ids[nb / 3] + nb % 3;
      const int s = tseg[3 * t + i];
      ts2[3 * u + i] = s >= 0 && s < ninput ? s : (tn2[3 * u + i] < 0 ? -2 : -1);
    }
  });
  step("numbering, copy and relink");
  // Domain-boundary edges that are not input segments become hull segments, numbered after
  // the input's in triangle order.
  Buf count(nt);
  int* cnt = count.data();
  Ops::for_each(nt, [=] GDR_HD(long long u) {
    cnt[u] = (ts2[3 * u] == -2) + (ts2[3 * u + 1] == -2) + (ts2[3 * u + 2] == -2);
  });
  const int nhull = static_cast<int>(Ops::exclusive_scan(cnt, cnt, nt));
  dm.seg.resize_discard(2 * std::size_t(ninput + nhull));
  if (ninput) Ops::copy_to_space(dm.seg.data(), input.data(), input.size() * sizeof(int));
  int* sg = dm.seg.data();
  Ops::for_each(nt, [=] GDR_HD(long long u) {
    int k = ninput + cnt[u];
    for (int i = 0; i < 3; ++i)
      if (ts2[3 * u + i] == -2) {
        ts2[3 * u + i] = k;
        sg[2 * k] = tv2[3 * u + (i + 1) % 3];
        sg[2 * k + 1] = tv2[3 * u + (i + 2) % 3];
        ++k;
      }
  });
  step("hull segments");
  // The engine's mesh: the CDT's points (its bounding triangle's three beyond npts), flags
  // from the segments, and the segments at each vertex in segment order.
  dm.npts = n;
  dm.ntri = nt;
  dm.xy = std::move(cdt.dm.xy);
  dm.ptype = std::move(cdt.dm.ptype);
  dm.pseg = std::move(cdt.dm.pseg);
  dm.tflag.resize_discard(nt);
  int* f = dm.tflag.data();
  Buf kept_region(rg ? nt : 0);
  int* kr = kept_region.data();
  if (rg)
    Ops::for_each(nt_all, [=] GDR_HD(long long t) {
      if (!is_out(static_cast<int>(t))) kr[ids[t]] = rg[t];
    });
  Ops::for_each(nt, [=] GDR_HD(long long t) {
    int bits = kFresh;
    for (int i = 0; i < 3; ++i)
      if (ts2[3 * t + i] >= 0) bits |= kSubseg0 << i;
    if (kr) bits |= kr[t] << kRegionShift;
    f[t] = bits;
  });
  out.regions = rg != nullptr;
  dm.mark.resize_discard(nt);
  dm.mark.zero();
  dm.aux.resize_discard(nt);
  const int ns = ninput + nhull;
  dm.vseg_begin.resize_discard(std::size_t(n) + 1);
  dm.vseg_begin.zero();
  dm.vseg.resize_discard(2 * std::size_t(ns));
  int* begin = dm.vseg_begin.data();
  int* vs = dm.vseg.data();
  Ops::for_each(ns, [=] GDR_HD(long long s) {
    exec::atomic_add(&begin[sg[2 * s]], 1);
    exec::atomic_add(&begin[sg[2 * s + 1]], 1);
  });
  Ops::exclusive_scan(begin, begin, std::size_t(n) + 1);
  Buf fill(n);
  int* fl = fill.data();
  Ops::copy_d2d(fl, begin, std::size_t(n) * sizeof(int));
  Ops::for_each(ns, [=] GDR_HD(long long s) {
    for (int k = 0; k < 2; ++k) vs[exec::atomic_add(&fl[sg[2 * s + k]], 1)] = static_cast<int>(s);
  });
  Ops::for_each(n, [=] GDR_HD(long long v) {  // a few per vertex: insertion sort
    for (int i = begin[v] + 1; i < begin[v + 1]; ++i)
      for (int j = i; j > begin[v] && vs[j - 1] > vs[j]; --j) {
        const int x = vs[j];
        vs[j] = vs[j - 1];
        vs[j - 1] = x;
      }
  });
  step("engine's mesh");
  out.input_segments = ninput;
  return true;
}

// The CDT assembled in the space, for refine_2d (engine_dispatch.h, PreparedCdt).
template <class Space>
class PreparedCdtIn final : public PreparedCdt {
 public:
  explicit PreparedCdtIn(std::unique_ptr<AssembledCdt<Space>> a) : a_(std::move(a)) {}
  int points() const override { return a_->dm.npts; }
  int triangles() const override { return a_->dm.ntri; }

  Areas areas(double max_area, const std::vector<double>& region_area2) override {
    using Ops = exec::Ops<Space>;
    const int nt = a_->dm.ntri;
    exec::Buffer<Space, double> at(nt), bounded(nt), bounds;
    bounds.upload(region_area2);
    double* ar = at.data();
    double* bd = bounded.data();
    const double* rb = bounds.data();
    const int nb = static_cast<int>(region_area2.size());
    const int* tv = a_->dm.tv.data();
    const int* fl = a_->dm.tflag.data();
    const double* xy = a_->dm.xy.data();
    Ops::for_each(nt, [=] GDR_HD(long long t) {
      const double* a = xy + 2 * tv[3 * t];
      const double* b = xy + 2 * tv[3 * t + 1];
      const double* c = xy + 2 * tv[3 * t + 2];
      ar[t] = 0.5 * fabs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
      // The triangles the area bounds ask for (estimate_size's rule, region by region).
      double bound = max_area;
      const int r = fl[t] >> kRegionShift;
      if (r > 0 && r <= nb && rb[r - 1] > 0) bound = bound > 0 ? fmin(bound, 0.5 * rb[r - 1]) : 0.5 * rb[r - 1];
      bd[t] = bound > 0 ? ar[t] / bound : 0.0;
    });
    Areas s;
    s.area = Ops::exclusive_scan(ar, ar, nt);
    s.bounded = Ops::exclusive_scan(bd, bd, nt);
    return s;
  }

  ThinEstimate thin_parts(double tan_theta, double max_width) override {
    using Ops = exec::Ops<Space>;
    ThinEstimate est;
    if (!(tan_theta > 0)) return est;
    const int nt = a_->dm.ntri;
    exec::Buffer<Space, double> credit(nt), largest(nt);
    exec::Buffer<Space, exec::u64> best(1);
    exec::Buffer<Space, int> at(1);
    exec::Buffer<Space, double> thinnest(2);
    best.zero();
    at.set(0, nt);
    double* cr = credit.data();
    double* lg = largest.data();
    exec::u64* bs = best.data();
    int* where = at.data();
    double* th = thinnest.data();
    const int *tv = a_->dm.tv.data(), *tn = a_->dm.tn.data(), *ts = a_->ts.data(), *sg = a_->dm.seg.data();
    const double* xy = a_->dm.xy.data();
    // Positive doubles order as their bits: the largest single credit by an integer maximum,
    // then the first triangle that has it.
    Ops::for_each_heavy(nt, [=] GDR_HD(long long t) {
      const ThinAt r = thin_parts_at(static_cast<int>(t), tv, tn, ts, sg, xy, tan_theta, max_width);
      cr[t] = r.credit;
      lg[t] = r.best;
      if (r.best > 0) exec::atomic_max(bs, detail::positive_bits(r.best));
    });
    Ops::for_each(nt, [=] GDR_HD(long long t) {
      if (lg[t] > 0 && detail::positive_bits(lg[t]) == *bs) exec::atomic_min(where, static_cast<int>(t));
    });
    Ops::for_each(1, [=] GDR_HD(long long) {
      th[0] = th[1] = 0;
      if (*where < nt) {
        const ThinAt r = thin_parts_at(*where, tv, tn, ts, sg, xy, tan_theta, max_width);
        th[0] = r.width;
        th[1] = r.length;
      }
    });
    est.triangles = Ops::exclusive_scan(cr, cr, nt);
    est.width = thinnest.get(0);
    est.length = thinnest.get(1);
    return est;
  }

  HostMesh download() override {
    HostMesh m;
    DeviceMesh<Space>& dm = a_->dm;
    dm.xy.resize(2 * std::size_t(dm.npts));
    dm.ptype.resize(dm.npts);
    dm.pseg.resize(dm.npts);
    dm.xy.to_host(m.xy);
    dm.ptype.to_host(m.ptype);
    dm.pseg.to_host(m.pseg);
    dm.tv.to_host(m.tv);
    dm.tn.to_host(m.tn);
    a_->ts.to_host(m.ts);
    dm.seg.to_host(m.seg);
    if (a_->regions) {
      exec::Buffer<Space, int> region(dm.ntri);
      int* rg = region.data();
      const int* fl = dm.tflag.data();
      exec::Ops<Space>::for_each(dm.ntri, [=] GDR_HD(long long t) { rg[t] = fl[t] >> kRegionShift; });
      region.to_host(m.tregion);
    }
    m.input_segments = a_->input_segments;
    return m;
  }

  EngineResult refine(MeshResult& out, const EngineParams& params, const Callbacks& cb) override {
    struct Trim {  // hand cached scratch memory back, also after an error
      ~Trim() { exec::Ops<Space>::trim(); }
    } trim;
    a_->ts.release();
    auto a = std::move(a_);
    return refine_mesh<Space>(std::move(a->dm), a->regions, out, params, cb);
  }

 private:
  std::unique_ptr<AssembledCdt<Space>> a_;
};

// The whole parallel CDT (cdt_engine.h) and, with `assemble`, its assembly in the space.
template <class Space>
ParallelCdtResult parallel_cdt_assembled(const std::vector<double>& xy, const std::vector<int>& input,
                                         bool hull, bool assemble, const std::vector<Point2>& seeds,
                                         int holes) {
  ParallelCdtResult r;
  ParallelCdt<Space> cdt;
  cdt.triangulate_points(xy);
  std::vector<int> segments = input;
  if (hull) {
    const std::vector<int> h = hull_segments(xy.data(), cdt.hull_candidates());
    segments.insert(segments.end(), h.begin(), h.end());
    cdt.clock.template stop<Space>("hull");
  }
  cdt.recover_segments(segments);
  auto a = std::make_unique<AssembledCdt<Space>>();
  cdt.release_scratch();
  if (assemble && assemble_in_space(cdt, input, seeds, holes, *a)) {
    cdt.clock.template stop<Space>("assembly");
    r.prepared = std::make_unique<PreparedCdtIn<Space>>(std::move(a));
  } else {
    cdt.download(r.raw);
  }
  r.phases = cdt.res.phases;
  return r;
}

}  // namespace gdr::r2d
