// Case inputs: files under the data dir, or generated (2D contour maps, 3D surfaces), each
// loaded or generated once per run and written to the work dir when a child process needs a file.
#include <algorithm>
#include <cctype>
#include <filesystem>

#include "bench.h"
#include "gdr/io.h"

namespace fs = std::filesystem;

namespace gdr_bench {

std::string Inputs::file(const std::string& input) const {
  if (fs::path(input).is_absolute() || fs::exists(input)) return input;
  return (fs::path(s_.data_dir) / input).string();
}

std::string Inputs::path(const std::string& input) {
  if (!is_generator_spec(input)) return file(input);
  auto it = written_.find(input);
  if (it != written_.end()) return it->second;
  std::string name = input;
  std::replace_if(name.begin(), name.end(), [](char c) { return !std::isalnum(c); }, '_');
  const bool surface = is_surface(input);
  name = (fs::path(s_.work_dir) / (name + (surface ? ".off" : ".poly"))).string();
  if (surface) write_off(name, this->surface(input));
  else write_poly(name, pslg(input));
  return written_[input] = name;
}

bool Inputs::is_surface(const std::string& input) {
  if (is_generator_spec(input)) return is_surface_spec(input);
  return gdr::io::detect_input_kind(file(input)) == gdr::io::InputKind::Surface3d;
}

const gdr::Pslg& Inputs::pslg(const std::string& input) {
  auto it = pslgs_.find(input);
  if (it != pslgs_.end()) return it->second;
  gdr::Pslg p = is_generator_spec(input) ? generate_pslg(input) : gdr::io::read_poly(file(input));
  return pslgs_.emplace(input, std::move(p)).first->second;
}

const gdr::Surface& Inputs::surface(const std::string& input) {
  auto it = surfaces_.find(input);
  if (it != surfaces_.end()) return it->second;
  gdr::Surface s = is_generator_spec(input) ? generate_surface(input, s_.data_dir)
                                            : gdr::io::read_surface(file(input));
  return surfaces_.emplace(input, std::move(s)).first->second;
}

}  // namespace gdr_bench
