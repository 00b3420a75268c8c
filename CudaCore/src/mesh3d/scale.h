// Exact rescaling of a 3D input by a power of two, shared by the 3D meshers' facades.
#pragma once
#include <algorithm>
#include <cmath>

#include "gdr/pslg.h"

namespace gdr::m3d {

// The input is multiplied by a power of two that brings its largest coordinate into [1, 2),
// so that the predicates' expansions neither overflow nor underflow whatever units the input
// uses (multiplying by 2^k is exact), and the output is scaled back.
struct PowerOfTwoScale {
  int k = 0;
  explicit PowerOfTwoScale(const Surface& s) {
    double m = 0;
    for (const Point3& p : s.points)
      m = std::max({m, std::fabs(p.x), std::fabs(p.y), std::fabs(p.z)});
    if (m > 0 && std::isfinite(m)) k = -std::ilogb(m);
  }
  Point3 apply(const Point3& p, int sign) const {
    return {std::ldexp(p.x, sign * k), std::ldexp(p.y, sign * k), std::ldexp(p.z, sign * k)};
  }
  double length(double v, int sign) const { return std::ldexp(v, sign * k); }
  double area(double v, int sign) const { return std::ldexp(v, 2 * sign * k); }
  double volume(double v, int sign) const { return std::ldexp(v, 3 * sign * k); }
  Surface scaled(const Surface& s) const {
    Surface out = s;
    for (Point3& p : out.points) p = apply(p, 1);
    for (Point3& p : out.holes) p = apply(p, 1);
    for (RegionSeed& r : out.regions) {
      r.point = apply(r.point, 1);
      r.max_volume = volume(r.max_volume, 1);
    }
    return out;
  }
};

}  // namespace gdr::m3d
