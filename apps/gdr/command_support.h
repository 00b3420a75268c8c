// Steps the meshing commands (gdr 2d, gdr tet) share: output paths checked before anything
// is read, folders made for outputs, interruption checked between steps, timing.
#pragma once
#include <chrono>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "gdr/backend.h"

namespace gdr::cli {

// A file a command line writes, and the option that names it (for messages).
struct OutputFile {
  std::string path, option;
};

// Whether two paths name the same file: through links, or the same place once resolved
// (for files that do not exist yet).
bool same_file(const std::string& a, const std::string& b);

// Refuses (UsageError of `command`) a command line that would write over one of the files
// it reads (`input` and the files `reads` lists, e.g. the .node beside a .poly) or write
// one file twice.
void refuse_overwrites(const std::string& command, const std::string& input,
                       const std::vector<std::string>& reads,
                       const std::vector<OutputFile>& outputs);

// Creates the folders above `path`; IoError when that fails.
void make_parent_dirs(const std::string& path);

// Throws Error(Aborted) between steps once a signal asked the run to stop (InterruptHandler).
void stop_if_interrupted();

// Runs `work` with Ctrl-C and SIGTERM caught (InterruptHandler). When a signal stops it,
// prints "gdr: interrupted" (naming `output` when work had set `written`) and returns
// 128 + the signal; otherwise returns what work returns.
int run_interruptible(const std::string& output, const std::function<int(bool& written)>& work);

// Seconds since t0.
double since(std::chrono::steady_clock::time_point t0);

// Wall-clock seconds of a command's own steps around the mesher.
struct CliTimes {
  double read = 0, write = 0, check = 0, wall = 0;
};

// The value of --backend (UsageError of `command` when it names none).
Backend parse_backend(const std::string& command, const std::string& value);

// The one INPUT operand of a command line (UsageError when missing or not alone).
std::string single_input(const std::string& command, const std::vector<std::string>& positional);

// A file name's extension in lower case (".VTU" is ".vtu", as the readers and writers take it).
std::string lower_extension(const std::string& path);

// "gpu (device name)" or "cpu (OpenMP, N threads)", for a run's statistics.
std::string backend_line(Backend used, const std::string& device_name);

// The dihedral-angle histogram (1-degree bins over [0, 180)) of gdr tet and gdr rdt: in
// 10-degree groups from the first group with angles to the last, as TetGen's -V statistics
// show it; and as a CSV file angle_lo,angle_hi,count (written atomically).
void print_dihedral_histogram(std::ostream& out, const std::vector<long long>& bins);

// The summary's line on sliver removal (--sliver-angle) of gdr tet and gdr rdt: the
// tetrahedra with an angle beyond `angle` degrees before and after smoothing, and the moves.
std::string sliver_summary(double angle, long long before, long long after, long long moves,
                           long long flips = 0);
void write_dihedral_histogram_csv(const std::string& path, const std::vector<long long>& bins);

}  // namespace gdr::cli
