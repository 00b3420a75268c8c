/**
 * @class   vtkTriangleTetGenReader
 * @brief   reads meshing inputs: Triangle .poly/.node, TetGen .poly/.smesh/.node, .off
 *
 * vtkTriangleTetGenReader reads the input files of Triangle and TetGen into polydata that
 * the meshing filters take as they are:
 *
 * - Triangle .poly (and .node): a planar straight-line graph at z = 0. Its segments are
 *   lines, points on no segment are vertex cells, and the holes section is kept in the
 *   field data array HoleSeeds (3 components), which vtkGPUConstrainedDelaunay2D uses as
 *   hole seeds (on top of any given on its HoleSeeds port). Boundary markers and point
 *   attributes, where the file has them, are the point array BoundaryMarker, the cell
 *   array BoundaryMarker (each line's segment marker; 0 on vertex cells) and the point
 *   array PointAttributes (one component per attribute), which the filter carries to its
 *   output.
 * - TetGen .poly, .smesh (and .node), and .off: a surface. Facets are triangles (polygons
 *   are triangulated in their plane; the cell array FacetId gives each triangle's facet so
 *   that vtkGPUQualityTetMesh keeps the facet whole), segments are lines. The volume holes
 *   go into the field data array HoleSeeds and the regions into RegionSeeds (3 components)
 *   with RegionAttribute and RegionMaximumVolume, which vtkGPUQualityTetMesh uses as seeds
 *   (on top of any given on its Seeds port).
 *
 * A .poly or .node is Triangle's or TetGen's by the dimension in its header (2 or 3), as
 * the gdr command line decides. A .poly whose point section is empty takes its points from
 * the .node beside it. Malformed files are reported with vtkErrorMacro (file, line, reason)
 * and give an empty output.
 */

#ifndef vtkTriangleTetGenReader_h
#define vtkTriangleTetGenReader_h

#include "GPUDelaunayFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <string> // for FileName

class GPUDELAUNAYFILTERS_EXPORT vtkTriangleTetGenReader : public vtkPolyDataAlgorithm
{
public:
  static vtkTriangleTetGenReader* New();
  vtkTypeMacro(vtkTriangleTetGenReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The file to read (.poly, .node, .smesh or .off).
   */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /**
   * 1 when the file name has one of the extensions this reader reads, else 0.
   */
  static int CanReadFile(const char* fileName);

protected:
  vtkTriangleTetGenReader();
  ~vtkTriangleTetGenReader() override = default;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  std::string FileName;

private:
  vtkTriangleTetGenReader(const vtkTriangleTetGenReader&) = delete;
  void operator=(const vtkTriangleTetGenReader&) = delete;
};

#endif
