/**
 * @class   vtkGPURestrictedDelaunay3D
 * @brief   surface and volume mesh approximating a surface (3D restricted Delaunay refinement)
 *
 * vtkGPURestrictedDelaunay3D resamples a triangulated surface with well-shaped triangles of
 * a chosen size and, when the surface is closed, fills the volume it encloses with
 * tetrahedra, with the gDP3d algorithm of Chen & Tan, "Delaunay Mesh Refinement on the GPU",
 * on a CUDA GPU or, with the same algorithm, on the CPU. It is the meshing CGAL Mesh_3 users
 * know, with the same criteria names. Unlike vtkGPUQualityTetMesh the input surface is
 * approximated, not kept: output surface vertices lie on it (up to rounding), output surface
 * triangles are the Delaunay faces whose Voronoi dual meets it, and tetrahedra are those
 * whose circumcentre lies inside it. Scanned, noisy or badly shaped surfaces are fine.
 * With FeatureAngle, sharp edges and corners of the input are kept.
 *
 * Input (port 0): a vtkPolyData surface. Every polygon (and triangle strip) is used;
 * polygons with more than three corners are triangulated. Lines and vertices are ignored.
 * Closed surfaces (one or more shells; a shell inside another bounds a cavity) give
 * tetrahedra and their surface; an open surface, or MeshVolume off, gives the surface alone
 * (an open surface with MeshVolume on also gives a warning). Non-manifold or
 * self-intersecting surfaces are refused with an error naming the edges or faces.
 *
 * Output (port 0, vtkUnstructuredGrid): the tetrahedra (empty when only the surface is
 * meshed). Cell data: RadiusEdgeRatio (circumradius over shortest edge), MinDihedralAngle
 * and MaxDihedralAngle (degrees), Volume, IsBad (1 above the criteria, left next to sharp
 * features or by a cap or a stall). Point data: PointType (0 a corner, 1 on a feature edge,
 * 3 on the surface, 2 inside). MinDihedralAngle is the active scalar, as in
 * vtkGPUQualityTetMesh. Field data, also when the tetrahedra are empty: the run's
 * statistics (Backend, DeviceName, Iterations, SteinerPoints, ClosedInput, VolumeMeshed,
 * FeatureEdges, Corners, FeaturePoints, BadFacets, BadTetrahedra, ManifoldSplits,
 * NonManifoldFacets, PinchRelabelled, Stalled,
 * SteinerCapReached, the criteria in effect with automatic sizes resolved as FacetAngle,
 * FacetSize, FacetDistance, CellRadiusEdgeRatio, CellSize, FeatureAngle, SliversBefore and
 * SliversAfter (SliverAngle), the qualities reached, Area, Volume, the times and the per-phase times as PhaseNames / PhaseSeconds).
 * Output (port 1, vtkPolyData): the restricted surface, triangles (outward for a closed
 * input) sharing the points of port 0 when it has tetrahedra. Cell data: MinAngle
 * (degrees, the active scalar), Size (radius of the surface Delaunay ball), Distance
 * (facet circumcentre to the input surface), IsBad (1 above the facet criteria). Point
 * data: PointType. Field data: the statistics, as port 0.
 * Output (port 2, vtkTable): the angle histograms in 1-degree bins over [0, 180):
 * bin_extents (bin center, degrees; the name ParaView's charts take for the x axis),
 * DihedralAngleCount (all six dihedral angles of every tetrahedron) and FacetAngleCount (the
 * smallest angle of every surface triangle; 0 above 60 degrees, the equilateral triangle's).
 *
 * Sizes are lengths in input units. A negative size asks for the automatic default,
 * relative to the diagonal D of the input's bounding box; 0 turns that criterion off.
 * Values the engine cannot honour (FacetAngle outside [0, 30], CellRadiusEdgeRatio in
 * (0, 1) or negative, all three facet criteria off, non-finite sizes, FeatureAngle outside
 * [0, 180), SliverAngle outside [0, 30], MaximumSteinerPoints below -1) are not clamped: the run is refused with an InvalidInput error, as gdr rdt
 * refuses them. Errors leave empty outputs; so does an aborted run.
 */

#ifndef vtkGPURestrictedDelaunay3D_h
#define vtkGPURestrictedDelaunay3D_h

#include "GPUDelaunayFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

class GPUDELAUNAYFILTERS_EXPORT vtkGPURestrictedDelaunay3D : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkGPURestrictedDelaunay3D* New();
  vtkTypeMacro(vtkGPURestrictedDelaunay3D, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// Where the refinement runs. AUTO uses the GPU when one is usable, else the CPU;
  /// GPU fails with an error when no usable device is present.
  enum Backends
  {
    AUTO = 0,
    GPU = 1,
    CPU = 2
  };

  ///@{
  /**
   * Lower bound on the angles of the surface triangles, in degrees (CGAL's facet_angle).
   * Range [0, 30], where refinement is guaranteed to end; 0 turns it off. Default 30.
   */
  vtkSetMacro(FacetAngle, double);
  vtkGetMacro(FacetAngle, double);
  ///@}

  ///@{
  /**
   * Upper bound on the radius of the surface Delaunay ball of a surface triangle
   * (CGAL's facet_size). Default -1: D / 20; 0 turns it off.
   */
  vtkSetMacro(FacetSize, double);
  vtkGetMacro(FacetSize, double);
  ///@}

  ///@{
  /**
   * Upper bound on the distance between a surface triangle's circumcentre and the input
   * surface (CGAL's facet_distance). Default -1: D / 500; 0 turns it off.
   */
  vtkSetMacro(FacetDistance, double);
  vtkGetMacro(FacetDistance, double);
  ///@}

  ///@{
  /**
   * Upper bound on the radius-edge ratio of the tetrahedra (CGAL's
   * cell_radius_edge_ratio). At least 1, or 0 to turn it off. Default 2, where refinement
   * is guaranteed to end; below 2 an automatic Steiner point cap ends a run that would not.
   */
  vtkSetMacro(CellRadiusEdgeRatio, double);
  vtkGetMacro(CellRadiusEdgeRatio, double);
  ///@}

  ///@{
  /**
   * Upper bound on the circumradius of the tetrahedra (CGAL's cell_size). Default -1:
   * the facet size in effect; 0 turns it off.
   */
  vtkSetMacro(CellSize, double);
  vtkGetMacro(CellSize, double);
  ///@}

  ///@{
  /**
   * Fill a closed surface with tetrahedra (default on). Off, or for an open surface, only
   * the surface is meshed and port 0 is empty.
   */
  vtkSetMacro(MeshVolume, vtkTypeBool);
  vtkGetMacro(MeshVolume, vtkTypeBool);
  vtkBooleanMacro(MeshVolume, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Sharp features, in degrees in [0, 180): input edges whose two triangles' normals differ
   * by more than this (and, for an open surface, its boundary edges) are kept as chains of
   * surface edges, and the corners where they meet as vertices, as CGAL Mesh_3 keeps
   * protected features. Default 0: none detected (sharp edges come out rounded).
   */
  vtkSetMacro(FeatureAngle, double);
  vtkGetMacro(FeatureAngle, double);
  ///@}

  ///@{
  /**
   * Refine where the surface is not a 2-manifold (default on), as CGAL Mesh_3's manifold():
   * once the criteria are met, the triangles at edges and vertices where the surface pinches
   * (a part thinner than the triangles) are refined until it is a manifold, down to
   * triangles of D/1000 or an eighth of FacetSize; pinches left (rough input, as a scan's
   * noise) are then undone by moving tetrahedra with all corners on the surface to the other
   * side (PinchRelabelled counts them). The field data NonManifoldFacets counts what is left
   * (with a warning), ManifoldSplits the triangles refined. Off: CGAL's non_manifold().
   */
  vtkSetMacro(Manifold, vtkTypeBool);
  vtkGetMacro(Manifold, vtkTypeBool);
  vtkBooleanMacro(Manifold, vtkTypeBool);
  ///@}

  ///@{
  /**
   * Sliver removal after refinement, in degrees in [0, 30] (default 0: off), as
   * vtkGPUQualityTetMesh's SliverAngle: interior points of tetrahedra with a dihedral angle
   * below it (or above 180 minus it) move to raise the smallest dihedral angle around them,
   * keeping CellRadiusEdgeRatio and CellSize where they were met. Only points whose
   * tetrahedra all lie inside the surface move (surface points stay), so the surface
   * (port 1) and the volume stay exactly as they were. The mesh is then not Delaunay where
   * points moved. The field data SliversBefore and SliversAfter count the tetrahedra beyond
   * the angle before and after. Volume meshing only.
   */
  vtkSetMacro(SliverAngle, double);
  vtkGetMacro(SliverAngle, double);
  ///@}

  ///@{
  /**
   * Cap on the number of inserted points; refinement stops cleanly when it is reached and
   * IsBad marks what is left above the criteria. -1 (default): an automatic cap, only
   * where termination is not guaranteed (CellRadiusEdgeRatio below 2).
   */
  vtkSetMacro(MaximumSteinerPoints, vtkIdType);
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

protected:
  vtkGPURestrictedDelaunay3D();
  ~vtkGPURestrictedDelaunay3D() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  int FillOutputPortInformation(int port, vtkInformation* info) override;
  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  double FacetAngle = 30.0;
  double FacetSize = -1.0;
  double FacetDistance = -1.0;
  double CellRadiusEdgeRatio = 2.0;
  double CellSize = -1.0;
  vtkTypeBool MeshVolume = 1;
  double FeatureAngle = 0.0;
  vtkTypeBool Manifold = 1;
  double SliverAngle = 0.0;
  vtkIdType MaximumSteinerPoints = -1;
  int Backend = AUTO;

private:
  vtkGPURestrictedDelaunay3D(const vtkGPURestrictedDelaunay3D&) = delete;
  void operator=(const vtkGPURestrictedDelaunay3D&) = delete;
};

#endif
