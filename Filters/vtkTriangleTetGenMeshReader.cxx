#include "vtkTriangleTetGenMeshReader.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkUnstructuredGrid.h"

#include "vtkGDRConversion.h"
#include "vtkGDRMeshingRun.h"

#include "gdr/io.h"

vtkStandardNewMacro(vtkTriangleTetGenMeshReader);

//------------------------------------------------------------------------------
vtkTriangleTetGenMeshReader::vtkTriangleTetGenMeshReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
int vtkTriangleTetGenMeshReader::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** vtkNotUsed(inputVector), vtkInformationVector* outputVector)
{
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  output->Initialize();
  if (this->FileName.empty())
  {
    vtkErrorMacro("No file name given.");
    return 0;
  }
  const std::string& ele = this->FileName;
  const std::string node = ele.substr(0, ele.find_last_of('.')) + ".node";
  vtkNew<vtkUnstructuredGrid> data;
  vtkGDRMeshingRun run(this);
  const bool ok = run.Execute(
    [&]()
    {
      if (gdr::io::element_file_dimension(ele) == 2)
      {
        vtkGDRConversion::FromTriMesh(gdr::io::read_triangle_mesh(node, ele), data);
      }
      else
      {
        vtkGDRConversion::FromTetMesh(gdr::io::read_tetgen_mesh(node, ele), data);
      }
    });
  if (!ok)
  {
    return 0;
  }
  output->ShallowCopy(data);
  return 1;
}

//------------------------------------------------------------------------------
void vtkTriangleTetGenMeshReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
