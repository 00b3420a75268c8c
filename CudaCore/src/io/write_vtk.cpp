// VTK XML writers (.vtu, .vtp) with inline base64 binary arrays (uncompressed, UInt64
// headers), written by the core so that builds without VTK still produce viewable results.
#include <cstdint>
#include <cstring>

#include "gdr/error.h"
#include "gdr/io.h"
#include "io/text_file.h"

namespace gdr::io {
namespace {

constexpr std::uint8_t kVtkTriangle = 5;
constexpr std::uint8_t kVtkTetra = 10;

// Appends the base64 text of `n` bytes (padded with '='). Large arrays are encoded in
// parallel: a 30M-tetrahedron mesh carries about 3 GB of it.
void append_base64(std::string& out, const unsigned char* src, std::size_t n) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const std::size_t start = out.size();
  out.resize(start + 4 * ((n + 2) / 3));
  char* dst = out.data() + start;
  const long long groups = static_cast<long long>(n / 3);
#pragma omp parallel for schedule(static) if (groups > (1 << 16))
  for (long long g = 0; g < groups; ++g) {
    const unsigned char* s = src + 3 * g;
    const unsigned v = (unsigned{s[0]} << 16) | (unsigned{s[1]} << 8) | s[2];
    char* d = dst + 4 * g;
    d[0] = table[v >> 18];
    d[1] = table[(v >> 12) & 63];
    d[2] = table[(v >> 6) & 63];
    d[3] = table[v & 63];
  }
  const std::size_t rest = n % 3;
  if (rest == 0) return;
  const unsigned char* s = src + 3 * groups;
  const unsigned v = (unsigned{s[0]} << 16) | (rest == 2 ? unsigned{s[1]} << 8 : 0u);
  char* d = dst + 4 * groups;
  d[0] = table[v >> 18];
  d[1] = table[(v >> 12) & 63];
  d[2] = rest == 2 ? table[(v >> 6) & 63] : '=';
  d[3] = '=';
}

std::string xml_escape(const std::string& s) {
  std::string r;
  for (char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      default: r += c;
    }
  }
  return r;
}

template <class T>
void append_array(std::string& out, const char* type, const std::string& name, int components,
                  const std::vector<T>& values) {
  out += "        <DataArray type=\"";
  out += type;
  out += "\"";
  if (!name.empty()) out += " Name=\"" + xml_escape(name) + "\"";
  out += " NumberOfComponents=\"" + std::to_string(components) + "\" format=\"binary\">\n";
  // One base64 stream: the UInt64 byte count, then the values. The 8-byte header and the
  // first data byte make three whole groups, so the rest is encoded straight from `values`.
  const std::uint64_t bytes = values.size() * sizeof(T);
  const auto* data = reinterpret_cast<const unsigned char*>(values.data());
  const std::size_t first = bytes > 0 ? 1 : 0;
  unsigned char head[sizeof bytes + 1];
  std::memcpy(head, &bytes, sizeof bytes);
  if (first) head[sizeof bytes] = data[0];
  append_base64(out, head, sizeof bytes + first);
  append_base64(out, data + first, bytes - first);
  out += "\n        </DataArray>\n";
}

void append_array(std::string& out, const DataArray& a) {
  if (!a.float32) return append_array(out, "Float64", a.name, a.components, a.values);
  append_array(out, "Float32", a.name, a.components,
               std::vector<float>(a.values.begin(), a.values.end()));
}

void check_arrays(const std::vector<DataArray>& arrays, std::size_t count, const char* where) {
  for (const DataArray& a : arrays) {
    if (a.components < 1 || a.values.size() != static_cast<std::size_t>(a.components) * count)
      throw Error(Status::InvalidInput,
                  std::string(where) + " array '" + a.name + "' has " +
                      std::to_string(a.values.size()) + " values for " + std::to_string(count) +
                      " elements of " + std::to_string(a.components) + " components");
  }
}

// Everything a VTK XML piece needs, gathered from either mesh type.
struct Piece {
  std::vector<double> points;  // xyz
  std::vector<std::int32_t> connectivity;  // vertex indices are ints
  std::vector<std::int64_t> offsets;
  std::uint8_t cell_type = 0;
  int corners = 0;
  const std::vector<PointType>* point_type = nullptr;
  const std::vector<int>* region = nullptr;  // per cell, written as "Region" when not empty
};

// Cells with their corners taken in `order` (VTK's orientation may differ from ours).
template <std::size_t N>
void fill_cells(Piece& piece, const std::vector<std::array<int, N>>& cells,
                const std::array<int, N>& order) {
  piece.corners = static_cast<int>(N);
  piece.connectivity.reserve(cells.size() * N);
  piece.offsets.reserve(cells.size());
  for (const auto& c : cells) {
    for (int k : order) piece.connectivity.push_back(c[k]);
    piece.offsets.push_back(static_cast<std::int64_t>(piece.connectivity.size()));
  }
}

// `mesh_arrays`: arrays the mesh itself carries, written after the caller's `attributes`.
std::string vtk_file(const Piece& piece, const Attributes& attributes, bool polydata,
                     const Attributes& mesh_arrays = {}) {
  const std::size_t np = piece.points.size() / 3, nc = piece.offsets.size();
  for (const Attributes* a : {&attributes, &mesh_arrays}) {
    check_arrays(a->point_data, np, "point");
    check_arrays(a->cell_data, nc, "cell");
  }
  if (piece.point_type && !piece.point_type->empty() && piece.point_type->size() != np)
    throw Error(Status::InvalidInput, "point_type has " + std::to_string(piece.point_type->size()) +
                                          " entries for " + std::to_string(np) + " points");
  const bool region = piece.region && !piece.region->empty();
  if (region && piece.region->size() != nc)
    throw Error(Status::InvalidInput, "tet_region has " + std::to_string(piece.region->size()) +
                                          " entries for " + std::to_string(nc) + " cells");
  const char* type = polydata ? "PolyData" : "UnstructuredGrid";
  std::string out;
  // Base64 takes 4 characters per 3 bytes; XML tags take a few hundred in all.
  std::size_t bytes = 8 * piece.points.size() + np + 4 * piece.connectivity.size() + 13 * nc;
  for (const auto* arrays : {&attributes.point_data, &attributes.cell_data,
                             &mesh_arrays.point_data, &mesh_arrays.cell_data})
    for (const DataArray& a : *arrays) bytes += (a.float32 ? 4 : 8) * a.values.size();
  out.reserve(bytes / 3 * 4 + 4096);
  out += "<?xml version=\"1.0\"?>\n<VTKFile type=\"";
  out += type;
  out += "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <";
  out += type;
  out += ">\n    <Piece NumberOfPoints=\"" + std::to_string(np) + "\" ";
  out += polydata ? "NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\""
                  : "NumberOfCells=\"";
  out += std::to_string(nc) + "\">\n      <PointData>\n";
  for (const DataArray& a : attributes.point_data) append_array(out, a);
  for (const DataArray& a : mesh_arrays.point_data) append_array(out, a);
  if (piece.point_type && !piece.point_type->empty()) {
    std::vector<std::uint8_t> pt(np);
    std::memcpy(pt.data(), piece.point_type->data(), np);
    append_array(out, "UInt8", "PointType", 1, pt);
  }
  out += "      </PointData>\n      <CellData>\n";
  for (const DataArray& a : attributes.cell_data) append_array(out, a);
  for (const DataArray& a : mesh_arrays.cell_data) append_array(out, a);
  if (region) append_array(out, "Int32", "Region", 1, *piece.region);
  out += "      </CellData>\n      <Points>\n";
  append_array(out, "Float64", "Points", 3, piece.points);
  out += "      </Points>\n      <";
  out += polydata ? "Polys" : "Cells";
  out += ">\n";
  append_array(out, "Int32", "connectivity", 1, piece.connectivity);
  append_array(out, "Int64", "offsets", 1, piece.offsets);
  if (!polydata) append_array(out, "UInt8", "types", 1, std::vector<std::uint8_t>(nc, piece.cell_type));
  out += "      </";
  out += polydata ? "Polys" : "Cells";
  out += ">\n    </Piece>\n  </";
  out += type;
  out += ">\n</VTKFile>\n";
  return out;
}

Piece tri_piece(const TriMesh& mesh) {
  Piece piece;
  piece.points.reserve(3 * mesh.points.size());
  for (const Point2& p : mesh.points) piece.points.insert(piece.points.end(), {p.x, p.y, 0.0});
  fill_cells(piece, mesh.triangles, {0, 1, 2});
  piece.cell_type = kVtkTriangle;
  piece.point_type = &mesh.point_type;
  return piece;
}

// What a TriMesh carries from Triangle's input (gdr/pslg.h), as VTK arrays: the cell array
// Region, the point arrays BoundaryMarker and PointAttributes (one component per attribute).
Attributes tri_mesh_arrays(const TriMesh& m) {
  Attributes a;
  const std::size_t np = m.points.size();
  if (!m.triangle_region.empty())
    a.cell_data.push_back({"Region", 1, m.triangle_region});
  if (m.point_markers.size() == np && np > 0)
    a.point_data.push_back({"BoundaryMarker", 1, std::vector<double>(m.point_markers.begin(), m.point_markers.end())});
  if (m.point_attribute_count > 0 && m.point_attributes.size() == np * m.point_attribute_count)
    a.point_data.push_back({"PointAttributes", m.point_attribute_count, m.point_attributes});
  return a;
}

// Legacy VTK binary data is big-endian.
template <class T>
void append_big_endian(std::string& out, const T* values, std::size_t n) {
  const std::size_t at = out.size();
  out.resize(at + n * sizeof(T));
  char* dst = &out[at];
  for (std::size_t i = 0; i < n; ++i) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &values[i], sizeof(T));
    for (std::size_t b = 0; b < sizeof(T); ++b) dst[i * sizeof(T) + b] = bytes[sizeof(T) - 1 - b];
  }
  out += '\n';
}

// Arrays of one kind (POINT_DATA or CELL_DATA) as one legacy FIELD (any number of
// components, doubles).
void append_legacy_field(std::string& out, const char* kind, std::size_t count,
                         const std::vector<const DataArray*>& arrays) {
  if (arrays.empty()) return;
  out += std::string(kind) + " " + std::to_string(count) + "\nFIELD FieldData " +
         std::to_string(arrays.size()) + "\n";
  for (const DataArray* a : arrays) {
    out += a->name + " " + std::to_string(a->components) + " " + std::to_string(count) + " double\n";
    append_big_endian(out, a->values.data(), a->values.size());
  }
}

}  // namespace

void write_vtk_legacy(const std::string& path, const TriMesh& mesh, const Attributes& attributes) {
  const std::size_t np = mesh.points.size(), nt = mesh.triangles.size();
  const Attributes own = tri_mesh_arrays(mesh);
  DataArray type{"PointType", 1, std::vector<double>(mesh.point_type.size())};
  for (std::size_t i = 0; i < mesh.point_type.size(); ++i)
    type.values[i] = static_cast<double>(mesh.point_type[i]);
  std::vector<const DataArray*> point_arrays, cell_arrays;
  for (const Attributes* a : {&attributes, &own}) {
    check_arrays(a->point_data, np, "point");
    check_arrays(a->cell_data, nt, "cell");
    for (const DataArray& d : a->point_data) point_arrays.push_back(&d);
    for (const DataArray& d : a->cell_data) cell_arrays.push_back(&d);
  }
  if (type.values.size() == np && np > 0) point_arrays.push_back(&type);
  std::string out = "# vtk DataFile Version 4.2\ngdr triangle mesh\nBINARY\nDATASET POLYDATA\nPOINTS " +
                    std::to_string(np) + " double\n";
  std::vector<double> xyz;
  xyz.reserve(3 * np);
  for (const Point2& p : mesh.points) xyz.insert(xyz.end(), {p.x, p.y, 0.0});
  append_big_endian(out, xyz.data(), xyz.size());
  out += "POLYGONS " + std::to_string(nt) + " " + std::to_string(4 * nt) + "\n";
  std::vector<std::int32_t> cells;
  cells.reserve(4 * nt);
  for (const auto& t : mesh.triangles) cells.insert(cells.end(), {3, t[0], t[1], t[2]});
  append_big_endian(out, cells.data(), cells.size());
  append_legacy_field(out, "CELL_DATA", nt, cell_arrays);
  append_legacy_field(out, "POINT_DATA", np, point_arrays);
  write_file_atomically(path, out);
}

void write_vtu(const std::string& path, const TriMesh& mesh, const Attributes& attributes) {
  write_file_atomically(path, vtk_file(tri_piece(mesh), attributes, false, tri_mesh_arrays(mesh)));
}

void write_vtp(const std::string& path, const TriMesh& mesh, const Attributes& attributes) {
  write_file_atomically(path, vtk_file(tri_piece(mesh), attributes, true, tri_mesh_arrays(mesh)));
}

void write_vtu(const std::string& path, const TetMesh& mesh, const Attributes& attributes) {
  Piece piece;
  piece.points.reserve(3 * mesh.points.size());
  for (const Point3& p : mesh.points) piece.points.insert(piece.points.end(), {p.x, p.y, p.z});
  // VTK's tetrahedra have (p1 - p0) x (p2 - p0) pointing towards p3, the opposite of ours
  // (orient3d > 0, gdr/validate.h): swap two corners, as write_tetgen does.
  fill_cells(piece, mesh.tets, {1, 0, 2, 3});
  piece.cell_type = kVtkTetra;
  piece.point_type = &mesh.point_type;
  piece.region = &mesh.tet_region;
  write_file_atomically(path, vtk_file(piece, attributes, false));
}

void write_surface_vtp(const std::string& path, const TetMesh& mesh, const Attributes& attributes) {
  Piece piece;
  piece.points.reserve(3 * mesh.points.size());
  for (const Point3& p : mesh.points) piece.points.insert(piece.points.end(), {p.x, p.y, p.z});
  fill_cells(piece, mesh.subfaces, {0, 1, 2});
  piece.cell_type = kVtkTriangle;
  piece.point_type = &mesh.point_type;
  write_file_atomically(path, vtk_file(piece, attributes, true));
}

}  // namespace gdr::io
