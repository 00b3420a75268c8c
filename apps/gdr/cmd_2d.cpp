// `gdr 2d`: quality constrained Delaunay refinement of a planar straight-line graph.
#include <cctype>
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
#include "gdr/refine2d.h"
#include "gdr/validate.h"
#include "interrupt.h"
#include "json_writer.h"
#include "mesh_attributes.h"
#include "progress_bar.h"
#include "table.h"
#include "vtk_input.h"

namespace gdr::cli {

namespace {

const char* kHelp2d = R"(gdr 2d - quality constrained Delaunay refinement of a 2D PSLG

Usage:
  gdr 2d INPUT.poly -o OUTPUT [options]
  gdr 2d -pq30a0.1 INPUT.poly -o OUTPUT [options]     (Triangle's switches)

INPUT is a planar straight-line graph in Triangle's .poly format (points, segments, optional
hole seeds and regions), a .node file (points only), or, in builds with VTK, VTK polydata
(.vtp, legacy .vtk) whose lines and polygon edges are the segments. Holes are emptied from their seeds;
the rest of the convex hull is meshed too unless --remove-exterior is given. A region's
maximum area bounds the triangles of its region, and its attribute goes to them (cell
array Region); boundary markers and point attributes are carried to the output, as
Triangle does (point attributes interpolated linearly at new points). OUTPUT is written by
its extension:
  .vtu / .vtp   VTK XML (ParaView; .vtk: legacy VTK) with cell arrays MinAngle, MaxAngle, RadiusEdgeRatio,
                Area, IsBad (and Region), point arrays PointType (0 input, 1 on a segment,
                2 free), BoundaryMarker (and PointAttributes)
  .node / .ele  Triangle's format: -o BASE.node (or BASE.ele) writes three files,
                BASE.node, BASE.ele and BASE.poly (the subsegments with their markers)
Without -o the mesh is computed, summarized and (with --check) validated, but not written.
gdr never writes over its input: an output (or --stats-json) that would replace INPUT, or
the .node beside a .poly INPUT (where a .poly without points takes them from), is refused
before anything is read. Each file is written in full under a temporary name, then renamed:
an existing output is only ever replaced by a complete new one. Ctrl-C (or SIGTERM) stops
the run: it prints "interrupted", exits with 130 (143) and leaves the outputs as they were,
unless it comes while they are being written (then they are completed first).

Triangle's switches, for users who know Triangle by heart, as one argument with one dash:
  p  the segments bound the domain (the exterior is removed unless c is given)
  c  keep the convex hull meshed        q[DEG]  minimum angle (20 without a number)
  a<A>  maximum triangle area           S<N>    Steiner point cap
  a  the regions' maximum areas         A       the regions' attributes (Region)
  D  diametral circles (--mode ruppert; without D the lens, --mode chew)
  z  number output files from 0         Q quiet         C check the mesh (--check)
Without q or a Triangle does not refine, nor does gdr; without a and A the regions are not
used (without switches they always are). Other switches are refused. Long
options after the switches refine what they set.
The .node/.ele/.poly output counts from 0 or 1 as the input does (Triangle's way).

Quality and size:
  --min-angle DEG         smallest angle wanted, in degrees (default 20, at most 34;
                          0 turns the angle criterion off; above 30 refinement may
                          cascade, see --max-steiner and README "Known limits")
  --max-edge L            longest edge allowed (default: no limit)
  --max-area A            largest triangle area allowed (default: no limit)
  --max-steiner N         stop cleanly after inserting N Steiner points (default: 1000
                          times the input points, at least 1M (100k at --min-angle 0)
                          and 4 times the triangles the size bounds ask for, within
                          memory); bounds whose mesh cannot fit in memory, and thin parts
                          that need more than the cap, are refused before refining
Algorithm:
  --mode chew|ruppert     a point encroaches a subsegment inside its diametral lens of
                          angle 180 - 2 x min angle (chew, default, as Triangle) or inside
                          its diametral circle (ruppert, as Triangle's -D: more points)
  --no-off-centers        insert circumcenters instead of Ungor's off-centers (the
                          default, as Triangle: fewer points); --off-centers is accepted
  --remove-exterior       keep only triangles enclosed by segments (and outside holes)
  --strict                refuse points lying on segments and crossing, touching or
                          overlapping segments (by default segments are split there, as
                          Triangle and CGAL do, with a warning that counts them);
                          --split-intersections, the old name of the default, is accepted
  --cdt-only              only the constrained Delaunay triangulation, no refinement
  --cdt auto|cgal|parallel  how the first constrained Delaunay triangulation is built:
                          CGAL's on the CPU, or the parallel one on the run's backend
                          (default auto: parallel on the GPU for large inputs, else CGAL)
  --backend auto|gpu|cpu  where to refine (default auto: GPU for large inputs when present)
  --deterministic         the same mesh on every run of the same input and options: the
                          CPU backend on one thread (README "Reproducibility")
Checking and reporting:
  --check                 validate the result (conformity, constrained Delaunay, quality);
                          exit code 1 when the mesh is invalid
  --stats-json FILE       write all statistics (and the validation) as JSON
  -q, --quiet             no progress, warnings or summary; errors only
  -h, --help              this text

Examples:
  gdr 2d apps/gdr/examples/gear.poly -o gear.vtu --remove-exterior
  gdr 2d shape.poly -o shape.vtu --min-angle 30 --max-area 0.5 --check
  gdr 2d map.poly -o map.vtp --remove-exterior --backend gpu --stats-json map.json
  gdr 2d shape.poly -o shape.node --cdt-only
  gdr 2d -pq30a0.1 shape.poly -o shape.node

Exit codes: 0 ok, 1 invalid mesh (--check), 2 usage error (also: an output that would
overwrite an input), 3 input error, 4 device error, 5 internal error, 130 interrupted.
)";

struct Args2d {
  std::string switches;  // Triangle's switch string, when given
  bool zero_based = false;
  std::string input;
  std::string output;
  std::string stats_json;
  Refine2dOptions options;
  bool check = false;
  bool quiet = false;
  bool help = false;
};

bool output_extension_supported(const std::string& path) {
  const std::string ext = lower_extension(path);
  return ext == ".vtu" || ext == ".vtp" || ext == ".vtk" || ext == ".node" || ext == ".ele";
}

Args2d parse_2d(const std::vector<std::string>& args) {
  const std::string cmd = "2d";
  Args2d a;
  auto number = [&](const char* name, double& dst) {
    return OptionSpec{name, 0, true, [&, name](const std::string& v) {
                        dst = parse_number(cmd, name, v);
                        if (dst < 0) throw UsageError(cmd, std::string("--") + name + " must be >= 0");
                      }};
  };
  const std::vector<OptionSpec> specs = {
      {"output", 'o', true, [&](const std::string& v) { a.output = v; }},
      number("min-angle", a.options.min_angle),
      number("max-edge", a.options.max_edge_length),
      number("max-area", a.options.max_area),
      {"max-steiner", 0, true,
       [&](const std::string& v) {
         a.options.max_steiner_points = parse_integer(cmd, "max-steiner", v);
         if (a.options.max_steiner_points < 0)
           throw UsageError(cmd, "--max-steiner must be >= 0");
       }},
      {"mode", 0, true,
       [&](const std::string& v) {
         if (v == "ruppert") a.options.mode = EncroachMode::Ruppert;
         else if (v == "chew") a.options.mode = EncroachMode::Chew;
         else throw UsageError(cmd, "--mode must be 'ruppert' or 'chew', got '" + v + "'");
       }},
      {"off-centers", 0, false, [&](const std::string&) { a.options.off_centers = true; }},
      {"no-off-centers", 0, false, [&](const std::string&) { a.options.off_centers = false; }},
      {"deterministic", 0, false, [&](const std::string&) { a.options.deterministic = true; }},
      {"remove-exterior", 0, false, [&](const std::string&) { a.options.remove_exterior = true; }},
      {"strict", 0, false, [&](const std::string&) { a.options.strict_input = true; }},
      {"split-intersections", 0, false, [&](const std::string&) { a.options.strict_input = false; }},
      {"cdt-only", 0, false, [&](const std::string&) { a.options.refine = false; }},
      {"cdt", 0, true,
       [&](const std::string& v) {
         if (v == "auto") a.options.cdt = CdtMethod::Auto;
         else if (v == "cgal") a.options.cdt = CdtMethod::Cgal;
         else if (v == "parallel") a.options.cdt = CdtMethod::Parallel;
         else throw UsageError(cmd, "--cdt must be 'auto', 'cgal' or 'parallel', got '" + v + "'");
       }},
      {"backend", 0, true, [&](const std::string& v) { a.options.backend = parse_backend(cmd, v); }},
      {"check", 0, false, [&](const std::string&) { a.check = true; }},
      {"stats-json", 0, true, [&](const std::string& v) { a.stats_json = v; }},
      {"quiet", 'q', false, [&](const std::string&) { a.quiet = true; }},
      {"help", 'h', false, [&](const std::string&) { a.help = true; }},
  };
  // Triangle's switch string ("-pq30a0.1"): one dash and more than one letter. It sets the
  // options first; long options after it refine them.
  std::vector<std::string> rest;
  bool options_done = false;
  for (const std::string& arg : args) {
    options_done = options_done || arg == "--";
    const bool triangle = !options_done && arg.size() > 2 && arg[0] == '-' &&
                          std::isalpha(static_cast<unsigned char>(arg[1]));
    if (!triangle) {
      rest.push_back(arg);
      continue;
    }
    if (!a.switches.empty())
      throw UsageError(cmd, "two Triangle switch strings, '" + a.switches + "' and '" + arg +
                                "': give one");
    a.switches = arg;
    try {
      const TriangleSwitches t = apply_triangle_switches(arg, a.options);
      a.zero_based = t.zero_based;
      a.quiet = a.quiet || t.quiet;
      a.check = a.check || t.check;
    } catch (const Error& e) {
      throw UsageError(cmd, e.what());
    }
  }
  const auto positional = parse_options(cmd, rest, specs);
  if (a.help) return a;
  a.input = single_input(cmd, positional);
  if (!a.output.empty() && !output_extension_supported(a.output))
    throw UsageError(cmd, "cannot tell the output format of '" + a.output +
                              "': use .vtu, .vtp, .vtk, .node or .ele");
  return a;
}


void print_summary(const Args2d& a, const Pslg& input, const Refine2dResult& r,
                   const ValidationReport* report, const CliTimes& t) {
  const Refine2dStats& s = r.stats;
  const auto count = [](std::size_t n) { return with_commas(static_cast<long long>(n)); };
  Table info(Table::Align::Left);
  info.row({"gdr 2d summary"});
  info.row({"input", a.input + ": " + count(input.points.size()) + " points, " +
                         count(input.segments.size()) + " segments, " +
                         count(input.holes.size()) + " holes"});
  if (s.duplicate_points_merged > 0)
    info.row({"", with_commas(s.duplicate_points_merged) + " duplicate points merged"});
  info.row({"output", (a.output.empty() ? std::string("(not written)") : a.output) + ": " +
                          with_commas(s.output_points) + " points, " +
                          with_commas(s.output_triangles) + " triangles"});
  info.row({"Steiner points", with_commas(s.steiner_points) + " in " +
                                  std::to_string(s.iterations) + " iterations"});
  if (s.steiner_cap_reached)
    info.row({"", std::string("stopped at the ") + (s.automatic_steiner_cap ? "automatic " : "") +
                      "cap of " + with_commas(s.steiner_cap)});
  if (s.stalled) info.row({"", "stalled: bad elements remain that no point could fix"});
  info.row({"backend", a.options.deterministic ? "cpu (refined on one thread: --deterministic)"
                                               : backend_line(s.backend_used, s.device_name)});
  info.row({"peak device memory", s.backend_used == Backend::Gpu ? bytes(s.peak_device_bytes)
                                                                  : "- (CPU backend)"});
  info.row({"min angle", fixed(s.min_angle_deg, 2) + " deg (bound " +
                             (a.options.min_angle > 0 ? fixed(a.options.min_angle, 2) + " deg)"
                                                      : std::string("off)"))});
  info.row({"bad triangles", with_commas(s.bad_triangles) + ", " +
                                 fixed(s.bad_area_percent, 4) + "% of the area"});
  if (s.small_angle_bad > 0)
    info.row({"", with_commas(s.small_angle_bad) + " of them next to small input angles"});
  if (report) info.row({"check", (report->valid ? "valid: " : "INVALID: ") + report->summary()});
  info.print(std::cout);

  Table times;
  times.row({"time", "seconds", "share"});
  times.row({"  input checks", fixed(s.input_seconds, 3), ""});
  times.row({"  initial CDT (" + s.cdt_method + ")", fixed(s.cdt_seconds, 3), ""});
  for (const auto& p : s.cdt_phases) times.row({"    " + p.name, fixed(p.seconds, 3), ""});
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
  std::cout.flush();
}

void write_stats_json(const std::string& path, const Args2d& a, const Refine2dResult& r,
                      const ValidationReport* report, const CliTimes& t) {
  std::ostringstream out;
  const Refine2dStats& s = r.stats;
  const Refine2dOptions& o = a.options;
  JsonWriter j(out);
  j.begin_object();
  j.field("tool", "gdr 2d");
  j.field("input", a.input);
  j.field("output", a.output);

  j.key("options");
  j.begin_object();
  j.field("min_angle", o.min_angle);
  j.field("max_edge_length", o.max_edge_length);
  j.field("max_area", o.max_area);
  j.field("max_steiner_points", o.max_steiner_points);
  j.field("mode", o.mode == EncroachMode::Chew ? "chew" : "ruppert");
  j.field("off_centers", o.off_centers);
  j.field("deterministic", o.deterministic);
  j.field("remove_exterior", o.remove_exterior);
  j.field("strict_input", o.strict_input);
  j.field("triangle_switches", a.switches);
  j.field("region_areas", o.region_areas);
  j.field("region_attributes", o.region_attributes);
  j.field("refine", o.refine);
  j.field("backend", to_string(o.backend));
  j.field("cdt", o.cdt == CdtMethod::Cgal ? "cgal" : (o.cdt == CdtMethod::Parallel ? "parallel" : "auto"));
  j.end_object();

  j.key("stats");
  j.begin_object();
  j.field("backend_used", to_string(s.backend_used));
  j.field("cdt_method", s.cdt_method);
  j.field("device_name", s.device_name);
  j.field("iterations", s.iterations);
  j.field("input_points", s.input_points);
  j.field("duplicate_points_merged", s.duplicate_points_merged);
  j.field("input_segments", s.input_segments);
  j.field("steiner_points", s.steiner_points);
  j.field("output_points", s.output_points);
  j.field("output_triangles", s.output_triangles);
  j.field("bad_triangles", s.bad_triangles);
  j.field("bad_area_percent", s.bad_area_percent);
  j.field("small_angle_bad", s.small_angle_bad);
  j.field("steiner_cap", s.steiner_cap);
  j.field("automatic_steiner_cap", s.automatic_steiner_cap);
  j.field("steiner_cap_reached", s.steiner_cap_reached);
  j.field("stalled", s.stalled);
  j.field("min_angle_deg", s.min_angle_deg);
  j.field("input_seconds", s.input_seconds);
  j.field("cdt_seconds", s.cdt_seconds);
  j.field("refine_seconds", s.refine_seconds);
  j.field("output_seconds", s.output_seconds);
  j.field("total_seconds", s.total_seconds);
  j.field("peak_device_bytes", static_cast<unsigned long long>(s.peak_device_bytes));
  j.phases_field("phases", s.phases);
  j.end_object();

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
    j.begin_object();
    j.field("valid", report->valid);
    j.field("inverted_elements", static_cast<unsigned long long>(report->inverted_elements));
    j.field("nonmanifold", static_cast<unsigned long long>(report->nonmanifold));
    j.field("missing_points", static_cast<unsigned long long>(report->missing_points));
    j.field("missing_segments", static_cast<unsigned long long>(report->missing_segments));
    j.field("non_delaunay", static_cast<unsigned long long>(report->non_delaunay));
    j.array_field("problems", report->problems);
    j.key("quality");
    j.begin_object();
    j.field("elements", static_cast<unsigned long long>(q.elements));
    j.field("min_angle_deg", q.min_angle_deg);
    j.field("max_angle_deg", q.max_angle_deg);
    j.field("max_radius_edge", q.max_radius_edge);
    j.field("mean_radius_edge", q.mean_radius_edge);
    j.field("bad_elements", static_cast<unsigned long long>(q.bad_elements));
    j.field("bad_area_percent", q.bad_measure_percent);
    j.field("total_area", q.total_measure);
    j.array_field("min_angle_histogram", q.histogram);
    j.end_object();
    j.field("summary", report->summary());
    j.end_object();
  }
  j.end_object();
  io::write_file_atomically(path, out.str());
}

// Refuses, before anything is read, a command line that would write over one of the files
// it reads or write one file twice.
void refuse_overwrites(const Args2d& a) {
  std::vector<OutputFile> outputs;
  if (!a.output.empty())
    for (const std::string& f : io::trimesh_output_files(a.output))
      outputs.push_back({f, "-o " + a.output});
  if (!a.stats_json.empty()) outputs.push_back({a.stats_json, "--stats-json " + a.stats_json});
  refuse_overwrites("2d", a.input, io::poly_input_files(a.input), outputs);
}

Pslg read_input(const std::string& path, const Callbacks& callbacks) {
  if (is_vtk_polydata(path)) {
    std::string warning;
    Pslg pslg = read_vtk_pslg(path, warning);
    if (!warning.empty() && callbacks.warning) callbacks.warning(warning);
    return pslg;
  }
  if (!std::filesystem::exists(path)) throw Error(Status::IoError, path + ": no such file");
  if (io::detect_input_kind(path) != io::InputKind::Pslg2d)
    throw Error(Status::InvalidInput,
                path + ": is a 3D surface; 'gdr 2d' needs a 2D planar straight-line graph");
  return io::read_poly(path);
}

int mesh_2d(const Args2d& a, bool& written) {
  const auto t_start = std::chrono::steady_clock::now();
  CliTimes t;
  ProgressBar bar(!a.quiet);

  Callbacks callbacks;
  callbacks.progress = [&bar](double f, const std::string& phase) { bar.update(f, phase); };
  if (!a.quiet)
    callbacks.warning = [&bar](const std::string& m) { bar.message("gdr: warning: " + m); };
  callbacks.abort = [] { return InterruptHandler::received() != 0; };

  bar.update(-1, "reading " + a.input);
  auto t0 = std::chrono::steady_clock::now();
  const Pslg input = read_input(a.input, callbacks);
  t.read = since(t0);
  stop_if_interrupted();
  const Refine2dResult result = refine_2d(input, a.options, callbacks);
  stop_if_interrupted();

  if (!a.output.empty()) {
    bar.update(-1, "writing " + a.output);
    t0 = std::chrono::steady_clock::now();
    make_parent_dirs(a.output);
    if (a.zero_based) {
      TriMesh zero = result.mesh;
      zero.first_index = 0;
      io::write_mesh(a.output, zero, triangle_attributes(zero, a.options.min_angle));
    } else {
      io::write_mesh(a.output, result.mesh, triangle_attributes(result.mesh, a.options.min_angle));
    }
    written = true;
    t.write = since(t0);
    stop_if_interrupted();
  }

  ValidationReport report;
  if (a.check) {
    bar.update(-1, "checking the mesh");
    t0 = std::chrono::steady_clock::now();
    ValidateOptions vo;
    vo.min_angle_deg = a.options.min_angle;
    report = validate_trimesh(result.mesh, &input, vo);
    t.check = since(t0);
    stop_if_interrupted();
  }
  t.wall = since(t_start);
  bar.finish();

  const ValidationReport* rep = a.check ? &report : nullptr;
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

int run_2d(const std::vector<std::string>& args) {
  const Args2d a = parse_2d(args);
  if (a.help) {
    std::fputs(kHelp2d, stdout);
    return kExitOk;
  }
  refuse_overwrites(a);
  return run_interruptible(a.output, [&a](bool& written) { return mesh_2d(a, written); });
}

}  // namespace gdr::cli
