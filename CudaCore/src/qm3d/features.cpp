#include "qm3d/features.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>
#include <vector>

#include "mesh3d/tet_topology.h"

namespace gdr::qm3d {
namespace {

using m3d::HostTetMesh;

const double* xyz(const HostTetMesh& m, int v) { return &m.xyz[3 * std::size_t(v)]; }

// Dihedral angle of tetrahedron t at its edge between corners i and j, in radians.
double dihedral_at(const HostTetMesh& m, int t, int i, int j) {
  int k = -1, l = -1;
  for (int c = 0; c < 4; ++c)
    if (c != i && c != j) (k < 0 ? k : l) = c;
  const double* a = xyz(m, m.tv[4 * t + i]);
  const double* b = xyz(m, m.tv[4 * t + j]);
  const double* p = xyz(m, m.tv[4 * t + k]);
  const double* q = xyz(m, m.tv[4 * t + l]);
  double u[3], x[3], y[3];
  double uu = 0;
  for (int d = 0; d < 3; ++d) {
    u[d] = b[d] - a[d];
    uu += u[d] * u[d];
  }
  double xu = 0, yu = 0;
  for (int d = 0; d < 3; ++d) {
    xu += (p[d] - a[d]) * u[d];
    yu += (q[d] - a[d]) * u[d];
  }
  double xx = 0, yy = 0, xy = 0;
  for (int d = 0; d < 3; ++d) {
    x[d] = p[d] - a[d] - xu / uu * u[d];
    y[d] = q[d] - a[d] - yu / uu * u[d];
    xx += x[d] * x[d];
    yy += y[d] * y[d];
    xy += x[d] * y[d];
  }
  const double c = xy / std::sqrt(xx * yy);
  return std::acos(std::max(-1.0, std::min(1.0, c)));
}

int corner(const HostTetMesh& m, int t, int v) {
  for (int c = 0; c < 4; ++c)
    if (m.tv[4 * t + c] == v) return c;
  return -1;
}

}  // namespace

void find_sharp_features(HostTetMesh& m, double sharp_angle_deg, double acute_angle_deg) {
  const int ns = m.segments(), np = m.points(), nt = m.tets();
  m.sharp.assign(ns, 0);
  m.prad.assign(np, 0.0f);
  auto key = [](int a, int b) {
    return (std::uint64_t(std::uint32_t(std::min(a, b))) << 32) | std::uint32_t(std::max(a, b));
  };
  std::unordered_map<std::uint64_t, int> by_ends;  // read by all threads below, written only here
  by_ends.reserve(2 * static_cast<std::size_t>(ns));
  for (int s = 0; s < ns; ++s) by_ends[key(m.seg[2 * s], m.seg[2 * s + 1])] = s;
  auto segment_of = [&](int a, int b) {
    if (m.ptype[a] == m3d::kSegmentPoint) return m.pseg[a];
    if (m.ptype[b] == m3d::kSegmentPoint) return m.pseg[b];
    const auto it = by_ends.find(key(a, b));
    return it == by_ends.end() ? -1 : it->second;
  };
  const double bound = sharp_angle_deg * 3.14159265358979323846 / 180.0;

  // Wedges: from a subface at a subsegment, turn around the subsegment through the
  // tetrahedra, adding their dihedral angles there, to the next subface. Threads only ever
  // set a flag to 1, so the order in which they find a wedge does not matter.
#pragma omp parallel for schedule(dynamic, 4096) if (nt > 20000)
  for (int t = 0; t < nt; ++t) {
    for (int e = 0; e < 6; ++e) {
      if (!(m.tseg[t] & (1 << e))) continue;
      const int a = m.tv[4 * t + m3d::edge_corner(e, 0)], b = m.tv[4 * t + m3d::edge_corner(e, 1)];
      const int s = segment_of(a, b);
      if (s < 0) continue;
      std::uint8_t seen;
#pragma omp atomic read
      seen = m.sharp[s];
      if (seen) continue;
      for (int side = 0; side < 2; ++side) {
        // The two faces of t at the edge are those opposite its two other corners.
        int f[2], k = 0;
        for (int c = 0; c < 4; ++c)
          if (c != m3d::edge_corner(e, 0) && c != m3d::edge_corner(e, 1)) f[k++] = c;
        if (m.tsub[4 * t + f[side]] < 0) continue;  // walks start at a subface
        int u = t, g = f[1 - side];
        double angle = 0;
        for (int guard = 0; guard < 1000; ++guard) {
          angle += dihedral_at(m, u, corner(m, u, a), corner(m, u, b));
          if (angle >= bound || m.tsub[4 * u + g] >= 0) break;
          const int nb = m.tn[4 * u + g];
          if (nb < 0) break;
          u = nb >> 2;
          const int ca = corner(m, u, a), cb = corner(m, u, b);
          for (int c = 0; c < 4; ++c)
            if (c != ca && c != cb && c != (nb & 3)) g = c;
        }
        if (angle < bound) {
#pragma omp atomic write
          m.sharp[s] = 1;
        }
      }
    }
  }

  // Protecting balls: the ends of sharp segments, radius the distance to the nearest
  // vertex they share a tetrahedron with.
  std::vector<double> r(np, 0.0);
  for (int s = 0; s < ns; ++s)
    if (m.sharp[s])
      for (int k = 0; k < 2; ++k) r[m.seg[2 * s + k]] = std::numeric_limits<double>::infinity();
  if (acute_angle_deg > 0) {
    // Acute vertices (TetGen): two segments meet there at less than acute_angle_deg.
    std::vector<std::vector<int>> ends(np);
    for (int s = 0; s < ns; ++s) {
      ends[m.seg[2 * s]].push_back(m.seg[2 * s + 1]);
      ends[m.seg[2 * s + 1]].push_back(m.seg[2 * s]);
    }
    const double cos_acute = std::cos(acute_angle_deg * 3.14159265358979323846 / 180.0);
    for (int v = 0; v < np; ++v) {
      const double* o = xyz(m, v);
      for (std::size_t i = 0; i < ends[v].size() && std::isfinite(r[v]); ++i)
        for (std::size_t j = i + 1; j < ends[v].size(); ++j) {
          const double* a = xyz(m, ends[v][i]);
          const double* b = xyz(m, ends[v][j]);
          double ab = 0, aa = 0, bb = 0;
          for (int d = 0; d < 3; ++d) {
            ab += (a[d] - o[d]) * (b[d] - o[d]);
            aa += (a[d] - o[d]) * (a[d] - o[d]);
            bb += (b[d] - o[d]) * (b[d] - o[d]);
          }
          if (ab > cos_acute * std::sqrt(aa * bb)) {
            r[v] = std::numeric_limits<double>::infinity();
            break;
          }
        }
    }
  }
  for (int t = 0; t < nt; ++t)
    for (int i = 0; i < 4; ++i) {
      const int v = m.tv[4 * t + i];
      if (r[v] == 0) continue;
      for (int j = 0; j < 4; ++j) {
        if (j == i) continue;
        const double* p = xyz(m, v);
        const double* q = xyz(m, m.tv[4 * t + j]);
        const double d = std::sqrt((p[0] - q[0]) * (p[0] - q[0]) + (p[1] - q[1]) * (p[1] - q[1]) +
                                   (p[2] - q[2]) * (p[2] - q[2]));
        r[v] = std::min(r[v], d);
      }
    }
  for (int v = 0; v < np; ++v)
    if (std::isfinite(r[v])) m.prad[v] = static_cast<float>(r[v]);
  // Points the CDT put on sharp segments: radii interpolated between the segment's ends.
  for (int v = 0; v < np; ++v) {
    if (m.ptype[v] != m3d::kSegmentPoint || m.pseg[v] < 0 || !m.sharp[m.pseg[v]]) continue;
    const int a = m.seg[2 * m.pseg[v]], b = m.seg[2 * m.pseg[v] + 1];
    const double* pa = xyz(m, a);
    const double* pb = xyz(m, b);
    const double* p = xyz(m, v);
    double ab = 0, ap = 0;
    for (int d = 0; d < 3; ++d) {
      ab += (pb[d] - pa[d]) * (pb[d] - pa[d]);
      ap += (p[d] - pa[d]) * (p[d] - pa[d]);
    }
    const double t = std::sqrt(ap / ab);
    m.prad[v] = static_cast<float>(m.prad[a] + t * (m.prad[b] - m.prad[a]));
  }
}

}  // namespace gdr::qm3d
