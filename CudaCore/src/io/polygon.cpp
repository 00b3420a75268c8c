// Ear clipping of facet polygons (TetGen facets, OFF faces) in the polygon's own plane.
#include <cmath>

#include "io/text_file.h"
#include "predicates/predicates.h"

namespace gdr::io {

bool triangulate_polygon(const std::vector<Point3>& points, const std::vector<int>& polygon,
                         std::vector<std::array<int, 3>>& triangles) {
  std::vector<int> ring;
  for (int v : polygon)
    if (ring.empty() || ring.back() != v) ring.push_back(v);
  while (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
  if (ring.size() < 3) return false;
  if (ring.size() == 3) {
    triangles.push_back({ring[0], ring[1], ring[2]});
    return true;
  }

  // Newell's normal picks the projection plane; dropping a coordinate keeps the
  // projected coordinates exact, so the exact orient2d decides convexity.
  double n[3] = {0, 0, 0};
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const Point3& a = points[ring[i]];
    const Point3& b = points[ring[(i + 1) % ring.size()]];
    n[0] += (a.y - b.y) * (a.z + b.z);
    n[1] += (a.z - b.z) * (a.x + b.x);
    n[2] += (a.x - b.x) * (a.y + b.y);
  }
  int k = 0;
  if (std::fabs(n[1]) > std::fabs(n[k])) k = 1;
  if (std::fabs(n[2]) > std::fabs(n[k])) k = 2;
  if (n[k] == 0) return false;
  const int ax = (k + 1) % 3, ay = (k + 2) % 3;
  const double sign = n[k] > 0 ? 1.0 : -1.0;
  auto proj = [&](int v, double out[2]) {
    const double c[3] = {points[v].x, points[v].y, points[v].z};
    out[0] = c[ax];
    out[1] = c[ay];
  };
  auto orient = [&](int a, int b, int c) {
    double pa[2], pb[2], pc[2];
    proj(a, pa);
    proj(b, pb);
    proj(c, pc);
    return sign * pred::orient2d(pa, pb, pc);
  };
  auto same = [&](int a, int b) {
    return points[a].x == points[b].x && points[a].y == points[b].y && points[a].z == points[b].z;
  };

  std::size_t i = 0, since_clip = 0;
  while (ring.size() > 3) {
    if (since_clip > ring.size()) return false;  // no ear left: not a simple polygon
    const std::size_t m = ring.size();
    const int p = ring[(i + m - 1) % m], v = ring[i % m], q = ring[(i + 1) % m];
    bool ear = orient(p, v, q) > 0;
    for (std::size_t j = 0; ear && j < m; ++j) {
      const int w = ring[j];
      if (w == p || w == v || w == q || same(w, p) || same(w, v) || same(w, q)) continue;
      ear = !(orient(p, v, w) >= 0 && orient(v, q, w) >= 0 && orient(q, p, w) >= 0);
    }
    if (ear) {
      triangles.push_back({p, v, q});
      ring.erase(ring.begin() + static_cast<std::ptrdiff_t>(i % m));
      i = (i + ring.size() - 1) % ring.size();
      since_clip = 0;
    } else {
      i = (i + 1) % m;
      ++since_clip;
    }
  }
  if (orient(ring[0], ring[1], ring[2]) <= 0) return false;
  triangles.push_back({ring[0], ring[1], ring[2]});
  return true;
}

}  // namespace gdr::io
