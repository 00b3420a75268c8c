// validate_surface: a triangulated surface as a 2-manifold (closed and consistently oriented
// when asked), without self-intersections (exact, cdt3d's triangle tests).
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <string>

#include "cdt3d/internal.h"
#include "gdr/validate.h"
#include "validate/conformity.h"
#include "validate/incidence.h"

namespace gdr {

ValidationReport validate_surface(const std::vector<Point3>& points,
                                  const std::vector<std::array<int, 3>>& triangles, bool closed,
                                  const ValidateOptions& options) {
  ValidationReport r;
  validate::Problems problems{r.problems, options.max_problems};
  const int np = static_cast<int>(points.size());
  auto text = [](const std::array<int, 3>& t) {
    return "(" + std::to_string(t[0]) + ", " + std::to_string(t[1]) + ", " + std::to_string(t[2]) + ")";
  };
  // Directed edges: a consistently oriented manifold uses each once, with its reverse once
  // (closed) or not at all (a boundary edge).
  std::map<std::pair<int, int>, int> directed;
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    const auto& t = triangles[i];
    bool ok = true;
    for (int v : t) ok = ok && v >= 0 && v < np;
    if (!ok) {
      ++r.invalid_indices;
      problems.add("triangle " + std::to_string(i) + " " + text(t) + " has a vertex index out of range");
      continue;
    }
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) {
      ++r.inverted_elements;
      problems.add("triangle " + std::to_string(i) + " " + text(t) + " repeats a vertex");
      continue;
    }
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  std::map<int, std::vector<std::pair<int, int>>> around;  // vertex -> its link edges
  for (const auto& t : triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
    for (int k = 0; k < 3; ++k) around[t[k]].push_back({t[(k + 1) % 3], t[(k + 2) % 3]});
  }
  for (const auto& [e, n] : directed) {
    const auto it = directed.find({e.second, e.first});
    const int back = it == directed.end() ? 0 : it->second;
    if (n > 1) {
      ++r.nonmanifold;
      problems.add("edge (" + std::to_string(e.first) + ", " + std::to_string(e.second) +
                   ") is used " + std::to_string(n) + " times in one direction (non-manifold or "
                   "inconsistently oriented)");
    } else if (back == 0 && closed) {
      ++r.boundary_errors;
      problems.add("edge (" + std::to_string(e.first) + ", " + std::to_string(e.second) +
                   ") has one triangle: the surface is not closed");
    }
  }
  // Each vertex's link must be one path or one cycle (no pinched vertices).
  for (auto& [v, link] : around) {
    std::map<int, int> next;
    for (const auto& [a, b] : link) next[a] = b;
    std::map<int, int> indegree;
    for (const auto& [a, b] : link) ++indegree[b];
    int start = link[0].first;
    for (const auto& [a, b] : link)
      if (!indegree.count(a)) start = a;  // a path starts where nothing enters
    std::size_t seen = 0;
    int x = start;
    while (seen <= link.size()) {
      const auto it = next.find(x);
      if (it == next.end()) break;
      x = it->second;
      ++seen;
      if (x == start) break;
    }
    if (seen != link.size()) {
      ++r.nonmanifold;
      problems.add("vertex " + std::to_string(v) + " is not manifold (its triangles form " +
                   "more than one fan)");
    }
  }
  std::vector<std::array<int, 2>> pairs;
  std::vector<std::array<int, 3>> good;
  for (const auto& t : triangles)
    if (t[0] != t[1] && t[1] != t[2] && t[0] != t[2] && t[0] >= 0 && t[1] >= 0 && t[2] >= 0 &&
        t[0] < np && t[1] < np && t[2] < np)
      good.push_back(t);
  const long long clashes = cdt3d::find_clashing_triangles(points, good, 5, pairs);
  if (clashes) {
    r.boundary_errors += static_cast<std::size_t>(clashes);
    for (const auto& p : pairs)
      problems.add("triangles " + text(good[p[0]]) + " and " + text(good[p[1]]) + " intersect");
  }
  // Quality as the summary prints it: plane angles and radius-edge ratios of the triangles.
  QualityStats& q = r.quality;
  q.elements = triangles.size();
  q.min_angle_deg = good.empty() ? 0 : 180;
  for (const auto& t : good) {
    const Point3 p[3] = {points[t[0]], points[t[1]], points[t[2]]};
    double edge[3], area2 = 0;
    for (int k = 0; k < 3; ++k) {  // the angle at corner k, between the edges to the others
      const Point3 &o = p[k], &x = p[(k + 1) % 3], &y = p[(k + 2) % 3];
      const double u[3] = {x.x - o.x, x.y - o.y, x.z - o.z}, v[3] = {y.x - o.x, y.y - o.y, y.z - o.z};
      const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      const double cross = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const double angle = std::atan2(cross, u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) * 180 / 3.14159265358979323846;
      q.min_angle_deg = std::min(q.min_angle_deg, angle);
      q.max_angle_deg = std::max(q.max_angle_deg, angle);
      edge[k] = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
      if (k == 0) area2 = cross;
    }
    q.total_measure += 0.5 * area2;
    const double shortest = std::min({edge[0], edge[1], edge[2]});
    const double ratio = area2 > 0 && shortest > 0 ? edge[0] * edge[1] * edge[2] / (2 * area2) / shortest : 1e300;
    q.max_radius_edge = std::max(q.max_radius_edge, ratio);
    q.mean_radius_edge += ratio / static_cast<double>(good.size());
  }
  r.valid = r.invalid_indices == 0 && r.inverted_elements == 0 && r.nonmanifold == 0 && r.boundary_errors == 0;
  return r;
}

ValidationReport validate_surface_features(const std::vector<Point3>& points,
                                           const std::vector<std::array<int, 3>>& triangles,
                                           const std::vector<std::array<int, 2>>& subsegments,
                                           const std::vector<std::array<int, 2>>& features,
                                           const ValidateOptions& options) {
  ValidationReport r;
  validate::Problems problems{r.problems, options.max_problems};
  const int np = static_cast<int>(points.size());
  auto in_range = [&](const std::array<int, 2>& e) { return e[0] >= 0 && e[1] >= 0 && e[0] < np && e[1] < np; };
  std::set<std::pair<int, int>> edges;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
  for (const auto& s : subsegments)
    if (!in_range(s) || !edges.count(std::minmax(s[0], s[1]))) {
      ++r.invalid_subsegments;
      problems.add("subsegment (" + std::to_string(s[0]) + ", " + std::to_string(s[1]) + ") is not a surface edge");
    }
  const validate::SubsegmentGraph graph(points.size(), subsegments);
  const double slack = validate::coordinate_slack(points);
  for (std::size_t i = 0; i < features.size(); ++i) {
    const auto& f = features[i];
    if (in_range(f) && validate::follow_segment(points, graph, f[0], f[1], options.segment_tolerance, slack)) continue;
    ++r.missing_segments;
    problems.add("feature " + std::to_string(i) + " (" + std::to_string(f[0]) + ", " + std::to_string(f[1]) +
                 ") is not a chain of subsegments");
  }
  r.valid = r.invalid_subsegments == 0 && r.missing_segments == 0;
  return r;
}

}  // namespace gdr
