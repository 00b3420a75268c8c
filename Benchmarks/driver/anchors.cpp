// The anchors (../shared/anchors/bin, copied to .device/bin): Triangle 1.6, and the authors'
// gDP2d and gQM3d, run as child processes from --bin-dir. gDP2d and gQM3d print one line
// `RESULT cdt_s=.. refine_s=.. total_s=.. points=.. triangles|tets=.. bad=..` at the end;
// Triangle's output files are read back and measured with our own quality formulas.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "bench.h"
#include "gdr/backend.h"
#include "gdr/error.h"
#include "gdr/io.h"
#include "gdr/validate.h"

namespace fs = std::filesystem;

namespace gdr_bench {
namespace {

// --bin-dir first (where package_device.sh puts them), then ../shared/anchors/bin of the
// source tree (runs on this machine).
std::string anchor(const Settings& s, const char* name) {
  const fs::path in_bin = fs::path(s.bin_dir) / name;
  if (fs::exists(in_bin)) return in_bin.string();
  const fs::path shared = fs::path(GDR_BENCH_ANCHORS_DIR) / name;
  return fs::exists(shared) ? shared.string() : in_bin.string();
}

Result skipped(const std::string& why) {
  Result r;
  r.status = "skipped";
  r.message = why;
  return r;
}

std::string last_line(const std::string& out) {
  const auto end = out.find_last_not_of("\r\n");
  if (end == std::string::npos) return "";
  const auto newline = out.find_last_of('\n', end);
  const std::size_t start = newline == std::string::npos ? 0 : newline + 1;
  return out.substr(start, end + 1 - start);
}

// A folder of its own per run: anchors write files beside their input or in the current dir.
fs::path scratch_dir(const Settings& s, const std::string& runner, const Case& c) {
  const fs::path dir = fs::path(s.work_dir) / (runner + "." + std::to_string(c.line));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// Runs a RESULT-printing anchor `repeat` times and keeps the median by total time.
// `elements_key` is "triangles" or "tets".
Result run_result_anchor(const Case& c, const std::vector<std::string>& argv, const fs::path& dir,
                         const char* elements_key, const std::string& hang_note) {
  const int repeat = std::max(1, static_cast<int>(c.number("repeat", 1)));
  const double timeout = c.number("timeout", 600);
  std::vector<Result> runs;
  for (int i = 0; i < repeat; ++i) {
    const ProcessResult p = run_process(argv, timeout, dir.string());
    Result one;
    one.peak_rss_mb = p.max_rss_mb;
    if (p.timed_out) {
      one.status = "timeout";
      one.message = "no result within " + number_arg(timeout) + " s, killed" + hang_note;
      return one;
    }
    const auto j = parse_result_line(p.out);
    if (!j.count(elements_key)) {
      one.status = "error";
      one.message = "exit code " + std::to_string(p.exit_code) + ", no RESULT line; last output: " +
                    last_line(p.out);
      return one;
    }
    auto num = [&](const char* key) { return j.count(key) ? std::atof(j.at(key).c_str()) : -1.0; };
    one.points = static_cast<long long>(num("points"));
    one.elements = static_cast<long long>(num(elements_key));
    one.cdt_s = num("cdt_s");
    one.refine_s = num("refine_s");
    one.total_s = j.count("total_s") ? num("total_s") : p.seconds;
    one.bad_elements = static_cast<long long>(num("bad"));
    if (p.exit_code != 0) one.message = "exit code " + std::to_string(p.exit_code) + ". ";
    runs.push_back(one);
  }
  std::sort(runs.begin(), runs.end(), [](const Result& x, const Result& y) { return x.total_s < y.total_s; });
  Result r = runs[runs.size() / 2];
  if (repeat > 1) r.message += "median of " + std::to_string(repeat) + " runs. ";
  return r;
}

}  // namespace

std::map<std::string, std::string> parse_result_line(const std::string& out) {
  std::map<std::string, std::string> j;
  std::istringstream lines(out);
  std::string line, found;
  while (std::getline(lines, line))
    if (line.rfind("RESULT", 0) == 0) found = line;
  std::istringstream tokens(found);
  std::string token;
  tokens >> token;  // RESULT
  while (tokens >> token) {
    const auto eq = token.find('=');
    if (eq != std::string::npos) j[token.substr(0, eq)] = token.substr(eq + 1);
  }
  return j;
}

// Triangle 1.6: CDT alone (-p) and CDT plus refinement (-pq) timed as whole processes with
// the output suppressed (-NEP), refinement = the difference; one more run writes x.1.node/.ele,
// which are measured with the formulas of our 2D results (gdr::triangle_quality).
Result run_triangle(const Case& c, Inputs& inputs, const Settings& s, double max_edge) {
  const std::string exe = anchor(s, "triangle");
  if (!fs::exists(exe)) return skipped(exe + " not found (copy ../shared/anchors/bin into --bin-dir)");
  if (max_edge > 0) return skipped("Triangle has no edge-length bound (compare at max_area instead)");
  const double theta = c.number("min_angle", 20.0);
  const double max_area = c.number("max_area", 0.0);
  // -c: the convex hull with its edges as segments, as our default domain; without it
  // Triangle removes what closed segment loops do not enclose (exterior=remove).
  std::string base = "-p";
  if (c.text("exterior", "keep") != "remove") base += "c";
  // Triangle's own encroachment is our chew mode (the lens of angle 180 - 2 theta); -D gives
  // diametral circles (and a conforming Delaunay mesh), our ruppert mode.
  if (c.text("mode", "chew") == "ruppert") base += "D";
  std::string quality;
  if (theta > 0) quality += "q" + number_arg(theta);
  if (max_area > 0) quality += "a" + plain_decimal(max_area);

  const gdr::Pslg& pslg = inputs.pslg(c.input);
  const fs::path dir = scratch_dir(s, "triangle", c);
  const std::string poly = (dir / "x.poly").string();
  write_poly(poly, pslg);

  const int repeat = std::max(1, static_cast<int>(c.number("repeat", 1)));
  const double timeout = c.number("timeout", 600);
  std::vector<double> cdt, total;
  for (int i = 0; i < repeat; ++i) {
    for (const bool refine : {false, true}) {
      const ProcessResult p = run_process({exe, base + "QNEP" + (refine ? quality : ""), poly}, timeout, dir.string());
      if (p.timed_out || p.exit_code != 0) {
        Result r;
        r.status = p.timed_out ? "timeout" : "error";
        r.message = p.timed_out ? "no result within " + number_arg(timeout) + " s"
                                : "exit code " + std::to_string(p.exit_code);
        fs::remove_all(dir);
        return r;
      }
      (refine ? total : cdt).push_back(p.seconds);
    }
  }
  const ProcessResult p = run_process({exe, base + "Q" + quality, poly}, timeout, dir.string());
  if (p.timed_out || p.exit_code != 0) {
    Result r;
    r.status = p.timed_out ? "timeout" : "error";
    r.message = "writing the mesh: " + std::string(p.timed_out ? "timeout" : "exit code " + std::to_string(p.exit_code));
    fs::remove_all(dir);
    return r;
  }
  const gdr::TriMesh mesh = gdr::io::read_triangle_mesh((dir / "x.1.node").string(), (dir / "x.1.ele").string());
  fs::remove_all(dir);

  std::sort(cdt.begin(), cdt.end());
  std::sort(total.begin(), total.end());
  Result r;
  r.input_points = static_cast<long long>(pslg.points.size());
  r.input_segments = static_cast<long long>(pslg.segments.size());
  r.points = static_cast<long long>(mesh.points.size());
  r.elements = static_cast<long long>(mesh.triangles.size());
  r.steiner = r.points - r.input_points;
  r.cdt_s = cdt[cdt.size() / 2];
  r.total_s = total[total.size() / 2];
  r.refine_s = std::max(0.0, r.total_s - r.cdt_s);
  const gdr::QualityStats q = gdr::triangle_quality(mesh, theta);
  r.min_quality_deg = q.min_angle_deg;
  r.bad_area_pct = q.bad_measure_percent;
  r.message = "switches " + base + quality + "; whole-process times (reading the .poly included, "
              "output suppressed), refine = total - CDT. ";
  if (repeat > 1) r.message += "median of " + std::to_string(repeat) + " runs. ";
  return r;
}

// The authors' gDP2d: `gdp2d x.poly -t THETA [-l MAXEDGE]`; its CDT is Triangle's with the
// convex hull ('pzQnc'), so it has no exterior removal and no area bound.
Result run_gdp2d(const Case& c, Inputs& inputs, const Settings& s, double max_edge) {
  const std::string exe = anchor(s, "gdp2d");
  if (!fs::exists(exe))
    return skipped(exe + " not found (the authors' gDP2d runs on the GPU machine only; "
                         "scripts/package_device.sh copies it from ../shared/anchors/bin)");
  if (!gdr::gpu_available()) return skipped("no GPU: " + gdr::device_info().reason);
  if (c.number("max_area", 0) > 0) return skipped("gDP2d has no area bound");
  if (c.text("exterior", "keep") == "remove") return skipped("gDP2d meshes the whole convex hull");
  std::vector<std::string> argv = {exe, fs::absolute(inputs.path(c.input)).string(), "-t",
                                   number_arg(c.number("min_angle", 20.0))};
  if (max_edge > 0) argv.insert(argv.end(), {"-l", number_arg(max_edge)});
  if (c.text("mode", "chew") == "chew") argv.insert(argv.end(), {"-enc", "0"});
  const fs::path dir = scratch_dir(s, "gdp2d", c);
  Result r = run_result_anchor(c, argv, dir, "triangles", "");
  fs::remove_all(dir);
  const gdr::Pslg& pslg = inputs.pslg(c.input);
  r.input_points = static_cast<long long>(pslg.points.size());
  r.input_segments = static_cast<long long>(pslg.segments.size());
  if (r.status == "ok") {
    r.steiner = r.points - r.input_points;
    r.message += "bad triangles as gdp2d prints them: " + std::to_string(r.bad_elements) +
                 " (no bad area, no angle). ";
  }
  return r;
}

Result run_gqm3d(const Case& c, Inputs& inputs, const Settings& s, const TetBounds& b) {
  const std::string exe = anchor(s, "gqm3d");
  if (!fs::exists(exe))
    return skipped(exe + " not found (the authors' gQM3d runs on the GPU machine only; "
                         "scripts/package_device.sh copies it from ../shared/anchors/bin)");
  if (!gdr::gpu_available()) return skipped("no GPU: " + gdr::device_info().reason);
  if (b.max_volume > 0) return skipped("the authors' gQM3d has no volume bound");
  if (b.min_dihedral > 0) return skipped("the authors' gQM3d has no dihedral bound");
  const std::string input = fs::absolute(inputs.path(c.input)).string();
  const std::string ext = fs::path(input).extension().string();
  if (ext != ".off" && ext != ".poly") return skipped("gqm3d reads .off and .poly only, not " + ext);
  // -scale 1000: the authors' code keeps the bounding box in integers (anchors README).
  const std::vector<std::string> argv = {exe, input, "-q", number_arg(b.radius_edge), "-scale",
                                         c.text("gqm3d_scale", "1000")};
  const fs::path dir = scratch_dir(s, "gqm3d", c);
  Result r = run_result_anchor(c, argv, dir, "tets", " (the authors' gQM3d can livelock at B = 1.4)");
  fs::remove_all(dir);
  const gdr::Surface& surface = inputs.surface(c.input);
  r.input_points = static_cast<long long>(surface.points.size());
  r.input_triangles = static_cast<long long>(surface.triangles.size());
  if (r.status == "ok") {
    r.steiner = r.points - r.input_points;
    if (r.bad_elements >= 0 && r.elements > 0)
      r.bad_elements_pct = 100.0 * double(r.bad_elements) / double(r.elements);
    r.message += "bad tets as gqm3d prints them (its own checker; no dihedral angles). ";
  }
  return r;
}

}  // namespace gdr_bench
