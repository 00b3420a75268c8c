// Holes given by polygon orientation (vtkDelaunay2D's convention): among the polygons of a
// PSLG, counter-clockwise ones bound the domain and clockwise ones bound holes. Each hole
// gets a seed point strictly inside it, in the face of the segment arrangement that touches
// the polygon from inside (an island inside the hole keeps its own mesh).
#include <algorithm>
#include <cmath>

#include "gdr/refine2d.h"
#include "predicates/predicates.h"

namespace gdr {
namespace {

const double* xy(const Pslg& g, int v) { return &g.points[v].x; }

// The sign of the polygon's area, exactly: the orientation at its lowest (then leftmost)
// vertex, where the polygon is convex. 0: degenerate there.
int orientation(const Pslg& g, const std::vector<int>& ring) {
  std::size_t lo = 0;
  for (std::size_t i = 1; i < ring.size(); ++i) {
    const Point2 &p = g.points[ring[i]], &q = g.points[ring[lo]];
    if (p.y < q.y || (p.y == q.y && p.x < q.x)) lo = i;
  }
  const std::size_t n = ring.size();
  const double o = pred::orient2d(xy(g, ring[(lo + n - 1) % n]), xy(g, ring[lo]), xy(g, ring[(lo + 1) % n]));
  return (o > 0) - (o < 0);
}

// Exact: is p strictly inside the ring (crossing number; on an edge counts as not inside)?
bool strictly_inside(const Pslg& g, const std::vector<int>& ring, const double* p) {
  bool inside = false;
  for (std::size_t i = 0; i < ring.size(); ++i) {
    const double* a = xy(g, ring[i]);
    const double* b = xy(g, ring[(i + 1) % ring.size()]);
    const double o = pred::orient2d(a, b, p);
    if (o == 0 && std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
        std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]))
      return false;
    if ((a[1] <= p[1]) != (b[1] <= p[1]) && ((o > 0) == (b[1] > a[1]))) inside = !inside;
  }
  return inside;
}

bool on_segment(const Pslg& g, const double* p) {
  for (const auto& s : g.segments) {
    const double* a = xy(g, s[0]);
    const double* b = xy(g, s[1]);
    if (pred::orient2d(a, b, p) == 0 && std::min(a[0], b[0]) <= p[0] && p[0] <= std::max(a[0], b[0]) &&
        std::min(a[1], b[1]) <= p[1] && p[1] <= std::max(a[1], b[1]))
      return true;
  }
  return false;
}

// x where segment ab crosses the horizontal line y (a, b on opposite sides of it).
double crossing_x(const Point2& a, const Point2& b, double y) {
  return a.x + (y - a.y) * (b.x - a.x) / (b.y - a.y);
}

// A seed inside the ring next to its leftmost crossing of a horizontal line through the
// widest gap between its vertices' heights: between that crossing and the next crossing of
// any segment to its right. Other gaps are tried when rounding defeats the first.
bool seed_inside(const Pslg& g, const std::vector<int>& ring, Point2& seed) {
  std::vector<double> ys;
  for (int v : ring) ys.push_back(g.points[v].y);
  std::sort(ys.begin(), ys.end());
  ys.erase(std::unique(ys.begin(), ys.end()), ys.end());
  std::vector<std::pair<double, double>> gaps;  // (width, middle)
  for (std::size_t i = 0; i + 1 < ys.size(); ++i) gaps.push_back({ys[i + 1] - ys[i], 0.5 * (ys[i] + ys[i + 1])});
  std::sort(gaps.rbegin(), gaps.rend());
  for (std::size_t k = 0; k < gaps.size() && k < 8; ++k) {
    const double y = gaps[k].second;
    double x1 = INFINITY;
    for (std::size_t i = 0; i < ring.size(); ++i) {
      const Point2 &a = g.points[ring[i]], &b = g.points[ring[(i + 1) % ring.size()]];
      if ((a.y < y) != (b.y < y)) x1 = std::min(x1, crossing_x(a, b, y));
    }
    double x2 = INFINITY;
    for (const auto& s : g.segments) {
      const Point2 &a = g.points[s[0]], &b = g.points[s[1]];
      if ((a.y < y) == (b.y < y)) continue;
      const double x = crossing_x(a, b, y);
      if (x > x1) x2 = std::min(x2, x);
    }
    if (!std::isfinite(x1) || !std::isfinite(x2)) continue;
    const double p[2] = {0.5 * (x1 + x2), y};
    if (strictly_inside(g, ring, p) && !on_segment(g, p)) {
      seed = {p[0], p[1]};
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<Point2> clockwise_polygon_holes(const Pslg& pslg, const std::vector<std::vector<int>>& polygons,
                                            int* unseeded) {
  std::vector<int> sign(polygons.size());
  bool any_ccw = false;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    sign[i] = polygons[i].size() >= 3 ? orientation(pslg, polygons[i]) : 0;
    any_ccw = any_ccw || sign[i] > 0;
  }
  std::vector<Point2> holes;
  if (unseeded) *unseeded = 0;
  if (!any_ccw) return holes;
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    if (sign[i] >= 0) continue;
    Point2 seed;
    if (seed_inside(pslg, polygons[i], seed)) holes.push_back(seed);
    else if (unseeded) ++*unseeded;
  }
  return holes;
}

}  // namespace gdr
