// Triangle (.node/.ele/.poly) and TetGen (.node/.ele/.face) writers, and write_mesh.
#include "gdr/error.h"
#include "gdr/io.h"
#include "io/text_file.h"

namespace gdr::io {
namespace {

template <std::size_t N>
void append_elements(std::string& out, const std::vector<std::array<int, N>>& elements,
                     const std::vector<int>* markers) {
  for (std::size_t i = 0; i < elements.size(); ++i) {
    append_number(out, static_cast<long long>(i));
    for (int v : elements[i]) {
      out += ' ';
      append_number(out, static_cast<long long>(v));
    }
    if (markers) {
      out += ' ';
      append_number(out, static_cast<long long>(i < markers->size() ? (*markers)[i] : -1));
    }
    out += '\n';
  }
}

template <class P>
void check_indices(const char* what, std::size_t points, const P& elements) {
  for (const auto& e : elements)
    for (int v : e)
      if (v < 0 || static_cast<std::size_t>(v) >= points)
        throw Error(Status::InvalidInput, std::string(what) + " refers to vertex " +
                                              std::to_string(v) + " of " + std::to_string(points));
}

// Files are 0-based, as both Triangle and TetGen accept.
std::string node_file_2d(const std::vector<Point2>& points) {
  std::string out = std::to_string(points.size()) + " 2 0 0\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    append_number(out, static_cast<long long>(i));
    out += ' ';
    append_number(out, points[i].x);
    out += ' ';
    append_number(out, points[i].y);
    out += '\n';
  }
  return out;
}

std::string node_file_3d(const std::vector<Point3>& points) {
  std::string out = std::to_string(points.size()) + " 3 0 0\n";
  for (std::size_t i = 0; i < points.size(); ++i) {
    append_number(out, static_cast<long long>(i));
    for (double c : {points[i].x, points[i].y, points[i].z}) {
      out += ' ';
      append_number(out, c);
    }
    out += '\n';
  }
  return out;
}

}  // namespace

void write_triangle(const std::string& base, const TriMesh& mesh) {
  check_indices("a triangle", mesh.points.size(), mesh.triangles);
  check_indices("a subsegment", mesh.points.size(), mesh.subsegments);
  std::string ele = std::to_string(mesh.triangles.size()) + " 3 0\n";
  append_elements(ele, mesh.triangles, nullptr);
  // Subsegments as a point-less .poly; the segment marker is the source input segment.
  std::string poly = "0 2 0 0\n" + std::to_string(mesh.subsegments.size()) + " 1\n";
  append_elements(poly, mesh.subsegments, &mesh.subsegment_source);
  poly += "0\n";
  write_file_atomically(base + ".node", node_file_2d(mesh.points));
  write_file_atomically(base + ".ele", ele);
  write_file_atomically(base + ".poly", poly);
}

void write_tetgen(const std::string& base, const TetMesh& mesh) {
  check_indices("a tetrahedron", mesh.points.size(), mesh.tets);
  check_indices("a subface", mesh.points.size(), mesh.subfaces);
  // Files follow TetGen's orientation (orient3d < 0): swap two corners of ours.
  std::vector<std::array<int, 4>> tets(mesh.tets);
  for (auto& t : tets) std::swap(t[0], t[1]);
  // The region as TetGen's regional attribute, the input facet as the face's boundary marker.
  const bool regions = !tets.empty() && mesh.tet_region.size() == tets.size();
  const bool facets = !mesh.subfaces.empty() && mesh.subface_facet.size() == mesh.subfaces.size();
  std::string ele = std::to_string(tets.size()) + (regions ? " 4 1\n" : " 4 0\n");
  append_elements(ele, tets, regions ? &mesh.tet_region : nullptr);
  std::string face = std::to_string(mesh.subfaces.size()) + (facets ? " 1\n" : " 0\n");
  append_elements(face, mesh.subfaces, facets ? &mesh.subface_facet : nullptr);
  write_file_atomically(base + ".node", node_file_3d(mesh.points));
  write_file_atomically(base + ".ele", ele);
  write_file_atomically(base + ".face", face);
}

void write_mesh(const std::string& path, const TriMesh& mesh, const Attributes& attributes) {
  const std::string ext = extension_of(path);
  if (ext == ".vtu") return write_vtu(path, mesh, attributes);
  if (ext == ".vtp") return write_vtp(path, mesh, attributes);
  if (ext == ".node" || ext == ".ele") return write_triangle(strip_extension(path), mesh);
  throw Error(Status::IoError, path + ": unsupported output format '" + ext +
                                   "' for a triangle mesh (expected .vtu, .vtp, .node or .ele)");
}

std::vector<std::string> tetmesh_output_files(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".node" && ext != ".ele" && ext != ".face") return {path};
  const std::string base = strip_extension(path);
  return {base + ".node", base + ".ele", base + ".face"};
}

void write_mesh(const std::string& path, const TetMesh& mesh, const Attributes& attributes) {
  const std::string ext = extension_of(path);
  if (ext == ".vtu") return write_vtu(path, mesh, attributes);
  if (ext == ".mesh") return write_medit(path, mesh);
  if (ext == ".node" || ext == ".ele" || ext == ".face") return write_tetgen(strip_extension(path), mesh);
  throw Error(Status::IoError, path + ": unsupported output format '" + ext +
                                   "' for a tetrahedral mesh (expected .vtu, .mesh, .node, .ele or .face)");
}

}  // namespace gdr::io
