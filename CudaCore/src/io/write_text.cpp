// Triangle (.node/.ele/.poly) and TetGen (.node/.ele/.face) writers, write_mesh, and the
// atomic file writing they all share.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <type_traits>

#include "gdr/error.h"
#include "gdr/io.h"
#include "io/text_file.h"

namespace gdr::io {
namespace {

// Files written as one set: each goes to a new temporary file beside its destination (the
// same folder, so that the rename stays on one file system), flushed to disk; commit()
// renames them all into place. Until then the destinations are untouched; the destructor
// removes temporaries that were not committed (an error, an exception).
class OutputFiles {
 public:
  OutputFiles() = default;
  OutputFiles(const OutputFiles&) = delete;
  OutputFiles& operator=(const OutputFiles&) = delete;
  ~OutputFiles() {
    for (const File& f : pending_)
      if (!f.temporary.empty()) ::unlink(f.temporary.c_str());
  }

  void write(const std::string& path, const std::string& bytes) { write(path, {std::string_view(bytes)}); }

  // One file from several pieces, in order (a large file need not be joined in memory first).
  void write(const std::string& path, const std::vector<std::string_view>& parts) {
    File f{temporary_name(path), path};
    // Exclusive creation: a temporary never replaces a file of the user's.
    int fd = -1;
    for (int attempt = 0; fd < 0; ++attempt) {
      fd = ::open(f.temporary.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
      if (fd >= 0) break;
      if (errno != EEXIST || attempt == 100) fail(path, "cannot open a new file in its folder");
      f.temporary = temporary_name(path);
    }
    pending_.push_back(f);
    for (const std::string_view bytes : parts) {
      const char* p = bytes.data();
      std::size_t left = bytes.size();
      while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
          const int e = errno;
          ::close(fd);
          errno = e;
          fail(path, "write failed");
        }
        p += n;
        left -= static_cast<std::size_t>(n);
      }
    }
    if (::fsync(fd) != 0) {
      const int e = errno;
      ::close(fd);
      errno = e;
      fail(path, "write failed");
    }
    if (::close(fd) != 0) fail(path, "write failed");
  }

  void commit() {
    // A folder in the way is what makes a rename fail in practice: look before moving any.
    for (const File& f : pending_)
      if (std::filesystem::is_directory(f.path))
        throw Error(Status::IoError, f.path + ": is a folder");
    for (File& f : pending_) {
      if (std::rename(f.temporary.c_str(), f.path.c_str()) != 0)
        fail(f.path, "cannot move the written file into place");
      f.temporary.clear();  // moved: nothing left to remove
    }
    pending_.clear();
  }

 private:
  struct File {
    std::string temporary, path;
  };

  // A hidden name beside `path`, unique to this process and call.
  static std::string temporary_name(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    const std::filesystem::path p(path);
    const std::string name = "." + p.filename().string() + "." + std::to_string(::getpid()) +
                             "-" + std::to_string(counter++) + ".tmp";
    return (p.parent_path() / name).string();
  }

  [[noreturn]] static void fail(const std::string& path, const char* what) {
    throw Error(Status::IoError, path + ": " + what + ": " + std::strerror(errno));
  }

  std::vector<File> pending_;
};

// Rows "index v0 v1 ... [marker]", elements and vertices numbered from `first`; the marker
// (an int marker or a double attribute) -1 where `markers` is short.
template <std::size_t N, class A, class Marker = int, class B = std::allocator<Marker>>
void append_elements(std::string& out, const std::vector<std::array<int, N>, A>& elements,
                     const std::vector<Marker, B>* markers, int first = 0) {
  append_rows(out, elements.size(), [&](std::string& text, std::size_t i) {
    append_number(text, static_cast<long long>(i) + first);
    for (int v : elements[i]) {
      text += ' ';
      append_number(text, static_cast<long long>(v) + first);
    }
    if (markers) {
      text += ' ';
      if constexpr (std::is_same_v<Marker, double>)
        append_number(text, i < markers->size() ? (*markers)[i] : -1.0);
      else
        append_number(text, static_cast<long long>(i < markers->size() ? (*markers)[i] : -1));
    }
    text += '\n';
  });
}

template <class P>
void check_indices(const char* what, std::size_t points, const P& elements) {
  for (const auto& e : elements)
    for (int v : e)
      if (v < 0 || static_cast<std::size_t>(v) >= points)
        throw Error(Status::InvalidInput, std::string(what) + " refers to vertex " +
                                              std::to_string(v) + " of " + std::to_string(points));
}

// TetGen files are 0-based, as TetGen accepts; Triangle files count from the mesh's
// first_index, with its point attributes and boundary markers.
std::string node_file_2d(const TriMesh& m) {
  const std::size_t n = m.points.size();
  const int na = m.point_attributes.size() == n * m.point_attribute_count ? m.point_attribute_count : 0;
  const bool markers = !m.point_markers.empty() && m.point_markers.size() == n;
  std::string out = std::to_string(n) + " 2 " + std::to_string(na) + (markers ? " 1\n" : " 0\n");
  append_rows(out, n, [&](std::string& text, std::size_t i) {
    append_number(text, static_cast<long long>(i) + m.first_index);
    text += ' ';
    append_number(text, m.points[i].x);
    text += ' ';
    append_number(text, m.points[i].y);
    for (int k = 0; k < na; ++k) {
      text += ' ';
      append_number(text, m.point_attributes[i * na + k]);
    }
    if (markers) {
      text += ' ';
      append_number(text, static_cast<long long>(m.point_markers[i]));
    }
    text += '\n';
  });
  return out;
}

std::string node_file_3d(const std::vector<Point3>& points) {
  std::string out = std::to_string(points.size()) + " 3 0 0\n";
  append_rows(out, points.size(), [&](std::string& text, std::size_t i) {
    append_number(text, static_cast<long long>(i));
    for (double c : {points[i].x, points[i].y, points[i].z}) {
      text += ' ';
      append_number(text, c);
    }
    text += '\n';
  });
  return out;
}

}  // namespace

void write_file_atomically(const std::string& path, const std::string& bytes) {
  OutputFiles files;
  files.write(path, bytes);
  files.commit();
}

void write_file_atomically(const std::string& path, const std::vector<std::string_view>& parts) {
  OutputFiles files;
  files.write(path, parts);
  files.commit();
}

std::vector<std::string> trimesh_output_files(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".node" && ext != ".ele") return {path};
  const std::string base = strip_extension(path);
  return {base + ".node", base + ".ele", base + ".poly"};
}

void write_triangle(const std::string& base, const TriMesh& mesh) {
  check_indices("a triangle", mesh.points.size(), mesh.triangles);
  check_indices("a subsegment", mesh.points.size(), mesh.subsegments);
  OutputFiles files;
  const int first = mesh.first_index;
  files.write(base + ".node", node_file_2d(mesh));
  // The regional attribute as the triangles' one attribute, as Triangle's -A writes it.
  const bool region = !mesh.triangles.empty() && mesh.triangle_region.size() == mesh.triangles.size();
  std::string ele = std::to_string(mesh.triangles.size()) + (region ? " 3 1\n" : " 3 0\n");
  append_elements(ele, mesh.triangles, region ? &mesh.triangle_region : nullptr, first);
  files.write(base + ".ele", ele);
  // Subsegments as a point-less .poly with their boundary markers, as Triangle writes them.
  const bool markers = !mesh.subsegments.empty() && mesh.subsegment_markers.size() == mesh.subsegments.size();
  std::string poly = "0 2 0 0\n" + std::to_string(mesh.subsegments.size()) + (markers ? " 1\n" : " 0\n");
  append_elements(poly, mesh.subsegments, markers ? &mesh.subsegment_markers : nullptr, first);
  poly += "0\n";
  files.write(base + ".poly", poly);
  files.commit();
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
  OutputFiles files;
  files.write(base + ".node", node_file_3d(mesh.points));
  files.write(base + ".ele", ele);
  files.write(base + ".face", face);
  files.commit();
}

void write_mesh(const std::string& path, const TriMesh& mesh, const Attributes& attributes) {
  const std::string ext = extension_of(path);
  if (ext == ".vtu") return write_vtu(path, mesh, attributes);
  if (ext == ".vtp") return write_vtp(path, mesh, attributes);
  if (ext == ".vtk") return write_vtk_legacy(path, mesh, attributes);
  if (ext == ".node" || ext == ".ele") return write_triangle(strip_extension(path), mesh);
  throw Error(Status::IoError, path + ": unsupported output format '" + ext +
                                   "' for a triangle mesh (expected .vtu, .vtp, .vtk, .node or .ele)");
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
