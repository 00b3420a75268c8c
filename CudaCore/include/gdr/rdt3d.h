// gDP3d: surface and volume meshing by 3D restricted Delaunay refinement (Chen & Tan,
// section 7; the criteria of CGAL Mesh_3). Public, VTK-free, CUDA-free facade.
//
// The output approximates the input surface rather than keeping it: surface vertices lie on
// it (up to rounding), surface triangles are the restricted facets (Delaunay faces whose
// Voronoi dual meets the input), tetrahedra are those whose circumcentre lies inside it. For
// a closed input, with tetrahedra or without, the surface is the boundary of the tetrahedra
// inside: a restricted facet between two tetrahedra on the same side (its dual touches the
// input without crossing it, or crosses it twice) bounds nothing and is left out, with a
// count (facets_left_out).
//
// Sharp features (optional: FeatureAngle, or the input's segments) are kept: feature edges
// are sampled first and protected as constrained segments are in Ruppert's refinement (a
// point in the diametral ball of a feature subsegment is refused and the subsegment split
// instead), so the output has every corner as a vertex and every feature edge as a chain of
// surface edges. Next to features at small angles, facets and cells that cannot meet the
// criteria are left as they are and reported (bad_facets, bad_tets).
#pragma once
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "gdr/backend.h"
#include "gdr/error.h"
#include "gdr/progress.h"
#include "gdr/pslg.h"
#include "gdr/refine2d.h"  // PhaseTime

namespace gdr {

// Sizes: a negative value asks for the automatic default (relative to the diagonal D of the
// input's bounding box), 0 turns the criterion off.
struct RestrictedDelaunayOptions {
  double facet_angle = 30.0;            // FacetAngle: smallest facet angle, degrees, in [0, 30]
  double facet_size = -1.0;             // FacetSize: surface Delaunay ball radius (auto: D / 20)
  double facet_distance = -1.0;         // FacetDistance: facet to surface (auto: D / 500)
  double cell_radius_edge_ratio = 2.0;  // CellRadiusEdgeRatio: 0 off, else at least 1 (2: guaranteed)
  double cell_size = -1.0;              // CellSize: circumradius (auto: the facet size)
  bool mesh_volume = true;              // MeshVolume: false (or an open input): surface only
  // FeatureAngle, degrees in [0, 180): input edges whose two triangles' normals differ by
  // more than this are sharp features, and so are the boundary edges of an open surface; 0
  // (the default) detects none. The input's segments are features in any case.
  double feature_angle = 0.0;
  // Manifold (CGAL Mesh_3's manifold()): once every facet and cell meets the criteria, the
  // facets at edges and vertices where the surface is not a 2-manifold (a thin part pinched,
  // an edge with one or three facets) are refined until it is one (for an open input: a
  // manifold with boundary), down to facets of D / 1000 or an eighth of the facet size;
  // what is left there is reported (non_manifold_facets). false: CGAL's non_manifold().
  bool manifold = true;
  // Refinement stops cleanly at this many Steiner points. -1 (automatic): a cap applies only
  // where termination is not guaranteed (radius-edge ratio below 2).
  long long max_steiner_points = -1;
  // SliverAngle: sliver removal after refinement, in degrees in [0, 30] (0, the default: off).
  // Interior Steiner points of tetrahedra with a dihedral angle below it (or above 180 minus
  // it) move to raise the smallest dihedral angle around them (mesh3d/smooth.h, the pass gQM3d
  // runs), keeping every tetrahedron that met CellRadiusEdgeRatio and CellSize meeting them.
  // Only points whose tetrahedra all lie inside the surface move (surface and feature points
  // stay): the surface (triangles, points, their measures) and the volume stay exactly as
  // they were. The mesh is then not Delaunay where points moved. Volume meshing only.
  double sliver_angle = 0.0;
  Backend backend = Backend::Auto;
  bool keep_triangulation = false;  // also return the whole Delaunay triangulation (checks)
};

struct RestrictedDelaunayStats {
  Backend backend_used = Backend::Cpu;
  std::string device_name;
  bool closed_input = false;
  bool volume_meshed = false;
  int iterations = 0;
  long long input_points = 0, input_triangles = 0;
  long long initial_points = 0;            // input points sampled for the initial triangulation
  long long feature_edges = 0, corners = 0;  // input feature edges and corners (FeatureAngle)
  long long feature_points = 0;            // output vertices on features (corners included)
  // Feature subsegments that no surface facet holds: there the surface cuts across the sharp
  // edge (an acute crease sampled unevenly on its two sides) and relabelling the tetrahedra
  // round them (rdt3d/feature_sides.h) did not bring it back; reported, and --check fails.
  long long features_off_surface = 0;
  long long feature_relabelled = 0;        // tetrahedra that changed side to keep feature subsegments
  long long steiner_points = 0;            // inserted by the refinement
  long long triangulation_points = 0, triangulation_tets = 0;  // the whole Delaunay triangulation
  long long output_points = 0, output_tets = 0, output_triangles = 0;
  long long bad_facets = 0, bad_tets = 0;  // left above the bounds (stall or cap)
  // Restricted facets between two tetrahedra on the same side of a closed input (a dual that
  // touches it or crosses it twice): they bound nothing and are not in the surface.
  long long facets_left_out = 0;
  long long manifold_splits = 0;           // facets refined by the manifold criterion
  long long non_manifold_facets = 0;       // surface facets at a non-manifold edge or vertex, at the end
  long long pinch_relabelled = 0;          // tetrahedra that changed side to undo pinches (rdt3d/pinches.h)
  double manifold_min_size = 0;            // the manifold criterion refines facets down to this
  long long steiner_cap = -1;
  bool steiner_cap_reached = false;
  bool stalled = false;
  double min_facet_angle_deg = 0, max_facet_size = 0, max_facet_distance = 0;
  double min_dihedral_deg = 0, max_dihedral_deg = 0, max_radius_edge = 0;
  // Sliver removal (sliver_angle > 0): tetrahedra with an angle beyond it before and after,
  // and the points moved (none: the mesh is still Delaunay).
  long long slivers_before = 0, slivers_after = 0, sliver_moves = 0;
  double sliver_angle = 0;                 // in effect (0 when only the surface is meshed)
  double volume = 0, area = 0;             // of the output
  double facet_angle = 0, facet_size = 0, facet_distance = 0, cell_radius_edge_ratio = 0,
         cell_size = 0, feature_angle = 0;  // the criteria in effect (automatic sizes resolved)
  double feature_min_length = 0;           // feature subsegments shorter are not split
  double input_seconds = 0, initial_seconds = 0, refine_seconds = 0, output_seconds = 0,
         total_seconds = 0;
  std::size_t peak_device_bytes = 0;
  std::vector<PhaseTime> phases;
};

struct RestrictedDelaunayResult {
  // Points used by the output; tets: those inside the surface (empty for a surface only);
  // subfaces: the restricted surface triangles (outward for a closed input, following the
  // input's orientation for an open one); subsegments: the surface edges on sharp features.
  // point_type: Input at corners, Segment on a feature edge, Facet on the surface (sampled or
  // inserted), Free inside it.
  TetMesh mesh;
  // The input's feature edges, as pairs of mesh points (their ends): each is a chain of
  // mesh.subsegments (validate_surface_features).
  std::vector<std::array<int, 2>> features;
  // Per surface triangle.
  std::vector<float> facet_min_angle;    // degrees
  std::vector<double> facet_size;        // surface Delaunay ball radius
  std::vector<double> facet_distance;    // facet circumcentre to the surface centre
  std::vector<unsigned char> facet_is_bad;
  // Per tetrahedron.
  std::vector<float> radius_edge, min_dihedral, max_dihedral;  // degrees
  std::vector<double> volume;
  std::vector<unsigned char> is_bad;
  std::vector<long long> dihedral_histogram;     // all six angles, 1-degree bins over [0, 180)
  std::vector<long long> facet_angle_histogram;  // smallest facet angles, 1-degree bins over [0, 60]
  // With keep_triangulation: every tetrahedron of the final Delaunay triangulation (inside
  // and outside the surface, up to the corners of the bounding box), on all its points.
  TetMesh triangulation;
  RestrictedDelaunayStats stats;
};

// Checks the options; throws gdr::Error(InvalidInput).
void validate_restricted_delaunay_options(const RestrictedDelaunayOptions& options);

// Meshes `input`. Throws gdr::Error (InvalidInput, SelfIntersectingInput, NoDevice,
// OutOfDeviceMemory, Aborted, InternalError).
RestrictedDelaunayResult restricted_delaunay_3d(const Surface& input,
                                                const RestrictedDelaunayOptions& options,
                                                const Callbacks& callbacks = {});

}  // namespace gdr
