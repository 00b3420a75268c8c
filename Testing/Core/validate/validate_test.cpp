#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <map>

#include "gdr/io.h"
#include "gdr/validate.h"
#include "predicates/predicates.h"

namespace {

using namespace gdr;

// 3x3 grid on [0,2]^2 (8 right triangles), with the boundary as 8 subsegments of the
// square's 4 input segments.
TriMesh grid() {
  TriMesh m;
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 3; ++x) m.points.push_back({double(x), double(y)});
  for (int y = 0; y < 2; ++y)
    for (int x = 0; x < 2; ++x) {
      const int a = 3 * y + x, b = a + 1, c = a + 4, d = a + 3;
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  m.subsegments = {{0, 1}, {1, 2}, {2, 5}, {5, 8}, {8, 7}, {7, 6}, {6, 3}, {3, 0}};
  m.subsegment_source = {0, 0, 1, 1, 2, 2, 3, 3};
  return m;
}

Pslg square() {
  Pslg p;
  p.points = {{0, 0}, {2, 0}, {2, 2}, {0, 2}, {2, 0}};  // one duplicate point
  p.segments = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  return p;
}

TEST(ValidateTriMesh, GoodGridPasses) {
  const TriMesh m = grid();
  const Pslg p = square();
  ValidateOptions o;
  o.min_angle_deg = 50;
  const ValidationReport r = validate_trimesh(m, &p, o);
  EXPECT_TRUE(r.valid) << r.summary();
  EXPECT_TRUE(r.problems.empty());
  EXPECT_EQ(r.quality.elements, 8u);
  EXPECT_NEAR(r.quality.min_angle_deg, 45, 1e-12);
  EXPECT_NEAR(r.quality.max_angle_deg, 90, 1e-12);
  EXPECT_NEAR(r.quality.max_radius_edge, std::sqrt(0.5), 1e-12);
  EXPECT_DOUBLE_EQ(r.quality.total_measure, 4.0);
  EXPECT_EQ(r.quality.bad_elements, 8u);
  EXPECT_DOUBLE_EQ(r.quality.bad_measure_percent, 100.0);
  ASSERT_EQ(r.quality.histogram.size(), 60u);
  EXPECT_EQ(r.quality.histogram[44] + r.quality.histogram[45], 8u);
  EXPECT_NE(r.summary().find("valid"), std::string::npos);
}

TEST(ValidateTriMesh, InvertedTriangle) {
  TriMesh m = grid();
  std::swap(m.triangles[3][1], m.triangles[3][2]);
  const ValidationReport r = validate_trimesh(m, nullptr);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.inverted_elements, 1u);
  EXPECT_NE(r.summary().find("INVALID"), std::string::npos);
}

TEST(ValidateTriMesh, DuplicatedTriangleIsNonManifold) {
  for (int t : {0, 3}) {  // a corner (boundary edges) and an interior one
    TriMesh m = grid();
    m.triangles.push_back(m.triangles[t]);
    const ValidationReport r = validate_trimesh(m, nullptr);
    EXPECT_FALSE(r.valid);
    EXPECT_GE(r.nonmanifold, 2u) << r.summary();
    EXPECT_EQ(r.inverted_elements, 0u);
  }
}

TEST(ValidateTriMesh, MissingSegment) {
  TriMesh m = grid();
  m.subsegments.erase(m.subsegments.begin() + 2);  // (2,5): half of input segment 1
  m.subsegment_source.erase(m.subsegment_source.begin() + 2);
  const Pslg p = square();
  const ValidationReport r = validate_trimesh(m, &p);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.missing_segments, 1u);
  EXPECT_EQ(r.missing_points, 0u);
}

// Messages number items as the files do: a 1-based .poly's segment 2 is "input segment 2",
// and a mesh written 1-based names its vertices from 1.
TEST(ValidateTriMesh, MessagesNumberItemsAsTheFilesDo) {
  TriMesh m = grid();
  m.subsegments.erase(m.subsegments.begin() + 2);
  m.subsegment_source.erase(m.subsegment_source.begin() + 2);
  m.subsegments.push_back({0, 8});
  m.subsegment_source.push_back(-1);
  Pslg p = square();
  auto problems = [&] {
    std::string all;
    for (const std::string& text : validate_trimesh(m, &p).problems) all += text + "\n";
    return all;
  };
  const std::string zero = problems();
  p.first_index = 1;
  m.first_index = 1;
  const std::string one = problems();
  const std::string seg = std::to_string(p.segments[1][0]) + ", " + std::to_string(p.segments[1][1]);
  const std::string seg1 = std::to_string(p.segments[1][0] + 1) + ", " + std::to_string(p.segments[1][1] + 1);
  EXPECT_NE(zero.find("input segment 1 (" + seg + ")"), std::string::npos) << zero;
  EXPECT_NE(one.find("input segment 2 (" + seg1 + ")"), std::string::npos) << one;
  EXPECT_NE(one.find("(1, 9) is not an edge"), std::string::npos) << one;
}

TEST(ValidateTriMesh, SubsegmentThatIsNotAnEdge) {
  TriMesh m = grid();
  m.subsegments.push_back({0, 8});
  const ValidationReport r = validate_trimesh(m, nullptr);
  EXPECT_EQ(r.invalid_subsegments, 1u);
  EXPECT_FALSE(r.valid);
}

TEST(ValidateTriMesh, MissingInputPoint) {
  const TriMesh m = grid();
  Pslg p = square();
  p.points.push_back({1.5, 0.5});
  const ValidationReport r = validate_trimesh(m, &p);
  EXPECT_EQ(r.missing_points, 1u);
  EXPECT_FALSE(r.valid);
}

TEST(ValidateTriMesh, SegmentChainMustStayOnTheSegment) {
  TriMesh m = grid();
  m.points[1].y = 1e-3;  // the subsegment chain 0-1-2 leaves segment (0,0)-(2,0)
  const Pslg p = square();
  EXPECT_EQ(validate_trimesh(m, &p).missing_segments, 1u);
  m.points[1].y = 1e-12;  // a rounded Steiner point is fine
  ValidationReport r = validate_trimesh(m, &p);
  EXPECT_EQ(r.missing_segments, 0u) << r.summary();
}

// Kite whose Delaunay diagonal is (1,3); the flipped diagonal (0,2) is not Delaunay.
TriMesh kite(bool delaunay) {
  TriMesh m;
  m.points = {{-2, 0}, {0, -1}, {2, 0}, {0, 1}};
  if (delaunay) m.triangles = {{0, 1, 3}, {1, 2, 3}};
  else m.triangles = {{0, 1, 2}, {0, 2, 3}};
  return m;
}

TEST(ValidateTriMesh, NonDelaunayEdge) {
  EXPECT_TRUE(validate_trimesh(kite(true), nullptr).valid);
  const ValidationReport r = validate_trimesh(kite(false), nullptr);
  EXPECT_FALSE(r.valid);
  EXPECT_EQ(r.non_delaunay, 1u);
  ValidateOptions off;
  off.check_delaunay = false;
  EXPECT_TRUE(validate_trimesh(kite(false), nullptr, off).valid);
}

TEST(ValidateTriMesh, ConstrainedEdgeMayBeNonDelaunay) {
  TriMesh m = kite(false);
  m.subsegments = {{0, 2}};
  m.subsegment_source = {0};
  Pslg p;
  p.points = {{-2, 0}, {2, 0}};
  p.segments = {{0, 1}};
  const ValidationReport r = validate_trimesh(m, &p);
  EXPECT_TRUE(r.valid) << r.summary();
}

TEST(ValidateTriMesh, BadIndicesAndProblemCap) {
  TriMesh m = grid();
  m.triangles.push_back({0, 1, 99});
  for (auto& t : m.triangles) std::swap(t[0], t[1]);  // all inverted
  ValidateOptions o;
  o.max_problems = 3;
  const ValidationReport r = validate_trimesh(m, nullptr, o);
  EXPECT_EQ(r.invalid_indices, 1u);
  EXPECT_EQ(r.inverted_elements, 8u);
  EXPECT_EQ(r.problems.size(), 3u);
}

TEST(ValidateTriMesh, LargeGridIsFast) {
  const int n = 600;  // 720k triangles
  TriMesh m;
  for (int y = 0; y <= n; ++y)
    for (int x = 0; x <= n; ++x) m.points.push_back({double(x), double(y)});
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const int a = (n + 1) * y + x, b = a + 1, c = a + n + 2, d = a + n + 1;
      m.triangles.push_back({a, b, c});
      m.triangles.push_back({a, c, d});
    }
  const auto t0 = std::chrono::steady_clock::now();
  const ValidationReport r = validate_trimesh(m, nullptr);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_TRUE(r.valid) << r.summary();
  EXPECT_LT(s, 5.0);
}

// Unit cube split into 5 tetrahedra (vertex index = x + 2y + 4z), made positive.
TetMesh cube5() {
  TetMesh m;
  for (int i = 0; i < 8; ++i) m.points.push_back({double(i & 1), double((i >> 1) & 1), double(i >> 2)});
  m.tets = {{0, 1, 2, 4}, {3, 1, 2, 7}, {5, 1, 4, 7}, {6, 2, 4, 7}, {1, 2, 4, 7}};
  for (auto& t : m.tets)
    if (pred::orient3d(&m.points[t[0]].x, &m.points[t[1]].x, &m.points[t[2]].x, &m.points[t[3]].x) < 0)
      std::swap(t[0], t[1]);
  return m;
}

// The boundary faces of a tet mesh (faces used once), outward.
std::vector<std::array<int, 3>> boundary_faces(const TetMesh& m) {
  std::map<std::array<int, 3>, std::pair<int, std::array<int, 3>>> count;
  const int face[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};
  for (const auto& t : m.tets)
    for (const auto& f : face) {
      std::array<int, 3> tri{t[f[0]], t[f[1]], t[f[2]]}, key = tri;
      std::sort(key.begin(), key.end());
      auto& e = count[key];
      ++e.first;
      e.second = tri;
    }
  std::vector<std::array<int, 3>> out;
  for (const auto& [k, v] : count)
    if (v.first == 1) out.push_back(v.second);
  return out;
}

TEST(ValidateTetMesh, CubeSplitPasses) {
  TetMesh m = cube5();
  m.subfaces = boundary_faces(m);
  ASSERT_EQ(m.subfaces.size(), 12u);
  Surface s;
  s.points = m.points;
  s.triangles = m.subfaces;
  ValidateOptions o;
  o.max_radius_edge = 0.8;
  const ValidationReport r = validate_tetmesh(m, &s, o);
  EXPECT_TRUE(r.valid) << r.summary();
  EXPECT_EQ(r.quality.elements, 5u);
  EXPECT_DOUBLE_EQ(r.quality.total_measure, 1.0);
  EXPECT_NEAR(r.quality.min_dihedral_deg, 54.735610317245346, 1e-9);  // acos(1/sqrt 3)
  EXPECT_NEAR(r.quality.max_dihedral_deg, 90, 1e-9);
  EXPECT_EQ(r.quality.bad_elements, 4u);  // corner tets: R = sqrt(3)/2, shortest edge 1
  ASSERT_EQ(r.quality.histogram.size(), 180u);
  std::size_t angles = 0;
  for (auto c : r.quality.histogram) angles += c;
  EXPECT_EQ(angles, 30u);
}

TEST(ValidateTetMesh, FacetsMayBeRetriangulated) {
  TetMesh m = cube5();
  m.subfaces = boundary_faces(m);
  const Surface s = io::read_off(std::string(GDR_DATA_DIR) + "/cube.off");  // other diagonals
  ValidationReport r = validate_tetmesh(m, &s);
  EXPECT_TRUE(r.valid) << r.summary();
  m.points[7].z = 1 + 1e-3;  // corner (1,1,1) moves off the input planes
  r = validate_tetmesh(m, &s);
  EXPECT_EQ(r.missing_points, 1u);
  EXPECT_GE(r.missing_facets, 2u) << r.summary();
}

TEST(ValidateTetMesh, InvertedTet) {
  TetMesh m = cube5();
  std::swap(m.tets[2][0], m.tets[2][1]);
  const ValidationReport r = validate_tetmesh(m, nullptr);
  EXPECT_EQ(r.inverted_elements, 1u);
  EXPECT_FALSE(r.valid);
}

TEST(ValidateTetMesh, DuplicatedTetIsNonManifold) {
  TetMesh m = cube5();
  m.tets.push_back(m.tets[4]);
  const ValidationReport r = validate_tetmesh(m, nullptr);
  EXPECT_GE(r.nonmanifold, 4u);
  EXPECT_FALSE(r.valid);
}

// Two tets on a triangle; the apex of one lies inside the other's circumsphere unless the
// configuration is flipped into three tets around the apex-apex edge.
TEST(ValidateTetMesh, NonDelaunayFace) {
  TetMesh m;
  m.points = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}, {1, 1, 0.3}, {1, 1, -0.3}};
  m.tets = {{0, 1, 2, 3}, {0, 2, 1, 4}};
  for (auto& t : m.tets)
    if (pred::orient3d(&m.points[t[0]].x, &m.points[t[1]].x, &m.points[t[2]].x, &m.points[t[3]].x) < 0)
      std::swap(t[0], t[1]);
  ValidationReport r = validate_tetmesh(m, nullptr);
  EXPECT_EQ(r.non_delaunay, 1u) << r.summary();
  EXPECT_FALSE(r.valid);
  m.subfaces = boundary_faces(m);
  m.subfaces.push_back({0, 1, 2});  // constrained: allowed
  r = validate_tetmesh(m, nullptr);
  EXPECT_TRUE(r.valid) << r.summary();
}

TEST(ValidateTetMesh, OpenBoundaryAndMissingFacet) {
  TetMesh m = cube5();
  m.subfaces = boundary_faces(m);
  Surface s;
  s.points = m.points;
  s.triangles = m.subfaces;
  m.subfaces.pop_back();  // a boundary face that is not a subface, and an uncovered facet
  const ValidationReport r = validate_tetmesh(m, &s);
  EXPECT_EQ(r.boundary_errors, 1u);
  EXPECT_EQ(r.missing_facets, 1u);
  EXPECT_FALSE(r.valid);

  // Without the central tet the corner tets only touch along edges: a pinched boundary.
  TetMesh pinched = cube5();
  pinched.tets.pop_back();
  const ValidationReport o = validate_tetmesh(pinched, nullptr);
  EXPECT_GT(o.boundary_errors, 0u) << o.summary();
  EXPECT_FALSE(o.valid);
}

TEST(ValidateTetMesh, MissingPoint) {
  const TetMesh m = cube5();
  Surface s;
  s.points = m.points;
  s.points.push_back({0.5, 0.5, 0.5});
  EXPECT_EQ(validate_tetmesh(m, &s).missing_points, 1u);
}

// Sharp features of a surface (gdr rdt): the bottom edge (0, 2) of a square, split at point
// 1, as a chain of subsegments that are surface edges.
TEST(ValidateSurfaceFeatures, ChainOfSurfaceEdges) {
  std::vector<Point3> p = {{0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::vector<std::array<int, 3>> tri = {{0, 1, 4}, {1, 2, 3}, {1, 3, 4}};
  const std::vector<std::array<int, 2>> feature = {{0, 2}};
  std::vector<std::array<int, 2>> sub = {{0, 1}, {1, 2}};
  EXPECT_TRUE(validate_surface_features(p, tri, sub, feature).valid);
  sub.pop_back();  // a gap in the chain
  ValidationReport r = validate_surface_features(p, tri, sub, feature);
  EXPECT_EQ(r.missing_segments, 1u);
  EXPECT_FALSE(r.valid);
  sub = {{0, 1}, {1, 2}, {0, 3}};  // (0, 3) is no surface edge
  r = validate_surface_features(p, tri, sub, feature);
  EXPECT_EQ(r.invalid_subsegments, 1u);
  EXPECT_EQ(r.missing_segments, 0u);
  EXPECT_FALSE(r.valid);
  sub = {{0, 1}, {1, 2}};
  p[1].y = 0.1;  // the chain leaves the feature
  r = validate_surface_features(p, tri, sub, feature);
  EXPECT_EQ(r.missing_segments, 1u);
  EXPECT_FALSE(r.valid);
}

}  // namespace
