// CPU validators, used by tests, the CLI (--check) and the benchmarks. All topology checks
// use exact predicates. Steiner points on segments are rounded constructions, so segment
// conformity is checked through the mesh's subsegment structure with a tiny relative
// tolerance on collinearity; the (constrained) Delaunay property is exact on the stored
// coordinates.
//
// Orientation conventions (pred:: are Shewchuk's predicates, signs exact):
//  - a triangle (a,b,c) is valid when orient2d(a,b,c) > 0 (counter-clockwise);
//  - a tetrahedron (a,b,c,d) is positively oriented when orient3d(a,b,c,d) > 0 in Shewchuk's
//    convention, i.e. d lies below the plane of a,b,c (a,b,c counter-clockwise seen from
//    the side away from d). Its faces seen from outside, counter-clockwise, are then
//    (a,b,c), (a,d,b), (b,d,c), (a,c,d). With that orientation insphere(a,b,c,d,e) > 0 iff e
//    is strictly inside the circumsphere, which is what the Delaunay check uses.
// Counters count every occurrence; only the first max_problems messages are kept.
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "gdr/pslg.h"

namespace gdr {

struct QualityStats {
  std::size_t elements = 0;
  double min_angle_deg = 0, max_angle_deg = 0;        // triangles: plane angles
  double min_dihedral_deg = 0, max_dihedral_deg = 0;  // tetrahedra
  double max_radius_edge = 0, mean_radius_edge = 0;
  std::size_t bad_elements = 0;       // min angle < bound (2D) / radius-edge > bound (3D)
  double bad_measure_percent = 0;     // bad area (2D) or volume (3D) over total, in percent
  double total_measure = 0;           // area or volume
  std::vector<std::size_t> histogram; // 2D: min angle per triangle, 1-degree bins [0,60];
                                      // 3D: dihedral angles, 1-degree bins [0,180]
};

struct ValidationReport {
  bool valid = true;                  // no topology or conformity error (quality is separate)
  std::vector<std::string> problems;  // first problems found, human readable (capped)
  std::size_t inverted_elements = 0;  // zero or negative orientation
  std::size_t nonmanifold = 0;        // edges (2D) / faces (3D) shared by more than two elements
  std::size_t missing_points = 0;     // input points absent from the output
  std::size_t missing_segments = 0;   // input segments not recovered as subsegment chains
  std::size_t missing_facets = 0;     // 3D: input facets not covered by subfaces
  std::size_t non_delaunay = 0;       // locally non-(constrained-)Delaunay edges / faces
  std::size_t invalid_indices = 0;    // elements with a vertex index out of range
  std::size_t invalid_subsegments = 0;  // subsegments that are not mesh edges
  std::size_t invalid_subfaces = 0;   // 3D: subfaces that are not mesh faces
  std::size_t boundary_errors = 0;    // 3D: boundary edges not shared by exactly two boundary
                                      // faces, and (when subfaces are given) boundary faces
                                      // that are not subfaces
  QualityStats quality;
  std::string summary() const;        // one paragraph for logs and the CLI
};

struct ValidateOptions {
  double min_angle_deg = 0;           // 2D quality bound for counting bad triangles (0 = off)
  double max_radius_edge = 0;         // 3D quality bound (0 = off)
  bool check_delaunay = true;         // constrained Delaunay by exact incircle/insphere
  bool check_conformity = true;       // input points/segments/facets present
  double segment_tolerance = 1e-9;    // relative distance of subsegment vertices from segments
  // 3D: how far (degrees) subfaces may turn from the input triangles they cover, where the
  // mesher merged near-flat facets (QualityTetOptions::coplanar_angle); 0: coplanar.
  double facet_bend_deg = 0;
  std::size_t max_problems = 20;      // cap on problem messages
};

// 2D: counter-clockwise triangles, manifold edges (two triangles sharing an edge must lie on
// opposite sides of it), every input point present (exact coordinates), every input segment
// a chain of TriMesh::subsegments, every interior edge that is not a subsegment locally
// Delaunay (exact incircle). `input` may be null (no conformity check).
ValidationReport validate_trimesh(const TriMesh& mesh, const Pslg* input,
                                  const ValidateOptions& options = {});

// 3D: positive tetrahedra, manifold faces, a closed manifold boundary (every subface a
// mesh face; every boundary face a subface when subfaces are given), every input point
// present, every input segment a chain of TetMesh::subsegments, every input triangle covered
// by subfaces in its plane (the areas they share with it sum to its area within 1e-6
// relative, so coplanar input triangles may be retriangulated by the mesher), and interior
// faces that are not subfaces locally Delaunay (exact insphere).
ValidationReport validate_tetmesh(const TetMesh& mesh, const Surface* input,
                                  const ValidateOptions& options = {});

// A triangulated surface (e.g. the restricted mesher's): every edge used at most once in each
// direction (manifold and consistently oriented), with `closed` every edge used in both, every
// vertex's triangles one fan, no two triangles meeting other than in a shared vertex or edge
// (exact). Counts go to nonmanifold (edges and vertices), boundary_errors (open edges and
// intersecting pairs), inverted_elements (triangles repeating a vertex), invalid_indices.
ValidationReport validate_surface(const std::vector<Point3>& points,
                                  const std::vector<std::array<int, 3>>& triangles, bool closed,
                                  const ValidateOptions& options = {});

// Sharp features of such a surface: every subsegment is an edge of one of its triangles, and
// every feature (a pair of surface points) is a chain of subsegments running along it (its
// vertices within options.segment_tolerance of the straight edge, relative to its length).
// Counts go to invalid_subsegments and missing_segments.
ValidationReport validate_surface_features(const std::vector<Point3>& points,
                                           const std::vector<std::array<int, 3>>& triangles,
                                           const std::vector<std::array<int, 2>>& subsegments,
                                           const std::vector<std::array<int, 2>>& features,
                                           const ValidateOptions& options = {});

// Quality only (no topology), e.g. for arrays in filters.
QualityStats triangle_quality(const TriMesh& mesh, double min_angle_deg = 0);
QualityStats tet_quality(const TetMesh& mesh, double max_radius_edge = 0);

// Per-element measures in degrees / ratios (for output arrays).
void triangle_angles(const Point2& a, const Point2& b, const Point2& c, double& min_deg,
                     double& max_deg);
double triangle_radius_edge(const Point2& a, const Point2& b, const Point2& c);
double triangle_area(const Point2& a, const Point2& b, const Point2& c);  // > 0 if ccw
double tet_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d);  // > 0 if positive
double tet_radius_edge(const Point3& a, const Point3& b, const Point3& c, const Point3& d);
// The six dihedral angles in degrees, at edges ab, ac, ad, bc, bd, cd.
void tet_dihedral_angles(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                         double angles_deg[6]);

// The per-tetrahedron arrays the 3D meshers output, computed in parallel: radius-edge ratio,
// smallest and largest dihedral angle (degrees), volume; the histogram of all six dihedral
// angles (1-degree bins over [0, 180)), and their extremes.
struct TetQualityArrays {
  std::vector<float> radius_edge, min_dihedral, max_dihedral;
  std::vector<double> volume;
  std::vector<long long> dihedral_histogram;
  double total_volume = 0, min_dihedral_deg = 0, max_dihedral_deg = 0, max_radius_edge = 0;
};
TetQualityArrays tet_quality_arrays(const std::vector<Point3>& points,
                                    const std::vector<std::array<int, 4>>& tets);
// Moves the arrays into a mesher's result (QualityTetResult, RestrictedDelaunayResult).
template <class MesherResult>
void move_tet_quality(TetQualityArrays& q, MesherResult& result) {
  result.radius_edge = std::move(q.radius_edge);
  result.min_dihedral = std::move(q.min_dihedral);
  result.max_dihedral = std::move(q.max_dihedral);
  result.volume = std::move(q.volume);
  result.dihedral_histogram = std::move(q.dihedral_histogram);
}

}  // namespace gdr
