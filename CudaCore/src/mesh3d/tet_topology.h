// Local numbering inside a tetrahedron, shared by the host and the device code of both 3D
// meshers (and by the TetGen adapter that builds their input).
//
// Tetrahedron t has vertices v0..v3 with orient3d(v0, v1, v2, v3) > 0 (Shewchuk's sign: v3
// lies below the plane of v0, v1, v2, which turn counter-clockwise seen from above).
// Face i is opposite vertex i; kFace[i] lists its corners counter-clockwise seen from
// outside the tetrahedron, so that replacing vertex i by any point p on the inner side of
// face i gives the positive tetrahedron (kFace[i][0], kFace[i][1], kFace[i][2], p).
// Edge e joins kEdge[e][0] and kEdge[e][1]: (0,1) (0,2) (0,3) (1,2) (1,3) (2,3).
#pragma once
#include "exec/hd.h"

namespace gdr::m3d {

GDR_HD_INLINE int face_corner(int face, int k) {
  // {{1,3,2},{0,2,3},{0,3,1},{0,1,2}} without a table (device code has no static arrays).
  switch (face) {
    case 0: return k == 0 ? 1 : (k == 1 ? 3 : 2);
    case 1: return k == 0 ? 0 : (k == 1 ? 2 : 3);
    case 2: return k == 0 ? 0 : (k == 1 ? 3 : 1);
    default: return k;
  }
}

GDR_HD_INLINE int edge_corner(int edge, int k) {
  // (0,1) (0,2) (0,3) (1,2) (1,3) (2,3)
  const int a = edge < 3 ? 0 : (edge < 5 ? 1 : 2);
  const int b = edge < 3 ? edge + 1 : (edge < 5 ? edge - 1 : 3);
  return k == 0 ? a : b;
}

// The edge joining corners a != b.
GDR_HD_INLINE int edge_index(int a, int b) {
  if (a > b) {
    const int t = a;
    a = b;
    b = t;
  }
  return a == 0 ? b - 1 : (a == 1 ? b + 1 : 5);
}

// Bit of edge e in a 6-bit edge mask.
GDR_HD_INLINE int edge_bit(int e) { return 1 << e; }

}  // namespace gdr::m3d
