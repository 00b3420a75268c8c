// Medit .mesh writer (ASCII, MeshVersionFormatted 2), read by Gmsh, MMG and Medit itself.
#include <array>

#include "gdr/error.h"
#include "gdr/io.h"
#include "io/text_file.h"

namespace gdr::io {
namespace {

template <std::size_t N>
void check_corners(const char* what, const std::vector<std::array<int, N>>& elements,
                   std::size_t points) {
  for (std::size_t i = 0; i < elements.size(); ++i)
    for (int v : elements[i])
      if (v < 0 || static_cast<std::size_t>(v) >= points)
        throw Error(Status::InvalidInput, std::string(what) + " " + std::to_string(i) +
                                              " refers to vertex " + std::to_string(v) + " of " +
                                              std::to_string(points));
}

// "Keyword\ncount\n" then one row per element: its corners (1-based, in `order`) and its
// reference.
template <std::size_t N, class Ref>
void append_section(std::string& out, const char* keyword,
                    const std::vector<std::array<int, N>>& elements,
                    const std::array<int, N>& order, const Ref& ref) {
  out += keyword;
  out += '\n';
  append_number(out, static_cast<long long>(elements.size()));
  out += '\n';
  append_rows(out, elements.size(), [&](std::string& text, std::size_t i) {
    for (int k : order) {
      append_number(text, static_cast<long long>(elements[i][k]) + 1);
      text += ' ';
    }
    append_number(text, static_cast<long long>(ref(i)));
    text += '\n';
  });
  out += '\n';
}

}  // namespace

void write_medit(const std::string& path, const TetMesh& mesh) {
  const std::size_t np = mesh.points.size();
  check_corners("tetrahedron", mesh.tets, np);
  check_corners("subface", mesh.subfaces, np);
  std::string out = "MeshVersionFormatted 2\n\nDimension 3\n\nVertices\n";
  out.reserve(40 * np + 30 * mesh.tets.size() + 24 * mesh.subfaces.size() + 128);
  append_number(out, static_cast<long long>(np));
  out += '\n';
  append_rows(out, np, [&](std::string& text, std::size_t i) {
    const Point3& p = mesh.points[i];
    for (double c : {p.x, p.y, p.z}) {
      append_number(text, c);
      text += ' ';
    }
    const int type = i < mesh.point_type.size() ? static_cast<int>(mesh.point_type[i]) : 0;
    append_number(text, static_cast<long long>(type));
    text += '\n';
  });
  out += '\n';
  // Medit's tetrahedra have a positive volume, (b-a) x (c-a) . (d-a) > 0, as TetGen's:
  // two corners of ours (orient3d > 0, gdr/validate.h) are swapped.
  const bool regions = mesh.tet_region.size() == mesh.tets.size();
  append_section(out, "Tetrahedra", mesh.tets, {1, 0, 2, 3},
                 [&](std::size_t t) { return regions ? mesh.tet_region[t] : 1; });
  // Facet ids + 1: Medit keeps reference 0 for "none" (no known facet).
  const bool facets = mesh.subface_facet.size() == mesh.subfaces.size();
  append_section(out, "Triangles", mesh.subfaces, {0, 1, 2},
                 [&](std::size_t s) { return facets ? mesh.subface_facet[s] + 1 : 0; });
  out += "End\n";
  write_file_atomically(path, out);
}

}  // namespace gdr::io
