// Case files: one case per line, `key=value` tokens separated by blanks, `#` starts a comment.
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "bench.h"
#include "gdr/error.h"

namespace gdr_bench {

double Case::number(const std::string& key, double fallback) const {
  const auto it = params.find(key);
  if (it == params.end() || it->second.empty()) return fallback;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (*end != '\0') {
    throw gdr::Error(gdr::Status::InvalidInput, "case line " + std::to_string(line) + ": '" +
                                                    key + "=" + it->second + "' is not a number");
  }
  return v;
}

std::string Case::text(const std::string& key, const std::string& fallback) const {
  const auto it = params.find(key);
  return it == params.end() ? fallback : it->second;
}

bool is_gdr_runner(const std::string& r) { return r == "gdr-gpu" || r == "gdr-cpu"; }
bool is_gdr_tet_runner(const std::string& r) { return r == "gdr-tet-gpu" || r == "gdr-tet-cpu"; }
bool is_gdr_rdt_runner(const std::string& r) { return r == "gdr-rdt-gpu" || r == "gdr-rdt-cpu"; }
bool is_2d_runner(const std::string& r) {
  return is_gdr_runner(r) || r == "cgal-mesh2" || r == "triangle" || r == "gdp2d";
}
bool is_3d_runner(const std::string& r) {
  return is_gdr_tet_runner(r) || is_gdr_rdt_runner(r) || r == "tetgen" || r == "gqm3d" || r == "cgal-mesh3-seq" ||
         r == "cgal-mesh3-par";
}

static bool known_runner(const std::string& r) { return is_2d_runner(r) || is_3d_runner(r); }

std::vector<Case> read_cases(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw gdr::Error(gdr::Status::IoError, path + ": cannot open the case file");
  std::vector<Case> cases;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream tokens(line);
    Case c;
    c.line = number;
    std::string token, runners;
    while (tokens >> token) {
      const auto eq = token.find('=');
      if (eq == std::string::npos || eq == 0) {
        throw gdr::Error(gdr::Status::InvalidInput, path + ":" + std::to_string(number) +
                                                        ": expected key=value, got '" + token + "'");
      }
      const std::string key = token.substr(0, eq), value = token.substr(eq + 1);
      if (key == "name") c.name = value;
      else if (key == "input") c.input = value;
      else if (key == "runner") runners = value;
      else c.params[key] = value;
    }
    if (c.name.empty() && c.input.empty() && runners.empty() && c.params.empty()) continue;
    if (c.name.empty() || c.input.empty() || runners.empty()) {
      throw gdr::Error(gdr::Status::InvalidInput,
                       path + ":" + std::to_string(number) + ": name, input and runner are required");
    }
    std::istringstream list(runners);
    std::string runner;
    while (std::getline(list, runner, ',')) {
      if (!known_runner(runner)) {
        throw gdr::Error(gdr::Status::InvalidInput,
                         path + ":" + std::to_string(number) + ": unknown runner '" + runner + "'");
      }
      Case one = c;
      one.runner = runner;
      cases.push_back(one);
    }
  }
  return cases;
}

}  // namespace gdr_bench
