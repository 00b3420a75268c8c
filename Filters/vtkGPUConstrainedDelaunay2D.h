/**
 * @class   vtkGPUConstrainedDelaunay2D
 * @brief   quality 2D constrained Delaunay refinement with Triangle's rules
 *
 * vtkGPUConstrainedDelaunay2D meshes a planar straight-line graph (PSLG) given in the
 * z = constant plane with the gDP2d refinement algorithm of Chen & Tan, "Delaunay Mesh
 * Refinement on the GPU", on a CUDA GPU or, with the same algorithm, on the CPU.
 *
 * Input (port 0, vtkPolyData): every line and polyline segment is a constrained
 * segment, every polygon contributes its edges (closing edge included) as segments,
 * and vertex cells are isolated input points. A polydata with no cells at all gives
 * all of its points as input points. Only x and y are used. As in vtkDelaunay2D,
 * clockwise polygons are holes when some polygon turns counter-clockwise. Triangle's
 * boundary markers and point attributes are taken from the arrays BoundaryMarker (point
 * data: point markers; cell data: the marker of the segments of each line or polygon) and
 * PointAttributes (point data, one component per attribute), as vtkTriangleTetGenReader
 * gives them for a .poly or .node.
 * Input (port 1, optional, any vtkDataSet): its points are hole seeds; the region
 * enclosed by segments around each seed is removed.
 *
 * Output (port 0, vtkPolyData): counter-clockwise triangles. Cell data: MinAngle and
 * MaxAngle (degrees), RadiusEdgeRatio (circumradius over shortest edge), Area, IsBad
 * (1 where MinAngle < MinimumAngle). Point data: PointType (0 input point, 1 Steiner
 * point on a segment, 2 free Steiner point); BoundaryMarker and PointAttributes, as
 * Triangle's output carries them: input points keep their marker, a point on a
 * subsegment without one takes the subsegment's, other points 0; attributes are
 * interpolated linearly at Steiner points. Field data: the run's statistics
 * (Backend, DeviceName, Iterations, SteinerPoints, BadTriangles, BadAreaPercent,
 * MinimumAngleReached, TotalSeconds, CDTSeconds, RefineSeconds, and the per-phase
 * times as the parallel arrays PhaseNames / PhaseSeconds).
 * Output (port 1, vtkTable): a histogram of MinAngle in 1-degree bins over [0, 60]
 * with the columns bin_extents (bin center, degrees) and bin_values (number of
 * triangles), named like the output of ParaView's Histogram filter.
 * Output (port 2, vtkPolyData): the subsegments, the mesh edges on input segments (and
 * on the convex hull unless the exterior is removed), as lines over the points and point
 * data of port 0, with the cell array BoundaryMarker: the segment's marker (as Triangle's
 * .poly output), 1 where that is 0 or absent on the mesh boundary, 0 inside.
 *
 * Errors of the engine (crossing segments, no GPU for Backend=GPU, out of memory...)
 * are reported with vtkErrorMacro and leave empty outputs. An aborted run also leaves
 * empty outputs.
 */

#ifndef vtkGPUConstrainedDelaunay2D_h
#define vtkGPUConstrainedDelaunay2D_h

#include "GPUDelaunayFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // for TriangleSwitches

class GPUDELAUNAYFILTERS_EXPORT vtkGPUConstrainedDelaunay2D : public vtkPolyDataAlgorithm
{
public:
  static vtkGPUConstrainedDelaunay2D* New();
  vtkTypeMacro(vtkGPUConstrainedDelaunay2D, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Segment encroachment rule: diametral circle (Ruppert) or diametral lens (Chew).
  enum Modes
  {
    RUPPERT = 0,
    CHEW = 1
  };

  /// Where the refinement runs. AUTO uses the GPU when one is usable, else the CPU
  /// (with a warning); GPU fails with an error when no usable device is present.
  enum Backends
  {
    AUTO = 0,
    GPU = 1,
    CPU = 2
  };

  ///@{
  /**
   * Lower bound on the angles of the output triangles, in degrees, in [0, 34]. 0 disables
   * the angle criterion. Default 20. A value out of range is refused with an error when
   * the filter runs, as gdr 2d refuses it (no silent clamping).
   */
  vtkSetMacro(MinimumAngle, double);
  vtkGetMacro(MinimumAngle, double);
  ///@}

  ///@{
  /**
   * Upper bound on the edge length of the output triangles; 0 (default) disables it.
   * Negative values are refused with an error when the filter runs.
   */
  vtkSetMacro(MaximumEdgeLength, double);
  vtkGetMacro(MaximumEdgeLength, double);
  ///@}

  ///@{
  /**
   * Upper bound on the area of the output triangles; 0 (default) disables it.
   * Negative values are refused with an error when the filter runs.
   */
  vtkSetMacro(MaximumArea, double);
  vtkGetMacro(MaximumArea, double);
  ///@}

  ///@{
  /**
   * Cap on the number of Steiner points; refinement stops cleanly when it is reached.
   * -1 (default) means an automatic cap, so that a run that cascades (above 30 degrees) or
   * a thin domain ends: 1000 times the input points, at least 1M and at least 4 times the
   * triangles the size bounds ask for, and no more than memory holds. Values below -1
   * are refused with an error when the filter runs.
   */
  vtkSetMacro(MaximumSteinerPoints, vtkIdType);
  vtkGetMacro(MaximumSteinerPoints, vtkIdType);
  ///@}

  ///@{
  /**
   * Encroachment mode: CHEW (default, as Triangle: a point encroaches a subsegment inside
   * its diametral lens of angle 180 - 2 MinimumAngle) or RUPPERT (inside its diametral
   * circle, as Triangle's -D: more Steiner points).
   */
  vtkSetClampMacro(Mode, int, RUPPERT, CHEW);
  vtkGetMacro(Mode, int);
  void SetModeToRuppert() { this->SetMode(RUPPERT); }
  void SetModeToChew() { this->SetMode(CHEW); }
  ///@}

  ///@{
  /**
   * Insert Ungor's off-centres instead of circumcentres: the same quality with fewer
   * Steiner points, as Triangle. Default on (off: gdr 2d --no-off-centers).
   */
  vtkSetMacro(OffCenters, vtkTypeBool);
  vtkGetMacro(OffCenters, vtkTypeBool);
  vtkBooleanMacro(OffCenters, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Only the constrained Delaunay triangulation of the input, without refinement (gdr 2d
   * --cdt-only): the quality bounds are not applied, IsBad still marks the triangles
   * below MinimumAngle. Default off.
   */
  vtkSetMacro(CDTOnly, vtkTypeBool);
  vtkGetMacro(CDTOnly, vtkTypeBool);
  vtkBooleanMacro(CDTOnly, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Execution backend: AUTO (default), GPU or CPU.
   */
  vtkSetClampMacro(Backend, int, AUTO, CPU);
  vtkGetMacro(Backend, int);
  void SetBackendToAuto() { this->SetBackend(AUTO); }
  void SetBackendToGPU() { this->SetBackend(GPU); }
  void SetBackendToCPU() { this->SetBackend(CPU); }
  ///@}

  ///@{
  /**
   * Keep only the triangles enclosed by segments (and outside holes). Default off.
   */
  vtkSetMacro(RemoveExterior, vtkTypeBool);
  vtkGetMacro(RemoveExterior, vtkTypeBool);
  vtkBooleanMacro(RemoveExterior, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Refuse points lying on segments and crossing, touching or overlapping segments with
   * an error. Default off: segments are split there (as Triangle and CGAL do), with a
   * warning that counts them.
   */
  vtkSetMacro(StrictInput, vtkTypeBool);
  vtkGetMacro(StrictInput, vtkTypeBool);
  vtkBooleanMacro(StrictInput, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Triangle's switch string ("pq30a0.1", see gdr::apply_triangle_switches), for users who
   * know Triangle by heart. When set it overrides MinimumAngle, MaximumArea,
   * MaximumSteinerPoints, RemoveExterior, Mode (RUPPERT with D, else CHEW) and refinement;
   * an unknown or unsupported switch is an error. Default empty (the properties alone).
   */
  vtkSetStdStringFromCharMacro(TriangleSwitches);
  vtkGetCharFromStdStringMacro(TriangleSwitches);
  ///@}

  ///@{
  /**
   * Optional hole seed points (input port 1).
   */
  void SetHoleSeedsConnection(vtkAlgorithmOutput* output);
  void SetHoleSeedsData(vtkDataObject* data);
  ///@}

protected:
  vtkGPUConstrainedDelaunay2D();
  ~vtkGPUConstrainedDelaunay2D() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double MinimumAngle = 20.0;
  double MaximumEdgeLength = 0.0;
  double MaximumArea = 0.0;
  vtkIdType MaximumSteinerPoints = -1;
  int Mode = CHEW;
  int Backend = AUTO;
  vtkTypeBool RemoveExterior = false;
  vtkTypeBool OffCenters = true;
  vtkTypeBool CDTOnly = false;
  vtkTypeBool StrictInput = false;
  std::string TriangleSwitches;

private:
  vtkGPUConstrainedDelaunay2D(const vtkGPUConstrainedDelaunay2D&) = delete;
  void operator=(const vtkGPUConstrainedDelaunay2D&) = delete;
};

#endif
