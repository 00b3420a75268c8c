// Small 3D vector arithmetic for the validators' quality measures (not for topology).
#pragma once
#include <cmath>

#include "gdr/pslg.h"

namespace gdr::detail {

struct V3 {
  double x, y, z;
};
inline V3 sub(const Point3& a, const Point3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V3 cross(const V3& a, const V3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double dot(const V3& a, const V3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline double norm(const V3& a) { return std::sqrt(dot(a, a)); }

}  // namespace gdr::detail
