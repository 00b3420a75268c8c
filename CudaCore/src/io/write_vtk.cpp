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

class Base64 {
 public:
  explicit Base64(std::string& out) : out_(out) {}
  void add(const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) {
      group_[n_++] = p[i];
      if (n_ == 3) flush();
    }
  }
  // Pads the last group; one array is one base64 stream (header and data together).
  void finish() {
    if (n_ == 0) return;
    const std::size_t n = n_;
    for (std::size_t i = n_; i < 3; ++i) group_[i] = 0;
    n_ = 3;
    flush();
    for (std::size_t i = n + 1; i < 4; ++i) out_[out_.size() - 4 + i] = '=';
  }

 private:
  void flush() {
    static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const unsigned v = (group_[0] << 16) | (group_[1] << 8) | group_[2];
    const char chars[4] = {table[(v >> 18) & 63], table[(v >> 12) & 63], table[(v >> 6) & 63],
                           table[v & 63]};
    out_.append(chars, 4);
    n_ = 0;
  }
  std::string& out_;
  unsigned char group_[3] = {0, 0, 0};
  std::size_t n_ = 0;
};

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
  Base64 b64(out);
  const std::uint64_t bytes = values.size() * sizeof(T);
  b64.add(&bytes, sizeof bytes);
  b64.add(values.data(), bytes);
  b64.finish();
  out += "\n        </DataArray>\n";
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
  std::vector<std::int64_t> connectivity, offsets;
  std::uint8_t cell_type = 0;
  int corners = 0;
  const std::vector<PointType>* point_type = nullptr;
};

template <std::size_t N>
void fill_cells(Piece& piece, const std::vector<std::array<int, N>>& cells) {
  piece.corners = static_cast<int>(N);
  piece.connectivity.reserve(cells.size() * N);
  piece.offsets.reserve(cells.size());
  for (const auto& c : cells) {
    for (int v : c) piece.connectivity.push_back(v);
    piece.offsets.push_back(static_cast<std::int64_t>(piece.connectivity.size()));
  }
}

std::string vtk_file(const Piece& piece, const Attributes& attributes, bool polydata) {
  const std::size_t np = piece.points.size() / 3, nc = piece.offsets.size();
  check_arrays(attributes.point_data, np, "point");
  check_arrays(attributes.cell_data, nc, "cell");
  if (piece.point_type && !piece.point_type->empty() && piece.point_type->size() != np)
    throw Error(Status::InvalidInput, "point_type has " + std::to_string(piece.point_type->size()) +
                                          " entries for " + std::to_string(np) + " points");
  const char* type = polydata ? "PolyData" : "UnstructuredGrid";
  std::string out;
  out.reserve(64 * (np + nc) + 1024);
  out += "<?xml version=\"1.0\"?>\n<VTKFile type=\"";
  out += type;
  out += "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <";
  out += type;
  out += ">\n    <Piece NumberOfPoints=\"" + std::to_string(np) + "\" ";
  out += polydata ? "NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\""
                  : "NumberOfCells=\"";
  out += std::to_string(nc) + "\">\n      <PointData>\n";
  for (const DataArray& a : attributes.point_data)
    append_array(out, "Float64", a.name, a.components, a.values);
  if (piece.point_type && !piece.point_type->empty()) {
    std::vector<std::uint8_t> pt(np);
    std::memcpy(pt.data(), piece.point_type->data(), np);
    append_array(out, "UInt8", "PointType", 1, pt);
  }
  out += "      </PointData>\n      <CellData>\n";
  for (const DataArray& a : attributes.cell_data)
    append_array(out, "Float64", a.name, a.components, a.values);
  out += "      </CellData>\n      <Points>\n";
  append_array(out, "Float64", "Points", 3, piece.points);
  out += "      </Points>\n      <";
  out += polydata ? "Polys" : "Cells";
  out += ">\n";
  append_array(out, "Int64", "connectivity", 1, piece.connectivity);
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
  fill_cells(piece, mesh.triangles);
  piece.cell_type = kVtkTriangle;
  piece.point_type = &mesh.point_type;
  return piece;
}

}  // namespace

void write_vtu(const std::string& path, const TriMesh& mesh, const Attributes& attributes) {
  write_file_atomically(path, vtk_file(tri_piece(mesh), attributes, false));
}

void write_vtp(const std::string& path, const TriMesh& mesh, const Attributes& attributes) {
  write_file_atomically(path, vtk_file(tri_piece(mesh), attributes, true));
}

void write_vtu(const std::string& path, const TetMesh& mesh, const Attributes& attributes) {
  Piece piece;
  piece.points.reserve(3 * mesh.points.size());
  for (const Point3& p : mesh.points) piece.points.insert(piece.points.end(), {p.x, p.y, p.z});
  fill_cells(piece, mesh.tets);
  piece.cell_type = kVtkTetra;
  piece.point_type = &mesh.point_type;
  write_file_atomically(path, vtk_file(piece, attributes, false));
}

}  // namespace gdr::io
