// Ratios between runners of one case, and the CSV / Markdown outputs.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "bench.h"
#include "gdr/error.h"

namespace gdr_bench {

namespace {

const Result* find_ok(const std::vector<Result>& results, const std::string& name,
                      const std::string& runner) {
  for (const auto& r : results)
    if (r.c.name == name && r.c.runner == runner && r.status == "ok") return &r;
  return nullptr;
}

double ratio(double num, double den) { return (num > 0 && den > 0) ? num / den : -1; }

// Blank for "does not apply"; otherwise a compact number.
std::string fmt(double v, int digits = 3) {
  if (v < 0 || !std::isfinite(v)) return "";
  char b[64];
  if (v != 0 && (std::abs(v) >= 1e7 || std::abs(v) < 1e-3)) std::snprintf(b, sizeof b, "%.*e", digits - 1, v);
  else std::snprintf(b, sizeof b, "%.*g", std::max(digits, static_cast<int>(std::log10(std::max(v, 1.0))) + 1), v);
  return b;
}
std::string fmt_int(long long v) { return v < 0 ? "" : std::to_string(v); }

std::string csv_escape(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string out = "\"";
  for (char c : s) out += c == '"' ? std::string("\"\"") : std::string(1, c);
  return out + "\"";
}

double steiner_rate(const Result& r, double seconds) {
  return (r.steiner >= 0 && seconds > 0) ? r.steiner / seconds : -1;
}

double bytes_per_element(const Result& r) {
  return (r.peak_device_bytes > 0 && r.elements > 0) ? r.peak_device_bytes / r.elements : -1;
}

}  // namespace

void compute_ratios(std::vector<Result>& results) {
  for (auto& r : results) {
    if (r.status != "ok") continue;
    if (const Result* cgal = find_ok(results, r.c.name, "cgal-mesh2"); cgal && &r != cgal) {
      r.speedup_vs_cgal_refine = ratio(cgal->refine_s, r.refine_s);
      r.speedup_vs_cgal_total = ratio(cgal->total_s, r.total_s);
      r.steiner_vs_cgal = ratio(double(r.steiner), double(cgal->steiner));
    }
    if (const Result* cpu = find_ok(results, r.c.name, "gdr-cpu"); cpu && &r != cpu) {
      r.speedup_vs_cpu_refine = ratio(cpu->refine_s, r.refine_s);
      r.speedup_vs_cpu_total = ratio(cpu->total_s, r.total_s);
    }
  }
}

void write_csv(const std::string& path, const std::vector<Result>& results,
               const std::string& date, const std::string& machine) {
  std::ofstream f(path);
  if (!f) throw gdr::Error(gdr::Status::IoError, path + ": cannot write");
  f << "date,machine,case,runner,input,params,status,valid,min_angle_bound,max_edge,min_input_angle,"
       "input_points,input_segments,points,elements,steiner_points,cdt_s,refine_s,total_s,"
       "steiner_per_s_refine,steiner_per_s_total,min_quality_deg,bad_area_pct,"
       "peak_device_bytes,device_bytes_per_element,peak_rss_mb,speedup_vs_cgal_refine,"
       "speedup_vs_cgal_total,steiner_vs_cgal,speedup_vs_cpu_refine,speedup_vs_cpu_total,"
       "phases,message\n";
  f.precision(9);
  for (const auto& r : results) {
    std::ostringstream params;
    for (const auto& [k, v] : r.c.params) params << k << '=' << v << ' ';
    auto num = [](double v) {
      std::ostringstream s;
      s.precision(9);
      if (v >= 0 && std::isfinite(v)) s << v;
      return s.str();
    };
    f << csv_escape(date) << ',' << csv_escape(machine) << ',' << csv_escape(r.c.name) << ','
      << r.c.runner << ',' << csv_escape(r.input_label) << ',' << csv_escape(params.str()) << ','
      << r.status << ',' << r.valid << ',' << num(r.min_angle_bound) << ',' << num(r.max_edge)
      << ',' << num(r.min_input_angle) << ',' << fmt_int(r.input_points) << ',' << fmt_int(r.input_segments) << ','
      << fmt_int(r.points) << ',' << fmt_int(r.elements) << ',' << fmt_int(r.steiner) << ','
      << num(r.cdt_s) << ',' << num(r.refine_s) << ',' << num(r.total_s) << ','
      << num(steiner_rate(r, r.refine_s)) << ',' << num(steiner_rate(r, r.total_s)) << ','
      << num(r.min_quality_deg) << ',' << num(r.bad_area_pct) << ','
      << num(r.peak_device_bytes) << ',' << num(bytes_per_element(r)) << ','
      << num(r.peak_rss_mb) << ',' << num(r.speedup_vs_cgal_refine) << ','
      << num(r.speedup_vs_cgal_total) << ',' << num(r.steiner_vs_cgal) << ','
      << num(r.speedup_vs_cpu_refine) << ',' << num(r.speedup_vs_cpu_total) << ','
      << csv_escape(r.phases) << ',' << csv_escape(r.message) << '\n';
  }
  if (!f) throw gdr::Error(gdr::Status::IoError, path + ": write failed");
}

std::string markdown_table(const std::vector<Result>& results, const std::string& date,
                           const std::string& machine) {
  std::ostringstream md;
  md << "Run " << date << " on " << machine << "\n\n"
     << "| case | runner | status | valid | input angle | points | elements | Steiner | CDT s | refine s | "
        "total s | Steiner/s refine | Steiner/s total | min angle | bad area % | peak dev MB | "
        "dev B/elem | x CGAL refine | x CGAL total | Steiner / CGAL | x CPU refine | "
        "x CPU total |\n"
     << "|---|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const auto& r : results) {
    md << "| " << r.c.name << " | " << r.c.runner << " | " << r.status << " | " << r.valid
       << " | " << fmt(r.min_input_angle) << " | " << fmt_int(r.points) << " | " << fmt_int(r.elements) << " | "
       << fmt_int(r.steiner) << " | " << fmt(r.cdt_s) << " | " << fmt(r.refine_s) << " | "
       << fmt(r.total_s) << " | " << fmt(steiner_rate(r, r.refine_s)) << " | "
       << fmt(steiner_rate(r, r.total_s)) << " | " << fmt(r.min_quality_deg) << " | "
       << fmt(r.bad_area_pct) << " | "
       << fmt(r.peak_device_bytes > 0 ? r.peak_device_bytes / (1024.0 * 1024.0) : -1) << " | "
       << fmt(bytes_per_element(r)) << " | " << fmt(r.speedup_vs_cgal_refine) << " | "
       << fmt(r.speedup_vs_cgal_total) << " | " << fmt(r.steiner_vs_cgal) << " | "
       << fmt(r.speedup_vs_cpu_refine) << " | " << fmt(r.speedup_vs_cpu_total) << " |\n";
  }
  md << "\ninput angle: smallest angle between input segments (2D). min angle: smallest triangle angle (2D) or smallest dihedral angle (3D), degrees. "
        "x CGAL / x CPU: speed-up over cgal-mesh2 / gdr-cpu on the same case (>1 is faster). "
        "Steiner / CGAL: Steiner points relative to cgal-mesh2.\n";
  for (const auto& r : results)
    if (r.status != "ok" || !r.message.empty())
      md << "\n- " << r.c.name << " / " << r.c.runner << ": " << r.status << ": " << r.message;
  md << "\n";
  return md.str();
}

}  // namespace gdr_bench
