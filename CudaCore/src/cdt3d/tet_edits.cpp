// Edits of the initial CDT after TetGen (tet_edits.h).
#include "cdt3d/tet_edits.h"

#include <algorithm>
#include <cstdint>
#include <unordered_set>

#include "cdt3d/internal.h"
#include "mesh3d/tet_topology.h"
#include "predicates/predicates.h"

namespace gdr::cdt3d {

using m3d::HostTetMesh;

void remove_tets(HostTetMesh& m, const std::vector<char>& dead) {
  const int nt = m.tets();
  std::vector<int> new_tet(nt, -1);
  int kt = 0;
  for (int t = 0; t < nt; ++t)
    if (!dead[t]) new_tet[t] = kt++;
  const auto map_face = [&](int x) { return x < 0 ? -1 : 4 * new_tet[x / 4] + x % 4; };
  for (int t = 0; t < nt; ++t) {
    const int u = new_tet[t];
    if (u < 0) continue;
    for (int k = 0; k < 4; ++k) {
      m.tv[4 * u + k] = m.tv[4 * t + k];
      m.tn[4 * u + k] = map_face(m.tn[4 * t + k]);
      m.tsub[4 * u + k] = m.tsub[4 * t + k];
    }
    m.tseg[u] = m.tseg[t];
    if (!m.tregion.empty()) m.tregion[u] = m.tregion[t];
  }
  m.tv.resize(4 * static_cast<std::size_t>(kt));
  m.tn.resize(4 * static_cast<std::size_t>(kt));
  m.tsub.resize(4 * static_cast<std::size_t>(kt));
  m.tseg.resize(kt);
  if (!m.tregion.empty()) m.tregion.resize(kt);
  for (int& x : m.st) x = map_face(x);
}

// Tetrahedra of zero or negative volume (exact orient3d) on the domain's boundary: with "c",
// TetGen triangulates the convex hull and glues a flat tetrahedron between a hull face pair
// and the input's two triangles of the same (nearly) coplanar quadrilateral when they use the
// other diagonal, and classifies it inside: exactly flat on a turned box whose faces' corners
// are coplanar, inverted by a rounding where TetGen merged a face that bends inward within its
// 0.1 degrees (a turned box of two bodies meshed one by one, fuzz3d seed 56003176). Such a
// tetrahedron has two faces on the boundary (subfaces of one facet, nothing beyond) and two
// towards the domain; it is dropped and its two inner faces become the facet's subfaces
// instead (the validators let coplanar input triangles be retriangulated, and a bend of
// rounding size is within their tolerance; TetGen's diagonal is the Delaunay one). Unless the
// diagonal it drops is a segment. Returns how many were dropped; other such tetrahedra stay.
int drop_flat_boundary_tets(const Plc& plc, HostTetMesh& m) {
  const int nt = m.tets();
  std::vector<int> flat;
#pragma omp parallel for schedule(static) if (nt > 20000)
  for (int t = 0; t < nt; ++t) {
    const double* p[4];
    for (int k = 0; k < 4; ++k) p[k] = &m.xyz[3 * static_cast<std::size_t>(m.tv[4 * t + k])];
    if (!(pred::orient3d(p[0], p[1], p[2], p[3]) > 0)) {
#pragma omp critical(gdr_cdt_flat)
      flat.push_back(t);
    }
  }
  if (flat.empty()) return 0;
  std::sort(flat.begin(), flat.end());
  std::unordered_set<std::uint64_t> segments;
  for (const auto& g : plc.segments) segments.insert(edge_key(g[0], g[1]));
  std::vector<char> dead(nt, 0);
  int dropped = 0;
  for (const int t : flat) {
    int outer[2], inner[2], no = 0, ni = 0;
    for (int i = 0; i < 4; ++i) {
      const int x = 4 * t + i;
      if (m.tsub[x] >= 0 && m.tn[x] < 0 && no < 2) outer[no++] = i;
      else if (m.tsub[x] < 0 && m.tn[x] >= 0 && !dead[m.tn[x] / 4] && ni < 2) inner[ni++] = i;
    }
    if (no != 2 || ni != 2) continue;
    const int s0 = m.tsub[4 * t + outer[0]], s1 = m.tsub[4 * t + outer[1]];
    // The faces opposite corners i and j share the edge of the other two corners.
    const int a = m.tv[4 * t + inner[0]], b = m.tv[4 * t + inner[1]];
    if (m.sfacet[s0] != m.sfacet[s1] || segments.count(edge_key(a, b))) continue;
    for (int k = 0; k < 2; ++k) {
      // The subface slot of an outer face moves to an inner face, seen from the neighbour
      // u across it: its corners counter-clockwise from outside u, so u is on side 0.
      const int s = k == 0 ? s0 : s1, x = m.tn[4 * t + inner[k]], u = x / 4, j = x % 4;
      for (int c = 0; c < 3; ++c) m.sv[3 * s + c] = m.tv[4 * u + m3d::face_corner(j, c)];
      m.st[2 * s] = x;
      m.st[2 * s + 1] = -1;
      m.tn[x] = -1;
      m.tsub[x] = s;
    }
    dead[t] = 1;
    ++dropped;
  }
  if (dropped > 0) remove_tets(m, dead);
  return dropped;
}

}  // namespace gdr::cdt3d
