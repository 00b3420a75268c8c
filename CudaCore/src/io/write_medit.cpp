// Medit .mesh writer (ASCII, MeshVersionFormatted 2), read by Gmsh, MMG and Medit itself.
#include <array>
#include <utility>

#include "gdr/error.h"
#include "gdr/io.h"
#include "io/text_file.h"

namespace gdr::io {
namespace {

// "KEYWORD\nCOUNT\n" then one line per element: its corners (1-based) and its reference.
template <std::size_t N, class Ref>
void append_section(std::string& out, const char* keyword,
                    const std::vector<std::array<int, N>>& elements, std::size_t points,
                    Ref ref) {
  out += keyword;
  out += '\n';
  append_number(out, static_cast<long long>(elements.size()));
  out += '\n';
  for (std::size_t i = 0; i < elements.size(); ++i) {
    for (int v : elements[i]) {
      if (v < 0 || static_cast<std::size_t>(v) >= points)
        throw Error(Status::InvalidInput, std::string(keyword) + " " + std::to_string(i) +
                                              " refers to vertex " + std::to_string(v) + " of " +
                                              std::to_string(points));
      append_number(out, static_cast<long long>(v) + 1);
      out += ' ';
    }
    append_number(out, static_cast<long long>(ref(i)));
    out += '\n';
  }
}

}  // namespace

void write_medit(const std::string& path, const TetMesh& mesh) {
  const std::size_t np = mesh.points.size();
  std::string out = "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n";
  out.reserve(40 * np + 30 * mesh.tets.size() + 24 * mesh.subfaces.size() + 128);
  append_number(out, static_cast<long long>(np));
  out += '\n';
  for (std::size_t i = 0; i < np; ++i) {
    const Point3& p = mesh.points[i];
    for (double c : {p.x, p.y, p.z}) {
      append_number(out, c);
      out += ' ';
    }
    const int type = i < mesh.point_type.size() ? static_cast<int>(mesh.point_type[i]) : 0;
    append_number(out, static_cast<long long>(type));
    out += '\n';
  }
  out += '\n';
  // Medit's tetrahedra have a positive volume, (b-a) x (c-a) . (d-a) > 0, as TetGen's:
  // swap two corners of ours (orient3d > 0, gdr/validate.h).
  std::vector<std::array<int, 4>> tets(mesh.tets);
  for (auto& t : tets) std::swap(t[0], t[1]);
  const bool regions = mesh.tet_region.size() == tets.size();
  append_section(out, "Tetrahedra", tets, np,
                 [&](std::size_t t) { return regions ? mesh.tet_region[t] : 1; });
  out += '\n';
  // Facet ids + 1: Medit reserves reference 0 for "none" (no known facet).
  const bool facets = mesh.subface_facet.size() == mesh.subfaces.size();
  append_section(out, "Triangles", mesh.subfaces, np,
                 [&](std::size_t s) { return facets ? mesh.subface_facet[s] + 1 : 0; });
  out += "\nEnd\n";
  write_file_atomically(path, out);
}

}  // namespace gdr::io
