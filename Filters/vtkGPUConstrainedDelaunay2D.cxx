#include "vtkGPUConstrainedDelaunay2D.h"

#include "vtkCellData.h"
#include "vtkDataSet.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkTable.h"

#include "vtkGDRConversion.h"
#include "vtkGDRMeshingRun.h"

#include "gdr/refine2d.h"

#include <string>

vtkStandardNewMacro(vtkGPUConstrainedDelaunay2D);

//------------------------------------------------------------------------------
vtkGPUConstrainedDelaunay2D::vtkGPUConstrainedDelaunay2D()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
}

//------------------------------------------------------------------------------
void vtkGPUConstrainedDelaunay2D::SetHoleSeedsConnection(vtkAlgorithmOutput* output)
{
  this->SetInputConnection(1, output);
}

//------------------------------------------------------------------------------
void vtkGPUConstrainedDelaunay2D::SetHoleSeedsData(vtkDataObject* data)
{
  this->SetInputDataObject(1, data);
}

//------------------------------------------------------------------------------
int vtkGPUConstrainedDelaunay2D::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    return 1;
  }
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkGPUConstrainedDelaunay2D::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

//------------------------------------------------------------------------------
int vtkGPUConstrainedDelaunay2D::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkDataSet* holeSeeds = vtkDataSet::GetData(inputVector[1], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkTable* histogram = vtkTable::GetData(outputVector, 1);
  vtkPolyData* subsegments = vtkPolyData::GetData(outputVector, 2);
  if (!output || !histogram || !subsegments)
  {
    vtkErrorMacro("Missing output data objects.");
    return 0;
  }
  output->Initialize();
  histogram->Initialize();
  subsegments->Initialize();

  gdr::Pslg pslg;
  double z = 0.0;
  std::string warning;
  vtkGDRConversion::ToPslg(input, holeSeeds, pslg, z, warning);
  if (pslg.points.empty())
  {
    vtkDebugMacro("Empty input: empty output.");
    return 1;
  }
  if (!warning.empty())
  {
    vtkWarningMacro(<< warning);
  }

  gdr::Refine2dOptions options;
  options.min_angle = this->MinimumAngle;
  options.max_edge_length = this->MaximumEdgeLength;
  options.max_area = this->MaximumArea;
  options.max_steiner_points = static_cast<long long>(this->MaximumSteinerPoints);
  options.mode = this->Mode == CHEW ? gdr::EncroachMode::Chew : gdr::EncroachMode::Ruppert;
  options.remove_exterior = this->RemoveExterior != 0;
  options.off_centers = this->OffCenters != 0;
  options.refine = this->CDTOnly == 0;
  options.strict_input = this->StrictInput != 0;

  vtkGDRMeshingRun run(this);
  if (!run.SelectBackend(this->Backend, options.backend))
  {
    return 0;
  }

  if (!this->TriangleSwitches.empty() &&
    !run.Execute([&]() { gdr::apply_triangle_switches(this->TriangleSwitches, options); }))
  {
    return 0;
  }

  gdr::Refine2dResult result;
  const gdr::Callbacks callbacks = run.GetCallbacks();
  if (!run.Execute([&]() { result = gdr::refine_2d(pslg, options, callbacks); }))
  {
    return run.WasAborted() ? 1 : 0;
  }

  vtkNew<vtkPolyData> mesh;
  vtkNew<vtkTable> table;
  vtkNew<vtkPolyData> lines;
  if (!run.Execute(
        [&]()
        {
          vtkGDRConversion::ToPolyData(result.mesh, z, mesh);
          vtkGDRConversion::ToSubsegments(result.mesh, mesh, lines);
          vtkGDRConversion::AddTriangleQuality(result.mesh, this->MinimumAngle, mesh);
          vtkGDRConversion::AddStats(result.stats, mesh->GetFieldData());
          vtkGDRConversion::Histogram(mesh->GetCellData()->GetArray("MinAngle"), 60, table);
        }))
  {
    return 0;
  }
  if (this->CheckAbort())
  {
    return 1;
  }

  output->ShallowCopy(mesh);
  histogram->ShallowCopy(table);
  subsegments->ShallowCopy(lines);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGPUConstrainedDelaunay2D::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MinimumAngle: " << this->MinimumAngle << "\n";
  os << indent << "MaximumEdgeLength: " << this->MaximumEdgeLength << "\n";
  os << indent << "MaximumArea: " << this->MaximumArea << "\n";
  os << indent << "MaximumSteinerPoints: " << this->MaximumSteinerPoints << "\n";
  os << indent << "Mode: " << (this->Mode == CHEW ? "Chew" : "Ruppert") << "\n";
  os << indent << "Backend: "
     << (this->Backend == GPU ? "GPU" : (this->Backend == CPU ? "CPU" : "Auto")) << "\n";
  os << indent << "RemoveExterior: " << (this->RemoveExterior ? "On" : "Off") << "\n";
  os << indent << "OffCenters: " << (this->OffCenters ? "On" : "Off") << "\n";
  os << indent << "CDTOnly: " << (this->CDTOnly ? "On" : "Off") << "\n";
  os << indent << "StrictInput: " << (this->StrictInput ? "On" : "Off") << "\n";
  os << indent << "TriangleSwitches: " << this->TriangleSwitches << "\n";
}
