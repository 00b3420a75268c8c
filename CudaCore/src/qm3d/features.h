// Sharp features and their protecting balls (after TetGen): where two facets meet at a
// small dihedral angle, or segments at a small angle, Delaunay refinement cannot fix every
// tetrahedron and would cascade trying. A segment is sharp when a wedge of the domain
// between two consecutive facets around it is narrower than a bound; its endpoints, and the
// acute vertices (input vertices where two segments meet at less than a bound: on a scanned
// surface, whose every edge is a segment, most of them), get a protecting ball whose radius
// is the distance to their nearest neighbour, and points later put on a sharp segment one
// interpolated between its ends. Bad tetrahedra whose
// circumcentre falls in a ball, subfaces whose circumcentre does, and sharp segments that are
// merely encroached are left as they are and reported (qm3d/kernels.h, mesh3d/cavity.h).
#pragma once
#include "mesh3d/host_mesh.h"

namespace gdr::qm3d {

// Fills m.sharp (per segment) and m.prad (per point). `sharp_angle_deg`: wedges narrower
// than this make a segment sharp (TetGen uses 65 degrees); `acute_angle_deg`: segments
// meeting at less than this make their vertex acute (TetGen: 60 degrees; 0: none).
void find_sharp_features(m3d::HostTetMesh& m, double sharp_angle_deg = 65.0, double acute_angle_deg = 60.0);

}  // namespace gdr::qm3d
