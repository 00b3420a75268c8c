// Input checking and clean-up for the 2D mesher, and the initial CDT (paper Algorithm 1
// line 1, on the CPU).
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "gdr/progress.h"
#include "gdr/refine2d.h"
#include "refine2d/mesh2d.h"

namespace gdr::r2d {

// The PSLG the mesher works on: duplicates merged, segments deduplicated and (optionally)
// split at intersections. Points keep the input order (first occurrences), then any
// intersection points.
struct CleanPslg {
  std::vector<Point2> points;
  std::vector<std::array<int, 2>> segments;
  std::vector<int> segment_origin;  // input segment each cleaned segment comes from
  std::vector<int> point_origin;    // input point of each point (-1: an intersection point)
  int first_index = 0;              // the input file's numbering (Pslg::first_index)
  std::vector<Point2> holes;
  std::vector<RegionSeed2> regions;  // region r + 1 is HostMesh::tregion's number for seed r
  long long duplicates_merged = 0;
};

// Throws InvalidInput / SelfIntersectingInput naming the offending items. With `on_gpu`,
// an input that needs no cleaning is recognised on the GPU (input_checks.h).
CleanPslg clean_input(const Pslg& input, const Refine2dOptions& options, const Callbacks& cb,
                      bool on_gpu = false);

// Whether the points and segments need no cleaning at all (input_checks.h), in each space.
bool input_is_clean_cpu(const std::vector<Point2>& points, const std::vector<std::array<int, 2>>& segments);
#if defined(GDR_HAVE_CUDA)
bool input_is_clean_cuda(const std::vector<Point2>& points, const std::vector<std::array<int, 2>>& segments);
#endif

// Splits the segments at every crossing, touching point, overlap and point lying on them,
// with CGAL's constrained triangulation (exact predicates; intersection points rounded to the
// nearest double or snapped to a vertex within a few ulps, so concurrent segments share one
// point). New points are appended (point_origin -1); segment_origin is kept.
void split_segments_at_intersections(CleanPslg& pslg);

// Constrained Delaunay triangulation of the cleaned PSLG. Convex-hull edges that are not
// segments become extra segments (as Triangle does), unless the exterior is removed.
HostMesh initial_cdt(const CleanPslg& pslg, bool remove_exterior);

// Any CDT's triangles, before the exterior and holes are removed: tseg[3t+e] is the segment
// on edge e (an index into the cleaned segments, or beyond them for convex-hull edges that
// were made segments) or -1, tn -1 where there is no triangle across.
struct CdtTriangles {
  exec::HostVector<int> tv, tn, tseg;
  std::vector<int> exterior_seeds;  // triangles outside the domain whatever the segments say
  std::vector<int> hole_tris;       // per hole: the triangle holding it, or -1
  std::vector<int> region_tris;     // per region seed: the triangle holding it, or -1
};

// The engine's input from a CDT: what the seeds and holes reach without crossing a segment
// is removed, so are slivers between a convex-hull edge and points within rounding of it
// (cdt_parallel.cpp, peel_hull_slivers), domain-boundary edges that are not input segments
// become hull segments, and regions are numbered by flooding from their seeds.
HostMesh assemble_cdt(const CleanPslg& g, CdtTriangles triangles);

// Slivers at the hull (cdt_parallel.cpp, peel_hull_slivers): a boundary triangle on a hull
// edge whose apex lies within this fraction of the edge's length from it.
constexpr double kHullSliver = 1e-9;

// Refuses a domain that removing the exterior and the holes left empty.
[[noreturn]] void throw_empty_domain();

// The same CDT as initial_cdt, built in parallel (cdt_engine.h) on the GPU or CPU threads;
// with `in_space`, assembled where it was built (`prepared`, engine_dispatch.h) unless
// slivers at the hull need the host's assembly (`host`). Its
// phases' times go to `phases` when given.
class PreparedCdt;
struct InitialCdt {
  HostMesh host;
  std::unique_ptr<PreparedCdt> prepared;
  InitialCdt();
  InitialCdt(InitialCdt&&) noexcept;
  ~InitialCdt();  // (defined where PreparedCdt is complete)
};
InitialCdt initial_cdt_parallel(const CleanPslg& pslg, bool remove_exterior, bool gpu, bool in_space,
                                std::vector<PhaseTime>* phases = nullptr);

// Values given at the points of `g` (`count` per point), interpolated linearly over its
// constrained Delaunay triangulation at `queries` (Triangle interpolates point attributes at
// Steiner points linearly).
std::vector<double> interpolate_over_cdt(const CleanPslg& g, const std::vector<double>& values,
                                         int count, const std::vector<Point2>& queries);

// What Triangle's output carries besides the mesh, from the input to `out` (gdr/pslg.h):
// boundary markers of subsegments (their segment's marker; 1 on the mesh boundary where
// that is 0 or absent, 0 inside) and of points (their own, else that of a marked subsegment
// they end), point attributes (interpolated at Steiner points), and with `region_attributes`
// the attribute of each triangle's region (`tregion`: region numbers, 0 for none; null
// without regions). `xy` are the engine's coordinates of out's points (2 per point),
// `subseg` its subsegments (MeshResult::subseg: 4 per subsegment, the 4th 1 on the mesh
// boundary), in the order of out.subsegments.
void carry_input_data(const Pslg& in, const CleanPslg& g, const double* xy, const int* subseg,
                      const int* tregion, bool region_attributes, TriMesh& out);

// Pairs of segments that cross, touch or overlap (exact predicates), at most `limit`.
struct SegmentConflict {
  int s, t;  // t = -1: an isolated point lies on segment s
  enum Kind { Cross, Touch, Overlap } kind;
  int point = -1;
};
std::vector<SegmentConflict> find_segment_conflicts(const std::vector<Point2>& points,
                                                    const std::vector<std::array<int, 2>>& segs,
                                                    std::size_t limit);

}  // namespace gdr::r2d
