// VTK XML writers (.vtu, .vtp) with raw appended binary arrays (uncompressed, UInt64
// headers), written by the core so that builds without VTK still produce viewable results.
#include <cstdint>
#include <cstring>
#include <deque>
#include <string_view>
#include <type_traits>

#include "gdr/error.h"
#include "gdr/io.h"
#include "io/text_file.h"

namespace gdr::io {
namespace {

constexpr std::uint8_t kVtkTriangle = 5;
constexpr std::uint8_t kVtkTetra = 10;

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

// A file as the XML part and its raw appended data: each array is a DataArray element that
// points (offset) at its block, a UInt64 byte count followed by the values as they are in
// memory. No base64, and no copy of arrays that are already laid out as VTK wants them: the
// blocks are written straight from the caller's vectors (which must outlive the write).
class VtkXml {
 public:
  std::string xml;

  template <class T>
  void array(const char* type, const std::string& name, int components, const T* values, std::size_t n) {
    xml += "        <DataArray type=\"";
    xml += type;
    xml += "\"";
    if (!name.empty()) xml += " Name=\"" + xml_escape(name) + "\"";
    xml += " NumberOfComponents=\"" + std::to_string(components) + "\" format=\"appended\" offset=\"" +
           std::to_string(offset_) + "\"/>\n";
    const std::uint64_t& bytes = counts_.emplace_back(n * sizeof(T));
    blocks_.emplace_back(reinterpret_cast<const char*>(&bytes), sizeof bytes);
    blocks_.emplace_back(reinterpret_cast<const char*>(values), bytes);
    offset_ += sizeof bytes + bytes;
  }
  template <class T>
  void array(const char* type, const std::string& name, int components, const std::vector<T>& values) {
    array(type, name, components, values.data(), values.size());
  }
  // Values made for the file (single precision, cell types) are kept here until it is written.
  void owned_array(const char* type, const std::string& name, int components, std::vector<float> values) {
    const std::vector<float>& kept = floats_.emplace_back(std::move(values));
    array(type, name, components, kept);
  }
  void owned_array(const char* type, const std::string& name, int components, std::vector<std::uint8_t> values) {
    const std::vector<std::uint8_t>& kept = bytes_.emplace_back(std::move(values));
    array(type, name, components, kept);
  }
  void array(const DataArray& a) {
    if (!a.float32) return array("Float64", a.name, a.components, a.values);
    owned_array("Float32", a.name, a.components, std::vector<float>(a.values.begin(), a.values.end()));
  }

  void write(const std::string& path, const std::string& end_tags) {
    std::vector<std::string_view> parts{xml};
    parts.insert(parts.end(), blocks_.begin(), blocks_.end());
    parts.emplace_back(end_tags);
    write_file_atomically(path, parts);
  }

 private:
  std::deque<std::uint64_t> counts_;  // deques: the blocks point into them
  std::deque<std::vector<float>> floats_;
  std::deque<std::vector<std::uint8_t>> bytes_;
  std::vector<std::string_view> blocks_;
  std::uint64_t offset_ = 0;
};

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
  const PointType* point_type = nullptr;  // per point, point_types of them (0: none)
  std::size_t point_types = 0;
  const std::vector<int>* region = nullptr;  // per cell, written as "Region" when not empty
};

// Cells with their corners taken in `order` (VTK's orientation may differ from ours).
// Filled in parallel: a large mesh's file is mostly these arrays.
template <std::size_t N, class A>
void fill_cells(Piece& piece, const std::vector<std::array<int, N>, A>& cells,
                const std::array<int, N>& order) {
  piece.corners = static_cast<int>(N);
  const long long n = static_cast<long long>(cells.size());
  piece.connectivity.resize(N * cells.size());
  piece.offsets.resize(cells.size());
  std::int32_t* conn = piece.connectivity.data();
  std::int64_t* off = piece.offsets.data();
#pragma omp parallel for schedule(static) if (n > (1 << 16))
  for (long long c = 0; c < n; ++c) {
    for (std::size_t k = 0; k < N; ++k) conn[N * c + k] = cells[c][order[k]];
    off[c] = static_cast<std::int64_t>(N * (c + 1));
  }
}

// Points as xyz (z = 0 in 2D).
template <class P, class A>
void fill_points(Piece& piece, const std::vector<P, A>& points) {
  const long long n = static_cast<long long>(points.size());
  piece.points.resize(3 * points.size());
  double* xyz = piece.points.data();
#pragma omp parallel for schedule(static) if (n > (1 << 16))
  for (long long i = 0; i < n; ++i) {
    xyz[3 * i] = points[i].x;
    xyz[3 * i + 1] = points[i].y;
    if constexpr (std::is_same_v<P, Point3>) xyz[3 * i + 2] = points[i].z;
    else xyz[3 * i + 2] = 0.0;
  }
}

// `mesh_arrays`: arrays the mesh itself carries, written after the caller's `attributes`.
void write_vtk_xml(const std::string& path, const Piece& piece, const Attributes& attributes, bool polydata,
                     const Attributes& mesh_arrays = {}) {
  const std::size_t np = piece.points.size() / 3, nc = piece.offsets.size();
  for (const Attributes* a : {&attributes, &mesh_arrays}) {
    check_arrays(a->point_data, np, "point");
    check_arrays(a->cell_data, nc, "cell");
  }
  if (piece.point_types && piece.point_types != np)
    throw Error(Status::InvalidInput, "point_type has " + std::to_string(piece.point_types) +
                                          " entries for " + std::to_string(np) + " points");
  const bool region = piece.region && !piece.region->empty();
  if (region && piece.region->size() != nc)
    throw Error(Status::InvalidInput, "tet_region has " + std::to_string(piece.region->size()) +
                                          " entries for " + std::to_string(nc) + " cells");
  const char* type = polydata ? "PolyData" : "UnstructuredGrid";
  VtkXml f;
  f.xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"";
  f.xml += type;
  f.xml += "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <";
  f.xml += type;
  f.xml += ">\n    <Piece NumberOfPoints=\"" + std::to_string(np) + "\" ";
  f.xml += polydata ? "NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\""
                    : "NumberOfCells=\"";
  f.xml += std::to_string(nc) + "\">\n      <PointData>\n";
  for (const DataArray& a : attributes.point_data) f.array(a);
  for (const DataArray& a : mesh_arrays.point_data) f.array(a);
  if (piece.point_types)
    f.array("UInt8", "PointType", 1, reinterpret_cast<const std::uint8_t*>(piece.point_type), np);
  f.xml += "      </PointData>\n      <CellData>\n";
  for (const DataArray& a : attributes.cell_data) f.array(a);
  for (const DataArray& a : mesh_arrays.cell_data) f.array(a);
  if (region) f.array("Int32", "Region", 1, *piece.region);
  f.xml += "      </CellData>\n      <Points>\n";
  f.array("Float64", "Points", 3, piece.points);
  f.xml += "      </Points>\n      <";
  f.xml += polydata ? "Polys" : "Cells";
  f.xml += ">\n";
  f.array("Int32", "connectivity", 1, piece.connectivity);
  f.array("Int64", "offsets", 1, piece.offsets);
  if (!polydata) f.owned_array("UInt8", "types", 1, std::vector<std::uint8_t>(nc, piece.cell_type));
  f.xml += "      </";
  f.xml += polydata ? "Polys" : "Cells";
  f.xml += ">\n    </Piece>\n  </";
  f.xml += type;
  f.xml += ">\n  <AppendedData encoding=\"raw\">\n   _";
  f.write(path, "\n  </AppendedData>\n</VTKFile>\n");
}

Piece tri_piece(const TriMesh& mesh) {
  Piece piece;
  fill_points(piece, mesh.points);
  fill_cells(piece, mesh.triangles, {0, 1, 2});
  piece.cell_type = kVtkTriangle;
  piece.point_type = mesh.point_type.data();
  piece.point_types = mesh.point_type.size();
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
  write_vtk_xml(path, tri_piece(mesh), attributes, false, tri_mesh_arrays(mesh));
}

void write_vtp(const std::string& path, const TriMesh& mesh, const Attributes& attributes) {
  write_vtk_xml(path, tri_piece(mesh), attributes, true, tri_mesh_arrays(mesh));
}

void write_vtu(const std::string& path, const TetMesh& mesh, const Attributes& attributes) {
  Piece piece;
  fill_points(piece, mesh.points);
  // VTK's tetrahedra have (p1 - p0) x (p2 - p0) pointing towards p3, the opposite of ours
  // (orient3d > 0, gdr/validate.h): swap two corners, as write_tetgen does.
  fill_cells(piece, mesh.tets, {1, 0, 2, 3});
  piece.cell_type = kVtkTetra;
  piece.point_type = mesh.point_type.data();
  piece.point_types = mesh.point_type.size();
  piece.region = &mesh.tet_region;
  write_vtk_xml(path, piece, attributes, false);
}

void write_surface_vtp(const std::string& path, const TetMesh& mesh, const Attributes& attributes) {
  Piece piece;
  fill_points(piece, mesh.points);
  fill_cells(piece, mesh.subfaces, {0, 1, 2});
  piece.cell_type = kVtkTriangle;
  piece.point_type = mesh.point_type.data();
  piece.point_types = mesh.point_type.size();
  write_vtk_xml(path, piece, attributes, true);
}

}  // namespace gdr::io
