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

}  // namespace gdr_test
