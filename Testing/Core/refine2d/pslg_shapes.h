// PSLG building blocks shared by the 2D core tests.
#pragma once
#include <cmath>
#include <random>
#include <vector>

#include "gdr/pslg.h"

namespace gdr_test {

constexpr double kPi = 3.14159265358979323846;

// A closed loop of segments through `pts`, appended to g.
inline void add_loop(gdr::Pslg& g, const std::vector<gdr::Point2>& pts) {
  const int base = static_cast<int>(g.points.size());
  const int n = static_cast<int>(pts.size());
  for (int i = 0; i < n; ++i) {
    g.points.push_back(pts[i]);
    g.segments.push_back({base + i, base + (i + 1) % n});
  }
}

inline std::vector<gdr::Point2> regular_polygon(int n, double r, double cx = 0, double cy = 0,
                                                double phase = 0) {
  std::vector<gdr::Point2> p;
  for (int i = 0; i < n; ++i)
    p.push_back({cx + r * std::cos(phase + 2 * kPi * i / n), cy + r * std::sin(phase + 2 * kPi * i / n)});
  return p;
}

// The axis-aligned rectangle [x0, x1] x [y0, y1], counter-clockwise.
inline std::vector<gdr::Point2> square(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

// One random segment per cell of an n x n grid of unit cells (seeded): many segments, no
// crossings by construction.
inline gdr::Pslg segments_in_cells(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  gdr::Pslg g;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = static_cast<int>(g.points.size());
      g.points.push_back({i + u(rng), j + u(rng)});
      g.points.push_back({i + u(rng), j + u(rng)});
      g.segments.push_back({a, a + 1});
    }
  return g;
}

// A map like a county map: an n x n grid of cells with corners moved at random, each
// border a polyline of m pieces whose inner vertices wander off the straight line (some a
// little, some 20 times less), the outer border straight. Planar by construction: the
// corners stay within 0.3 of the grid, the wander within 0.08 of the border's length.
inline gdr::Pslg wobbly_grid_map(int n, int m, unsigned seed) {
  std::mt19937 rng(seed);
  const auto u = [&rng](double lo, double hi) { return lo + (hi - lo) * (rng() / 4294967296.0); };
  gdr::Pslg g;
  std::vector<int> corner((n + 1) * (n + 1));
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double jx = (i == 0 || i == n) ? 0 : u(-0.3, 0.3);
      const double jy = (j == 0 || j == n) ? 0 : u(-0.3, 0.3);
      corner[i * (n + 1) + j] = static_cast<int>(g.points.size());
      g.points.push_back({i + jx, j + jy});
    }
  const auto border = [&](int a, int b, bool straight) {
    const gdr::Point2 p = g.points[a], q = g.points[b];
    const double nx = p.y - q.y, ny = q.x - p.x;
    int prev = a;
    for (int t = 1; t < m; ++t) {
      const double s = static_cast<double>(t) / m;
      const double amp = straight ? 0 : u(-0.08, 0.08) * (rng() % 3 == 0 ? 0.05 : 1.0);
      const int v = static_cast<int>(g.points.size());
      g.points.push_back({p.x + s * (q.x - p.x) + amp * nx, p.y + s * (q.y - p.y) + amp * ny});
      g.segments.push_back({prev, v});
      prev = v;
    }
    g.segments.push_back({prev, b});
  };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const int c = corner[i * (n + 1) + j];
      if (i < n) border(c, corner[(i + 1) * (n + 1) + j], j == 0 || j == n);
      if (j < n) border(c, corner[i * (n + 1) + j + 1], i == 0 || i == n);
    }
  return g;
}

}  // namespace gdr_test
