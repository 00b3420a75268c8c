// Small hand-made surfaces for the cdt3d tests.
#pragma once
#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "gdr/pslg.h"

namespace gdr::test {

// Appends an axis-aligned box [lo, hi] as 12 outward triangles (two per face).
inline void add_box(Surface& s, Point3 lo, Point3 hi) {
  const int b = static_cast<int>(s.points.size());
  for (int i = 0; i < 8; ++i)
    s.points.push_back({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  // Corner i has bits (x, y, z). Each face as a quad, counter-clockwise from outside.
  const int quads[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4},
                           {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};
  for (const auto& q : quads) {
    s.triangles.push_back({b + q[0], b + q[1], b + q[2]});
    s.triangles.push_back({b + q[0], b + q[2], b + q[3]});
  }
}

inline Surface unit_cube() {
  Surface s;
  add_box(s, {0, 0, 0}, {1, 1, 1});
  return s;
}

// The box [0,2] x [0,1] x [0,1] cut by the internal facet x = 1 (a square, two triangles)
// into two unit cubes: 12 points, 20 boundary triangles and 2 internal ones.
inline Surface split_box() {
  Surface s;
  for (int i = 0; i < 12; ++i) s.points.push_back({double(i % 3), double((i / 3) % 2), double(i / 6)});
  auto id = [](int x, int y, int z) { return x + 3 * y + 6 * z; };
  auto quad = [&](int a, int b, int c, int d) {
    s.triangles.push_back({a, b, c});
    s.triangles.push_back({a, c, d});
  };
  for (int x = 0; x < 2; ++x) {
    quad(id(x, 0, 0), id(x, 1, 0), id(x + 1, 1, 0), id(x + 1, 0, 0));  // bottom
    quad(id(x, 0, 1), id(x + 1, 0, 1), id(x + 1, 1, 1), id(x, 1, 1));  // top
    quad(id(x, 0, 0), id(x + 1, 0, 0), id(x + 1, 0, 1), id(x, 0, 1));  // front (y = 0)
    quad(id(x, 1, 0), id(x, 1, 1), id(x + 1, 1, 1), id(x + 1, 1, 0));  // back (y = 1)
  }
  quad(id(0, 0, 0), id(0, 0, 1), id(0, 1, 1), id(0, 1, 0));  // x = 0
  quad(id(2, 0, 0), id(2, 1, 0), id(2, 1, 1), id(2, 0, 1));  // x = 2
  quad(id(1, 0, 0), id(1, 1, 0), id(1, 1, 1), id(1, 0, 1));  // internal, x = 1
  return s;
}

// The unit cube with its top face cut into a fan of skinny triangles whose far corners are
// lifted by up to 4e-5 (for n = 8, 14 of their 15 inner edges are not flat, but within 0.06
// degrees of it), `n` triangles along each of the two far edges. The faces x = 1 and y = 1 take the
// lifted corners as fans from their bottom corners and stay exactly planar. The volume is
// 1 plus the little the lifts add.
inline Surface cube_with_rough_top(int n) {
  Surface s;
  auto point = [&](double x, double y, double z) {
    s.points.push_back({x, y, z});
    return static_cast<int>(s.points.size()) - 1;
  };
  const int b00 = point(0, 0, 0), b10 = point(1, 0, 0), b11 = point(1, 1, 0), b01 = point(0, 1, 0);
  const int t00 = point(0, 0, 1), t10 = point(1, 0, 1), t11 = point(1, 1, 1), t01 = point(0, 1, 1);
  auto lift = [](int k) { return 1 + 4e-5 * (((k * 7) % 5) - 2) / 2.0; };
  std::vector<int> along_x1 = {t10}, along_y1 = {t11};  // far edges, away from t00's corner
  for (int k = 1; k < n; ++k) along_x1.push_back(point(1, double(k) / n, lift(k)));
  along_x1.push_back(t11);
  for (int k = 1; k < n; ++k) along_y1.push_back(point(1 - double(k) / n, 1, lift(k + n)));
  along_y1.push_back(t01);
  auto tri = [&](int a, int b, int c) { s.triangles.push_back({a, b, c}); };
  tri(b00, b01, b11), tri(b00, b11, b10);  // bottom
  tri(b00, b10, t10), tri(b00, t10, t00);  // y = 0
  tri(b00, t00, t01), tri(b00, t01, b01);  // x = 0
  for (int k = 0; k < n; ++k) {
    tri(t00, along_x1[k], along_x1[k + 1]);  // top
    tri(t00, along_y1[k], along_y1[k + 1]);
    tri(b10, along_x1[k + 1], along_x1[k]);  // x = 1
    tri(b11, along_y1[k + 1], along_y1[k]);  // y = 1
  }
  tri(b10, b11, t11);
  tri(b11, b01, t01);
  return s;
}

// A prism over a regular n-gon of radius 1 (height 1): its n sides turn 360/n degrees from
// one to the next.
inline Surface polygon_prism(int n) {
  Surface s;
  for (int z = 0; z < 2; ++z)
    for (int k = 0; k < n; ++k) {
      const double a = 2 * 3.14159265358979323846 * k / n;
      s.points.push_back({std::cos(a), std::sin(a), double(z)});
    }
  for (int k = 0; k < n; ++k) {
    const int j = (k + 1) % n;
    s.triangles.push_back({k, j, n + j});
    s.triangles.push_back({k, n + j, n + k});
  }
  for (int k = 1; k + 1 < n; ++k) {
    s.triangles.push_back({0, k + 1, k});
    s.triangles.push_back({n, n + k, n + k + 1});
  }
  return s;
}

// A sphere of radius r around c: an icosahedron subdivided `levels` times (20 * 4^levels
// triangles), outward.
inline Surface icosphere(int levels, double r = 1, Point3 c = {0, 0, 0}) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<std::array<double, 3>> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0},
                                          {0, -1, t}, {0, 1, t}, {0, -1, -t}, {0, 1, -t},
                                          {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  auto normalize = [](std::array<double, 3> p) {
    const double n = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{p[0] / n, p[1] / n, p[2] / n};
  };
  for (auto& p : v) p = normalize(p);
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(normalize({v[a][0] + v[b][0], v[a][1] + v[b][1], v[a][2] + v[b][2]}));
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> g;
    g.reserve(4 * f.size());
    for (const auto& tri : f) {
      const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      g.push_back({tri[0], a, c});
      g.push_back({tri[1], b, a});
      g.push_back({tri[2], c, b});
      g.push_back({a, b, c});
    }
    f.swap(g);
  }
  Surface s;
  for (const auto& p : v) s.points.push_back({c.x + r * p[0], c.y + r * p[1], c.z + r * p[2]});
  s.triangles = f;
  return s;
}

// A part turned on a lathe with a polygonal bore: `sectors` faces around, the bundled
// bushing's profile with the hub `height` tall, coordinates rounded to 9 decimals as
// make_bushing.py does (32 sectors, height 1.2: apps/gdr/examples/bushing.off). Closed,
// outward-facing.
inline Surface turned_bushing(int sectors, double height) {
  const double profile[7][2] = {{0.5, 0.0}, {2.0, 0.0}, {2.0, 0.3}, {1.0, 0.3},
                                {1.0, height - 0.1}, {0.9, height}, {0.5, height}};
  Surface s;
  for (const auto& rz : profile)
    for (int k = 0; k < sectors; ++k) {
      const double a = 2 * 3.14159265358979323846 * k / sectors;
      const auto nine = [](double v) { return std::round(v * 1e9) / 1e9; };  // as make_bushing.py
      s.points.push_back({nine(rz[0] * std::cos(a)), nine(rz[0] * std::sin(a)), rz[1]});
    }
  for (int i = 0; i < 7; ++i) {
    const int j = (i + 1) % 7;
    for (int k = 0; k < sectors; ++k) {
      const int t = (k + 1) % sectors;
      const int a = i * sectors + k, b = i * sectors + t, c = j * sectors + t, d = j * sectors + k;
      s.triangles.push_back({a, c, d});
      s.triangles.push_back({a, b, c});
    }
  }
  return s;
}

// Appends surface b to a (renumbering b's vertices).
inline void append(Surface& a, const Surface& b) {
  const int n = static_cast<int>(a.points.size());
  a.points.insert(a.points.end(), b.points.begin(), b.points.end());
  for (const auto& t : b.triangles) a.triangles.push_back({t[0] + n, t[1] + n, t[2] + n});
}

}  // namespace gdr::test
