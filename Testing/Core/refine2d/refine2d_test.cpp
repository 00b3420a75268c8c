// gDP2d end to end, on every backend: each mesh is checked by the validators (valid
// triangulation, input points and segments present, constrained Delaunay by exact
// predicates) and against the quality bound with its reported small-angle exceptions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>

#include <unistd.h>

#include "gdr/backend.h"
#include "gdr/io.h"
#include "gdr/refine2d.h"
#include "gdr/validate.h"
#include "on_backend.h"
#include "pslg_shapes.h"

namespace {

using gdr::Backend;
using gdr::Point2;
using gdr::Pslg;
using gdr_test::add_loop;
using gdr_test::kPi;
using gdr_test::regular_polygon;
using gdr_test::square;
using gdr_test::wobbly_grid_map;

// Subsegments whose reported input segment does not hold both their endpoints (split points
// are rounded, so "on" is up to a relative 1e-9; this checks labels, not topology).
int mislabelled_subsegments(const gdr::TriMesh& m, const Pslg& g) {
  int bad = 0;
  for (std::size_t k = 0; k < m.subsegments.size(); ++k) {
    const int s = m.subsegment_source[k];
    if (s < 0) continue;
    if (s >= static_cast<int>(g.segments.size())) {
      ++bad;
      continue;
    }
    const Point2 a = g.points[g.segments[s][0]], b = g.points[g.segments[s][1]];
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    for (int v : m.subsegments[k]) {
      const Point2 p = m.points[v];
      const double cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
      const double along = ((p.x - a.x) * (b.x - a.x) + (p.y - a.y) * (b.y - a.y)) / (len * len);
      if (std::fabs(cross) > 1e-9 * len * len || along < -1e-9 || along > 1 + 1e-9) ++bad;
    }
  }
  return bad;
}

class Refine2d : public gdr::test::OnBackend {
 protected:
  gdr::Refine2dOptions options() const {
    gdr::Refine2dOptions o;
    o.backend = GetParam();
    return o;
  }

  // mesh() with the design strategies `disabled` switched off (GDR_DISABLE).
  gdr::Refine2dResult mesh_without(const char* disabled, const Pslg& g, const gdr::Refine2dOptions& o) {
    setenv("GDR_DISABLE", disabled, 1);
    gdr::Refine2dResult r = mesh(g, o);
    unsetenv("GDR_DISABLE");
    return r;
  }

  // Meshes and validates; returns the result for further checks.
  gdr::Refine2dResult mesh(const Pslg& g, gdr::Refine2dOptions o, bool check_input = true) {
    o.backend = GetParam();
    gdr::Refine2dResult r = gdr::refine_2d(g, o);
    gdr::ValidateOptions vo;
    // The engine's bound is sin^2 of the angle in doubles (sin 30 degrees rounds below 1/2):
    // a triangle an ulp from the bound may fall either side of the validator's degrees.
    vo.min_angle_deg = o.refine ? o.min_angle * (1 - 1e-12) : 0;
    const gdr::ValidationReport rep = gdr::validate_trimesh(r.mesh, check_input ? &g : nullptr, vo);
    EXPECT_TRUE(rep.valid) << rep.summary();
    EXPECT_EQ(rep.inverted_elements, 0u);
    EXPECT_EQ(rep.nonmanifold, 0u);
    EXPECT_EQ(rep.missing_points, 0u);
    EXPECT_EQ(rep.missing_segments, 0u);
    EXPECT_EQ(rep.non_delaunay, 0u);
    if (check_input) EXPECT_EQ(mislabelled_subsegments(r.mesh, g), 0);
    const auto& s = r.stats;
    EXPECT_EQ(s.output_triangles, static_cast<long long>(r.mesh.triangles.size()));
    EXPECT_EQ(s.output_points, static_cast<long long>(r.mesh.points.size()));
    // The smallest angle is measured by the engine (on the device for the GPU backend).
    if (!r.mesh.triangles.empty()) EXPECT_NEAR(s.min_angle_deg, rep.quality.min_angle_deg, 1e-6);
    if (o.refine && !s.steiner_cap_reached) {
      EXPECT_FALSE(s.stalled);
      // The bound holds except where the small-input-angle rule protected a triangle.
      EXPECT_EQ(s.bad_triangles, s.small_angle_bad);
      EXPECT_LE(rep.quality.bad_elements, static_cast<std::size_t>(s.bad_triangles));
    }
    return r;
  }
};

TEST_P(Refine2d, SquareMeetsAngleBound) {
  Pslg g;
  add_loop(g, square(0, 0, 1, 1));
  g.points.push_back({0.3, 0.31});
  auto o = options();
  o.min_angle = 30;
  auto r = mesh(g, o);
  EXPECT_EQ(r.stats.bad_triangles, 0);
  EXPECT_GE(r.stats.min_angle_deg, 30.0 - 1e-9);
}

TEST_P(Refine2d, CdtOnlyAddsNoPoints) {
  Pslg g;
  add_loop(g, regular_polygon(7, 1.0));
  auto o = options();
  o.refine = false;
  auto r = mesh(g, o);
  EXPECT_EQ(r.stats.steiner_points, 0);
  EXPECT_EQ(r.mesh.triangles.size(), 5u);
}

TEST_P(Refine2d, EdgeAndAreaBounds) {
  Pslg g;
  add_loop(g, square(0, 0, 10, 10));
  auto o = options();
  o.max_edge_length = 0.5;
  auto r = mesh(g, o);
  for (const auto& t : r.mesh.triangles)
    for (int i = 0; i < 3; ++i) {
      const Point2 &a = r.mesh.points[t[i]], &b = r.mesh.points[t[(i + 1) % 3]];
      ASSERT_LE(std::hypot(a.x - b.x, a.y - b.y), 0.5 * (1 + 1e-12));
    }
  o.max_edge_length = 0;
  o.max_area = 0.01;
  r = mesh(g, o);
  for (const auto& t : r.mesh.triangles)
    ASSERT_LE(gdr::triangle_area(r.mesh.points[t[0]], r.mesh.points[t[1]], r.mesh.points[t[2]]),
              0.01 * (1 + 1e-12));
}

TEST_P(Refine2d, PolygonWithHoleKeepsOnlyTheDomain) {
  Pslg g;
  add_loop(g, square(0, 0, 4, 4));
  add_loop(g, square(1, 1, 2, 3));
  g.holes.push_back({1.5, 2});
  auto o = options();
  o.remove_exterior = true;
  o.max_area = 0.05;
  auto r = mesh(g, o);
  double area = 0;
  for (const auto& t : r.mesh.triangles) {
    const Point2 &a = r.mesh.points[t[0]], &b = r.mesh.points[t[1]], &c = r.mesh.points[t[2]];
    area += gdr::triangle_area(a, b, c);
    const double cx = (a.x + b.x + c.x) / 3, cy = (a.y + b.y + c.y) / 3;
    ASSERT_FALSE(cx > 1 && cx < 2 && cy > 1 && cy < 3) << "triangle inside the hole";
  }
  EXPECT_NEAR(area, 16.0 - 2.0, 1e-9);
}

TEST_P(Refine2d, ExteriorOfConcavePolygonRemoved) {
  Pslg g;  // an L shape: its convex hull has a notch the mesh must not fill
  add_loop(g, {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}});
  auto o = options();
  o.remove_exterior = true;
  auto r = mesh(g, o);
  double area = 0;
  for (const auto& t : r.mesh.triangles)
    area += gdr::triangle_area(r.mesh.points[t[0]], r.mesh.points[t[1]], r.mesh.points[t[2]]);
  EXPECT_NEAR(area, 3.0, 1e-12);
}

TEST_P(Refine2d, ConcentricPolygonsAndRefineAgainAddsNothing) {
  Pslg g;
  for (int k = 1; k <= 4; ++k) add_loop(g, regular_polygon(6 + 5 * k, k, 0, 0, 0.1 * k));
  auto o = options();
  o.min_angle = 25;
  auto r = mesh(g, o);
  EXPECT_GT(r.stats.steiner_points, 0);
  EXPECT_EQ(r.stats.bad_triangles, 0);
  // The output, read back as a PSLG (its subsegments as segments), is already good.
  Pslg again;
  again.points.assign(r.mesh.points.begin(), r.mesh.points.end());
  for (const auto& s : r.mesh.subsegments) again.segments.push_back({s[0], s[1]});
  auto r2 = mesh(again, o);
  EXPECT_EQ(r2.stats.steiner_points, 0);
  EXPECT_EQ(r2.mesh.triangles.size(), r.mesh.triangles.size());
}

// The benchmark's strategy switches (GDR_DISABLE) change how the work is scheduled, never
// the guarantees: with any one of them off, the mesh still validates and meets the bound.
TEST_P(Refine2d, EachStrategySwitchedOffStillGivesAValidMesh) {
  Pslg g;
  for (int k = 1; k <= 3; ++k) add_loop(g, regular_polygon(5 + 7 * k, k, 0, 0, 0.3 * k));
  add_loop(g, square(-4, -4, 4, 4));
  auto o = options();
  o.min_angle = 28;
  o.max_edge_length = 0.06;  // ~50k points: more bad elements than compete in one iteration
  for (const char* name : {"s1", "s3", "s4", "s5", "touching", "block_rounds", "grid_rounds", "worst_first",
                           "graded", "s1,s3,s4,s5,touching"}) {
    SCOPED_TRACE(std::string("GDR_DISABLE=") + name);
    setenv("GDR_DISABLE", name, 1);
    auto r = mesh(g, o);
    EXPECT_GT(r.stats.steiner_points, 30000);
    EXPECT_EQ(r.stats.bad_triangles, 0);
  }
  setenv("GDR_DISABLE", "s2", 1);
  try {
    gdr::refine_2d(g, o);
    ADD_FAILURE() << "an unknown strategy name was accepted";
  } catch (const gdr::Error& e) {
    EXPECT_EQ(e.status(), gdr::Status::InvalidInput);
    EXPECT_NE(std::string(e.what()).find("'s2'"), std::string::npos) << e.what();
  }
  unsetenv("GDR_DISABLE");
}

TEST_P(Refine2d, GridOfCocircularPoints) {
  Pslg g;
  const int n = 40;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) g.points.push_back({double(i), double(j)});
  add_loop(g, square(-1, -1, n, n));
  auto o = options();
  o.min_angle = 28;
  auto r = mesh(g, o);
  EXPECT_EQ(r.stats.bad_triangles, 0);
}

// Points on a circle (issue 9): every triangle of their Delaunay triangulation has the same
// circumcircle, and once the centre is in, the mesh is a fan of n slivers whose circles each
// hold the splitting points of the slivers within about 60 degrees. Few points can win an
// iteration and every loser used to locate its point and grow a cavity of up to n/3
// triangles, half the iterations thrown away by deferment: 77 to 82 iterations and 4 s on 2
// cores for the 26,244 points below; 500,000 points ended in "broken cavity" (a fixed bound
// of 100,000 on the walk around a vertex of a cavity). The points are exactly on the
// circle: products of Gaussian integers of norm p for eight primes p = 1 mod 4, so that
// x^2 + y^2 = R^2 holds in integers (R = 5*13*...*61, about 1.6e11, exact in doubles).
// That is the case of circumcentres; off-centres (the default) are the next test's.
TEST_P(Refine2d, ExactlyCocircularPoints) {
  const long long gauss[8][2] = {{1, 2}, {2, 3}, {1, 4}, {2, 5}, {1, 6}, {4, 5}, {2, 7}, {5, 6}};
  std::vector<std::pair<long long, long long>> z = {{1, 0}};
  for (const auto& g : gauss) {
    const long long a = g[0], b = g[1], p = a * a + b * b;
    const long long f[3][2] = {{a * a - b * b, 2 * a * b}, {a * a - b * b, -2 * a * b}, {p, 0}};
    std::vector<std::pair<long long, long long>> next;
    for (const auto& q : z)
      for (const auto& u : f)
        next.push_back({q.first * u[0] - q.second * u[1], q.first * u[1] + q.second * u[0]});
    z.swap(next);
  }
  Pslg g;
  for (const auto& q : z) {  // times the four units
    const long long x = q.first, y = q.second;
    for (const auto& v : {std::make_pair(x, y), std::make_pair(-y, x), std::make_pair(-x, -y),
                          std::make_pair(y, -x)})
      g.points.push_back({double(v.first), double(v.second)});
  }
  ASSERT_EQ(g.points.size(), 26244u);  // 4 * 3^8, all distinct
  auto o = options();
  o.off_centers = false;
  const auto r = mesh(g, o);
  EXPECT_EQ(r.stats.bad_triangles, 0);
  EXPECT_EQ(r.stats.output_points - r.stats.steiner_points, 26244);
  // Wall time depends on the machine; the iteration count does not (much): 52 to 56
  // without the graded order, about 67 with it (the same time).
  EXPECT_LE(r.stats.iterations, 80);
}

// The same on a circle in floating point (cos, sin: cocircular up to rounding). Off-centres
// do not meet at the centre: each sliver of the fan proposes its own point near the circle,
// inside the circumcircle of the whole fan, so that few win an iteration and the fan is cut
// from its ends: about 150 iterations for 2k points, 310 for 10k (1.7x the time of
// circumcentres on one thread), 510 for 40k, with 9% fewer points.
TEST_P(Refine2d, NearlyCocircularPoints) {
  Pslg g;
  g.points = regular_polygon(10000, 1.0);
  auto o = options();
  o.off_centers = false;
  const auto r = mesh(g, o);
  EXPECT_EQ(r.stats.bad_triangles, 0);
  // 54 before the fix; 40-44 with it on 2 CPU threads (2026-11-24, idle or loaded), and 46
  // once in a CI run under load: thread timing decides which of two touching points waits.
  EXPECT_LE(r.stats.iterations, 50);
  g.points = regular_polygon(2000, 1.0);
  const auto circumcentres = mesh(g, o);
  const auto off = mesh(g, options());
  EXPECT_EQ(off.stats.bad_triangles, 0);
  EXPECT_LE(off.stats.iterations, 300);
  EXPECT_LT(off.stats.steiner_points, circumcentres.stats.steiner_points);
}

TEST_P(Refine2d, RandomSegmentsInCells) {
  const Pslg g = gdr_test::segments_in_cells(30, 7);
  auto o = options();
  auto r = mesh(g, o);
  EXPECT_EQ(r.stats.bad_triangles, r.stats.small_angle_bad);
}

TEST_P(Refine2d, CollinearChainsAndHullSegments) {
  Pslg g;
  for (int i = 0; i <= 20; ++i) g.points.push_back({i * 0.5, 0.0});
  for (int i = 0; i < 20; ++i) g.segments.push_back({i, i + 1});
  g.points.push_back({5, 3});
  auto r = mesh(g, options());
  // Hull edges become subsegments with no input segment.
  int hull = 0;
  for (int s : r.mesh.subsegment_source) hull += s < 0;
  EXPECT_GT(hull, 0);
}

TEST_P(Refine2d, TinyInputAnglesTerminateAndReport) {
  // A fan of segments 1 degree apart from one vertex (a comb of tiny angles), inside a box.
  Pslg g;
  add_loop(g, square(-2, -2, 2, 2));
  const int apex = static_cast<int>(g.points.size());
  g.points.push_back({0, 0});
  for (int k = 0; k < 12; ++k) {
    const double a = (k * 1.0) * kPi / 180.0;
    g.points.push_back({1.5 * std::cos(a), 1.5 * std::sin(a)});
    g.segments.push_back({apex, apex + 1 + k});
  }
  auto o = options();
  auto r = mesh(g, o);
  // The 1-degree wedges themselves (about 1.3% of the box) are where bad triangles may stay.
  EXPECT_GT(r.stats.small_angle_bad, 0);
  EXPECT_LT(r.stats.bad_area_percent, 1.35);
}

// Fans of the seeded fuzzer (issue 9) at 1e-8 and 1e-12 radians with diametral circles and
// no angle bound: the segments at the apex are split down to 1e-64 and less, where the
// coordinate grid rounds a split point off its subsegment, outside the circle of the
// triangle across. That triangle went into the cavity anyway and left an edge that was not
// locally Delaunay (one per mesh). The second fan stalls: that is said, and its mesh is as
// valid as any.
TEST_P(Refine2d, SplitPointsRoundedOffTheirSubsegmentKeepTheMeshDelaunay) {
  const std::vector<std::vector<Point2>> fans = {
      {{2.0, 7.166409890266019e-15}, {2.0, 1.9716542486439405e-08}},
      {{2.0, 3.4586190430523573e-12}, {2.0, 1.8180602481328246e-14},
       {1.9999999977061202, 9.578892793150807e-05}, {1.999999999999997, 1.107855720128553e-07}}};
  for (const auto& ends : fans) {
    Pslg g;
    add_loop(g, square(-1, -1, 3, 3));
    g.points.push_back({0, 0});
    for (const Point2& e : ends) {
      g.points.push_back(e);
      g.segments.push_back({4, static_cast<int>(g.points.size()) - 1});
    }
    auto o = options();
    o.min_angle = 0;
    o.mode = gdr::EncroachMode::Ruppert;
    std::string warnings;
    gdr::Callbacks cb;
    cb.warning = [&](const std::string& w) { warnings += w + "\n"; };
    const gdr::Refine2dResult r = gdr::refine_2d(g, o, cb);
    const gdr::ValidationReport rep = gdr::validate_trimesh(r.mesh, &g, gdr::ValidateOptions{});
    EXPECT_TRUE(rep.valid) << ends.size() << ": " << rep.summary();
    EXPECT_EQ(rep.non_delaunay, 0u) << ends.size();
    EXPECT_EQ(rep.missing_segments, 0u) << ends.size();
    EXPECT_EQ(mislabelled_subsegments(r.mesh, g), 0) << ends.size();
    // The apex was refined once; the shells there no longer cascade (kernels.h,
    // on_matching_shell): 429 and 889 points before, down to 1e-100 from the apex.
    EXPECT_GT(r.stats.steiner_points, 0) << ends.size();
    EXPECT_LT(r.stats.steiner_points, 50) << ends.size();
    if (r.stats.stalled) EXPECT_NE(warnings.find("refinement stopped"), std::string::npos);
  }
}

TEST_P(Refine2d, SpiralWithSubDegreeAngles) {
  Pslg g;
  std::vector<Point2> pts;
  for (int i = 0; i < 200; ++i) {
    const double t = 0.15 * i;
    pts.push_back({(1 + 0.3 * t) * std::cos(t), (1 + 0.3 * t) * std::sin(t)});
  }
  for (std::size_t i = 0; i < pts.size(); ++i) g.points.push_back(pts[i]);
  for (int i = 0; i + 1 < 200; ++i) g.segments.push_back({i, i + 1});
  // A spike at 0.5 degrees off the last spiral segment.
  const Point2 e = pts.back(), d = pts[198];
  const double ang = std::atan2(d.y - e.y, d.x - e.x) + 0.5 * kPi / 180.0;
  g.points.push_back({e.x + 0.3 * std::cos(ang), e.y + 0.3 * std::sin(ang)});
  g.segments.push_back({199, 200});
  auto r = mesh(g, options());
  EXPECT_LT(r.stats.bad_area_percent, 1.0);
}

TEST_P(Refine2d, HugeAndTinyCoordinates) {
  for (double scale : {1e-9, 1e12}) {
    for (double offset : {0.0, 1e6}) {
      Pslg g;
      std::vector<Point2> p = regular_polygon(9, scale, offset * scale, 0);
      add_loop(g, p);
      g.points.push_back({offset * scale + 0.1 * scale, 0.2 * scale});
      auto o = options();
      o.min_angle = 25;
      auto r = mesh(g, o);
      EXPECT_EQ(r.stats.bad_triangles, 0) << "scale " << scale << " offset " << offset;
    }
  }
}

// Every combination of the rules meets the bound; the defaults are Triangle's (the lens and
// off-centres). (Not always the fewest points: on the gear at 25 degrees diametral circles
// with off-centres took 195 Steiner points, the defaults 224, Triangle 189.)
TEST_P(Refine2d, EncroachmentModesAndOffCenters) {
  Pslg g;
  add_loop(g, regular_polygon(13, 1.0));
  add_loop(g, regular_polygon(5, 0.3, 0.2, 0.1));
  auto o = options();
  EXPECT_EQ(o.mode, gdr::EncroachMode::Chew);
  EXPECT_TRUE(o.off_centers);
  o.min_angle = 25;
  for (auto mode : {gdr::EncroachMode::Ruppert, gdr::EncroachMode::Chew})
    for (bool off_centers : {false, true}) {
      SCOPED_TRACE(std::string(mode == gdr::EncroachMode::Chew ? "chew" : "ruppert") +
                   (off_centers ? " off-centres" : " circumcentres"));
      o.mode = mode;
      o.off_centers = off_centers;
      EXPECT_EQ(mesh(g, o).stats.bad_triangles, 0);
    }
}

// Off-centres must grade the mesh away from small features as circumcentres do. Placed at
// the centre of the circle of radius |pq| / (2 sin theta) through the shortest edge pq, they
// made new edges no longer than pq at 30 degrees: 2972 points where circumcentres need 262
// on sharp_angle.poly (and 9.8M against 0.34M on a contour map, 18 minutes).
TEST_P(Refine2d, OffCentersGradeLikeCircumcenters) {
  for (const char* name : {"sharp_angle.poly", "cascade34.poly"})
    for (double angle : {20.0, 25.0, 30.0}) {
      SCOPED_TRACE(std::string(name) + " at " + std::to_string(angle) + " degrees");
      const Pslg g = gdr::io::read_poly(std::string(GDR_DATA_DIR) + "/" + name);
      auto o = options();
      o.min_angle = angle;
      o.off_centers = false;
      const auto circumcenters = mesh(g, o);
      o.off_centers = true;
      const auto off = mesh(g, o);
      EXPECT_FALSE(off.stats.steiner_cap_reached);
      // (+10: on a few dozen points the order of insertion alone moves the counts by as much)
      EXPECT_LE(off.stats.steiner_points, circumcenters.stats.steiner_points * 11 / 10 + 10);
    }
}

// Mesh size against Triangle 1.6 (issue 13): with Triangle's rules, the defaults (lens of
// angle 180 - 2 theta, off-centres), the gear needs at most 10% more Steiner points than
// `triangle -pcq` (117 at 20 degrees, 269 at 30; Triangle counts hole seeds alike). Before,
// shells at every input vertex and worst-first order gave 7-10% more points on segments and
// 3-10% more free points on the maps of ../shared/data.
TEST_P(Refine2d, SizeNearTriangle) {
  const Pslg g = gdr::io::read_poly(std::string(GDR_DATA_DIR) + "/../apps/gdr/examples/gear.poly");
  for (const auto& [angle, triangle] : {std::pair{20.0, 117}, std::pair{30.0, 269}}) {
    auto o = options();
    o.min_angle = angle;
    const auto r = mesh(g, o);  // and validates
    EXPECT_EQ(r.stats.bad_triangles, 0) << angle;
    EXPECT_LE(r.stats.steiner_points, triangle * 11 / 10) << angle;
  }
}

// One point at a time (issue 14): on up to 4 CPU threads the refinement takes its bad
// elements from a priority queue and inserts each point at once. It must give a valid mesh
// (mesh() validates) of about the parallel iteration's size, and give way to the parallel
// iteration where segments meet at tiny angles (there it cascaded: 8,182 points and a stall
// against 1,487 on FanOfTinyAnglesDoesNotCascade's first fan).
TEST_P(Refine2d, OneAtATimeMeshesLikeTheParallelIteration) {
  if (GetParam() != Backend::Cpu) GTEST_SKIP() << "one point at a time is the CPU backend's";
  const char* before = std::getenv("GDR_DISABLE");
  const std::string kept = before ? before : "";
  const auto ran_one_at_a_time = [](const gdr::Refine2dResult& r) {
    for (const auto& p : r.stats.phases)
      if (p.name == "one at a time") return true;
    return false;
  };
  gdr::CpuThreadLimit two(2);
  auto o = options();
  o.min_angle = 30;
  const Pslg g = wobbly_grid_map(24, 8, 5);
  unsetenv("GDR_DISABLE");
  const auto one = mesh(g, o);
  setenv("GDR_DISABLE", "one_at_a_time", 1);
  const auto parallel = mesh(g, o);
  unsetenv("GDR_DISABLE");
  EXPECT_TRUE(ran_one_at_a_time(one));
  EXPECT_FALSE(ran_one_at_a_time(parallel));
  EXPECT_GT(one.stats.steiner_points, parallel.stats.steiner_points * 95 / 100);
  EXPECT_LT(one.stats.steiner_points, parallel.stats.steiner_points * 103 / 100);
  // Segments from one point whose ends lie 1e-13 apart: the parallel iteration.
  Pslg fan;
  fan.points = {{-1, -1}, {3, -1}, {3, 3}, {-1, 3}, {0, 0}, {2.0, 3.558401084489544e-11}, {2.0, 7.92454647949038e-13}};
  fan.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {4, 6}};
  o.min_angle = 20;
  const auto tiny = mesh(fan, o);
  EXPECT_FALSE(ran_one_at_a_time(tiny));
  if (!kept.empty()) setenv("GDR_DISABLE", kept.c_str(), 1);
}

// Graded order (issue 13): on a map, the parallel insertion without it split coarse
// triangles before the grading around small features reached them, and needed 13% more
// points than Triangle 1.6 on the counties map at 30 degrees (98,703 Steiner points). Since
// the petal sinks (kernels.h) it buys less: on the development box's CPU 90,323 against
// 95,500 there (a generated wobbly map, which this test used before, showed only 1%).
TEST_P(Refine2d, GradedOrderKeepsAMapNearTriangle) {
  const auto f = std::filesystem::path(GDR_SHARED_DATA_DIR) / "pslg" / "us_counties_albers.poly";
  if (!std::filesystem::exists(f)) GTEST_SKIP() << "no shared data at " << f.string();
  const Pslg g = gdr::io::read_poly(f.string());
  auto o = options();
  o.min_angle = 30;
  // The graded order is the parallel iteration's (the CPU inserts one point at a time on
  // few threads: Engine::one_at_a_time, smallest first by a queue).
  const auto graded = mesh_without("one_at_a_time", g, o);
  const auto plain = mesh_without("graded,one_at_a_time", g, o);
  std::printf("counties map at 30 degrees: %lld Steiner points graded, %lld without\n",
              graded.stats.steiner_points, plain.stats.steiner_points);
  EXPECT_LT(graded.stats.bad_area_percent, 0.03);  // all next to small input angles
  EXPECT_LE(graded.stats.steiner_points, 98703);
  EXPECT_LE(graded.stats.steiner_points * 103 / 100, plain.stats.steiner_points);
}

// Locally optimal points (issue 13): off-centres whose circumcentre lies in the petal of the
// shortest edge climb to larger empty circles there (kernels.h, move_to_petal_sink). On the
// wobbly map at 30 degrees: 29,310 Steiner points against 33,070 without on the CPU of
// the development box, one point at a time (Triangle 1.6: 34,995); both meshes valid
// (mesh() validates).
TEST_P(Refine2d, PetalSinksNeedFewerPoints) {
  const Pslg g = wobbly_grid_map(40, 8, 7);
  auto o = options();
  o.min_angle = 30;
  const auto sinks = mesh(g, o);
  const auto off = mesh_without("petal_sinks", g, o);
  std::printf("wobbly map at 30 degrees: %lld Steiner points with petal sinks, %lld without\n",
              sinks.stats.steiner_points, off.stats.steiner_points);
  EXPECT_LT(sinks.stats.bad_area_percent, 0.02);  // all next to small input angles
  EXPECT_LE(sinks.stats.steiner_points * 105 / 100, off.stats.steiner_points);
}

// A map turned by a few degrees keeps its straight border only up to rounding: its border
// points lie 1e-17 to 1e-15 of the border's length off the line through the corners. With the
// convex hull kept, the slivers between hull edges and those points asked for 1e12-1e15
// Steiner points and the run was refused (Triangle 1.6 ran out of 16 GB on such a map); the
// CDT now leaves such slivers out, so the points join the boundary.
TEST_P(Refine2d, TurnedBorderPointsJoinTheHull) {
  for (const bool border_segments : {false, true}) {
    SCOPED_TRACE(border_segments ? "border segments" : "border points only");
    const double a = 0.3, ca = std::cos(a), sa = std::sin(a);
    Pslg g;
    auto turned = [&](double x, double y) { return Point2{ca * x - sa * y + 1e5, sa * x + ca * y - 3e4}; };
    const int k = 40;  // points per side
    for (int side = 0; side < 4; ++side)
      for (int i = 0; i < k; ++i) {
        const double f = static_cast<double>(i) / k;
        const double x[4] = {f, 1, 1 - f, 0}, y[4] = {0, f, 1, 1 - f};
        g.points.push_back(turned(100 * x[side], 100 * y[side]));
      }
    if (border_segments)
      for (int i = 0; i < 4 * k; ++i) g.segments.push_back({i, (i + 1) % (4 * k)});
    std::vector<Point2> inner = regular_polygon(7, 20, 50, 50, 0.1);  // a feature inside
    for (Point2& p : inner) p = turned(p.x, p.y);
    add_loop(g, inner);
    auto o = options();
    o.min_angle = 25;
    o.remove_exterior = false;
    // Before: with border segments refused (1.3e13 Steiner points asked for the slivers),
    // without them stalled after 6,803 points with 47% of the area bad.
    const auto r = mesh(g, o);
    EXPECT_EQ(r.stats.bad_triangles, 0);
    EXPECT_LT(r.stats.steiner_points, 2000);
    double area = 0;
    for (const auto& t : r.mesh.triangles) {
      const Point2 &p = r.mesh.points[t[0]], &q = r.mesh.points[t[1]], &s2 = r.mesh.points[t[2]];
      area += 0.5 * ((q.x - p.x) * (s2.y - p.y) - (q.y - p.y) * (s2.x - p.x));
    }
    EXPECT_NEAR(area, 1e4, 1e-6);  // the square's, less slivers of rounding size
  }
}

// The CPU's work-list collect (issue 14) looks only at the last list's triangles, the new
// ones and those whose flags changed; it must find exactly what a scan of the whole mesh
// finds. On one thread both give the same mesh, point for point, on a map whose segments
// are split with triangles on both sides and whose circumcentres are often refused for
// encroaching (the flags the log must catch).
TEST_P(Refine2d, WorkListCollectsWhatTheWholeMeshScanFinds) {
  if (GetParam() != Backend::Cpu) GTEST_SKIP() << "the work list is the CPU backend's";
  struct Case {
    std::string name;
    Pslg g;
    double angle;
    gdr::EncroachMode mode;
  };
  std::vector<Case> cases = {{"wobbly map", wobbly_grid_map(24, 8, 5), 30, gdr::EncroachMode::Chew},
                             {"wobbly map", wobbly_grid_map(24, 8, 5), 25, gdr::EncroachMode::Ruppert}};
  // Here a walk that ran into a subsegment flags it in an iteration where it is not split
  // (a log without walks gave one point more).
  const auto world = std::filesystem::path(GDR_SHARED_DATA_DIR) / "pslg" / "world_land_110m.poly";
  if (std::filesystem::exists(world))
    cases.push_back({"world map", gdr::io::read_poly(world.string()), 20, gdr::EncroachMode::Chew});
  else
    std::printf("no shared data at %s: the world map is left out\n", world.string().c_str());
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name + " at " + std::to_string(c.angle));
    auto o = options();
    o.min_angle = c.angle;
    o.mode = c.mode;
    o.deterministic = true;
    const auto listed = mesh(c.g, o);
    // (Both ways in the one engine mode this test runs in: see parallel_iteration.*.)
    const char* before = std::getenv("GDR_DISABLE");
    const std::string kept = before ? before : "";
    setenv("GDR_DISABLE", (kept.empty() ? "work_list" : kept + ",work_list").c_str(), 1);
    const auto scanned = mesh(c.g, o);
    if (kept.empty()) unsetenv("GDR_DISABLE");
    else setenv("GDR_DISABLE", kept.c_str(), 1);
    const auto phase = [](const gdr::Refine2dResult& r, const std::string& name) {
      for (const auto& p : r.stats.phases)
        if (p.name == name) return true;
      return false;
    };
    EXPECT_TRUE(phase(listed, "collect, listed"));  // the work list did collect
    EXPECT_FALSE(phase(scanned, "collect, listed"));
    EXPECT_GT(listed.stats.steiner_points, 5000);
    EXPECT_EQ(listed.stats.iterations, scanned.stats.iterations);
    ASSERT_EQ(listed.mesh.points.size(), scanned.mesh.points.size());
    ASSERT_EQ(listed.mesh.triangles.size(), scanned.mesh.triangles.size());
    for (std::size_t i = 0; i < listed.mesh.points.size(); ++i) {
      ASSERT_EQ(listed.mesh.points[i].x, scanned.mesh.points[i].x) << i;
      ASSERT_EQ(listed.mesh.points[i].y, scanned.mesh.points[i].y) << i;
    }
    EXPECT_TRUE(listed.mesh.triangles == scanned.mesh.triangles);
  }
}

// Edges that are not locally Delaunay, subsegments included (unconstrained).
std::size_t non_delaunay_edges(gdr::TriMesh m) {
  m.subsegments.clear();
  m.subsegment_source.clear();
  m.subsegment_markers.clear();
  return gdr::validate_trimesh(m, nullptr).non_delaunay;
}

// Diametral circles (Triangle's -D) leave no vertex of a subsegment's two triangles inside its
// diametral circle, so subsegments are locally Delaunay as well as the other edges: the mesh
// is Delaunay, not only constrained Delaunay. With the lens it is not: a segment inside a
// rectangle, seen from two points at 110 degrees, inside its circle but not its lens of 140.
TEST_P(Refine2d, DiametralCirclesGiveADelaunayMesh) {
  Pslg g;
  add_loop(g, square(-1, -1, 2, 1));
  g.points.insert(g.points.end(), {{0, 0}, {1, 0}, {0.5, 0.35}, {0.5, -0.35}});
  g.segments.push_back({4, 5});
  for (auto mode : {gdr::EncroachMode::Ruppert, gdr::EncroachMode::Chew}) {
    auto o = options();
    o.min_angle = 20;
    o.mode = mode;
    const std::size_t n = non_delaunay_edges(mesh(g, o).mesh);  // mesh() validates it
    if (mode == gdr::EncroachMode::Ruppert)
      EXPECT_EQ(n, 0u);
    else
      EXPECT_GT(n, 0u);
  }
  const Pslg gear = gdr::io::read_poly(std::string(GDR_DATA_DIR) + "/../apps/gdr/examples/gear.poly");
  auto o = options();
  o.mode = gdr::EncroachMode::Ruppert;
  for (double angle : {20.0, 30.0}) {
    o.min_angle = angle;
    EXPECT_EQ(non_delaunay_edges(mesh(gear, o).mesh), 0u) << angle;
  }
}

TEST_P(Refine2d, SteinerCapStopsCleanly) {
  Pslg g;
  add_loop(g, square(0, 0, 1, 1));
  auto o = options();
  o.max_area = 1e-4;
  o.max_steiner_points = 100;
  auto r = mesh(g, o);
  EXPECT_TRUE(r.stats.steiner_cap_reached);
  EXPECT_LE(r.stats.steiner_points, 100);
  EXPECT_GT(r.stats.bad_triangles, 0);
}

// Refinement may not end (above 30 degrees, or in a thin domain at any angle), so unless a
// cap is set an automatic one applies: on an input where refinement cascaded at 34 degrees
// with diametral circles and circumcentres (on the CPU path; the GPU's rounding happened to
// steer clear), the run stops there cleanly with a valid mesh, or else meets the bound (with
// the defaults it does, with about 200 Steiner points).
TEST_P(Refine2d, AnAutomaticCapEndsACascade) {
  const Pslg g = gdr::io::read_poly(std::string(GDR_DATA_DIR) + "/cascade34.poly");
  auto o = options();
  for (double angle : {0.0, 20.0, 30.0}) {  // at every angle
    o.min_angle = angle;
    const auto r = mesh(g, o);
    // At least 1M, or 100k without an angle bound (only encroached subsegments are split).
    EXPECT_EQ(r.stats.steiner_cap, angle > 0 ? 1000000 : 100000) << angle;
    EXPECT_TRUE(r.stats.automatic_steiner_cap) << angle;
  }
  o.min_angle = 33.8;
  auto r = mesh(g, o);
  EXPECT_EQ(r.stats.steiner_cap, 1000000);  // max(1000 x 54 points, 1M)
  EXPECT_TRUE(r.stats.automatic_steiner_cap);
  EXPECT_FALSE(r.stats.steiner_cap_reached);
  EXPECT_LT(r.stats.steiner_points, 1000);
  o.min_angle = 34;
  r = mesh(g, o);
  if (r.stats.steiner_cap_reached) {
    EXPECT_EQ(r.stats.steiner_points, 1000000);
    EXPECT_GT(r.stats.bad_triangles, 0);
  }
  o.max_steiner_points = 5000;  // a cap of the caller's own replaces the automatic one
  r = mesh(g, o);
  EXPECT_EQ(r.stats.steiner_cap, 5000);
  EXPECT_FALSE(r.stats.automatic_steiner_cap);
  EXPECT_LE(r.stats.steiner_points, 5000);
}

// A thin domain needs more points than any cap allows: the run is refused from the CDT with
// the estimate, on both backends (beside the GPU's refinement the estimate runs on the host
// meanwhile and stops it); with a cap of the caller's it is meshed up to the cap.
TEST_P(Refine2d, ThinPartsAreRefusedWithTheEstimate) {
  Pslg g;
  add_loop(g, square(0, 0, 1, 1e-11));
  auto o = options();
  o.min_angle = 25;
  try {
    mesh(g, o);
    ADD_FAILURE() << "a 1 x 1e-11 rectangle at 25 degrees was meshed";
  } catch (const gdr::Error& e) {
    EXPECT_EQ(e.status(), gdr::Status::InvalidInput);
    EXPECT_NE(std::string(e.what()).find("Steiner points in the input's thin parts (the thinnest 1e-11 wide"),
              std::string::npos) << e.what();
  }
  o.max_steiner_points = 2000;
  const auto r = mesh(g, o);
  EXPECT_TRUE(r.stats.steiner_cap_reached);
  EXPECT_LE(r.stats.steiner_points, 2000);
}

// Worst-first ordering keeps refinement finite on the world map at 33.5 degrees (larger-first
// cascaded to 1.4M points; CGAL Mesh_2 did not finish in 300 s).
TEST_P(Refine2d, WorldMapAtThirtyThreeAndAHalfDegrees) {
  const auto f = std::filesystem::path(GDR_SHARED_DATA_DIR) / "pslg" / "world_land_110m.poly";
  if (!std::filesystem::exists(f)) GTEST_SKIP() << "no shared data at " << f;
  auto o = options();
  o.min_angle = 33.5;
  auto r = mesh(gdr::io::read_poly(f.string()), o);
  EXPECT_FALSE(r.stats.steiner_cap_reached);
  EXPECT_LT(r.stats.steiner_points, 1000000);
  EXPECT_LT(r.stats.bad_area_percent, 0.01);
}

TEST_P(Refine2d, IntersectionsSplitUnlessStrict) {
  Pslg g;
  add_loop(g, square(0, 0, 4, 4));
  g.points.push_back({1, 1});
  g.points.push_back({3, 3});
  g.points.push_back({1, 3});
  g.points.push_back({3, 1});
  g.points.push_back({2, 0.5});
  g.segments.push_back({4, 5});
  g.segments.push_back({6, 7});  // crosses (4, 5) at (2, 2)
  g.segments.push_back({8, 2});  // crosses (6, 7) too: (6, 7) in 3 pieces, 7 in all
  g.segments.push_back({1, 8});
  // Split by default, with a warning that counts what was split.
  auto o = options();
  std::vector<std::string> warnings;
  gdr::Callbacks cb;
  cb.warning = [&](const std::string& w) { warnings.push_back(w); };
  auto r = gdr::refine_2d(g, o, cb);
  EXPECT_GT(r.mesh.points.size(), g.points.size());
  ASSERT_FALSE(warnings.empty());
  EXPECT_NE(warnings[0].find("split 3 segment(s) into 7 pieces"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[0].find("2 intersection point(s) added"), std::string::npos) << warnings[0];
  r = mesh(g, o);  // and validates
  // Strict input refuses it.
  o.strict_input = true;
  try {
    gdr::refine_2d(g, o);
    ADD_FAILURE() << "crossing segments accepted with strict input";
  } catch (const gdr::Error& e) {
    EXPECT_EQ(e.status(), gdr::Status::SelfIntersectingInput);
  }
  o.strict_input = false;
  // An isolated point on a segment: the segment is split there, and both still validate.
  Pslg on_segment;
  add_loop(on_segment, square(0, 0, 1, 1));
  on_segment.points.push_back({0.25, 0});
  mesh(on_segment, o);
}

// Issue 9: any arrangement of segments is split, not only simple crossings: concurrent
// segments (3 and 50 through one point segfaulted in CGAL or hung; 4 concurrent lines were
// left "could not be split"), and a soup of random segments with many crossings.
TEST_P(Refine2d, SplitIntersectionsAnyArrangement) {
  auto o = options();
  auto star = [](int n, double cx, double cy) {
    Pslg g;
    for (int k = 0; k < n; ++k) {
      const double t = 3.14159265358979323846 * k / n + 0.1;
      g.points.push_back({cx + std::cos(t), cy + std::sin(t)});
      g.points.push_back({cx - std::cos(t), cy - std::sin(t)});
      g.segments.push_back({2 * k, 2 * k + 1});
    }
    return g;
  };
  for (const int n : {3, 50}) {
    SCOPED_TRACE("star of " + std::to_string(n));
    const auto r = mesh(star(n, 0.3, -0.2), o);
    // One shared centre (near (0.3, -0.2)): 2n ends + 1 point before refinement.
    o.refine = false;
    const auto cdt = mesh(star(n, 0.3, -0.2), o);
    o.refine = true;
    EXPECT_EQ(cdt.mesh.points.size(), static_cast<std::size_t>(2 * n + 1));
    EXPECT_GE(r.mesh.points.size(), cdt.mesh.points.size());  // a 3-star is 60 degrees
  }
  {
    SCOPED_TRACE("four concurrent lines with exact intersection (0.25, 0.75)");
    Pslg g;
    const double d[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -2}};
    for (int k = 0; k < 4; ++k) {
      g.points.push_back({0.25 - d[k][0], 0.75 - d[k][1]});
      g.points.push_back({0.25 + d[k][0], 0.75 + d[k][1]});
      g.segments.push_back({2 * k, 2 * k + 1});
    }
    o.refine = false;
    const auto cdt = mesh(g, o);
    o.refine = true;
    ASSERT_EQ(cdt.mesh.points.size(), 9u);
    EXPECT_EQ(cdt.mesh.points[8].x, 0.25);  // the exact intersection, shared by all four
    EXPECT_EQ(cdt.mesh.points[8].y, 0.75);
    mesh(g, o);
  }
  {
    SCOPED_TRACE("soup of 150 random segments");
    std::mt19937 rng(9);
    std::uniform_real_distribution<double> u(0, 1);
    Pslg g;
    for (int k = 0; k < 150; ++k) {
      for (int e = 0; e < 2; ++e) g.points.push_back({u(rng), u(rng)});
      g.segments.push_back({2 * k, 2 * k + 1});
    }
    const auto r = mesh(g, o);
    EXPECT_GT(r.stats.output_points, 1000);
    // With strict input: refused with a short message, a few pairs and the count, numbered
    // as in the input file.
    o.strict_input = true;
    g.first_index = 1;
    std::string msg;
    try {
      gdr::refine_2d(g, o);
      ADD_FAILURE() << "crossing segments accepted";
    } catch (const gdr::Error& e) {
      EXPECT_EQ(e.status(), gdr::Status::SelfIntersectingInput);
      msg = e.what();
    }
    EXPECT_LT(msg.size(), 400u) << msg;
    EXPECT_NE(msg.find(" in all)"), std::string::npos) << msg;
    EXPECT_EQ(msg.find("segment 0 "), std::string::npos) << msg;  // numbered from 1
    o.strict_input = false;
  }
}

TEST_P(Refine2d, SharedDataPslgs) {
  const std::filesystem::path dir = std::filesystem::path(GDR_SHARED_DATA_DIR) / "pslg";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no shared data at " << dir;
  int n = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    if (f.path().extension() != ".poly") continue;
    SCOPED_TRACE(f.path().string());
    const Pslg g = gdr::io::read_poly(f.path().string());
    auto r = mesh(g, options());
    EXPECT_GT(r.stats.steiner_points, 0);
    EXPECT_LT(r.stats.bad_area_percent, 0.01);
    ++n;
  }
  EXPECT_GE(n, 3);
}

TEST_P(Refine2d, BundledData) {
  const std::filesystem::path dir = std::filesystem::path(GDR_DATA_DIR);
  int n = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    if (f.path().extension() != ".poly" || f.path().filename().string().rfind("broken", 0) == 0)
      continue;
    SCOPED_TRACE(f.path().string());
    Pslg g;
    try {
      if (gdr::io::detect_input_kind(f.path().string()) != gdr::io::InputKind::Pslg2d) continue;
      g = gdr::io::read_poly(f.path().string());
    } catch (const gdr::Error&) {
      continue;  // deliberately broken files are the I/O tests' business
    }
    auto o = options();
    o.remove_exterior = !g.holes.empty();
    mesh(g, o);
    ++n;
  }
  EXPECT_GE(n, 1);
}

// ---- Bad input: each gives its own error, naming what is wrong. ----------------------

gdr::Status status_of(const Pslg& g, gdr::Refine2dOptions o, std::string* msg = nullptr) {
  try {
    gdr::refine_2d(g, o);
  } catch (const gdr::Error& e) {
    if (msg) *msg = e.what();
    return e.status();
  }
  return gdr::Status::Ok;
}

TEST_P(Refine2d, BadInputs) {
  auto o = options();
  Pslg ok;
  add_loop(ok, square(0, 0, 1, 1));
  std::string msg;

  Pslg nan = ok;
  nan.points[2].y = std::nan("");
  EXPECT_EQ(status_of(nan, o, &msg), gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("NaN"), std::string::npos) << msg;
  EXPECT_NE(msg.find("2"), std::string::npos) << msg;

  Pslg missing = ok;
  missing.segments.push_back({1, 9});
  EXPECT_EQ(status_of(missing, o, &msg), gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("segment 4"), std::string::npos) << msg;

  Pslg zero = ok;
  zero.points.push_back(zero.points[0]);
  zero.segments.push_back({0, 4});
  EXPECT_EQ(status_of(zero, o, &msg), gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("zero length"), std::string::npos) << msg;

  Pslg line;
  for (int i = 0; i < 5; ++i) line.points.push_back({double(i), 2.0 * i});
  EXPECT_EQ(status_of(line, o, &msg), gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("collinear"), std::string::npos) << msg;

  EXPECT_EQ(status_of(Pslg{}, o), gdr::Status::InvalidInput);

  // Crossings, overlaps and points on segments are split by default (issue 15) and refused
  // with strict input, naming them.
  auto strict = o;
  strict.strict_input = true;
  Pslg cross = ok;
  cross.segments.push_back({0, 2});
  cross.segments.push_back({1, 3});
  EXPECT_EQ(status_of(cross, o), gdr::Status::Ok);
  EXPECT_EQ(status_of(cross, strict, &msg), gdr::Status::SelfIntersectingInput);
  EXPECT_NE(msg.find("segment 4"), std::string::npos) << msg;
  EXPECT_NE(msg.find("cross"), std::string::npos) << msg;

  Pslg overlap = ok;
  overlap.points.push_back({0.5, 0});
  overlap.segments.push_back({0, 4});
  EXPECT_EQ(status_of(overlap, o), gdr::Status::Ok);
  EXPECT_EQ(status_of(overlap, strict, &msg), gdr::Status::SelfIntersectingInput);
  EXPECT_NE(msg.find("overlap"), std::string::npos) << msg;

  Pslg on_segment = ok;
  on_segment.points.push_back({0.25, 0});
  EXPECT_EQ(status_of(on_segment, o), gdr::Status::Ok);
  EXPECT_EQ(status_of(on_segment, strict, &msg), gdr::Status::SelfIntersectingInput);
  EXPECT_NE(msg.find("point 4 lies on segment 0"), std::string::npos) << msg;

  auto big = o;
  big.min_angle = 40;
  EXPECT_EQ(status_of(ok, big, &msg), gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("34"), std::string::npos) << msg;
  big = o;
  big.max_edge_length = -1;
  EXPECT_EQ(status_of(ok, big), gdr::Status::InvalidInput);
  big = o;
  big.max_area = std::nan("");
  EXPECT_EQ(status_of(ok, big), gdr::Status::InvalidInput);

  // Duplicates are merged and reported, not refused: the first of equal points stays, in
  // input order (-0 equals 0), and segments on a later twin move to it.
  Pslg dup;
  dup.points = {{0.5, 0.5}, {0, 0}, {1, 0}, {1, 1}, {-0.0, 0}, {0, 1}, {1, 0}, {0.5, 0.5}};
  dup.segments = {{1, 2}, {6, 3}, {3, 5}, {5, 4}, {2, 1}};
  gdr::Callbacks cb;
  std::string warned;
  cb.warning = [&](const std::string& w) { warned += w; };
  auto r = gdr::refine_2d(dup, o, cb);
  EXPECT_EQ(r.stats.duplicate_points_merged, 3);
  EXPECT_NE(warned.find("duplicate"), std::string::npos);
  EXPECT_NE(warned.find("1 duplicate segment"), std::string::npos) << warned;  // {2, 1}
  const std::vector<gdr::Point2> kept = {{0.5, 0.5}, {0, 0}, {1, 0}, {1, 1}, {0, 1}};
  ASSERT_GE(r.mesh.points.size(), kept.size());
  for (std::size_t i = 0; i < kept.size(); ++i) {
    EXPECT_EQ(r.mesh.points[i].x, kept[i].x) << i;
    EXPECT_EQ(r.mesh.points[i].y, kept[i].y) << i;
  }
  EXPECT_TRUE(gdr::validate_trimesh(r.mesh, &dup).valid);
}

// The kernels compare squared lengths, twice the area and sin^2 of the angle: a bound that
// would underflow or overflow there is refused rather than silently ignored (a maximum edge
// of 1e-200 used to mean no bound at all), unless no element could exceed it anyway.
TEST_P(Refine2d, BoundsTheKernelsCannotHonourAreRefused) {
  Pslg g;
  add_loop(g, square(0, 0, 1, 1));
  auto o = options();
  std::string msg;
  for (double edge : {1e-200, 1e-161}) {
    o.max_edge_length = edge;
    EXPECT_EQ(status_of(g, o, &msg), gdr::Status::InvalidInput) << edge;
    EXPECT_NE(msg.find("maximum edge length"), std::string::npos) << msg;
    EXPECT_NE(msg.find("underflows"), std::string::npos) << msg;
  }
  o.max_edge_length = 1e200;  // longer than any edge can be: met by the CDT already
  EXPECT_EQ(mesh(g, o).stats.bad_triangles, 0);
  o.max_edge_length = 0;
  o.min_angle = 1e-300;
  EXPECT_EQ(status_of(g, o, &msg), gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("minimum angle"), std::string::npos) << msg;
}

// Size bounds whose mesh cannot be held are refused before refining, the estimate in the
// message (gear.poly with a maximum area of 1e-9 took 8.2 GB in 141 s before it died); a
// Steiner cap of the caller's own keeps such a run small, and then it goes ahead.
TEST_P(Refine2d, SizeBoundsBeyondWhatFitsAreRefused) {
  Pslg g;
  add_loop(g, square(0, 0, 1, 1));
  auto o = options();
  o.max_area = 1e-9;
  std::string msg;
  EXPECT_EQ(status_of(g, o, &msg), gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("at least 1e+09 triangles"), std::string::npos) << msg;
  o.max_edge_length = 1e-5;
  o.max_area = 0;
  EXPECT_EQ(status_of(g, o, &msg), gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("maximum edge length 1e-05"), std::string::npos) << msg;
  o.max_steiner_points = 100;
  const auto r = mesh(g, o);
  EXPECT_TRUE(r.stats.steiner_cap_reached);
  EXPECT_EQ(r.stats.steiner_points, 100);
}

TEST_P(Refine2d, AbortStopsTheRun) {
  Pslg g;
  add_loop(g, square(0, 0, 1, 1));
  auto o = options();
  o.max_area = 1e-5;
  gdr::Callbacks cb;
  int polls = 0;
  cb.abort = [&] { return ++polls > 3; };
  EXPECT_EQ([&] {
    try {
      gdr::refine_2d(g, o, cb);
    } catch (const gdr::Error& e) {
      return e.status();
    }
    return gdr::Status::Ok;
  }(),
            gdr::Status::Aborted);
}

TEST(Refine2dBackends, GpuAndCpuAgree) {
  if (!gdr::gpu_available()) GTEST_SKIP() << "no usable CUDA device: " << gdr::device_info().reason;
  const std::filesystem::path f =
      std::filesystem::path(GDR_SHARED_DATA_DIR) / "pslg" / "us_counties_albers.poly";
  if (!std::filesystem::exists(f)) GTEST_SKIP() << "no shared data";
  const Pslg g = gdr::io::read_poly(f.string());
  gdr::Refine2dOptions o;
  o.backend = Backend::Cpu;
  auto cpu = gdr::refine_2d(g, o);
  o.backend = Backend::Gpu;
  auto gpu = gdr::refine_2d(g, o);
  EXPECT_EQ(gpu.stats.backend_used, Backend::Gpu);
  const double a = double(cpu.stats.steiner_points), b = double(gpu.stats.steiner_points);
  EXPECT_LE(std::fabs(a - b), 0.02 * std::max(a, b)) << "cpu " << a << " gpu " << b;
  EXPECT_TRUE(gdr::validate_trimesh(gpu.mesh, &g).valid);
}

TEST(Refine2dBackends, GpuRequestedWithoutDeviceIsAClearError) {
  if (gdr::gpu_available()) GTEST_SKIP() << "a GPU is present";
  Pslg g;
  add_loop(g, square(0, 0, 1, 1));
  gdr::Refine2dOptions o;
  o.backend = Backend::Gpu;
  std::string msg;
  EXPECT_EQ(status_of(g, o, &msg), gdr::Status::NoDevice);
  EXPECT_NE(msg.find("GPU"), std::string::npos);
  o.backend = Backend::Auto;
  EXPECT_EQ(gdr::refine_2d(g, o).stats.backend_used, Backend::Cpu);
}

// Auto: a tiny job stays on the CPU (the GPU is not even probed); the threshold can be set.
TEST(Refine2dBackends, AutoChoosesByEstimatedSize) {
  Pslg g;
  add_loop(g, square(0, 0, 1, 1));
  gdr::Refine2dOptions o;
  o.backend = Backend::Auto;
  EXPECT_EQ(gdr::refine_2d(g, o).stats.backend_used, Backend::Cpu);
  o.gpu_min_triangles = 1;
  EXPECT_EQ(gdr::refine_2d(g, o).stats.backend_used,
            gdr::gpu_available() ? Backend::Gpu : Backend::Cpu);
  if (gdr::gpu_available()) EXPECT_TRUE(gdr::gpu_warm());
}

INSTANTIATE_TEST_SUITE_P(Backends, Refine2d, gdr::test::both_backends(), gdr::test::backend_name);

}  // namespace

// Triangle's switch string maps to the options as Triangle reads it; anything else is refused
// by name, never ignored (issue 15).
TEST(TriangleSwitches, MapToOptions) {
  gdr::Refine2dOptions o;
  gdr::TriangleSwitches t = gdr::apply_triangle_switches("-pq30a0.1", o);
  EXPECT_EQ(o.min_angle, 30);
  EXPECT_EQ(o.max_area, 0.1);
  EXPECT_TRUE(o.refine);
  EXPECT_TRUE(o.remove_exterior);  // p without c: Triangle eats the exterior
  EXPECT_FALSE(t.zero_based || t.quiet || t.check);

  o = {};
  t = gdr::apply_triangle_switches("pcqzQCa1e-3S500", o);
  EXPECT_EQ(o.min_angle, 20);  // q without a number
  EXPECT_EQ(o.max_area, 1e-3);
  EXPECT_EQ(o.max_steiner_points, 500);
  EXPECT_FALSE(o.remove_exterior);
  EXPECT_TRUE(t.zero_based && t.quiet && t.check);

  o = {};
  gdr::apply_triangle_switches("p", o);  // no q, no a: the CDT only, no angle bound
  EXPECT_FALSE(o.refine);
  EXPECT_EQ(o.min_angle, 0);
  o = {};
  gdr::apply_triangle_switches("pa0.5", o);  // an area bound alone
  EXPECT_TRUE(o.refine);
  EXPECT_EQ(o.min_angle, 0);
  EXPECT_EQ(o.mode, gdr::EncroachMode::Chew);  // Triangle's lens
  gdr::apply_triangle_switches("pqD", o);     // and its diametral circles
  EXPECT_EQ(o.mode, gdr::EncroachMode::Ruppert);
  gdr::apply_triangle_switches("pq", o);
  EXPECT_EQ(o.mode, gdr::EncroachMode::Chew);

  for (const char* bad : {"pq30Y", "pqV", "-", "pq3.0.1", "pS"}) {
    SCOPED_TRACE(bad);
    gdr::Refine2dOptions r;
    try {
      gdr::apply_triangle_switches(bad, r);
      ADD_FAILURE() << "accepted";
    } catch (const gdr::Error& e) {
      EXPECT_EQ(e.status(), gdr::Status::InvalidInput);
      EXPECT_NE(std::string(e.what()).find(std::string("'") + bad + "'"), std::string::npos) << e.what();
    }
  }
}

// A mesh keeps the input's numbering: Triangle files written from a 1-based input count from
// 1 (points and triangles), and read back the same, boundary markers included.
TEST(Refine2dNumbering, TriangleFilesCountAsTheInputDoes) {
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  g.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  g.first_index = 1;
  gdr::Refine2dOptions o;
  o.backend = Backend::Cpu;
  o.max_area = 0.1;
  const auto r = gdr::refine_2d(g, o);
  EXPECT_EQ(r.mesh.first_index, 1);
  const auto dir = std::filesystem::temp_directory_path() / ("gdr_numbering_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string base = (dir / "square").string();
  gdr::io::write_triangle(base, r.mesh);
  std::ifstream node(base + ".node"), ele(base + ".ele");
  std::string header, first;
  std::getline(node, header);
  node >> first;
  EXPECT_EQ(first, "1");
  std::getline(ele, header);
  ele >> first;
  EXPECT_EQ(first, "1");
  const gdr::TriMesh back = gdr::io::read_triangle_mesh(base + ".node", base + ".ele");
  EXPECT_EQ(back.first_index, 1);
  EXPECT_EQ(back.triangles, r.mesh.triangles);
  EXPECT_EQ(back.subsegment_markers, r.mesh.subsegment_markers);
  EXPECT_EQ(back.point_markers, r.mesh.point_markers);
  std::filesystem::remove_all(dir);
}

// Regions, markers and point attributes as Triangle's .poly carries them (issue 15): the
// left half of a 2 x 1 rectangle (split by a marked segment) has an area bound and
// attribute 10, the right half attribute 20 and no bound; markers 5 outside, 7 inside; the
// point attribute x + 2y is linear, so its interpolation is exact at every Steiner point.
Pslg two_regions() {
  Pslg g;
  g.points = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {0, 1}};
  g.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 4}, {4, 5}, {5, 0}, {1, 4}};
  g.segment_markers = {5, 5, 5, 5, 5, 5, 7};
  g.point_markers = {5, 0, 5, 5, 0, 5};
  g.point_attribute_count = 1;
  for (const auto& p : g.points) g.point_attributes.push_back(p.x + 2 * p.y);
  g.regions = {{{0.5, 0.5}, 10, 0.001}, {{1.5, 0.5}, 20, -1}};
  return g;
}

TEST_P(Refine2d, RegionsMarkersAndPointAttributes) {
  const Pslg g = two_regions();
  auto o = options();
  const auto r = mesh(g, o);
  const auto& m = r.mesh;
  ASSERT_EQ(m.triangle_region.size(), m.triangles.size());
  double largest[2] = {0, 0};
  long long count[2] = {0, 0};
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    const double cx = (m.points[tri[0]].x + m.points[tri[1]].x + m.points[tri[2]].x) / 3;
    const int side = cx < 1 ? 0 : 1;
    EXPECT_EQ(m.triangle_region[t], side ? 20 : 10);
    const double area = gdr::triangle_area(m.points[tri[0]], m.points[tri[1]], m.points[tri[2]]);
    largest[side] = std::max(largest[side], area);
    ++count[side];
  }
  EXPECT_LE(largest[0], 0.001);  // the left region's bound holds
  EXPECT_GT(largest[1], 0.001);  // and only there
  EXPECT_GT(count[0], 500);
  // Markers: the segment's on its subsegments and their points; free points 0.
  ASSERT_EQ(m.subsegment_markers.size(), m.subsegments.size());
  ASSERT_EQ(m.point_markers.size(), m.points.size());
  int inner = 0;
  for (std::size_t k = 0; k < m.subsegments.size(); ++k) {
    const int s = m.subsegment_source[k];
    EXPECT_EQ(m.subsegment_markers[k], s == 6 ? 7 : 5);
    for (const int v : m.subsegments[k])
      if (m.point_type[v] == gdr::PointType::Segment) EXPECT_EQ(m.point_markers[v], s == 6 ? 7 : 5);
    inner += s == 6;
  }
  EXPECT_GT(inner, 10);  // the inner segment was split
  // Unmarked input points take the marker of the first marked segment through them in input
  // order, as in Triangle: point 1 that of segment 0, not the inner segment's.
  EXPECT_EQ(m.point_markers[1], 5);
  EXPECT_EQ(m.point_markers[0], 5);
  for (std::size_t v = 0; v < m.points.size(); ++v)
    if (m.point_type[v] == gdr::PointType::Free) EXPECT_EQ(m.point_markers[v], 0);
  ASSERT_EQ(m.point_attribute_count, 1);
  ASSERT_EQ(m.point_attributes.size(), m.points.size());
  for (std::size_t v = 0; v < m.points.size(); ++v)
    EXPECT_NEAR(m.point_attributes[v], m.points[v].x + 2 * m.points[v].y, 1e-12) << v;

  // Without region areas (Triangle without -a) the left region is not bounded; without
  // region attributes there is no Region; without markers in the input, boundary
  // subsegments get 1 and inner ones 0.
  Pslg plain = g;
  plain.segment_markers.clear();
  plain.point_markers.clear();
  o.region_areas = false;
  o.region_attributes = false;
  const auto q = mesh(plain, o);
  EXPECT_TRUE(q.mesh.triangle_region.empty());
  EXPECT_LT(q.mesh.triangles.size(), m.triangles.size() / 10);
  for (std::size_t k = 0; k < q.mesh.subsegments.size(); ++k)
    EXPECT_EQ(q.mesh.subsegment_markers[k], q.mesh.subsegment_source[k] == 6 ? 0 : 1);
}

TEST(TriangleSwitches, RegionSwitches) {
  gdr::Refine2dOptions o;
  gdr::apply_triangle_switches("pq", o);  // Triangle uses regions only when asked
  EXPECT_FALSE(o.region_areas || o.region_attributes);
  gdr::apply_triangle_switches("pqaA", o);
  EXPECT_TRUE(o.region_areas && o.region_attributes && o.refine);
  EXPECT_EQ(o.max_area, 0);
}

// The regions' area bounds count in the size estimate: bounds whose mesh cannot be numbered
// are refused at once, as a global bound is (it used to refine up to the automatic cap).
TEST(Refine2dRegions, RegionalBoundsCountInTheSizeEstimate) {
  Pslg g = two_regions();
  g.regions[0].max_area = 1e-10;
  gdr::Refine2dOptions o;
  o.backend = Backend::Cpu;
  try {
    gdr::refine_2d(g, o);
    ADD_FAILURE() << "accepted";
  } catch (const gdr::Error& e) {
    EXPECT_EQ(e.status(), gdr::Status::InvalidInput);
    EXPECT_NE(std::string(e.what()).find("the regions' maximum areas) ask for at least 1e+10"),
              std::string::npos) << e.what();
  }
}
