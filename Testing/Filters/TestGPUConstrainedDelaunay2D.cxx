// Filter tests for vtkGPUConstrainedDelaunay2D. Each test is one ctest entry:
//   TestGPUConstrainedDelaunay2D <test name>
// The meshes are converted back to gdr::TriMesh by this file (independently of the
// filter's converter) and checked with the core validator gdr::validate_trimesh.
#include "FilterTestSupport.h"
#include "vtkGPUConstrainedDelaunay2D.h"
#include "vtkTriangleTetGenReader.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkXMLPolyDataReader.h"

#include "gdr/backend.h"
#include "gdr/pslg.h"
#include "gdr/validate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace
{
using gdr_test::EventLog;

vtkSmartPointer<vtkPolyData> ReadPlate()
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(GDR_TEST_PLATE);
  reader->Update();
  return reader->GetOutput();
}

// The PSLG as this test sees the polydata: every point, line/polyline pieces and polygon
// edges as segments.
gdr::Pslg PslgOf(vtkPolyData* pd)
{
  gdr::Pslg pslg;
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pd->GetPoint(i, p);
    pslg.points.push_back({ p[0], p[1] });
  }
  vtkIdType n;
  const vtkIdType* ids;
  for (pd->GetLines()->InitTraversal(); pd->GetLines()->GetNextCell(n, ids);)
  {
    for (vtkIdType i = 0; i + 1 < n; ++i)
    {
      pslg.segments.push_back({ int(ids[i]), int(ids[i + 1]) });
    }
  }
  for (pd->GetPolys()->InitTraversal(); pd->GetPolys()->GetNextCell(n, ids);)
  {
    for (vtkIdType i = 0; i < n; ++i)
    {
      pslg.segments.push_back({ int(ids[i]), int(ids[(i + 1) % n]) });
    }
  }
  return pslg;
}

bool OnSegment(const gdr::Point2& p, const gdr::Point2& a, const gdr::Point2& b)
{
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double len2 = dx * dx + dy * dy;
  const double t = ((p.x - a.x) * dx + (p.y - a.y) * dy) / len2;
  const double cross = (p.x - a.x) * dy - (p.y - a.y) * dx;
  return t >= -1e-12 && t <= 1 + 1e-12 && std::fabs(cross) <= 1e-9 * len2;
}

// Output polydata -> TriMesh, with subsegments recovered as the mesh edges lying on an
// input segment.
gdr::TriMesh TriMeshOf(vtkPolyData* out, const gdr::Pslg& input)
{
  gdr::TriMesh mesh;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    mesh.points.push_back({ p[0], p[1] });
  }
  vtkIdType n;
  const vtkIdType* ids;
  std::set<std::pair<int, int>> edges;
  for (out->GetPolys()->InitTraversal(); out->GetPolys()->GetNextCell(n, ids);)
  {
    CHECK(n == 3);
    if (n != 3)
    {
      continue;
    }
    mesh.triangles.push_back({ int(ids[0]), int(ids[1]), int(ids[2]) });
    for (int k = 0; k < 3; ++k)
    {
      edges.insert(std::minmax(int(ids[k]), int(ids[(k + 1) % 3])));
    }
  }
  if (vtkDataArray* type = out->GetPointData()->GetArray("PointType"))
  {
    for (vtkIdType i = 0; i < type->GetNumberOfTuples(); ++i)
    {
      mesh.point_type.push_back(static_cast<gdr::PointType>(int(type->GetComponent(i, 0))));
    }
  }
  for (const auto& e : edges)
  {
    for (std::size_t s = 0; s < input.segments.size(); ++s)
    {
      const gdr::Point2& a = input.points[input.segments[s][0]];
      const gdr::Point2& b = input.points[input.segments[s][1]];
      if (OnSegment(mesh.points[e.first], a, b) && OnSegment(mesh.points[e.second], a, b))
      {
        mesh.subsegments.push_back({ e.first, e.second });
        mesh.subsegment_source.push_back(int(s));
        break;
      }
    }
  }
  return mesh;
}

double PolygonArea(const std::vector<gdr::Point2>& p)
{
  double a = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
  {
    const gdr::Point2& u = p[i];
    const gdr::Point2& v = p[(i + 1) % p.size()];
    a += u.x * v.y - v.x * u.y;
  }
  return 0.5 * std::fabs(a);
}

double ArraySum(vtkDataArray* a)
{
  double s = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    s += a->GetComponent(i, 0);
  }
  return s;
}

// Checks the arrays of a successful run: sizes, ranges, IsBad, histogram, field data.
void CheckArrays(vtkGPUConstrainedDelaunay2D* filter)
{
  vtkPolyData* out = filter->GetOutput();
  const vtkIdType ncells = out->GetNumberOfCells();
  CHECK(ncells > 0);
  CHECK(out->GetNumberOfPolys() == ncells);
  vtkCellData* cd = out->GetCellData();
  for (const char* name : { "MinAngle", "MaxAngle", "RadiusEdgeRatio", "Area", "IsBad" })
  {
    vtkDataArray* a = cd->GetArray(name);
    CHECK(a != nullptr);
    if (a)
    {
      CHECK(a->GetNumberOfTuples() == ncells);
    }
  }
  vtkDataArray* minAngle = cd->GetArray("MinAngle");
  vtkDataArray* maxAngle = cd->GetArray("MaxAngle");
  vtkDataArray* ratio = cd->GetArray("RadiusEdgeRatio");
  vtkDataArray* area = cd->GetArray("Area");
  vtkDataArray* bad = cd->GetArray("IsBad");
  if (!minAngle || !maxAngle || !ratio || !area || !bad)
  {
    return;
  }
  vtkIdType nbad = 0;
  for (vtkIdType c = 0; c < ncells; ++c)
  {
    const double lo = minAngle->GetComponent(c, 0);
    const double hi = maxAngle->GetComponent(c, 0);
    CHECK(lo > 0 && lo <= 60 + 1e-9);
    CHECK(hi >= 60 - 1e-9 && hi < 180);
    CHECK(ratio->GetComponent(c, 0) >= 1 / std::sqrt(3.0) - 1e-9);
    CHECK(area->GetComponent(c, 0) > 0);
    const bool isBad = bad->GetComponent(c, 0) != 0;
    CHECK(isBad == (lo < filter->GetMinimumAngle()));
    nbad += isBad ? 1 : 0;
  }
  vtkDataArray* type = out->GetPointData()->GetArray("PointType");
  CHECK(type != nullptr);
  if (type)
  {
    CHECK(type->GetNumberOfTuples() == out->GetNumberOfPoints());
    double range[2];
    type->GetRange(range);
    CHECK(range[0] >= 0 && range[1] <= 2);
  }

  vtkTable* histogram = vtkTable::SafeDownCast(filter->GetOutputDataObject(1));
  CHECK(histogram != nullptr);
  if (histogram)
  {
    CHECK(histogram->GetNumberOfRows() == 60);
    vtkDataArray* centers = vtkDataArray::SafeDownCast(histogram->GetColumnByName("bin_extents"));
    vtkDataArray* counts = vtkDataArray::SafeDownCast(histogram->GetColumnByName("bin_values"));
    CHECK(centers && counts);
    if (centers && counts)
    {
      CHECK(centers->GetComponent(0, 0) == 0.5 && centers->GetComponent(59, 0) == 59.5);
      CHECK(ArraySum(counts) == double(ncells));
    }
  }

  vtkFieldData* fd = out->GetFieldData();
  auto* backend = vtkStringArray::SafeDownCast(fd->GetAbstractArray("Backend"));
  CHECK(backend && backend->GetNumberOfValues() == 1);
  if (backend && !gdr::gpu_available())
  {
    CHECK(backend->GetValue(0) == "cpu");
  }
  for (const char* name : { "Iterations", "SteinerPoints", "BadTriangles", "BadAreaPercent",
         "TotalSeconds", "MinimumAngleReached", "PhaseSeconds" })
  {
    CHECK(fd->GetArray(name) != nullptr);
  }
  auto* phases = vtkStringArray::SafeDownCast(fd->GetAbstractArray("PhaseNames"));
  CHECK(phases && fd->GetArray("PhaseSeconds") &&
    phases->GetNumberOfValues() == fd->GetArray("PhaseSeconds")->GetNumberOfTuples());
  if (vtkDataArray* badTriangles = fd->GetArray("BadTriangles"))
  {
    CHECK(badTriangles->GetComponent(0, 0) == double(nbad));
  }
  if (vtkDataArray* steiner = fd->GetArray("SteinerPoints"))
  {
    CHECK(out->GetNumberOfPoints() >= steiner->GetComponent(0, 0));
  }
}

void Validate(vtkPolyData* out, const gdr::Pslg& input, double minAngle, bool expectQuality)
{
  const gdr::TriMesh mesh = TriMeshOf(out, input);
  gdr::ValidateOptions options;
  options.min_angle_deg = minAngle;
  const gdr::ValidationReport report = gdr::validate_trimesh(mesh, &input, options);
  if (!report.valid)
  {
    std::cerr << report.summary() << std::endl;
  }
  CHECK(report.valid);
  CHECK(report.missing_points == 0 && report.missing_segments == 0);
  if (expectQuality)
  {
    CHECK(report.quality.bad_elements == 0);
  }
}

//------------------------------------------------------------------------------
void TestPlate()
{
  vtkSmartPointer<vtkPolyData> plate = ReadPlate();
  CHECK(plate->GetNumberOfPoints() == 29);
  vtkNew<vtkPoints> seedPoints;
  seedPoints->InsertNextPoint(2.0, 3.0, 0.0);
  vtkNew<vtkPolyData> seeds;
  seeds->SetPoints(seedPoints);

  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(plate);
  filter->SetHoleSeedsData(seeds);
  filter->SetBackendToCPU();
  filter->SetMinimumAngle(25);
  filter->RemoveExteriorOn();
  int progressEvents = 0;
  vtkNew<vtkCallbackCommand> countProgress;
  countProgress->SetClientData(&progressEvents);
  countProgress->SetCallback(
    [](vtkObject*, unsigned long, void* client, void*) { ++*static_cast<int*>(client); });
  filter->AddObserver(vtkCommand::ProgressEvent, countProgress);
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(progressEvents >= 2); // the engine's iterations and the final 1.0
  CheckArrays(filter);
  Validate(filter->GetOutput(), PslgOf(plate), 25, true);

  // The mesh covers exactly the plate minus the hole (boundary does not drift).
  const gdr::Pslg input = PslgOf(plate);
  std::vector<gdr::Point2> outer(input.points.begin(), input.points.begin() + 20);
  std::vector<gdr::Point2> hole(input.points.begin() + 20, input.points.begin() + 24);
  const double expected = PolygonArea(outer) - PolygonArea(hole);
  const double area = ArraySum(filter->GetOutput()->GetCellData()->GetArray("Area"));
  CHECK(std::fabs(area - expected) <= 1e-9 * expected);

  // All input points are in the output and are typed as input points.
  vtkDataArray* type = filter->GetOutput()->GetPointData()->GetArray("PointType");
  vtkIdType inputTyped = 0;
  for (vtkIdType i = 0; type && i < type->GetNumberOfTuples(); ++i)
  {
    inputTyped += type->GetComponent(i, 0) == 0 ? 1 : 0;
  }
  CHECK(inputTyped == plate->GetNumberOfPoints());
}

// Holes by polygon orientation, as vtkDelaunay2D: a clockwise square inside a
// counter-clockwise one is a hole, a counter-clockwise island inside the hole is meshed
// again; without a counter-clockwise polygon, orientation means nothing.
void TestPolygonOrientation()
{
  const double outer[4][2] = { { 0, 0 }, { 10, 0 }, { 10, 10 }, { 0, 10 } };
  const double hole[4][2] = { { 3, 3 }, { 3, 7 }, { 7, 7 }, { 7, 3 } };     // clockwise
  const double island[4][2] = { { 4, 4 }, { 6, 4 }, { 6, 6 }, { 4, 6 } };   // counter-clockwise
  auto mesh = [](const std::vector<std::vector<std::array<double, 2>>>& polygons) {
    vtkNew<vtkPoints> points;
    vtkNew<vtkCellArray> polys;
    for (const auto& polygon : polygons)
    {
      std::vector<vtkIdType> ids;
      for (const auto& p : polygon)
      {
        ids.push_back(points->InsertNextPoint(p[0], p[1], 0));
      }
      polys->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    }
    vtkNew<vtkPolyData> pd;
    pd->SetPoints(points);
    pd->SetPolys(polys);
    vtkNew<vtkGPUConstrainedDelaunay2D> filter;
    EventLog log;
    log.Watch(filter);
    filter->SetInputData(pd);
    filter->SetBackendToCPU();
    filter->SetMinimumAngle(20);
    filter->Update();
    CHECK(log.Errors.empty());
    Validate(filter->GetOutput(), PslgOf(pd), 20, true);
    return ArraySum(filter->GetOutput()->GetCellData()->GetArray("Area"));
  };
  auto ring = [](const double (*p)[2], bool reversed) {
    std::vector<std::array<double, 2>> r;
    for (int i = 0; i < 4; ++i)
    {
      const int k = reversed ? 3 - i : i;
      r.push_back({ p[k][0], p[k][1] });
    }
    return r;
  };
  const double withHole = mesh({ ring(outer, false), ring(hole, false), ring(island, false) });
  CHECK(std::fabs(withHole - (100 - 16 + 4)) < 1e-9);
  const double noHole = mesh({ ring(outer, false), ring(hole, true), ring(island, false) });
  CHECK(std::fabs(noHole - 100) < 1e-9);
  const double allClockwise = mesh({ ring(outer, true), ring(hole, false) });
  CHECK(std::fabs(allClockwise - 100) < 1e-9);
}

void TestLinesAndPoints()
{
  // Open polylines plus free points (vertex cells), meshed over their convex hull.
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkCellArray> verts;
  const vtkIdType a = points->InsertNextPoint(0, 0, 1);
  const vtkIdType b = points->InsertNextPoint(4, 1, 1);
  const vtkIdType c = points->InsertNextPoint(8, 0, 1);
  const vtkIdType d = points->InsertNextPoint(4, 5, 1);
  const vtkIdType e = points->InsertNextPoint(2, 3, 1);
  const vtkIdType line1[3] = { a, b, c };
  lines->InsertNextCell(3, line1);
  const vtkIdType line2[2] = { b, d };
  lines->InsertNextCell(2, line2);
  verts->InsertNextCell(1, &e);
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  pd->SetLines(lines);
  pd->SetVerts(verts);

  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  filter->SetInputData(pd);
  filter->SetBackendToCPU();
  filter->Update();
  CheckArrays(filter);
  // The segment (0,0)-(4,1) meets the hull edge at 14 degrees: triangles there may stay bad.
  Validate(filter->GetOutput(), PslgOf(pd), 20, false);
  double bounds[6];
  filter->GetOutput()->GetBounds(bounds);
  CHECK(bounds[4] == 1 && bounds[5] == 1); // stays in the input's plane

  // Points only (no cells at all): a quality mesh of the points' convex hull.
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  filter->SetInputData(cloud);
  filter->SetModeToRuppert(); // the default is Chew
  filter->Update();
  CheckArrays(filter);
  gdr::Pslg cloudPslg = PslgOf(cloud);
  Validate(filter->GetOutput(), cloudPslg, 20, true);
}

void TestSizeBounds()
{
  vtkSmartPointer<vtkPolyData> plate = ReadPlate();
  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  filter->SetInputData(plate);
  filter->SetBackendToCPU();
  filter->RemoveExteriorOn();
  filter->SetMaximumArea(0.05);
  filter->Update();
  CheckArrays(filter);
  vtkDataArray* area = filter->GetOutput()->GetCellData()->GetArray("Area");
  CHECK(area && area->GetRange()[1] <= 0.05 * (1 + 1e-9));
  const vtkIdType fine = filter->GetOutput()->GetNumberOfCells();

  // A Steiner point cap stops refinement cleanly.
  filter->SetMaximumArea(0);
  filter->SetMaximumSteinerPoints(5);
  filter->Update();
  CHECK(filter->GetOutput()->GetNumberOfCells() > 0);
  CHECK(filter->GetOutput()->GetNumberOfCells() < fine);
  vtkDataArray* steiner = filter->GetOutput()->GetFieldData()->GetArray("SteinerPoints");
  CHECK(steiner && steiner->GetComponent(0, 0) <= 5);
}

// Bounds out of range are refused with the CLI's message, not clamped silently; the
// output is empty and the error code tells a script that the run failed.
void TestOutOfRange()
{
  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  CHECK(filter->GetMinimumAngle() == 20);
  CHECK(filter->GetMaximumSteinerPoints() == -1);
  // Triangle's rules by default: the lens and off-centres.
  CHECK(filter->GetMode() == vtkGPUConstrainedDelaunay2D::CHEW && filter->GetOffCenters());
  CHECK(filter->GetBackend() == vtkGPUConstrainedDelaunay2D::AUTO);
  filter->SetBackend(9);
  CHECK(filter->GetBackend() == vtkGPUConstrainedDelaunay2D::CPU);

  EventLog log;
  log.Watch(filter);
  filter->SetInputData(ReadPlate());
  filter->SetMinimumAngle(40);
  CHECK(filter->GetMinimumAngle() == 40);
  filter->Update();
  CHECK(log.ErrorContains("InvalidInput: minimum angle 40"));
  CHECK(log.ErrorContains("out of range [0, 34]"));
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  CHECK(filter->GetErrorCode() != 0);

  const std::pair<std::function<void()>, const char*> cases[] = {
    { [&] { filter->SetMaximumArea(-1); }, "maximum area" },
    { [&] { filter->SetMaximumEdgeLength(-1); }, "maximum edge length" },
    { [&] { filter->SetMaximumSteinerPoints(-7); }, "maximum Steiner points" },
  };
  for (const auto& c : cases)
  {
    filter->SetMinimumAngle(20);
    filter->SetMaximumArea(0);
    filter->SetMaximumEdgeLength(0);
    filter->SetMaximumSteinerPoints(-1);
    c.first();
    log.Clear();
    filter->Update();
    CHECK(log.ErrorContains(c.second));
    CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  }

  // A good run afterwards clears the error code.
  filter->SetMaximumSteinerPoints(-1);
  log.Clear();
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(filter->GetErrorCode() == 0);
  CHECK(filter->GetOutput()->GetNumberOfCells() > 0);
}

// OffCenters (the default) changes where points go; CDTOnly inserts none.
void TestOffCentersAndCDTOnly()
{
  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  filter->SetInputData(ReadPlate());
  filter->SetBackendToCPU();
  filter->RemoveExteriorOn();
  filter->SetMinimumAngle(33);
  auto steinerPoints = [&]()
  {
    filter->Update();
    vtkDataArray* a = filter->GetOutput()->GetFieldData()->GetArray("SteinerPoints");
    return a ? a->GetComponent(0, 0) : -1.0;
  };
  // The points' coordinates summed: where they go, whatever their number.
  auto where = [&]()
  {
    double sum = 0;
    vtkPoints* pts = filter->GetOutput()->GetPoints();
    for (vtkIdType i = 0; pts && i < pts->GetNumberOfPoints(); ++i)
      sum += pts->GetPoint(i)[0] + 2 * pts->GetPoint(i)[1];
    return sum;
  };
  filter->OffCentersOff();
  const double circumcenters = steinerPoints();
  const double circumcentersAt = where();
  filter->OffCentersOn();
  const double offCenters = steinerPoints();
  const double offCentersAt = where();
  CheckArrays(filter);
  vtkDataArray* minAngle = filter->GetOutput()->GetCellData()->GetArray("MinAngle");
  CHECK(minAngle && minAngle->GetRange()[0] >= 33 - 1e-9);
  // (The property reaches the engine: the points go elsewhere. On this plate of 29 points the
  // counts come out alike or differ either way with the order of insertion; on maps
  // off-centres need 10-55% fewer.)
  CHECK(offCenters > 0 && circumcenters > 0 && offCentersAt != circumcentersAt);
  filter->OffCentersOff();
  filter->CDTOnlyOn();
  CHECK(steinerPoints() == 0);
  CHECK(filter->GetOutput()->GetNumberOfPoints() == ReadPlate()->GetNumberOfPoints());
}

void TestEmptyInput()
{
  vtkNew<vtkPolyData> empty;
  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(empty);
  filter->SetBackendToCPU();
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(filter->GetOutput()->GetNumberOfPoints() == 0);
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
}

void TestCrossingLines()
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 0);
  points->InsertNextPoint(2, 2, 0);
  points->InsertNextPoint(0, 2, 0);
  points->InsertNextPoint(2, 0, 0);
  vtkNew<vtkCellArray> lines;
  const vtkIdType l1[2] = { 0, 1 };
  const vtkIdType l2[2] = { 2, 3 };
  lines->InsertNextCell(2, l1);
  lines->InsertNextCell(2, l2);
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  pd->SetLines(lines);

  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(pd);
  filter->SetBackendToCPU();
  // By default the crossing lines are split, with a warning that counts them.
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(log.WarningContains("split 2 segment(s) into 4 pieces"));
  CHECK(filter->GetOutput()->GetNumberOfCells() > 0);
  // StrictInput refuses them.
  log.Clear();
  filter->StrictInputOn();
  filter->Update();
  CHECK(!log.Errors.empty());
  CHECK(log.ErrorContains("SelfIntersectingInput"));
  for (const std::string& e : log.Errors)
  {
    std::cout << "reported: " << e << std::endl;
  }
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  CHECK(filter->GetOutput()->GetNumberOfPoints() == 0);

}

// Triangle's boundary markers and point attributes, from arrays of any polydata: a 4 x 4
// square of four lines marked 1 to 4 (corners marked 10, 20, 30, 40) and a free point
// marked 7, with the attributes 2x + 3y + 1 (linear: reproduced exactly) and x^2.
void TestMarkersAndAttributes()
{
  const double corners[4][2] = { { 0, 0 }, { 4, 0 }, { 4, 4 }, { 0, 4 } };
  vtkNew<vtkPoints> points;
  vtkNew<vtkIntArray> pointMarkers;
  pointMarkers->SetName("BoundaryMarker");
  vtkNew<vtkDoubleArray> attributes;
  attributes->SetName("PointAttributes");
  attributes->SetNumberOfComponents(2);
  auto f = [](double x, double y) { return 2 * x + 3 * y + 1; };
  auto add = [&](double x, double y, int marker)
  {
    pointMarkers->InsertNextValue(marker);
    attributes->InsertNextTuple2(f(x, y), x * x);
    return points->InsertNextPoint(x, y, 0);
  };
  for (int i = 0; i < 4; ++i)
  {
    add(corners[i][0], corners[i][1], 10 * (i + 1));
  }
  const vtkIdType inner = add(1, 1, 7);
  vtkNew<vtkCellArray> verts;
  verts->InsertNextCell(1, &inner);
  vtkNew<vtkCellArray> lines;
  vtkNew<vtkIntArray> segmentMarkers; // on every cell: the vertex first (0), then the lines
  segmentMarkers->SetName("BoundaryMarker");
  segmentMarkers->InsertNextValue(0);
  for (vtkIdType i = 0; i < 4; ++i)
  {
    const vtkIdType line[2] = { i, (i + 1) % 4 };
    lines->InsertNextCell(2, line);
    segmentMarkers->InsertNextValue(static_cast<int>(i + 1));
  }
  vtkNew<vtkPolyData> pd;
  pd->SetPoints(points);
  pd->SetVerts(verts);
  pd->SetLines(lines);
  pd->GetPointData()->AddArray(pointMarkers);
  pd->GetPointData()->AddArray(attributes);
  pd->GetCellData()->AddArray(segmentMarkers);

  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(pd);
  filter->SetBackendToCPU();
  filter->SetMinimumAngle(25);
  filter->SetMaximumArea(0.1);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckArrays(filter);
  Validate(filter->GetOutput(), PslgOf(pd), 25, true);

  // The segment (0-based) a point lies on, between its ends, else -1.
  auto segmentOf = [&](const double p[3])
  {
    for (int s = 0; s < 4; ++s)
    {
      const double* a = corners[s];
      const double* b = corners[(s + 1) % 4];
      const bool end = (p[0] == a[0] && p[1] == a[1]) || (p[0] == b[0] && p[1] == b[1]);
      if (!end && OnSegment({ p[0], p[1] }, { a[0], a[1] }, { b[0], b[1] }))
      {
        return s;
      }
    }
    return -1;
  };
  vtkPolyData* out = filter->GetOutput();
  vtkDataArray* marker = out->GetPointData()->GetArray("BoundaryMarker");
  vtkDataArray* attribute = out->GetPointData()->GetArray("PointAttributes");
  vtkDataArray* type = out->GetPointData()->GetArray("PointType");
  CHECK(marker && marker->GetNumberOfTuples() == out->GetNumberOfPoints());
  CHECK(attribute && attribute->GetNumberOfComponents() == 2 &&
    attribute->GetNumberOfTuples() == out->GetNumberOfPoints());
  if (!marker || !attribute || !type)
  {
    return;
  }
  int onSegment[4] = { 0, 0, 0, 0 };
  int free = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    const int m = static_cast<int>(marker->GetComponent(i, 0));
    const int s = segmentOf(p);
    int corner = -1;
    for (int c = 0; c < 4; ++c)
    {
      corner = p[0] == corners[c][0] && p[1] == corners[c][1] ? c : corner;
    }
    // Linear attributes are reproduced (up to rounding) wherever the point is.
    CHECK(std::fabs(attribute->GetComponent(i, 0) - f(p[0], p[1])) <= 1e-12 * 21);
    if (corner >= 0)
    {
      CHECK(m == 10 * (corner + 1)); // input points keep their markers
    }
    else if (p[0] == 1 && p[1] == 1)
    {
      CHECK(m == 7);
    }
    else if (s >= 0)
    {
      ++onSegment[s];
      CHECK(m == s + 1); // a point on a subsegment takes the segment's marker
      CHECK(type->GetComponent(i, 0) == 1);
      // Along the segment the attributes are interpolated between its ends' values.
      const double* a = corners[s];
      const double* b = corners[(s + 1) % 4];
      const double lo = std::min(a[0] * a[0], b[0] * b[0]);
      const double hi = std::max(a[0] * a[0], b[0] * b[0]);
      const double x2 = attribute->GetComponent(i, 1);
      CHECK(x2 >= lo - 1e-12 && x2 <= hi + 1e-12);
    }
    else
    {
      ++free;
      CHECK(m == 0); // interior Steiner points
      CHECK(type->GetComponent(i, 0) == 2);
    }
  }
  CHECK(onSegment[0] > 0 && onSegment[1] > 0 && onSegment[2] > 0 && onSegment[3] > 0);
  CHECK(free > 0);

  // Port 2: the subsegments with their segment's marker, covering each segment once.
  vtkPolyData* subsegments = vtkPolyData::SafeDownCast(filter->GetOutputDataObject(2));
  CHECK(subsegments && subsegments->GetNumberOfLines() == subsegments->GetNumberOfCells());
  CHECK(subsegments && subsegments->GetNumberOfPoints() == out->GetNumberOfPoints());
  vtkDataArray* lineMarker =
    subsegments ? subsegments->GetCellData()->GetArray("BoundaryMarker") : nullptr;
  CHECK(lineMarker && lineMarker->GetNumberOfTuples() == subsegments->GetNumberOfCells());
  if (!lineMarker)
  {
    return;
  }
  CHECK(subsegments->GetNumberOfCells() == 4 + onSegment[0] + onSegment[1] + onSegment[2] + onSegment[3]);
  double length[4] = { 0, 0, 0, 0 };
  vtkIdType n;
  const vtkIdType* ids;
  vtkIdType cell = 0;
  for (subsegments->GetLines()->InitTraversal(); subsegments->GetLines()->GetNextCell(n, ids); ++cell)
  {
    CHECK(n == 2);
    double a[3], b[3], mid[3];
    subsegments->GetPoint(ids[0], a);
    subsegments->GetPoint(ids[1], b);
    for (int k = 0; k < 3; ++k)
    {
      mid[k] = 0.5 * (a[k] + b[k]);
    }
    const int s = segmentOf(mid);
    CHECK(s >= 0);
    if (s >= 0)
    {
      CHECK(lineMarker->GetComponent(cell, 0) == s + 1);
      length[s] += std::hypot(b[0] - a[0], b[1] - a[1]);
    }
  }
  for (const double l : length)
  {
    CHECK(std::fabs(l - 4) < 1e-12);
  }

  // Without markers, as Triangle: 1 on the mesh boundary, 0 inside; without attributes none.
  pd->GetPointData()->Initialize();
  pd->GetCellData()->Initialize();
  filter->Update();
  CHECK(log.Errors.empty());
  out = filter->GetOutput();
  CHECK(out->GetPointData()->GetArray("PointAttributes") == nullptr);
  marker = out->GetPointData()->GetArray("BoundaryMarker");
  CHECK(marker != nullptr);
  for (vtkIdType i = 0; marker && i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    const bool boundary = p[0] == 0 || p[0] == 4 || p[1] == 0 || p[1] == 4;
    CHECK(marker->GetComponent(i, 0) == (boundary ? 1 : 0));
  }
  lineMarker = filter->GetOutput(2)->GetCellData()->GetArray("BoundaryMarker");
  CHECK(lineMarker && lineMarker->GetRange()[0] == 1 && lineMarker->GetRange()[1] == 1);

  // A polygon's marker goes to its edges (cell ids count the vertex cell first).
  vtkNew<vtkCellArray> polys;
  const vtkIdType square[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, square);
  vtkNew<vtkIntArray> polygonMarkers;
  polygonMarkers->SetName("BoundaryMarker");
  polygonMarkers->InsertNextValue(0);
  polygonMarkers->InsertNextValue(9);
  pd->SetLines(nullptr);
  pd->SetPolys(polys);
  pd->GetCellData()->AddArray(polygonMarkers);
  filter->Update();
  CHECK(log.Errors.empty());
  Validate(filter->GetOutput(), PslgOf(pd), 25, true);
  lineMarker = filter->GetOutput(2)->GetCellData()->GetArray("BoundaryMarker");
  CHECK(lineMarker && lineMarker->GetRange()[0] == 9 && lineMarker->GetRange()[1] == 9);
}

// The same from a Triangle file through the reader: two_regions.poly, a 2 x 1 rectangle of
// segments marked 5 split by the segment x = 1 marked 7; points marked 5 but the inner
// segment's ends (unmarked: they take 5, from the first marked segment through them);
// one attribute, x + 2y.
void TestFileMarkers()
{
  vtkNew<vtkTriangleTetGenReader> reader;
  reader->SetFileName(GDR_TEST_TWO_REGIONS);
  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputConnection(reader->GetOutputPort());
  filter->SetBackendToCPU();
  filter->SetMaximumArea(0.01);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckArrays(filter);
  Validate(filter->GetOutput(), PslgOf(reader->GetOutput()), 20, true);

  vtkPolyData* out = filter->GetOutput();
  vtkDataArray* marker = out->GetPointData()->GetArray("BoundaryMarker");
  vtkDataArray* attribute = out->GetPointData()->GetArray("PointAttributes");
  CHECK(marker && attribute && attribute->GetNumberOfComponents() == 1);
  int inner = 0;
  for (vtkIdType i = 0; marker && attribute && i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    const bool boundary = p[0] == 0 || p[0] == 2 || p[1] == 0 || p[1] == 1;
    const bool onInner = p[0] == 1 && !boundary;
    inner += onInner ? 1 : 0;
    CHECK(marker->GetComponent(i, 0) == (boundary ? 5 : (onInner ? 7 : 0)));
    CHECK(std::fabs(attribute->GetComponent(i, 0) - (p[0] + 2 * p[1])) <= 1e-12 * 4);
  }
  CHECK(inner > 0);
  vtkDataArray* lineMarker = filter->GetOutput(2)->GetCellData()->GetArray("BoundaryMarker");
  CHECK(lineMarker && lineMarker->GetNumberOfTuples() > 0);
  vtkIdType marked7 = 0;
  for (vtkIdType c = 0; lineMarker && c < lineMarker->GetNumberOfTuples(); ++c)
  {
    const double m = lineMarker->GetComponent(c, 0);
    CHECK(m == 5 || m == 7);
    marked7 += m == 7 ? 1 : 0;
  }
  CHECK(marked7 == inner + 1); // the inner segment's pieces
}

void TestAbort()
{
  vtkSmartPointer<vtkPolyData> plate = ReadPlate();
  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(plate);
  filter->SetBackendToCPU();
  filter->SetMaximumArea(0.001);
  vtkNew<vtkCallbackCommand> abortOnProgress;
  abortOnProgress->SetCallback([](vtkObject* caller, unsigned long, void*, void*)
    { static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1); });
  filter->AddObserver(vtkCommand::ProgressEvent, abortOnProgress);
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  CHECK(filter->GetOutput()->GetNumberOfPoints() == 0);
  CHECK(filter->GetOutput()->GetCellData()->GetNumberOfArrays() == 0);
}

void TestBackends()
{
  vtkSmartPointer<vtkPolyData> plate = ReadPlate();
  vtkNew<vtkGPUConstrainedDelaunay2D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(plate);

  filter->SetBackendToGPU();
  filter->Update();
  if (gdr::gpu_available())
  {
    CHECK(log.Errors.empty());
    CHECK(filter->GetOutput()->GetNumberOfCells() > 0);
  }
  else
  {
    CHECK(log.ErrorContains("no usable CUDA device"));
    CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  }

  log.Errors.clear();
  log.Warnings.clear();
  filter->SetBackendToAuto();
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(filter->GetOutput()->GetNumberOfCells() > 0);
  if (!gdr::gpu_available())
  {
    CHECK(log.Warnings.empty()); // the CPU fallback is said once per session, as information
    auto* backend =
      vtkStringArray::SafeDownCast(filter->GetOutput()->GetFieldData()->GetAbstractArray("Backend"));
    CHECK(backend && backend->GetValue(0) == "cpu");
  }
}
}

int main(int argc, char* argv[])
{
  const std::map<std::string, std::function<void()>> tests = {
    { "Plate", TestPlate },
    { "PolygonOrientation", TestPolygonOrientation },
    { "LinesAndPoints", TestLinesAndPoints },
    { "SizeBounds", TestSizeBounds },
    { "OutOfRange", TestOutOfRange },
    { "OffCentersAndCDTOnly", TestOffCentersAndCDTOnly },
    { "EmptyInput", TestEmptyInput },
    { "CrossingLines", TestCrossingLines },
    { "MarkersAndAttributes", TestMarkersAndAttributes },
    { "FileMarkers", TestFileMarkers },
    { "Abort", TestAbort },
    { "Backends", TestBackends },
  };
  return gdr_test::RunNamedTest(argc, argv, tests);
}
