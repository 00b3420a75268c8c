// gQM3d: quality tetrahedral meshing of a piecewise linear complex by 3D constrained
// Delaunay refinement (Chen & Tan, section 6). Public, VTK-free, CUDA-free facade.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "gdr/backend.h"
#include "gdr/error.h"
#include "gdr/progress.h"
#include "gdr/pslg.h"
#include "gdr/refine2d.h"  // PhaseTime

namespace gdr {

// How far (degrees) the triangles of one facet merged by coplanar_angle may turn from its
// first triangle's plane; two of them, and so a subface from the input triangles it covers,
// up to twice that (what validation allows: ValidateOptions::facet_bend_deg).
constexpr double kMergedFacetCone = 10.0;
constexpr double kMergedFacetBend = 2 * kMergedFacetCone;
// TetGen's own facet tolerance (degrees): the coplanar_angle of the retry when TetGen stops
// on an internal assertion or loops in every point order tried (flat faces of a part turned
// to an angle).
constexpr double kTetGenFacetTolerance = 0.1;

struct QualityTetOptions {
  // Largest radius-edge ratio allowed (TetGen's -q B): at least 1.0; 0 turns it off.
  double radius_edge_ratio = 2.0;
  // Smallest dihedral angle allowed, in degrees (TetGen's -q B/d); 0 (default) is off.
  double min_dihedral_angle = 0.0;
  // Largest tetrahedron volume allowed (TetGen's -a); 0 is off.
  double max_volume = 0.0;
  // Refinement stops cleanly at this many Steiner points. -1 (automatic): a cap applies
  // only where termination is not guaranteed (radius-edge below 2 or a dihedral bound).
  long long max_steiner_points = -1;
  // Input triangles that meet within this many degrees of flat form one facet: the edge
  // between them is no segment, and refinement may flip it away, so the mesh boundary
  // follows the input within that bend instead of keeping every input edge (TetGen's -p
  // facet tolerance). A merged facet bends at most kMergedFacetCone degrees in all; beyond,
  // a segment stays. Default kTetGenFacetTolerance, as TetGen: the flat faces of a CAD part
  // turned to an angle (or stored in single precision) are planar only up to rounding, and
  // kept triangle by triangle their edges are segments at 180 degrees whose splits fail on
  // rounding (a quarter of the volume left bad). 0: only exactly coplanar triangles merge,
  // and every input edge between two facets is kept (unless TetGen fails in every point
  // order tried: then the tetrahedralization is tried again, with a warning, at
  // kTetGenFacetTolerance). At most 5.
  double coplanar_angle = kTetGenFacetTolerance;
  bool refine = true;      // false: only the constrained Delaunay tetrahedralization
  // Sliver removal after refinement (TetGen's -O, by vertex smoothing only): interior
  // Steiner points of tetrahedra with a dihedral angle below this many degrees (or above
  // 180 minus it) move to raise the smallest dihedral angle around them, keeping the
  // radius-edge bound. The mesh is then no longer Delaunay where points moved. 0: off.
  double sliver_angle = 0.0;
  Backend backend = Backend::Auto;
  std::size_t gpu_min_tets = 0;  // Auto uses the GPU from this estimated size; 0: measured default
};

struct QualityTetStats {
  Backend backend_used = Backend::Cpu;
  std::string device_name;
  int iterations = 0;
  long long input_points = 0;
  long long input_triangles = 0;
  long long input_facets = 0;
  long long input_segments = 0;
  long long duplicate_points_merged = 0;
  long long duplicate_triangles_merged = 0;
  // The coplanar_angle in effect: the option's, or kTetGenFacetTolerance after TetGen
  // stopped on an assertion (validate with ValidateOptions::facet_bend_deg when > 0).
  double coplanar_angle_used = 0;
  long long presplit_points = 0;        // on segments that would wait on each other, before the CDT
  long long cdt_steiner_points = 0;     // added by the initial CDT (boundary recovery)
  long long interior_seeds = 0;         // lattice points put inside with the CDT (cdt3d.h)
  long long steiner_points = 0;         // added in total (CDT and refinement)
  long long output_points = 0;
  long long output_tets = 0;
  long long output_subfaces = 0;
  long long bad_tets = 0;               // left above the bounds
  long long protected_bad_tets = 0;     // of those: left as they are (unfixable)
  // Of the protected: slivers under MinDihedralAngle whose circumradius is below their
  // shortest edge, left once the mesh had grown fourfold (splitting them would only make
  // smaller ones: a cascade); the others lie next to small input angles.
  long long slivers_left = 0;
  double bad_volume_percent = 0;
  long long steiner_cap = -1;           // the cap in effect (-1: none)
  bool automatic_steiner_cap = false;
  bool steiner_cap_reached = false;
  bool stalled = false;                 // bad elements remain that could not be split
  // Input segments left unsplit after their splits failed again and again (a nearly
  // coplanar facet next to them): what would encroach them is left bad (protected_bad_tets).
  long long blocked_segments = 0;
  // Points that failed for reasons of their own and slept until their cavity changed,
  // instead of failing again every iteration (summed over the iterations).
  long long sleeping_points = 0;
  double min_dihedral_deg = 0, max_dihedral_deg = 0;
  double max_radius_edge = 0;
  // Sliver removal (sliver_angle > 0): tetrahedra with an angle beyond it before and after,
  // the points moved, and the edge flips made (slivers whose corners all lie on the surface).
  long long slivers_before = 0, slivers_after = 0, sliver_moves = 0, sliver_flips = 0;
  double volume = 0;                    // of the output
  double input_volume = 0;              // enclosed by the input surface
  double input_seconds = 0, cdt_seconds = 0, refine_seconds = 0, output_seconds = 0;
  double total_seconds = 0;
  std::size_t peak_device_bytes = 0;
  std::vector<PhaseTime> phases;
};

struct QualityTetResult {
  TetMesh mesh;                          // with subface_facet and (regions given) tet_region
  // Per tetrahedron, for output arrays.
  std::vector<float> radius_edge;
  std::vector<float> min_dihedral, max_dihedral;  // degrees
  std::vector<double> volume;
  std::vector<unsigned char> is_bad;     // 1 above the bounds, 2 above them but protected
  // All six dihedral angles of every tetrahedron, 1-degree bins over [0, 180).
  std::vector<long long> dihedral_histogram;
  QualityTetStats stats;
};

// Checks the surface and the options; throws gdr::Error naming the offending items.
void validate_quality_tet_input(const Surface& input, const QualityTetOptions& options);

// Meshes the volume enclosed by `input`. Throws gdr::Error (InvalidInput,
// SelfIntersectingInput, NoDevice, OutOfDeviceMemory, Aborted, InternalError).
QualityTetResult quality_tet_mesh(const Surface& input, const QualityTetOptions& options,
                                  const Callbacks& callbacks = {});

}  // namespace gdr
