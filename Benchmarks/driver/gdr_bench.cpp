// gdr_bench: runs a case file of (input, bounds, runner) lines. Our engines run in-process
// through gdr::refine_2d and gdr::quality_tet_mesh (both return after the device has
// synchronised) and their outputs are checked by gdr::validate_trimesh / validate_tetmesh;
// baselines run as child processes printing one JSON line, anchors (Triangle, gDP2d, gQM3d)
// as child processes read back by anchors.cpp. Writes bench.csv, bench.md and
// histograms.csv (3D dihedral angles) and prints the Markdown tables last.
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>

#include "bench.h"
#include "process_settings.h"
#include "gdr/backend.h"
#include "gdr/error.h"
#include "gdr/io.h"
#include "gdr/qm3d.h"
#include "gdr/refine2d.h"
#include "gdr/validate.h"

namespace fs = std::filesystem;
using namespace gdr_bench;

namespace {

std::string utc_now() {
  char b[32];
  const std::time_t t = std::time(nullptr);
  std::strftime(b, sizeof b, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&t));
  return b;
}

std::string machine_description() {
  std::string cpu = "unknown CPU";
  std::ifstream info("/proc/cpuinfo");
  for (std::string line; std::getline(info, line);) {
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  }
  const auto& dev = gdr::device_info();
  std::ostringstream s;
  s << (dev.available ? dev.name : "no GPU (" + dev.reason + ")") << "; " << cpu << ", "
    << sysconf(_SC_NPROCESSORS_ONLN) << " logical CPUs, gdr CPU backend " << gdr::cpu_threads()
    << " threads";
  return s.str();
}

// Edge length bound that gives about `points` output points over the domain: an output point
// owns about 0.433 l^2 of area (two triangles whose edges are mostly a little under l).
double edge_for_points(const gdr::Pslg& pslg, double points) {
  return std::sqrt(convex_hull_area(pslg.points) / (0.433 * points));
}

gdr::Refine2dOptions refine_options(const Case& c, double max_edge) {
  gdr::Refine2dOptions o;
  o.min_angle = c.number("min_angle", 20.0);
  o.max_edge_length = max_edge;
  o.max_area = c.number("max_area", 0.0);
  o.max_steiner_points = static_cast<long long>(c.number("max_steiner", -1));
  const std::string mode = c.text("mode", "chew");  // the engine's defaults: Triangle's rules
  if (mode != "ruppert" && mode != "chew")
    throw gdr::Error(gdr::Status::InvalidInput, "mode must be ruppert or chew, not " + mode);
  o.mode = mode == "chew" ? gdr::EncroachMode::Chew : gdr::EncroachMode::Ruppert;
  o.off_centers = c.number("off_centers", 1) != 0;
  o.remove_exterior = c.text("exterior", "keep") == "remove";
  o.backend = c.runner == "gdr-gpu" ? gdr::Backend::Gpu : gdr::Backend::Cpu;
  const std::string cdt = c.text("cdt", "auto");  // the initial CDT: auto, cgal or parallel
  if (cdt != "auto" && cdt != "cgal" && cdt != "parallel")
    throw gdr::Error(gdr::Status::InvalidInput, "cdt must be auto, cgal or parallel, not " + cdt);
  o.cdt = cdt == "cgal" ? gdr::CdtMethod::Cgal
                        : (cdt == "parallel" ? gdr::CdtMethod::Parallel : gdr::CdtMethod::Auto);
  return o;
}

std::string phases_text(const gdr::Refine2dStats& s) {
  std::ostringstream out;
  out.precision(4);
  // Where the end-to-end time goes: input checks, CDT, refinement, output, and the rest
  // (scaling, size and thin-part estimates) as setup.
  const double setup = s.total_seconds - s.input_seconds - s.cdt_seconds - s.refine_seconds - s.output_seconds;
  out << "input:" << s.input_seconds << ";setup:" << setup << ";output:" << s.output_seconds
      << ";cdt:" << s.cdt_method << ";iterations:" << s.iterations;
  for (const auto& p : s.cdt_phases) out << ";cdt " << p.name << ':' << p.seconds;
  for (const auto& p : s.phases) out << ';' << p.name << ':' << p.seconds;
  return out.str();
}

// The GPU's first call pays for context creation and module loading; keep that out of cases.
bool warm_up_gpu(std::string& why_not) {
  if (!gdr::gpu_available()) {
    why_not = "no GPU: " + gdr::device_info().reason;
    return false;
  }
  try {
    gdr::Pslg square;
    square.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    square.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
    gdr::Refine2dOptions o;
    o.backend = gdr::Backend::Gpu;
    o.max_edge_length = 0.05;
    gdr::refine_2d(square, o);
    return true;
  } catch (const std::exception& e) {
    why_not = std::string("GPU warm-up failed: ") + e.what();
    return false;
  }
}


Result run_gdr(const Case& c, Inputs& inputs, double max_edge, bool validate) {
  Result r;
  const gdr::Pslg& pslg = inputs.pslg(c.input);
  const gdr::Refine2dOptions options = refine_options(c, max_edge);
  const int repeat = std::max(1, static_cast<int>(c.number("repeat", 1)));
  // The engine polls the abort hook between phases: a case over its time limit stops cleanly
  // (Status::Aborted) and the run goes on with the next case.
  const double timeout = c.number("timeout", 600);
  std::vector<gdr::Refine2dStats> runs;
  gdr::Refine2dResult last;
  for (int i = 0; i < repeat; ++i) {
    const auto start = std::chrono::steady_clock::now();
    gdr::Callbacks callbacks;
    callbacks.abort = [&] {
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout;
    };
    last = gdr::Refine2dResult{};  // free the previous mesh before the next run
    // Strategy ablation: the engine reads GDR_DISABLE (s1, s3, s4, s5, touching, block_rounds,
    // grid_rounds, worst_first).
    const std::string disable = c.text("disable", "");
    if (disable.empty()) unsetenv("GDR_DISABLE");
    else setenv("GDR_DISABLE", disable.c_str(), 1);
    try {
      last = gdr::refine_2d(pslg, options, callbacks);
    } catch (const gdr::Error& e) {
      if (e.status() != gdr::Status::Aborted) throw;
      r.status = "timeout";
      r.message = "stopped after " + number_arg(timeout) + " s";
      return r;
    }
    runs.push_back(last.stats);
  }
  std::sort(runs.begin(), runs.end(), [](const auto& a, const auto& b) {
    return a.total_seconds < b.total_seconds;
  });
  const gdr::Refine2dStats& s = runs[runs.size() / 2];
  r.input_points = s.input_points;
  r.input_segments = s.input_segments;
  r.points = s.output_points;
  r.elements = s.output_triangles;
  r.steiner = s.steiner_points;
  r.cdt_s = s.cdt_seconds;
  r.refine_s = s.refine_seconds;
  r.total_s = s.total_seconds;
  r.min_quality_deg = s.min_angle_deg;
  r.bad_area_pct = s.bad_area_percent;
  r.peak_device_bytes = options.backend == gdr::Backend::Gpu ? double(s.peak_device_bytes) : -1;
  r.phases = phases_text(s);
  if (s.steiner_cap_reached) r.message += "Steiner cap reached. ";
  if (s.stalled) r.message += "refinement stalled. ";
  if (repeat > 1) r.message += "median of " + std::to_string(repeat) + " runs. ";

  if (!validate) {
    r.valid = "skipped";
    return r;
  }
  gdr::ValidateOptions vo;
  vo.min_angle_deg = options.min_angle;
  const auto t0 = std::chrono::steady_clock::now();
  const gdr::ValidationReport report = gdr::validate_trimesh(last.mesh, &pslg, vo);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::fprintf(stderr, "    validated in %.2f s: %s\n", seconds, report.valid ? "valid" : "INVALID");
  r.valid = report.valid ? "yes" : "no";
  if (!report.valid && !report.problems.empty()) r.message += report.problems.front() + " ";
  // The validator's own quality figures, independent of the engine's statistics.
  r.min_quality_deg = report.quality.min_angle_deg;
  r.bad_area_pct = report.quality.bad_measure_percent;
  return r;
}

Result run_baseline(const Case& c, Inputs& inputs, const Settings& s, double max_edge,
                    const TetBounds& bounds) {
  std::vector<std::string> argv;
  auto exe = [&](const char* name) { return (fs::path(s.bin_dir) / name).string(); };
  if (c.runner == "cgal-mesh2") {
    argv = {exe("bench_cgal_mesh2"), inputs.path(c.input),
            "--min-angle", number_arg(c.number("min_angle", 20.0)),
            "--max-edge", number_arg(max_edge),
            "--domain", c.text("exterior", "keep") == "remove" ? "enclosed" : "hull"};
  } else if (c.runner == "tetgen") {
    // B goes along for the checker: the share of tets above it, as for our meshes.
    argv = {exe("bench_tetgen"), inputs.path(c.input), tetgen_switches(c, bounds), "--radius-edge",
            number_arg(bounds.radius_edge)};
  } else {
    argv = {exe("bench_cgal_mesh3"), inputs.path(c.input)};
    if (c.runner == "cgal-mesh3-par") {
      argv.push_back("--parallel");
      argv.insert(argv.end(), {"--threads", c.text("threads", "0")});
    }
    for (const char* key : {"facet_angle", "facet_size", "facet_distance",
                            "cell_radius_edge_ratio", "cell_size", "feature_angle"}) {
      if (c.params.count(key)) {
        std::string flag = std::string("--") + key;
        std::replace(flag.begin(), flag.end(), '_', '-');
        argv.insert(argv.end(), {flag, c.text(key, "")});
      }
    }
    if (c.number("optimize", 1) == 0) argv.push_back("--no-optimize");
  }
  if (!fs::exists(argv[0])) {
    Result r;
    r.status = "skipped";
    r.message = argv[0] + " is not built (its package was missing)";
    return r;
  }

  const int repeat = std::max(1, static_cast<int>(c.number("repeat", 1)));
  const double timeout = c.number("timeout", 600);
  std::vector<Result> runs;
  for (int i = 0; i < repeat; ++i) {
    const ProcessResult p = run_process(argv, timeout);
    Result r;
    r.peak_rss_mb = p.max_rss_mb;
    if (p.timed_out) {
      r.status = "timeout";
      r.message = "no result within " + number_arg(timeout) + " s";
      return r;
    }
    const auto last_brace = p.out.rfind("\n{");
    const auto j = parse_json_line(p.out.substr(last_brace == std::string::npos ? 0 : last_brace));
    auto num = [&](const char* key) {
      const auto it = j.find(key);
      return it == j.end() || it->second == "null" ? -1.0 : std::atof(it->second.c_str());
    };
    auto count = [&](const char* key) { return static_cast<long long>(num(key)); };
    const auto status = j.find("status");
    if (status == j.end() || status->second != "ok") {
      r.status = "error";
      r.message = j.count("message") ? j.at("message")
                                     : "exit code " + std::to_string(p.exit_code) + ", no JSON result";
      return r;
    }
    r.input_points = count("input_points");
    r.input_segments = j.count("input_segments") ? count("input_segments") : count("input_triangles");
    r.points = count("points");
    r.elements = j.count("triangles") ? count("triangles") : count("tets");
    r.steiner = count("steiner_points");
    r.cdt_s = num("cdt_seconds");
    r.refine_s = num("refine_seconds");
    r.total_s = num("total_seconds");
    r.min_quality_deg = j.count("min_angle_deg") ? num("min_angle_deg") : num("min_dihedral_deg");
    r.bad_area_pct = j.count("bad_volume_percent") ? num("bad_volume_percent") : num("bad_area_percent");
    r.bad_elements = count("bad_tets");
    r.bad_elements_pct = num("bad_tets_percent");
    r.max_radius_edge = num("max_radius_edge");
    if (j.count("dihedral_histogram")) {
      std::istringstream bins(j.at("dihedral_histogram"));
      for (long long n; bins >> n;) r.histogram.push_back(n);
    }
    if (j.count("switches")) r.message += "switches " + j.at("switches") + ". ";
    if (j.count("threads")) r.message = "threads=" + j.at("threads") + ". ";
    runs.push_back(r);
  }
  std::sort(runs.begin(), runs.end(), [](const Result& a, const Result& b) { return a.total_s < b.total_s; });
  Result r = runs[runs.size() / 2];
  if (c.runner == "tetgen")
    r.message += "CDT: a TetGen run with the quality and volume switches left out; refine = total - CDT. ";
  if (repeat > 1) r.message += "median of " + std::to_string(repeat) + " runs. ";
  return r;
}

// --generate: writes a generated input; --check puts a surface through the mesher's own
// checks and its CDT (gdr::quality_tet_mesh without refinement), as every case would.
int generate(const std::string& spec, const std::string& out, const Settings& s, bool check) {
  if (!is_surface_spec(spec)) {
    const gdr::Pslg p = generate_pslg(spec);
    write_poly(out, p);
    std::printf("%s: %zu points, %zu segments\n", out.c_str(), p.points.size(), p.segments.size());
    return 0;
  }
  const gdr::Surface surface = generate_surface(spec, s.data_dir);
  write_off(out, surface);
  std::printf("%s: %zu points, %zu triangles, enclosed volume %.9g\n", out.c_str(),
              surface.points.size(), surface.triangles.size(), enclosed_volume(surface));
  if (!check) return 0;
  gdr::QualityTetOptions o;
  o.refine = false;
  o.backend = gdr::Backend::Cpu;
  const gdr::QualityTetStats st = gdr::quality_tet_mesh(surface, o).stats;
  std::printf("checked: closed, manifold, no self-intersection (%.2f s); CDT %lld tets, %lld "
              "Steiner points (%.2f s); domain volume %.9g\n",
              st.input_seconds, st.output_tets, st.cdt_steiner_points, st.cdt_seconds, st.input_volume);
  return 0;
}

void usage() {
  std::cerr
      << "usage: gdr_bench CASES.txt [--out-dir DIR] [--data-dir DIR] [--bin-dir DIR]\n"
         "                 [--work-dir DIR] [--only SUBSTRING]\n"
         "       gdr_bench --generate SPEC OUT.(poly|off) [--check] [--data-dir DIR]\n"
         "  CASES.txt: one case per line, key=value tokens (see Benchmarks/README.md).\n"
         "  --out-dir: where bench.csv and bench.md go (default .)\n"
         "  --data-dir: base of relative input paths (default ../shared/data of the source tree)\n"
         "  --bin-dir: where the baseline programs are (default: beside gdr_bench)\n"
         "  --only: run only cases whose name contains SUBSTRING\n"
         "  --check: put a generated surface through the mesher's surface checks and its CDT\n"
         "  SPEC: gen:contours:segments=N:seed=S[:amplitude=A] (2D, writes .poly)\n"
         "        gen:surface:base=FILE:subdiv=K[:turn=1][:noise=S], gen:torus:triangles=N[:bump=A] (3D, writes .off)\n";
}

}  // namespace

int main(int argc, char** argv) {
  gdr::cli::settle_process(argv);  // as gdr starts (the baselines get the user's settings back)
  Settings s;
  s.data_dir = GDR_BENCH_DATA_DIR;
  std::string cases_path, generate_spec, generate_out;
  bool check_generated = false;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      const bool has_value = i + 1 < argc;
      if (a == "--generate" && i + 2 < argc) {
        generate_spec = argv[++i];
        generate_out = argv[++i];
        continue;
      }
      if (a == "--check") {
        check_generated = true;
        continue;
      }
      if (a == "--out-dir" && has_value) s.out_dir = argv[++i];
      else if (a == "--data-dir" && has_value) s.data_dir = argv[++i];
      else if (a == "--bin-dir" && has_value) s.bin_dir = argv[++i];
      else if (a == "--work-dir" && has_value) s.work_dir = argv[++i];
      else if (a == "--only" && has_value) s.only = argv[++i];
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else if (cases_path.empty() && a[0] != '-') cases_path = a;
      else { usage(); return 2; }
    }
    if (!generate_spec.empty()) return generate(generate_spec, generate_out, s, check_generated);
    if (cases_path.empty()) {
      usage();
      return 2;
    }
    if (s.bin_dir.empty()) s.bin_dir = fs::read_symlink("/proc/self/exe").parent_path().string();
    const bool own_work_dir = s.work_dir.empty();
    if (own_work_dir)
      s.work_dir = (fs::temp_directory_path() / ("gdr_bench." + std::to_string(getpid()))).string();
    fs::create_directories(s.work_dir);
    fs::create_directories(s.out_dir);

    std::vector<Case> cases = read_cases(cases_path);
    if (!s.only.empty()) {
      cases.erase(std::remove_if(cases.begin(), cases.end(),
                                 [&](const Case& c) { return c.name.find(s.only) == std::string::npos; }),
                  cases.end());
    }
    const std::string date = utc_now(), machine = machine_description();
    std::fprintf(stderr, "gdr_bench: %zu cases, %s\n", cases.size(), machine.c_str());

    Inputs inputs(s);
    std::vector<Result> results;
    int gpu_state = 0, gpu3d_state = 0;  // 0 not tried, 1 ready, -1 unusable
    std::string gpu_problem, gpu3d_problem;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      const Case& c = cases[i];
      std::fprintf(stderr, "[%zu/%zu] %s %s ...\n", i + 1, cases.size(), c.name.c_str(), c.runner.c_str());
      Result r;
      try {
        double max_edge = c.number("max_edge", 0.0);
        if (is_2d_runner(c.runner) && c.number("target_points", 0) > 0)
          max_edge = edge_for_points(inputs.pslg(c.input), c.number("target_points", 0));
        const bool bounded_3d = is_gdr_tet_runner(c.runner) || c.runner == "tetgen" || c.runner == "gqm3d";
        const TetBounds bounds = bounded_3d ? tet_bounds(c, inputs) : TetBounds{};
        if (c.runner == "gdr-gpu" && gpu_state == 0) gpu_state = warm_up_gpu(gpu_problem) ? 1 : -1;
        const bool gpu3d = c.runner == "gdr-tet-gpu" || c.runner == "gdr-rdt-gpu";
        if (gpu3d && gpu3d_state == 0) gpu3d_state = warm_up_gpu_3d(gpu3d_problem) ? 1 : -1;
        if (c.runner == "gdr-gpu" && gpu_state < 0) {
          r.status = "skipped";
          r.message = gpu_problem;
        } else if (gpu3d && gpu3d_state < 0) {
          r.status = "skipped";
          r.message = gpu3d_problem;
        } else if (is_gdr_runner(c.runner)) {
          r = run_gdr(c, inputs, max_edge, c.number("validate", 1) != 0);
        } else if (is_gdr_tet_runner(c.runner)) {
          r = run_gdr_tet(c, inputs, bounds, c.number("validate", 1) != 0);
        } else if (is_gdr_rdt_runner(c.runner)) {
          r = run_gdr_rdt(c, inputs, c.number("validate", 1) != 0);
        } else if (c.runner == "triangle") {
          r = run_triangle(c, inputs, s, max_edge);
        } else if (c.runner == "gdp2d") {
          r = run_gdp2d(c, inputs, s, max_edge);
        } else if (c.runner == "gqm3d") {
          r = run_gqm3d(c, inputs, s, bounds);
        } else {
          r = run_baseline(c, inputs, s, max_edge, bounds);
        }
        if (is_2d_runner(c.runner)) {
          r.min_angle_bound = c.number("min_angle", 20.0);
          r.max_edge = max_edge;
          r.min_input_angle = smallest_input_angle(inputs.pslg(c.input));
        }
        if (bounded_3d) {
          r.radius_edge_bound = bounds.radius_edge;
          r.max_volume = bounds.max_volume > 0 ? bounds.max_volume : -1;
          r.min_dihedral_bound = bounds.min_dihedral > 0 ? bounds.min_dihedral : -1;
        }
      } catch (const gdr::Error& e) {
        r.status = "error";
        r.message = std::string(gdr::to_string(e.status())) + ": " + e.what();
      } catch (const std::exception& e) {
        r.status = "error";
        r.message = e.what();
      }
      r.c = c;
      r.input_label = c.input;
      std::fprintf(stderr, "    %s: points %lld, elements %lld, refine %.4f s, total %.4f s %s\n",
                   r.status.c_str(), r.points, r.elements, r.refine_s, r.total_s, r.message.c_str());
      results.push_back(r);
      // Partial results survive a run cut short by the device's time limit.
      compute_ratios(results);
      write_csv((fs::path(s.out_dir) / "bench.csv").string(), results, date, machine);
      write_histograms((fs::path(s.out_dir) / "histograms.csv").string(), results);
      std::ofstream((fs::path(s.out_dir) / "bench.md").string())
          << markdown_table(results, date, machine);
    }
    std::cout << markdown_table(results, date, machine) << std::flush;
    if (own_work_dir) fs::remove_all(s.work_dir);
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "gdr_bench: " << e.what() << "\n";
    return 1;
  }
}
