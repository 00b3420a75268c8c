#include "io/text_file.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sys/stat.h>

#include "gdr/error.h"

namespace gdr::io {

std::string read_file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(Status::IoError, path + ": cannot open file");
  in.seekg(0, std::ios::end);
  const std::streamoff size = in.tellg();
  if (size < 0) throw Error(Status::IoError, path + ": cannot read file");
  in.seekg(0, std::ios::beg);
  std::string data(static_cast<std::size_t>(size), '\0');
  if (size > 0 && !in.read(data.data(), size))
    throw Error(Status::IoError, path + ": cannot read file");
  return data;
}

std::string extension_of(const std::string& path) {
  const std::size_t slash = path.find_last_of("/\\");
  const std::size_t dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
  std::string ext = path.substr(dot);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string strip_extension(const std::string& path) {
  const std::size_t n = extension_of(path).size();
  return path.substr(0, path.size() - n);
}

bool file_exists(const std::string& path) {
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && S_ISREG(st.st_mode);
}

void append_number(std::string& out, double v) {
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void append_number(std::string& out, long long v) {
  char buf[24];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

namespace {

// A token as messages show it: bytes outside printable ASCII as \xNN, and at most 40 of them.
std::string shown(std::string_view token) {
  std::string out;
  for (std::size_t i = 0; i < token.size() && i < 40; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 32 && c < 127) {
      out += static_cast<char>(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02X", c);
      out += buf;
    }
  }
  if (token.size() > 40) out += "...";
  return out;
}

}  // namespace

// Text conventions other tools write are read as such: a UTF-8 byte order mark is skipped,
// CR-only line ends (classic Mac) are line ends. (A NUL byte in a text line: next().)
TextFile::TextFile(const std::string& path) : path_(path), data_(read_file_bytes(path)) {
  if (data_.compare(0, 3, "\xEF\xBB\xBF") == 0) data_.erase(0, 3);
  if (data_.find('\n') == std::string::npos) std::replace(data_.begin(), data_.end(), '\r', '\n');
}

bool TextFile::next(Tokens& tokens) {
  tokens.clear();
  while (pos_ < data_.size()) {
    ++line_;
    std::size_t end = data_.find('\n', pos_);
    if (end == std::string::npos) end = data_.size();
    std::string_view text(data_.data() + pos_, end - pos_);
    pos_ = end + 1;
    if (text.find('\0') != std::string_view::npos)
      fail("contains a NUL byte: not a text file (binary or damaged)");
    const std::size_t hash = text.find('#');
    if (hash != std::string_view::npos) text = text.substr(0, hash);
    std::size_t i = 0;
    while (i < text.size()) {
      while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      const std::size_t start = i;
      while (i < text.size() && !std::isspace(static_cast<unsigned char>(text[i]))) ++i;
      if (i > start) tokens.push_back(text.substr(start, i - start));
    }
    if (!tokens.empty()) return true;
  }
  return false;
}

void TextFile::expect(Tokens& tokens, std::size_t min_tokens, const std::string& what) {
  if (!next(tokens)) {
    line_ += 1;
    fail("unexpected end of file, expected " + what);
  }
  if (tokens.size() < min_tokens)
    fail("expected " + std::to_string(min_tokens) + " values for " + what + ", found " +
         std::to_string(tokens.size()));
}

void TextFile::fail(const std::string& reason) const {
  throw Error(Status::IoError, path_ + ":" + std::to_string(line_) + ": " + reason);
}

long long TextFile::integer(std::string_view token, const std::string& what) const {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  long long value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size())
    fail("bad integer '" + shown(token) + "' for " + what);
  return value;
}

double TextFile::real(std::string_view token, const std::string& what) const {
  if (!token.empty() && token.front() == '+') token.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(token.data(), token.data() + token.size(), value);
  if (ec != std::errc() || end != token.data() + token.size())
    fail("bad number '" + shown(token) + "' for " + what);
  if (!std::isfinite(value)) fail("non-finite value '" + shown(token) + "' for " + what);
  return value;
}

std::size_t TextFile::count(std::string_view token, std::size_t min_tokens,
                            const std::string& what) const {
  const long long n = integer(token, what);
  if (n < 0) fail("negative " + what + " " + std::to_string(n));
  // Each token needs at least one character and one separator.
  const std::size_t fits = data_.size() / (2 * std::max<std::size_t>(min_tokens, 1));
  if (static_cast<unsigned long long>(n) > fits)
    fail(what + " " + std::to_string(n) + " is larger than the file can hold");
  return static_cast<std::size_t>(n);
}

}  // namespace gdr::io

namespace gdr::io {

NodeList read_node_section(TextFile& file, const Tokens& header, int dimension) {
  NodeList nodes;
  const std::size_t n = file.count(header[0], 1 + dimension, "point count");
  if (header.size() >= 2) {
    const long long dim = file.integer(header[1], "dimension");
    if (dim != dimension)
      file.fail("dimension " + std::to_string(dim) + " where " + std::to_string(dimension) +
                " is expected");
  }
  nodes.dimension = dimension;
  nodes.coords.reserve(n * dimension);
  const long long attributes = header.size() >= 3 ? file.integer(header[2], "attribute count") : 0;
  if (attributes < 0 || attributes > 1000) file.fail("attribute count " + std::to_string(attributes) + " out of range [0, 1000]");
  const bool markers = header.size() >= 4 && file.integer(header[3], "boundary marker count") != 0;
  nodes.attribute_count = static_cast<int>(attributes);
  const std::size_t columns = 1 + dimension + attributes + (markers ? 1 : 0);
  Tokens t;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string what = "point " + std::to_string(i);
    file.expect(t, columns, what);
    const long long index = file.integer(t[0], "index of " + what);
    if (i == 0) {
      if (index != 0 && index != 1) file.fail("first point index must be 0 or 1, found " +
                                              std::to_string(index));
      nodes.first_index = static_cast<int>(index);
    } else if (index != nodes.first_index + static_cast<long long>(i)) {
      file.fail("point index " + std::to_string(index) + " where " +
                std::to_string(nodes.first_index + static_cast<long long>(i)) +
                " is expected (points must be numbered consecutively)");
    }
    static const char* axis[3] = {"x", "y", "z"};
    for (int d = 0; d < dimension; ++d)
      nodes.coords.push_back(file.real(t[1 + d], std::string(axis[d]) + " of " + what));
    for (long long k = 0; k < attributes; ++k)
      nodes.attributes.push_back(file.real(t[1 + dimension + k], "attribute of " + what));
    if (markers)
      nodes.markers.push_back(static_cast<int>(file.integer(t[1 + dimension + attributes], "boundary marker of " + what)));
  }
  return nodes;
}

NodeList read_node_file(const std::string& path, int dimension) {
  TextFile file(path);
  Tokens header;
  file.expect(header, 1, "the point count header");
  return read_node_section(file, header, dimension);
}

// The point part of a .poly: inline, or from the .node beside it when the count is 0.
NodeList read_poly_point_section(TextFile& file, int dimension) {
  Tokens header;
  file.expect(header, 1, "the point count header");
  if (header.size() >= 2) {
    const long long dim = file.integer(header[1], "dimension");
    if (dim != dimension)
      file.fail("dimension " + std::to_string(dim) + " where " + std::to_string(dimension) +
                " is expected" + (dim == 3 ? " (a TetGen .poly: read it as a surface)" : ""));
  }
  if (file.integer(header[0], "point count") != 0) return read_node_section(file, header, dimension);
  const std::string node_path = strip_extension(file.path()) + ".node";
  if (!file_exists(node_path))
    file.fail("the .poly has no points and there is no " + node_path + " beside it");
  return read_node_file(node_path, dimension);
}

int vertex_index(const TextFile& file, std::string_view token, int first_index,
                 std::size_t count, const std::string& what) {
  const long long v = file.integer(token, what);
  const long long first = first_index, last = first + static_cast<long long>(count);
  if (v < first || v >= last)
    file.fail("vertex index " + std::to_string(v) + " of " + what + " is out of range [" +
              std::to_string(first) + ", " + std::to_string(last - 1) + "]");
  return static_cast<int>(v - first);
}

}  // namespace gdr::io
