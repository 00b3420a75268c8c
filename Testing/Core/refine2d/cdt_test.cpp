// The parallel constrained Delaunay triangulation (refine2d/cdt_engine.h) against CGAL's,
// its oracle, on every backend: the same triangles where no four points are cocircular,
// and where they are (grids, circles), a valid constrained Delaunay triangulation of the
// same domain by the validators.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <random>

#include "gdr/io.h"
#include "gdr/refine2d.h"
#include "gdr/validate.h"
#include "on_backend.h"
#include "pslg_shapes.h"
#include "refine2d/input.h"

namespace {

using gdr::Backend;
using gdr::CdtMethod;
using gdr::Point2;
using gdr::Pslg;
using gdr_test::add_loop;
using gdr_test::kPi;

// Triangles as sorted triples of point coordinates' indices, each rotated to start at its
// smallest vertex (orientation kept).
std::vector<std::array<int, 3>> canonical(const gdr::TriMesh& m) {
  std::vector<std::array<int, 3>> t;
  for (const auto& tri : m.triangles) {
    std::array<int, 3> a = {tri[0], tri[1], tri[2]};
    std::rotate(a.begin(), std::min_element(a.begin(), a.end()), a.end());
    t.push_back(a);
  }
  std::sort(t.begin(), t.end());
  return t;
}

class ParallelCdt : public gdr::test::OnBackend {
 protected:
  gdr::TriMesh cdt(const Pslg& g, CdtMethod method, bool remove_exterior) {
    gdr::Refine2dOptions o;
    o.refine = false;
    o.cdt = method;
    o.remove_exterior = remove_exterior;
    o.backend = method == CdtMethod::Cgal ? Backend::Cpu : GetParam();
    gdr::Refine2dResult r = gdr::refine_2d(g, o);
    const gdr::ValidationReport rep = gdr::validate_trimesh(r.mesh, &g, {});
    EXPECT_TRUE(rep.valid) << rep.summary();
    EXPECT_EQ(rep.non_delaunay, 0u);
    EXPECT_EQ(rep.missing_segments, 0u);
    EXPECT_EQ(rep.missing_points, 0u);
    if (method == CdtMethod::Parallel)
      EXPECT_EQ(r.stats.cdt_method, GetParam() == Backend::Gpu ? "parallel-gpu" : "parallel-cpu");
    return r.mesh;
  }

  // Both CDTs of g: the same triangles (general position) or as many (cocircular points).
  void compare(const Pslg& g, bool remove_exterior, bool general_position) {
    const gdr::TriMesh a = cdt(g, CdtMethod::Cgal, remove_exterior);
    const gdr::TriMesh b = cdt(g, CdtMethod::Parallel, remove_exterior);
    ASSERT_EQ(a.points.size(), b.points.size());
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    EXPECT_EQ(a.subsegments.size(), b.subsegments.size());
    if (general_position) EXPECT_TRUE(canonical(a) == canonical(b)) << "the triangulations differ";
  }
};

TEST_P(ParallelCdt, RandomPoints) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  Pslg g;
  for (int i = 0; i < 20000; ++i) g.points.push_back({u(rng), u(rng)});
  compare(g, false, true);
}

// Points in a tight cluster and a few far away: many rounds insert into a few triangles.
TEST_P(ParallelCdt, ClusteredPoints) {
  std::mt19937 rng(5);
  std::normal_distribution<double> u(0, 1e-6);
  Pslg g;
  for (int i = 0; i < 5000; ++i) g.points.push_back({0.3 + u(rng), 0.2 + u(rng)});
  add_loop(g, gdr_test::square(-1, -1, 1, 1));
  compare(g, false, true);
  compare(g, true, true);
}

TEST_P(ParallelCdt, RandomSegmentsInCells) {
  const int n = 60;
  Pslg g = gdr_test::segments_in_cells(n, 7);
  compare(g, false, true);
  add_loop(g, gdr_test::square(-0.5, -0.5, n + 0.5, n + 0.5));
  compare(g, true, true);
}

// Long segments across a dense cloud: each crosses hundreds of triangles, so the
// pseudo-polygons on its sides are long (and claims of neighbouring segments collide).
TEST_P(ParallelCdt, LongSegmentsThroughACloud) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1);
  Pslg g;
  for (int i = 0; i < 20000; ++i) g.points.push_back({u(rng), u(rng)});
  for (int k = 0; k < 40; ++k) {  // chords between the left and right sides, not crossing
    const int a = static_cast<int>(g.points.size());
    const double y = (k + 0.5) / 40;
    g.points.push_back({-0.01, y});
    g.points.push_back({1.01, y + 0.01 * std::sin(k)});
    g.segments.push_back({a, a + 1});
  }
  compare(g, false, true);
}

TEST_P(ParallelCdt, CocircularGridAndCircle) {
  Pslg g;
  const int n = 60;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) g.points.push_back({double(i), double(j)});
  add_loop(g, gdr_test::square(-1, -1, n, n));
  g.segments.push_back({0, n * n - 1});  // the grid's diagonal: through grid points, split
  compare(g, false, false);
  Pslg c;
  for (int i = 0; i < 4096; ++i) {
    // Exactly cocircular where cos and sin are exact (multiples of 90 degrees) and within
    // rounding elsewhere: ties and near-ties.
    const double t = 2 * kPi * i / 4096;
    c.points.push_back({std::cos(t), std::sin(t)});
  }
  compare(c, false, false);
}

TEST_P(ParallelCdt, CollinearPointsOnTheHullAndOnSegments) {
  Pslg g;
  for (int i = 0; i <= 40; ++i) g.points.push_back({i * 0.25, 0.0});  // a hull edge's points
  for (int i = 0; i < 20; ++i) g.segments.push_back({i, i + 1});      // half of them joined
  g.points.push_back({5, 3});
  for (int i = 1; i < 30; ++i) g.points.push_back({5 + i * 0.1, 3 - i * 0.1});  // collinear run
  compare(g, false, false);
}

TEST_P(ParallelCdt, HolesAndRegions) {
  Pslg g;
  add_loop(g, gdr_test::square(0, 0, 4, 2));
  add_loop(g, gdr_test::square(0.5, 0.5, 1.5, 1.5));
  add_loop(g, gdr_test::square(2.5, 0.5, 3.5, 1.5));
  g.holes.push_back({1, 1});
  gdr::RegionSeed2 r;
  r.point = {3, 1};
  r.attribute = 7;
  g.regions.push_back(r);
  compare(g, true, false);
  const gdr::TriMesh m = cdt(g, CdtMethod::Parallel, true);
  ASSERT_EQ(m.triangle_region.size(), m.triangles.size());
  int in_region = 0;
  for (double a : m.triangle_region) in_region += a == 7;
  EXPECT_GT(in_region, 0);
}

TEST_P(ParallelCdt, SharedDataPslgs) {
  const std::filesystem::path dir = std::filesystem::path(GDR_SHARED_DATA_DIR) / "pslg";
  if (!std::filesystem::exists(dir)) GTEST_SKIP() << "no shared data at " << dir;
  int n = 0;
  for (const auto& f : std::filesystem::directory_iterator(dir)) {
    if (f.path().extension() != ".poly") continue;
    SCOPED_TRACE(f.path().string());
    const Pslg g = gdr::io::read_poly(f.path().string());
    compare(g, false, false);
    compare(g, true, false);
    ++n;
  }
  EXPECT_GE(n, 3);
}

// The parallel CDT is assembled where it ran (refine2d/cdt_assembly.h), or on the host
// (GDR_DISABLE=cdt_assembly; always for hole and region seeds and for slivers at the hull):
// the same triangles and subsegments, with the same sources, either way; and the thin-part
// estimate made there refuses what the host's refuses, with the same numbers.
TEST_P(ParallelCdt, AssembledWhereItRanAsOnTheHost) {
  const auto both = [&](const Pslg& g, bool remove_exterior) {
    unsetenv("GDR_DISABLE");
    const gdr::TriMesh a = cdt(g, CdtMethod::Parallel, remove_exterior);
    setenv("GDR_DISABLE", "cdt_assembly", 1);
    const gdr::TriMesh b = cdt(g, CdtMethod::Parallel, remove_exterior);
    unsetenv("GDR_DISABLE");
    ASSERT_EQ(a.points.size(), b.points.size());
    EXPECT_TRUE(canonical(a) == canonical(b)) << "the triangulations differ";
    std::vector<std::array<int, 3>> sa, sb;  // (ends, source) of each subsegment
    for (std::size_t k = 0; k < a.subsegments.size(); ++k)
      sa.push_back({std::min(a.subsegments[k][0], a.subsegments[k][1]),
                    std::max(a.subsegments[k][0], a.subsegments[k][1]), a.subsegment_source[k]});
    for (std::size_t k = 0; k < b.subsegments.size(); ++k)
      sb.push_back({std::min(b.subsegments[k][0], b.subsegments[k][1]),
                    std::max(b.subsegments[k][0], b.subsegments[k][1]), b.subsegment_source[k]});
    std::sort(sa.begin(), sa.end());
    std::sort(sb.begin(), sb.end());
    EXPECT_TRUE(sa == sb) << "the subsegments differ";
    ASSERT_EQ(a.triangle_region.size(), b.triangle_region.size());
    const auto regions = [](const gdr::TriMesh& m) {  // (corners, region) of each triangle
      std::vector<std::pair<std::array<int, 3>, double>> r;
      for (std::size_t t = 0; t < m.triangle_region.size(); ++t) {
        std::array<int, 3> c = m.triangles[t];
        std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
        r.push_back({c, m.triangle_region[t]});
      }
      std::sort(r.begin(), r.end());
      return r;
    };
    EXPECT_TRUE(regions(a) == regions(b)) << "the regions differ";
  };
  const int n = 40;
  Pslg g = gdr_test::segments_in_cells(n, 3);
  both(g, false);  // the convex hull: hull segments numbered in the space
  add_loop(g, gdr_test::square(-0.5, -0.5, n + 0.5, n + 0.5));
  both(g, true);   // the exterior removed
  // Holes and regions: a hole inside a region, two seeds in one region (the later wins), a
  // seed in a hole and one outside (they mark nothing), seeds on a vertex and on a segment.
  Pslg r = gdr_test::segments_in_cells(20, 5);
  add_loop(r, gdr_test::square(-0.5, -0.5, 20.5, 20.5));
  add_loop(r, gdr_test::square(2.2, 2.2, 7.8, 7.8));
  add_loop(r, gdr_test::square(3.1, 3.1, 3.9, 3.9));
  r.holes.push_back({3.5, 3.5});
  for (const Point2 p : {Point2{2.5, 2.5}, Point2{7.5, 7.5}, Point2{3.5, 3.45}, Point2{40, 40},
                         Point2{15.3, 12.6}, r.points[0], Point2{-0.5, 5}})
    r.regions.push_back({p, static_cast<double>(r.regions.size() + 1), 0});
  both(r, true);
  both(r, false);
  // Points within 1e-12 of a hull edge: slivers to peel, left to the host. (The square's
  // sides are input and hull segments at once: the subsegments keep the input's numbers.)
  Pslg h;
  add_loop(h, gdr_test::square(0, 0, 10, 10));
  for (int i = 1; i < 10; ++i) h.points.push_back({double(i), (i % 2 ? -1e-12 : 1e-12) + 0.0});
  both(h, false);

  // A thin domain: refused from the estimate made where the CDT is.
  Pslg thin;
  add_loop(thin, gdr_test::square(0, 0, 1, 1e-11));
  for (int i = 0; i < 200; ++i) thin.points.push_back({0.3 + i * 1e-3, 0.5e-11});
  gdr::Refine2dOptions o;
  o.min_angle = 25;
  o.cdt = CdtMethod::Parallel;
  o.backend = GetParam();
  std::string said[2];
  for (int host = 0; host < 2; ++host) {
    if (host) setenv("GDR_DISABLE", "cdt_assembly", 1);
    try {
      gdr::refine_2d(thin, o);
      ADD_FAILURE() << "a 1 x 1e-11 rectangle at 25 degrees was meshed";
    } catch (const gdr::Error& e) {
      said[host] = e.what();
    }
    unsetenv("GDR_DISABLE");
  }
  EXPECT_NE(said[0].find("Steiner points in the input's thin parts"), std::string::npos) << said[0];
  EXPECT_EQ(said[0], said[1]);
}

// Refinement from the parallel CDT: a valid quality mesh, as from CGAL's.
TEST_P(ParallelCdt, RefinementFromIt) {
  Pslg g;
  add_loop(g, gdr_test::square(0, 0, 3, 1));
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(0.1, 0.9);
  for (int i = 0; i < 200; ++i) g.points.push_back({3 * u(rng), u(rng)});
  gdr::Refine2dOptions o;
  o.cdt = CdtMethod::Parallel;
  o.backend = GetParam();
  o.min_angle = 30;
  const gdr::Refine2dResult r = gdr::refine_2d(g, o);
  gdr::ValidateOptions vo;
  vo.min_angle_deg = 30;
  const gdr::ValidationReport rep = gdr::validate_trimesh(r.mesh, &g, vo);
  EXPECT_TRUE(rep.valid) << rep.summary();
  EXPECT_EQ(r.stats.bad_triangles, 0);
  EXPECT_GT(r.stats.steiner_points, 0);
}

// The input checks of large GPU runs (refine2d/input_checks.h) call an input clean exactly
// when the host's checks find nothing to mend: each defect alone, on a map of segments in
// cells (many cells of the grid), is found in each space; the host's path agrees (a GPU run
// of a defective input takes the host's path and gives the CPU's mesh).
TEST_P(ParallelCdt, InputChecksFindEachDefect) {
  const auto is_clean = [&](const Pslg& g) {
#if defined(GDR_HAVE_CUDA)
    if (GetParam() == Backend::Gpu) return gdr::r2d::input_is_clean_cuda(g.points, g.segments);
#endif
    return gdr::r2d::input_is_clean_cpu(g.points, g.segments);
  };
  const auto host_mends = [](const Pslg& g) {
    gdr::Refine2dOptions o;
    o.refine = false;
    std::vector<std::string> said;
    gdr::Callbacks cb;
    cb.warning = [&](const std::string& w) { said.push_back(w); };
    const gdr::r2d::CleanPslg c = gdr::r2d::clean_input(g, o, cb);
    return !said.empty() || c.points.size() != g.points.size() || c.segments.size() != g.segments.size();
  };
  Pslg base = gdr_test::segments_in_cells(40, 3);
  base.points.push_back({20.5, 20.5});  // a point on no segment, in no segment's way
  add_loop(base, gdr_test::square(-1, -1, 41, 41));
  EXPECT_TRUE(is_clean(base));
  EXPECT_FALSE(host_mends(base));
  const int a = base.segments[100][0], b = base.segments[100][1];
  const Point2 pa = base.points[a], pb = base.points[b];
  std::vector<std::pair<std::string, Pslg>> defects;
  auto with = [&](const std::string& what, auto change) {
    Pslg g = base;
    change(g);
    defects.push_back({what, g});
  };
  with("duplicate point", [&](Pslg& g) { g.points.push_back(g.points[7]); });
  with("-0 beside 0", [&](Pslg& g) {
    g.points.push_back({0.0, 45.0});
    g.points.push_back({-0.0, 45.0});
  });
  with("repeated segment, reversed", [&](Pslg& g) { g.segments.push_back({b, a}); });
  with("crossing", [&](Pslg& g) {
    const int n = static_cast<int>(g.points.size());
    const Point2 m{(pa.x + pb.x) / 2, (pa.y + pb.y) / 2};
    g.points.push_back({m.x - (pb.y - pa.y), m.y + (pb.x - pa.x)});
    g.points.push_back({m.x + (pb.y - pa.y), m.y - (pb.x - pa.x)});
    g.segments.push_back({n, n + 1});
  });
  with("an end on another's interior", [&](Pslg& g) {
    const int n = static_cast<int>(g.points.size());
    g.points.push_back({(pa.x + pb.x) / 2, (pa.y + pb.y) / 2});
    g.points.push_back({(pa.x + pb.x) / 2 + 0.01, (pa.y + pb.y) / 2 - 0.003});
    g.segments.push_back({n, n + 1});
  });
  with("collinear overlap", [&](Pslg& g) {
    const int n = static_cast<int>(g.points.size());
    for (double x : {50.0, 52.0, 51.0, 53.0}) g.points.push_back({x, 0.5 * x});
    g.segments.push_back({n, n + 1});
    g.segments.push_back({n + 2, n + 3});
  });
  with("a point on a segment", [&](Pslg& g) { g.points.push_back({-1, 3.25}); });
  for (const auto& [what, g] : defects) {
    EXPECT_FALSE(is_clean(g)) << what;
    EXPECT_TRUE(host_mends(g)) << what;
  }
  // Through the facade: the crossing is split, as on the CPU, and the CDT is valid.
  gdr::Refine2dOptions o;
  o.refine = false;
  o.cdt = CdtMethod::Parallel;
  o.backend = GetParam();
  std::vector<std::string> said;
  gdr::Callbacks cb;
  cb.warning = [&](const std::string& w) { said.push_back(w); };
  const gdr::Refine2dResult r = gdr::refine_2d(defects[3].second, o, cb);
  EXPECT_EQ(r.mesh.points.size(), defects[3].second.points.size() + 1);  // the crossing point
  ASSERT_FALSE(said.empty());
  EXPECT_NE(said[0].find("split"), std::string::npos) << said[0];
  EXPECT_TRUE(gdr::validate_trimesh(r.mesh, &defects[3].second, {}).valid);
}

INSTANTIATE_TEST_SUITE_P(Backends, ParallelCdt, gdr::test::both_backends(), gdr::test::backend_name);

}  // namespace
