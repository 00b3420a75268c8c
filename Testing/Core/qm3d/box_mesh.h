// Test fixture: a constrained tetrahedral mesh of a box made of nx x ny x nz cubes, each cut
// into the six Kuhn tetrahedra (conforming from cube to cube), built directly as the engine's
// HostTetMesh so that the engine can be tested without the initial CDT. The box's six sides
// are its facets and its twelve edges its segments; optionally the plane x = split cuts it
// into two regions with an internal facet.
#pragma once
#include <algorithm>
#include <array>
#include <map>
#include <stdexcept>
#include <vector>

#include "gdr/pslg.h"
#include "mesh3d/host_mesh.h"
#include "mesh3d/tet_topology.h"
#include "predicates/predicates.h"

namespace gdr::test {

struct BoxMesh {
  m3d::HostTetMesh mesh;
  Surface surface;  // the input it stands for: boundary triangles (and the internal facet)
};

// split_at: index of the grid plane x = split_at (0 < split_at < nx) holding an internal
// facet; 0 for none. scale and offset map the unit grid spacing to world coordinates.
inline BoxMesh box_mesh(int nx, int ny, int nz, int split_at = 0, double scale = 1.0,
                        double offset = 0.0) {
  BoxMesh b;
  m3d::HostTetMesh& m = b.mesh;
  auto id = [&](int i, int j, int k) { return (k * (ny + 1) + j) * (nx + 1) + i; };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i) {
        m.xyz.insert(m.xyz.end(), {offset + scale * i, offset + scale * j, offset + scale * k});
        b.surface.points.push_back({offset + scale * i, offset + scale * j, offset + scale * k});
      }
  const int np = static_cast<int>(b.surface.points.size());
  m.ptype.assign(np, m3d::kInputPoint);
  m.pseg.assign(np, -1);
  m.pfacet.assign(np, -1);
  m.input_points = np;
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<int, 4> t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          const double* x[4];
          for (int q = 0; q < 4; ++q) x[q] = &m.xyz[3 * t[q]];
          if (pred::orient3d(x[0], x[1], x[2], x[3]) < 0) std::swap(t[2], t[3]);
          m.tv.insert(m.tv.end(), t.begin(), t.end());
          if (split_at > 0) m.tregion.push_back(i < split_at ? 1 : 2);
        }
  const int nt = m.tets();
  m.tn.assign(4 * nt, -1);
  m.tsub.assign(4 * nt, -1);
  m.tseg.assign(nt, 0);
  // Faces by sorted corners -> the tetrahedron faces that have them.
  std::map<std::array<int, 3>, std::vector<int>> faces;
  for (int t = 0; t < nt; ++t)
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> key;
      for (int q = 0; q < 3; ++q) key[q] = m.tv[4 * t + m3d::face_corner(f, q)];
      std::sort(key.begin(), key.end());
      faces[key].push_back(4 * t + f);
    }
  // Facet of a face: box side 0..5 (x=0, x=nx, y=0, y=ny, z=0, z=nz), 6 the split plane.
  auto grid = [&](int v, int axis) {
    const int i = v % (nx + 1), j = (v / (nx + 1)) % (ny + 1), k = v / ((nx + 1) * (ny + 1));
    return axis == 0 ? i : (axis == 1 ? j : k);
  };
  const int extent[3] = {nx, ny, nz};
  auto facet_of = [&](const std::array<int, 3>& f, bool boundary) {
    for (int axis = 0; axis < 3; ++axis) {
      const int g = grid(f[0], axis);
      if (grid(f[1], axis) != g || grid(f[2], axis) != g) continue;
      if (boundary && g == 0) return 2 * axis;
      if (boundary && g == extent[axis]) return 2 * axis + 1;
      if (!boundary && axis == 0 && split_at > 0 && g == split_at) return 6;
    }
    return -1;
  };
  for (const auto& [key, list] : faces) {
    if (list.size() == 2) {
      m.tn[list[0]] = list[1];
      m.tn[list[1]] = list[0];
    }
    const int facet = facet_of(key, list.size() == 1);
    if (facet < 0) continue;
    const int s = m.subfaces();
    const int t0 = list[0] >> 2, f0 = list[0] & 3;
    int corners[3];
    for (int q = 0; q < 3; ++q) corners[q] = m.tv[4 * t0 + m3d::face_corner(f0, q)];
    m.sv.insert(m.sv.end(), corners, corners + 3);
    m.st.push_back(list[0]);
    m.st.push_back(list.size() == 2 ? list[1] : -1);
    m.sfacet.push_back(facet);
    for (int tf : list) m.tsub[tf] = s;
    b.surface.triangles.push_back({corners[0], corners[1], corners[2]});
    b.surface.triangle_facet.push_back(facet);
  }
  // Segments: grid edges on two box sides (the box's edges), or on a side and the split plane.
  std::map<std::array<int, 2>, int> segment_id;
  auto on_segment = [&](int a, int c) {
    int shared = 0;
    for (int axis = 0; axis < 3; ++axis) {
      const int g = grid(a, axis);
      if (grid(c, axis) != g) continue;
      if (g == 0 || g == extent[axis] || (axis == 0 && split_at > 0 && g == split_at)) ++shared;
    }
    return shared >= 2;
  };
  for (int t = 0; t < nt; ++t)
    for (int e = 0; e < 6; ++e) {
      int a = m.tv[4 * t + m3d::edge_corner(e, 0)], c = m.tv[4 * t + m3d::edge_corner(e, 1)];
      if (!on_segment(a, c)) continue;
      m.tseg[t] |= 1 << e;
      if (a > c) std::swap(a, c);
      if (segment_id.emplace(std::array<int, 2>{a, c}, m.segments()).second) {
        m.seg.push_back(a);
        m.seg.push_back(c);
      }
    }
  return b;
}

}  // namespace gdr::test
