#include "vtkGPUQualityTetMesh.h"

#include "vtkDataSet.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkUnstructuredGrid.h"

#include "vtkGDRConversion.h"
#include "vtkGDRMeshingRun.h"

#include "gdr/qm3d.h"

#include <string>

vtkStandardNewMacro(vtkGPUQualityTetMesh);

//------------------------------------------------------------------------------
vtkGPUQualityTetMesh::vtkGPUQualityTetMesh()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
}

//------------------------------------------------------------------------------
void vtkGPUQualityTetMesh::SetRadiusEdgeRatio(double ratio)
{
  // 0 turns the bound off; a bound below 1 cannot be met, 1 is the closest that can.
  const double value = !(ratio > 0.0) ? 0.0 : (ratio < 1.0 ? 1.0 : ratio);
  if (this->RadiusEdgeRatio != value)
  {
    this->RadiusEdgeRatio = value;
    this->Modified();
  }
}

//------------------------------------------------------------------------------
void vtkGPUQualityTetMesh::AddSeedsConnection(vtkAlgorithmOutput* output)
{
  this->AddInputConnection(1, output);
}

//------------------------------------------------------------------------------
void vtkGPUQualityTetMesh::AddSeedsData(vtkDataObject* data)
{
  this->AddInputDataObject(1, data);
}

//------------------------------------------------------------------------------
void vtkGPUQualityTetMesh::RemoveAllSeeds()
{
  this->SetInputConnection(1, nullptr);
}

//------------------------------------------------------------------------------
int vtkGPUQualityTetMesh::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
    return 1;
  }
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
    info->Set(vtkAlgorithm::INPUT_IS_REPEATABLE(), 1);
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkGPUQualityTetMesh::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  if (port == 2)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkPolyData");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

//------------------------------------------------------------------------------
int vtkGPUQualityTetMesh::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkTable* histogram = vtkTable::GetData(outputVector, 1);
  vtkPolyData* subfaces = vtkPolyData::GetData(outputVector, 2);
  if (!output || !histogram || !subfaces)
  {
    vtkErrorMacro("Missing output data objects.");
    return 0;
  }
  output->Initialize();
  histogram->Initialize();
  subfaces->Initialize();

  vtkGDRMeshingRun run(this);
  gdr::Surface surface;
  std::string warning;
  if (!run.Execute(
        [&]()
        {
          if (auto* grid = vtkUnstructuredGrid::SafeDownCast(input))
          {
            vtkGDRConversion::ToSurface(grid, surface, warning);
          }
          else
          {
            vtkGDRConversion::ToSurface(vtkPolyData::SafeDownCast(input), surface);
          }
          for (int i = 0; i < inputVector[1]->GetNumberOfInformationObjects(); ++i)
          {
            vtkGDRConversion::AddSeeds(vtkDataSet::GetData(inputVector[1], i), surface);
          }
        }))
  {
    return 0;
  }
  if (!warning.empty())
  {
    vtkWarningMacro(<< warning);
  }
  if (surface.triangles.empty())
  {
    if (input && input->GetNumberOfPoints() > 0)
    {
      vtkWarningMacro("The input has no polygons (or no cells): there is no surface to mesh.");
    }
    return 1;
  }

  gdr::QualityTetOptions options;
  options.radius_edge_ratio = this->RadiusEdgeRatio;
  options.min_dihedral_angle = this->MinimumDihedralAngle;
  options.sliver_angle = this->SliverAngle;
  options.coplanar_angle = this->CoplanarAngle;
  options.max_volume = this->MaximumVolume;
  options.max_steiner_points = static_cast<long long>(this->MaximumSteinerPoints);
  if (!run.SelectBackend(this->Backend, options.backend))
  {
    return 0;
  }

  gdr::QualityTetResult result;
  const gdr::Callbacks callbacks = run.GetCallbacks();
  if (!run.Execute([&]() { result = gdr::quality_tet_mesh(surface, options, callbacks); }))
  {
    return run.WasAborted() ? 1 : 0;
  }

  vtkNew<vtkUnstructuredGrid> mesh;
  vtkNew<vtkTable> table;
  vtkNew<vtkPolyData> faces;
  if (!run.Execute(
        [&]()
        {
          vtkGDRConversion::ToUnstructuredGrid(result, mesh);
          vtkGDRConversion::AddStats(result.stats, mesh->GetFieldData());
          vtkGDRConversion::HistogramTable(result.dihedral_histogram, "DihedralAngleCount", table);
          vtkGDRConversion::ToSubfaces(result.mesh, mesh, faces);
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
  subfaces->ShallowCopy(faces);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGPUQualityTetMesh::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "RadiusEdgeRatio: " << this->RadiusEdgeRatio << "\n";
  os << indent << "MinimumDihedralAngle: " << this->MinimumDihedralAngle << "\n";
  os << indent << "SliverAngle: " << this->SliverAngle << "\n";
  os << indent << "CoplanarAngle: " << this->CoplanarAngle << "\n";
  os << indent << "MaximumVolume: " << this->MaximumVolume << "\n";
  os << indent << "MaximumSteinerPoints: " << this->MaximumSteinerPoints << "\n";
  os << indent << "Backend: "
     << (this->Backend == GPU ? "GPU" : (this->Backend == CPU ? "CPU" : "Auto")) << "\n";
}
