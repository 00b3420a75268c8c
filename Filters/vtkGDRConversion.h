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
#include "gdr/refine2d.h"

#include <string>

class vtkDataArray;
class vtkDataSet;
class vtkFieldData;
class vtkPolyData;
class vtkTable;

class vtkGDRConversion
{
public:
  /**
   * Builds a PSLG from polydata: line and polyline pieces and polygon (and triangle
   * strip) edges become segments (repeated ids skipped, duplicates merged), vertex
   * cells give isolated points; with no cells at all every point is an input point.
   * Only points used by cells are kept. Points of `holeSeeds` (may be null) become
   * hole seeds. `z` receives the plane height of the input; `warning` is set when the
   * input is not in a z = constant plane.
   */
  static void ToPslg(vtkPolyData* input, vtkDataSet* holeSeeds, gdr::Pslg& pslg, double& z,
    std::string& warning);

  /**
   * Triangles of `mesh` at height `z` into `output` (reset first), with the point array
   * PointType (0 input, 1 segment Steiner point, 2 free Steiner point) when the mesh
   * carries point types.
   */
  static void ToPolyData(const gdr::TriMesh& mesh, double z, vtkPolyData* output);

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
};

#endif
// VTK-HeaderTest-Exclude: vtkGDRConversion.h
