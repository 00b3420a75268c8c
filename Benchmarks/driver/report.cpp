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

double element_rate(const Result& r) {
  return (r.elements >= 0 && r.refine_s > 0) ? r.elements / r.refine_s : -1;
}

double bytes_per_element(const Result& r) {
  return (r.peak_device_bytes > 0 && r.elements > 0) ? r.peak_device_bytes / r.elements : -1;
}

}  // namespace

void compute_ratios(std::vector<Result>& results) {
  for (auto& r : results) {
    if (r.status != "ok") continue;
    auto other = [&](const char* runner) {
      const Result* o = find_ok(results, r.c.name, runner);
      return o == &r ? nullptr : o;
    };
    if (const Result* cgal = other("cgal-mesh2")) {
      r.speedup_vs_cgal_refine = ratio(cgal->refine_s, r.refine_s);
      r.speedup_vs_cgal_total = ratio(cgal->total_s, r.total_s);
      r.steiner_vs_cgal = ratio(double(r.steiner), double(cgal->steiner));
    }
    if (const Result* tri = other("triangle")) {
      r.speedup_vs_triangle_refine = ratio(tri->refine_s, r.refine_s);
      r.speedup_vs_triangle_total = ratio(tri->total_s, r.total_s);
      r.steiner_vs_triangle = ratio(double(r.steiner), double(tri->steiner));
    }
    if (const Result* gdp = other("gdp2d")) r.speedup_vs_gdp2d_total = ratio(gdp->total_s, r.total_s);
    if (const Result* tg = other("tetgen")) {
      r.speedup_vs_tetgen_refine = ratio(tg->refine_s, r.refine_s);
      r.speedup_vs_tetgen_total = ratio(tg->total_s, r.total_s);
      r.tets_vs_tetgen = ratio(double(r.elements), double(tg->elements));
    }
    if (const Result* gqm = other("gqm3d")) r.speedup_vs_gqm3d_total = ratio(gqm->total_s, r.total_s);
    // Our CPU path of the same dimension.
    const char* cpu_runner = is_gdr_rdt_runner(r.c.runner) ? "gdr-rdt-cpu"
                             : is_3d_runner(r.c.runner)    ? "gdr-tet-cpu"
                                                           : "gdr-cpu";
    if (const Result* cpu = other(cpu_runner)) {
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
       "steiner_vs_triangle,speedup_vs_triangle_refine,speedup_vs_triangle_total,"
       "speedup_vs_gdp2d_total,input_triangles,radius_edge_bound,max_volume,min_dihedral_bound,"
       "elements_per_s_refine,bad_elements,bad_elements_pct,max_radius_edge,"
       "speedup_vs_tetgen_refine,speedup_vs_tetgen_total,speedup_vs_gqm3d_total,elements_vs_tetgen,"
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
      << num(r.steiner_vs_triangle) << ',' << num(r.speedup_vs_triangle_refine) << ','
      << num(r.speedup_vs_triangle_total) << ',' << num(r.speedup_vs_gdp2d_total) << ','
      << fmt_int(r.input_triangles) << ',' << num(r.radius_edge_bound) << ',' << num(r.max_volume) << ','
      << num(r.min_dihedral_bound) << ',' << num(element_rate(r)) << ',' << fmt_int(r.bad_elements) << ','
      << num(r.bad_elements_pct) << ',' << num(r.max_radius_edge) << ','
      << num(r.speedup_vs_tetgen_refine) << ',' << num(r.speedup_vs_tetgen_total) << ','
      << num(r.speedup_vs_gqm3d_total) << ',' << num(r.tets_vs_tetgen) << ','
      << csv_escape(r.phases) << ',' << csv_escape(r.message) << '\n';
  }
  if (!f) throw gdr::Error(gdr::Status::IoError, path + ": write failed");
}

void write_histograms(const std::string& path, const std::vector<Result>& results) {
  std::ofstream f(path);
  if (!f) throw gdr::Error(gdr::Status::IoError, path + ": cannot write");
  f << "case,runner,bin,count\n";
  for (const auto& r : results)
    for (std::size_t b = 0; b < r.histogram.size(); ++b)
      f << csv_escape(r.c.name) << ',' << r.c.runner << ',' << b << ',' << r.histogram[b] << '\n';
  if (!f) throw gdr::Error(gdr::Status::IoError, path + ": write failed");
}

namespace {

void table_2d(std::ostringstream& md, const std::vector<const Result*>& rows) {
  md << "| case | runner | status | valid | input angle | points | elements | Steiner | CDT s | refine s | "
        "total s | Steiner/s refine | Steiner/s total | min angle | bad area % | peak dev MB | "
        "dev B/elem | x CGAL refine | x CGAL total | Steiner / CGAL | Steiner / Triangle | x CPU refine | "
        "x CPU total |\n"
     << "|---|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const Result* p : rows) {
    const Result& r = *p;
    md << "| " << r.c.name << " | " << r.c.runner << " | " << r.status << " | " << r.valid
       << " | " << fmt(r.min_input_angle) << " | " << fmt_int(r.points) << " | " << fmt_int(r.elements) << " | "
       << fmt_int(r.steiner) << " | " << fmt(r.cdt_s) << " | " << fmt(r.refine_s) << " | "
       << fmt(r.total_s) << " | " << fmt(steiner_rate(r, r.refine_s)) << " | "
       << fmt(steiner_rate(r, r.total_s)) << " | " << fmt(r.min_quality_deg) << " | "
       << fmt(r.bad_area_pct) << " | "
       << fmt(r.peak_device_bytes > 0 ? r.peak_device_bytes / (1024.0 * 1024.0) : -1) << " | "
       << fmt(bytes_per_element(r)) << " | " << fmt(r.speedup_vs_cgal_refine) << " | "
       << fmt(r.speedup_vs_cgal_total) << " | " << fmt(r.steiner_vs_cgal) << " | "
       << fmt(r.steiner_vs_triangle) << " | "
       << fmt(r.speedup_vs_cpu_refine) << " | " << fmt(r.speedup_vs_cpu_total) << " |\n";
  }
  md << "\ninput angle: smallest angle between input segments. min angle: smallest triangle angle, "
        "degrees. x CGAL / x CPU: speed-up over cgal-mesh2 / gdr-cpu on the same case (>1 is "
        "faster). Steiner / CGAL, Steiner / Triangle: Steiner points relative to cgal-mesh2's, "
        "triangle's.\n";
}

void table_3d(std::ostringstream& md, const std::vector<const Result*>& rows) {
  md << "| case | runner | status | valid | B | max volume | tets | points | Steiner | CDT s | "
        "refine s | total s | tets/s refine | % tets > B | min dihedral | dev B/tet | "
        "x TetGen refine | x TetGen total | x gQM3d total | x CPU refine | x CPU total | "
        "tets / TetGen |\n"
     << "|---|---|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";
  for (const Result* p : rows) {
    const Result& r = *p;
    md << "| " << r.c.name << " | " << r.c.runner << " | " << r.status << " | " << r.valid << " | "
       << fmt(r.radius_edge_bound) << " | " << fmt(r.max_volume) << " | " << fmt_int(r.elements)
       << " | " << fmt_int(r.points) << " | " << fmt_int(r.steiner) << " | " << fmt(r.cdt_s)
       << " | " << fmt(r.refine_s) << " | " << fmt(r.total_s) << " | " << fmt(element_rate(r))
       << " | " << fmt(r.bad_elements_pct) << " | " << fmt(r.min_quality_deg) << " | "
       << fmt(bytes_per_element(r)) << " | " << fmt(r.speedup_vs_tetgen_refine) << " | "
       << fmt(r.speedup_vs_tetgen_total) << " | " << fmt(r.speedup_vs_gqm3d_total) << " | "
       << fmt(r.speedup_vs_cpu_refine) << " | " << fmt(r.speedup_vs_cpu_total) << " | "
       << fmt(r.tets_vs_tetgen) << " |\n";
  }
  md << "\nB: radius-edge bound. % tets > B: share of the output tets whose radius-edge ratio "
        "exceeds B, measured by gdr::tet_quality on the tets of every runner except gqm3d (its "
        "own printed count). min dihedral: smallest dihedral angle, degrees. dev B/tet: peak "
        "device bytes per output tet. x TetGen / x gQM3d / x CPU: speed-up over tetgen / gqm3d "
        "/ gdr-tet-cpu on the same case (>1 is faster). tets / TetGen: output tets relative to "
        "TetGen's.\n";
}

// Dihedral angles side by side: per case and runner, the share of all angles in 10-degree
// bands (histograms.csv has the 1-degree bins).
void histogram_bands(std::ostringstream& md, const std::vector<const Result*>& rows) {
  md << "\nDihedral angles, percent of all angles per band (degrees):\n\n| case | runner |";
  for (int b = 0; b < 180; b += 10) md << ' ' << b << '-' << b + 10 << " |";
  md << "\n|---|---|";
  for (int b = 0; b < 180; b += 10) md << "--:|";
  md << '\n';
  for (const Result* p : rows) {
    const Result& r = *p;
    if (r.histogram.empty()) continue;
    double all = 0;
    for (long long n : r.histogram) all += double(n);
    md << "| " << r.c.name << " | " << r.c.runner << " |";
    for (int b = 0; b < 180; b += 10) {
      double band = 0;
      for (int k = b; k < b + 10 && k < static_cast<int>(r.histogram.size()); ++k) band += double(r.histogram[k]);
      char text[32];
      std::snprintf(text, sizeof text, " %.2f |", all > 0 ? 100.0 * band / all : 0.0);
      md << text;
    }
    md << '\n';
  }
}

}  // namespace

std::string markdown_table(const std::vector<Result>& results, const std::string& date,
                           const std::string& machine) {
  std::ostringstream md;
  md << "Run " << date << " on " << machine << "\n";
  std::vector<const Result*> two, three;
  for (const auto& r : results) (is_3d_runner(r.c.runner) ? three : two).push_back(&r);
  if (!two.empty()) {
    md << "\n";
    table_2d(md, two);
  }
  if (!three.empty()) {
    md << "\n";
    table_3d(md, three);
    if (std::any_of(three.begin(), three.end(), [](const Result* r) { return !r->histogram.empty(); }))
      histogram_bands(md, three);
  }
  for (const auto& r : results)
    if (r.status != "ok" || !r.message.empty())
      md << "\n- " << r.c.name << " / " << r.c.runner << ": " << r.status << ": " << r.message;
  md << "\n";
  return md.str();
}

}  // namespace gdr_bench
