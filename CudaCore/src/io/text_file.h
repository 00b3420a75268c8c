// Line-oriented tokenizer for the text mesh formats. Every error names the file and line,
// so a malformed input is reported as "PATH:LINE: reason" and never reaches the mesher.
#pragma once
#include <algorithm>
#include <array>
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "gdr/pslg.h"

namespace gdr::io {

using Tokens = std::vector<std::string_view>;

class TextFile {
 public:
  explicit TextFile(const std::string& path);
  TextFile(const std::string& path, std::string data) : path_(path), data_(std::move(data)) {}

  const std::string& path() const { return path_; }
  std::size_t size() const { return data_.size(); }
  const std::string& data() const { return data_; }
  int line() const { return line_; }

  // Next non-blank line with '#' comments removed, split on white space; false at the end.
  bool next(Tokens& tokens);
  // next(), but a missing line or a line with fewer than `min_tokens` tokens is an error.
  void expect(Tokens& tokens, std::size_t min_tokens, const std::string& what);

  [[noreturn]] void fail(const std::string& reason) const;
  long long integer(std::string_view token, const std::string& what) const;
  double real(std::string_view token, const std::string& what) const;
  // A count read from a header: non-negative and small enough that `count` records of at
  // least `min_tokens` tokens each fit in the file, so a corrupt header cannot make us
  // allocate absurd sizes.
  std::size_t count(std::string_view token, std::size_t min_tokens, const std::string& what) const;

 private:
  std::string path_;
  std::string data_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

// A node section (Triangle / TetGen .node, or the first part of a .poly) after its header
// line `header` = "<count> <dimension> [<attributes> [<markers>]]", with its attributes and
// boundary markers; the first index (0 or 1) sets the numbering of the whole file.
struct NodeList {
  int dimension = 0;
  int first_index = 0;
  std::vector<double> coords;  // dimension values per point
  int attribute_count = 0;
  std::vector<double> attributes;  // attribute_count values per point
  std::vector<int> markers;        // per point, when the header says there are markers
  std::size_t size() const { return dimension ? coords.size() / dimension : 0; }
};
NodeList read_node_section(TextFile& file, const Tokens& header, int dimension);
NodeList read_node_file(const std::string& path, int dimension);

// The point part of a .poly (2D Triangle or 3D TetGen): inline, or from the .node beside
// the file when its point count is 0.
NodeList read_poly_point_section(TextFile& file, int dimension);

// A vertex reference of an element or segment, converted to 0-based and range checked.
int vertex_index(const TextFile& file, std::string_view token, int first_index,
                 std::size_t count, const std::string& what);
inline int vertex_index(const TextFile& file, std::string_view token, const NodeList& nodes,
                        const std::string& what) {
  return vertex_index(file, token, nodes.first_index, nodes.size(), what);
}

// write_file_atomically (gdr/io.h) of a file made of pieces, in order.
void write_file_atomically(const std::string& path, const std::vector<std::string_view>& parts);

// Reads a whole file into memory; IoError if it cannot be opened or read.
std::string read_file_bytes(const std::string& path);

// Lower-case extension with its dot ("" if none).
std::string extension_of(const std::string& path);
// Path without its extension.
std::string strip_extension(const std::string& path);
bool file_exists(const std::string& path);
// Shortest decimal text that reads back to the same double.
void append_number(std::string& out, double v);
void append_number(std::string& out, long long v);

// Appends rows 0..n-1 of a text file, each formatted by row(text, i) (which must not
// throw). Blocks of rows are formatted in parallel: number formatting is most of the time
// a large mesh takes to write.
template <class Row>
void append_rows(std::string& out, std::size_t n, const Row& row) {
  constexpr std::size_t kBlock = 1 << 15;
  const long long blocks = static_cast<long long>((n + kBlock - 1) / kBlock);
  std::vector<std::string> text(blocks);
#pragma omp parallel for schedule(dynamic) if (blocks > 1)
  for (long long b = 0; b < blocks; ++b) {
    const std::size_t begin = static_cast<std::size_t>(b) * kBlock;
    const std::size_t end = std::min(n, begin + kBlock);
    for (std::size_t i = begin; i < end; ++i) row(text[b], i);
  }
  for (const std::string& t : text) out += t;
}

// Triangulates a simple polygon given by vertex indices into `points` (3D, any plane) by ear
// clipping in the polygon's plane; appends triangles with the polygon's orientation.
// Returns false when the polygon is degenerate or not simple enough to clip.
bool triangulate_polygon(const std::vector<Point3>& points, const std::vector<int>& polygon,
                         std::vector<std::array<int, 3>>& triangles);

}  // namespace gdr::io
