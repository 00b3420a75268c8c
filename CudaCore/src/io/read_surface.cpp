// 3D surface readers: TetGen .poly / .smesh / .node / .ele / .face, OFF and STL (PLY and
// OBJ in read_ply.cpp and read_obj.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <unordered_map>

#include "gdr/error.h"
#include "gdr/io.h"
#include "io/face_collector.h"
#include "io/text_file.h"

namespace gdr::io {
namespace {

std::vector<Point3> to_points3(const NodeList& nodes) {
  std::vector<Point3> points(nodes.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = {nodes.coords[3 * i], nodes.coords[3 * i + 1], nodes.coords[3 * i + 2]};
  return points;
}

// One facet polygon: a point (ignored), a segment, or a polygon cut into triangles of
// facet `facet` (recorded per triangle in `facet_of`).
void add_polygon(const TextFile& file, const std::vector<Point3>& points,
                 const std::vector<int>& polygon, const std::string& what, int facet,
                 Surface& surface, std::vector<int>& facet_of) {
  if (polygon.size() == 2) {
    surface.segments.push_back({polygon[0], polygon[1]});
  } else if (polygon.size() >= 3 && !triangulate_polygon(points, polygon, surface.triangles)) {
    file.fail(what + " cannot be triangulated (degenerate or not a simple planar polygon)");
  }
  facet_of.resize(surface.triangles.size(), facet);
}

// "<#corners> c1 ... cn" at the start of `t`; returns the corners, 0-based.
std::vector<int> read_corners(const TextFile& file, const Tokens& t, int first_index,
                              std::size_t count, const std::string& what) {
  const long long n = file.integer(t[0], "corner count of " + what);
  if (n < 1) file.fail("corner count of " + what + " must be positive, found " + std::to_string(n));
  if (static_cast<unsigned long long>(n) + 1 > t.size())
    file.fail(what + " declares " + std::to_string(n) + " corners but lists " +
              std::to_string(t.size() - 1));
  std::vector<int> corners(static_cast<std::size_t>(n));
  for (long long i = 0; i < n; ++i) corners[i] = vertex_index(file, t[1 + i], first_index, count, what);
  return corners;
}

}  // namespace

Surface read_tetgen_poly(const std::string& path) {
  const bool smesh = extension_of(path) == ".smesh";
  TextFile file(path);
  const NodeList nodes = read_poly_point_section(file, 3);
  Surface surface;
  surface.points = to_points3(nodes);
  std::vector<int> facet_of;  // per triangle
  bool multi = false;         // some facet has several triangles
  Tokens t;
  file.expect(t, 1, "the facet count header");
  const std::size_t facets = file.count(t[0], 2, "facet count");
  for (std::size_t f = 0; f < facets; ++f) {
    const std::string what = "facet " + std::to_string(f);
    const std::size_t before = surface.triangles.size();
    if (smesh) {
      file.expect(t, 2, what);
      add_polygon(file, surface.points, read_corners(file, t, nodes.first_index, nodes.size(), what), what,
                  static_cast<int>(f), surface, facet_of);
    } else {
      file.expect(t, 1, what);
      const std::size_t polygons = file.count(t[0], 2, "polygon count of " + what);
      const long long holes = t.size() > 1 ? file.integer(t[1], "hole count of " + what) : 0;
      if (holes != 0) file.fail(what + " has holes, which are not supported (split the facet)");
      for (std::size_t p = 0; p < polygons; ++p) {
        const std::string pwhat = "polygon " + std::to_string(p) + " of " + what;
        file.expect(t, 2, pwhat);
        add_polygon(file, surface.points, read_corners(file, t, nodes.first_index, nodes.size(), pwhat), pwhat,
                    static_cast<int>(f), surface, facet_of);
      }
    }
    multi = multi || surface.triangles.size() > before + 1;
  }
  if (multi) surface.triangle_facet = facet_of;

  // Volume holes: "<count>", then "<index> x y z" each.
  if (!file.next(t)) return surface;
  const std::size_t holes = file.count(t[0], 4, "hole count");
  for (std::size_t h = 0; h < holes; ++h) {
    const std::string what = "hole " + std::to_string(h);
    file.expect(t, 4, what);
    surface.holes.push_back({file.real(t[1], "x of " + what), file.real(t[2], "y of " + what),
                             file.real(t[3], "z of " + what)});
  }
  // Regions: "<count>", then "<index> x y z attribute [max volume]" each.
  if (!file.next(t)) return surface;
  const std::size_t regions = file.count(t[0], 5, "region count");
  for (std::size_t r = 0; r < regions; ++r) {
    const std::string what = "region " + std::to_string(r);
    file.expect(t, 5, what);
    RegionSeed seed;
    seed.point = {file.real(t[1], "x of " + what), file.real(t[2], "y of " + what), file.real(t[3], "z of " + what)};
    const double attribute = file.real(t[4], "attribute of " + what);
    if (attribute != std::floor(attribute) || std::fabs(attribute) > 2147483647.0)
      file.fail("the attribute of " + what + " must be an integer, found " + std::string(t[4]));
    seed.attribute = static_cast<int>(attribute);
    if (t.size() > 5) seed.max_volume = std::max(0.0, file.real(t[5], "maximum volume of " + what));
    surface.regions.push_back(seed);
  }
  return surface;
}

TetMesh read_tetgen_mesh(const std::string& node_path, const std::string& ele_path) {
  const NodeList nodes = read_node_file(node_path, 3);
  TetMesh mesh;
  mesh.points = to_points3(nodes);
  TextFile file(ele_path);
  Tokens t;
  file.expect(t, 1, "the tetrahedron count header");
  const std::size_t n = file.count(t[0], 5, "tetrahedron count");
  long long corners = 4;
  if (t.size() >= 2) {
    corners = file.integer(t[1], "nodes per tetrahedron");
    if (corners != 4 && corners != 10)
      file.fail("nodes per tetrahedron must be 4 or 10, found " + std::to_string(corners));
  }
  // The first attribute is TetGen's region attribute.
  const bool regions = t.size() >= 3 && file.integer(t[2], "attribute count") > 0;
  mesh.tets.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string what = "tetrahedron " + std::to_string(i);
    file.expect(t, 1 + corners + (regions ? 1 : 0), what);
    file.integer(t[0], "index of " + what);
    // TetGen's tetrahedra have orient3d < 0; swapping two corners gives ours (> 0).
    mesh.tets.push_back({vertex_index(file, t[2], nodes, what), vertex_index(file, t[1], nodes, what),
                         vertex_index(file, t[3], nodes, what), vertex_index(file, t[4], nodes, what)});
    if (regions)
      mesh.tet_region.push_back(static_cast<int>(file.real(t[1 + corners], "region of " + what)));
  }
  // Boundary / constrained faces, as TetGen and write_tetgen store them beside the .ele.
  const std::string face_path = strip_extension(ele_path) + ".face";
  if (file_exists(face_path)) {
    TextFile faces(face_path);
    faces.expect(t, 1, "the face count header");
    const std::size_t nf = faces.count(t[0], 4, "face count");
    // Boundary markers: the input facet of each face, as write_tetgen writes them.
    const bool markers = t.size() >= 2 && faces.integer(t[1], "boundary marker flag") != 0;
    mesh.subfaces.reserve(nf);
    for (std::size_t i = 0; i < nf; ++i) {
      const std::string what = "face " + std::to_string(i);
      faces.expect(t, markers ? 5 : 4, what);
      faces.integer(t[0], "index of " + what);
      mesh.subfaces.push_back({vertex_index(faces, t[1], nodes, what),
                               vertex_index(faces, t[2], nodes, what),
                               vertex_index(faces, t[3], nodes, what)});
      if (markers)
        mesh.subface_facet.push_back(static_cast<int>(faces.integer(t[4], "marker of " + what)));
    }
  }
  return mesh;
}

Surface read_off(const std::string& path) {
  TextFile file(path);
  Tokens t;
  file.expect(t, 1, "the OFF header");
  if (t[0] != "OFF") file.fail("expected 'OFF', found '" + std::string(t[0]) + "'");
  // The counts may follow OFF on the same line.
  if (t.size() > 1) {
    t.erase(t.begin());
  } else {
    file.expect(t, 2, "the vertex and face counts");
  }
  if (t.size() < 2) file.fail("expected the vertex and face counts");
  const std::size_t nv = file.count(t[0], 3, "vertex count");
  const std::size_t nf = file.count(t[1], 4, "face count");
  Surface surface;
  surface.points.reserve(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    const std::string what = "point " + std::to_string(i);
    file.expect(t, 3, what);
    surface.points.push_back({file.real(t[0], "x of " + what), file.real(t[1], "y of " + what),
                              file.real(t[2], "z of " + what)});
  }
  surface.triangles.reserve(nf);
  FaceCollector faces(surface);
  for (std::size_t i = 0; i < nf; ++i) {
    const std::string what = "face " + std::to_string(i);
    file.expect(t, 4, what);
    std::vector<int> corners = read_corners(file, t, 0, nv, what);
    if (corners.size() < 3) file.fail(what + " has fewer than 3 corners");
    if (!faces.add(corners, static_cast<int>(i)))
      file.fail(what + " cannot be triangulated (degenerate or not a simple planar polygon)");
  }
  faces.finish();
  return surface;
}

namespace {

struct Key3 {
  double x, y, z;
  bool operator==(const Key3& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct Key3Hash {
  std::size_t operator()(const Key3& k) const {
    auto bits = [](double v) {
      std::uint64_t b;
      std::memcpy(&b, &v, sizeof b);
      return b;
    };
    std::uint64_t h = bits(k.x) * 0x9E3779B97F4A7C15ull;
    h = (h ^ (h >> 29)) + bits(k.y) * 0xBF58476D1CE4E5B9ull;
    h = (h ^ (h >> 31)) + bits(k.z) * 0x94D049BB133111EBull;
    return static_cast<std::size_t>(h ^ (h >> 32));
  }
};

// Merges exactly identical STL vertices (-0 and +0 are the same point).
class VertexMerger {
 public:
  explicit VertexMerger(Surface& s) : surface_(s) {}
  int add(double x, double y, double z) {
    const Key3 key{x + 0.0, y + 0.0, z + 0.0};
    const auto [it, inserted] = index_.emplace(key, static_cast<int>(surface_.points.size()));
    if (inserted) surface_.points.push_back({key.x, key.y, key.z});
    return it->second;
  }

 private:
  Surface& surface_;
  std::unordered_map<Key3, int, Key3Hash> index_;
};

Surface read_stl_binary(const std::string& path, const std::string& data, std::size_t n) {
  Surface surface;
  VertexMerger merger(surface);
  surface.triangles.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const char* rec = data.data() + 84 + 50 * i;
    float v[9];
    std::memcpy(v, rec + 12, sizeof v);
    std::array<int, 3> tri;
    for (int k = 0; k < 3; ++k) {
      for (int d = 0; d < 3; ++d)
        if (!std::isfinite(v[3 * k + d]))
          throw Error(Status::IoError, path + ": triangle " + std::to_string(i) +
                                           " has a non-finite coordinate");
      tri[k] = merger.add(v[3 * k], v[3 * k + 1], v[3 * k + 2]);
    }
    surface.triangles.push_back(tri);
  }
  return surface;
}

Surface read_stl_ascii(const std::string& path, std::string data) {
  TextFile file(path, std::move(data));
  Surface surface;
  VertexMerger merger(surface);
  Tokens t;
  auto keyword = [&](const char* word, std::size_t min_tokens) {
    file.expect(t, min_tokens, std::string("'") + word + "'");
    if (t[0] != word) file.fail(std::string("expected '") + word + "', found '" + std::string(t[0]) + "'");
  };
  keyword("solid", 1);
  std::size_t facet = 0;
  while (file.next(t)) {
    if (t[0] == "endsolid" || t[0] == "solid") continue;  // several solids may follow each other
    if (t[0] != "facet") file.fail("expected 'facet' or 'endsolid', found '" + std::string(t[0]) + "'");
    keyword("outer", 2);
    std::array<int, 3> tri;
    for (int k = 0; k < 3; ++k) {
      keyword("vertex", 4);
      const std::string what = "vertex " + std::to_string(k) + " of facet " + std::to_string(facet);
      tri[k] = merger.add(file.real(t[1], "x of " + what), file.real(t[2], "y of " + what),
                          file.real(t[3], "z of " + what));
    }
    keyword("endloop", 1);
    keyword("endfacet", 1);
    surface.triangles.push_back(tri);
    ++facet;
  }
  return surface;
}

}  // namespace

Surface read_stl(const std::string& path) {
  std::string data = read_file_bytes(path);
  if (data.size() >= 84) {
    std::uint32_t n = 0;
    std::memcpy(&n, data.data() + 80, sizeof n);
    if (84 + 50 * static_cast<std::uint64_t>(n) == data.size()) return read_stl_binary(path, data, n);
  }
  const std::size_t start = data.find_first_not_of(" \t\r\n");
  if (start != std::string::npos && data.compare(start, 5, "solid") == 0) return read_stl_ascii(path, std::move(data));
  if (data.size() < 84) throw Error(Status::IoError, path + ": too short for a binary STL and not ASCII");
  throw Error(Status::IoError,
              path + ": binary STL size " + std::to_string(data.size()) +
                  " does not match its triangle count (expected 84 + 50 * count bytes)");
}

std::vector<std::string> surface_input_files(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext != ".poly" && ext != ".smesh") return {path};
  return {path, strip_extension(path) + ".node"};  // as read_poly_point_section finds it
}

Surface read_surface(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext == ".off") return read_off(path);
  if (ext == ".stl") return read_stl(path);
  if (ext == ".ply") return read_ply(path);
  if (ext == ".obj") return read_obj(path);
  if (ext == ".poly" || ext == ".smesh") return read_tetgen_poly(path);
  if (ext == ".node") {  // TetGen points alone: a surface without facets
    Surface surface;
    surface.points = to_points3(read_node_file(path, 3));
    return surface;
  }
  throw Error(Status::IoError, path + ": unsupported surface format '" + ext +
                                   "' (expected .off, .stl, .ply, .obj, .poly, .smesh or .node)");
}

}  // namespace gdr::io
