// Pinches of the volume's surface, undone by relabelling tetrahedra (host, after refinement).
//
// With a volume, the output surface is the boundary of the tetrahedra whose circumcentres
// lie inside. Where the input is rough at the scale of the mesh (a scan's noise: creases
// between its triangles everywhere), tetrahedra with four corners on the surface have their
// circumcentres within rounding of the input, inside or outside almost at random; two of
// them inside, touching along an edge or at a vertex with outside ones between, pinch the
// surface there. The manifold criterion's refinement does not converge on them (splitting
// there makes new ones: on a 40k-triangle noisy sphere, 9,400 surface triangles at pinches
// after refinement down to D/1000, more at D/10^4), so what it leaves is undone here: at each
// non-manifold vertex or edge, the tetrahedra around it that are inside (or outside) form
// several groups, connected across faces through it; all but the largest group by volume,
// of the side where that costs less volume, change side. Only tetrahedra with every corner
// on the surface change (never one with an interior point, a hull face or a feature edge), each at most
// once; where both sides would need such a change again, the whole star takes the side of
// most volume. The triangulation stays as it is (Delaunay), the surface stays the
// boundary of the tetrahedra inside, and what moves is of the mesh's smallest size.
#pragma once
#include <cstdint>
#include <vector>

namespace gdr::rdt3d {

struct PinchRepair {
  long long relabelled = 0;   // tetrahedra that changed side
  long long places_left = 0;  // non-manifold vertices and edges left after max_rounds
  std::vector<int> left_at;   // their vertices
  std::vector<char> moved;    // per tetrahedron: it changed side
  int rounds = 0;
};

// Used without sharp features (restricted_delaunay.cpp says why).
// tv, tn: the triangulation (4 per tetrahedron; tn = 4 u + g, -1 on the hull), no dead
// tetrahedra; flag: `inside_bit` set on tetrahedra inside (changed in place); tetrahedra
// with any of `fixed_bits` (feature subsegments) never change side; ptype: point types
// (m3d::kFreePoint marks interior points).
PinchRepair undo_pinches(const double* xyz, const std::uint8_t* ptype, int npts, const int* tv, const int* tn,
                         int* flag, int ntet, int inside_bit, int fixed_bits, int max_rounds = 32);

}  // namespace gdr::rdt3d
