// Filter tests for vtkGPUQualityTetMesh. Each test is one ctest entry:
//   TestGPUQualityTetMesh <test name>
// The outputs are converted back to gdr::TetMesh by this file (independently of the
// filter's converter) and checked with the core validator gdr::validate_tetmesh.
#include "FilterTestSupport.h"
#include "vtkGPUQualityTetMesh.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
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
#include "vtkUnstructuredGrid.h"
#include "vtkXMLPolyDataReader.h"

#include "../Core/cdt3d/surfaces.h"
#include "gdr/backend.h"
#include "gdr/io.h"
#include "gdr/pslg.h"
#include "gdr/qm3d.h"
#include "gdr/validate.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace
{
using gdr_test::EventLog;

vtkSmartPointer<vtkPolyData> ReadHollowSphere()
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(GDR_TEST_HOLLOW_SPHERE);
  reader->Update();
  return reader->GetOutput();
}

vtkSmartPointer<vtkPolyData> PolyDataOf(const gdr::Surface& surface)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (const gdr::Point3& p : surface.points)
  {
    points->InsertNextPoint(p.x, p.y, p.z);
  }
  vtkNew<vtkCellArray> polys;
  for (const auto& t : surface.triangles)
  {
    const vtkIdType ids[3] = { t[0], t[1], t[2] };
    polys->InsertNextCell(3, ids);
  }
  auto pd = vtkSmartPointer<vtkPolyData>::New();
  pd->SetPoints(points);
  pd->SetPolys(polys);
  return pd;
}

// The surface as this test sees the polydata: every point, polygons fanned into triangles
// (the test inputs have convex polygons).
gdr::Surface SurfaceOf(vtkPolyData* pd)
{
  gdr::Surface surface;
  for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pd->GetPoint(i, p);
    surface.points.push_back({ p[0], p[1], p[2] });
  }
  vtkIdType n;
  const vtkIdType* ids;
  for (pd->GetPolys()->InitTraversal(); pd->GetPolys()->GetNextCell(n, ids);)
  {
    for (vtkIdType i = 1; i + 1 < n; ++i)
    {
      surface.triangles.push_back({ int(ids[0]), int(ids[i]), int(ids[i + 1]) });
    }
  }
  return surface;
}

// Signed volume enclosed by the triangles of a surface (divergence theorem).
double EnclosedVolume(const gdr::Surface& s)
{
  double v = 0;
  for (const auto& t : s.triangles)
  {
    const gdr::Point3& a = s.points[t[0]];
    const gdr::Point3& b = s.points[t[1]];
    const gdr::Point3& c = s.points[t[2]];
    v += (a.x * (b.y * c.z - b.z * c.y) - a.y * (b.x * c.z - b.z * c.x) +
           a.z * (b.x * c.y - b.y * c.x)) /
      6.0;
  }
  return v;
}

// Output tetrahedra and subfaces -> TetMesh (VTK tetrahedra turn the other way round).
gdr::TetMesh TetMeshOf(vtkUnstructuredGrid* grid, vtkPolyData* subfaces)
{
  gdr::TetMesh mesh;
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
  {
    double p[3];
    grid->GetPoint(i, p);
    mesh.points.push_back({ p[0], p[1], p[2] });
  }
  vtkIdType n;
  const vtkIdType* ids;
  vtkCellArray* cells = grid->GetCells();
  for (cells->InitTraversal(); cells->GetNextCell(n, ids);)
  {
    CHECK(n == 4);
    if (n == 4)
    {
      mesh.tets.push_back({ int(ids[1]), int(ids[0]), int(ids[2]), int(ids[3]) });
    }
  }
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    CHECK(grid->GetCellType(c) == VTK_TETRA);
  }
  vtkDataArray* facet = subfaces->GetCellData()->GetArray("FacetId");
  for (subfaces->GetPolys()->InitTraversal(); subfaces->GetPolys()->GetNextCell(n, ids);)
  {
    CHECK(n == 3);
    mesh.subfaces.push_back({ int(ids[0]), int(ids[1]), int(ids[2]) });
    mesh.subface_facet.push_back(
      facet ? int(facet->GetComponent(mesh.subfaces.size() - 1, 0)) : -1);
  }
  return mesh;
}

double Sum(vtkDataArray* a)
{
  double s = 0;
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    s += a->GetComponent(i, 0);
  }
  return s;
}

double FieldValue(vtkDataObject* data, const char* name)
{
  vtkDataArray* a = data->GetFieldData()->GetArray(name);
  CHECK(a != nullptr);
  return a ? a->GetComponent(0, 0) : 0.0;
}

// Checks the outputs of a successful run: sizes and ranges of the arrays, the histogram,
// the subfaces and the statistics.
void CheckOutputs(vtkGPUQualityTetMesh* filter)
{
  vtkUnstructuredGrid* out = filter->GetOutput();
  const vtkIdType ntets = out->GetNumberOfCells();
  CHECK(ntets > 0);
  vtkCellData* cd = out->GetCellData();
  for (const char* name :
    { "RadiusEdgeRatio", "MinDihedralAngle", "MaxDihedralAngle", "Volume", "IsBad", "Region" })
  {
    vtkDataArray* a = cd->GetArray(name);
    CHECK(a != nullptr);
    if (!a)
    {
      return;
    }
    CHECK(a->GetNumberOfTuples() == ntets);
  }
  CHECK(cd->GetScalars() && std::string(cd->GetScalars()->GetName()) == "MinDihedralAngle");
  vtkDataArray* ratio = cd->GetArray("RadiusEdgeRatio");
  vtkDataArray* lo = cd->GetArray("MinDihedralAngle");
  vtkDataArray* hi = cd->GetArray("MaxDihedralAngle");
  vtkDataArray* volume = cd->GetArray("Volume");
  vtkDataArray* bad = cd->GetArray("IsBad");
  vtkIdType nbad = 0;
  for (vtkIdType t = 0; t < ntets; ++t)
  {
    CHECK(ratio->GetComponent(t, 0) >= std::sqrt(6.0) / 4 - 1e-6);
    CHECK(lo->GetComponent(t, 0) >= 0 && lo->GetComponent(t, 0) <= 70.6);
    CHECK(hi->GetComponent(t, 0) >= 70.5 && hi->GetComponent(t, 0) <= 180);
    CHECK(volume->GetComponent(t, 0) > 0);
    const double b = bad->GetComponent(t, 0);
    CHECK(b == 0 || b == 1 || b == 2);
    nbad += b != 0 ? 1 : 0;
  }
  vtkDataArray* type = out->GetPointData()->GetArray("PointType");
  CHECK(type && type->GetNumberOfTuples() == out->GetNumberOfPoints());
  if (type)
  {
    CHECK(type->GetRange()[0] >= 0 && type->GetRange()[1] <= 3);
  }

  // The histogram counts all six angles of every tetrahedron, from the smallest to the
  // largest dihedral angle.
  vtkTable* histogram = vtkTable::SafeDownCast(filter->GetOutputDataObject(1));
  CHECK(histogram && histogram->GetNumberOfRows() == 180);
  vtkDataArray* centers =
    histogram ? vtkDataArray::SafeDownCast(histogram->GetColumnByName("bin_extents")) : nullptr;
  vtkDataArray* counts = histogram
    ? vtkDataArray::SafeDownCast(histogram->GetColumnByName("DihedralAngleCount"))
    : nullptr;
  CHECK(centers && counts);
  if (centers && counts)
  {
    CHECK(centers->GetComponent(0, 0) == 0.5 && centers->GetComponent(179, 0) == 179.5);
    CHECK(Sum(counts) == 6.0 * ntets);
    int first = 0;
    int last = 179;
    while (first < 179 && counts->GetComponent(first, 0) == 0)
    {
      ++first;
    }
    while (last > 0 && counts->GetComponent(last, 0) == 0)
    {
      --last;
    }
    CHECK(std::abs(first - std::floor(lo->GetRange()[0])) <= 1);
    CHECK(std::abs(last - std::floor(hi->GetRange()[1])) <= 1);
  }

  vtkPolyData* subfaces = vtkPolyData::SafeDownCast(filter->GetOutputDataObject(2));
  CHECK(subfaces && subfaces->GetNumberOfPolys() > 0);
  if (subfaces)
  {
    CHECK(subfaces->GetPoints() == out->GetPoints());
    vtkDataArray* facet = subfaces->GetCellData()->GetArray("FacetId");
    CHECK(facet && facet->GetNumberOfTuples() == subfaces->GetNumberOfCells());
    CHECK(facet && facet->GetRange()[0] >= 0);
    CHECK(subfaces->GetPointData()->GetArray("PointType") != nullptr);
  }

  vtkFieldData* fd = out->GetFieldData();
  auto* backend = vtkStringArray::SafeDownCast(fd->GetAbstractArray("Backend"));
  CHECK(backend && backend->GetNumberOfValues() == 1);
  if (backend && !gdr::gpu_available())
  {
    CHECK(backend->GetValue(0) == "cpu");
  }
  auto* phases = vtkStringArray::SafeDownCast(fd->GetAbstractArray("PhaseNames"));
  CHECK(phases && fd->GetArray("PhaseSeconds") &&
    phases->GetNumberOfValues() == fd->GetArray("PhaseSeconds")->GetNumberOfTuples());
  CHECK(FieldValue(out, "BadTetrahedra") == double(nbad));
  CHECK(FieldValue(out, "SteinerPoints") <= out->GetNumberOfPoints());
  // Interior seeds are free points (PointType 2) put in with the CDT.
  CHECK(FieldValue(out, "InteriorSeeds") + FieldValue(out, "CDTSteinerPoints") <=
    FieldValue(out, "SteinerPoints"));
  if (vtkDataArray* type = out->GetPointData()->GetArray("PointType"))
  {
    vtkIdType free = 0;
    for (vtkIdType i = 0; i < type->GetNumberOfTuples(); ++i)
    {
      free += type->GetComponent(i, 0) == 2;
    }
    CHECK(free >= FieldValue(out, "InteriorSeeds"));
  }
  CHECK(FieldValue(out, "TotalSeconds") >= 0);
  const double total = Sum(volume);
  CHECK(std::fabs(FieldValue(out, "Volume") - total) <= 1e-9 * total);
  // Merged nearly flat facets (CoplanarAngle) let the boundary bend a little off the input.
  const double inputTolerance = filter->GetCoplanarAngle() > 0 ? 1e-4 : 1e-9;
  CHECK(std::fabs(FieldValue(out, "InputVolume") - total) <= inputTolerance * total);
  CHECK(std::fabs(FieldValue(out, "MinimumDihedralAngleReached") - lo->GetRange()[0]) < 1e-4);
}

gdr::ValidationReport Validate(
  vtkGPUQualityTetMesh* filter, const gdr::Surface* input, double maxRadiusEdge)
{
  const gdr::TetMesh mesh = TetMeshOf(
    filter->GetOutput(), vtkPolyData::SafeDownCast(filter->GetOutputDataObject(2)));
  gdr::ValidateOptions options;
  options.max_radius_edge = maxRadiusEdge;
  options.check_delaunay = filter->GetSliverAngle() == 0; // smoothing moves points off Delaunay
  if (filter->GetCoplanarAngle() > 0)
  {
    options.facet_bend_deg = gdr::kMergedFacetBend; // as gdr tet --check
  }
  const gdr::ValidationReport report = gdr::validate_tetmesh(mesh, input, options);
  if (!report.valid)
  {
    std::cerr << report.summary() << std::endl;
  }
  CHECK(report.valid);
  CHECK(report.missing_points == 0 && report.missing_facets == 0);
  return report;
}

// A box [0, nx] x [0, ny] x [0, nz] of unit hexahedra; with regionBelow > 0, the cells with
// x < regionBelow get Region 1 and the others Region 2.
vtkSmartPointer<vtkUnstructuredGrid> HexGrid(int nx, int ny, int nz, int regionBelow)
{
  vtkNew<vtkPoints> points;
  auto id = [&](int i, int j, int k) { return vtkIdType((k * (ny + 1) + j) * (nx + 1) + i); };
  for (int k = 0; k <= nz; ++k)
  {
    for (int j = 0; j <= ny; ++j)
    {
      for (int i = 0; i <= nx; ++i)
      {
        points->InsertNextPoint(i, j, k);
      }
    }
  }
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  vtkNew<vtkIntArray> region;
  region->SetName("Region");
  for (int k = 0; k < nz; ++k)
  {
    for (int j = 0; j < ny; ++j)
    {
      for (int i = 0; i < nx; ++i)
      {
        const vtkIdType hex[8] = { id(i, j, k), id(i + 1, j, k), id(i + 1, j + 1, k),
          id(i, j + 1, k), id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1),
          id(i, j + 1, k + 1) };
        grid->InsertNextCell(VTK_HEXAHEDRON, 8, hex);
        region->InsertNextValue(i < regionBelow ? 1 : 2);
      }
    }
  }
  if (regionBelow > 0)
  {
    grid->GetCellData()->AddArray(region);
  }
  return grid;
}

//------------------------------------------------------------------------------
void TestHollowSphere()
{
  vtkSmartPointer<vtkPolyData> sphere = ReadHollowSphere();
  CHECK(sphere->GetNumberOfPolys() == 1600);
  vtkNew<vtkGPUQualityTetMesh> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(sphere);
  filter->SetBackendToCPU();
  filter->SetRadiusEdgeRatio(1.4);
  int progressEvents = 0;
  vtkNew<vtkCallbackCommand> countProgress;
  countProgress->SetClientData(&progressEvents);
  countProgress->SetCallback(
    [](vtkObject*, unsigned long, void* client, void*) { ++*static_cast<int*>(client); });
  filter->AddObserver(vtkCommand::ProgressEvent, countProgress);
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(progressEvents >= 3);
  CheckOutputs(filter);
  const gdr::Surface input = SurfaceOf(sphere);
  const gdr::ValidationReport report = Validate(filter, &input, 1.4);
  CHECK(report.quality.bad_elements == 0);
  CHECK(FieldValue(filter->GetOutput(), "BadTetrahedra") == 0);
  CHECK(filter->GetOutput()->GetCellData()->GetArray("RadiusEdgeRatio")->GetRange()[1] <= 1.4);
  CHECK(filter->GetOutput()->GetCellData()->GetArray("Region")->GetRange()[1] == 0);

  // The mesh fills the ball less the cavity, and every input triangle is a facet.
  const double expected = EnclosedVolume(input);
  const double volume = Sum(filter->GetOutput()->GetCellData()->GetArray("Volume"));
  CHECK(expected > 3.5 && std::fabs(volume - expected) <= 1e-9 * expected);
  vtkDataArray* facet =
    vtkPolyData::SafeDownCast(filter->GetOutputDataObject(2))->GetCellData()->GetArray("FacetId");
  CHECK(facet->GetRange()[0] == 0 && facet->GetRange()[1] == 1599);

  // Input points keep their ids: all of them are input points of the mesh.
  vtkDataArray* type = filter->GetOutput()->GetPointData()->GetArray("PointType");
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    CHECK(type->GetComponent(i, 0) == 0);
  }

  // A volume bound and a dihedral bound refine further.
  const vtkIdType coarse = filter->GetOutput()->GetNumberOfCells();
  filter->SetMaximumVolume(0.002);
  filter->Update();
  CheckOutputs(filter);
  CHECK(filter->GetOutput()->GetNumberOfCells() > coarse);
  CHECK(filter->GetOutput()->GetCellData()->GetArray("Volume")->GetRange()[1] <= 0.002 * (1 + 1e-9));
  filter->SetMaximumVolume(0);
  filter->SetRadiusEdgeRatio(2);
  filter->SetMinimumDihedralAngle(10);
  filter->Update();
  CheckOutputs(filter);
  Validate(filter, &input, 0);
  if (FieldValue(filter->GetOutput(), "BadTetrahedra") == 0)
  {
    CHECK(filter->GetOutput()->GetCellData()->GetArray("MinDihedralAngle")->GetRange()[0] >= 10);
  }
}

// Sliver removal: the same mesh stays valid, conforming and within the bounds, and the
// tetrahedra with a dihedral angle beyond 15 degrees become fewer (SliversBefore/After count
// them in the mesh before and after smoothing; the angle arrays agree with the count after).
void TestSliverAngle()
{
  vtkSmartPointer<vtkPolyData> sphere = ReadHollowSphere();
  const gdr::Surface input = SurfaceOf(sphere);
  vtkNew<vtkGPUQualityTetMesh> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(sphere);
  filter->SetBackendToCPU();
  filter->SetRadiusEdgeRatio(1.4);
  filter->SetMaximumVolume(0.002);
  filter->SetSliverAngle(15);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckOutputs(filter);
  const gdr::ValidationReport report = Validate(filter, &input, 1.4);
  CHECK(report.quality.bad_elements == 0);
  const double before = FieldValue(filter->GetOutput(), "SliversBefore");
  const double after = FieldValue(filter->GetOutput(), "SliversAfter");
  CHECK(before > 0 && after < 0.5 * before);
  CHECK(FieldValue(filter->GetOutput(), "SliverFlips") >= 0); // present (the sphere may need none)
  vtkDataArray* lo = filter->GetOutput()->GetCellData()->GetArray("MinDihedralAngle");
  vtkDataArray* hi = filter->GetOutput()->GetCellData()->GetArray("MaxDihedralAngle");
  vtkIdType beyond = 0;
  for (vtkIdType t = 0; t < lo->GetNumberOfTuples(); ++t)
  {
    beyond += lo->GetComponent(t, 0) < 15 || hi->GetComponent(t, 0) > 165 ? 1 : 0;
  }
  CHECK(std::fabs(beyond - after) <= 0.01 * after + 2); // float arrays against doubles
  filter->SetSliverAngle(45);
  CHECK(filter->GetSliverAngle() == 30);
}

// CoplanarAngle (TetGen's facet tolerance, 0.1 degrees by default as TetGen's): the cube
// whose top is a fan of skinny, nearly coplanar triangles meshes with fewer points when they
// merge into one facet than kept exactly (0); the mesh is valid with its subfaces allowed to
// bend from the input triangles, and not without.
void TestCoplanarAngle()
{
  const gdr::Surface input = gdr::test::cube_with_rough_top(8);
  vtkSmartPointer<vtkPolyData> pd = PolyDataOf(input);
  vtkNew<vtkGPUQualityTetMesh> filter;
  CHECK(filter->GetCoplanarAngle() == 0.1);
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(pd);
  filter->SetBackendToCPU();
  filter->SetRadiusEdgeRatio(1.4);
  filter->SetCoplanarAngle(0);
  filter->Update();
  CHECK(log.Errors.empty());
  Validate(filter, &input, 0);
  const vtkIdType exact = filter->GetOutput()->GetNumberOfPoints();
  filter->SetCoplanarAngle(0.1);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckOutputs(filter);
  const vtkIdType merged = filter->GetOutput()->GetNumberOfPoints();
  CHECK(merged < exact);
  Validate(filter, &input, 0);
  const gdr::TetMesh mesh = TetMeshOf(
    filter->GetOutput(), vtkPolyData::SafeDownCast(filter->GetOutputDataObject(2)));
  CHECK(!gdr::validate_tetmesh(mesh, &input, {}).valid); // the fan's edges are not kept
  filter->SetCoplanarAngle(9);
  CHECK(filter->GetCoplanarAngle() == 5);
}

void TestBushing()
{
  // The bundled CLI example, a coarse part turned on a lathe: its first refinement stalls (46%
  // of the volume bad), and the run is redone with interior seeds; under 1% is left at the
  // default radius-edge bound.
  const gdr::Surface input = gdr::io::read_off(GDR_TEST_BUSHING);
  vtkSmartPointer<vtkPolyData> pd = PolyDataOf(input);
  vtkNew<vtkGPUQualityTetMesh> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(pd);
  filter->SetBackendToCPU();
  filter->Update();
  CHECK(log.Errors.empty());
  CheckOutputs(filter);
  Validate(filter, &input, 0);
  const double expected = EnclosedVolume(input);
  const double volume = Sum(filter->GetOutput()->GetCellData()->GetArray("Volume"));
  CHECK(std::fabs(volume - expected) <= 1e-9 * expected);
  vtkDataArray* bad = filter->GetOutput()->GetFieldData()->GetArray("BadVolumePercent");
  CHECK(bad && bad->GetTuple1(0) < 1.0);
}

void TestPolygons()
{
  // A hexagonal prism of polygons: two hexagons and six quadrilaterals.
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 2; ++k)
  {
    for (int i = 0; i < 6; ++i)
    {
      const double a = i * M_PI / 3;
      points->InsertNextPoint(std::cos(a), std::sin(a), 1.5 * k);
    }
  }
  vtkNew<vtkCellArray> polys;
  const vtkIdType bottom[6] = { 5, 4, 3, 2, 1, 0 };
  const vtkIdType top[6] = { 6, 7, 8, 9, 10, 11 };
  polys->InsertNextCell(6, bottom);
  polys->InsertNextCell(6, top);
  for (vtkIdType i = 0; i < 6; ++i)
  {
    const vtkIdType quad[4] = { i, (i + 1) % 6, 6 + (i + 1) % 6, 6 + i };
    polys->InsertNextCell(4, quad);
  }
  vtkNew<vtkPolyData> prism;
  prism->SetPoints(points);
  prism->SetPolys(polys);

  vtkNew<vtkGPUQualityTetMesh> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(prism);
  filter->SetBackendToCPU();
  filter->SetRadiusEdgeRatio(1.5);
  filter->SetMaximumVolume(0.05);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckOutputs(filter);
  const gdr::Surface input = SurfaceOf(prism);
  Validate(filter, &input, 0);
  const double volume = Sum(filter->GetOutput()->GetCellData()->GetArray("Volume"));
  const double expected = EnclosedVolume(input);
  CHECK(std::fabs(volume - expected) <= 1e-9 * expected);
  CHECK(std::fabs(volume - 1.5 * 1.5 * std::sqrt(3.0)) <= 1e-6); // hexagon 3 sqrt(3) / 2
  // Each polygon is one facet: the subfaces carry the eight cell ids.
  vtkDataArray* facet =
    vtkPolyData::SafeDownCast(filter->GetOutputDataObject(2))->GetCellData()->GetArray("FacetId");
  std::set<int> facets;
  for (vtkIdType f = 0; f < facet->GetNumberOfTuples(); ++f)
  {
    facets.insert(int(facet->GetComponent(f, 0)));
  }
  CHECK(facets == std::set<int>({ 0, 1, 2, 3, 4, 5, 6, 7 }));

  // A cube of quadrilaterals, four points of its own each (as vtkCubeSource makes it): the
  // engine merges the duplicates and says so.
  vtkNew<vtkPoints> cornerPoints;
  vtkNew<vtkCellArray> faces;
  const int sides[6][4][3] = { { { 0, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 1, 0, 0 } },
    { { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } },
    { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 0, 1 }, { 0, 0, 1 } },
    { { 0, 1, 0 }, { 0, 1, 1 }, { 1, 1, 1 }, { 1, 1, 0 } },
    { { 0, 0, 0 }, { 0, 0, 1 }, { 0, 1, 1 }, { 0, 1, 0 } },
    { { 1, 0, 0 }, { 1, 1, 0 }, { 1, 1, 1 }, { 1, 0, 1 } } };
  for (const auto& side : sides)
  {
    vtkIdType ids[4];
    for (int k = 0; k < 4; ++k)
    {
      ids[k] = cornerPoints->InsertNextPoint(side[k][0], side[k][1], side[k][2]);
    }
    faces->InsertNextCell(4, ids);
  }
  vtkNew<vtkPolyData> cube;
  cube->SetPoints(cornerPoints);
  cube->SetPolys(faces);
  log.Clear();
  filter->SetInputData(cube);
  filter->SetMaximumVolume(0.01);
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(log.WarningContains("merged"));
  CheckOutputs(filter);
  CHECK(std::fabs(Sum(filter->GetOutput()->GetCellData()->GetArray("Volume")) - 1.0) <= 1e-9);
}

void TestUnstructuredGrid()
{
  // Without a Region array: the boundary of the grid is meshed as one region.
  vtkSmartPointer<vtkUnstructuredGrid> grid = HexGrid(3, 2, 2, 0);
  vtkNew<vtkGPUQualityTetMesh> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(grid);
  filter->SetBackendToCPU();
  filter->SetRadiusEdgeRatio(1.4);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckOutputs(filter);
  Validate(filter, nullptr, 1.4);
  CHECK(std::fabs(Sum(filter->GetOutput()->GetCellData()->GetArray("Volume")) - 12) <= 1e-9);
  CHECK(filter->GetOutput()->GetCellData()->GetArray("Region")->GetRange()[1] == 0);

  // With Region: the face x = 1 between the regions stays, and each part keeps its value.
  grid = HexGrid(3, 2, 2, 1);
  filter->SetInputData(grid);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckOutputs(filter);
  Validate(filter, nullptr, 1.4);
  vtkDataArray* region = filter->GetOutput()->GetCellData()->GetArray("Region");
  vtkDataArray* volume = filter->GetOutput()->GetCellData()->GetArray("Volume");
  std::map<int, double> perRegion;
  for (vtkIdType t = 0; t < region->GetNumberOfTuples(); ++t)
  {
    perRegion[int(region->GetComponent(t, 0))] += volume->GetComponent(t, 0);
  }
  CHECK(perRegion.size() == 2);
  CHECK(std::fabs(perRegion[1] - 4) <= 1e-9 && std::fabs(perRegion[2] - 8) <= 1e-9);
  // No tetrahedron crosses x = 1.
  for (vtkIdType t = 0; t < region->GetNumberOfTuples(); ++t)
  {
    double bounds[6];
    filter->GetOutput()->GetCell(t)->GetBounds(bounds);
    CHECK(region->GetComponent(t, 0) == 1 ? bounds[1] <= 1 : bounds[0] >= 1);
  }

  // A floating-point Region is not a region attribute: ignored with a warning.
  vtkNew<vtkDoubleArray> real;
  real->SetName("Region");
  real->SetNumberOfValues(grid->GetNumberOfCells());
  real->Fill(1.5);
  grid->GetCellData()->AddArray(real);
  log.Clear();
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(log.WarningContains("Region"));
  CHECK(filter->GetOutput()->GetCellData()->GetArray("Region")->GetRange()[1] == 0);
}

void TestSeeds()
{
  // A region seed in the cavity fills it (region 5); a hole seed in the shell empties it.
  vtkSmartPointer<vtkPolyData> sphere = ReadHollowSphere();
  vtkNew<vtkPoints> regionPoints;
  regionPoints->InsertNextPoint(0.1, 0.0, 0.0);
  vtkNew<vtkIntArray> attribute;
  attribute->SetName("RegionAttribute");
  attribute->InsertNextValue(5);
  vtkNew<vtkPolyData> regions;
  regions->SetPoints(regionPoints);
  regions->GetPointData()->AddArray(attribute);
  vtkNew<vtkPoints> holePoints;
  holePoints->InsertNextPoint(0.0, 0.75, 0.0);
  vtkNew<vtkPolyData> holes;
  holes->SetPoints(holePoints);

  vtkNew<vtkGPUQualityTetMesh> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(sphere);
  filter->AddSeedsData(regions);
  filter->AddSeedsData(holes);
  filter->SetBackendToCPU();
  filter->Update();
  CHECK(log.Errors.empty());
  CheckOutputs(filter);
  vtkDataArray* region = filter->GetOutput()->GetCellData()->GetArray("Region");
  CHECK(region->GetRange()[0] == 5 && region->GetRange()[1] == 5);
  gdr::Surface input = SurfaceOf(sphere);
  gdr::Surface inner = input;
  inner.triangles.erase(inner.triangles.begin(), inner.triangles.begin() + 1280);
  const double cavity = -EnclosedVolume(inner); // its triangles face the cavity
  const double volume = Sum(filter->GetOutput()->GetCellData()->GetArray("Volume"));
  CHECK(cavity > 0.4 && std::fabs(volume - cavity) <= 1e-9 * cavity);

  // Without the hole seed, the shell is meshed too, with region 0.
  filter->RemoveAllSeeds();
  filter->AddSeedsData(regions);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckOutputs(filter);
  region = filter->GetOutput()->GetCellData()->GetArray("Region");
  vtkDataArray* tetVolume = filter->GetOutput()->GetCellData()->GetArray("Volume");
  double regionVolume[2] = { 0, 0 };
  for (vtkIdType t = 0; t < region->GetNumberOfTuples(); ++t)
  {
    const bool inCavity = region->GetComponent(t, 0) == 5;
    CHECK(inCavity || region->GetComponent(t, 0) == 0);
    regionVolume[inCavity ? 1 : 0] += tetVolume->GetComponent(t, 0);
  }
  CHECK(std::fabs(regionVolume[1] - cavity) <= 1e-9 * cavity);
  CHECK(std::fabs(regionVolume[0] - EnclosedVolume(input)) <= 1e-9 * regionVolume[0]);

  // RegionMaximumVolume bounds the tetrahedra of the seed's region only.
  double largest[2] = { 0, 0 };
  for (vtkIdType t = 0; t < region->GetNumberOfTuples(); ++t)
  {
    const int k = region->GetComponent(t, 0) == 5 ? 1 : 0;
    largest[k] = std::max(largest[k], tetVolume->GetComponent(t, 0));
  }
  const double bound = 0.25 * largest[1];
  vtkNew<vtkDoubleArray> maxVolume;
  maxVolume->SetName("RegionMaximumVolume");
  maxVolume->InsertNextValue(bound);
  regions->GetPointData()->AddArray(maxVolume);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckOutputs(filter);
  region = filter->GetOutput()->GetCellData()->GetArray("Region");
  tetVolume = filter->GetOutput()->GetCellData()->GetArray("Volume");
  double bounded[2] = { 0, 0 };
  for (vtkIdType t = 0; t < region->GetNumberOfTuples(); ++t)
  {
    const int k = region->GetComponent(t, 0) == 5 ? 1 : 0;
    bounded[k] = std::max(bounded[k], tetVolume->GetComponent(t, 0));
  }
  CHECK(bounded[1] <= bound * (1 + 1e-6));
  CHECK(bounded[0] > bound); // the shell has no bound of its own
}

void TestClamping()
{
  vtkNew<vtkGPUQualityTetMesh> filter;
  CHECK(filter->GetRadiusEdgeRatio() == 2);
  CHECK(filter->GetMinimumDihedralAngle() == 0);
  CHECK(filter->GetMaximumVolume() == 0);
  CHECK(filter->GetMaximumSteinerPoints() == -1);
  CHECK(filter->GetBackend() == vtkGPUQualityTetMesh::AUTO);
  filter->SetRadiusEdgeRatio(0.5);
  CHECK(filter->GetRadiusEdgeRatio() == 1);
  filter->SetRadiusEdgeRatio(-2);
  CHECK(filter->GetRadiusEdgeRatio() == 0);
  filter->SetRadiusEdgeRatio(1.2);
  CHECK(filter->GetRadiusEdgeRatio() == 1.2);
  filter->SetMinimumDihedralAngle(75);
  CHECK(filter->GetMinimumDihedralAngle() == 60);
  filter->SetMinimumDihedralAngle(-1);
  CHECK(filter->GetMinimumDihedralAngle() == 0);
  filter->SetMaximumVolume(-1);
  CHECK(filter->GetMaximumVolume() == 0);
  filter->SetMaximumSteinerPoints(-7);
  CHECK(filter->GetMaximumSteinerPoints() == -1);
  filter->SetBackend(9);
  CHECK(filter->GetBackend() == vtkGPUQualityTetMesh::CPU);
}

void TestEmptyInput()
{
  vtkNew<vtkGPUQualityTetMesh> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetBackendToCPU();
  vtkNew<vtkPolyData> empty;
  filter->SetInputData(empty);
  filter->Update();
  vtkNew<vtkUnstructuredGrid> emptyGrid;
  filter->SetInputData(emptyGrid);
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(log.Warnings.empty());
  CHECK(filter->GetOutput()->GetNumberOfPoints() == 0);
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  CHECK(vtkTable::SafeDownCast(filter->GetOutputDataObject(1))->GetNumberOfRows() == 0);
  CHECK(vtkPolyData::SafeDownCast(filter->GetOutputDataObject(2))->GetNumberOfCells() == 0);

  // Points without polygons: nothing to mesh, and the filter says so.
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(ReadHollowSphere()->GetPoints());
  filter->SetInputData(cloud);
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(log.WarningContains("no polygons"));
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
}

void RunExpectingError(
  vtkPolyData* input, const std::string& status, const std::vector<std::string>& texts)
{
  vtkNew<vtkGPUQualityTetMesh> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(input);
  filter->SetBackendToCPU();
  filter->Update();
  for (const std::string& e : log.Errors)
  {
    std::cout << "reported: " << e << std::endl;
  }
  CHECK(log.ErrorContains(status));
  for (const std::string& text : texts)
  {
    CHECK(log.ErrorContains(text));
  }
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  CHECK(filter->GetOutput()->GetNumberOfPoints() == 0);
  CHECK(vtkTable::SafeDownCast(filter->GetOutputDataObject(1))->GetNumberOfRows() == 0);
}

void TestOpenSurface()
{
  // The hollow sphere less its first triangle: the error names the three edges of the
  // hole by the input's point ids.
  vtkSmartPointer<vtkPolyData> sphere = ReadHollowSphere();
  vtkIdType n;
  const vtkIdType* ids;
  sphere->GetPolys()->GetCellAtId(0, n, ids);
  const std::vector<vtkIdType> removed(ids, ids + n);
  vtkNew<vtkCellArray> polys;
  for (vtkIdType c = 1; c < sphere->GetNumberOfPolys(); ++c)
  {
    sphere->GetPolys()->GetCellAtId(c, n, ids);
    polys->InsertNextCell(n, ids);
  }
  vtkNew<vtkPolyData> open;
  open->SetPoints(sphere->GetPoints());
  open->SetPolys(polys);
  std::vector<std::string> texts = { "the surface is open: edges with one triangle" };
  for (int k = 0; k < 3; ++k)
  {
    const vtkIdType a = std::min(removed[k], removed[(k + 1) % 3]);
    const vtkIdType b = std::max(removed[k], removed[(k + 1) % 3]);
    texts.push_back("(" + std::to_string(a) + ", " + std::to_string(b) + ")");
  }
  RunExpectingError(open, "InvalidInput", texts);
}

void TestSelfIntersecting()
{
  // The hollow sphere with its cavity moved half out of the ball.
  vtkSmartPointer<vtkPolyData> sphere = ReadHollowSphere();
  vtkNew<vtkPoints> moved;
  moved->DeepCopy(sphere->GetPoints());
  for (vtkIdType i = 642; i < moved->GetNumberOfPoints(); ++i)
  {
    double p[3];
    moved->GetPoint(i, p);
    moved->SetPoint(i, p[0] + 0.75, p[1], p[2]);
  }
  sphere->SetPoints(moved);
  RunExpectingError(sphere, "SelfIntersectingInput", { "intersects itself: triangle pairs" });
}

void TestAbort()
{
  vtkNew<vtkGPUQualityTetMesh> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(ReadHollowSphere());
  filter->SetBackendToCPU();
  filter->SetMaximumVolume(0.0005);
  vtkNew<vtkCallbackCommand> abortOnProgress;
  abortOnProgress->SetCallback([](vtkObject* caller, unsigned long, void*, void* data)
    {
      // Let the checks and the CDT pass, abort in the refinement.
      if (*static_cast<double*>(data) > 0.1)
      {
        static_cast<vtkAlgorithm*>(caller)->SetAbortExecute(1);
      }
    });
  filter->AddObserver(vtkCommand::ProgressEvent, abortOnProgress);
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  CHECK(filter->GetOutput()->GetNumberOfPoints() == 0);
  CHECK(filter->GetOutput()->GetCellData()->GetNumberOfArrays() == 0);
  CHECK(vtkTable::SafeDownCast(filter->GetOutputDataObject(1))->GetNumberOfRows() == 0);
  CHECK(vtkPolyData::SafeDownCast(filter->GetOutputDataObject(2))->GetNumberOfCells() == 0);
}

void TestBackends()
{
  vtkNew<vtkGPUQualityTetMesh> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(ReadHollowSphere());

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

  log.Clear();
  filter->SetBackendToAuto();
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(filter->GetOutput()->GetNumberOfCells() > 0);
  if (!gdr::gpu_available())
  {
    CHECK(!log.WarningContains("CUDA")); // said once per session, as information

    auto* backend = vtkStringArray::SafeDownCast(
      filter->GetOutput()->GetFieldData()->GetAbstractArray("Backend"));
    CHECK(backend && backend->GetValue(0) == "cpu");
  }
}
}

int main(int argc, char* argv[])
{
  const std::map<std::string, std::function<void()>> tests = {
    { "HollowSphere", TestHollowSphere },
    { "SliverAngle", TestSliverAngle },
    { "CoplanarAngle", TestCoplanarAngle },
    { "Bushing", TestBushing },
    { "Polygons", TestPolygons },
    { "UnstructuredGrid", TestUnstructuredGrid },
    { "Seeds", TestSeeds },
    { "Clamping", TestClamping },
    { "EmptyInput", TestEmptyInput },
    { "OpenSurface", TestOpenSurface },
    { "SelfIntersecting", TestSelfIntersecting },
    { "Abort", TestAbort },
    { "Backends", TestBackends },
  };
  return gdr_test::RunNamedTest(argc, argv, tests);
}
