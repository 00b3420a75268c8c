// triangles_clash against an independent exact oracle: CGAL's triangle/triangle intersection
// with exact constructions (Epeck), on random triangles over a tiny integer grid, where
// coplanar, collinear and touching configurations are the rule rather than the exception.
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>

#include <random>

#include "cdt3d/geometry.h"

namespace {

using K = CGAL::Exact_predicates_exact_constructions_kernel;

// The oracle: the triangles meet in more than the convex hull of their shared vertices.
bool oracle(const std::vector<gdr::Point3>& p, const std::array<int, 3>& t1, const std::array<int, 3>& t2) {
  auto P = [&](int v) { return K::Point_3(p[v].x, p[v].y, p[v].z); };
  const K::Triangle_3 a(P(t1[0]), P(t1[1]), P(t1[2])), b(P(t2[0]), P(t2[1]), P(t2[2]));
  const auto hit = CGAL::intersection(a, b);
  if (!hit) return false;
  std::vector<K::Point_3> shared;
  for (int i : t1)
    for (int j : t2)
      if (i == j) shared.push_back(P(i));
  // Is x in the hull of the shared vertices (empty, a point or a segment)?
  auto in_shared = [&](const K::Point_3& x) {
    if (shared.size() == 1) return x == shared[0];
    if (shared.size() == 2) return K::Segment_3(shared[0], shared[1]).has_on(x);
    return false;
  };
  if (const K::Point_3* x = boost::get<K::Point_3>(&*hit)) return !in_shared(*x);
  if (const K::Segment_3* s = boost::get<K::Segment_3>(&*hit)) return !(in_shared(s->source()) && in_shared(s->target()));
  return true;  // a triangle or a polygon: more than a vertex or an edge
}

TEST(TriangleClash, AgreesWithCgalOnRandomDegenerateTriangles) {
  std::mt19937 rng(12345);
  std::uniform_int_distribution<int> coord(0, 3);
  std::vector<gdr::Point3> p;
  for (int i = 0; i < 24; ++i) p.push_back({double(coord(rng)), double(coord(rng)), double(coord(rng))});
  std::uniform_int_distribution<int> vertex(0, static_cast<int>(p.size()) - 1);
  auto random_triangle = [&] {
    for (;;) {
      std::array<int, 3> t = {vertex(rng), vertex(rng), vertex(rng)};
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
      if (gdr::cdt3d::geom::projection_axis(p[t[0]], p[t[1]], p[t[2]]) < 0) continue;  // collinear
      return t;
    }
  };
  int cases = 0, clashes = 0, mismatches = 0;
  int by_shared[3] = {0, 0, 0};
  for (int n = 0; n < 60000; ++n) {
    std::array<int, 3> t1 = random_triangle(), t2 = random_triangle();
    // Often make them share one or two vertices.
    if (n % 3 == 1) t2[0] = t1[n % 2];
    if (n % 3 == 2) {
      t2[0] = t1[0];
      t2[1] = t1[1];
    }
    if (t2[0] == t2[1] || t2[1] == t2[2] || t2[0] == t2[2]) continue;
    if (gdr::cdt3d::geom::projection_axis(p[t2[0]], p[t2[1]], p[t2[2]]) < 0) continue;
    std::array<int, 3> s1 = t1, s2 = t2;
    std::sort(s1.begin(), s1.end());
    std::sort(s2.begin(), s2.end());
    if (s1 == s2) continue;
    int shared = 0;
    for (int i : t1)
      for (int j : t2) shared += i == j;
    const bool expect = oracle(p, t1, t2);
    const bool got = gdr::cdt3d::geom::triangles_clash(p, t1, t2);
    ++cases;
    clashes += expect;
    ++by_shared[shared];
    if (got != expect && ++mismatches <= 5)
      ADD_FAILURE() << "triangles (" << t1[0] << " " << t1[1] << " " << t1[2] << ") and (" << t2[0] << " "
                    << t2[1] << " " << t2[2] << "): got " << got << ", CGAL says " << expect;
  }
  EXPECT_EQ(mismatches, 0);
  EXPECT_GT(clashes, cases / 20);  // both answers are well represented
  EXPECT_GT(by_shared[1], 1000);
  EXPECT_GT(by_shared[2], 1000);
  std::printf("%d cases (%d, %d, %d sharing 0, 1, 2 vertices), %d clashes\n", cases, by_shared[0], by_shared[1],
              by_shared[2], clashes);
}

}  // namespace
