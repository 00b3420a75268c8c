// The 3D constrained front end shared by the 3D meshers: checks and cleans a surface into a
// piecewise linear complex, and computes its constrained Delaunay tetrahedralization on the
// CPU (TetGen's library), mapped once into the engines' HostTetMesh.
#pragma once
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gdr/error.h"
#include "gdr/progress.h"
#include "gdr/pslg.h"
#include "mesh3d/host_mesh.h"

namespace gdr::cdt3d {

struct EdgeTable;  // cdt3d/internal.h

// A checked piecewise linear complex. Points keep the input order, with exact duplicates
// merged into their first occurrence and points that no triangle or segment uses dropped.
//
// The domain is decided here, once, exactly: the surface cuts space into cells (connected
// parts of space off the surface; cell 0 is the unbounded outside). A cell belongs to the
// domain when it is reached from outside by crossing the surface an odd number of times at
// least (so a shell inside another bounds a cavity, and an internal facet does not change
// that), or when it holds a region seed; a cell with a hole seed never does. Triangles with
// no domain cell on either side are dropped.
struct Plc {
  std::vector<Point3> points;
  std::vector<int> point_map;                    // input point -> PLC point (-1: unused)
  std::vector<std::array<int, 3>> triangles;     // duplicate triangles removed
  std::vector<int> triangle_origin;              // PLC triangle -> input triangle
  std::vector<int> triangle_facet;               // PLC triangle -> facet id (dense, from 0)
  std::vector<int> facet_origin;                 // facet id -> the input facet id it reports
  std::vector<unsigned char> facet_planar;       // facet id -> 1: exactly planar; 0: merged
                                                 // across near-flat edges (coplanar_angle)
  std::vector<std::array<int, 2>> segments;      // every edge that must stay an edge: facet
                                                 // boundaries, edges of 3+ triangles, and the
                                                 // input's own segments (PLC point ids)
  std::vector<unsigned char> segment_flat;       // per segment: its two triangles meet within
                                                 // 10 degrees of flat
  std::vector<Point3> holes;
  std::vector<RegionSeed> regions;
  // Cells (empty when the surface need not be closed). Front is the side where the
  // triangle's corners turn counter-clockwise, i.e. orient3d(v0, v1, v2, p) < 0.
  std::vector<std::array<int, 2>> triangle_cell;  // per triangle: cell in front, behind
  std::vector<unsigned char> cell_in_domain;      // per cell
  std::vector<int> cell_region;                   // per cell: index into regions, or -1
  std::vector<double> cell_volume;                // per cell (cell 0: 0)
  long long duplicate_points_merged = 0;
  long long duplicate_triangles_merged = 0;
  long long unused_points = 0;                   // input points no triangle or segment uses
  long long outside_triangles = 0;               // dropped: no domain cell on either side
  // Edge counts of the final triangles: edges of one triangle (an open boundary), and the
  // first edge (in point order) of three or more triangles with its count, or {-1, -1}.
  long long open_edges = 0;
  std::array<int, 2> first_branching_edge = {-1, -1};
  int first_branching_triangles = 0;
  double volume = 0;                             // of the domain: sum of its cells' volumes
  std::shared_ptr<const EdgeTable> edges;        // of the final triangles (CheckOptions::keep_edges)
};

struct CheckOptions {
  bool require_closed = true;  // false: open surfaces pass (the restricted mesher)
  // Triangles meeting within this many degrees of flat join one facet, and their shared
  // edge is no segment (TetGen's facet separation tolerance, -p179.9: 0.1 here); 0: only
  // exactly coplanar triangles do.
  double coplanar_angle = 0;
  double merge_cone = 10;  // degrees: a merged facet stays within this of its first plane
  // Refuse triangles of zero area but for rounding too (the tet mesher: TetGen's recovery
  // of such needles stopped on assertions, or left them half covered).
  bool refuse_rounding_degenerate = false;
  // false: no facets and no segments but the input's own (checked to be triangle edges);
  // the restricted mesher finds its features itself.
  bool facets = true;
  // Keep the edge table of the final triangles in Plc::edges (the restricted mesher's
  // feature search reads it: building it again took 0.25 s for 1.48M triangles on 2 cores).
  bool keep_edges = false;
};

// Checks `surface` and cleans it into a Plc. Throws Error(InvalidInput) for NaN/Inf
// coordinates, fewer than four non-coplanar points, out-of-range indices, degenerate
// triangles (a repeated vertex, or collinear corners), open boundaries (edges of one
// triangle, when options.require_closed), seeds lying on the surface, and input segments
// that are not triangle edges; Error(SelfIntersectingInput) for triangles meeting other than
// in a shared vertex or edge (exact; pairs of input triangle ids). Edges of three or more
// triangles are legal (internal facets). Messages name at most five items plus a count,
// numbered as in the input. Merged duplicates and ignored points go to callbacks.warning.
//
// Facets: triangles joined across edges of exactly two triangles that are exactly coplanar
// and flat. Plc::facet_origin reports, per facet, the input facet id of its first triangle
// (Surface::triangle_facet), or that triangle's input id when the input has no facet ids.
// Segments: every edge whose triangles are not all in one facet, and the input segments.
Plc check_surface(const Surface& surface, const CheckOptions& options = {},
                  const Callbacks& callbacks = {});

// The constrained Delaunay tetrahedralization of `plc` (TetGen -p: Steiner points on
// segments and facets where recovery needs them), restricted to the domain cells (see Plc),
// with tregion = the attribute of the cell's region seed (0 without one) when plc.regions is
// not empty. Points: the PLC points first, in PLC order (input points that end up in no tet
// stay, unreferenced), then TetGen's Steiner points in use, typed by what they lie on.
// Subfaces: the faces on PLC facets between domain tets or on the domain boundary. The
// PLC needs check_surface with require_closed. Throws Error(InvalidInput) when TetGen fails.
// `seeds` (x, y, z each; see interior_seeds) join the Delaunay tetrahedralization as
// isolated points; those in the domain come back as free points after the Steiner points.
// `meanwhile` runs once, in this process, while TetGen's child runs (work to overlap with it).
m3d::HostTetMesh initial_cdt(const Plc& plc, const Callbacks& callbacks = {},
                             const std::vector<double>& seeds = {}, const std::function<void()>& meanwhile = {});

// TetGen's tetrahedralization stopped on one of its internal assertions, or did not finish,
// in every point order tried (see tetgen_process.h). Seen on parts turned to an angle,
// whose flat faces meet at bends of rounding size, each edge between them a segment:
// merging such faces avoids it.
class TetGenAborted : public Error {
 public:
  explicit TetGenAborted(const std::string& what) : Error(Status::InternalError, what) {}
};

// The Delaunay tetrahedralization of the points xyz (3 per point; no constraints, TetGen
// without -p): every tetrahedron of the convex hull, neighbours linked (-1 on the hull), no
// subfaces or subsegments, points typed kInputPoint in their order. The restricted mesher's
// initial triangulation. Throws Error when TetGen fails (e.g. all points coplanar).
m3d::HostTetMesh delaunay_tetrahedralization(const std::vector<double>& xyz);

// Two segments (not nearly flat, sharing no endpoint) each of whose midpoints lies in the
// other's diametral sphere wait on each other in refinement: the point that splits one
// encroaches the other, and where it sees a subface beside the other from behind (the
// generators of a bore, a few degrees apart and longer than twice their distance), no
// constrained Delaunay tetrahedralization with it exists until the other is split too.
// Such segments are split at their midpoints, with the triangles beside them, for up to
// `max_rounds` rounds, before the CDT (TetGen resolves what the new points need). Returns
// the points added (presplit.cpp).
int split_mutually_encroaching_segments(Plc& plc, int max_rounds);

// Interior seeds (seeds.cpp): x, y, z of points of a lattice over the PLC's bounding box,
// of spacing h = `spacing_factor` times the mean triangle edge length next to the surface
// and coarser deeper in, that lie at least h/2 from every triangle and are not connected to
// the outside. Those in cavities or holes are kept (initial_cdt drops them). Empty for a
// lattice of under 64 cells, unless `min_cells` > 0: then the spacing is cut to make about
// that many cells over the bounding box.
std::vector<double> interior_seeds(const Plc& plc, double spacing_factor, double min_cells = 0);

}  // namespace gdr::cdt3d
