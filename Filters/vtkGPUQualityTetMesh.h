/**
 * @class   vtkGPUQualityTetMesh
 * @brief   quality tetrahedral mesh of a closed surface (3D constrained Delaunay refinement)
 *
 * vtkGPUQualityTetMesh fills the volume enclosed by a closed surface with tetrahedra whose
 * radius-edge ratio (and, optionally, smallest dihedral angle and volume) meet the given
 * bounds, with the gQM3d algorithm of Chen & Tan, "Delaunay Mesh Refinement on the GPU", on
 * a CUDA GPU or, with the same algorithm, on the CPU. It is the refinement TetGen users know
 * as `tetgen -pq`: the surface is kept (its facets are split, never moved) and the mesh is
 * constrained Delaunay.
 *
 * Input (port 0): a vtkPolyData surface, one or more closed shells (a shell inside another
 * bounds a cavity), or faces inside the volume that split it into regions. Every polygon
 * (and triangle strip) is one facet; polygons with more than three corners are triangulated.
 * Lines and vertices are ignored. Or a vtkUnstructuredGrid: its boundary surface is meshed;
 * when it has an integer cell array Region, the faces between cells of different Region
 * values are kept as internal facets and each part of the volume gets its Region value.
 * Input (port 1, optional, repeatable, any vtkDataSet): seed points. A dataset with the
 * point array RegionAttribute gives region seeds (the region around each point gets that
 * attribute in the cell array Region; an optional point array RegionMaximumVolume bounds
 * the volume of its tetrahedra, 0 for none); a dataset without it gives hole seeds (the
 * region around each point is left empty).
 *
 * Output (port 0, vtkUnstructuredGrid): the tetrahedra. Cell data: RadiusEdgeRatio
 * (circumradius over shortest edge; 0.61 for a regular tetrahedron), MinDihedralAngle and
 * MaxDihedralAngle (degrees), Volume, IsBad (1 above the bounds, 2 above them but next to
 * small input angles, where no point can fix it), Region (0 without regions). Point data:
 * PointType (0 input point, 1 on an input segment, 2 free, 3 on an input facet). Field
 * data: the run's statistics (Backend, DeviceName, Iterations, SteinerPoints,
 * BadTetrahedra, BadVolumePercent, Stalled, MinimumDihedralAngleReached, TotalSeconds,
 * CDTSeconds, RefineSeconds, the per-phase times as PhaseNames / PhaseSeconds, ...).
 * Output (port 1, vtkTable): the histogram of all six dihedral angles of every tetrahedron
 * in 1-degree bins over [0, 180): bin_extents (bin center, degrees; the name ParaView's
 * charts take for the x axis) and DihedralAngleCount (number of angles).
 * Output (port 2, vtkPolyData): the subfaces, the triangles of the mesh that lie on input
 * facets (boundary and internal), over the points of port 0, with the cell array FacetId:
 * the input facet each lies on (the polydata cell id of its polygon; for an unstructured
 * grid, the index of its face in the extracted surface).
 *
 * Errors of the engine (open or self-intersecting surfaces, naming the offending edges or
 * faces; Backend GPU without a GPU; out of memory...) are reported with vtkErrorMacro and
 * leave empty outputs. An aborted run also leaves empty outputs.
 */

#ifndef vtkGPUQualityTetMesh_h
#define vtkGPUQualityTetMesh_h

#include "GPUDelaunayFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

class GPUDELAUNAYFILTERS_EXPORT vtkGPUQualityTetMesh : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkGPUQualityTetMesh* New();
  vtkTypeMacro(vtkGPUQualityTetMesh, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

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
   * Upper bound on the radius-edge ratio of the tetrahedra (TetGen's -q B). Values in
   * (0, 1) become 1, the smallest bound allowed; 0 (or less) turns the criterion off.
   * Default 2.0, where refinement is guaranteed to end; below 2 it usually does, and an
   * automatic Steiner point cap ends it otherwise.
   */
  virtual void SetRadiusEdgeRatio(double ratio);
  vtkGetMacro(RadiusEdgeRatio, double);
  ///@}

  ///@{
  /**
   * Lower bound on the dihedral angles of the tetrahedra, in degrees (TetGen's -q B/d).
   * Clamped to [0, 60]; 0 (default) turns it off. Refinement has no termination guarantee
   * with it: an automatic Steiner point cap applies; bounds above about 20 degrees are
   * rarely met.
   */
  vtkSetClampMacro(MinimumDihedralAngle, double, 0.0, 60.0);
  vtkGetMacro(MinimumDihedralAngle, double);
  ///@}

  ///@{
  /**
   * Sliver removal after refinement, in degrees (TetGen's -O smoothing): interior Steiner
   * points of tetrahedra with a dihedral angle below it (or above 180 minus it) move to
   * raise the smallest dihedral angle around them, keeping the other bounds; then slivers
   * with all four corners on the surface are removed by 3-2, 4-4 and 5-6 flips where one
   * raises their smallest angle. Clamped to [0, 30]; 0 (default) turns it off. The mesh is then not
   * Delaunay where points moved or tetrahedra flipped. The field data SliversBefore and
   * SliversAfter count such tetrahedra, SliverFlips the flips.
   */
  vtkSetClampMacro(SliverAngle, double, 0.0, 30.0);
  vtkGetMacro(SliverAngle, double);
  ///@}

  ///@{
  /**
   * Input triangles that meet within this many degrees of flat form one facet whose inner
   * edges the mesh need not keep (TetGen's -p facet tolerance, 0.1 there by default): far
   * fewer points where a curved or rounded surface was cut into nearly flat triangles, and
   * the boundary follows the input within that bend. Clamped to [0, 5]; default 0.1 (as
   * TetGen: faces of a part turned to an angle are flat only up to rounding); 0 keeps every
   * edge between two facets that are not exactly coplanar.
   */
  vtkSetClampMacro(CoplanarAngle, double, 0.0, 5.0);
  vtkGetMacro(CoplanarAngle, double);
  ///@}

  ///@{
  /**
   * Upper bound on the volume of the tetrahedra (TetGen's -a); 0 (default) turns it off.
   */
  vtkSetClampMacro(MaximumVolume, double, 0.0, VTK_DOUBLE_MAX);
  vtkGetMacro(MaximumVolume, double);
  ///@}

  ///@{
  /**
   * Cap on the number of Steiner points; refinement stops cleanly when it is reached and
   * IsBad marks the tetrahedra left above the bounds. -1 (default): an automatic cap, only
   * where termination is not guaranteed (RadiusEdgeRatio below 2 or a dihedral bound).
   */
  vtkSetClampMacro(MaximumSteinerPoints, vtkIdType, -1, VTK_ID_MAX);
  vtkGetMacro(MaximumSteinerPoints, vtkIdType);
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
   * Seed points (input port 1, repeatable): hole seeds, or region seeds when the dataset
   * has the point array RegionAttribute.
   */
  void AddSeedsConnection(vtkAlgorithmOutput* output);
  void AddSeedsData(vtkDataObject* data);
  void RemoveAllSeeds();
  ///@}

protected:
  vtkGPUQualityTetMesh();
  ~vtkGPUQualityTetMesh() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double RadiusEdgeRatio = 2.0;
  double MinimumDihedralAngle = 0.0;
  double SliverAngle = 0.0;
  double CoplanarAngle = 0.1;
  double MaximumVolume = 0.0;
  vtkIdType MaximumSteinerPoints = -1;
  int Backend = AUTO;

private:
  vtkGPUQualityTetMesh(const vtkGPUQualityTetMesh&) = delete;
  void operator=(const vtkGPUQualityTetMesh&) = delete;
};

#endif
