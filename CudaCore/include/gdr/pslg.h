// Plain data types shared by readers, meshers, validators and filters.
#pragma once
#include <array>
#include <cstdint>
#include <memory>
#include <new>
#include <type_traits>
#include <utility>
#include <vector>

namespace gdr {

// An allocator whose resize() default-initialises: new elements of plain types are left
// uninitialised instead of zeroed. For large results that threads fill at once: each thread
// then touches its own pages first, where a zeroing resize makes one thread touch them all
// (0.1 s of a 16M-triangle mesh, more than copying it in).
template <class T>
struct DefaultInitAllocator : std::allocator<T> {
  template <class U>
  struct rebind {
    using other = DefaultInitAllocator<U>;
  };
  DefaultInitAllocator() = default;
  template <class U>
  DefaultInitAllocator(const DefaultInitAllocator<U>&) noexcept {}
  template <class U>
  void construct(U* p) noexcept(noexcept(U())) {
    // Plain data (Point2 too, whose members say 0) is left as it is: the filling threads
    // write it.
    if constexpr (!(std::is_trivially_copyable_v<U> && std::is_trivially_destructible_v<U>))
      ::new (static_cast<void*>(p)) U;
  }
  template <class U, class... Args>
  void construct(U* p, Args&&... args) {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

// Output arrays filled in parallel: resize() leaves new elements uninitialised (assign,
// insert and the constructors with a value still set them).
template <class T>
using FilledVector = std::vector<T, DefaultInitAllocator<T>>;

struct Point2 { double x = 0, y = 0; };
struct Point3 { double x = 0, y = 0, z = 0; };

// A region seed of a planar straight-line graph (Triangle's regional attribute and area
// constraint): the part of the domain that holds `point`, bounded by segments, gets
// `attribute`, and, when max_area > 0, that area bound.
struct RegionSeed2 {
  Point2 point;
  double attribute = 0;
  double max_area = 0;  // <= 0: none
};

// Planar straight-line graph: vertices, segments (vertex index pairs, 0-based), hole seeds,
// and what Triangle's files may carry besides: per-point attributes and boundary markers,
// per-segment boundary markers, region seeds (each empty when the input has none).
struct Pslg {
  std::vector<Point2> points;
  std::vector<std::array<int, 2>> segments;
  std::vector<Point2> holes;
  int point_attribute_count = 0;
  std::vector<double> point_attributes;  // point_attribute_count values per point
  std::vector<int> point_markers;        // per point
  std::vector<int> segment_markers;      // per segment
  std::vector<RegionSeed2> regions;
  // The number of the first point (and segment) in the file it was read from (Triangle files
  // count from 0 or 1): messages about the input number items as the file does.
  int first_index = 0;
};

// A region seed (TetGen's regional attribute): the region of the domain that holds `point`
// gets `attribute`, and, when max_volume > 0, that volume bound.
struct RegionSeed {
  Point3 point;
  int attribute = 0;
  double max_volume = 0;
};

// Piecewise linear complex given as a triangulated surface: one or several closed shells,
// optional internal facets, optional segments, hole and region seeds.
struct Surface {
  std::vector<Point3> points;
  std::vector<std::array<int, 3>> triangles;
  // Per triangle, the input facet (polygon) it belongs to: the triangles of one facet are
  // coplanar and the edges they share are not segments. Empty: every triangle is a facet.
  std::vector<int> triangle_facet;
  std::vector<std::array<int, 2>> segments;
  std::vector<Point3> holes;         // seeds of volumes to leave empty
  std::vector<RegionSeed> regions;   // seeds of regions with attributes
};

// Where a mesh vertex lies: an input vertex, on an input segment, on an input facet (3D),
// or free in the interior.
enum class PointType : std::uint8_t { Input = 0, Segment = 1, Free = 2, Facet = 3 };

// A triangle mesh. Triangles are counter-clockwise.
// (The large arrays are FilledVectors: resize() does not zero them.)
struct TriMesh {
  FilledVector<Point2> points;
  FilledVector<std::array<int, 3>> triangles;
  FilledVector<PointType> point_type;        // per point (may be empty)
  // Subsegments: mesh edges lying on input segments, with the input segment they belong to.
  FilledVector<std::array<int, 2>> subsegments;
  FilledVector<int> subsegment_source;       // index into the input segments, or -1 for hull edges
  // Input segments (ascending) left out because they border only removed regions (holes, or
  // the exterior): the validator expects no subsegment of them.
  std::vector<int> removed_segments;
  // The number of the first point in Triangle files written from the mesh (the input's own
  // numbering, 0 or 1, as Triangle writes its output).
  int first_index = 0;
  // As Triangle's output carries them (each empty when unknown): boundary markers of the
  // subsegments and points, point attributes (interpolated linearly at Steiner points), and
  // per triangle the attribute of its region.
  FilledVector<int> subsegment_markers;  // per subsegment
  FilledVector<int> point_markers;       // per point
  int point_attribute_count = 0;
  std::vector<double> point_attributes;  // point_attribute_count values per point
  std::vector<double> triangle_region;   // per triangle
};

// A tetrahedral mesh. Tetrahedra are positively oriented (orient3d > 0).
struct TetMesh {
  std::vector<Point3> points;
  std::vector<std::array<int, 4>> tets;
  std::vector<PointType> point_type;
  std::vector<std::array<int, 3>> subfaces;  // boundary / constrained faces
  std::vector<std::array<int, 2>> subsegments;
  std::vector<int> subface_facet;            // per subface: its input facet (may be empty)
  std::vector<int> tet_region;               // per tetrahedron: region attribute (may be empty)
};

}  // namespace gdr
