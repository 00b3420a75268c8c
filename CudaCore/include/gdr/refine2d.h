// gDP2d: quality 2D constrained Delaunay refinement (Chen & Tan, section 5).
// Public, VTK-free, CUDA-free facade. One call meshes a PSLG on the GPU or the CPU.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "gdr/backend.h"
#include "gdr/error.h"
#include "gdr/progress.h"
#include "gdr/pslg.h"

namespace gdr {

// How a point encroaches a subsegment: inside its diametral circle (Ruppert; Triangle's -D) or
// inside its diametral lens of angle 180 - 2 theta (Chew; Triangle's default), which keeps
// fewer points near segments.
enum class EncroachMode { Ruppert = 0, Chew = 1 };

// Bounds are refused (InvalidInput) when the kernels could not honour them: a maximum edge
// length whose square, or a maximum area whose double, or a minimum angle whose sin^2 leaves
// the normal range of doubles. Size bounds whose least output cannot fit in memory are
// refused before refinement (OutOfDeviceMemory), with the estimate in the message.
// How the initial constrained Delaunay triangulation is built: CGAL's sequential one on the
// CPU, or the parallel one of the engine (points by rounds of parallel insertion, segments
// by parallel retriangulation of the triangles they cross) on the run's backend. Auto: the
// parallel one where the run takes the GPU (the same threshold as prewarming it), else CGAL.
enum class CdtMethod { Auto = 0, Cgal = 1, Parallel = 2 };

struct Refine2dOptions {
  double min_angle = 20.0;         // degrees, (0, 34]; 0 disables the angle criterion
  double max_edge_length = 0.0;    // 0 = off
  double max_area = 0.0;           // 0 = off
  // Refinement stops cleanly at this many Steiner points. -1 (automatic): 1000 times the
  // input points, at least 1M and at least 4x the triangles the size bounds ask for, and no
  // more than memory holds, so that a run that cascades (above 30 degrees) or a thin domain
  // ends and reports instead of taking all memory.
  long long max_steiner_points = -1;
  // Triangle's rules by default: the lens and off-centres. Diametral circles and circumcentres
  // took a third more to twice as many Steiner points on real maps (Benchmarks/RESULTS.md).
  EncroachMode mode = EncroachMode::Chew;
  bool off_centers = true;         // Ungor off-centers instead of circumcenters (fewer points)
  bool remove_exterior = false;    // keep only triangles enclosed by segments (and outside holes)
  // Points lying on segments and crossing, touching or overlapping segments are valid input
  // (as for Triangle and CGAL): segments are split there, with a warning that counts them.
  // strict_input refuses such input instead (SelfIntersectingInput, naming the items).
  bool strict_input = false;
  // Region seeds (Pslg::regions): their maximum areas bound the triangles of their regions
  // on top of max_area (Triangle's -a without a number), and their attributes are given to
  // the triangles of their regions (TriMesh::triangle_region, Triangle's -A).
  bool region_areas = true;
  bool region_attributes = true;
  bool refine = true;              // false: only the constrained Delaunay triangulation
  Backend backend = Backend::Auto;
  // Auto uses the GPU from this estimated output size. 0 (default): chosen per run, for the
  // CPU path's thread count and whether this process has used the GPU yet (refine2d.cpp).
  std::size_t gpu_min_triangles = 0;
  // The same mesh on every run of the same input and options: the CPU engine on one thread
  // (with several, which losing cavities stop early, and the encroachments they flag, depend
  // on thread timing; the GPU's too). Refused with Backend::Gpu.
  bool deterministic = false;
  CdtMethod cdt = CdtMethod::Auto;
};

struct PhaseTime {
  std::string name;
  double seconds = 0;
};

struct Refine2dStats {
  Backend backend_used = Backend::Cpu;
  std::string device_name;
  int iterations = 0;
  long long input_points = 0;
  long long duplicate_points_merged = 0;
  long long input_segments = 0;
  long long steiner_points = 0;
  long long output_points = 0;
  long long output_triangles = 0;
  long long bad_triangles = 0;        // left bad (next to small input angles, or capped)
  double bad_area_percent = 0;
  long long small_angle_bad = 0;      // of those: protected by the small-input-angle rule
  long long steiner_cap = -1;         // the cap in effect (-1: none, without refinement)
  bool automatic_steiner_cap = false; // it is the automatic one
  bool steiner_cap_reached = false;
  bool stalled = false;               // no point could be inserted although bad elements remain
  double min_angle_deg = 0;           // smallest angle in the output
  double input_seconds = 0;           // input checks and cleaning (duplicates, crossings)
  double cdt_seconds = 0;             // initial CDT
  std::string cdt_method;             // "cgal", "parallel-gpu" or "parallel-cpu"
  double refine_seconds = 0;          // refinement including transfers
  double output_seconds = 0;          // conversion to the output mesh and its bad-area count
  double total_seconds = 0;
  std::size_t peak_device_bytes = 0;  // GPU backend: peak bytes held by the engine on the device
  std::vector<PhaseTime> phases;      // accumulated refinement time per phase
  std::vector<PhaseTime> cdt_phases;  // the parallel CDT's time per phase
};

struct Refine2dResult {
  TriMesh mesh;
  Refine2dStats stats;
};

// Triangle's command-line switches, for users who know Triangle by heart: "pq30a0.1" (a
// leading '-' is allowed) sets `options` as Triangle would read it. p: the input's segments
// bound the domain (remove_exterior unless c); c: keep the convex hull meshed; q[angle]:
// minimum angle (20 without a number); a<area>: maximum area; a without a number: the
// regions' area bounds; A: the regions' attributes; S<n>: Steiner point cap; D: diametral
// circles (mode Ruppert; without D the lens, mode Chew, as Triangle). Without q or a there is
// no refinement (refine = false), without q no angle bound, and without a and A no use of the
// regions, as in Triangle. The switches for the caller: z, Q and C. Any other switch is
// refused (InvalidInput, naming it), never ignored.
struct TriangleSwitches {
  bool zero_based = false;  // z: number the output files from 0 whatever the input does
  bool quiet = false;       // Q
  bool check = false;       // C: check the output (gdr's validators)
};
TriangleSwitches apply_triangle_switches(const std::string& switches, Refine2dOptions& options);

// Holes by polygon orientation, as vtkDelaunay2D takes them: when some of `polygons` (rings
// of PSLG point indices, simple, their edges among pslg.segments) turn counter-clockwise,
// each clockwise one bounds a hole, and a seed strictly inside it (in the region next to its
// boundary) is returned for it. Without a counter-clockwise polygon orientation says
// nothing and no seed is returned. `unseeded` (optional): clockwise polygons too thin for
// a seed in double precision.
std::vector<Point2> clockwise_polygon_holes(const Pslg& pslg, const std::vector<std::vector<int>>& polygons,
                                            int* unseeded = nullptr);

// Checks input and parameters; throws gdr::Error naming the offending items.
void validate_refine2d_input(const Pslg& input, const Refine2dOptions& options);

// Meshes `input`. Throws gdr::Error (InvalidInput, SelfIntersectingInput, NoDevice,
// OutOfDeviceMemory, Aborted, InternalError).
Refine2dResult refine_2d(const Pslg& input, const Refine2dOptions& options,
                         const Callbacks& callbacks = {});

}  // namespace gdr
