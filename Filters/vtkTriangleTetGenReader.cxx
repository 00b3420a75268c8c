#include "vtkTriangleTetGenReader.h"

#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"

#include "vtkGDRConversion.h"
#include "vtkGDRMeshingRun.h"

#include "gdr/io.h"

#include <algorithm>
#include <cctype>

vtkStandardNewMacro(vtkTriangleTetGenReader);

//------------------------------------------------------------------------------
vtkTriangleTetGenReader::vtkTriangleTetGenReader()
{
  this->SetNumberOfInputPorts(0);
}

//------------------------------------------------------------------------------
int vtkTriangleTetGenReader::CanReadFile(const char* fileName)
{
  std::string name = fileName ? fileName : "";
  std::transform(name.begin(), name.end(), name.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  for (const char* ext : { ".poly", ".node", ".smesh", ".off" })
  {
    const std::string e = ext;
    if (name.size() > e.size() && name.compare(name.size() - e.size(), e.size(), e) == 0)
    {
      return 1;
    }
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkTriangleTetGenReader::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** vtkNotUsed(inputVector), vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  output->Initialize();
  if (this->FileName.empty())
  {
    vtkErrorMacro("No file name given.");
    return 0;
  }
  // The reading and its errors (IoError: FILE:LINE: reason) go through the filters' one
  // run helper, so that they read the same as the meshing filters' errors.
  vtkNew<vtkPolyData> data;
  vtkGDRMeshingRun run(this);
  const bool ok = run.Execute(
    [&]()
    {
      if (gdr::io::detect_input_kind(this->FileName) == gdr::io::InputKind::Pslg2d)
      {
        vtkGDRConversion::FromPslg(gdr::io::read_poly(this->FileName), data);
      }
      else
      {
        vtkGDRConversion::FromSurface(gdr::io::read_surface(this->FileName), data);
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
void vtkTriangleTetGenReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
}
