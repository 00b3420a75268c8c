// PLY surfaces: ASCII and binary (little or big endian). Vertex x, y, z of any numeric type;
// the face list "vertex_indices" (or "vertex_index") with any integer count and index types;
// other elements and properties are skipped.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "gdr/error.h"
#include "gdr/io.h"
#include "io/face_collector.h"
#include "io/text_file.h"

namespace gdr::io {
namespace {

enum class Type { I8, U8, I16, U16, I32, U32, F32, F64 };

int type_size(Type t) {
  switch (t) {
    case Type::I8: case Type::U8: return 1;
    case Type::I16: case Type::U16: return 2;
    case Type::I32: case Type::U32: case Type::F32: return 4;
    default: return 8;
  }
}

bool is_integer(Type t) { return t != Type::F32 && t != Type::F64; }

bool parse_type(std::string_view name, Type& t) {
  static const struct { const char* name; Type type; } names[] = {
      {"char", Type::I8},     {"int8", Type::I8},     {"uchar", Type::U8},   {"uint8", Type::U8},
      {"short", Type::I16},   {"int16", Type::I16},   {"ushort", Type::U16}, {"uint16", Type::U16},
      {"int", Type::I32},     {"int32", Type::I32},   {"uint", Type::U32},   {"uint32", Type::U32},
      {"float", Type::F32},   {"float32", Type::F32}, {"double", Type::F64}, {"float64", Type::F64}};
  for (const auto& n : names)
    if (name == n.name) {
      t = n.type;
      return true;
    }
  return false;
}

struct Property {
  std::string name;
  bool list = false;
  Type count = Type::U8;  // list length type
  Type value = Type::F32;
};

struct Element {
  std::string name;
  std::size_t count = 0;
  std::vector<Property> properties;
  int line = 0;  // of its header line
};

// Binary values at `pos` in `data`, bounds checked by the caller's reader.
class BinaryReader {
 public:
  BinaryReader(const std::string& path, const std::string& data, std::size_t pos, bool big_endian)
      : path_(path), data_(data), pos_(pos), swap_(big_endian) {}

  double read(Type t, const std::string& what) {
    const int n = type_size(t);
    if (pos_ + n > data_.size())
      throw Error(Status::IoError, path_ + ": the binary data ends inside " + what);
    unsigned char b[8];
    std::memcpy(b, data_.data() + pos_, n);
    pos_ += n;
    if (swap_)
      for (int i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
    switch (t) {
      case Type::I8: { std::int8_t v; std::memcpy(&v, b, 1); return v; }
      case Type::U8: return b[0];
      case Type::I16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
      case Type::U16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
      case Type::I32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
      case Type::U32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
      case Type::F32: { float v; std::memcpy(&v, b, 4); return v; }
      default: { double v; std::memcpy(&v, b, 8); return v; }
    }
  }
  std::size_t remaining() const { return data_.size() - pos_; }

 private:
  const std::string& path_;
  const std::string& data_;
  std::size_t pos_;
  bool swap_;
};

}  // namespace

Surface read_ply(const std::string& path) {
  TextFile file(path);
  Tokens t;
  file.expect(t, 1, "the 'ply' header");
  if (t[0] != "ply") file.fail("expected 'ply', found '" + std::string(t[0]) + "'");
  enum { Ascii, Little, Big } format = Ascii;
  bool have_format = false;
  std::vector<Element> elements;
  for (;;) {
    file.expect(t, 1, "'end_header'");
    if (t[0] == "end_header") break;
    if (t[0] == "comment" || t[0] == "obj_info") continue;
    if (t[0] == "format") {
      if (t.size() < 2) file.fail("format without a name");
      if (t[1] == "ascii") format = Ascii;
      else if (t[1] == "binary_little_endian") format = Little;
      else if (t[1] == "binary_big_endian") format = Big;
      else file.fail("unknown format '" + std::string(t[1]) + "'");
      have_format = true;
    } else if (t[0] == "element") {
      if (t.size() < 3) file.fail("expected 'element NAME COUNT'");
      Element e;
      e.name = std::string(t[1]);
      const long long n = file.integer(t[2], "count of element " + e.name);
      if (n < 0) file.fail("negative count of element " + e.name);
      e.count = static_cast<std::size_t>(n);
      e.line = file.line();
      elements.push_back(e);
    } else if (t[0] == "property") {
      if (elements.empty()) file.fail("property before any element");
      Property p;
      if (t.size() >= 5 && t[1] == "list") {
        p.list = true;
        if (!parse_type(t[2], p.count) || !is_integer(p.count)) file.fail("bad list count type '" + std::string(t[2]) + "'");
        if (!parse_type(t[3], p.value)) file.fail("unknown type '" + std::string(t[3]) + "'");
        p.name = std::string(t[4]);
      } else if (t.size() >= 3) {
        if (!parse_type(t[1], p.value)) file.fail("unknown type '" + std::string(t[1]) + "'");
        p.name = std::string(t[2]);
      } else {
        file.fail("expected 'property TYPE NAME' or 'property list COUNT_TYPE TYPE NAME'");
      }
      elements.back().properties.push_back(p);
    } else {
      file.fail("unexpected header line '" + std::string(t[0]) + "'");
    }
  }
  if (!have_format) file.fail("the header has no format line");

  // Where the vertex coordinates and the face corners are.
  const Element* vertex = nullptr;
  const Element* face = nullptr;
  int coord[3] = {-1, -1, -1}, corners = -1;
  for (const Element& e : elements) {
    if (e.name == "vertex") {
      vertex = &e;
      for (std::size_t i = 0; i < e.properties.size(); ++i)
        for (int d = 0; d < 3; ++d)
          if (!e.properties[i].list && e.properties[i].name == std::string(1, "xyz"[d])) coord[d] = static_cast<int>(i);
    } else if (e.name == "face") {
      face = &e;
      for (std::size_t i = 0; i < e.properties.size(); ++i)
        if (e.properties[i].list && (e.properties[i].name == "vertex_indices" || e.properties[i].name == "vertex_index"))
          corners = static_cast<int>(i);
    }
  }
  if (!vertex || coord[0] < 0 || coord[1] < 0 || coord[2] < 0)
    file.fail("no 'element vertex' with properties x, y and z");
  if (!face || corners < 0) file.fail("no 'element face' with a list property vertex_indices");
  if (!is_integer(face->properties[corners].value)) file.fail("face vertex indices must be integers");

  // The body, element by element: ASCII one element per line, or binary records.
  const bool ascii = format == Ascii;
  std::size_t pos = 0;
  if (!ascii) {  // the binary body starts after the line "end_header"
    const std::string& data = file.data();
    pos = data.find("end_header");
    while (pos != std::string::npos && pos > 0 && data[pos - 1] != '\n') pos = data.find("end_header", pos + 1);
    if (pos == std::string::npos) file.fail("cannot find the end of the header");
    pos = data.find('\n', pos);
    pos = pos == std::string::npos ? data.size() : pos + 1;
  }
  BinaryReader bin(path, file.data(), pos, format == Big);
  std::size_t k = 0;  // next token of the current ASCII line
  auto value = [&](Type type, const std::string& what) -> double {
    if (!ascii) return bin.read(type, what);
    if (k >= t.size()) file.fail(what + ": too few values on the line");
    return file.real(t[k++], what);
  };
  auto where = [&] { return ascii ? path + ":" + std::to_string(file.line()) : path; };

  Surface surface;
  const std::size_t nv = vertex->count;
  std::vector<int> corner, first = {0};  // face corners, flat, and where each face starts
  std::vector<int> face_line;             // ASCII: the line of each face, for messages
  for (const Element& e : elements) {
    std::size_t min_size = 0;
    for (const Property& p : e.properties) min_size += ascii ? 2 : type_size(p.list ? p.count : p.value);
    const std::size_t room = ascii ? file.size() : bin.remaining();
    if (min_size > 0 && e.count > room / min_size)
      throw Error(Status::IoError, path + ":" + std::to_string(e.line) + ": element " + e.name + " count " +
                                       std::to_string(e.count) + " is larger than the file can hold");
    if (&e == vertex) surface.points.reserve(e.count);
    for (std::size_t i = 0; i < e.count; ++i) {
      const std::string what = e.name + " " + std::to_string(i);
      if (ascii) {
        file.expect(t, 1, what);
        k = 0;
      }
      Point3 point;
      for (std::size_t p = 0; p < e.properties.size(); ++p) {
        const Property& prop = e.properties[p];
        if (!prop.list) {
          const double v = value(prop.value, prop.name + " of " + what);
          if (&e == vertex) {
            if (!std::isfinite(v)) throw Error(Status::IoError, where() + ": " + what + " has a non-finite " + prop.name);
            if (static_cast<int>(p) == coord[0]) point.x = v;
            if (static_cast<int>(p) == coord[1]) point.y = v;
            if (static_cast<int>(p) == coord[2]) point.z = v;
          }
          continue;
        }
        const double n = value(prop.count, "list length of " + what);
        if (!(n >= 0) || n != std::floor(n) || n > 1e7)
          throw Error(Status::IoError, where() + ": " + what + " has a bad list length");
        const bool is_corners = &e == face && static_cast<int>(p) == corners;
        for (long long j = 0; j < static_cast<long long>(n); ++j) {
          const double v = value(prop.value, prop.name + " of " + what);
          if (!is_corners) continue;
          if (!(v >= 0 && v < static_cast<double>(nv)) || v != std::floor(v))
            throw Error(Status::IoError, where() + ": " + what + " refers to vertex " +
                                             (v == std::floor(v) && std::fabs(v) < 1e18 ? std::to_string(static_cast<long long>(v)) : std::to_string(v)) +
                                             ", outside [0, " + std::to_string(nv) + ")");
          corner.push_back(static_cast<int>(v));
        }
        if (is_corners) {
          if (n < 3) throw Error(Status::IoError, where() + ": " + what + " has fewer than 3 corners");
          first.push_back(static_cast<int>(corner.size()));
          face_line.push_back(file.line());
        }
      }
      if (&e == vertex) surface.points.push_back(point);
    }
  }

  // Faces once all points are known (polygons are clipped in their plane).
  FaceCollector faces(surface);
  std::vector<int> c;
  for (std::size_t f = 0; f + 1 < first.size(); ++f) {
    c.assign(corner.begin() + first[f], corner.begin() + first[f + 1]);
    if (!faces.add(c, static_cast<int>(f)))
      throw Error(Status::IoError, (ascii ? path + ":" + std::to_string(face_line[f]) : path) + ": face " +
                                       std::to_string(f) + " cannot be triangulated (degenerate or not a simple planar polygon)");
  }
  faces.finish();
  return surface;
}

}  // namespace gdr::io
