// gDP2d robustness (issue 9): exactness over the whole accepted coordinate range, refusal of
// spreads it cannot handle, statistics that stay finite, and a validator that follows the
// mesher's subsegment chains instead of walking geometry with a tolerance.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "gdr/backend.h"
#include "gdr/refine2d.h"
#include "gdr/validate.h"
#include "on_backend.h"
#include "pslg_shapes.h"

namespace {

using gdr::Point2;
using gdr::Pslg;
using gdr_test::add_loop;

// The 8-point square-in-square, scaled by s.
Pslg square_in_square(double s) {
  Pslg g;
  add_loop(g, {{-2 * s, -2 * s}, {2 * s, -2 * s}, {2 * s, 2 * s}, {-2 * s, 2 * s}});
  add_loop(g, {{-s, -s}, {s, -s}, {s, s}, {-s, s}});
  return g;
}

gdr::Refine2dOptions on(gdr::Backend backend, double min_angle) {
  gdr::Refine2dOptions o;
  o.min_angle = min_angle;
  o.backend = backend;
  return o;
}
gdr::Refine2dOptions cpu(double min_angle) { return on(gdr::Backend::Cpu, min_angle); }

std::string error_of(const Pslg& g, const gdr::Refine2dOptions& o, gdr::Status* status) {
  try {
    gdr::refine_2d(g, o);
  } catch (const gdr::Error& e) {
    *status = e.status();
    return e.what();
  }
  *status = gdr::Status::Ok;
  return {};
}

bool finite_quality(const gdr::QualityStats& q) {
  for (double v : {q.min_angle_deg, q.max_angle_deg, q.max_radius_edge, q.mean_radius_edge,
                   q.bad_measure_percent})
    if (!std::isfinite(v)) return false;
  return true;
}

// At 1e-90..1e-300 and 1e78..1e300 the mesh is the unscaled one, scaled: valid, Delaunay
// (the validator decides with exact predicates at any magnitude) and 45 degrees at a 30
// degree bound (the predicates' underflow used to give 21.8 degrees and non-Delaunay edges).
// Scaled by a power of two, the points are the unscaled mesh's times that power exactly.
// The same on both backends (the GPU test skips itself without a usable device).
class Refine2dScaleOn : public gdr::test::OnBackend {};
INSTANTIATE_TEST_SUITE_P(Backends, Refine2dScaleOn, gdr::test::both_backends(), gdr::test::backend_name);

TEST_P(Refine2dScaleOn, ExtremeMagnitudesMeshAsTheUnscaledInput) {
  const gdr::Refine2dResult unit = gdr::refine_2d(square_in_square(1), on(GetParam(), 30));
  EXPECT_NEAR(unit.stats.min_angle_deg, 45, 1e-9);
  for (double s : {1e-90, 1e-120, 1e-160, 1e-200, 1e-300, 1e78, 1e120, 1e150, 1e300}) {
    const Pslg g = square_in_square(s);
    const gdr::Refine2dResult r = gdr::refine_2d(g, on(GetParam(), 30));
    gdr::ValidateOptions vo;
    vo.min_angle_deg = 30;
    const gdr::ValidationReport v = gdr::validate_trimesh(r.mesh, &g, vo);
    EXPECT_TRUE(v.valid) << s << ": " << v.summary();
    EXPECT_EQ(v.non_delaunay, 0u) << s;
    EXPECT_EQ(r.mesh.points.size(), unit.mesh.points.size()) << s;
    EXPECT_NEAR(r.stats.min_angle_deg, 45, 1e-9) << s;
    EXPECT_NEAR(v.quality.min_angle_deg, r.stats.min_angle_deg, 1e-9) << s;
    EXPECT_TRUE(finite_quality(v.quality)) << s << ": " << v.summary();
  }
  for (int e : {-1000, -500, 500, 1000}) {
    const gdr::Refine2dResult r = gdr::refine_2d(square_in_square(std::ldexp(1.0, e)), on(GetParam(), 30));
    ASSERT_EQ(r.mesh.points.size(), unit.mesh.points.size()) << e;
    for (std::size_t i = 0; i < r.mesh.points.size(); ++i) {
      EXPECT_EQ(r.mesh.points[i].x, std::ldexp(unit.mesh.points[i].x, e)) << e << " " << i;
      EXPECT_EQ(r.mesh.points[i].y, std::ldexp(unit.mesh.points[i].y, e)) << e << " " << i;
    }
  }
}

// A box of +-1e54 around a 2x2 square: refinement grades out and ends (it never did).
TEST_P(Refine2dScaleOn, HugeBoxAroundASmallSquareEnds) {
  Pslg g;
  add_loop(g, {{-1e54, -1e54}, {1e54, -1e54}, {1e54, 1e54}, {-1e54, 1e54}});
  add_loop(g, {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}});
  const gdr::Refine2dResult r = gdr::refine_2d(g, on(GetParam(), 25));
  EXPECT_FALSE(r.stats.steiner_cap_reached);
  EXPECT_EQ(r.stats.bad_triangles, 0);
  EXPECT_LT(r.stats.output_points, 20000);
  const gdr::ValidationReport v = gdr::validate_trimesh(r.mesh, &g);
  EXPECT_TRUE(v.valid) << v.summary();
}

// Coordinates that cannot be handled exactly beside the largest are refused, naming the
// point; a bound whose square underflows beside the input's extent too.
TEST(Refine2dScale, SpreadBeyondExactArithmeticIsRefused) {
  Pslg axis;
  for (int i = 0; i < 10; ++i) axis.points.push_back({double(i), 0});
  axis.points.push_back({5, 1e-300});
  gdr::Status status;
  std::string msg = error_of(axis, cpu(20), &status);
  EXPECT_EQ(status, gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("point 10 (5, 1e-300)"), std::string::npos) << msg;
  EXPECT_NE(msg.find("exact arithmetic"), std::string::npos) << msg;

  Pslg wide;
  wide.points = {{0, 0}, {-1e308, 0}, {0, 1}};
  msg = error_of(wide, cpu(20), &status);
  EXPECT_EQ(status, gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("point 2"), std::string::npos) << msg;

  // Within the spread: 1e-60 beside 2 is exact and meshes.
  Pslg near_limit = square_in_square(1);
  near_limit.points.push_back({1e-60, 1.5});
  const gdr::Refine2dResult r = gdr::refine_2d(near_limit, cpu(20));
  EXPECT_TRUE(gdr::validate_trimesh(r.mesh, &near_limit).valid);

  auto o = cpu(20);
  o.max_edge_length = 1e-200;  // 1e-50 of a 1e150 input: fine once scaled
  msg = error_of(square_in_square(1e-150), o, &status);
  EXPECT_EQ(status, gdr::Status::InvalidInput) << "a bound 1e50 below the extent asks for 1e100 triangles";
  o.max_edge_length = 1e-151;
  const gdr::Refine2dResult bounded = gdr::refine_2d(square_in_square(1e-150), o);
  EXPECT_GT(bounded.stats.output_points, 100);
  o.max_edge_length = 1e-320;
  msg = error_of(square_in_square(1), o, &status);
  EXPECT_NE(msg.find("underflows"), std::string::npos) << msg;
}

// The validator decides with exact predicates at any magnitude: two triangles whose shared
// edge is not Delaunay, at 1e-160 (where a double incircle determinant underflows to 0).
TEST(Refine2dScale, ValidatorFindsNonDelaunayEdgesAtAnyMagnitude) {
  for (double s : {1.0, 1e-160, 1e150}) {
    gdr::TriMesh m;
    m.points = {{0, 0}, {s, 0}, {0.9 * s, 0.9 * s}, {0, 0.9 * s}};
    // (0,1,3) and (1,2,3): point 2 lies inside the circle of (0,1,3).
    m.triangles = {{0, 1, 3}, {1, 2, 3}};
    const gdr::ValidationReport v = gdr::validate_trimesh(m, nullptr);
    EXPECT_EQ(v.non_delaunay, 1u) << s << ": " << v.summary();
    EXPECT_TRUE(finite_quality(v.quality)) << v.summary();
  }
}

// Statistics never overflow: a needle from (0,0) to (-1e308,0).
TEST(Refine2dScale, StatisticsStayFinite) {
  gdr::TriMesh m;
  m.points = {{0, 0}, {0, 1}, {-1e308, 0}};
  m.triangles = {{0, 1, 2}};
  const gdr::ValidationReport v = gdr::validate_trimesh(m, nullptr);
  EXPECT_TRUE(finite_quality(v.quality)) << v.summary();
  EXPECT_NEAR(v.quality.max_angle_deg, 90, 1e-9);
  EXPECT_TRUE(std::isfinite(v.quality.total_measure));
  const std::string text = v.summary();
  EXPECT_EQ(text.find("inf"), std::string::npos) << text;
  EXPECT_EQ(text.find("nan"), std::string::npos) << text;
  m.points = {{0, 0}, {1e300, 0}, {0, 1e300}};  // area beyond the doubles
  const std::string huge = gdr::validate_trimesh(m, nullptr).summary();
  EXPECT_EQ(huge.find("inf"), std::string::npos) << huge;
}

// --check false alarms: segments from one point 1e-9..1e-15 rad apart, and segments crossing
// at a tiny angle (split), were reported missing by the geometric chain walk, which stepped
// onto the neighbouring segment within its tolerance. The subsegment structure says which
// input segment each subsegment lies on.
TEST(Refine2dScale, ConformityFollowsTheSubsegmentStructure) {
  const std::vector<Point2> box = {{-1, -1}, {3, -1}, {3, 3}, {-1, 3}};
  for (double a : {1e-9, 1e-12, 1e-15}) {
    Pslg g;
    add_loop(g, box);
    g.points.insert(g.points.end(), {{0, 0}, {2, 0}, {2 * std::cos(a), 2 * std::sin(a)}});
    g.segments.insert(g.segments.end(), {{4, 5}, {4, 6}});
    const gdr::Refine2dResult r = gdr::refine_2d(g, cpu(20));
    const gdr::ValidationReport v = gdr::validate_trimesh(r.mesh, &g);
    EXPECT_TRUE(v.valid) << a << ": " << v.summary();
  }
  Pslg x;  // two segments crossing at 5e-13 rad, split at their intersection
  add_loop(x, box);
  x.points.insert(x.points.end(), {{0, 0}, {2, 1e-12}, {0, 1e-12}, {2, 0}});
  x.segments.insert(x.segments.end(), {{4, 5}, {6, 7}});
  const gdr::Refine2dResult r = gdr::refine_2d(x, cpu(20));
  const gdr::ValidationReport v = gdr::validate_trimesh(r.mesh, &x);
  EXPECT_TRUE(v.valid) << v.summary();
  // A broken chain is still found: one subsegment of a crossing segment dropped.
  gdr::TriMesh broken = r.mesh;
  for (std::size_t k = 0; k < broken.subsegments.size(); ++k)
    if (broken.subsegment_source[k] == 4) {
      broken.subsegments.erase(broken.subsegments.begin() + k);
      broken.subsegment_source.erase(broken.subsegment_source.begin() + k);
      break;
    }
  EXPECT_EQ(gdr::validate_trimesh(broken, &x).missing_segments, 1u);
}

}  // namespace

namespace {

// Segments that border only removed regions (a hole ring inside a hole; an open chain with
// the exterior removed; the outer half of a segment leaving the domain) are said while
// meshing, listed in the mesh, and not reported missing.
TEST(Refine2dRemoved, SegmentsBorderingOnlyRemovedRegionsAreSaidAndAccepted) {
  Pslg nested;
  add_loop(nested, {{0, 0}, {4, 0}, {4, 4}, {0, 4}});
  add_loop(nested, {{1, 1}, {3, 1}, {3, 3}, {1, 3}});
  add_loop(nested, {{1.5, 1.5}, {2.5, 1.5}, {2.5, 2.5}, {1.5, 2.5}});
  nested.holes = {{1.2, 1.2}, {2, 2}};
  Pslg open;
  open.points = {{0, 0}, {4, 0}, {4, 4}, {0, 4}, {1, 1}, {3, 1}, {3, 3}, {1, 3}};
  open.segments = {{0, 1}, {1, 2}, {2, 3}, {4, 5}, {5, 6}, {6, 7}, {7, 4}};  // 3-0 missing
  Pslg leaving;
  add_loop(leaving, {{0, 0}, {4, 0}, {4, 4}, {0, 4}});
  leaving.points.insert(leaving.points.end(), {{2, 2}, {6, 2}});
  leaving.segments.push_back({4, 5});  // split at (4, 2); its outer half goes
  for (const Pslg* g : {&nested, &open, &leaving}) {
    auto o = cpu(20);
    o.remove_exterior = true;
    std::string said;
    gdr::Callbacks cb;
    cb.warning = [&](const std::string& w) { said += w; };
    const gdr::Refine2dResult r = gdr::refine_2d(*g, o, cb);
    const std::vector<int> expected = g == &nested ? std::vector<int>{8, 9, 10, 11}
                                      : g == &open ? std::vector<int>{0, 1, 2}
                                                   : std::vector<int>{4};
    EXPECT_EQ(r.mesh.removed_segments, expected);
    EXPECT_NE(said.find(std::to_string(expected.size()) + " input segment(s) border removed"),
              std::string::npos) << said;
    if (g == &open) EXPECT_NE(said.find("open (point 0, 3)"), std::string::npos) << said;
    const gdr::ValidationReport v = gdr::validate_trimesh(r.mesh, g);
    EXPECT_TRUE(v.valid) << v.summary();
    gdr::TriMesh unlisted = r.mesh;  // without the list they are missing
    unlisted.removed_segments.clear();
    EXPECT_EQ(gdr::validate_trimesh(unlisted, g).missing_segments, expected.size());
  }
}

}  // namespace

namespace {

// Reproducibility: with deterministic set, two runs of a segment soup (split at its 2,000-odd
// crossings) give the same mesh, point for point; a GPU run cannot promise that and is refused.
TEST(Refine2dDeterministic, SameMeshOnEveryRun) {
  Pslg soup;
  unsigned x = 12345;
  const auto next = [&x] {
    x = x * 1103515245u + 12345u;
    return (x >> 8) / 16777216.0;
  };
  for (int i = 0; i < 80; ++i) {
    soup.points.push_back({next(), next()});
    soup.points.push_back({next(), next()});
    soup.segments.push_back({2 * i, 2 * i + 1});
  }
  auto o = cpu(25);
  o.deterministic = true;
  const gdr::Refine2dResult a = gdr::refine_2d(soup, o), b = gdr::refine_2d(soup, o);
  ASSERT_EQ(a.mesh.points.size(), b.mesh.points.size());
  EXPECT_GT(a.mesh.points.size(), 1000u);
  for (std::size_t i = 0; i < a.mesh.points.size(); ++i) {
    EXPECT_EQ(a.mesh.points[i].x, b.mesh.points[i].x) << i;
    EXPECT_EQ(a.mesh.points[i].y, b.mesh.points[i].y) << i;
  }
  EXPECT_EQ(a.mesh.triangles, b.mesh.triangles);
  EXPECT_TRUE(gdr::validate_trimesh(a.mesh, &soup).valid);
  o.backend = gdr::Backend::Gpu;
  gdr::Status status;
  const std::string msg = error_of(soup, o, &status);
  EXPECT_EQ(status, gdr::Status::InvalidInput);
  EXPECT_NE(msg.find("deterministic"), std::string::npos) << msg;
}

}  // namespace

namespace {

// Hole seeds that cannot empty a region are said: outside the domain, on a point, on a segment.
TEST(Refine2dHoles, MisplacedSeedsAreSaid) {
  const std::vector<std::pair<Point2, std::string>> cases = {
      {{10, 10}, "hole 0 lies outside the domain"},
      {{1, 1}, "hole 0 lies on an input point"},
      {{2, 1}, "hole 0 lies on segment 4"},
      {{2, 2}, ""}};
  for (const auto& [seed, expected] : cases) {
    Pslg g;
    add_loop(g, {{0, 0}, {4, 0}, {4, 4}, {0, 4}});
    add_loop(g, {{1, 1}, {3, 1}, {3, 3}, {1, 3}});
    g.holes = {seed};
    std::string said;
    gdr::Callbacks cb;
    cb.warning = [&](const std::string& w) { said += w + "\n"; };
    gdr::refine_2d(g, cpu(20), cb);
    if (expected.empty()) EXPECT_EQ(said.find("hole"), std::string::npos) << said;
    else EXPECT_NE(said.find(expected), std::string::npos) << said;
  }
}

}  // namespace

namespace {

// Segments from one vertex at angles of 1e-8 to 1e-14 rad (scripts/fuzz2d.py fan) with
// diametral circles: the shells that split them at matching distances from the apex lie
// just outside each other's diametral circles, by less than rounding; rounding made them
// encroach each other, and the shells went on down to 1e-71 from the apex (9,407 points in
// 1,082 iterations and a stall at 20 degrees; 267,139 points in 1,418 iterations at 33).
// Now a few hundred points, no stall, a valid mesh.
TEST(Refine2dSmallAngles, FanOfTinyAnglesDoesNotCascade) {
  struct Case {
    std::vector<Point2> ends;
    double angle;
  };
  const std::vector<Case> cases = {
      {{{1.9999999999999998, 3.059677494714037e-08},
        {1.9999999999999998, 2.637710378872713e-08},
        {1.9999999999904727, 6.173245868785925e-06}},
       20},
      {{{2.0, 3.558401084489544e-11}, {2.0, 7.92454647949038e-13}}, 33}};
  for (const Case& c : cases) {
    Pslg g;
    add_loop(g, {{-1, -1}, {3, -1}, {3, 3}, {-1, 3}});
    g.points.push_back({0, 0});
    for (const Point2& e : c.ends) {
      g.points.push_back(e);
      g.segments.push_back({4, static_cast<int>(g.points.size()) - 1});
    }
    gdr::Refine2dOptions o = cpu(c.angle);
    o.mode = gdr::EncroachMode::Ruppert;
    const gdr::Refine2dResult r = gdr::refine_2d(g, o);
    EXPECT_LT(r.stats.steiner_points, 3000) << c.angle;
    EXPECT_FALSE(r.stats.stalled) << c.angle;
    EXPECT_FALSE(r.stats.steiner_cap_reached) << c.angle;
    const gdr::ValidationReport rep = gdr::validate_trimesh(r.mesh, &g, gdr::ValidateOptions{});
    EXPECT_TRUE(rep.valid) << c.angle << ": " << rep.summary();
  }
}

}  // namespace
