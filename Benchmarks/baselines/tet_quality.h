// Dihedral angles and radius-edge ratios of tetrahedra, measured the same way for every
// 3D baseline so their JSON lines compare.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>

namespace gdr_bench {

struct TetQuality {
  long long tets = 0;
  double min_dihedral_deg = 180.0, max_dihedral_deg = 0.0;
  double max_radius_edge = 0.0;
  double volume = 0.0;

  void add(const std::array<double, 3>& a, const std::array<double, 3>& b,
           const std::array<double, 3>& c, const std::array<double, 3>& d) {
    const std::array<const std::array<double, 3>*, 4> v = {&a, &b, &c, &d};
    auto sub = [](const std::array<double, 3>& p, const std::array<double, 3>& q) {
      return std::array<double, 3>{p[0] - q[0], p[1] - q[1], p[2] - q[2]};
    };
    auto cross = [](const std::array<double, 3>& p, const std::array<double, 3>& q) {
      return std::array<double, 3>{p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2],
                                   p[0] * q[1] - p[1] * q[0]};
    };
    auto dot = [](const std::array<double, 3>& p, const std::array<double, 3>& q) {
      return p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
    };
    const double pi = 3.14159265358979323846;
    // Outward face normals; the dihedral at edge (i,j) is pi minus the angle between the
    // normals of the two faces that share it (faces opposite the other two vertices).
    std::array<std::array<double, 3>, 4> n;
    for (int k = 0; k < 4; ++k) {
      const auto& p = *v[(k + 1) % 4];
      const auto& q = *v[(k + 2) % 4];
      const auto& r = *v[(k + 3) % 4];
      n[k] = cross(sub(q, p), sub(r, p));
      if (dot(n[k], sub(p, *v[k])) < 0) n[k] = {-n[k][0], -n[k][1], -n[k][2]};
    }
    double shortest2 = INFINITY;
    for (int i = 0; i < 4; ++i) {
      for (int j = i + 1; j < 4; ++j) {
        const auto e = sub(*v[i], *v[j]);
        shortest2 = std::min(shortest2, dot(e, e));
        int f[2], m = 0;
        for (int k = 0; k < 4; ++k)
          if (k != i && k != j) f[m++] = k;
        const double nn = std::sqrt(dot(n[f[0]], n[f[0]]) * dot(n[f[1]], n[f[1]]));
        if (nn == 0) continue;
        const double cosine = std::clamp(dot(n[f[0]], n[f[1]]) / nn, -1.0, 1.0);
        const double deg = (pi - std::acos(cosine)) * 180.0 / pi;
        min_dihedral_deg = std::min(min_dihedral_deg, deg);
        max_dihedral_deg = std::max(max_dihedral_deg, deg);
      }
    }
    // Circumradius from the standard closed form relative to vertex a.
    const auto ab = sub(b, a), ac = sub(c, a), ad = sub(d, a);
    const double det = 2.0 * dot(ab, cross(ac, ad));
    volume += std::abs(det) / 12.0;
    if (det != 0 && shortest2 > 0) {
      const auto t1 = cross(ac, ad), t2 = cross(ad, ab), t3 = cross(ab, ac);
      const double l1 = dot(ab, ab), l2 = dot(ac, ac), l3 = dot(ad, ad);
      const std::array<double, 3> o = {(l1 * t1[0] + l2 * t2[0] + l3 * t3[0]) / det,
                                       (l1 * t1[1] + l2 * t2[1] + l3 * t3[1]) / det,
                                       (l1 * t1[2] + l2 * t2[2] + l3 * t3[2]) / det};
      max_radius_edge = std::max(max_radius_edge, std::sqrt(dot(o, o) / shortest2));
    }
    ++tets;
  }
};

}  // namespace gdr_bench
