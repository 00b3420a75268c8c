// write_surface: a TetMesh's subfaces as a surface file (.vtp or .off).
#include <cctype>
#include <cstdio>
#include <string>

#include "gdr/error.h"
#include "gdr/io.h"

namespace gdr::io {

namespace {

std::string lower_extension(const std::string& path) {
  const std::size_t dot = path.find_last_of('.');
  const std::size_t slash = path.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

}  // namespace

void write_surface(const std::string& path, const TetMesh& mesh, const Attributes& attributes) {
  const std::string ext = lower_extension(path);
  if (ext == ".vtp") return write_surface_vtp(path, mesh, attributes);
  if (ext != ".off")
    throw Error(Status::IoError, path + ": unsupported output format '" + ext +
                                     "' for a surface (expected .vtp or .off)");
  std::string out = "OFF\n" + std::to_string(mesh.points.size()) + " " +
                    std::to_string(mesh.subfaces.size()) + " 0\n";
  char line[128];
  for (const Point3& p : mesh.points) {
    std::snprintf(line, sizeof line, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
    out += line;
  }
  for (const auto& t : mesh.subfaces)
    out += "3 " + std::to_string(t[0]) + " " + std::to_string(t[1]) + " " + std::to_string(t[2]) + "\n";
  write_file_atomically(path, out);
}

}  // namespace gdr::io
