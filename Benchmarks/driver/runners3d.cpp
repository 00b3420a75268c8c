// Our 3D runners in-process: gQM3d (gdr::quality_tet_mesh) and gDP3d
// (gdr::restricted_delaunay_3d), each on the GPU or the CPU; and the bounds the constrained
// 3D runners share (TetGen's switches are derived from them).
#include <stdlib.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "bench.h"
#include "gdr/backend.h"
#include "gdr/error.h"
#include "gdr/qm3d.h"
#include "gdr/rdt3d.h"
#include "gdr/validate.h"

namespace gdr_bench {

// A volume bound V gives about kTetsPerVolumeBound * (enclosed volume) / V tetrahedra where
// it, not the surface, sets the size: measured with TetGen 1.5 on a 2k-triangle torus, 2.17
// (B = 1.4) and 1.99 (B = 2.0) at 1M volume units, 2.3 and 2.1 at 300k. Where the surface
// alone asks for many tets the output is larger than the target.
const double kTetsPerVolumeBound = 2.1;

namespace {

// The number after `letter` in TetGen switches ("pq1.4/10a0.01": q -> 1.4, second 10), or -1.
double switch_number(const std::string& sw, char letter, bool after_slash = false) {
  const auto at = sw.find(letter);
  if (at == std::string::npos) return -1;
  std::size_t i = at + 1;
  auto number = [&](std::size_t& k) {
    const std::size_t from = k;
    while (k < sw.size() && (std::isdigit(static_cast<unsigned char>(sw[k])) || sw[k] == '.' ||
                             ((sw[k] == 'e' || sw[k] == 'E') && k + 1 < sw.size() &&
                              (std::isdigit(static_cast<unsigned char>(sw[k + 1])) || sw[k + 1] == '-'))))
      k += (sw[k] == 'e' || sw[k] == 'E') && sw[k + 1] == '-' ? 2 : 1;
    return k > from ? std::atof(sw.substr(from, k - from).c_str()) : -1.0;
  };
  const double first = number(i);
  if (!after_slash) return first;
  if (i < sw.size() && sw[i] == '/') return number(++i);
  return -1;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::string phases_text(const gdr::QualityTetStats& s) {
  std::ostringstream out;
  out.precision(4);
  out << "iterations:" << s.iterations << ";input:" << s.input_seconds << ";cdt:" << s.cdt_seconds;
  for (const auto& p : s.phases) out << ';' << p.name << ':' << p.seconds;
  out << ";output:" << s.output_seconds;
  return out.str();
}

}  // namespace

std::string number_arg(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// A positive number in plain decimals with about 7 significant digits: TetGen's parser
// reads digits and '.' only after a switch letter.
std::string plain_decimal(double v) {
  const int decimals = std::clamp(6 - static_cast<int>(std::floor(std::log10(v))), 0, 30);
  char b[80];
  std::snprintf(b, sizeof b, "%.*f", decimals, v);
  std::string s = b;
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

TetBounds tet_bounds(const Case& c, Inputs& inputs) {
  const std::string sw = c.text("switches", "");
  TetBounds b;
  const double q = switch_number(sw, 'q');
  b.radius_edge = c.number("radius_edge", q > 0 ? q : 2.0);
  const double d = switch_number(sw, 'q', true);
  b.min_dihedral = c.number("min_dihedral", d > 0 ? d : 0.0);
  const double a = switch_number(sw, 'a');
  b.max_volume = c.number("max_volume", a > 0 ? a : 0.0);
  const double target = c.number("target_tets", 0);
  if (target > 0) {
    if (c.params.count("max_volume"))
      throw gdr::Error(gdr::Status::InvalidInput, "give max_volume or target_tets, not both");
    b.max_volume = kTetsPerVolumeBound * enclosed_volume(inputs.surface(c.input)) / target;
  }
  return b;
}

std::string tetgen_switches(const Case& c, const TetBounds& b) {
  if (c.params.count("switches")) return c.text("switches", "");
  std::string s = "p";
  if (b.radius_edge > 0 || b.min_dihedral > 0) {
    // TetGen cannot switch the ratio off under -q: a ratio of 100 bounds nothing in practice.
    s += "q" + plain_decimal(b.radius_edge > 0 ? b.radius_edge : 100.0);
    if (b.min_dihedral > 0) s += "/" + plain_decimal(b.min_dihedral);
  }
  if (b.max_volume > 0) s += "a" + plain_decimal(b.max_volume);
  return s;
}

bool warm_up_gpu_3d(std::string& why_not) {
  if (!gdr::gpu_available()) {
    why_not = "no GPU: " + gdr::device_info().reason;
    return false;
  }
  try {
    gdr::Surface cube;
    for (int i = 0; i < 8; ++i) cube.points.push_back({double(i & 1), double((i >> 1) & 1), double(i >> 2)});
    cube.triangles = {{0, 2, 1}, {1, 2, 3}, {4, 5, 6}, {5, 7, 6}, {0, 1, 4}, {1, 5, 4},
                      {2, 6, 3}, {3, 6, 7}, {0, 4, 2}, {2, 4, 6}, {1, 3, 5}, {3, 7, 5}};
    gdr::QualityTetOptions o;
    o.backend = gdr::Backend::Gpu;
    o.radius_edge_ratio = 1.4;
    o.max_volume = 0.002;
    gdr::quality_tet_mesh(cube, o);
    return true;
  } catch (const std::exception& e) {
    why_not = std::string("GPU 3D warm-up failed: ") + e.what();
    return false;
  }
}

Result run_gdr_tet(const Case& c, Inputs& inputs, const TetBounds& b, bool validate) {
  Result r;
  const gdr::Surface& surface = inputs.surface(c.input);
  gdr::QualityTetOptions o;
  o.radius_edge_ratio = b.radius_edge;
  o.min_dihedral_angle = b.min_dihedral;
  o.max_volume = b.max_volume;
  o.max_steiner_points = static_cast<long long>(c.number("max_steiner", -1));
  o.sliver_angle = c.number("sliver_angle", 0);  // TetGen smooths by default (-O2); we only on request
  o.coplanar_angle = c.number("coplanar_angle", gdr::kTetGenFacetTolerance);  // TetGen's default too
  o.backend = c.runner == "gdr-tet-gpu" ? gdr::Backend::Gpu : gdr::Backend::Cpu;
  const int repeat = std::max(1, static_cast<int>(c.number("repeat", 1)));
  const double timeout = c.number("timeout", 600);
  const std::string disable = c.text("disable", "");
  if (disable.empty()) unsetenv("GDR_DISABLE");
  else setenv("GDR_DISABLE", disable.c_str(), 1);

  // Every run's result is kept until the median is known: use repeat= on small cases only.
  std::vector<gdr::QualityTetResult> runs;
  for (int i = 0; i < repeat; ++i) {
    const auto start = std::chrono::steady_clock::now();
    gdr::Callbacks callbacks;
    callbacks.abort = [&] { return seconds_since(start) > timeout; };
    try {
      runs.push_back(gdr::quality_tet_mesh(surface, o, callbacks));
    } catch (const gdr::Error& e) {
      if (e.status() != gdr::Status::Aborted) throw;
      r.status = "timeout";
      r.message = "stopped after " + number_arg(timeout) + " s";
      return r;
    }
  }
  std::sort(runs.begin(), runs.end(), [](const auto& x, const auto& y) {
    return x.stats.total_seconds < y.stats.total_seconds;
  });
  const gdr::QualityTetResult& kept = runs[runs.size() / 2];
  const gdr::QualityTetStats& s = kept.stats;
  r.input_points = s.input_points;
  r.input_triangles = s.input_triangles;
  r.input_segments = s.input_segments;
  r.points = s.output_points;
  r.elements = s.output_tets;
  r.steiner = s.steiner_points;
  r.cdt_s = s.cdt_seconds;
  r.refine_s = s.refine_seconds;
  r.total_s = s.total_seconds;
  r.peak_device_bytes = o.backend == gdr::Backend::Gpu ? double(s.peak_device_bytes) : -1;
  r.phases = phases_text(s);
  if (s.steiner_cap_reached)
    r.message += std::string(s.automatic_steiner_cap ? "automatic " : "") + "Steiner cap (" +
                 std::to_string(s.steiner_cap) + ") reached. ";
  if (s.stalled) r.message += "refinement stalled. ";
  if (o.sliver_angle > 0)
    r.message += "slivers (angle beyond " + number_arg(o.sliver_angle) + " deg) " + std::to_string(s.slivers_before) +
                 " -> " + std::to_string(s.slivers_after) + " (" + std::to_string(s.sliver_flips) + " flips). ";
  if (s.protected_bad_tets > 0)
    r.message += std::to_string(s.protected_bad_tets) + " bad tets protected (small input angles). ";
  if (repeat > 1) r.message += "median of " + std::to_string(repeat) + " runs. ";

  // The same checker as for TetGen's output (bench_tetgen): gdr::tet_quality on the tets.
  const gdr::QualityStats q = gdr::tet_quality(kept.mesh, b.radius_edge);
  r.min_quality_deg = q.min_dihedral_deg;
  r.max_radius_edge = q.max_radius_edge;
  r.bad_elements = static_cast<long long>(q.bad_elements);
  r.bad_elements_pct = q.elements ? 100.0 * double(q.bad_elements) / double(q.elements) : 0.0;
  r.bad_area_pct = q.bad_measure_percent;
  r.histogram.assign(q.histogram.begin(), q.histogram.end());

  if (!validate) {
    r.valid = "skipped";
    return r;
  }
  gdr::ValidateOptions vo;
  vo.max_radius_edge = b.radius_edge;
  vo.check_delaunay = o.sliver_angle == 0;  // smoothing moves points off Delaunay
  if (o.coplanar_angle > 0) vo.facet_bend_deg = gdr::kMergedFacetBend;
  const auto t0 = std::chrono::steady_clock::now();
  const gdr::ValidationReport report = gdr::validate_tetmesh(kept.mesh, &surface, vo);
  std::fprintf(stderr, "    validated in %.2f s: %s\n", seconds_since(t0), report.valid ? "valid" : "INVALID");
  r.valid = report.valid ? "yes" : "no";
  if (!report.valid && !report.problems.empty()) r.message += report.problems.front() + " ";
  return r;
}

// gDP3d with CGAL Mesh_3's criteria, as the case names them for cgal-mesh3-* (facet_angle,
// facet_size, facet_distance, cell_radius_edge_ratio, cell_size, feature_angle; absent: our
// defaults).
// Elements are the tetrahedra inside the surface; the message gives the surface triangles
// and their smallest angle. validate=1 checks the surface (closed, oriented, manifold, no
// self-intersection) and the tetrahedra (positive, bounded by it).
Result run_gdr_rdt(const Case& c, Inputs& inputs, bool validate) {
  Result r;
  const gdr::Surface& surface = inputs.surface(c.input);
  gdr::RestrictedDelaunayOptions o;
  o.facet_angle = c.number("facet_angle", o.facet_angle);
  o.facet_size = c.number("facet_size", o.facet_size);
  o.facet_distance = c.number("facet_distance", o.facet_distance);
  o.cell_radius_edge_ratio = c.number("cell_radius_edge_ratio", o.cell_radius_edge_ratio);
  o.cell_size = c.number("cell_size", o.cell_size);
  o.sliver_angle = c.number("sliver_angle", 0);  // CGAL's optimisers are off too (optimize=0)
  o.feature_angle = c.number("feature_angle", 0);
  o.backend = c.runner == "gdr-rdt-gpu" ? gdr::Backend::Gpu : gdr::Backend::Cpu;
  const double timeout = c.number("timeout", 600);
  const auto start = std::chrono::steady_clock::now();
  gdr::Callbacks callbacks;
  callbacks.abort = [&] { return seconds_since(start) > timeout; };
  gdr::RestrictedDelaunayResult res;
  try {
    res = gdr::restricted_delaunay_3d(surface, o, callbacks);
  } catch (const gdr::Error& e) {
    if (e.status() != gdr::Status::Aborted) throw;
    r.status = "timeout";
    r.message = "stopped after " + number_arg(timeout) + " s";
    return r;
  }
  const gdr::RestrictedDelaunayStats& s = res.stats;
  r.input_points = s.input_points;
  r.input_triangles = s.input_triangles;
  r.points = s.output_points;
  r.elements = s.output_tets;
  r.steiner = s.steiner_points;
  r.cdt_s = s.initial_seconds;  // the initial Delaunay triangulation of the sample
  r.refine_s = s.refine_seconds;
  r.total_s = s.total_seconds;
  r.peak_device_bytes = o.backend == gdr::Backend::Gpu ? double(s.peak_device_bytes) : -1;
  r.min_quality_deg = s.min_dihedral_deg;
  r.max_radius_edge = s.max_radius_edge;
  r.bad_elements = s.bad_tets;
  r.bad_elements_pct = s.output_tets ? 100.0 * double(s.bad_tets) / double(s.output_tets) : 0.0;
  r.histogram = res.dihedral_histogram;
  std::ostringstream msg;
  msg << s.output_triangles << " surface triangles, smallest facet angle " << s.min_facet_angle_deg
      << " deg, " << s.bad_facets << " bad facets. ";
  if (o.feature_angle > 0)
    msg << s.feature_edges << " feature edges, " << s.corners << " corners, " << s.feature_points
        << " points on features. ";
  if (s.stalled) msg << "refinement stalled. ";
  if (s.steiner_cap_reached) msg << "Steiner cap (" << s.steiner_cap << ") reached. ";
  if (o.sliver_angle > 0)
    msg << "slivers (angle beyond " << number_arg(o.sliver_angle) << " deg) " << s.slivers_before << " -> "
        << s.slivers_after << ". ";
  r.message = msg.str();
  r.phases = "";
  for (const auto& p : s.phases) r.phases += p.name + ":" + std::to_string(p.seconds) + ";";
  if (!validate) {
    r.valid = "skipped";
    return r;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const gdr::ValidationReport surf = gdr::validate_surface(res.mesh.points, res.mesh.subfaces, s.closed_input);
  gdr::ValidateOptions vo;
  vo.check_conformity = false;
  vo.check_delaunay = s.sliver_moves == 0;  // smoothing moves points off Delaunay
  const gdr::ValidationReport tets = gdr::validate_tetmesh(res.mesh, nullptr, vo);
  const bool ok = surf.valid && tets.valid;
  std::fprintf(stderr, "    validated in %.2f s: %s\n", seconds_since(t0), ok ? "valid" : "INVALID");
  r.valid = ok ? "yes" : "no";
  for (const auto* rep : {&surf, &tets})
    if (!rep->valid && !rep->problems.empty()) r.message += rep->problems.front() + " ";
  return r;
}

}  // namespace gdr_bench
