#include "command_support.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>

#include "cli.h"
#include "gdr/error.h"
#include "gdr/io.h"
#include "interrupt.h"
#include "table.h"

namespace gdr::cli {

Backend parse_backend(const std::string& command, const std::string& value) {
  try {
    return backend_from_string(value);
  } catch (const Error& e) {
    throw UsageError(command, e.what());
  }
}

std::string single_input(const std::string& command, const std::vector<std::string>& positional) {
  if (positional.empty()) throw UsageError(command, "missing INPUT file");
  if (positional.size() > 1) throw UsageError(command, "unexpected argument '" + positional[1] + "'");
  return positional[0];
}

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string backend_line(Backend used, const std::string& device_name) {
  if (used == Backend::Gpu) return "gpu (" + (device_name.empty() ? std::string("CUDA device") : device_name) + ")";
  // The run's own count ("CPU (N OpenMP threads)"): small 3D meshes use fewer threads.
  const std::string prefix = "CPU (";
  if (device_name.compare(0, prefix.size(), prefix) == 0) return "cpu (" + device_name.substr(prefix.size());
  return "cpu (OpenMP, " + std::to_string(cpu_threads()) + " threads)";
}

bool same_file(const std::string& a, const std::string& b) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::equivalent(a, b, ec)) return true;
  std::error_code ea, eb;
  const fs::path ca = fs::weakly_canonical(fs::absolute(a), ea);
  const fs::path cb = fs::weakly_canonical(fs::absolute(b), eb);
  return !ea && !eb && ca == cb;
}

void refuse_overwrites(const std::string& command, const std::string& input,
                       const std::vector<std::string>& reads,
                       const std::vector<OutputFile>& outputs) {
  for (const std::string& r : reads)
    for (const OutputFile& w : outputs)
      if (same_file(w.path, r))
        throw UsageError(command, w.option + " would overwrite " +
                                      (r == input ? "the input " : "the .node beside the input, ") +
                                      r + ": choose another output name");
  for (std::size_t i = 0; i < outputs.size(); ++i)
    for (std::size_t j = i + 1; j < outputs.size(); ++j)
      if (same_file(outputs[i].path, outputs[j].path))
        throw UsageError(command, outputs[j].option + " would overwrite " + outputs[i].path +
                                      ", which " + outputs[i].option + " writes");
}

void make_parent_dirs(const std::string& path) {
  const auto parent = std::filesystem::path(path).parent_path();
  std::error_code ec;
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  if (ec) throw Error(Status::IoError, parent.string() + ": cannot create folder: " + ec.message());
}

void stop_if_interrupted() {
  if (InterruptHandler::received()) throw Error(Status::Aborted, "interrupted");
}

int run_interruptible(const std::string& output, const std::function<int(bool& written)>& work) {
  InterruptHandler interrupts;
  bool written = false;
  try {
    return work(written);
  } catch (const Error& e) {
    const int signal = InterruptHandler::received();
    if (e.status() != Status::Aborted || signal == 0) throw;
    std::fprintf(stderr, "gdr: interrupted%s\n",
                 written ? (" (" + output + " was written, nothing else)").c_str() : "");
    return kExitSignalBase + signal;
  }
}

double since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The dihedral histogram in 10-degree groups, from the first group with angles to the last,
// as TetGen's -V statistics show it.
std::string sliver_summary(double angle, long long before, long long after, long long moves, long long flips) {
  return with_commas(before) + " tetrahedra with an angle below " + fixed(angle, 1) + " deg (or above " +
         fixed(180 - angle, 1) + ") before smoothing, " + with_commas(after) + " after (" + with_commas(moves) +
         " moves" + (flips > 0 ? ", " + with_commas(flips) + " flips)" : ")");
}

void print_dihedral_histogram(std::ostream& out, const std::vector<long long>& bins) {
  std::vector<long long> groups(18, 0);
  long long total = 0;
  for (std::size_t b = 0; b < bins.size(); ++b) {
    groups[std::min<std::size_t>(b / 10, 17)] += bins[b];
    total += bins[b];
  }
  if (total == 0) return;
  const auto used = [](long long n) { return n > 0; };
  const int first = static_cast<int>(std::find_if(groups.begin(), groups.end(), used) - groups.begin());
  const int last = 17 - static_cast<int>(std::find_if(groups.rbegin(), groups.rend(), used) - groups.rbegin());
  const long long most = *std::max_element(groups.begin(), groups.end());
  out << "dihedral angles (all six of every tetrahedron)\n";
  for (int g = first; g <= last; ++g) {
    const int width = static_cast<int>(40.0 * groups[g] / most + 0.5);
    char line[160];
    std::snprintf(line, sizeof line, "  %3d-%3d deg  %13s  %5.1f%%  %s", 10 * g, 10 * g + 10,
                  with_commas(groups[g]).c_str(), 100.0 * groups[g] / total,
                  std::string(groups[g] > 0 ? std::max(width, 1) : 0, '#').c_str());
    out << line << '\n';
  }
}

void write_dihedral_histogram_csv(const std::string& path, const std::vector<long long>& bins) {
  std::string csv = "angle_lo,angle_hi,count\n";
  for (std::size_t b = 0; b < bins.size(); ++b)
    csv += std::to_string(b) + "," + std::to_string(b + 1) + "," + std::to_string(bins[b]) + "\n";
  io::write_file_atomically(path, csv);
}

}  // namespace gdr::cli
