// gDP2d facade: the paper's Algorithm 1 end to end.
//   1. clean and check the PSLG, compute its CDT on the CPU (line 1);
//   2. refine on the chosen backend (lines 2-9, engine.h);
//   3. convert back and measure what is left bad.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <future>
#include <new>
#include <sstream>
#include <string>

#include <omp.h>
#include <sys/resource.h>

#include "common/disabled_strategies.h"
#include "common/trace.h"
#include "exec/space.h"
#include "gdr/refine2d.h"
#include "gdr/validate.h"
#include "predicates/predicates.h"
#include "refine2d/engine_dispatch.h"
#include "refine2d/input.h"
#include "refine2d/thin_parts.h"
#include "validate/conformity.h"

namespace gdr {
namespace {

constexpr double kPi = 3.14159265358979323846;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

r2d::Criteria make_criteria(const Refine2dOptions& o) {
  r2d::Criteria c;
  const double s = std::sin(o.min_angle * kPi / 180.0);
  c.sin2_min_angle = o.min_angle > 0 ? s * s : 0.0;
  c.max_edge2 = o.max_edge_length * o.max_edge_length;
  c.max_area2 = 2.0 * o.max_area;
  // Off-centres: the new triangle on the shortest edge gets an apex angle of theta at the
  // height cot(theta/2)/2 over it (kernels.h); 5% lower, so that rounding cannot leave that
  // triangle just below theta, bad again.
  if (o.off_centers && o.min_angle > 0) c.offcenter_h = 0.95 * 0.5 / std::tan(o.min_angle * kPi / 360.0);
  // Chew: the lens of angle 180 - 2 theta, as Triangle's (120 degrees at 30; without an angle
  // bound, 120): a vertex there is seen from the subsegment at an angle above theta.
  if (o.mode == EncroachMode::Chew) {
    const double lens = o.min_angle > 0 ? std::cos(2.0 * o.min_angle * kPi / 180.0) : 0.5;
    c.lens_cos2 = lens * lens;
  }
  return c;
}

// Up to this many CPU threads, refinement inserts its points one at a time
// (r2d::Engine::one_at_a_time) instead of by parallel iterations (on the H200 machine's host
// one thread that way beat the parallel iteration on four, eightieth to eighty-second runs;
// on sixteen the parallel iteration is 2x faster), unless segments meet at
// angles below kOneAtATimeLeastAngle radians: there (segments from one point whose ends lie
// within rounding of each other) one point at a time cascaded where the parallel
// iteration's graded order ends (Testing: fan_cascade33.poly, FanOfTinyAnglesDoesNotCascade,
// 8,182 points and a stall against 1,487). Fans down to 1.7e-5 rad meshed alike both ways.
constexpr int kOneAtATimeThreads = 4;
constexpr double kOneAtATimeLeastAngle = 1e-5;
// Below this many estimated output triangles the CPU refines on at most kOneAtATimeThreads
// threads (so one point at a time), whatever the machine has: on the H200 machine's 16
// threads the parallel iteration's synchronisation cost more than its threads gave on a
// 5k-segment map (0.09-0.20 s for the whole process against 0.06 s on one thread, Triangle
// 0.05 s; hundred-and-sixth run), while maps of 25-30k points (about 100k triangles) ran
// 1.5x faster on 16 threads. As gQM3d's threads follow its mesh.
constexpr double kFewThreadsTriangles = 40000;

// Whether two segments meet at a shared point at an angle below `angle` radians (small).
// Most points of a map end two segments: their pair is tested with one cross and one dot
// product; points with more are sorted by direction (an atan2 each, 2M of them on a
// 1M-segment map took a tenth of a second on one thread).
bool segments_meet_below(const r2d::CleanPslg& g, double angle) {
  const int n = static_cast<int>(g.points.size());
  std::vector<int> start(n + 1, 0), other(2 * g.segments.size());
  for (const auto& s : g.segments) ++start[s[0] + 1], ++start[s[1] + 1];
  for (int v = 0; v < n; ++v) start[v + 1] += start[v];
  std::vector<int> at(start.begin(), start.end() - 1);
  for (const auto& s : g.segments) other[at[s[0]]++] = s[1], other[at[s[1]]++] = s[0];
  const double tan_angle = std::tan(angle);
  bool below = false;
#pragma omp parallel reduction(|| : below)
  {
    std::vector<double> dir;  // one per thread, not one per point
#pragma omp for schedule(dynamic, 4096)
    for (int v = 0; v < n; ++v) {
      const int d = start[v + 1] - start[v];
      if (d < 2) continue;
      const Point2& o = g.points[v];
      if (d == 2) {
        const Point2 &a = g.points[other[start[v]]], &b = g.points[other[start[v] + 1]];
        const double ux = a.x - o.x, uy = a.y - o.y, wx = b.x - o.x, wy = b.y - o.y;
        const double dot = ux * wx + uy * wy, cross = std::fabs(ux * wy - uy * wx);
        below = below || (dot > 0 && cross < tan_angle * dot);
        continue;
      }
      dir.clear();
      for (int k = start[v]; k < start[v + 1]; ++k)
        dir.push_back(std::atan2(g.points[other[k]].y - o.y, g.points[other[k]].x - o.x));
      std::sort(dir.begin(), dir.end());
      dir.push_back(dir.front() + 2 * kPi);
      for (std::size_t k = 0; k + 1 < dir.size(); ++k) below = below || dir[k + 1] - dir[k] < angle;
    }
  }
  return below;
}

// Design strategies switched off for a measurement: GDR_DISABLE=s1,s3,s4,s5,touching,block_rounds,grid_rounds,worst_first,graded,work_list,cdt_assembly,one_at_a_time,petal_sinks
// (benchmarks only; see Benchmarks/README.md).
r2d::Strategies strategies_from_environment() {
  r2d::Strategies s;
  for_each_disabled_strategy(
      [&s](const std::string& name) {
        if (name == "s1") s.compaction = false;
        else if (name == "s3") s.filtering = false;
        else if (name == "s4") s.irregular = false;
        else if (name == "s5") s.deferment = false;
        else if (name == "touching") s.touching = false;
        else if (name == "block_rounds") s.block_rounds = false;
        else if (name == "grid_rounds") s.grid_rounds = false;
        else if (name == "worst_first") s.worst_first = false;
        else if (name == "graded") s.graded = false;
        else if (name == "work_list") s.work_list = false;
        else if (name == "cdt_assembly") s.cdt_assembly = false;
        else if (name == "one_at_a_time") s.one_at_a_time = false;
        else if (name == "petal_sinks") s.petal_sinks = false;
        else return false;
        return true;
      },
      "s1, s3, s4, s5, touching, block_rounds, grid_rounds, worst_first, graded, work_list, cdt_assembly, one_at_a_time, petal_sinks");
  return s;
}

// Output size from the size bounds and the area of the domain (the CDT has lost its holes
// and, with remove_exterior, its exterior). `least` is a lower bound: no triangle can be
// larger than the bounds allow (with edges up to L, the equilateral one is the largest).
// `typical` is about what refinement makes: it chooses the backend and sizes the cap.
struct SizeEstimate {
  double area = 0;
  double least = 0;
  double typical = 0;
};

// From the domain's area and the triangles the area bounds ask for (`area_bounded`).
SizeEstimate estimate_size(double area, double area_bounded, int triangles, int points,
                           const Refine2dOptions& o) {
  SizeEstimate e;
  e.area = area;
  double bounds = area_bounded;
  if (o.max_edge_length > 0)
    bounds = std::max(bounds, e.area / (0.433 * o.max_edge_length * o.max_edge_length));
  e.least = std::max(static_cast<double>(triangles), bounds);
  e.typical = std::max(4.0 * points, 2.0 * bounds);
  return e;
}

// `region_area2`: twice the regions' area bounds by region number - 1 (EngineParams).
SizeEstimate estimate_size(const r2d::HostMesh& m, const Refine2dOptions& o,
                           const std::vector<double>& region_area2) {
  double area_bounded = 0;  // the triangles the area bounds ask for, region by region
  double area = 0;
  const int nt = m.triangles();
#pragma omp parallel for reduction(+ : area, area_bounded)
  for (int t = 0; t < nt; ++t) {
    const double* a = &m.xy[2 * m.tv[3 * t]];
    const double* b = &m.xy[2 * m.tv[3 * t + 1]];
    const double* c = &m.xy[2 * m.tv[3 * t + 2]];
    const double at = 0.5 * std::fabs((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]));
    area += at;
    double bound = o.max_area;
    const int r = m.tregion.empty() ? 0 : m.tregion[t];
    if (r > 0 && r <= static_cast<int>(region_area2.size()) && region_area2[r - 1] > 0)
      bound = bound > 0 ? std::min(bound, 0.5 * region_area2[r - 1]) : 0.5 * region_area2[r - 1];
    if (bound > 0) area_bounded += at / bound;
  }
  return estimate_size(area, area_bounded, m.triangles(), m.points(), o);
}

// The same for a CDT assembled in the engine's space.
SizeEstimate estimate_size(r2d::PreparedCdt& m, const Refine2dOptions& o,
                           const std::vector<double>& region_area2) {
  const r2d::PreparedCdt::Areas a = m.areas(o.max_area, region_area2);
  return estimate_size(a.area, a.bounded, m.triangles(), m.points(), o);
}

// Smallest estimated output for which Auto takes the GPU. Measured on the H100 machine
// against the CPU path on 16 threads (Benchmarks/RESULTS.md, crossover tier): once the
// process has used the GPU, it wins from about 5k triangles (1.1x at 5.7k, 0.64x at 1.9k);
// the first GPU run of a process also pays about 0.35 s for the CUDA context and kernel
// loading, which the CPU path only loses beyond about 600k triangles. Both scale with the
// CPU path's threads.
std::size_t gpu_min_triangles(const Refine2dOptions& o) {
  if (o.gpu_min_triangles > 0) return o.gpu_min_triangles;
  const std::size_t threads = static_cast<std::size_t>(std::max(1, cpu_threads()));
  return (gpu_warm() ? 300 : 40000) * threads;
}

// Memory per triangle: the engine's arrays peak at 75-78 bytes on the H100 (100 leaves room
// for the lists of a busy iteration), on the device or, for the CPU backend, on the host; the
// output (downloaded arrays and TriMesh) takes about 45 more on the host (50 with room).
constexpr double kEngineBytesPerTriangle = 100;
constexpr double kOutputBytesPerTriangle = 50;
// Triangle edges are numbered 3t+e in ints, and dead triangles wait in the same arrays until
// compaction (up to a tenth): live triangles stay well below INT_MAX / 3.
constexpr double kMaxTriangles = 0.8 * (INT_MAX / 3);

// The value of `key` ("MemAvailable:") in a /proc file of "key value kB" lines, in bytes;
// 0 when absent.
double proc_kib_field(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string k, rest;
  double kib = 0;
  while (in >> k >> kib && std::getline(in, rest))
    if (k == key) return 1024 * kib;
  return 0;
}

// Host memory this process may still take: MemAvailable, or less under a cgroup limit (a
// container) or an address-space limit (ulimit -v). 0 when unknown.
double available_host_bytes() {
  double available = proc_kib_field("/proc/meminfo", "MemAvailable:");
  const auto limit_to = [&](double left) {
    left = std::max(0.0, left);
    available = available > 0 ? std::min(available, left) : left;
  };
  std::ifstream limit_file("/sys/fs/cgroup/memory.max"), used_file("/sys/fs/cgroup/memory.current");
  double limit = 0, used = 0;
  if (limit_file >> limit && used_file >> used) limit_to(limit - used);  // "max" does not parse
  struct rlimit as;
  if (getrlimit(RLIMIT_AS, &as) == 0 && as.rlim_cur != RLIM_INFINITY)
    limit_to(static_cast<double>(as.rlim_cur) - proc_kib_field("/proc/self/status", "VmSize:"));
  return available;
}

// The most triangles a run on backend `b` can hold, by memory and by the engine's numbering.
double triangle_capacity(Backend b) {
  double capacity = kMaxTriangles;
  const double host = available_host_bytes();
  const double host_per_triangle =
      kOutputBytesPerTriangle + (b == Backend::Gpu ? 0 : kEngineBytesPerTriangle);
  if (host > 0) capacity = std::min(capacity, host / host_per_triangle);
  if (b == Backend::Gpu && device_info().total_memory > 0)
    capacity = std::min(capacity, device_info().total_memory / kEngineBytesPerTriangle);
  return capacity;
}

std::string rounded(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v;
  return s.str();
}

// Size bounds whose least output cannot fit are refused before any time is spent on them,
// unless the caller's Steiner cap keeps the output small enough.
// (`o` and `area` in the caller's units, for the message.)
void refuse_what_cannot_fit(const SizeEstimate& e, double capacity, int cdt_triangles,
                            Backend b, const Refine2dOptions& o, double area) {
  double need = e.least;
  if (o.max_steiner_points >= 0)
    need = std::min(need, cdt_triangles + 2.0 * static_cast<double>(o.max_steiner_points));
  if (need <= capacity) return;
  std::string bounds;
  if (o.max_edge_length > 0) bounds += "maximum edge length " + rounded(o.max_edge_length);
  if (o.max_area > 0) bounds += (bounds.empty() ? "" : ", ") + ("maximum area " + rounded(o.max_area));
  if (bounds.empty()) bounds = "the regions' maximum areas";  // the only other size bounds
  const std::string ask = "the size bounds (" + bounds + ") ask for at least " +
                          rounded(std::min(need, 1e300)) + " triangles over the domain's area of " +
                          rounded(area);
  if (need > kMaxTriangles)
    throw Error(Status::InvalidInput, ask + ", more than the " + rounded(kMaxTriangles) +
                                          " that the engine can number: raise the bounds");
  const double per_triangle =
      b == Backend::Gpu ? kEngineBytesPerTriangle : kEngineBytesPerTriangle + kOutputBytesPerTriangle;
  throw Error(Status::OutOfDeviceMemory,
              ask + ", about " + rounded(need * per_triangle / 1e9) + " GB of " +
                  (b == Backend::Gpu ? "device" : "host") + " memory at " + rounded(per_triangle) +
                  " bytes per triangle, where this machine has room for " + rounded(capacity) +
                  " triangles: raise the bounds, or set a Steiner point cap");
}

// Refinement stops cleanly at a Steiner point cap: the caller's, or an automatic one. Above
// 30 degrees it may never end (the termination proofs stop near 20.7 degrees; ours cascades
// on some generated contour maps at 34 degrees, CGAL Mesh_2 on the world map at 33.5), and
// at any angle a thin domain (a needle triangle) can ask for more points than any machine
// holds. The automatic cap is 1000 times the input points, at least 1M (100k without an
// angle bound) and at least 4 times
// the triangles the size bounds ask for (the largest run measured that did finish needed
// 130 times its input points: the contour map at 33.5 degrees), and within memory. No cap
// goes beyond what the engine can number.
long long steiner_cap(int cdt_points, const SizeEstimate& e, double capacity,
                      const Refine2dOptions& o) {
  const double numbered = kMaxTriangles / 2 - cdt_points;  // about 2 triangles per point
  if (o.max_steiner_points >= 0)
    return static_cast<long long>(std::min(static_cast<double>(o.max_steiner_points), numbered));
  // Without an angle bound only encroached subsegments are split: a few points per input
  // point where refinement ends (at most 5 times the input points in fuzz2d's runs at 0
  // degrees), so the floor is 100k there (collinear points with one 1e-16 off their line
  // split each other until the cap: 1M points took 8-16 s on 2 cores).
  const double floor = o.min_angle > 0 ? 1e6 : 1e5;
  const double wanted = std::max({1000.0 * cdt_points, floor, 4.0 * e.typical});
  return static_cast<long long>(std::max(0.0, std::min(wanted, capacity / 2 - cdt_points)));
}

// The length of every segment and of the bounding box's sides (at least the convex hull's
// perimeter, whose edges can be segments too).
double segment_length(const Pslg& in) {
  double length = 0, lo[2] = {DBL_MAX, DBL_MAX}, hi[2] = {-DBL_MAX, -DBL_MAX};
  for (const auto& s : in.segments) {
    const Point2 &a = in.points[s[0]], &b = in.points[s[1]];
    length += std::hypot(b.x - a.x, b.y - a.y);
  }
  for (const Point2& p : in.points) {
    lo[0] = std::min(lo[0], p.x), hi[0] = std::max(hi[0], p.x);
    lo[1] = std::min(lo[1], p.y), hi[1] = std::max(hi[1], p.y);
  }
  return in.points.empty() ? length : length + 2 * ((hi[0] - lo[0]) + (hi[1] - lo[1]));
}

// Thin parts (thin_parts.h), on the host's copy of the CDT.
r2d::ThinEstimate estimate_thin_parts(const r2d::HostMesh& m, double tan_theta, double max_width) {
  r2d::ThinEstimate est;
  if (!(tan_theta > 0)) return est;
  double best = 0, total = 0;
  const int ntri = m.triangles();
#pragma omp parallel
  {
    r2d::ThinAt mine;
#pragma omp for schedule(dynamic, 256) nowait
    for (int t = 0; t < ntri; ++t) {
      const r2d::ThinAt r = r2d::thin_parts_at(t, m.tv.data(), m.tn.data(), m.ts.data(), m.seg.data(),
                                               m.xy.data(), tan_theta, max_width);
      mine.credit += r.credit;
      if (r.best > mine.best) mine.best = r.best, mine.width = r.width, mine.length = r.length;
    }
#pragma omp critical
    {
      total += mine.credit;
      if (mine.best > best) best = mine.best, est.width = mine.width, est.length = mine.length;
    }
  }
  est.triangles = total;
  return est;
}

// Exact rescaling (as gQM3d does): the input is multiplied by 2^k, which brings its largest
// coordinate magnitude into [1, 2), so that the predicates neither overflow nor underflow
// whatever units the input uses; the output is multiplied back by 2^-k. Both are exact when
// every coordinate is a multiple of 2^-grid_exp after scaling: grid_exp is 260 (products of
// four differences stay multiples of 2^-1040, docs/predicates.md), or less for inputs near
// the smallest doubles, so that scaling back cannot round. The engine keeps new points on
// that grid (kernels.h, on_grid); input coordinates off it are refused.
struct PowerOfTwoScale {
  int k = 0;
  int grid_exp = 260;
  explicit PowerOfTwoScale(const Pslg& in) {
    double m = 0;
    const long long n = static_cast<long long>(in.points.size());
#pragma omp parallel for reduction(max : m)
    for (long long i = 0; i < n; ++i) {
      const Point2& p = in.points[i];
      if (std::isfinite(p.x) && std::isfinite(p.y)) m = std::max({m, std::fabs(p.x), std::fabs(p.y)});
    }
    if (m > 0) k = -std::ilogb(m);
    grid_exp = std::min(grid_exp, 1074 - k);
  }
  Point2 apply(const Point2& p, int sign) const {
    return {std::ldexp(p.x, sign * k), std::ldexp(p.y, sign * k)};
  }
  // Refuses coordinates that are not multiples of 2^-grid_exp once scaled: magnitudes more
  // than about 2^208 (1e62) below the largest, where the predicates could not stay exact.
  void check_spread(const Pslg& in) const {
    long long count = 0, first = LLONG_MAX;
    const long long n = static_cast<long long>(in.points.size());
#pragma omp parallel for reduction(+ : count) reduction(min : first)
    for (long long i = 0; i < n; ++i) {
      const Point2 q = apply(in.points[i], 1);
      bool off = false;
      for (const double v : {q.x, q.y})
        off = off || (std::isfinite(v) && std::ldexp(v, grid_exp) != std::rint(std::ldexp(v, grid_exp)));
      if (off) {
        ++count;
        first = std::min(first, i);
      }
    }
    if (!count) return;
    const Point2& p = in.points[first];
    std::ostringstream msg;
    msg.precision(17);
    msg << "point " << first + in.first_index << " (" << p.x << ", " << p.y
        << ") has a coordinate too small beside the largest coordinate magnitude, 2^" << -k
        << ", for exact arithmetic";
    if (count > 1) msg << " (" << count << " points in all)";
    msg << ": nonzero coordinates must be multiples of 2^" << -(grid_exp + k)
        << " (about 2^-208 of the largest); round such coordinates to 0 or remove the point";
    throw Error(Status::InvalidInput, msg.str());
  }
  Pslg scaled(const Pslg& in) const {
    Pslg out = in;
    const long long n = static_cast<long long>(out.points.size());
#pragma omp parallel for
    for (long long i = 0; i < n; ++i) out.points[i] = apply(out.points[i], 1);
    for (Point2& p : out.holes) p = apply(p, 1);
    for (RegionSeed2& r : out.regions) {
      r.point = apply(r.point, 1);
      r.max_area = std::ldexp(r.max_area, 2 * k);
    }
    return out;
  }
  // The kernels compare squared edge lengths and twice the area: a bound whose scaled square
  // would overflow is larger than any element (off); one that would underflow is refused.
  Refine2dOptions scaled(const Refine2dOptions& o) const {
    Refine2dOptions out = o;
    const double l = std::ldexp(o.max_edge_length, k), a = std::ldexp(o.max_area, 2 * k);
    const auto refuse = [&](const std::string& what, double v, const char* square) {
      throw Error(Status::InvalidInput,
                  what + " " + rounded(v) + " cannot be honoured: its " + square +
                      " underflows the range of doubles beside the input's largest coordinate "
                      "magnitude, 2^" + std::to_string(-k) + " (it is more than 2^500 smaller)");
    };
    if (o.max_edge_length > 0 && std::isfinite(o.max_edge_length)) {
      if (!(l * l >= DBL_MIN)) refuse("maximum edge length", o.max_edge_length, "square");
      out.max_edge_length = l * l <= DBL_MAX ? l : 0.0;
    }
    if (o.max_area > 0 && std::isfinite(o.max_area)) {
      if (!(2 * a >= DBL_MIN)) refuse("maximum area", o.max_area, "double");
      out.max_area = 2 * a <= DBL_MAX ? a : 0.0;
    }
    return out;
  }
};

// Input segments not kept whole border removed regions: a hole seed on a segment or vertex,
// hole rings inside a hole, or, with remove_exterior, a chain left open (the exterior floods
// through the gap and takes what the chain was to enclose) or a dangling segment. They are
// listed in the mesh (for the validator) and said, the first few numbered as in the input
// file, instead of dropped silently.
void note_removed_segments(const Pslg& input, const r2d::CleanPslg& pslg, TriMesh& out,
                           bool remove_exterior, const Callbacks& cb) {
  out.removed_segments.clear();
  // The whole convex hull meshed: every segment lies in it, whole (0.03 s of a 1M-segment
  // run's output). The validator still checks that each is in the mesh.
  if (!remove_exterior && pslg.holes.empty()) return;
  const std::size_t inputs = input.segments.size();
  std::vector<char> present(inputs, 0);
  for (const int o : pslg.segment_origin) present[o] = 1;
  // A segment is kept when its subsegments form one path between its ends (mesh vertices
  // keep the cleaned points' numbers); a segment whose end is a merged duplicate point, when
  // any of it is left.
  std::vector<int> cleaned(input.points.size(), -1);
  for (std::size_t v = 0; v < pslg.point_origin.size(); ++v)
    if (pslg.point_origin[v] >= 0) cleaned[pslg.point_origin[v]] = static_cast<int>(v);
  // Each segment's subsegments, grouped by a counting sort (no vector per segment: a
  // million small allocations took most of the output time).
  std::vector<int> begin(inputs + 1, 0), order(out.subsegments.size());
  for (const int s : out.subsegment_source)
    if (s >= 0) ++begin[s + 1];
  for (std::size_t s = 0; s < inputs; ++s) begin[s + 1] += begin[s];
  {
    std::vector<int> fill(begin.begin(), begin.end() - 1);
    for (std::size_t k = 0; k < out.subsegments.size(); ++k)
      if (out.subsegment_source[k] >= 0) order[fill[out.subsegment_source[k]]++] = static_cast<int>(k);
  }
  std::vector<char> kept(inputs, 0);
  const long long ninputs = static_cast<long long>(inputs);
#pragma omp parallel
  {
    std::vector<std::array<int, 2>> chain;
#pragma omp for schedule(dynamic, 4096)
    for (long long s = 0; s < ninputs; ++s) {
      const int a = cleaned[input.segments[s][0]], b = cleaned[input.segments[s][1]];
      const int n = begin[s + 1] - begin[s];
      if (a < 0 || b < 0 || n == 0) {
        kept[s] = n > 0;
        continue;
      }
      const auto& e = out.subsegments[order[begin[s]]];
      if (n == 1) {  // not split: the common case needs no path search
        kept[s] = (e[0] == a && e[1] == b) || (e[0] == b && e[1] == a);
        continue;
      }
      chain.clear();
      for (int k = begin[s]; k < begin[s + 1]; ++k) chain.push_back(out.subsegments[order[k]]);
      kept[s] = !validate::chain_path(chain, a, b).empty();
    }
  }
  std::string list;
  for (std::size_t s = 0; s < inputs; ++s)
    if (present[s] && !kept[s]) {
      if (out.removed_segments.size() < 5)
        list += (list.empty() ? "" : ", ") + std::to_string(s + pslg.first_index);
      out.removed_segments.push_back(static_cast<int>(s));
    }
  const std::size_t count = out.removed_segments.size();
  if (!count || !cb.warning) return;
  // With the exterior removed, the ends of open chains (points on one segment) are named.
  std::string ends;
  long long open = 0;
  if (remove_exterior) {
    std::vector<int> degree(pslg.points.size(), 0);
    for (const auto& sg : pslg.segments) ++degree[sg[0]], ++degree[sg[1]];
    for (std::size_t v = 0; v < degree.size(); ++v)
      if (degree[v] == 1 && pslg.point_origin[v] >= 0 && open++ < 5)
        ends += (ends.empty() ? "" : ", ") + std::to_string(pslg.point_origin[v] + pslg.first_index);
  }
  cb.warning(std::to_string(count) + " input segment(s) border removed regions and are not in the mesh, or only in part (segment " +
             list + (count > 5 ? ", ..." : "") + "): " +
             (open ? std::to_string(open) + " segment chain end(s) are open (point " + ends +
                         (open > 5 ? ", ..." : "") +
                         "), and the exterior floods through the gaps: close the chains"
                   : "a hole seed on a segment or vertex, a hole ring inside a hole, or, with the exterior removed, a boundary chain that is not closed"));
}

// Hole seeds that cannot empty a region are said: outside the points' bounding box (outside
// the domain), or exactly on an input point or segment (which side they empty is then
// arbitrary). Exact tests; segments are scanned only while holes x segments stays small.
void warn_misplaced_holes(const r2d::CleanPslg& g, const Callbacks& cb) {
  if (!cb.warning || g.holes.empty() || g.points.empty()) return;
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Point2& p : g.points) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  const bool scan = static_cast<double>(g.holes.size()) * (g.segments.size() + g.points.size()) < 1e8;
  for (std::size_t h = 0; h < g.holes.size(); ++h) {
    const Point2& q = g.holes[h];
    std::string where;
    if (q.x < x0 || q.x > x1 || q.y < y0 || q.y > y1) where = "outside the domain";
    for (std::size_t v = 0; scan && where.empty() && v < g.points.size(); ++v)
      if (g.points[v].x == q.x && g.points[v].y == q.y) where = "on an input point";
    for (std::size_t s = 0; scan && where.empty() && s < g.segments.size(); ++s) {
      const Point2 &a = g.points[g.segments[s][0]], &b = g.points[g.segments[s][1]];
      if (pred::orient2d(&a.x, &b.x, &q.x) == 0 && std::min(a.x, b.x) <= q.x &&
          q.x <= std::max(a.x, b.x) && std::min(a.y, b.y) <= q.y && q.y <= std::max(a.y, b.y))
        where = "on segment " + std::to_string(g.segment_origin[s] + g.first_index);
    }
    if (!where.empty())
      cb.warning("hole " + std::to_string(h + g.first_index) + " lies " + where +
                 (where[0] == 'o' && where[1] == 'u' ? ": it removes nothing"
                                                     : ": which side it empties is arbitrary; move it inside the region to remove"));
  }
}

// The initial CDT's builder and where it runs (Refine2dOptions::cdt). The parallel one on
// the GPU from the size at which a large run prewarms the GPU; CGAL below, where it is fast.
struct CdtChoice {
  bool parallel = false, gpu = false;
};
constexpr std::size_t kGpuCdtMinInput = 50000;
CdtChoice choose_cdt(const Refine2dOptions& o, std::size_t input_size) {
  CdtChoice c;
  const bool gpu = !o.deterministic && o.backend != Backend::Cpu &&
                   resolve_backend(o.backend, input_size, kGpuCdtMinInput) == Backend::Gpu;
  switch (o.cdt) {
    case CdtMethod::Cgal: break;
    case CdtMethod::Parallel: c.parallel = true, c.gpu = !o.deterministic && o.backend != Backend::Cpu &&
                                                          resolve_backend(o.backend) == Backend::Gpu; break;
    case CdtMethod::Auto: c.parallel = c.gpu = gpu; break;
  }
  return c;
}

}  // namespace

Refine2dResult refine_2d(const Pslg& unscaled, const Refine2dOptions& user_options,
                         const Callbacks& cb) {
  const auto t_start = Clock::now();
  Refine2dResult result;
  Refine2dStats& st = result.stats;
  st.input_points = static_cast<long long>(unscaled.points.size());
  st.input_segments = static_cast<long long>(unscaled.segments.size());
  // Large inputs: the CUDA context is created while the CPU checks the input and builds the
  // CDT (it cost about 0.35 s of a first GPU run).
  if (!user_options.deterministic)
    prewarm_gpu(user_options.backend, unscaled.points.size() + unscaled.segments.size(), kGpuCdtMinInput);
  TraceSteps step("run");
  const PowerOfTwoScale scale(unscaled);
  scale.check_spread(unscaled);
  const Pslg input = scale.scaled(unscaled);
  const Refine2dOptions options = scale.scaled(user_options);
  auto aborted = [&] { return cb.abort && cb.abort(); };
  auto progress = [&](double f, const std::string& what) {
    if (cb.progress) cb.progress(f, what);
  };

  step("scaled");
  progress(0.0, "checking input");
  // Large inputs bound for the GPU's CDT are checked there first (input_checks.h).
  r2d::CleanPslg pslg = r2d::clean_input(
      input, options, cb, choose_cdt(options, input.points.size() + input.segments.size()).gpu);
  warn_misplaced_holes(pslg, cb);
  for (std::size_t v = 0; v < pslg.points.size(); ++v)  // intersection points onto the grid
    if (pslg.point_origin[v] < 0)
      for (double* c : {&pslg.points[v].x, &pslg.points[v].y}) *c = r2d::on_grid(*c, scale.grid_exp);
  st.input_seconds = since(t_start);
  st.duplicate_points_merged = pslg.duplicates_merged;
  if (aborted()) throw Error(Status::Aborted, "aborted by the caller");

  progress(0.02, "constrained Delaunay triangulation");
  auto t0 = Clock::now();
  const CdtChoice cdt = choose_cdt(options, pslg.points.size() + pslg.segments.size());
  // The GPU CDT leaves its memory cached for the refinement; hand it back when the run ends,
  // however it ends (the refinement may run on the CPU, or not at all after a refusal).
  struct TrimDevice {
    bool on;
    ~TrimDevice() {
#if defined(GDR_HAVE_CUDA)
      if (on) r2d::trim_device_memory_cuda();
#endif
    }
  } trim_device{cdt.gpu};
  const r2d::Strategies strategies = strategies_from_environment();
  r2d::HostMesh mesh;
  std::unique_ptr<r2d::PreparedCdt> prepared;  // the CDT left where it was made
  bool parallel = cdt.parallel;
  if (parallel) {
    try {
      r2d::InitialCdt c = r2d::initial_cdt_parallel(pslg, options.remove_exterior, cdt.gpu,
                                                    strategies.cdt_assembly, &st.cdt_phases);
      mesh = std::move(c.host);
      prepared = std::move(c.prepared);
    } catch (const Error& e) {
      // Chosen automatically, the GPU's CDT gives way to CGAL's when the device is full; and
      // whichever way chosen, where its own checks find it inconsistent.
      const bool full = e.status() == Status::OutOfDeviceMemory && options.cdt == CdtMethod::Auto;
      if (!full && e.status() != Status::InternalError) throw;
      if (cb.warning)
        cb.warning(std::string(full ? "the GPU's CDT ran out of memory" : "the parallel CDT failed its checks") +
                   "; CGAL's on the CPU instead: " + e.what());
      parallel = false;
      prepared.reset();
      st.cdt_phases.clear();
    }
  }
  if (!parallel) mesh = r2d::initial_cdt(pslg, options.remove_exterior);
  st.cdt_method = !parallel ? "cgal" : (cdt.gpu ? "parallel-gpu" : "parallel-cpu");
  if (cdt.gpu) mark_gpu_warm();
  st.cdt_seconds = since(t0);
  if (aborted()) throw Error(Status::Aborted, "aborted by the caller");
  const int cdt_points = prepared ? prepared->points() : mesh.points();
  const int cdt_triangles = prepared ? prepared->triangles() : mesh.triangles();
  const int input_segments = prepared ? static_cast<int>(pslg.segments.size()) : mesh.input_segments;
  step("CDT");

  r2d::Criteria crit = make_criteria(options);
  crit.grid_exp = scale.grid_exp;
  // Off-centres take larger empty circles in their petal where there are (kernels.h,
  // move_to_petal_sink); a few steps: the climbs on the maps stop after one or two. Up to 30
  // degrees, where Delaunay refinement is known to end: above, at tiny input angles, they
  // fed a cascade that the off-centres alone do not (Testing/CLI fan_cascade33.poly at 33
  // degrees: 4,120 points and a stall with 34% of the area bad, against 1,484 and none).
  if (crit.offcenter_h > 0 && strategies.petal_sinks && options.min_angle <= 30) crit.sink_steps = 4;
  std::vector<double> region_area2;  // twice each region's area bound, by region number - 1
  if (options.region_areas)
    for (const RegionSeed2& r : pslg.regions) region_area2.push_back(r.max_area > 0 ? 2 * r.max_area : 0.0);
  const SizeEstimate estimate =
      prepared ? estimate_size(*prepared, options, region_area2) : estimate_size(mesh, options, region_area2);
  step("size estimate");
  if (options.deterministic && options.backend == Backend::Gpu)
    throw Error(Status::InvalidInput,
                "deterministic runs use the CPU backend on one thread: on the GPU, as on several "
                "CPU threads, the mesh depends on thread timing");
  st.backend_used = options.deterministic
                        ? Backend::Cpu
                        : resolve_backend(options.backend,
                                          static_cast<std::size_t>(std::min(estimate.typical, 1e15)),
                                          gpu_min_triangles(options));
  const int engine_threads = options.deterministic ? 1
                             : estimate.typical < kFewThreadsTriangles ? std::min(cpu_threads(), kOneAtATimeThreads)
                                                                      : cpu_threads();
  if (prepared && (st.backend_used == Backend::Gpu) != cdt.gpu) {  // refined elsewhere
    mesh = prepared->download();
    prepared.reset();
  }
  if (st.backend_used == Backend::Gpu) st.device_name = device_info().name;
  else st.device_name = cpu_device_name(engine_threads);

  // Refinement (or, with refine off, only the engine's upload and download, which list the
  // subsegments and bad triangles the same way).
  r2d::EngineParams params;
  params.criteria = crit;
  params.one_at_a_time = options.refine && st.backend_used == Backend::Cpu && strategies.one_at_a_time &&
                         engine_threads <= kOneAtATimeThreads &&
                         !segments_meet_below(pslg, kOneAtATimeLeastAngle);
  params.region_area2 = region_area2;
  if (options.refine) {
    const double capacity = triangle_capacity(st.backend_used);
    refuse_what_cannot_fit(estimate, capacity, cdt_triangles, st.backend_used, user_options,
                           std::ldexp(estimate.area, -2 * scale.k));
    params.max_steiner = steiner_cap(cdt_points, estimate, capacity, options);
    st.steiner_cap = params.max_steiner;
    st.automatic_steiner_cap = options.max_steiner_points < 0;
  }
  // Thin parts that certainly need more points than the automatic cap allows are refused
  // before much time is spent on them (a 1 x 1e-11 rectangle at 25 degrees ran 15-40 s to
  // the cap of 1M); a cap of the caller's own meshes them up to that cap. The estimate reads
  // only the CDT: on a CDT assembled in the engine's space it runs there first; on the host's
  // copy before a CPU refinement it runs first too, and beside a GPU one it runs on the host
  // meanwhile (0.1 s of set-up on a 1M-segment map), where a refusal stops the refinement.
  const auto thin_refusal = [&]() -> std::string {
    const auto t_thin = Clock::now();
    const double tan_theta = std::tan(options.min_angle * kPi / 180.0);
    const double max_width = r2d::thin_width_limit(segment_length(input), tan_theta, double(params.max_steiner));
    const r2d::ThinEstimate thin =
        prepared ? prepared->thin_parts(tan_theta, max_width) : estimate_thin_parts(mesh, tan_theta, max_width);
    const double points = 0.5 * thin.triangles;  // about 2 triangles per point, or fewer
    if (std::getenv("GDR_TRACE"))
      std::fprintf(stderr, "gdr-trace thin parts: at least %.3g triangles (thinnest %.3g wide), %.3f s\n",
                   thin.triangles, thin.width, since(t_thin));
    if (points <= static_cast<double>(params.max_steiner)) return {};
    return "the minimum angle of " + rounded(user_options.min_angle) + " degrees asks for at least " +
           rounded(points) + " Steiner points in the input's thin parts (the thinnest " +
           rounded(std::ldexp(thin.width, -scale.k)) + " wide along " +
           rounded(std::ldexp(thin.length, -scale.k)) + "), more than the automatic cap of " +
           rounded(double(params.max_steiner)) +
           ": lower the angle, or set --max-steiner to mesh up to a cap";
  };
  std::atomic<bool> thin_refused{false};
  std::future<std::string> thin_beside;
  if (options.refine && options.min_angle > 0 && st.automatic_steiner_cap) {
    // (Beside one point at a time too: that refinement keeps one thread busy.)
    if ((st.backend_used == Backend::Gpu || params.one_at_a_time) && !prepared)
      thin_beside = std::async(std::launch::async, [&] {
        std::string why = thin_refusal();
        if (!why.empty()) thin_refused = true;
        return why;
      });
    else if (const std::string why = thin_refusal(); !why.empty())
      throw Error(Status::InvalidInput, why);
  }
  const auto refuse_thin = [&] {
    if (!thin_beside.valid()) return;
    const std::string why = thin_beside.get();
    if (!why.empty()) throw Error(Status::InvalidInput, why);
  };

  step("caps");
  params.strategies = strategies;
  if (!options.refine) params.max_iterations = 0;
  Callbacks engine_cb = cb;
  engine_cb.abort = [&] { return thin_refused.load() || (cb.abort && cb.abort()); };
  if (cb.progress)  // iterations have no known total: report a slowly saturating fraction
    engine_cb.progress = [&cb, n = 0](double, const std::string& what) mutable {
      ++n;
      cb.progress(0.05 + 0.9 * (1.0 - 1.0 / (1.0 + 0.05 * n)), what);
    };
  t0 = Clock::now();
  r2d::MeshResult mesh_out;
  r2d::EngineResult er;
  try {
    if (st.backend_used == Backend::Gpu) {
#if defined(GDR_HAVE_CUDA)
      er = prepared ? prepared->refine(mesh_out, params, engine_cb)
                    : r2d::refine_mesh_cuda(mesh, mesh_out, params, engine_cb);
      mark_gpu_warm();
#endif
    } else {
      const int threads = cpu_threads();
      omp_set_num_threads(engine_threads);
      try {
        er = prepared ? prepared->refine(mesh_out, params, engine_cb)
                      : r2d::refine_mesh_cpu(mesh, mesh_out, params, engine_cb);
      } catch (...) {
        omp_set_num_threads(threads);
        throw;
      }
      omp_set_num_threads(threads);
    }
  } catch (const std::bad_alloc&) {
    refuse_thin();
    throw Error(Status::OutOfDeviceMemory, "out of memory during refinement");
  } catch (const Error&) {
    refuse_thin();
    throw;
  }
  refuse_thin();
  if (options.refine) {
    st.refine_seconds = since(t0);
    st.iterations = er.iterations;
    st.steiner_cap_reached = er.cap_reached;
    st.stalled = er.stalled;
    st.phases = er.phases;
    if (st.backend_used == Backend::Gpu) st.peak_device_bytes = er.peak_bytes;
    if (er.cap_reached && cb.warning)
      cb.warning(st.automatic_steiner_cap
                     ? "refinement stopped at the automatic cap of " +
                           std::to_string(st.steiner_cap) +
                           " Steiner points: the bounds ask for more here (a cascade above 30 "
                           "degrees, a thin domain); relax them, or set a cap of your own"
                     : "refinement stopped at the Steiner point cap (" +
                           std::to_string(st.steiner_cap) + ")");
    if (er.small_angle_cascade && cb.warning)
      cb.warning("refinement stopped: " + std::to_string(er.stuck) + " of the " +
                 std::to_string(er.live) +
                 " triangles are bad next to small input angles, and new points only add more "
                 "(a needle, or segments at tiny angles); the mesh is valid: relax --min-angle, "
                 "or widen those angles");
    else if (er.slow_cascade && cb.warning)
      cb.warning("refinement stopped after " + std::to_string(er.iterations) + " iterations: " +
                 std::to_string(er.stuck) +
                 " bad elements remain, and 512 iterations did not halve them (a cascade, as "
                 "above 30 degrees or at tiny input angles); the mesh is valid: relax --min-angle");
    else if (er.starved && cb.warning)
      cb.warning("refinement stopped after " + std::to_string(er.iterations) + " iterations: " +
                 std::to_string(er.stuck) +
                 " bad elements remain, and 32 iterations inserted under a hundredth of that many "
                 "points (a cascade at tiny input angles); the mesh is valid: relax --min-angle, "
                 "or widen those angles");
    else if (er.stalled && cb.warning)
      cb.warning("refinement stopped: no point can split the " + std::to_string(er.stuck) +
                 " element(s) left (bad triangles or encroached subsegments)");
  }
  step("refinement");
  progress(0.96, "writing the mesh");
  const auto t_output = Clock::now();

  // Convert back: points, triangles, point types, subsegments with their input segment.
  TriMesh& out = result.mesh;
  out.first_index = input.first_index;
  const int np = mesh_out.points(), nt = mesh_out.triangles();
  out.points.resize(np);
#pragma omp parallel for
  for (int i = 0; i < np; ++i)
    out.points[i] = scale.apply(Point2{mesh_out.xy[2 * i], mesh_out.xy[2 * i + 1]}, -1);
  out.point_type = std::move(mesh_out.ptype);
  out.triangles = std::move(mesh_out.tv);
  const std::size_t nsub = mesh_out.subseg.size() / 4;
  out.subsegments.resize(nsub);
  out.subsegment_source.resize(nsub);
#pragma omp parallel for
  for (std::size_t k = 0; k < nsub; ++k) {
    const int s = mesh_out.subseg[4 * k + 2];
    out.subsegments[k] = {mesh_out.subseg[4 * k], mesh_out.subseg[4 * k + 1]};
    out.subsegment_source[k] = s < input_segments ? pslg.segment_origin[s] : -1;
  }
  step("output converted");
  note_removed_segments(input, pslg, out, options.remove_exterior, cb);
  step("segments kept");
  r2d::carry_input_data(input, pslg, mesh_out.xy.data(), mesh_out.subseg.data(),
                        mesh_out.tregion.empty() ? nullptr : mesh_out.tregion.data(),
                        options.region_attributes, out);

  step("markers and attributes");
  // What is left bad (classified on the device), and how much of it the small-angle rule
  // protected; the total area and least sin^2 of an angle come from the engine (download).
  const auto scaled_point = [&](int v) { return Point2{mesh_out.xy[2 * v], mesh_out.xy[2 * v + 1]}; };
  const auto scaled_area = [&](const std::array<int, 3>& tri) {
    return triangle_area(scaled_point(tri[0]), scaled_point(tri[1]), scaled_point(tri[2]));
  };
  const double total_area = mesh_out.area, min_sin2 = mesh_out.min_sin2;
  const double min_angle = std::asin(std::sqrt(std::min(1.0, min_sin2))) * 180.0 / kPi;
  double bad_area = 0;
  long long protected_bad = 0;
  for (const int code : mesh_out.bad) {
    const auto& tri = out.triangles[code >> 1];
    bad_area += scaled_area(tri);
    protected_bad += code & 1;
  }
  const long long bad = static_cast<long long>(mesh_out.bad.size());
  st.output_points = np;
  st.output_triangles = nt;
  st.steiner_points = np - cdt_points;
  st.bad_triangles = bad;
  st.small_angle_bad = protected_bad;
  st.bad_area_percent = total_area > 0 ? 100.0 * bad_area / total_area : 0.0;
  st.min_angle_deg = nt ? min_angle : 0.0;
  step("bad area");
  st.output_seconds = since(t_output);
  st.total_seconds = since(t_start);
  progress(1.0, "done");
  return result;
}

}  // namespace gdr
