#include "vtkGPURestrictedDelaunay3D.h"

#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkTable.h"
#include "vtkUnstructuredGrid.h"

#include "vtkGDRConversion.h"
#include "vtkGDRMeshingRun.h"

#include "gdr/rdt3d.h"

vtkStandardNewMacro(vtkGPURestrictedDelaunay3D);

//------------------------------------------------------------------------------
vtkGPURestrictedDelaunay3D::vtkGPURestrictedDelaunay3D()
{
  this->SetNumberOfInputPorts(1);
  this->SetNumberOfOutputPorts(3);
}

//------------------------------------------------------------------------------
int vtkGPURestrictedDelaunay3D::FillInputPortInformation(int port, vtkInformation* info)
{
  if (port == 0)
  {
    info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPolyData");
    return 1;
  }
  return 0;
}

//------------------------------------------------------------------------------
int vtkGPURestrictedDelaunay3D::FillOutputPortInformation(int port, vtkInformation* info)
{
  if (port == 1)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkPolyData");
    return 1;
  }
  if (port == 2)
  {
    info->Set(vtkDataObject::DATA_TYPE_NAME(), "vtkTable");
    return 1;
  }
  return this->Superclass::FillOutputPortInformation(port, info);
}

//------------------------------------------------------------------------------
int vtkGPURestrictedDelaunay3D::RequestData(vtkInformation* vtkNotUsed(request),
  vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkPolyData* input = vtkPolyData::GetData(inputVector[0], 0);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkPolyData* surfaceOutput = vtkPolyData::GetData(outputVector, 1);
  vtkTable* histogram = vtkTable::GetData(outputVector, 2);
  if (!output || !surfaceOutput || !histogram)
  {
    vtkErrorMacro("Missing output data objects.");
    return 0;
  }
  output->Initialize();
  surfaceOutput->Initialize();
  histogram->Initialize();

  vtkGDRMeshingRun run(this);
  gdr::Surface surface;
  if (!run.Execute([&]() { vtkGDRConversion::ToSurface(input, surface); }))
  {
    return 0;
  }
  if (surface.triangles.empty())
  {
    if (input && input->GetNumberOfPoints() > 0)
    {
      vtkWarningMacro("The input has no polygons: there is no surface to mesh.");
    }
    return 1;
  }

  // Out-of-range values are not clamped here: the engine refuses them, naming the value.
  gdr::RestrictedDelaunayOptions options;
  options.facet_angle = this->FacetAngle;
  options.facet_size = this->FacetSize;
  options.facet_distance = this->FacetDistance;
  options.cell_radius_edge_ratio = this->CellRadiusEdgeRatio;
  options.cell_size = this->CellSize;
  options.mesh_volume = this->MeshVolume != 0;
  options.feature_angle = this->FeatureAngle;
  options.manifold = this->Manifold != 0;
  options.sliver_angle = this->SliverAngle;
  options.max_steiner_points = static_cast<long long>(this->MaximumSteinerPoints);
  if (!run.SelectBackend(this->Backend, options.backend))
  {
    return 0;
  }

  gdr::RestrictedDelaunayResult result;
  const gdr::Callbacks callbacks = run.GetCallbacks();
  if (!run.Execute([&]() { result = gdr::restricted_delaunay_3d(surface, options, callbacks); }))
  {
    return run.WasAborted() ? 1 : 0;
  }

  vtkNew<vtkUnstructuredGrid> tets;
  vtkNew<vtkPolyData> restricted;
  vtkNew<vtkTable> angles;
  if (!run.Execute(
        [&]()
        {
          vtkGDRConversion::ToRestrictedMesh(result, tets, restricted);
          vtkGDRConversion::AddStats(result.stats, tets->GetFieldData());
          restricted->GetFieldData()->ShallowCopy(tets->GetFieldData());
          // One table, one chart: the facet angles' 61 bins share the dihedral angles' 180.
          vtkGDRConversion::HistogramTable(
            result.dihedral_histogram, "DihedralAngleCount", angles);
          vtkGDRConversion::AddHistogramColumn(
            result.facet_angle_histogram, "FacetAngleCount", angles);
        }))
  {
    return 0;
  }
  if (this->CheckAbort())
  {
    return 1;
  }

  if (result.stats.volume_meshed)
  {
    output->ShallowCopy(tets);
  }
  else
  {
    // Surface only: no tetrahedra, and no points without cells; the statistics stay.
    output->GetFieldData()->ShallowCopy(tets->GetFieldData());
  }
  surfaceOutput->ShallowCopy(restricted);
  histogram->ShallowCopy(angles);
  this->UpdateProgress(1.0);
  return 1;
}

//------------------------------------------------------------------------------
void vtkGPURestrictedDelaunay3D::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FacetAngle: " << this->FacetAngle << "\n";
  os << indent << "FacetSize: " << this->FacetSize << "\n";
  os << indent << "FacetDistance: " << this->FacetDistance << "\n";
  os << indent << "CellRadiusEdgeRatio: " << this->CellRadiusEdgeRatio << "\n";
  os << indent << "CellSize: " << this->CellSize << "\n";
  os << indent << "MeshVolume: " << this->MeshVolume << "\n";
  os << indent << "FeatureAngle: " << this->FeatureAngle << "\n";
  os << indent << "Manifold: " << this->Manifold << "\n";
  os << indent << "SliverAngle: " << this->SliverAngle << "\n";
  os << indent << "MaximumSteinerPoints: " << this->MaximumSteinerPoints << "\n";
  os << indent << "Backend: "
     << (this->Backend == GPU ? "GPU" : (this->Backend == CPU ? "CPU" : "Auto")) << "\n";
}
