// The host form of a constrained tetrahedral mesh: what the initial CDT (cdt3d/) produces
// and the 3D engines take as input. Conventions in mesh3d/tet_topology.h.
#pragma once
#include <cstdint>
#include <vector>

namespace gdr::m3d {

// Per-point types (same values as gdr::PointType).
enum : std::uint8_t { kInputPoint = 0, kSegmentPoint = 1, kFreePoint = 2, kFacetPoint = 3 };
// HostTetMesh::sharp bits.
enum : std::uint8_t { kSharp = 1, kNearlyFlat = 2 };

struct HostTetMesh {
  std::vector<double> xyz;          // 3 per point; the input points first, in input order
  std::vector<std::uint8_t> ptype;  // per point
  std::vector<int> pseg;            // per point: the segment a segment point lies on, else -1
  std::vector<int> pfacet;          // per point: the facet a facet point lies on, else -1

  std::vector<int> tv;              // 4 per tetrahedron, positively oriented
  std::vector<int> tn;              // 4 per tetrahedron: neighbour across face i as 4*t'+i',
                                    // -1 on the domain boundary (always a subface)
  std::vector<int> tsub;            // 4 per tetrahedron: the subface on face i, or -1
  std::vector<std::uint8_t> tseg;   // per tetrahedron: bit e set when edge e is a subsegment
  std::vector<int> tregion;         // per tetrahedron: region attribute (empty: no regions)

  std::vector<int> sv;              // 3 per subface
  std::vector<int> st;              // 2 per subface: the tetrahedron faces (4*t+i) on its two
                                    // sides. st[2s] is the side where (sv0, sv1, sv2) is the
                                    // face's outside-counter-clockwise order (orient3d(sv0,
                                    // sv1, sv2, apex) > 0), st[2s+1] the other side; -1 where
                                    // there is no tetrahedron (outside the domain).
  std::vector<int> sfacet;          // per subface: the facet it lies in
  std::vector<int> fplane;          // 3 per facet: input points spanning its plane (its
                                    // largest triangle), which points put on it are projected
                                    // on; empty: not projected

  std::vector<int> seg;             // 2 per segment: endpoint point ids (input points)
  int input_points = 0;             // points [0, input_points) are the input's

  // Sharp features, found by the refinement (qm3d/features.h) and empty until then: per
  // segment, bit kSharp when two facets meet there at a small dihedral angle (or its splits
  // kept failing: qm3d's blocking), bit kNearlyFlat when its facets meet nearly flat; per
  // point, the radius of its protecting ball (0: none).
  std::vector<std::uint8_t> sharp;
  std::vector<float> prad;

  int points() const { return static_cast<int>(ptype.size()); }
  int tets() const { return static_cast<int>(tv.size() / 4); }
  int subfaces() const { return static_cast<int>(sv.size() / 3); }
  int segments() const { return static_cast<int>(seg.size() / 2); }
};

// Checks every link and orientation of `m` with exact predicates: a thrown
// Error(InternalError) names the first inconsistency. For tests and debugging.
void check_host_mesh(const HostTetMesh& m);

}  // namespace gdr::m3d
