// gDP2d facade: the paper's Algorithm 1 end to end.
//   1. clean and check the PSLG, compute its CDT on the CPU (line 1);
//   2. refine on the chosen backend (lines 2-9, engine.h);
//   3. convert back and measure what is left bad.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <new>
#include <sstream>
#include <string>

#include "exec/space.h"
#include "gdr/refine2d.h"
#include "gdr/validate.h"
#include "refine2d/engine_dispatch.h"
#include "refine2d/input.h"

namespace gdr {
namespace {

constexpr double kPi = 3.14159265358979323846;
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
double squared_distance(const Point2& a, const Point2& b) {
  return (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
}

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
  c.chew = o.mode == EncroachMode::Chew ? 1 : 0;
  return c;
}

// Design strategies switched off for a measurement: GDR_DISABLE=s1,s3,s4,s5,touching,block_rounds,worst_first
// (benchmarks only; see Benchmarks/README.md).
r2d::Strategies strategies_from_environment() {
  r2d::Strategies s;
  const char* env = std::getenv("GDR_DISABLE");
  if (!env) return s;
  std::stringstream list(env);
  std::string name;
  while (std::getline(list, name, ',')) {
    if (name == "s1") s.compaction = false;
    else if (name == "s3") s.filtering = false;
    else if (name == "s4") s.irregular = false;
    else if (name == "s5") s.deferment = false;
    else if (name == "touching") s.touching = false;
    else if (name == "block_rounds") s.block_rounds = false;
    else if (name == "worst_first") s.worst_first = false;
    else if (!name.empty())
      throw Error(Status::InvalidInput, "GDR_DISABLE: unknown strategy '" + name +
                                            "' (known: s1, s3, s4, s5, touching, block_rounds, worst_first)");
  }
  return s;
}

// Rough output size, to let Auto choose the CPU for small jobs.
std::size_t estimate_triangles(const r2d::HostMesh& m, const Refine2dOptions& o) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (std::size_t i = 0; i < m.xy.size(); i += 2) {
    x0 = std::min(x0, m.xy[i]), x1 = std::max(x1, m.xy[i]);
    y0 = std::min(y0, m.xy[i + 1]), y1 = std::max(y1, m.xy[i + 1]);
  }
  const double area = (x1 - x0) * (y1 - y0);
  double est = 4.0 * m.points();
  if (o.max_edge_length > 0) est = std::max(est, 2.0 * area / (0.433 * o.max_edge_length * o.max_edge_length));
  if (o.max_area > 0) est = std::max(est, 2.0 * area / o.max_area);
  return est > 1e15 ? std::size_t(1e15) : static_cast<std::size_t>(est);
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

// Above 30 degrees Delaunay refinement may never end: its termination proofs stop near
// 20.7 degrees; in practice ours cascades on some generated contour maps at 34 degrees, and
// CGAL Mesh_2 on the world map at 33.5. An automatic cap makes such a run stop and report.
// The largest run measured that did finish needed 130 times its input points (the contour
// map at 33.5 degrees).
long long automatic_steiner_cap(int cdt_points, std::size_t estimated_triangles,
                                const Refine2dOptions& o) {
  if (o.max_steiner_points >= 0) return o.max_steiner_points;
  if (o.min_angle <= 30.0) return -1;
  return static_cast<long long>(
      std::max({1000.0 * cdt_points, 1e6, 4.0 * static_cast<double>(estimated_triangles)}));
}

}  // namespace

Refine2dResult refine_2d(const Pslg& input, const Refine2dOptions& options, const Callbacks& cb) {
  const auto t_start = Clock::now();
  Refine2dResult result;
  Refine2dStats& st = result.stats;
  st.input_points = static_cast<long long>(input.points.size());
  st.input_segments = static_cast<long long>(input.segments.size());
  auto aborted = [&] { return cb.abort && cb.abort(); };
  auto progress = [&](double f, const std::string& what) {
    if (cb.progress) cb.progress(f, what);
  };

  progress(0.0, "checking input");
  const r2d::CleanPslg pslg = r2d::clean_input(input, options, cb);
  st.input_seconds = since(t_start);
  st.duplicate_points_merged = pslg.duplicates_merged;
  if (aborted()) throw Error(Status::Aborted, "aborted by the caller");

  progress(0.02, "constrained Delaunay triangulation");
  auto t0 = Clock::now();
  r2d::HostMesh mesh = r2d::initial_cdt(pslg, options.remove_exterior);
  st.cdt_seconds = since(t0);
  if (aborted()) throw Error(Status::Aborted, "aborted by the caller");
  const int cdt_points = mesh.points();

  const r2d::Criteria crit = make_criteria(options);
  const std::size_t estimated_triangles = estimate_triangles(mesh, options);
  st.backend_used =
      resolve_backend(options.backend, estimated_triangles, gpu_min_triangles(options));
  if (st.backend_used == Backend::Gpu) st.device_name = device_info().name;
  else st.device_name = "CPU (" + std::to_string(cpu_threads()) + " OpenMP threads)";

  // Refinement (or, with refine off, only the engine's upload and download, which list the
  // subsegments and bad triangles the same way).
  r2d::EngineParams params;
  params.criteria = crit;
  params.max_steiner = automatic_steiner_cap(cdt_points, estimated_triangles, options);
  st.steiner_cap = params.max_steiner;
  st.automatic_steiner_cap = options.max_steiner_points < 0 && params.max_steiner >= 0;
  params.strategies = strategies_from_environment();
  if (!options.refine) params.max_iterations = 0;
  Callbacks engine_cb = cb;
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
      er = r2d::refine_mesh_cuda(mesh, mesh_out, params, engine_cb);
      mark_gpu_warm();
#endif
    } else {
      er = r2d::refine_mesh_cpu(mesh, mesh_out, params, engine_cb);
    }
  } catch (const std::bad_alloc&) {
    throw Error(Status::OutOfDeviceMemory, "out of memory during refinement");
  }
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
                           " Steiner points: above 30 degrees refinement can cascade without "
                           "end; lower the minimum angle, or set a cap of your own"
                     : "refinement stopped at the Steiner point cap (" +
                           std::to_string(st.steiner_cap) + ")");
    if (er.stalled && cb.warning)
      cb.warning("refinement stopped: the remaining bad elements cannot be split");
  }
  progress(0.96, "writing the mesh");
  const auto t_output = Clock::now();

  // Convert back: points, triangles, point types, subsegments with their input segment.
  TriMesh& out = result.mesh;
  const int np = mesh_out.points(), nt = mesh_out.triangles();
  out.points.resize(np);
  out.point_type.resize(np);
  out.triangles.resize(nt);
#pragma omp parallel for
  for (int i = 0; i < np; ++i) {
    out.points[i] = Point2{mesh_out.xy[2 * i], mesh_out.xy[2 * i + 1]};
    out.point_type[i] = static_cast<PointType>(mesh_out.ptype[i]);
  }
#pragma omp parallel for
  for (int t = 0; t < nt; ++t)
    out.triangles[t] = {mesh_out.tv[3 * t], mesh_out.tv[3 * t + 1], mesh_out.tv[3 * t + 2]};
  const std::size_t nsub = mesh_out.subseg.size() / 3;
  out.subsegments.resize(nsub);
  out.subsegment_source.resize(nsub);
  for (std::size_t k = 0; k < nsub; ++k) {
    const int s = mesh_out.subseg[3 * k + 2];
    out.subsegments[k] = {mesh_out.subseg[3 * k], mesh_out.subseg[3 * k + 1]};
    out.subsegment_source[k] = s < mesh.input_segments ? pslg.segment_origin[s] : -1;
  }

  // What is left bad (classified on the device), and how much of it the small-angle rule
  // protected.
  // The smallest angle faces the shortest edge and is at most 60 degrees, where the sine
  // grows: track the least sin^2 = (2 area)^2 / (product of the two longer squared edges),
  // and take one arcsine at the end (no trigonometry per triangle).
  double total_area = 0, min_sin2 = 1;
#pragma omp parallel for reduction(+ : total_area) reduction(min : min_sin2)
  for (int t = 0; t < nt; ++t) {
    const Point2 &a = out.points[out.triangles[t][0]], &b = out.points[out.triangles[t][1]],
                 &c = out.points[out.triangles[t][2]];
    const double area = triangle_area(a, b, c);
    total_area += area;
    const double la = squared_distance(b, c), lb = squared_distance(c, a), lc = squared_distance(a, b);
    const double others = la * lb * lc / std::min({la, lb, lc});
    min_sin2 = std::min(min_sin2, others > 0 ? 4 * area * area / others : 0.0);
  }
  const double min_angle = std::asin(std::sqrt(std::min(1.0, min_sin2))) * 180.0 / kPi;
  double bad_area = 0;
  long long protected_bad = 0;
  for (const int code : mesh_out.bad) {
    const auto& tri = out.triangles[code >> 1];
    bad_area += triangle_area(out.points[tri[0]], out.points[tri[1]], out.points[tri[2]]);
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
  st.output_seconds = since(t_output);
  st.total_seconds = since(t_start);
  progress(1.0, "done");
  return result;
}

}  // namespace gdr
