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
  std::string runner;  // see known runners in cases.cpp and Benchmarks/README.md
  std::map<std::string, std::string> params;  // everything else, as written
  int line = 0;

  double number(const std::string& key, double fallback) const;
  std::string text(const std::string& key, const std::string& fallback) const;
};

std::vector<Case> read_cases(const std::string& path);
bool is_gdr_runner(const std::string& runner);      // gdr-gpu, gdr-cpu (2D, in-process)
bool is_gdr_tet_runner(const std::string& runner);  // gdr-tet-gpu, gdr-tet-cpu (3D, in-process)
bool is_gdr_rdt_runner(const std::string& runner);  // gdr-rdt-gpu, gdr-rdt-cpu (3D, in-process)
bool is_2d_runner(const std::string& runner);       // gdr-*, cgal-mesh2, triangle, gdp2d
bool is_3d_runner(const std::string& runner);       // gdr-tet-*, gdr-rdt-*, tetgen, gqm3d, cgal-mesh3-*

// Paths and folders of one gdr_bench run.
struct Settings {
  std::string data_dir;
  std::string bin_dir;
  std::string work_dir;
  std::string out_dir = ".";
  std::string only;
};

// Generated 2D inputs. "gen:contours:segments=N:seed=S" gives nested wavy closed curves
// (contour lines of smooth hills) in a grid of cells, inside a square frame; curves never cross.
bool is_generator_spec(const std::string& input);
gdr::Pslg generate_pslg(const std::string& spec);
void write_poly(const std::string& path, const gdr::Pslg& pslg);
double convex_hull_area(const std::vector<gdr::Point2>& points);
// Smallest angle between two segments sharing an endpoint, in degrees (180 if none meet).
// Issue 3's Steiner-count target applies to inputs without angles below 60 degrees.
double smallest_input_angle(const gdr::Pslg& pslg);

// Generated closed surfaces (surfaces.cpp):
//   gen:surface:base=FILE[:subdiv=K]  midpoint subdivision of a closed surface, K times (x4
//                                     triangles each time; the shape does not change)
//   gen:torus:triangles=N[:bump=A]    a bumpy torus of about N triangles
// A relative base file is looked up under data_dir (as case inputs are).
bool is_surface_spec(const std::string& input);
gdr::Surface generate_surface(const std::string& spec, const std::string& data_dir);
void write_off(const std::string& path, const gdr::Surface& surface);
// Volume enclosed by a closed, consistently oriented surface (absolute value).
double enclosed_volume(const gdr::Surface& surface);

// Inputs are loaded or generated once and shared by every runner of every case using them.
class Inputs {
 public:
  explicit Inputs(const Settings& s) : s_(s) {}
  // A file holding the input: the file itself, or the generated input written into the work
  // dir (.poly for 2D, .off for 3D).
  std::string path(const std::string& input);
  bool is_surface(const std::string& input);  // a 3D input (by generator or file type)
  const gdr::Pslg& pslg(const std::string& input);
  const gdr::Surface& surface(const std::string& input);

 private:
  std::string file(const std::string& input) const;
  const Settings& s_;
  std::map<std::string, gdr::Pslg> pslgs_;
  std::map<std::string, gdr::Surface> surfaces_;
  std::map<std::string, std::string> written_;
};

// Result of one case. Numbers that do not apply stay negative and print as blanks.
struct Result {
  Case c;
  std::string status = "ok";  // ok | error | timeout | skipped
  std::string message;
  std::string valid = "-";    // yes | no | skipped | - (baselines)
  std::string input_label;
  double min_angle_bound = -1, max_edge = -1, min_input_angle = -1;
  double radius_edge_bound = -1, max_volume = -1, min_dihedral_bound = -1;  // 3D bounds
  long long input_points = -1, input_segments = -1, input_triangles = -1;
  long long points = -1, elements = -1, steiner = -1;
  double cdt_s = -1, refine_s = -1, total_s = -1;
  double min_quality_deg = -1;  // 2D: smallest angle; 3D: smallest dihedral angle
  double bad_area_pct = -1;     // 2D: bad area; 3D: volume of the tets above B, percent
  long long bad_elements = -1;  // 3D: tets above the radius-edge bound B
  double bad_elements_pct = -1; // 3D: their share of the tets, percent
  double max_radius_edge = -1;
  double peak_device_bytes = -1, peak_rss_mb = -1;
  std::string phases;           // name:seconds;...
  std::vector<long long> histogram;  // 3D: all dihedral angles, 1-degree bins over [0, 180)
  // Filled after all cases ran, within the same case name.
  double speedup_vs_cgal_refine = -1, speedup_vs_cgal_total = -1, steiner_vs_cgal = -1;
  double speedup_vs_cpu_refine = -1, speedup_vs_cpu_total = -1;  // gdr-cpu / gdr-tet-cpu
  double steiner_vs_triangle = -1, speedup_vs_triangle_refine = -1, speedup_vs_triangle_total = -1;
  double speedup_vs_gdp2d_total = -1;
  double speedup_vs_tetgen_refine = -1, speedup_vs_tetgen_total = -1, tets_vs_tetgen = -1;
  double speedup_vs_gqm3d_total = -1;
};

void compute_ratios(std::vector<Result>& results);
void write_csv(const std::string& path, const std::vector<Result>& results,
               const std::string& date, const std::string& machine);
// case,runner,bin,count for every 3D result with a histogram.
void write_histograms(const std::string& path, const std::vector<Result>& results);
std::string markdown_table(const std::vector<Result>& results, const std::string& date,
                           const std::string& machine);

// Runs argv with a wall-clock limit, in `cwd` when given; captures stdout.
struct ProcessResult {
  int exit_code = 0;
  bool timed_out = false;
  std::string out;
  double seconds = 0;
  double max_rss_mb = 0;
};
ProcessResult run_process(const std::vector<std::string>& argv, double timeout_seconds,
                          const std::string& cwd = "");

// Flat JSON object -> key/value strings (numbers as written, strings unquoted).
std::map<std::string, std::string> parse_json_line(const std::string& line);
// The last line of `out` that starts with `RESULT`, as key=value pairs (the anchors' format).
std::map<std::string, std::string> parse_result_line(const std::string& out);

// Runners (anchors.cpp, runners3d.cpp). Each returns a Result with status and numbers;
// the caller fills in the case and the input label.
std::string number_arg(double v);    // all digits, for command lines
std::string plain_decimal(double v); // > 0, ~7 digits, no exponent (Triangle's and TetGen's -a)
Result run_triangle(const Case& c, Inputs& inputs, const Settings& s, double max_edge);
Result run_gdp2d(const Case& c, Inputs& inputs, const Settings& s, double max_edge);

// The 3D bounds of a case, the same for every runner: radius_edge (B, default 2.0, or the
// q value of explicit TetGen switches), min_dihedral, and max_volume (or target_tets, which
// sets it from the enclosed volume).
struct TetBounds {
  double radius_edge = 2.0, min_dihedral = 0, max_volume = 0;
};
TetBounds tet_bounds(const Case& c, Inputs& inputs);
// TetGen switches for these bounds: `switches` when the case gives them, else pq<B>[/<d>][a<V>].
std::string tetgen_switches(const Case& c, const TetBounds& b);
// Tets per unit of max_volume: max_volume = kTetsPerVolumeBound * volume / target_tets.
extern const double kTetsPerVolumeBound;
Result run_gdr_tet(const Case& c, Inputs& inputs, const TetBounds& b, bool validate);
Result run_gdr_rdt(const Case& c, Inputs& inputs, bool validate);
// The authors' gQM3d (anchors): B only; skipped with a volume or dihedral bound.
Result run_gqm3d(const Case& c, Inputs& inputs, const Settings& s, const TetBounds& b);
// The GPU's first 3D call loads the 3D kernels: a tiny mesh keeps that out of the cases.
bool warm_up_gpu_3d(std::string& why_not);

}  // namespace gdr_bench
