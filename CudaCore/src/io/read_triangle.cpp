// Triangle's .poly / .node / .ele readers and input-kind detection.
#include "gdr/error.h"
#include "gdr/io.h"
#include "io/text_file.h"

namespace gdr::io {
namespace {

std::vector<Point2> to_points2(const NodeList& nodes) {
  std::vector<Point2> points(nodes.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = {nodes.coords[2 * i], nodes.coords[2 * i + 1]};
  return points;
}

// Segments section of a Triangle .poly: "<count> [<markers>]", then "<i> <a> <b> [marker]".
// The markers, when the header announces them, go to `markers`.
void read_segments(TextFile& file, const NodeList& nodes, std::vector<std::array<int, 2>>& segments,
                   std::vector<int>& markers) {
  Tokens t;
  file.expect(t, 1, "the segment count header");
  const std::size_t n = file.count(t[0], 3, "segment count");
  const bool marked = t.size() >= 2 && file.integer(t[1], "segment marker count") != 0;
  segments.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string what = "segment " + std::to_string(i);
    file.expect(t, marked ? 4 : 3, what);
    file.integer(t[0], "index of " + what);
    segments.push_back({vertex_index(file, t[1], nodes, what), vertex_index(file, t[2], nodes, what)});
    if (marked) markers.push_back(static_cast<int>(file.integer(t[3], "boundary marker of " + what)));
  }
}

}  // namespace

std::vector<std::string> poly_input_files(const std::string& path) {
  if (extension_of(path) != ".poly") return {path};
  return {path, strip_extension(path) + ".node"};  // as read_poly_point_section finds it
}

Pslg read_poly(const std::string& path) {
  Pslg pslg;
  const auto take_nodes = [&pslg](NodeList&& nodes) {
    pslg.points = to_points2(nodes);
    pslg.first_index = nodes.first_index;
    pslg.point_attribute_count = nodes.attribute_count;
    pslg.point_attributes = std::move(nodes.attributes);
    pslg.point_markers = std::move(nodes.markers);
  };
  if (extension_of(path) == ".node") {
    take_nodes(read_node_file(path, 2));
    return pslg;
  }
  TextFile file(path);
  NodeList nodes = read_poly_point_section(file, 2);
  read_segments(file, nodes, pslg.segments, pslg.segment_markers);
  take_nodes(std::move(nodes));
  Tokens t;
  file.expect(t, 1, "the hole count header");
  const std::size_t holes = file.count(t[0], 3, "hole count");
  for (std::size_t i = 0; i < holes; ++i) {
    const std::string what = "hole " + std::to_string(i);
    file.expect(t, 3, what);
    pslg.holes.push_back({file.real(t[1], "x of " + what), file.real(t[2], "y of " + what)});
  }
  // Optional regional attributes and area constraints: "<i> <x> <y> <attribute> [<area>]".
  if (!file.next(t)) return pslg;
  const std::size_t regions = file.count(t[0], 4, "region count");
  for (std::size_t i = 0; i < regions; ++i) {
    const std::string what = "region " + std::to_string(i);
    file.expect(t, 4, what);
    RegionSeed2 r;
    r.point = {file.real(t[1], "x of " + what), file.real(t[2], "y of " + what)};
    r.attribute = file.real(t[3], "attribute of " + what);
    if (t.size() > 4) r.max_area = file.real(t[4], "maximum area of " + what);
    pslg.regions.push_back(r);
  }
  return pslg;
}

TriMesh read_triangle_mesh(const std::string& node_path, const std::string& ele_path) {
  TriMesh mesh;
  const NodeList nodes = read_node_file(node_path, 2);
  const std::vector<Point2> points = to_points2(nodes);
  mesh.points.assign(points.begin(), points.end());
  mesh.first_index = nodes.first_index;
  mesh.point_markers.assign(nodes.markers.begin(), nodes.markers.end());
  mesh.point_attribute_count = nodes.attribute_count;
  mesh.point_attributes = nodes.attributes;
  TextFile file(ele_path);
  Tokens t;
  file.expect(t, 1, "the triangle count header");
  const std::size_t n = file.count(t[0], 4, "triangle count");
  long long corners = 3;
  if (t.size() >= 2) {
    corners = file.integer(t[1], "nodes per triangle");
    if (corners != 3 && corners != 6)
      file.fail("nodes per triangle must be 3 or 6, found " + std::to_string(corners));
  }
  // The first triangle attribute is the regional attribute (Triangle's -A).
  const bool region = t.size() >= 3 && file.integer(t[2], "triangle attribute count") > 0;
  mesh.triangles.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    const std::string what = "triangle " + std::to_string(i);
    file.expect(t, 1 + corners + (region ? 1 : 0), what);
    file.integer(t[0], "index of " + what);
    mesh.triangles.push_back({vertex_index(file, t[1], nodes, what),
                              vertex_index(file, t[2], nodes, what),
                              vertex_index(file, t[3], nodes, what)});
    if (region) mesh.triangle_region.push_back(file.real(t[1 + corners], "attribute of " + what));
  }
  // Subsegments, as write_triangle stores them: a point-less .poly beside the .ele.
  const std::string poly_path = strip_extension(ele_path) + ".poly";
  if (file_exists(poly_path)) {
    TextFile poly(poly_path);
    Tokens header;
    poly.expect(header, 1, "the point count header");
    if (poly.integer(header[0], "point count") == 0) {
      std::vector<std::array<int, 2>> segments;
      std::vector<int> markers;
      read_segments(poly, nodes, segments, markers);
      mesh.subsegments.assign(segments.begin(), segments.end());
      mesh.subsegment_markers.assign(markers.begin(), markers.end());
    }
  }
  return mesh;
}

InputKind detect_input_kind(const std::string& path) {
  const std::string ext = extension_of(path);
  if (ext == ".off" || ext == ".stl" || ext == ".ply" || ext == ".obj" || ext == ".smesh")
    return InputKind::Surface3d;
  if (ext != ".poly" && ext != ".node")
    throw Error(Status::IoError, path + ": unsupported input format '" + ext +
                                     "' (expected .poly, .node, .off, .stl, .ply, .obj or .smesh)");
  TextFile file(path);
  Tokens t;
  file.expect(t, 2, "the point count header");
  const long long dim = file.integer(t[1], "dimension");
  if (dim == 2) return InputKind::Pslg2d;
  if (dim == 3) return InputKind::Surface3d;
  file.fail("dimension must be 2 or 3, found " + std::to_string(dim));
}

int element_file_dimension(const std::string& ele_path) {
  TextFile file(ele_path);
  Tokens t;
  file.expect(t, 2, "the element count header");
  const long long corners = file.integer(t[1], "nodes per element");
  if (corners == 3 || corners == 6) return 2;   // Triangle
  if (corners == 4 || corners == 10) return 3;  // TetGen
  file.fail("nodes per element must be 3 or 6 (Triangle) or 4 or 10 (TetGen), found " +
            std::to_string(corners));
}

}  // namespace gdr::io
