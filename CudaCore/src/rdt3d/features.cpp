#include "rdt3d/features.h"

#include <algorithm>
#include <cmath>

#include "cdt3d/internal.h"

namespace gdr::rdt3d {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Vec {
  double x, y, z;
};
Vec sub(const Point3& a, const Point3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Vec cross(const Vec& u, const Vec& v) { return {u.y * v.z - u.z * v.y, u.z * v.x - u.x * v.z, u.x * v.y - u.y * v.x}; }
double dot(const Vec& u, const Vec& v) { return u.x * v.x + u.y * v.y + u.z * v.z; }
Vec scaled(const Vec& u, double s) { return {s * u.x, s * u.y, s * u.z}; }

// The angle between u and v in degrees: a classification by the user's threshold, not a
// topological decision.
double angle_deg(const Vec& u, const Vec& v) {
  const Vec w = cross(u, v);
  return std::atan2(std::sqrt(dot(w, w)), dot(u, v)) * 180 / kPi;
}

// The normal of triangle t, turned as if t ran along the edge a -> b (two triangles of a
// consistently oriented surface run along their shared edge in opposite directions).
Vec normal_along(const cdt3d::Plc& plc, const std::array<int, 3>& t, int a, int b) {
  const Vec n = cross(sub(plc.points[t[1]], plc.points[t[0]]), sub(plc.points[t[2]], plc.points[t[0]]));
  const int k = static_cast<int>(std::find(t.begin(), t.end(), a) - t.begin());
  return t[(k + 1) % 3] == b ? n : scaled(n, -1);
}

}  // namespace

Features find_features(const cdt3d::Plc& plc, const std::vector<std::array<int, 2>>& input_segments,
                       double feature_angle_deg) {
  Features f;
  f.edges = input_segments;
  for (auto& e : f.edges)
    if (e[0] > e[1]) std::swap(e[0], e[1]);
  if (feature_angle_deg > 0) {
    if (!plc.edges) throw Error(Status::InternalError, "feature search: the surface check kept no edge table");
    const cdt3d::EdgeTable& table = *plc.edges;
    for (int k = 0; k < table.size(); ++k) {
      const auto [a, b] = table.edge[k];
      bool sharp = table.count(k) != 2;  // a boundary edge (an edge of 3+ is refused before)
      if (!sharp) {
        const auto& t1 = plc.triangles[table.tri[table.start[k]]];
        const auto& t2 = plc.triangles[table.tri[table.start[k] + 1]];
        sharp = angle_deg(normal_along(plc, t1, a, b), normal_along(plc, t2, b, a)) > feature_angle_deg;
      }
      if (sharp) f.edges.push_back({a, b});
    }
  }
  std::sort(f.edges.begin(), f.edges.end());
  f.edges.erase(std::unique(f.edges.begin(), f.edges.end()), f.edges.end());

  // Corners: polyline ends and branches, and vertices where a polyline turns sharply.
  const std::size_t np = plc.points.size();
  std::vector<std::vector<int>> next(np);
  for (const auto& e : f.edges) {
    next[e[0]].push_back(e[1]);
    next[e[1]].push_back(e[0]);
  }
  f.kind.assign(np, kNotFeature);
  for (std::size_t v = 0; v < np; ++v) {
    if (next[v].empty()) continue;
    bool corner = next[v].size() != 2;
    if (!corner) {
      const Point3& p = plc.points[v];
      corner = angle_deg(sub(p, plc.points[next[v][0]]), sub(plc.points[next[v][1]], p)) > feature_angle_deg;
    }
    f.kind[v] = corner ? kCorner : kOnFeature;
    f.corners += corner;
  }
  return f;
}

}  // namespace gdr::rdt3d
