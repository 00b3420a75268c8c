// Point location by walking through tetrahedra (visibility walk), for host and device code.
#pragma once
#include "mesh3d/mesh3d.h"

namespace gdr::m3d {

// The tetrahedron holding p (on its boundary counts), found by walking from `start` across
// a face that has p strictly on its outer side; the first face tried rotates with the step
// so that the walk does not cycle. Returns -1 when the walk leaves the mesh (p lies outside
// it), crosses a subface (a wall for the constrained meshers), or takes more than
// step_limit steps.
GDR_HD_INLINE int locate_point(const TetView& m, int start, const double* p, int step_limit) {
  int u = start;
  for (int step = 0; step < step_limit; ++step) {
    int exit = -1;
    for (int f0 = 0; f0 < 4 && exit < 0; ++f0) {
      const int f = (f0 + step) % 4;
      if (face_orient(m, u, f, p) < 0) exit = f;
    }
    if (exit < 0) return u;
    const int nb = m.tn[4 * u + exit];
    if (nb < 0 || m.tsub[4 * u + exit] >= 0) return -1;
    u = nb >> 2;
  }
  return -1;
}

// Is p one of the corners of tetrahedron t (same coordinates)?
GDR_HD_INLINE bool is_corner_point(const TetView& m, int t, const double* p) {
  for (int k = 0; k < 4; ++k) {
    const double* q = pt(m, m.tv[4 * t + k]);
    if (q[0] == p[0] && q[1] == p[1] && q[2] == p[2]) return true;
  }
  return false;
}

}  // namespace gdr::m3d
