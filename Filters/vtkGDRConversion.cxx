#include "vtkGDRConversion.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataSet.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnsignedCharArray.h"

#include "gdr/backend.h"
#include "gdr/validate.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <utility>
#include <vector>

namespace
{
// Maps VTK point ids to PSLG vertex indices, adding points on first use.
class PointMap
{
public:
  PointMap(vtkPoints* points, gdr::Pslg& pslg)
    : Points(points)
    , Pslg(pslg)
    , Index(points->GetNumberOfPoints(), -1)
  {
  }

  int Use(vtkIdType id)
  {
    if (this->Index[id] < 0)
    {
      double p[3];
      this->Points->GetPoint(id, p);
      this->Index[id] = static_cast<int>(this->Pslg.points.size());
      this->Pslg.points.push_back({ p[0], p[1] });
      this->ZMin = std::min(this->ZMin, p[2]);
      this->ZMax = std::max(this->ZMax, p[2]);
      if (this->Pslg.points.size() == 1)
      {
        this->Z = p[2];
      }
    }
    return this->Index[id];
  }

  void Segment(vtkIdType a, vtkIdType b)
  {
    if (a == b)
    {
      return;
    }
    const int ia = this->Use(a);
    const int ib = this->Use(b);
    if (ia == ib)
    {
      return;
    }
    if (this->Seen.insert(std::minmax(ia, ib)).second)
    {
      this->Pslg.segments.push_back({ ia, ib });
    }
  }

  vtkPoints* Points;
  gdr::Pslg& Pslg;
  std::vector<int> Index;
  std::set<std::pair<int, int>> Seen;
  double Z = 0.0;
  double ZMin = VTK_DOUBLE_MAX;
  double ZMax = VTK_DOUBLE_MIN;
};
}

//------------------------------------------------------------------------------
void vtkGDRConversion::ToPslg(
  vtkPolyData* input, vtkDataSet* holeSeeds, gdr::Pslg& pslg, double& z, std::string& warning)
{
  pslg = gdr::Pslg();
  z = 0.0;
  warning.clear();
  if (!input || !input->GetPoints() || input->GetNumberOfPoints() == 0)
  {
    return;
  }

  PointMap map(input->GetPoints(), pslg);
  vtkIdType npts;
  const vtkIdType* ids;

  vtkCellArray* verts = input->GetVerts();
  for (verts->InitTraversal(); verts->GetNextCell(npts, ids);)
  {
    for (vtkIdType i = 0; i < npts; ++i)
    {
      map.Use(ids[i]);
    }
  }
  vtkCellArray* lines = input->GetLines();
  for (lines->InitTraversal(); lines->GetNextCell(npts, ids);)
  {
    if (npts == 1)
    {
      map.Use(ids[0]);
    }
    for (vtkIdType i = 0; i + 1 < npts; ++i)
    {
      map.Segment(ids[i], ids[i + 1]);
    }
  }
  vtkCellArray* polys = input->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids);)
  {
    for (vtkIdType i = 0; i < npts; ++i)
    {
      map.Segment(ids[i], ids[(i + 1) % npts]);
    }
  }
  vtkCellArray* strips = input->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(npts, ids);)
  {
    for (vtkIdType i = 0; i + 2 < npts; ++i)
    {
      map.Segment(ids[i], ids[i + 1]);
      map.Segment(ids[i + 1], ids[i + 2]);
      map.Segment(ids[i + 2], ids[i]);
    }
  }
  if (input->GetNumberOfCells() == 0)
  {
    for (vtkIdType id = 0; id < input->GetNumberOfPoints(); ++id)
    {
      map.Use(id);
    }
  }

  z = map.Z;
  if (!pslg.points.empty())
  {
    double bounds[6];
    input->GetBounds(bounds);
    const double extent = std::max(bounds[1] - bounds[0], bounds[3] - bounds[2]);
    if (map.ZMax - map.ZMin > 1e-9 * std::max(extent, 1e-300))
    {
      std::ostringstream note;
      note << "The input is not in a z = constant plane (z from " << map.ZMin << " to "
           << map.ZMax << "): z is ignored and the mesh is placed at z = " << z << ".";
      warning = note.str();
    }
  }

  if (holeSeeds)
  {
    for (vtkIdType id = 0; id < holeSeeds->GetNumberOfPoints(); ++id)
    {
      double p[3];
      holeSeeds->GetPoint(id, p);
      pslg.holes.push_back({ p[0], p[1] });
    }
  }
}

//------------------------------------------------------------------------------
void vtkGDRConversion::ToPolyData(const gdr::TriMesh& mesh, double z, vtkPolyData* output)
{
  output->Initialize();
  const vtkIdType npoints = static_cast<vtkIdType>(mesh.points.size());
  const vtkIdType ntris = static_cast<vtkIdType>(mesh.triangles.size());

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(npoints);
  for (vtkIdType i = 0; i < npoints; ++i)
  {
    points->SetPoint(i, mesh.points[i].x, mesh.points[i].y, z);
  }

  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(ntris + 1);
  connectivity->SetNumberOfValues(3 * ntris);
  for (vtkIdType t = 0; t < ntris; ++t)
  {
    offsets->SetValue(t, 3 * t);
    for (int k = 0; k < 3; ++k)
    {
      connectivity->SetValue(3 * t + k, mesh.triangles[t][k]);
    }
  }
  offsets->SetValue(ntris, 3 * ntris);
  vtkNew<vtkCellArray> triangles;
  triangles->SetData(offsets, connectivity);

  output->SetPoints(points);
  output->SetPolys(triangles);

  if (static_cast<vtkIdType>(mesh.point_type.size()) == npoints)
  {
    vtkNew<vtkUnsignedCharArray> type;
    type->SetName("PointType");
    type->SetNumberOfValues(npoints);
    for (vtkIdType i = 0; i < npoints; ++i)
    {
      type->SetValue(i, static_cast<unsigned char>(mesh.point_type[i]));
    }
    output->GetPointData()->AddArray(type);
    output->GetPointData()->SetActiveScalars("PointType");
  }
}

//------------------------------------------------------------------------------
void vtkGDRConversion::AddTriangleQuality(
  const gdr::TriMesh& mesh, double minimumAngle, vtkPolyData* output)
{
  const vtkIdType ntris = static_cast<vtkIdType>(mesh.triangles.size());
  vtkNew<vtkDoubleArray> minAngle;
  vtkNew<vtkDoubleArray> maxAngle;
  vtkNew<vtkDoubleArray> radiusEdge;
  vtkNew<vtkDoubleArray> area;
  vtkNew<vtkUnsignedCharArray> isBad;
  minAngle->SetName("MinAngle");
  maxAngle->SetName("MaxAngle");
  radiusEdge->SetName("RadiusEdgeRatio");
  area->SetName("Area");
  isBad->SetName("IsBad");
  minAngle->SetNumberOfValues(ntris);
  maxAngle->SetNumberOfValues(ntris);
  radiusEdge->SetNumberOfValues(ntris);
  area->SetNumberOfValues(ntris);
  isBad->SetNumberOfValues(ntris);

  for (vtkIdType t = 0; t < ntris; ++t)
  {
    const gdr::Point2& a = mesh.points[mesh.triangles[t][0]];
    const gdr::Point2& b = mesh.points[mesh.triangles[t][1]];
    const gdr::Point2& c = mesh.points[mesh.triangles[t][2]];
    double lo = 0.0;
    double hi = 0.0;
    gdr::triangle_angles(a, b, c, lo, hi);
    minAngle->SetValue(t, lo);
    maxAngle->SetValue(t, hi);
    radiusEdge->SetValue(t, gdr::triangle_radius_edge(a, b, c));
    area->SetValue(t, gdr::triangle_area(a, b, c));
    isBad->SetValue(t, lo < minimumAngle ? 1 : 0);
  }

  vtkCellData* cd = output->GetCellData();
  cd->AddArray(minAngle);
  cd->AddArray(maxAngle);
  cd->AddArray(radiusEdge);
  cd->AddArray(area);
  cd->AddArray(isBad);
  cd->SetActiveScalars("MinAngle");
}

//------------------------------------------------------------------------------
void vtkGDRConversion::Histogram(vtkDataArray* values, int upper, vtkTable* table)
{
  table->Initialize();
  vtkNew<vtkDoubleArray> centers;
  vtkNew<vtkIdTypeArray> counts;
  centers->SetName("bin_extents");
  counts->SetName("bin_values");
  centers->SetNumberOfValues(upper);
  counts->SetNumberOfValues(upper);
  for (int i = 0; i < upper; ++i)
  {
    centers->SetValue(i, i + 0.5);
    counts->SetValue(i, 0);
  }
  if (values)
  {
    for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    {
      const double v = values->GetComponent(i, 0);
      if (!std::isfinite(v))
      {
        continue;
      }
      const int bin = std::min(upper - 1, std::max(0, static_cast<int>(std::floor(v))));
      counts->SetValue(bin, counts->GetValue(bin) + 1);
    }
  }
  table->AddColumn(centers);
  table->AddColumn(counts);
}

//------------------------------------------------------------------------------
namespace
{
template <typename ArrayT, typename ValueT>
void AddValue(vtkFieldData* fd, const char* name, ValueT value)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfValues(1);
  array->SetValue(0, value);
  fd->AddArray(array);
}
}

void vtkGDRConversion::AddStats(const gdr::Refine2dStats& stats, vtkFieldData* fd)
{
  AddValue<vtkStringArray>(fd, "Backend", gdr::to_string(stats.backend_used));
  AddValue<vtkStringArray>(fd, "DeviceName", stats.device_name);
  AddValue<vtkIntArray>(fd, "Iterations", stats.iterations);
  AddValue<vtkIdTypeArray>(fd, "InputPoints", static_cast<vtkIdType>(stats.input_points));
  AddValue<vtkIdTypeArray>(fd, "InputSegments", static_cast<vtkIdType>(stats.input_segments));
  AddValue<vtkIdTypeArray>(
    fd, "DuplicatePointsMerged", static_cast<vtkIdType>(stats.duplicate_points_merged));
  AddValue<vtkIdTypeArray>(fd, "SteinerPoints", static_cast<vtkIdType>(stats.steiner_points));
  AddValue<vtkIdTypeArray>(fd, "BadTriangles", static_cast<vtkIdType>(stats.bad_triangles));
  AddValue<vtkDoubleArray>(fd, "BadAreaPercent", stats.bad_area_percent);
  AddValue<vtkIdTypeArray>(fd, "SteinerCap", static_cast<vtkIdType>(stats.steiner_cap));
  AddValue<vtkIntArray>(fd, "SteinerCapReached", stats.steiner_cap_reached ? 1 : 0);
  AddValue<vtkIntArray>(fd, "Stalled", stats.stalled ? 1 : 0);
  AddValue<vtkDoubleArray>(fd, "MinimumAngleReached", stats.min_angle_deg);
  AddValue<vtkDoubleArray>(fd, "InputSeconds", stats.input_seconds);
  AddValue<vtkDoubleArray>(fd, "CDTSeconds", stats.cdt_seconds);
  AddValue<vtkDoubleArray>(fd, "RefineSeconds", stats.refine_seconds);
  AddValue<vtkDoubleArray>(fd, "OutputSeconds", stats.output_seconds);
  AddValue<vtkDoubleArray>(fd, "TotalSeconds", stats.total_seconds);
  AddValue<vtkDoubleArray>(
    fd, "PeakDeviceBytes", static_cast<double>(stats.peak_device_bytes));

  vtkNew<vtkStringArray> names;
  vtkNew<vtkDoubleArray> seconds;
  names->SetName("PhaseNames");
  seconds->SetName("PhaseSeconds");
  for (const gdr::PhaseTime& phase : stats.phases)
  {
    names->InsertNextValue(phase.name);
    seconds->InsertNextValue(phase.seconds);
  }
  fd->AddArray(names);
  fd->AddArray(seconds);
}
