/**
 * @class   vtkGDRConversion
 * @brief   the one converter between VTK data and gdr::core types (private, not wrapped)
 *
 * All meshing filters convert through this class: VTK input -> core input, core mesh
 * -> VTK output, per-element quality arrays (computed by the core's measures), the
 * histogram table and the run statistics as field data.
 */

#ifndef vtkGDRConversion_h
#define vtkGDRConversion_h

#include "gdr/pslg.h"
#include "gdr/qm3d.h"
#include "gdr/rdt3d.h"
#include "gdr/refine2d.h"

#include <string>
#include <vector>

class vtkDataArray;
class vtkDataSet;
class vtkFieldData;
class vtkPolyData;
class vtkTable;
class vtkUnstructuredGrid;

class vtkGDRConversion
{
public:
  /**
   * Builds a PSLG from polydata: line and polyline pieces and polygon (and triangle
   * strip) edges become segments (repeated ids skipped, duplicates merged), vertex
   * cells give isolated points; with no cells at all every point is an input point.
   * Only points used by cells are kept. Triangle's data is read from arrays where present
   * (any numeric type): the point array BoundaryMarker (point markers), the 1-component
   * cell array BoundaryMarker (the marker of each cell's segments; a segment given twice
   * keeps its first cell's) and the point array PointAttributes (one component per
   * attribute). Points of `holeSeeds` (may be null) become
   * hole seeds, and so do the tuples of the input's field data array HoleSeeds (the
   * holes of a .poly file, see FromPslg). `z` receives the plane height of the input;
   * `warning` is set when the input is not in a z = constant plane.
   */
  static void ToPslg(vtkPolyData* input, vtkDataSet* holeSeeds, gdr::Pslg& pslg, double& z,
    std::string& warning);

  /**
   * Triangles of `mesh` at height `z` into `output` (reset first), with the point arrays
   * PointType (0 input, 1 segment Steiner point, 2 free Steiner point), BoundaryMarker and
   * PointAttributes (one component per attribute) and the cell array Region, each where
   * the mesh carries it.
   */
  static void ToPolyData(const gdr::TriMesh& mesh, double z, vtkPolyData* output);

  /**
   * The subsegments of `mesh` as lines over the points and point data of `triangles` (its
   * ToPolyData output, shared), with the cell array BoundaryMarker, the active scalars.
   */
  static void ToSubsegments(const gdr::TriMesh& mesh, vtkPolyData* triangles, vtkPolyData* output);

  /**
   * Cell arrays MinAngle, MaxAngle (degrees), RadiusEdgeRatio, Area and IsBad
   * (MinAngle < minimumAngle) for the triangles of `mesh`, added to `output`.
   */
  static void AddTriangleQuality(const gdr::TriMesh& mesh, double minimumAngle,
    vtkPolyData* output);

  /**
   * Histogram of `values` in 1-unit bins over [0, upper] (the top value falls in the last
   * bin), with the column names of ParaView's Histogram filter so that its bar chart picks
   * them up: bin_extents (bin centers) and bin_values (counts).
   */
  static void Histogram(vtkDataArray* values, int upper, vtkTable* table);

  /**
   * The statistics of a 2D run as field data arrays.
   */
  static void AddStats(const gdr::Refine2dStats& stats, vtkFieldData* fieldData);

  /**
   * Builds a surface from polydata: each polygon and each triangle strip is one facet
   * (Surface::triangle_facet holds its polydata cell id); polygons with more than three
   * corners are triangulated by vtkPolygon. Lines and vertices are ignored. All points are
   * kept, in order, so that the engine's messages name the input's point ids. A cell
   * array FacetId, where present, gives the facet of each cell instead (the readers'
   * triangulated polygons), and the field data seeds of a file (FromSurface) are added.
   * Throws gdr::Error(InvalidInput) for a polygon that cannot be triangulated.
   */
  static void ToSurface(vtkPolyData* input, gdr::Surface& surface);

  /**
   * Builds a surface from an unstructured grid: its boundary faces (vtkDataSetSurfaceFilter)
   * and, when the grid has an integer cell array Region, also the faces between cells of
   * different Region values, with one region seed (the center of one of its cells) per
   * connected part of each Region value. Facet ids are the indices of the extracted faces.
   * `warning` is set when a Region array is present but not of an integer type (then it is
   * ignored).
   */
  static void ToSurface(vtkUnstructuredGrid* input, gdr::Surface& surface, std::string& warning);

  /**
   * Appends the points of `seeds` to `surface`: as region seeds when `seeds` has the point
   * array RegionAttribute (its value the attribute), else as hole seeds.
   */
  static void AddSeeds(vtkDataSet* seeds, gdr::Surface& surface);

  /**
   * The tetrahedra of `result` into `output` (reset first) with the point array PointType
   * and the cell arrays RadiusEdgeRatio, MinDihedralAngle, MaxDihedralAngle, Volume, IsBad
   * and Region (0 where the input has no regions), as the engine measured them.
   * MinDihedralAngle is the active cell scalar, so that ParaView colors by it.
   */
  static void ToUnstructuredGrid(const gdr::QualityTetResult& result, vtkUnstructuredGrid* output);

  /**
   * The subfaces of `mesh` as triangles over the points and point data of `tets` (its
   * ToUnstructuredGrid output, shared) with the cell array FacetId, the active scalars: the
   * input facet each lies on (-1 where unknown).
   */
  static void ToSubfaces(const gdr::TetMesh& mesh, vtkUnstructuredGrid* tets, vtkPolyData* output);

  /**
   * A histogram table of precomputed 1-unit bins: bin_extents (bin centers, the column
   * name ParaView's charts take as the x axis) and `countName` (counts, the series name in
   * the chart's legend).
   */
  static void HistogramTable(
    const std::vector<long long>& counts, const char* countName, vtkTable* table);

  /**
   * One more series of 1-unit bins for a HistogramTable: the column `countName`, with 0
   * for the bins beyond `counts` (the table keeps its rows; extra counts are an error).
   */
  static void AddHistogramColumn(
    const std::vector<long long>& counts, const char* countName, vtkTable* table);

  /**
   * The statistics of a 3D run as field data arrays.
   */
  static void AddStats(const gdr::QualityTetStats& stats, vtkFieldData* fieldData);

  /**
   * The mesh of a restricted Delaunay run: `tets` as ToUnstructuredGrid makes it (without
   * Region), and `surface`, the restricted surface triangles over the same points and point
   * data, with the cell arrays MinAngle (the active scalars), Size, Distance and IsBad.
   */
  static void ToRestrictedMesh(
    const gdr::RestrictedDelaunayResult& result, vtkUnstructuredGrid* tets, vtkPolyData* surface);

  /**
   * The statistics of a restricted Delaunay run, with the criteria in effect (automatic
   * sizes resolved), as field data arrays.
   */
  static void AddStats(const gdr::RestrictedDelaunayStats& stats, vtkFieldData* fieldData);

  ///@{
  /**
   * Meshing inputs read from files, as the readers give them: a PSLG as points at z = 0,
   * its segments as lines and its isolated points as vertices, with the arrays ToPslg
   * reads back where the file has them: point and cell (segment) arrays BoundaryMarker (0
   * on vertex cells), point array PointAttributes; a surface as triangles
   * (cell array FacetId: the input facet of each, where polygons were triangulated),
   * lines for its segments and vertices for isolated points. Hole seeds go into the field
   * data array HoleSeeds (3 components), region seeds into RegionSeeds (3 components) with
   * RegionAttribute and RegionMaximumVolume: AddFileSeeds reads them back (ToPslg and
   * ToSurface call it), so that a file's holes and regions reach the filters.
   */
  static void FromPslg(const gdr::Pslg& pslg, vtkPolyData* output);
  static void FromSurface(const gdr::Surface& surface, vtkPolyData* output);
  static void AddFileSeeds(vtkPolyData* input, gdr::Pslg& pslg);
  static void AddFileSeeds(vtkDataSet* input, gdr::Surface& surface);
  ///@}

  ///@{
  /**
   * Meshes read from files: triangles (at z = 0) or tetrahedra, with the cell array Region
   * when the mesh has regions, and for triangles the point arrays BoundaryMarker and
   * PointAttributes when the .node has them.
   */
  static void FromTriMesh(const gdr::TriMesh& mesh, vtkUnstructuredGrid* output);
  static void FromTetMesh(const gdr::TetMesh& mesh, vtkUnstructuredGrid* output);
  ///@}
};

#endif
// VTK-HeaderTest-Exclude: vtkGDRConversion.h
