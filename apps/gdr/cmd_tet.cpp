// `gdr tet`: quality tetrahedral meshing of a closed surface (gQM3d).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "args.h"
#include "cli.h"
#include "command_support.h"
#include "gdr/backend.h"
#include "gdr/io.h"
#include "gdr/qm3d.h"
#include "gdr/validate.h"
#include "interrupt.h"
#include "json_writer.h"
#include "mesh_attributes.h"
#include "progress_bar.h"
#include "table.h"

namespace gdr::cli {

namespace {

const char* kHelpTet = R"(gdr tet - quality tetrahedral mesh of a closed surface

Usage:
  gdr tet INPUT -o OUTPUT [options]

INPUT is a closed triangulated surface, one or several shells (a shell inside another
bounds a cavity): .off, .stl (ASCII or binary), .ply, .obj, or TetGen's .poly / .smesh
(polygonal facets, internal facets, segments, region attributes). Duplicate points and
triangles are merged and reported; open, non-manifold or self-intersecting surfaces are
refused with the faces or edges named. The volume inside is meshed with tetrahedra by 3D
constrained Delaunay refinement (as TetGen -pq). OUTPUT is written by its extension:
  .vtu                 VTK XML (ParaView) with cell arrays RadiusEdgeRatio,
                       MinDihedralAngle, MaxDihedralAngle, Volume, IsBad (1 above the
                       bounds, 2 above them next to small input angles), Region (when the
                       input has regions) and point array PointType (0 input, 1 on a
                       segment, 2 free, 3 on a facet)
  .node / .ele / .face TetGen's format: -o BASE.node (or .ele, .face) writes BASE.node,
                       BASE.ele (region attributes) and BASE.face (the subfaces, with the
                       input facet as boundary marker)
  .mesh                Medit (Gmsh, MMG): vertex reference = point type, tetrahedron
                       reference = region (1 without), triangle reference = facet + 1
Without -o the mesh is computed, summarized and (with --check) validated, but not written.
gdr never writes over its input: an output that would replace INPUT (or the .node beside
a .poly / .smesh INPUT) is refused before anything is read. Files are written under a
temporary name, then renamed. Ctrl-C (or SIGTERM) stops the run: it prints "interrupted",
exits with 130 (143) and leaves the outputs as they were.

Quality and size:
  --radius-edge B         largest circumradius-to-shortest-edge ratio of a tetrahedron
                          (TetGen's -q B; default 2.0, at least 1.0; 0 turns it off)
  --min-dihedral DEG      smallest dihedral angle allowed (TetGen's -q B/DEG; default off,
                          at most 60). Not guaranteed: once the mesh has grown fourfold,
                          slivers whose circumcentres would only make smaller ones are
                          left, and counted (--sliver-angle raises many of them)
  --max-volume V          largest tetrahedron volume (TetGen's -a V; default: no limit)
  --sliver-angle DEG      after refinement, move interior Steiner points to raise dihedral
                          angles below DEG (and above 180 - DEG) as TetGen's -O smoothing
                          does, keeping --radius-edge, then flip the slivers left where that
                          raises their angles (default off; at most 30; the mesh is then
                          not Delaunay there, and --check skips that test)
  --max-steiner N         stop cleanly after inserting N Steiner points (default: no cap
                          for B >= 2 without --min-dihedral, where refinement terminates;
                          otherwise an automatic cap, reported in the summary)
Input surface:
  --coplanar-angle DEG    input triangles meeting within DEG of flat form one facet whose
                          inner edges the mesh need not keep (TetGen's -p facet tolerance;
                          default 0.1 as TetGen's, at most 5); the boundary then follows the
                          input within that bend, far fewer points go where a curved or
                          rounded surface was cut into near-flat triangles, and the faces of
                          a part turned to an angle (flat only up to rounding) mesh well.
                          0: every edge between two facets not exactly coplanar is kept
Algorithm:
  --cdt-only              only the constrained Delaunay tetrahedralization, no refinement
  --backend auto|gpu|cpu  where to refine (default auto: GPU for large inputs when present)
Checking and reporting:
  --check                 validate the result (positive tetrahedra, closed boundary, every
                          input facet and segment recovered, constrained Delaunay) and
                          count the tetrahedra above --radius-edge; exit code 1 when the
                          mesh is invalid
  --stats-json FILE       write all options, statistics, the dihedral histogram and the
                          validation as JSON
  --histogram FILE.csv    write the dihedral-angle histogram (all six angles of every
                          tetrahedron, 1-degree bins): angle_lo,angle_hi,count, 180 rows
  -q, --quiet             no progress, warnings or summary; errors only
  -h, --help              this text

Examples:
  gdr tet apps/gdr/examples/bushing.off -o bushing.vtu --check
  gdr tet part.stl -o part.mesh --radius-edge 1.4 --max-volume 0.01
  gdr tet body.poly -o body.node --min-dihedral 10 --stats-json body.json
  gdr tet part.off -o part.vtu --cdt-only

Exit codes: 0 ok, 1 invalid mesh (--check), 2 usage error (also: an output that would
overwrite an input), 3 input error, 4 device error, 5 internal error, 130 interrupted.
)";

struct ArgsTet {
  std::string input;
  std::string output;
  std::string stats_json;
  std::string histogram;
  QualityTetOptions options;
  bool check = false;
  bool quiet = false;
  bool help = false;
};

bool output_extension_supported(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".vtu" || ext == ".mesh" || ext == ".node" || ext == ".ele" || ext == ".face";
}

ArgsTet parse_tet(const std::vector<std::string>& args) {
  const std::string cmd = "tet";
  ArgsTet a;
  auto number = [&](const char* name, double& dst) {
    return OptionSpec{name, 0, true, [&, name](const std::string& v) {
                        dst = parse_number(cmd, name, v);
                        if (dst < 0) throw UsageError(cmd, std::string("--") + name + " must be >= 0");
                      }};
  };
  const std::vector<OptionSpec> specs = {
      {"output", 'o', true, [&](const std::string& v) { a.output = v; }},
      number("radius-edge", a.options.radius_edge_ratio),
      number("min-dihedral", a.options.min_dihedral_angle),
      number("max-volume", a.options.max_volume),
      number("sliver-angle", a.options.sliver_angle),
      number("coplanar-angle", a.options.coplanar_angle),
      {"max-steiner", 0, true,
       [&](const std::string& v) {
         a.options.max_steiner_points = parse_integer(cmd, "max-steiner", v);
         if (a.options.max_steiner_points < 0)
           throw UsageError(cmd, "--max-steiner must be >= 0");
       }},
      {"cdt-only", 0, false, [&](const std::string&) { a.options.refine = false; }},
      {"backend", 0, true, [&](const std::string& v) { a.options.backend = parse_backend(cmd, v); }},
      {"check", 0, false, [&](const std::string&) { a.check = true; }},
      {"stats-json", 0, true, [&](const std::string& v) { a.stats_json = v; }},
      {"histogram", 0, true, [&](const std::string& v) { a.histogram = v; }},
      {"quiet", 'q', false, [&](const std::string&) { a.quiet = true; }},
      {"help", 'h', false, [&](const std::string&) { a.help = true; }},
  };
  const auto positional = parse_options(cmd, args, specs);
  if (a.help) return a;
  a.input = single_input(cmd, positional);
  if (!a.output.empty() && !output_extension_supported(a.output))
    throw UsageError(cmd, "cannot tell the output format of '" + a.output +
                              "': use .vtu, .mesh, .node, .ele or .face");
  return a;
}


// A ratio that may be huge (a flat tetrahedron's): fixed decimals, or 3 digits and exponent.
std::string ratio(double v) {
  if (v < 1e6) return fixed(v, 3);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

std::string bound(double value, const std::string& unit) {
  return value > 0 ? "bound " + fixed(value, 2) + unit : std::string("no bound");
}

void print_summary(const ArgsTet& a, const Surface& input, const QualityTetResult& r,
                   const ValidationReport* report, const CliTimes& t) {
  const QualityTetStats& s = r.stats;
  const QualityTetOptions& o = a.options;
  Table info(Table::Align::Left);
  info.row({"gdr tet summary"});
  std::string in = a.input + ": " + with_commas(s.input_points) + " points, " +
                   with_commas(s.input_triangles) + " triangles, " + with_commas(s.input_facets) +
                   " facets, " + with_commas(s.input_segments) + " segments";
  if (!input.holes.empty()) in += ", " + with_commas(static_cast<long long>(input.holes.size())) + " holes";
  if (!input.regions.empty())
    in += ", " + with_commas(static_cast<long long>(input.regions.size())) + " regions";
  info.row({"input", in});
  if (s.duplicate_points_merged > 0 || s.duplicate_triangles_merged > 0)
    info.row({"", "merged " + with_commas(s.duplicate_points_merged) + " duplicate points, " +
                      with_commas(s.duplicate_triangles_merged) + " duplicate triangles"});
  info.row({"output", (a.output.empty() ? std::string("(not written)") : a.output) + ": " +
                          with_commas(s.output_points) + " points, " +
                          with_commas(s.output_tets) + " tetrahedra, " +
                          with_commas(s.output_subfaces) + " subfaces"});
  info.row({"Steiner points", with_commas(s.steiner_points) + " (" +
                                  (s.presplit_points > 0 ? with_commas(s.presplit_points) + " on close segments, " : "") +
                                  with_commas(s.cdt_steiner_points) + " in the CDT, " +
                                  with_commas(s.interior_seeds) + " interior seeds) in " +
                                  std::to_string(s.iterations) + " iterations"});
  if (s.steiner_cap_reached)
    info.row({"", std::string("stopped at the ") + (s.automatic_steiner_cap ? "automatic " : "") +
                      "cap of " + with_commas(s.steiner_cap)});
  if (s.stalled) info.row({"", "stalled: bad elements remain that no point could fix"});
  if (s.blocked_segments > 0)
    info.row({"", with_commas(s.blocked_segments) + " input segments left unsplit: their splits kept failing "
                                                      "(a nearly coplanar facet beside them" +
                      (s.coplanar_angle_used > 0 ? std::string(")")
                                            : std::string("; --coplanar-angle 0.1 merges such facets, as TetGen does)"))});
  info.row({"backend", backend_line(s.backend_used, s.device_name)});
  info.row({"peak device memory", s.backend_used == Backend::Gpu ? bytes(s.peak_device_bytes)
                                                                  : "- (CPU backend)"});
  info.row({"dihedral angles", "min " + fixed(s.min_dihedral_deg, 2) + " deg (" +
                                   bound(o.min_dihedral_angle, " deg") + "), max " +
                                   fixed(s.max_dihedral_deg, 2) + " deg"});
  if (o.sliver_angle > 0)
    info.row({"slivers", sliver_summary(o.sliver_angle, s.slivers_before, s.slivers_after, s.sliver_moves,
                                        s.sliver_flips)});
  info.row({"radius-edge ratio", "max " + ratio(s.max_radius_edge) + " (" +
                                     bound(o.radius_edge_ratio, "") + ")"});
  info.row({"bad tetrahedra", with_commas(s.bad_tets) + ", " + fixed(s.bad_volume_percent, 4) +
                                  "% of the volume"});
  if (s.protected_bad_tets > s.slivers_left)
    info.row({"", with_commas(s.protected_bad_tets - s.slivers_left) +
                      " of them protected (next to small input angles)"});
  if (s.slivers_left > 0)
    info.row({"", with_commas(s.slivers_left) +
                      " of them slivers left under the dihedral bound (their circumcentres would only make "
                      "smaller ones; --sliver-angle moves points to raise them)"});
  info.row({"volume", fixed(s.volume, 6) + " (input " + fixed(s.input_volume, 6) + ")"});
  if (report) info.row({"check", (report->valid ? "valid: " : "INVALID: ") + report->summary()});
  info.print(std::cout);

  Table times;
  times.row({"time", "seconds", "share"});
  times.row({"  input checks", fixed(s.input_seconds, 3), ""});
  times.row({"  initial CDT", fixed(s.cdt_seconds, 3), ""});
  times.row({"  refinement", fixed(s.refine_seconds, 3), ""});
  for (const auto& p : s.phases)
    times.row({"    " + p.name, fixed(p.seconds, 3),
               s.refine_seconds > 0 ? fixed(100 * p.seconds / s.refine_seconds, 1) + "%" : ""});
  times.row({"  output mesh", fixed(s.output_seconds, 3), ""});
  times.row({"  mesher total", fixed(s.total_seconds, 3), ""});
  times.row({"  read input", fixed(t.read, 3), ""});
  if (!a.output.empty()) times.row({"  write output", fixed(t.write, 3), ""});
  if (report) times.row({"  check", fixed(t.check, 3), ""});
  times.row({"  wall clock", fixed(t.wall, 3), ""});
  times.print(std::cout);
  print_dihedral_histogram(std::cout, r.dihedral_histogram);
  std::cout.flush();
}

void write_stats_json(const std::string& path, const ArgsTet& a, const QualityTetResult& r,
                      const ValidationReport* report, const CliTimes& t) {
  std::ostringstream out;
  const QualityTetStats& s = r.stats;
  const QualityTetOptions& o = a.options;
  JsonWriter j(out);
  j.begin_object();
  j.field("tool", "gdr tet");
  j.field("input", a.input);
  j.field("output", a.output);

  j.key("options");
  j.begin_object();
  j.field("radius_edge_ratio", o.radius_edge_ratio);
  j.field("min_dihedral_angle", o.min_dihedral_angle);
  j.field("max_volume", o.max_volume);
  j.field("sliver_angle", o.sliver_angle);
  j.field("coplanar_angle", o.coplanar_angle);
  j.field("max_steiner_points", o.max_steiner_points);
  j.field("refine", o.refine);
  j.field("backend", to_string(o.backend));
  j.end_object();

  j.key("stats");
  j.begin_object();
  j.field("backend_used", to_string(s.backend_used));
  j.field("coplanar_angle_used", s.coplanar_angle_used);
  j.field("device_name", s.device_name);
  j.field("iterations", s.iterations);
  j.field("input_points", s.input_points);
  j.field("input_triangles", s.input_triangles);
  j.field("input_facets", s.input_facets);
  j.field("input_segments", s.input_segments);
  j.field("duplicate_points_merged", s.duplicate_points_merged);
  j.field("duplicate_triangles_merged", s.duplicate_triangles_merged);
  j.field("presplit_points", s.presplit_points);
  j.field("cdt_steiner_points", s.cdt_steiner_points);
  j.field("interior_seeds", s.interior_seeds);
  j.field("steiner_points", s.steiner_points);
  j.field("output_points", s.output_points);
  j.field("output_tets", s.output_tets);
  j.field("output_subfaces", s.output_subfaces);
  j.field("bad_tets", s.bad_tets);
  j.field("protected_bad_tets", s.protected_bad_tets);
  j.field("slivers_left", s.slivers_left);
  j.field("bad_volume_percent", s.bad_volume_percent);
  j.field("steiner_cap", s.steiner_cap);
  j.field("automatic_steiner_cap", s.automatic_steiner_cap);
  j.field("steiner_cap_reached", s.steiner_cap_reached);
  j.field("stalled", s.stalled);
  j.field("blocked_segments", s.blocked_segments);
  j.field("sleeping_points", s.sleeping_points);
  j.field("min_dihedral_deg", s.min_dihedral_deg);
  j.field("max_dihedral_deg", s.max_dihedral_deg);
  j.field("slivers_before", s.slivers_before);
  j.field("slivers_after", s.slivers_after);
  j.field("sliver_moves", s.sliver_moves);
  j.field("sliver_flips", s.sliver_flips);
  j.field("max_radius_edge", s.max_radius_edge);
  j.field("volume", s.volume);
  j.field("input_volume", s.input_volume);
  j.field("input_seconds", s.input_seconds);
  j.field("cdt_seconds", s.cdt_seconds);
  j.field("refine_seconds", s.refine_seconds);
  j.field("output_seconds", s.output_seconds);
  j.field("total_seconds", s.total_seconds);
  j.field("peak_device_bytes", static_cast<unsigned long long>(s.peak_device_bytes));
  j.phases_field("phases", s.phases);
  j.end_object();

  j.array_field("dihedral_histogram", r.dihedral_histogram);  // 1-degree bins over [0, 180)

  j.key("cli_seconds");
  j.begin_object();
  j.field("read", t.read);
  j.field("write", t.write);
  j.field("check", t.check);
  j.field("wall", t.wall);
  j.end_object();

  j.key("validation");
  if (!report) {
    j.null();
  } else {
    const QualityStats& q = report->quality;
    const auto count = [](std::size_t n) { return static_cast<unsigned long long>(n); };
    j.begin_object();
    j.field("valid", report->valid);
    j.field("inverted_elements", count(report->inverted_elements));
    j.field("nonmanifold", count(report->nonmanifold));
    j.field("missing_points", count(report->missing_points));
    j.field("missing_segments", count(report->missing_segments));
    j.field("missing_facets", count(report->missing_facets));
    j.field("non_delaunay", count(report->non_delaunay));
    j.field("invalid_indices", count(report->invalid_indices));
    j.field("invalid_subsegments", count(report->invalid_subsegments));
    j.field("invalid_subfaces", count(report->invalid_subfaces));
    j.field("boundary_errors", count(report->boundary_errors));
    j.array_field("problems", report->problems);
    j.key("quality");
    j.begin_object();
    j.field("elements", count(q.elements));
    j.field("min_dihedral_deg", q.min_dihedral_deg);
    j.field("max_dihedral_deg", q.max_dihedral_deg);
    j.field("max_radius_edge", q.max_radius_edge);
    j.field("mean_radius_edge", q.mean_radius_edge);
    j.field("bad_elements", count(q.bad_elements));
    j.field("bad_volume_percent", q.bad_measure_percent);
    j.field("total_volume", q.total_measure);
    j.end_object();
    j.field("summary", report->summary());
    j.end_object();
  }
  j.end_object();
  io::write_file_atomically(path, out.str());
}

// Refuses, before anything is read, a command line that would write over one of the files
// it reads or write one file twice.
void refuse_overwrites(const ArgsTet& a) {
  std::vector<OutputFile> outputs;
  if (!a.output.empty())
    for (const std::string& f : io::tetmesh_output_files(a.output)) outputs.push_back({f, "-o " + a.output});
  if (!a.stats_json.empty()) outputs.push_back({a.stats_json, "--stats-json " + a.stats_json});
  if (!a.histogram.empty()) outputs.push_back({a.histogram, "--histogram " + a.histogram});
  refuse_overwrites("tet", a.input, io::surface_input_files(a.input), outputs);
}

Surface read_input(const std::string& path) {
  if (!std::filesystem::exists(path)) throw Error(Status::IoError, path + ": no such file");
  if (io::detect_input_kind(path) != io::InputKind::Surface3d)
    throw Error(Status::InvalidInput,
                path + ": is a 2D planar straight-line graph; 'gdr tet' needs a closed 3D "
                       "surface (use 'gdr 2d' for 2D inputs)");
  return io::read_surface(path);
}

int mesh_tet(const ArgsTet& a, bool& written) {
  const auto t_start = std::chrono::steady_clock::now();
  CliTimes t;
  ProgressBar bar(!a.quiet);

  bar.update(-1, "reading " + a.input);
  auto t0 = std::chrono::steady_clock::now();
  const Surface input = read_input(a.input);
  t.read = since(t0);
  stop_if_interrupted();

  Callbacks callbacks;
  callbacks.progress = [&bar](double f, const std::string& phase) { bar.update(f, phase); };
  if (!a.quiet)
    callbacks.warning = [&bar](const std::string& m) { bar.message("gdr: warning: " + m); };
  callbacks.abort = [] { return InterruptHandler::received() != 0; };
  const QualityTetResult result = quality_tet_mesh(input, a.options, callbacks);
  stop_if_interrupted();

  if (!a.output.empty()) {
    bar.update(-1, "writing " + a.output);
    t0 = std::chrono::steady_clock::now();
    make_parent_dirs(a.output);
    io::write_mesh(a.output, result.mesh, tet_attributes(result));
    written = true;
    t.write = since(t0);
    stop_if_interrupted();
  }

  ValidationReport report;
  if (a.check) {
    bar.update(-1, "checking the mesh");
    t0 = std::chrono::steady_clock::now();
    ValidateOptions vo;
    vo.max_radius_edge = a.options.radius_edge_ratio;
    vo.check_delaunay = a.options.sliver_angle == 0;  // smoothing moves points off Delaunay
    if (result.stats.coplanar_angle_used > 0) vo.facet_bend_deg = kMergedFacetBend;
    report = validate_tetmesh(result.mesh, &input, vo);
    t.check = since(t0);
    stop_if_interrupted();
  }
  t.wall = since(t_start);
  bar.finish();

  const ValidationReport* rep = a.check ? &report : nullptr;
  if (!a.histogram.empty()) {
    make_parent_dirs(a.histogram);
    write_dihedral_histogram_csv(a.histogram, result.dihedral_histogram);
  }
  if (!a.stats_json.empty()) {
    make_parent_dirs(a.stats_json);
    write_stats_json(a.stats_json, a, result, rep, t);
  }
  if (!a.quiet) print_summary(a, input, result, rep, t);
  if (a.check && !report.valid) {
    std::fprintf(stderr, "gdr: error: the mesh is invalid (%zu problems listed)\n",
                 report.problems.size());
    for (const auto& p : report.problems) std::fprintf(stderr, "  %s\n", p.c_str());
    return kExitInvalidMesh;
  }
  return kExitOk;
}

}  // namespace

int run_tet(const std::vector<std::string>& args) {
  const ArgsTet a = parse_tet(args);
  if (a.help) {
    std::fputs(kHelpTet, stdout);
    return kExitOk;
  }
  refuse_overwrites(a);
  return run_interruptible(a.output, [&a](bool& written) { return mesh_tet(a, written); });
}

}  // namespace gdr::cli
