// gdr_bench: cases, results and the pieces of the driver.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "gdr/pslg.h"

namespace gdr_bench {

// One line of a case file: `key=value` tokens. `runner=a,b,c` expands to one case per runner.
struct Case {
  std::string name;    // groups the runners of one input and bounds (ratios are per name)
  std::string input;   // file path (absolute, or relative to the data dir) or gen:... spec
  std::string runner;  // gdr-gpu | gdr-cpu | cgal-mesh2 | tetgen | cgal-mesh3-seq | cgal-mesh3-par
  std::map<std::string, std::string> params;  // everything else, as written
  int line = 0;

  double number(const std::string& key, double fallback) const;
  std::string text(const std::string& key, const std::string& fallback) const;
};

std::vector<Case> read_cases(const std::string& path);
bool is_gdr_runner(const std::string& runner);
bool is_2d_runner(const std::string& runner);

// Generated inputs. "gen:contours:segments=N:seed=S" gives nested wavy closed curves (contour
// lines of smooth hills) in a grid of cells, inside a square frame; curves never cross.
bool is_generator_spec(const std::string& input);
gdr::Pslg generate_pslg(const std::string& spec);
void write_poly(const std::string& path, const gdr::Pslg& pslg);
double convex_hull_area(const std::vector<gdr::Point2>& points);
// Smallest angle between two segments sharing an endpoint, in degrees (180 if none meet).
// Issue 3's Steiner-count target applies to inputs without angles below 60 degrees.
double smallest_input_angle(const gdr::Pslg& pslg);

// Result of one case. Numbers that do not apply stay negative and print as blanks.
struct Result {
  Case c;
  std::string status = "ok";  // ok | error | timeout | skipped
  std::string message;
  std::string valid = "-";    // yes | no | skipped | - (baselines)
  std::string input_label;
  double min_angle_bound = -1, max_edge = -1, min_input_angle = -1;
  long long input_points = -1, input_segments = -1;
  long long points = -1, elements = -1, steiner = -1;
  double cdt_s = -1, refine_s = -1, total_s = -1;
  double min_quality_deg = -1;  // 2D: smallest angle; 3D: smallest dihedral angle
  double bad_area_pct = -1;
  double peak_device_bytes = -1, peak_rss_mb = -1;
  std::string phases;           // name:seconds;...
  // Filled after all cases ran, within the same case name.
  double speedup_vs_cgal_refine = -1, speedup_vs_cgal_total = -1, steiner_vs_cgal = -1;
  double speedup_vs_cpu_refine = -1, speedup_vs_cpu_total = -1;
};

void compute_ratios(std::vector<Result>& results);
void write_csv(const std::string& path, const std::vector<Result>& results,
               const std::string& date, const std::string& machine);
std::string markdown_table(const std::vector<Result>& results, const std::string& date,
                           const std::string& machine);

// Runs argv with a wall-clock limit; captures stdout. Returns the exit code, or -1 on timeout.
struct ProcessResult {
  int exit_code = 0;
  bool timed_out = false;
  std::string out;
  double seconds = 0;
  double max_rss_mb = 0;
};
ProcessResult run_process(const std::vector<std::string>& argv, double timeout_seconds);

// Flat JSON object -> key/value strings (numbers as written, strings unquoted).
std::map<std::string, std::string> parse_json_line(const std::string& line);

}  // namespace gdr_bench
