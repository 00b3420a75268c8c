#include "vtkGDRConversion.h"

#include "vtkCellArray.h"
#include "vtkCellCenters.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkConnectivityFilter.h"
#include "vtkDataSet.h"
#include "vtkDataSetSurfaceFilter.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdFilter.h"
#include "vtkIdList.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkPolygon.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkThreshold.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnstructuredGrid.h"

#include "gdr/backend.h"
#include "gdr/error.h"
#include "gdr/refine2d.h"
#include "gdr/validate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace
{
// Cells of N corners each, as a vtkCellArray; corner k of a cell is cell[order[k]].
template <std::size_t N, class A>
vtkSmartPointer<vtkCellArray> FixedSizeCells(
  const std::vector<std::array<int, N>, A>& cells, const std::array<int, N>& order)
{
  const vtkIdType n = static_cast<vtkIdType>(cells.size());
  vtkNew<vtkIdTypeArray> offsets;
  vtkNew<vtkIdTypeArray> connectivity;
  offsets->SetNumberOfValues(n + 1);
  connectivity->SetNumberOfValues(static_cast<vtkIdType>(N) * n);
  for (vtkIdType c = 0; c < n; ++c)
  {
    offsets->SetValue(c, static_cast<vtkIdType>(N) * c);
    for (std::size_t k = 0; k < N; ++k)
    {
      connectivity->SetValue(static_cast<vtkIdType>(N) * c + k, cells[c][order[k]]);
    }
  }
  offsets->SetValue(n, static_cast<vtkIdType>(N) * n);
  vtkSmartPointer<vtkCellArray> array = vtkSmartPointer<vtkCellArray>::New();
  array->SetData(offsets, connectivity);
  return array;
}

// `values` as an array of `components` components added to `data` (cell or point data).
template <typename ArrayT, typename ValueT, class A>
void AddArray(vtkDataSetAttributes* data, const char* name, const std::vector<ValueT, A>& values,
  int components = 1)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  std::copy(values.begin(), values.end(), array->GetPointer(0));
  data->AddArray(array);
}
}

namespace
{
// What Triangle's .node and .ele carry besides the mesh, where `mesh` has it: the cell array
// Region (the regional attribute, -A), the point arrays BoundaryMarker and PointAttributes.
void AddTriangleFileData(const gdr::TriMesh& mesh, vtkDataSet* output)
{
  if (!mesh.triangle_region.empty() && mesh.triangle_region.size() == mesh.triangles.size())
  {
    AddArray<vtkDoubleArray>(output->GetCellData(), "Region", mesh.triangle_region);
  }
  if (!mesh.points.empty() && mesh.point_markers.size() == mesh.points.size())
  {
    AddArray<vtkIntArray>(output->GetPointData(), "BoundaryMarker", mesh.point_markers);
  }
  const int na = mesh.point_attribute_count;
  if (na > 0 && mesh.point_attributes.size() == mesh.points.size() * na)
  {
    AddArray<vtkDoubleArray>(output->GetPointData(), "PointAttributes", mesh.point_attributes, na);
  }
}

// Maps VTK point ids to PSLG vertex indices, adding points on first use. With
// `segmentMarkers` (a cell array), each new segment takes the marker of its cell.
class PointMap
{
public:
  PointMap(vtkPoints* points, gdr::Pslg& pslg, vtkDataArray* segmentMarkers)
    : Points(points)
    , Pslg(pslg)
    , Index(points->GetNumberOfPoints(), -1)
    , SegmentMarkers(segmentMarkers)
  {
  }

  int Use(vtkIdType id)
  {
    if (this->Index[id] < 0)
    {
      double p[3];
      this->Points->GetPoint(id, p);
      this->Index[id] = static_cast<int>(this->Pslg.points.size());
      this->Ids.push_back(id);
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

  void Segment(vtkIdType cell, vtkIdType a, vtkIdType b)
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
      if (this->SegmentMarkers)
      {
        this->Pslg.segment_markers.push_back(
          static_cast<int>(std::lround(this->SegmentMarkers->GetComponent(cell, 0))));
      }
    }
  }

  vtkPoints* Points;
  gdr::Pslg& Pslg;
  std::vector<int> Index;
  std::vector<vtkIdType> Ids; // the VTK id of each PSLG point
  vtkDataArray* SegmentMarkers;
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

  // Triangle's boundary markers and point attributes, under the names the reader and gdr 2d
  // give them (any numeric type; markers are rounded to integers).
  vtkDataArray* segmentMarkers = input->GetCellData()->GetArray("BoundaryMarker");
  if (segmentMarkers &&
    (segmentMarkers->GetNumberOfComponents() != 1 ||
      segmentMarkers->GetNumberOfTuples() != input->GetNumberOfCells()))
  {
    segmentMarkers = nullptr;
  }
  PointMap map(input->GetPoints(), pslg, segmentMarkers);
  vtkIdType npts;
  const vtkIdType* ids;
  vtkIdType cell = 0; // polydata cell ids count vertices, lines, polygons, strips in turn

  vtkCellArray* verts = input->GetVerts();
  for (verts->InitTraversal(); verts->GetNextCell(npts, ids); ++cell)
  {
    for (vtkIdType i = 0; i < npts; ++i)
    {
      map.Use(ids[i]);
    }
  }
  vtkCellArray* lines = input->GetLines();
  for (lines->InitTraversal(); lines->GetNextCell(npts, ids); ++cell)
  {
    if (npts == 1)
    {
      map.Use(ids[0]);
    }
    for (vtkIdType i = 0; i + 1 < npts; ++i)
    {
      map.Segment(cell, ids[i], ids[i + 1]);
    }
  }
  std::vector<std::vector<int>> rings;  // the polygons, for holes by orientation
  vtkCellArray* polys = input->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids); ++cell)
  {
    rings.emplace_back();
    for (vtkIdType i = 0; i < npts; ++i)
    {
      map.Segment(cell, ids[i], ids[(i + 1) % npts]);
      const int v = map.Use(ids[i]);
      if (rings.back().empty() || (rings.back().back() != v && rings.back().front() != v))
      {
        rings.back().push_back(v);
      }
    }
  }
  vtkCellArray* strips = input->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(npts, ids); ++cell)
  {
    for (vtkIdType i = 0; i + 2 < npts; ++i)
    {
      map.Segment(cell, ids[i], ids[i + 1]);
      map.Segment(cell, ids[i + 1], ids[i + 2]);
      map.Segment(cell, ids[i + 2], ids[i]);
    }
  }
  if (input->GetNumberOfCells() == 0)
  {
    for (vtkIdType id = 0; id < input->GetNumberOfPoints(); ++id)
    {
      map.Use(id);
    }
  }

  vtkPointData* pd = input->GetPointData();
  vtkDataArray* pointMarkers = pd->GetArray("BoundaryMarker");
  if (pointMarkers && pointMarkers->GetNumberOfComponents() == 1)
  {
    for (const vtkIdType id : map.Ids)
    {
      pslg.point_markers.push_back(static_cast<int>(std::lround(pointMarkers->GetComponent(id, 0))));
    }
  }
  if (vtkDataArray* attributes = pd->GetArray("PointAttributes"))
  {
    pslg.point_attribute_count = attributes->GetNumberOfComponents();
    for (const vtkIdType id : map.Ids)
    {
      for (int c = 0; c < pslg.point_attribute_count; ++c)
      {
        pslg.point_attributes.push_back(attributes->GetComponent(id, c));
      }
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
  AddFileSeeds(input, pslg);
  // As vtkDelaunay2D: clockwise polygons inside counter-clockwise ones are holes.
  int unseeded = 0;
  for (const gdr::Point2& seed : gdr::clockwise_polygon_holes(pslg, rings, &unseeded))
  {
    pslg.holes.push_back(seed);
  }
  if (unseeded > 0)
  {
    warning += std::string(warning.empty() ? "" : " ") + std::to_string(unseeded) +
      " clockwise polygon(s) are too thin to place a hole seed in; they are meshed, give Hole "
      "Seeds for them.";
  }
}

//------------------------------------------------------------------------------
void vtkGDRConversion::ToPolyData(const gdr::TriMesh& mesh, double z, vtkPolyData* output)
{
  output->Initialize();
  const vtkIdType npoints = static_cast<vtkIdType>(mesh.points.size());

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(npoints);
  for (vtkIdType i = 0; i < npoints; ++i)
  {
    points->SetPoint(i, mesh.points[i].x, mesh.points[i].y, z);
  }

  vtkSmartPointer<vtkCellArray> triangles = FixedSizeCells(mesh.triangles, { 0, 1, 2 });

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
    // Not the active scalars: ParaView colours by active point scalars before cell ones,
    // and the mesh is to be coloured by MinAngle (AddTriangleQuality).
    output->GetPointData()->AddArray(type);
  }
  AddTriangleFileData(mesh, output);
}

//------------------------------------------------------------------------------
void vtkGDRConversion::ToSubsegments(
  const gdr::TriMesh& mesh, vtkPolyData* triangles, vtkPolyData* output)
{
  output->Initialize();
  output->SetPoints(triangles->GetPoints());
  output->SetLines(FixedSizeCells(mesh.subsegments, { 0, 1 }));
  output->GetPointData()->PassData(triangles->GetPointData());
  if (mesh.subsegment_markers.size() == mesh.subsegments.size())
  {
    AddArray<vtkIntArray>(output->GetCellData(), "BoundaryMarker", mesh.subsegment_markers);
    output->GetCellData()->SetActiveScalars("BoundaryMarker");
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
  std::vector<long long> counts(upper, 0);
  if (values)
  {
    for (vtkIdType i = 0; i < values->GetNumberOfTuples(); ++i)
    {
      const double v = values->GetComponent(i, 0);
      if (!std::isfinite(v))
      {
        continue;
      }
      ++counts[std::min(upper - 1, std::max(0, static_cast<int>(std::floor(v))))];
    }
  }
  vtkGDRConversion::HistogramTable(counts, "bin_values", table);
}

//------------------------------------------------------------------------------
void vtkGDRConversion::HistogramTable(
  const std::vector<long long>& counts, const char* countName, vtkTable* table)
{
  table->Initialize();
  const vtkIdType nbins = static_cast<vtkIdType>(counts.size());
  vtkNew<vtkDoubleArray> centers;
  centers->SetName("bin_extents");
  centers->SetNumberOfValues(nbins);
  for (vtkIdType i = 0; i < nbins; ++i)
  {
    centers->SetValue(i, i + 0.5);
  }
  table->AddColumn(centers);
  vtkGDRConversion::AddHistogramColumn(counts, countName, table);
}

//------------------------------------------------------------------------------
void vtkGDRConversion::AddHistogramColumn(
  const std::vector<long long>& counts, const char* countName, vtkTable* table)
{
  const vtkIdType nbins = table->GetNumberOfRows();
  if (static_cast<vtkIdType>(counts.size()) > nbins)
  {
    throw gdr::Error(gdr::Status::InternalError,
      std::string("histogram ") + countName + " has more bins than its table");
  }
  vtkNew<vtkIdTypeArray> values;
  values->SetName(countName);
  values->SetNumberOfValues(nbins);
  values->Fill(0);
  for (std::size_t i = 0; i < counts.size(); ++i)
  {
    values->SetValue(static_cast<vtkIdType>(i), static_cast<vtkIdType>(counts[i]));
  }
  table->AddColumn(values);
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

// The statistics every mesher reports, under the same names.
template <typename Stats>
void AddRunStats(const Stats& stats, vtkFieldData* fd)
{
  AddValue<vtkStringArray>(fd, "Backend", gdr::to_string(stats.backend_used));
  AddValue<vtkStringArray>(fd, "DeviceName", stats.device_name);
  AddValue<vtkIntArray>(fd, "Iterations", stats.iterations);
  AddValue<vtkIdTypeArray>(fd, "InputPoints", static_cast<vtkIdType>(stats.input_points));
  AddValue<vtkIdTypeArray>(fd, "SteinerPoints", static_cast<vtkIdType>(stats.steiner_points));
  AddValue<vtkIdTypeArray>(fd, "SteinerCap", static_cast<vtkIdType>(stats.steiner_cap));
  AddValue<vtkIntArray>(fd, "SteinerCapReached", stats.steiner_cap_reached ? 1 : 0);
  AddValue<vtkIntArray>(fd, "Stalled", stats.stalled ? 1 : 0);
  AddValue<vtkDoubleArray>(fd, "InputSeconds", stats.input_seconds);
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

// Sliver removal (SliverAngle) of the two 3D meshers: the tetrahedra beyond the angle before
// and after smoothing.
template <typename Stats>
void AddSliverStats(const Stats& stats, vtkFieldData* fd)
{
  AddValue<vtkIdTypeArray>(fd, "SliversBefore", static_cast<vtkIdType>(stats.slivers_before));
  AddValue<vtkIdTypeArray>(fd, "SliversAfter", static_cast<vtkIdType>(stats.slivers_after));
}

// And those of the two constrained meshers, which keep their input segments and start from
// a constrained Delaunay triangulation.
template <typename Stats>
void AddConstrainedRunStats(const Stats& stats, vtkFieldData* fd)
{
  AddRunStats(stats, fd);
  AddValue<vtkIdTypeArray>(fd, "InputSegments", static_cast<vtkIdType>(stats.input_segments));
  AddValue<vtkIdTypeArray>(
    fd, "DuplicatePointsMerged", static_cast<vtkIdType>(stats.duplicate_points_merged));
  AddValue<vtkDoubleArray>(fd, "CDTSeconds", stats.cdt_seconds);
}
}

void vtkGDRConversion::AddStats(const gdr::Refine2dStats& stats, vtkFieldData* fd)
{
  AddConstrainedRunStats(stats, fd);
  AddValue<vtkIdTypeArray>(fd, "BadTriangles", static_cast<vtkIdType>(stats.bad_triangles));
  AddValue<vtkDoubleArray>(fd, "BadAreaPercent", stats.bad_area_percent);
  AddValue<vtkDoubleArray>(fd, "MinimumAngleReached", stats.min_angle_deg);
}

//------------------------------------------------------------------------------
void vtkGDRConversion::AddStats(const gdr::QualityTetStats& stats, vtkFieldData* fd)
{
  AddConstrainedRunStats(stats, fd);
  AddValue<vtkIdTypeArray>(fd, "InputTriangles", static_cast<vtkIdType>(stats.input_triangles));
  AddValue<vtkIdTypeArray>(fd, "InputFacets", static_cast<vtkIdType>(stats.input_facets));
  AddValue<vtkIdTypeArray>(
    fd, "DuplicateTrianglesMerged", static_cast<vtkIdType>(stats.duplicate_triangles_merged));
  AddValue<vtkIdTypeArray>(
    fd, "PresplitPoints", static_cast<vtkIdType>(stats.presplit_points));
  AddValue<vtkIdTypeArray>(
    fd, "CDTSteinerPoints", static_cast<vtkIdType>(stats.cdt_steiner_points));
  AddValue<vtkIdTypeArray>(fd, "InteriorSeeds", static_cast<vtkIdType>(stats.interior_seeds));
  AddValue<vtkIdTypeArray>(fd, "BlockedSegments", static_cast<vtkIdType>(stats.blocked_segments));
  AddValue<vtkIdTypeArray>(fd, "BadTetrahedra", static_cast<vtkIdType>(stats.bad_tets));
  AddValue<vtkIdTypeArray>(
    fd, "ProtectedBadTetrahedra", static_cast<vtkIdType>(stats.protected_bad_tets));
  AddValue<vtkIdTypeArray>(fd, "SliversLeft", static_cast<vtkIdType>(stats.slivers_left));
  AddValue<vtkDoubleArray>(fd, "BadVolumePercent", stats.bad_volume_percent);
  AddValue<vtkDoubleArray>(fd, "MinimumDihedralAngleReached", stats.min_dihedral_deg);
  AddValue<vtkDoubleArray>(fd, "MaximumDihedralAngleReached", stats.max_dihedral_deg);
  AddValue<vtkDoubleArray>(fd, "MaximumRadiusEdgeRatioReached", stats.max_radius_edge);
  AddSliverStats(stats, fd);
  AddValue<vtkIdTypeArray>(fd, "SliverFlips", static_cast<vtkIdType>(stats.sliver_flips));
  AddValue<vtkDoubleArray>(fd, "Volume", stats.volume);
  AddValue<vtkDoubleArray>(fd, "InputVolume", stats.input_volume);
}

//------------------------------------------------------------------------------
void vtkGDRConversion::AddStats(const gdr::RestrictedDelaunayStats& stats, vtkFieldData* fd)
{
  AddRunStats(stats, fd);
  AddValue<vtkIdTypeArray>(fd, "InputTriangles", static_cast<vtkIdType>(stats.input_triangles));
  AddValue<vtkIntArray>(fd, "ClosedInput", stats.closed_input ? 1 : 0);
  AddValue<vtkIntArray>(fd, "VolumeMeshed", stats.volume_meshed ? 1 : 0);
  AddValue<vtkIdTypeArray>(fd, "InitialPoints", static_cast<vtkIdType>(stats.initial_points));
  AddValue<vtkIdTypeArray>(fd, "FeatureEdges", static_cast<vtkIdType>(stats.feature_edges));
  AddValue<vtkIdTypeArray>(fd, "Corners", static_cast<vtkIdType>(stats.corners));
  AddValue<vtkIdTypeArray>(fd, "FeaturePoints", static_cast<vtkIdType>(stats.feature_points));
  AddValue<vtkIdTypeArray>(fd, "FeaturesOffSurface", static_cast<vtkIdType>(stats.features_off_surface));
  AddValue<vtkIdTypeArray>(fd, "FeatureRelabelled", static_cast<vtkIdType>(stats.feature_relabelled));
  AddValue<vtkIdTypeArray>(fd, "BadFacets", static_cast<vtkIdType>(stats.bad_facets));
  AddValue<vtkIdTypeArray>(fd, "BadTetrahedra", static_cast<vtkIdType>(stats.bad_tets));
  AddValue<vtkIdTypeArray>(fd, "FacetsLeftOut", static_cast<vtkIdType>(stats.facets_left_out));
  AddValue<vtkIdTypeArray>(fd, "ManifoldSplits", static_cast<vtkIdType>(stats.manifold_splits));
  AddValue<vtkIdTypeArray>(fd, "NonManifoldFacets", static_cast<vtkIdType>(stats.non_manifold_facets));
  AddValue<vtkIdTypeArray>(fd, "PinchRelabelled", static_cast<vtkIdType>(stats.pinch_relabelled));
  AddValue<vtkDoubleArray>(fd, "FacetAngle", stats.facet_angle);
  AddValue<vtkDoubleArray>(fd, "FacetSize", stats.facet_size);
  AddValue<vtkDoubleArray>(fd, "FacetDistance", stats.facet_distance);
  AddValue<vtkDoubleArray>(fd, "CellRadiusEdgeRatio", stats.cell_radius_edge_ratio);
  AddValue<vtkDoubleArray>(fd, "CellSize", stats.cell_size);
  AddValue<vtkDoubleArray>(fd, "FeatureAngle", stats.feature_angle);
  AddValue<vtkDoubleArray>(fd, "MinimumFacetAngleReached", stats.min_facet_angle_deg);
  AddValue<vtkDoubleArray>(fd, "MaximumFacetSizeReached", stats.max_facet_size);
  AddValue<vtkDoubleArray>(fd, "MaximumFacetDistanceReached", stats.max_facet_distance);
  AddValue<vtkDoubleArray>(fd, "MinimumDihedralAngleReached", stats.min_dihedral_deg);
  AddValue<vtkDoubleArray>(fd, "MaximumDihedralAngleReached", stats.max_dihedral_deg);
  AddValue<vtkDoubleArray>(fd, "MaximumRadiusEdgeRatioReached", stats.max_radius_edge);
  AddSliverStats(stats, fd);
  AddValue<vtkDoubleArray>(fd, "Area", stats.area);
  AddValue<vtkDoubleArray>(fd, "Volume", stats.volume);
  AddValue<vtkDoubleArray>(fd, "InitialSeconds", stats.initial_seconds);
}

//------------------------------------------------------------------------------
namespace
{
// Collects facets into a gdr::Surface over the ids of `points`. With `allPoints`, every point
// is taken in order, so that the engine's messages name the input's own point ids; else
// points are taken on first use.
class SurfaceBuilder
{
public:
  SurfaceBuilder(vtkPoints* points, gdr::Surface& surface, bool allPoints)
    : Points(points)
    , Surface(surface)
    , Index(points->GetNumberOfPoints(), -1)
  {
    for (vtkIdType id = 0; allPoints && id < points->GetNumberOfPoints(); ++id)
    {
      this->Use(id);
    }
  }

  // One facet; a polygon with more than three corners is triangulated by vtkPolygon.
  void AddPolygon(vtkIdType npts, const vtkIdType* ids, int facet)
  {
    if (npts < 3)
    {
      return;
    }
    if (npts == 3)
    {
      this->AddTriangle(ids[0], ids[1], ids[2], facet);
      return;
    }
    this->Polygon->Initialize(static_cast<int>(npts), ids, this->Points);
    if (!this->Polygon->Triangulate(this->Corners) || this->Corners->GetNumberOfIds() == 0)
    {
      throw gdr::Error(gdr::Status::InvalidInput,
        "polygon " + std::to_string(facet) + " (" + std::to_string(npts) +
          " corners) cannot be triangulated: it is degenerate or not planar enough");
    }
    for (vtkIdType k = 0; k + 2 < this->Corners->GetNumberOfIds(); k += 3)
    {
      this->AddTriangle(ids[this->Corners->GetId(k)], ids[this->Corners->GetId(k + 1)],
        ids[this->Corners->GetId(k + 2)], facet);
    }
  }

  void AddTriangle(vtkIdType a, vtkIdType b, vtkIdType c, int facet)
  {
    this->Surface.triangles.push_back({ this->Use(a), this->Use(b), this->Use(c) });
    this->Surface.triangle_facet.push_back(facet);
  }

private:
  int Use(vtkIdType id)
  {
    if (this->Index[id] < 0)
    {
      double p[3];
      this->Points->GetPoint(id, p);
      this->Index[id] = static_cast<int>(this->Surface.points.size());
      this->Surface.points.push_back({ p[0], p[1], p[2] });
    }
    return this->Index[id];
  }

  vtkPoints* Points;
  gdr::Surface& Surface;
  std::vector<int> Index;
  vtkNew<vtkPolygon> Polygon;
  vtkNew<vtkIdList> Corners;
};

const char* const GridPointIds = "vtkGDRGridPointIds";
}

//------------------------------------------------------------------------------
void vtkGDRConversion::ToSurface(vtkPolyData* input, gdr::Surface& surface)
{
  surface = gdr::Surface();
  if (!input || !input->GetPoints() || input->GetNumberOfPoints() == 0)
  {
    return;
  }
  SurfaceBuilder builder(input->GetPoints(), surface, true);
  // A cell array FacetId (the readers' triangulated polygons) groups cells into facets.
  vtkDataArray* facetIds = input->GetCellData()->GetArray("FacetId");
  auto facetOf = [facetIds](vtkIdType cell)
  { return static_cast<int>(facetIds ? std::lround(facetIds->GetComponent(cell, 0)) : cell); };
  // Cell ids of a polydata count vertices, lines, polygons, then strips.
  vtkIdType cellId = input->GetNumberOfVerts() + input->GetNumberOfLines();
  vtkIdType npts;
  const vtkIdType* ids;
  vtkCellArray* polys = input->GetPolys();
  for (polys->InitTraversal(); polys->GetNextCell(npts, ids); ++cellId)
  {
    builder.AddPolygon(npts, ids, facetOf(cellId));
  }
  vtkCellArray* strips = input->GetStrips();
  for (strips->InitTraversal(); strips->GetNextCell(npts, ids); ++cellId)
  {
    for (vtkIdType i = 0; i + 2 < npts; ++i)
    {
      // Every other triangle of a strip turns the other way round.
      const vtkIdType a = ids[i % 2 ? i + 1 : i];
      const vtkIdType b = ids[i % 2 ? i : i + 1];
      builder.AddTriangle(a, b, ids[i + 2], facetOf(cellId));
    }
  }
  AddFileSeeds(input, surface);
}

//------------------------------------------------------------------------------
void vtkGDRConversion::ToSurface(
  vtkUnstructuredGrid* input, gdr::Surface& surface, std::string& warning)
{
  surface = gdr::Surface();
  warning.clear();
  if (!input || !input->GetPoints() || input->GetNumberOfCells() == 0)
  {
    return;
  }
  vtkDataArray* region = input->GetCellData()->GetArray("Region");
  if (region &&
    (region->GetDataType() == VTK_FLOAT || region->GetDataType() == VTK_DOUBLE ||
      region->GetNumberOfComponents() != 1))
  {
    warning = "The cell array Region is not a single integer per cell: it is ignored.";
    region = nullptr;
  }
  if (!region)
  {
    vtkNew<vtkDataSetSurfaceFilter> boundary;
    boundary->SetInputData(input);
    boundary->Update();
    vtkGDRConversion::ToSurface(boundary->GetOutput(), surface);
    return;
  }

  // Each Region value is extracted and its faces taken with the grid's point ids, so that
  // the faces of all regions share one numbering and a face between two regions is taken
  // once.
  std::set<long long> values;
  for (vtkIdType c = 0; c < region->GetNumberOfTuples(); ++c)
  {
    values.insert(static_cast<long long>(region->GetComponent(c, 0)));
  }
  vtkNew<vtkIdFilter> gridIds;
  gridIds->SetInputData(input);
  gridIds->PointIdsOn();
  gridIds->CellIdsOff();
  gridIds->FieldDataOff();
  gridIds->SetPointIdsArrayName(GridPointIds);

  SurfaceBuilder builder(input->GetPoints(), surface, false);
  std::set<std::vector<vtkIdType>> taken;
  int facet = 0;
  for (const long long value : values)
  {
    vtkNew<vtkThreshold> part;
    part->SetInputConnection(gridIds->GetOutputPort());
    part->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_CELLS, "Region");
    part->SetThresholdFunction(vtkThreshold::THRESHOLD_BETWEEN);
    part->SetLowerThreshold(static_cast<double>(value));
    part->SetUpperThreshold(static_cast<double>(value));

    vtkNew<vtkDataSetSurfaceFilter> faces;
    faces->SetInputConnection(part->GetOutputPort());
    faces->Update();
    vtkPolyData* pd = faces->GetOutput();
    vtkDataArray* ids = pd->GetPointData()->GetArray(GridPointIds);
    vtkIdType npts;
    const vtkIdType* local;
    std::vector<vtkIdType> corners;
    vtkCellArray* polys = pd->GetPolys();
    for (polys->InitTraversal(); ids && polys->GetNextCell(npts, local); ++facet)
    {
      corners.resize(npts);
      for (vtkIdType i = 0; i < npts; ++i)
      {
        corners[i] = static_cast<vtkIdType>(ids->GetComponent(local[i], 0));
      }
      std::vector<vtkIdType> key = corners;
      std::sort(key.begin(), key.end());
      if (taken.insert(std::move(key)).second)
      {
        builder.AddPolygon(npts, corners.data(), facet);
      }
    }

    // One seed per connected part: the center of one of its cells lies inside it.
    vtkNew<vtkConnectivityFilter> parts;
    parts->SetInputConnection(part->GetOutputPort());
    parts->SetExtractionModeToAllRegions();
    parts->ColorRegionsOn();
    vtkNew<vtkCellCenters> centers;
    centers->SetInputConnection(parts->GetOutputPort());
    centers->Update();
    vtkDataSet* seeds = centers->GetOutput();
    vtkDataArray* partIds = seeds->GetPointData()->GetArray("RegionId");
    std::vector<char> seeded(parts->GetNumberOfExtractedRegions(), 0);
    for (vtkIdType i = 0; partIds && i < seeds->GetNumberOfPoints(); ++i)
    {
      const vtkIdType id = static_cast<vtkIdType>(partIds->GetComponent(i, 0));
      if (id < 0 || id >= static_cast<vtkIdType>(seeded.size()) || seeded[id])
      {
        continue;
      }
      seeded[id] = 1;
      double p[3];
      seeds->GetPoint(i, p);
      gdr::RegionSeed seed;
      seed.point = { p[0], p[1], p[2] };
      seed.attribute = static_cast<int>(value);
      surface.regions.push_back(seed);
    }
  }
}

//------------------------------------------------------------------------------
void vtkGDRConversion::AddSeeds(vtkDataSet* seeds, gdr::Surface& surface)
{
  if (!seeds)
  {
    return;
  }
  vtkDataArray* attribute = seeds->GetPointData()->GetArray("RegionAttribute");
  vtkDataArray* maxVolume = seeds->GetPointData()->GetArray("RegionMaximumVolume");
  for (vtkIdType id = 0; id < seeds->GetNumberOfPoints(); ++id)
  {
    double p[3];
    seeds->GetPoint(id, p);
    if (!attribute)
    {
      surface.holes.push_back({ p[0], p[1], p[2] });
      continue;
    }
    gdr::RegionSeed seed;
    seed.point = { p[0], p[1], p[2] };
    seed.attribute = static_cast<int>(std::lround(attribute->GetComponent(id, 0)));
    if (maxVolume)
    {
      seed.max_volume = maxVolume->GetComponent(id, 0); // checked (finite, >= 0) by the core
    }
    surface.regions.push_back(seed);
  }
}

//------------------------------------------------------------------------------
namespace
{
// The points, tetrahedra, PointType and quality arrays of a 3D mesher's result (the
// constrained and the restricted mesher measure their tetrahedra alike).
template <typename Result>
void TetQualityGrid(const Result& result, vtkUnstructuredGrid* output)
{
  output->Initialize();
  const gdr::TetMesh& mesh = result.mesh;
  const vtkIdType npoints = static_cast<vtkIdType>(mesh.points.size());

  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(npoints);
  for (vtkIdType i = 0; i < npoints; ++i)
  {
    points->SetPoint(i, mesh.points[i].x, mesh.points[i].y, mesh.points[i].z);
  }

  // VTK's tetrahedra have (p1 - p0) x (p2 - p0) pointing towards p3, the opposite of the
  // core's orientation (orient3d > 0, gdr/validate.h): two corners are swapped.
  vtkSmartPointer<vtkCellArray> tets = FixedSizeCells(mesh.tets, { 1, 0, 2, 3 });
  output->SetPoints(points);
  output->SetCells(VTK_TETRA, tets);

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
  }

  vtkCellData* cd = output->GetCellData();
  AddArray<vtkFloatArray>(cd, "RadiusEdgeRatio", result.radius_edge);
  AddArray<vtkFloatArray>(cd, "MinDihedralAngle", result.min_dihedral);
  AddArray<vtkFloatArray>(cd, "MaxDihedralAngle", result.max_dihedral);
  AddArray<vtkDoubleArray>(cd, "Volume", result.volume);
  AddArray<vtkUnsignedCharArray>(cd, "IsBad", result.is_bad);
  cd->SetActiveScalars("MinDihedralAngle");
}
}

void vtkGDRConversion::ToUnstructuredGrid(
  const gdr::QualityTetResult& result, vtkUnstructuredGrid* output)
{
  TetQualityGrid(result, output);
  const gdr::TetMesh& mesh = result.mesh;
  AddArray<vtkIntArray>(output->GetCellData(), "Region",
    mesh.tet_region.empty() ? std::vector<int>(mesh.tets.size(), 0) : mesh.tet_region);
}

//------------------------------------------------------------------------------
void vtkGDRConversion::ToRestrictedMesh(
  const gdr::RestrictedDelaunayResult& result, vtkUnstructuredGrid* tets, vtkPolyData* surface)
{
  TetQualityGrid(result, tets);
  surface->Initialize();
  surface->SetPoints(tets->GetPoints());
  surface->SetPolys(FixedSizeCells(result.mesh.subfaces, { 0, 1, 2 }));
  surface->GetPointData()->PassData(tets->GetPointData());
  vtkCellData* cd = surface->GetCellData();
  AddArray<vtkFloatArray>(cd, "MinAngle", result.facet_min_angle);
  AddArray<vtkDoubleArray>(cd, "Size", result.facet_size);
  AddArray<vtkDoubleArray>(cd, "Distance", result.facet_distance);
  AddArray<vtkUnsignedCharArray>(cd, "IsBad", result.facet_is_bad);
  cd->SetActiveScalars("MinAngle");
}

//------------------------------------------------------------------------------
void vtkGDRConversion::ToSubfaces(
  const gdr::TetMesh& mesh, vtkUnstructuredGrid* tets, vtkPolyData* output)
{
  output->Initialize();
  vtkSmartPointer<vtkCellArray> triangles = FixedSizeCells(mesh.subfaces, { 0, 1, 2 });
  output->SetPoints(tets->GetPoints());
  output->SetPolys(triangles);
  output->GetPointData()->PassData(tets->GetPointData());
  AddArray<vtkIntArray>(output->GetCellData(), "FacetId",
    mesh.subface_facet.size() == mesh.subfaces.size() ? mesh.subface_facet
                                                      : std::vector<int>(mesh.subfaces.size(), -1));
  output->GetCellData()->SetActiveScalars("FacetId");
}

//------------------------------------------------------------------------------
// Meshing inputs and meshes read from files (the readers).
namespace
{
template <typename PointT, class A>
vtkSmartPointer<vtkPoints> ToPoints(const std::vector<PointT, A>& in)
{
  vtkSmartPointer<vtkPoints> points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(in.size()));
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(in.size()); ++i)
  {
    if constexpr (std::is_same_v<PointT, gdr::Point2>)
    {
      points->SetPoint(i, in[i].x, in[i].y, 0.0);
    }
    else
    {
      points->SetPoint(i, in[i].x, in[i].y, in[i].z);
    }
  }
  return points;
}

// The seeds as a 3-component field data array (empty seeds: no array).
template <typename PointT>
void AddSeedArray(const char* name, const std::vector<PointT>& seeds, vtkFieldData* fd)
{
  if (seeds.empty())
  {
    return;
  }
  vtkNew<vtkDoubleArray> array;
  array->SetName(name);
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(static_cast<vtkIdType>(seeds.size()));
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(seeds.size()); ++i)
  {
    if constexpr (std::is_same_v<PointT, gdr::Point2>)
    {
      array->SetTuple3(i, seeds[i].x, seeds[i].y, 0.0);
    }
    else
    {
      array->SetTuple3(i, seeds[i].x, seeds[i].y, seeds[i].z);
    }
  }
  fd->AddArray(array);
}

// Vertex cells for the points that no other cell uses, so that they are drawn and kept.
void AddIsolatedPointVertices(vtkIdType npoints, const std::vector<char>& used, vtkPolyData* pd)
{
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < npoints; ++i)
  {
    if (!used[i])
    {
      verts->InsertNextCell(1, &i);
    }
  }
  if (verts->GetNumberOfCells() > 0)
  {
    pd->SetVerts(verts);
  }
}
}

void vtkGDRConversion::FromPslg(const gdr::Pslg& pslg, vtkPolyData* output)
{
  output->Initialize();
  const vtkIdType npoints = static_cast<vtkIdType>(pslg.points.size());
  output->SetPoints(ToPoints(pslg.points));
  std::vector<char> used(npoints, 0);
  for (const auto& s : pslg.segments)
  {
    used[s[0]] = used[s[1]] = 1;
  }
  AddIsolatedPointVertices(npoints, used, output);
  output->SetLines(FixedSizeCells(pslg.segments, { 0, 1 }));
  if (static_cast<vtkIdType>(pslg.point_markers.size()) == npoints)
  {
    AddArray<vtkIntArray>(output->GetPointData(), "BoundaryMarker", pslg.point_markers);
  }
  const int na = pslg.point_attribute_count;
  if (na > 0 && pslg.point_attributes.size() == pslg.points.size() * na)
  {
    AddArray<vtkDoubleArray>(output->GetPointData(), "PointAttributes", pslg.point_attributes, na);
  }
  if (!pslg.segments.empty() && pslg.segment_markers.size() == pslg.segments.size())
  {
    // Cell ids count the vertex cells first: they get 0, no marker.
    std::vector<int> markers(static_cast<std::size_t>(output->GetNumberOfVerts()), 0);
    markers.insert(markers.end(), pslg.segment_markers.begin(), pslg.segment_markers.end());
    AddArray<vtkIntArray>(output->GetCellData(), "BoundaryMarker", markers);
  }
  vtkFieldData* fd = output->GetFieldData();
  AddSeedArray("HoleSeeds", pslg.holes, fd);
  if (!pslg.regions.empty())
  {
    std::vector<gdr::Point2> points;
    vtkNew<vtkDoubleArray> attribute;
    vtkNew<vtkDoubleArray> maxArea;
    attribute->SetName("RegionAttribute");
    maxArea->SetName("RegionMaximumArea");
    for (const gdr::RegionSeed2& r : pslg.regions)
    {
      points.push_back(r.point);
      attribute->InsertNextValue(r.attribute);
      maxArea->InsertNextValue(r.max_area);
    }
    AddSeedArray("RegionSeeds", points, fd);
    fd->AddArray(attribute);
    fd->AddArray(maxArea);
  }
}

void vtkGDRConversion::FromSurface(const gdr::Surface& surface, vtkPolyData* output)
{
  output->Initialize();
  const vtkIdType npoints = static_cast<vtkIdType>(surface.points.size());
  output->SetPoints(ToPoints(surface.points));
  std::vector<char> used(npoints, 0);
  for (const auto& t : surface.triangles)
  {
    used[t[0]] = used[t[1]] = used[t[2]] = 1;
  }
  for (const auto& s : surface.segments)
  {
    used[s[0]] = used[s[1]] = 1;
  }
  AddIsolatedPointVertices(npoints, used, output);
  output->SetLines(FixedSizeCells(surface.segments, { 0, 1 }));
  output->SetPolys(FixedSizeCells(surface.triangles, { 0, 1, 2 }));
  if (surface.triangle_facet.size() == surface.triangles.size() && !surface.triangles.empty())
  {
    // Cell ids count vertices and lines first: FacetId is defined on every cell.
    std::vector<int> facet(static_cast<std::size_t>(output->GetNumberOfCells()), -1);
    std::copy(surface.triangle_facet.begin(), surface.triangle_facet.end(),
      facet.end() - static_cast<std::ptrdiff_t>(surface.triangles.size()));
    AddArray<vtkIntArray>(output->GetCellData(), "FacetId", facet);
  }
  vtkFieldData* fd = output->GetFieldData();
  AddSeedArray("HoleSeeds", surface.holes, fd);
  if (!surface.regions.empty())
  {
    std::vector<gdr::Point3> points;
    std::vector<int> attribute;
    std::vector<double> maxVolume;
    for (const gdr::RegionSeed& r : surface.regions)
    {
      points.push_back(r.point);
      attribute.push_back(r.attribute);
      maxVolume.push_back(r.max_volume);
    }
    AddSeedArray("RegionSeeds", points, fd);
    vtkNew<vtkIntArray> a;
    a->SetName("RegionAttribute");
    a->SetNumberOfValues(static_cast<vtkIdType>(attribute.size()));
    std::copy(attribute.begin(), attribute.end(), a->GetPointer(0));
    fd->AddArray(a);
    vtkNew<vtkDoubleArray> v;
    v->SetName("RegionMaximumVolume");
    v->SetNumberOfValues(static_cast<vtkIdType>(maxVolume.size()));
    std::copy(maxVolume.begin(), maxVolume.end(), v->GetPointer(0));
    fd->AddArray(v);
  }
}

void vtkGDRConversion::FromTriMesh(const gdr::TriMesh& mesh, vtkUnstructuredGrid* output)
{
  output->Initialize();
  output->SetPoints(ToPoints(mesh.points));
  output->SetCells(VTK_TRIANGLE, FixedSizeCells(mesh.triangles, { 0, 1, 2 }));
  AddTriangleFileData(mesh, output);
}

void vtkGDRConversion::FromTetMesh(const gdr::TetMesh& mesh, vtkUnstructuredGrid* output)
{
  output->Initialize();
  output->SetPoints(ToPoints(mesh.points));
  // The same corner swap as ToUnstructuredGrid: VTK's orientation is the core's opposite.
  output->SetCells(VTK_TETRA, FixedSizeCells(mesh.tets, { 1, 0, 2, 3 }));
  if (mesh.tet_region.size() == mesh.tets.size() && !mesh.tets.empty())
  {
    AddArray<vtkIntArray>(output->GetCellData(), "Region", mesh.tet_region);
  }
}

void vtkGDRConversion::AddFileSeeds(vtkPolyData* input, gdr::Pslg& pslg)
{
  vtkFieldData* fd = input ? input->GetFieldData() : nullptr;
  if (!fd)
  {
    return;
  }
  vtkDataArray* holes = fd->GetArray("HoleSeeds");
  if (holes && holes->GetNumberOfComponents() >= 2)
  {
    for (vtkIdType i = 0; i < holes->GetNumberOfTuples(); ++i)
    {
      pslg.holes.push_back({ holes->GetComponent(i, 0), holes->GetComponent(i, 1) });
    }
  }
  // Triangle's regions (.poly region list, or gpudelaunay.refine_2d's regions=).
  vtkDataArray* regions = fd->GetArray("RegionSeeds");
  vtkDataArray* attribute = fd->GetArray("RegionAttribute");
  vtkDataArray* maxArea = fd->GetArray("RegionMaximumArea");
  if (!regions || regions->GetNumberOfComponents() < 2)
  {
    return;
  }
  const vtkIdType n = regions->GetNumberOfTuples();
  for (vtkIdType i = 0; i < n; ++i)
  {
    gdr::RegionSeed2 seed;
    seed.point = { regions->GetComponent(i, 0), regions->GetComponent(i, 1) };
    seed.attribute = attribute && attribute->GetNumberOfTuples() == n ? attribute->GetComponent(i, 0) : 0.0;
    seed.max_area = maxArea && maxArea->GetNumberOfTuples() == n ? maxArea->GetComponent(i, 0) : 0.0;
    pslg.regions.push_back(seed);
  }
}

void vtkGDRConversion::AddFileSeeds(vtkDataSet* input, gdr::Surface& surface)
{
  vtkFieldData* fd = input ? input->GetFieldData() : nullptr;
  if (!fd)
  {
    return;
  }
  vtkDataArray* holes = fd->GetArray("HoleSeeds");
  if (holes && holes->GetNumberOfComponents() == 3)
  {
    for (vtkIdType i = 0; i < holes->GetNumberOfTuples(); ++i)
    {
      surface.holes.push_back(
        { holes->GetComponent(i, 0), holes->GetComponent(i, 1), holes->GetComponent(i, 2) });
    }
  }
  vtkDataArray* regions = fd->GetArray("RegionSeeds");
  vtkDataArray* attribute = fd->GetArray("RegionAttribute");
  vtkDataArray* maxVolume = fd->GetArray("RegionMaximumVolume");
  if (!regions || regions->GetNumberOfComponents() != 3 || !attribute ||
    attribute->GetNumberOfTuples() != regions->GetNumberOfTuples())
  {
    return;
  }
  for (vtkIdType i = 0; i < regions->GetNumberOfTuples(); ++i)
  {
    gdr::RegionSeed seed;
    seed.point = { regions->GetComponent(i, 0), regions->GetComponent(i, 1),
      regions->GetComponent(i, 2) };
    seed.attribute = static_cast<int>(std::lround(attribute->GetComponent(i, 0)));
    if (maxVolume && maxVolume->GetNumberOfTuples() == regions->GetNumberOfTuples())
    {
      seed.max_volume = maxVolume->GetComponent(i, 0);
    }
    surface.regions.push_back(seed);
  }
}
