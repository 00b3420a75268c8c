/**
 * @class   vtkTriangleTetGenMeshReader
 * @brief   reads meshes in Triangle's or TetGen's .node/.ele files
 *
 * vtkTriangleTetGenMeshReader reads the .ele file it is given and the .node file beside it
 * (same base name): a Triangle mesh (3 or 6 nodes per element) gives triangles at z = 0, a
 * TetGen mesh (4 or 10) gives tetrahedra, with the cell array Region when the .ele has a
 * region attribute. These are the files `gdr 2d -o x.node` and `gdr tet -o x.node` write,
 * as Triangle and TetGen do. Malformed files are reported with vtkErrorMacro and give an
 * empty output.
 */

#ifndef vtkTriangleTetGenMeshReader_h
#define vtkTriangleTetGenMeshReader_h

#include "GPUDelaunayFiltersModule.h" // for export macro
#include "vtkUnstructuredGridAlgorithm.h"

#include <string> // for FileName

class GPUDELAUNAYFILTERS_EXPORT vtkTriangleTetGenMeshReader : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkTriangleTetGenMeshReader* New();
  vtkTypeMacro(vtkTriangleTetGenMeshReader, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /**
   * The .ele file to read; its points come from the .node file beside it.
   */
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

protected:
  vtkTriangleTetGenMeshReader();
  ~vtkTriangleTetGenMeshReader() override = default;

  int RequestData(vtkInformation* request, vtkInformationVector** inputVector,
    vtkInformationVector* outputVector) override;

  std::string FileName;

private:
  vtkTriangleTetGenMeshReader(const vtkTriangleTetGenMeshReader&) = delete;
  void operator=(const vtkTriangleTetGenMeshReader&) = delete;
};

#endif
