// Plain data types shared by readers, meshers, validators and filters.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

namespace gdr {

struct Point2 { double x = 0, y = 0; };
struct Point3 { double x = 0, y = 0, z = 0; };

// Planar straight-line graph: vertices, segments (vertex index pairs, 0-based), hole seeds.
struct Pslg {
  std::vector<Point2> points;
  std::vector<std::array<int, 2>> segments;
  std::vector<Point2> holes;
};

// Piecewise linear complex given as a triangulated surface (plus optional segments).
struct Surface {
  std::vector<Point3> points;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 2>> segments;
};

enum class PointType : std::uint8_t { Input = 0, Segment = 1, Free = 2 };

// A triangle mesh. Triangles are counter-clockwise.
struct TriMesh {
  std::vector<Point2> points;
  std::vector<std::array<int, 3>> triangles;
  std::vector<PointType> point_type;        // per point (may be empty)
  // Subsegments: mesh edges lying on input segments, with the input segment they belong to.
  std::vector<std::array<int, 2>> subsegments;
  std::vector<int> subsegment_source;       // index into the input segments, or -1 for hull edges
};

// A tetrahedral mesh. Tetrahedra are positively oriented (orient3d > 0).
struct TetMesh {
  std::vector<Point3> points;
  std::vector<std::array<int, 4>> tets;
  std::vector<PointType> point_type;
  std::vector<std::array<int, 3>> subfaces;  // boundary / constrained faces
  std::vector<std::array<int, 2>> subsegments;
};

}  // namespace gdr
