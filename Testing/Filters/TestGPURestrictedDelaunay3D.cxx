// Filter tests for vtkGPURestrictedDelaunay3D. Each test is one ctest entry:
//   TestGPURestrictedDelaunay3D <test name>
// The outputs are converted back to core types by this file (independently of the filter's
// converter) and checked with the validators `gdr rdt --check` uses: validate_tetmesh (positive
// tetrahedra, bounded by the surface, locally Delaunay) and validate_surface (a closed or open
// oriented 2-manifold without self-intersections).
#include "FilterTestSupport.h"
#include "vtkGPURestrictedDelaunay3D.h"

#include "vtkCallbackCommand.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"
#include "vtkTable.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLPolyDataReader.h"

#include "gdr/backend.h"
#include "gdr/pslg.h"
#include "gdr/validate.h"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace
{
using gdr_test::EventLog;

// A ball of radius 1 with a spherical cavity of radius 0.5: 1280 + 320 triangles.
vtkSmartPointer<vtkPolyData> ReadHollowSphere()
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(GDR_TEST_HOLLOW_SPHERE);
  reader->Update();
  return reader->GetOutput();
}

// The hollow sphere's outer shell (its first 1280 triangles): those whose corners all pass
// `keep`, on the sphere's points scaled along z by `zscale`.
vtkSmartPointer<vtkPolyData> OuterShell(const std::function<bool(const double*)>& keep, double zscale)
{
  vtkSmartPointer<vtkPolyData> sphere = ReadHollowSphere();
  vtkNew<vtkCellArray> polys;
  vtkIdType n;
  const vtkIdType* ids;
  for (vtkIdType c = 0; c < 1280; ++c)
  {
    sphere->GetPolys()->GetCellAtId(c, n, ids);
    bool kept = true;
    for (vtkIdType k = 0; k < n; ++k)
    {
      kept = kept && keep(sphere->GetPoint(ids[k]));
    }
    if (kept)
    {
      polys->InsertNextCell(n, ids);
    }
  }
  vtkNew<vtkPoints> points;
  for (vtkIdType i = 0; i < sphere->GetNumberOfPoints(); ++i)
  {
    const double* p = sphere->GetPoint(i);
    points->InsertNextPoint(p[0], p[1], zscale * p[2]);
  }
  auto shell = vtkSmartPointer<vtkPolyData>::New();
  shell->SetPoints(points);
  shell->SetPolys(polys);
  return shell;
}

// The outer shell above z = 0: an open surface.
vtkSmartPointer<vtkPolyData> Hemisphere()
{
  return OuterShell([](const double* p) { return p[2] >= 0; }, 1.0);
}

// A unit sphere of latitude-longitude quadrilaterals (triangles at the poles).
vtkSmartPointer<vtkPolyData> QuadSphere(int rings, int sectors)
{
  vtkNew<vtkPoints> points;
  points->InsertNextPoint(0, 0, 1);
  for (int i = 1; i < rings; ++i)
  {
    const double theta = M_PI * i / rings;
    for (int j = 0; j < sectors; ++j)
    {
      const double phi = 2 * M_PI * j / sectors;
      points->InsertNextPoint(
        std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  }
  const vtkIdType south = points->InsertNextPoint(0, 0, -1);
  auto id = [&](int ring, int j) { return vtkIdType(1 + (ring - 1) * sectors + j % sectors); };
  vtkNew<vtkCellArray> polys;
  for (int j = 0; j < sectors; ++j)
  {
    const vtkIdType top[3] = { 0, id(1, j), id(1, j + 1) };
    polys->InsertNextCell(3, top);
    for (int i = 1; i + 1 < rings; ++i)
    {
      const vtkIdType quad[4] = { id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1) };
      polys->InsertNextCell(4, quad);
    }
    const vtkIdType bottom[3] = { south, id(rings - 1, j + 1), id(rings - 1, j) };
    polys->InsertNextCell(3, bottom);
  }
  auto sphere = vtkSmartPointer<vtkPolyData>::New();
  sphere->SetPoints(points);
  sphere->SetPolys(polys);
  return sphere;
}

// Signed volume enclosed by the polygons of a closed surface (fanned into triangles).
double EnclosedVolume(vtkPolyData* pd)
{
  double v = 0;
  vtkIdType n;
  const vtkIdType* ids;
  for (pd->GetPolys()->InitTraversal(); pd->GetPolys()->GetNextCell(n, ids);)
  {
    double a[3], b[3], c[3];
    pd->GetPoint(ids[0], a);
    for (vtkIdType k = 1; k + 1 < n; ++k)
    {
      pd->GetPoint(ids[k], b);
      pd->GetPoint(ids[k + 1], c);
      v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
             a[2] * (b[0] * c[1] - b[1] * c[0])) /
        6.0;
    }
  }
  return v;
}

std::vector<gdr::Point3> PointsOf(vtkDataSet* data)
{
  std::vector<gdr::Point3> points;
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double p[3];
    data->GetPoint(i, p);
    points.push_back({ p[0], p[1], p[2] });
  }
  return points;
}

std::vector<std::array<int, 3>> TrianglesOf(vtkPolyData* surface)
{
  std::vector<std::array<int, 3>> triangles;
  vtkIdType n;
  const vtkIdType* ids;
  for (surface->GetPolys()->InitTraversal(); surface->GetPolys()->GetNextCell(n, ids);)
  {
    CHECK(n == 3);
    triangles.push_back({ int(ids[0]), int(ids[1]), int(ids[2]) });
  }
  return triangles;
}

// Tetrahedra and surface -> TetMesh (VTK tetrahedra turn the other way round).
gdr::TetMesh TetMeshOf(vtkUnstructuredGrid* grid, vtkPolyData* surface)
{
  gdr::TetMesh mesh;
  mesh.points = PointsOf(grid);
  vtkIdType n;
  const vtkIdType* ids;
  vtkCellArray* cells = grid->GetCells();
  for (cells->InitTraversal(); cells->GetNextCell(n, ids);)
  {
    CHECK(n == 4);
    mesh.tets.push_back({ int(ids[1]), int(ids[0]), int(ids[2]), int(ids[3]) });
  }
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    CHECK(grid->GetCellType(c) == VTK_TETRA);
  }
  mesh.subfaces = TrianglesOf(surface);
  return mesh;
}

double Sum(vtkDataArray* a)
{
  double s = 0;
  for (vtkIdType i = 0; a && i < a->GetNumberOfTuples(); ++i)
  {
    s += a->GetComponent(i, 0);
  }
  return s;
}

double FieldValue(vtkDataObject* data, const char* name)
{
  vtkDataArray* a = data->GetFieldData()->GetArray(name);
  CHECK(a != nullptr);
  return a ? a->GetComponent(0, 0) : std::numeric_limits<double>::quiet_NaN();
}

vtkPolyData* SurfaceOutput(vtkGPURestrictedDelaunay3D* filter)
{
  return vtkPolyData::SafeDownCast(filter->GetOutputDataObject(1));
}

vtkTable* HistogramOutput(vtkGPURestrictedDelaunay3D* filter)
{
  return vtkTable::SafeDownCast(filter->GetOutputDataObject(2));
}

// Every array named is there, one finite value per element.
void CheckArrays(vtkFieldData* data, vtkIdType count, const std::vector<const char*>& names)
{
  for (const char* name : names)
  {
    vtkDataArray* a = data->GetArray(name);
    CHECK(a != nullptr);
    if (!a)
    {
      std::cerr << "missing array " << name << std::endl;
      continue;
    }
    CHECK(a->GetNumberOfTuples() == count);
    for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
    {
      CHECK(std::isfinite(a->GetComponent(i, 0)));
    }
  }
}

// The histogram table: 180 rows of 1-degree bins, the counts of `countName` summing to `total`.
void CheckHistogram(vtkTable* table, const char* countName, double total)
{
  const vtkIdType bins = 180;
  CHECK(table && table->GetNumberOfRows() == bins);
  vtkDataArray* centers =
    table ? vtkDataArray::SafeDownCast(table->GetColumnByName("bin_extents")) : nullptr;
  vtkDataArray* counts =
    table ? vtkDataArray::SafeDownCast(table->GetColumnByName(countName)) : nullptr;
  CHECK(centers && counts);
  if (centers && counts)
  {
    CHECK(centers->GetComponent(0, 0) == 0.5 && centers->GetComponent(bins - 1, 0) == bins - 0.5);
    CHECK(Sum(counts) == total);
  }
}

// The restricted surface: arrays, criteria, statistics, its facet-angle histogram, and
// validate_surface. Returns the number of triangles.
vtkIdType CheckSurface(vtkGPURestrictedDelaunay3D* filter, bool closed)
{
  vtkPolyData* surface = SurfaceOutput(filter);
  const vtkIdType ntris = surface->GetNumberOfCells();
  CHECK(ntris > 0 && surface->GetNumberOfPolys() == ntris);
  CheckArrays(surface->GetCellData(), ntris, { "MinAngle", "Size", "Distance", "IsBad" });
  CheckArrays(surface->GetPointData(), surface->GetNumberOfPoints(), { "PointType" });
  vtkCellData* cd = surface->GetCellData();
  CHECK(cd->GetScalars() && std::string(cd->GetScalars()->GetName()) == "MinAngle");
  vtkDataArray* angle = cd->GetArray("MinAngle");
  vtkDataArray* size = cd->GetArray("Size");
  vtkDataArray* distance = cd->GetArray("Distance");
  vtkDataArray* bad = cd->GetArray("IsBad");
  if (!angle || !size || !distance || !bad)
  {
    return ntris;
  }
  // The facet criteria in effect (automatic sizes resolved) hold on every triangle.
  const double facetAngle = FieldValue(surface, "FacetAngle");
  const double facetSize = FieldValue(surface, "FacetSize");
  const double facetDistance = FieldValue(surface, "FacetDistance");
  CHECK(facetAngle == filter->GetFacetAngle());
  CHECK(FieldValue(surface, "BadFacets") == 0);
  CHECK(Sum(bad) == 0);
  for (vtkIdType t = 0; t < ntris; ++t)
  {
    CHECK(angle->GetComponent(t, 0) >= facetAngle - 1e-4 && angle->GetComponent(t, 0) <= 60);
    CHECK(size->GetComponent(t, 0) > 0 && size->GetComponent(t, 0) <= facetSize * (1 + 1e-9));
    CHECK(distance->GetComponent(t, 0) >= 0 &&
      distance->GetComponent(t, 0) <= facetDistance * (1 + 1e-9));
  }
  CHECK(std::fabs(FieldValue(surface, "MinimumFacetAngleReached") - angle->GetRange()[0]) < 1e-4);
  CHECK(FieldValue(surface, "Stalled") == 0 && FieldValue(surface, "SteinerCapReached") == 0);

  // The histogram of the smallest facet angles: one count per triangle, none below the bound
  // or above 60 degrees.
  vtkTable* histogram = HistogramOutput(filter);
  CheckHistogram(histogram, "FacetAngleCount", double(ntris));
  vtkDataArray* counts = vtkDataArray::SafeDownCast(histogram->GetColumnByName("FacetAngleCount"));
  for (int b = 0; counts && b < 180; ++b)
  {
    CHECK(counts->GetComponent(b, 0) == 0 || (b >= int(facetAngle) - 1 && b <= 60));
  }

  const gdr::ValidationReport report =
    gdr::validate_surface(PointsOf(surface), TrianglesOf(surface), closed);
  if (!report.valid)
  {
    std::cerr << report.summary() << std::endl;
  }
  CHECK(report.valid);
  return ntris;
}

// The tetrahedra: arrays, statistics, the dihedral histogram, and validate_tetmesh with the
// surface as their boundary (locally Delaunay unless the sliver pass moved points). Returns
// the volume of the tetrahedra.
double CheckTetrahedra(vtkGPURestrictedDelaunay3D* filter)
{
  vtkUnstructuredGrid* out = filter->GetOutput();
  const vtkIdType ntets = out->GetNumberOfCells();
  CHECK(ntets > 0);
  vtkCellData* cd = out->GetCellData();
  CheckArrays(cd, ntets, { "RadiusEdgeRatio", "MinDihedralAngle", "MaxDihedralAngle", "Volume",
                           "IsBad" });
  CheckArrays(out->GetPointData(), out->GetNumberOfPoints(), { "PointType" });
  CHECK(cd->GetScalars() && std::string(cd->GetScalars()->GetName()) == "MinDihedralAngle");
  vtkDataArray* ratio = cd->GetArray("RadiusEdgeRatio");
  vtkDataArray* lo = cd->GetArray("MinDihedralAngle");
  vtkDataArray* volume = cd->GetArray("Volume");
  vtkDataArray* bad = cd->GetArray("IsBad");
  vtkDataArray* type = out->GetPointData()->GetArray("PointType");
  if (!ratio || !lo || !volume || !bad || !type)
  {
    return 0;
  }
  for (vtkIdType t = 0; t < ntets; ++t)
  {
    CHECK(volume->GetComponent(t, 0) > 0);
    CHECK(ratio->GetComponent(t, 0) <= filter->GetCellRadiusEdgeRatio() * (1 + 1e-6));
  }
  CHECK(Sum(bad) == 0 && FieldValue(out, "BadTetrahedra") == 0);
  // 0 corner, 1 on a feature edge, 3 on the surface, 2 inside; the surface has no free points.
  CHECK(type->GetRange()[0] >= 0 && type->GetRange()[1] <= 3);
  vtkPolyData* surface = SurfaceOutput(filter);
  CHECK(surface->GetPoints() == out->GetPoints());
  for (const auto& triangle : TrianglesOf(surface))
  {
    for (int v : triangle)
    {
      CHECK(type->GetComponent(v, 0) != 2);
    }
  }

  CheckHistogram(HistogramOutput(filter), "DihedralAngleCount", 6.0 * ntets);
  const double total = Sum(volume);
  CHECK(std::fabs(FieldValue(out, "Volume") - total) <= 1e-9 * total);
  CHECK(std::fabs(FieldValue(out, "MinimumDihedralAngleReached") - lo->GetRange()[0]) < 1e-4);

  gdr::ValidateOptions options;
  options.check_conformity = false; // the surface is approximated, not kept
  options.check_delaunay = filter->GetSliverAngle() == 0; // smoothing moves points off Delaunay
  const gdr::ValidationReport report =
    gdr::validate_tetmesh(TetMeshOf(out, surface), nullptr, options);
  if (!report.valid)
  {
    std::cerr << report.summary() << std::endl;
  }
  CHECK(report.valid && report.non_delaunay == 0);
  // The surface bounds the tetrahedra: it encloses their volume.
  CHECK(std::fabs(EnclosedVolume(surface) - total) <= 1e-9 * total);
  return total;
}

void TestHollowSphere()
{
  vtkSmartPointer<vtkPolyData> input = ReadHollowSphere();
  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(input);
  filter->SetBackendToCPU();
  filter->SetFacetSize(0.2);
  filter->SetFacetDistance(0.01);
  filter->Update();
  CHECK(log.Errors.empty() && log.Warnings.empty());
  const vtkIdType ntris = CheckSurface(filter, true);
  const double volume = CheckTetrahedra(filter);
  vtkUnstructuredGrid* out = filter->GetOutput();
  std::cout << out->GetNumberOfCells() << " tetrahedra, " << ntris << " surface triangles, volume "
            << volume << std::endl;

  // The volume of the input polyhedron, within the facet distance's worth of it.
  const double expected = EnclosedVolume(input);
  CHECK(std::fabs(volume - expected) <= 0.03 * expected);
  // Surface points lie on the input: between its faces' distance to the centre and 1 (or
  // between those of the cavity and 0.5).
  vtkPolyData* surface = SurfaceOutput(filter);
  vtkIdType n;
  const vtkIdType* ids;
  for (surface->GetPolys()->InitTraversal(); surface->GetPolys()->GetNextCell(n, ids);)
  {
    for (vtkIdType k = 0; k < n; ++k)
    {
      double p[3];
      surface->GetPoint(ids[k], p);
      const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
      CHECK((r > 0.98 && r < 1 + 1e-9) || (r > 0.49 && r < 0.5 + 1e-9));
    }
  }

  vtkFieldData* fd = out->GetFieldData();
  auto* backend = vtkStringArray::SafeDownCast(fd->GetAbstractArray("Backend"));
  CHECK(backend && backend->GetValue(0) == "cpu");
  auto* phases = vtkStringArray::SafeDownCast(fd->GetAbstractArray("PhaseNames"));
  CHECK(phases && fd->GetArray("PhaseSeconds") &&
    phases->GetNumberOfValues() == fd->GetArray("PhaseSeconds")->GetNumberOfTuples());
  CHECK(FieldValue(out, "ClosedInput") == 1 && FieldValue(out, "VolumeMeshed") == 1);
  CHECK(FieldValue(out, "FacetSize") == 0.2 && FieldValue(out, "FacetDistance") == 0.01);
  CHECK(FieldValue(out, "CellSize") == 0.2); // automatic: the facet size
  CHECK(FieldValue(out, "SteinerPoints") > 0 && FieldValue(out, "TotalSeconds") >= 0);

  // Default sizes: relative to the bounding box diagonal D (2 sqrt 3).
  filter->SetFacetSize(-1);
  filter->SetFacetDistance(-1);
  filter->SetCellSize(0.3);
  filter->Update();
  CHECK(log.Errors.empty());
  const double diagonal = 2 * std::sqrt(3.0);
  CHECK(std::fabs(FieldValue(filter->GetOutput(), "FacetSize") - diagonal / 20) < 1e-12);
  CHECK(std::fabs(FieldValue(filter->GetOutput(), "FacetDistance") - diagonal / 500) < 1e-12);
  CHECK(FieldValue(filter->GetOutput(), "CellSize") == 0.3);
  CheckSurface(filter, true);
  CheckTetrahedra(filter);
}

// The restricted surface as sorted triangles of coordinates (each from its smallest corner).
std::vector<std::array<double, 9>> SurfaceCoordinates(vtkPolyData* surface)
{
  std::vector<std::array<double, 9>> out;
  for (const auto& t : TrianglesOf(surface))
  {
    double p[3][3];
    for (int i = 0; i < 3; ++i)
    {
      surface->GetPoint(t[i], p[i]);
    }
    int k = 0;
    for (int i = 1; i < 3; ++i)
    {
      if (std::lexicographical_compare(p[i], p[i] + 3, p[k], p[k] + 3))
      {
        k = i;
      }
    }
    std::array<double, 9> c;
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        c[3 * i + j] = p[(k + i) % 3][j];
      }
    }
    out.push_back(c);
  }
  std::sort(out.begin(), out.end());
  return out;
}

// SliverAngle: interior points move, and only they. With one OpenMP thread a CPU run repeats
// itself, so the run with the pass is compared with the one without: the same surface (the
// same triangles on the same points, with the same Size and Distance), the same volume, the
// tetrahedra valid and within the cell criteria (not Delaunay where points moved), and fewer
// of them with a dihedral angle beyond 15 degrees (SliversBefore and SliversAfter count them;
// the angle arrays agree with the count after), the smallest angle no worse.
void TestSliverAngle()
{
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(ReadHollowSphere());
  filter->SetBackendToCPU();
  filter->SetFacetSize(0.15);
  filter->SetFacetDistance(0.01);
  filter->Update();
  CHECK(log.Errors.empty() && log.Warnings.empty());
  CHECK(FieldValue(filter->GetOutput(), "SliversBefore") == 0);
  CHECK(FieldValue(filter->GetOutput(), "SliversAfter") == 0);
  const double plainVolume = CheckTetrahedra(filter);
  const auto plainSurface = SurfaceCoordinates(SurfaceOutput(filter));
  vtkNew<vtkPolyData> plain;
  plain->DeepCopy(SurfaceOutput(filter));
  vtkNew<vtkUnstructuredGrid> plainTets;
  plainTets->DeepCopy(filter->GetOutput());

  filter->SetSliverAngle(15);
  filter->Update();
  omp_set_num_threads(threads);
  CHECK(log.Errors.empty() && log.Warnings.empty());
  CheckSurface(filter, true);
  const double volume = CheckTetrahedra(filter);
  vtkUnstructuredGrid* out = filter->GetOutput();
  CHECK(out->GetNumberOfCells() == plainTets->GetNumberOfCells());
  CHECK(SurfaceCoordinates(SurfaceOutput(filter)) == plainSurface);
  for (const char* name : { "Size", "Distance", "MinAngle" })
  {
    vtkDataArray* a = plain->GetCellData()->GetArray(name);
    vtkDataArray* b = SurfaceOutput(filter)->GetCellData()->GetArray(name);
    CHECK(a && b && a->GetNumberOfTuples() == b->GetNumberOfTuples());
    for (vtkIdType i = 0; a && b && i < a->GetNumberOfTuples() && i < b->GetNumberOfTuples(); ++i)
    {
      CHECK(a->GetComponent(i, 0) == b->GetComponent(i, 0));
    }
  }
  CHECK(std::fabs(volume - plainVolume) <= 1e-12 * plainVolume);
  const double before = FieldValue(out, "SliversBefore");
  const double after = FieldValue(out, "SliversAfter");
  std::cout << "SliverAngle 15: " << before << " -> " << after << " slivers, min dihedral "
            << FieldValue(plainTets, "MinimumDihedralAngleReached") << " -> "
            << FieldValue(out, "MinimumDihedralAngleReached") << " deg" << std::endl;
  CHECK(before > 0 && after < 0.75 * before);
  CHECK(FieldValue(out, "MinimumDihedralAngleReached") >=
    FieldValue(plainTets, "MinimumDihedralAngleReached"));
  auto beyond = [](vtkDataSet* tets)
  {
    vtkDataArray* lo = tets->GetCellData()->GetArray("MinDihedralAngle");
    vtkDataArray* hi = tets->GetCellData()->GetArray("MaxDihedralAngle");
    vtkIdType n = 0;
    for (vtkIdType t = 0; t < lo->GetNumberOfTuples(); ++t)
    {
      n += lo->GetComponent(t, 0) < 15 || hi->GetComponent(t, 0) > 165 ? 1 : 0;
    }
    return double(n);
  };
  CHECK(std::fabs(beyond(out) - after) <= 2); // float arrays against doubles
  CHECK(std::fabs(beyond(plainTets) - before) <= 2);
  // Only interior points moved: surface points are where they were (PointType 2 is inside).
  vtkDataArray* type = out->GetPointData()->GetArray("PointType");
  for (vtkIdType i = 0; type && i < out->GetNumberOfPoints(); ++i)
  {
    if (type->GetComponent(i, 0) != 2)
    {
      double p[3], q[3];
      out->GetPoint(i, p);
      plainTets->GetPoint(i, q);
      CHECK(p[0] == q[0] && p[1] == q[1] && p[2] == q[2]);
    }
  }
}

void TestOpenSurface()
{
  // An open surface with MeshVolume on: the surface alone, and a warning that says why.
  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(Hemisphere());
  filter->SetBackendToCPU();
  filter->SetFacetSize(0.2);
  filter->SetFacetDistance(0.01);
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(log.WarningContains("the surface is open"));
  CheckSurface(filter, false);
  vtkUnstructuredGrid* out = filter->GetOutput();
  CHECK(out->GetNumberOfCells() == 0 && out->GetNumberOfPoints() == 0);
  CHECK(FieldValue(out, "ClosedInput") == 0 && FieldValue(out, "VolumeMeshed") == 0);
  CheckHistogram(HistogramOutput(filter), "DihedralAngleCount", 0);
  // The restricted facets stop short of the open rim: less than the half sphere's area.
  CHECK(FieldValue(out, "Area") < 2 * M_PI && FieldValue(out, "Area") > 0.7 * 2 * M_PI);
}

void TestSurfaceOnly()
{
  // MeshVolume off: a closed surface, no tetrahedra, no warning.
  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(ReadHollowSphere());
  filter->SetBackendToCPU();
  filter->SetFacetSize(0.2);
  filter->MeshVolumeOff();
  filter->Update();
  CHECK(log.Errors.empty() && log.Warnings.empty());
  CheckSurface(filter, true);
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  CHECK(FieldValue(filter->GetOutput(), "ClosedInput") == 1);
  CHECK(FieldValue(filter->GetOutput(), "VolumeMeshed") == 0);
}

void TestManifold()
{
  // The outer shell of the hollow sphere flattened 33 times: thinner than the default facet
  // size, so the restricted surface pinches at the rim unless the Manifold criterion refines
  // there (on by default).
  vtkSmartPointer<vtkPolyData> thin = OuterShell([](const double*) { return true; }, 0.03);

  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(thin);
  filter->SetBackendToCPU();
  CHECK(filter->GetManifold() == 1);
  filter->Update();
  // (The inner shell's points are unused: a warning.) Duals that cross the thin part twice
  // make restricted facets between two outside tetrahedra: left out of the surface, counted.
  CHECK(log.Errors.empty() && !log.WarningContains("not a manifold"));
  CHECK(FieldValue(filter->GetOutput(), "FacetsLeftOut") > 0);
  CheckSurface(filter, true);
  CheckTetrahedra(filter);
  CHECK(FieldValue(filter->GetOutput(), "ManifoldSplits") > 0);
  CHECK(FieldValue(filter->GetOutput(), "NonManifoldFacets") == 0);

  // Off: the pinched places are counted, and a warning says so.
  filter->ManifoldOff();
  log.Warnings.clear();
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(FieldValue(filter->GetOutput(), "ManifoldSplits") == 0);
  CHECK(FieldValue(filter->GetOutput(), "NonManifoldFacets") > 0);
  CHECK(log.WarningContains("not a manifold"));
}

void TestPolygons()
{
  // Quadrilaterals are triangulated; the sphere's volume comes out within 3%.
  vtkSmartPointer<vtkPolyData> sphere = QuadSphere(16, 24);
  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(sphere);
  filter->SetBackendToCPU();
  filter->SetFacetSize(0.25);
  filter->SetFacetDistance(0.01);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckSurface(filter, true);
  const double volume = CheckTetrahedra(filter);
  CHECK(std::fabs(volume - EnclosedVolume(sphere)) <= 0.03 * EnclosedVolume(sphere));
  CHECK(std::fabs(volume - 4 * M_PI / 3) <= 0.05 * 4 * M_PI / 3);
}

void TestFeatures()
{
  // A unit cube of quadrilaterals, turned off the axes (rotated about z by a, then about x by
  // b) so that the points on its faces are rounded constructions, as on any CAD part: with
  // FeatureAngle its 12 edges and 8 corners are kept and the volume is the cube's; without,
  // the edges come out rounded.
  const double ca = std::cos(0.3), sa = std::sin(0.3), cb = std::cos(0.7), sb = std::sin(0.7);
  const double turn[3][3] = { { ca, -sa, 0 }, { cb * sa, cb * ca, -sb }, { sb * sa, sb * ca, cb } };
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int k = 0; k < 8; ++k)
  {
    const double c[3] = { double(k & 1), double((k >> 1) & 1), double((k >> 2) & 1) };
    double p[3];
    for (int i = 0; i < 3; ++i)
    {
      p[i] = turn[i][0] * c[0] + turn[i][1] * c[1] + turn[i][2] * c[2];
    }
    points->InsertNextPoint(p);
  }
  vtkNew<vtkCellArray> faces;
  const vtkIdType sides[6][4] = { { 0, 2, 3, 1 }, { 4, 5, 7, 6 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 4, 6, 2 }, { 1, 3, 7, 5 } };
  for (const auto& side : sides)
  {
    faces->InsertNextCell(4, side);
  }
  vtkNew<vtkPolyData> cube;
  cube->SetPoints(points);
  cube->SetPolys(faces);
  CHECK(std::fabs(EnclosedVolume(cube) - 1) < 1e-12);
  // Distances of a point to the cube's faces, in the cube's own axes (turned back).
  auto onFaces = [&](const double p[3])
  {
    int on = 0;
    for (int j = 0; j < 3; ++j)
    {
      const double c = turn[0][j] * p[0] + turn[1][j] * p[1] + turn[2][j] * p[2];
      on += (std::fabs(c) < 1e-12 || std::fabs(c - 1) < 1e-12) ? 1 : 0;
    }
    return on;
  };

  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(cube);
  filter->SetBackendToCPU();
  filter->SetFacetSize(0.3);
  filter->SetFeatureAngle(30);
  filter->Update();
  CHECK(log.Errors.empty());
  CheckSurface(filter, true);
  const double volume = CheckTetrahedra(filter);
  CHECK(std::fabs(volume - 1) < 1e-9);
  vtkUnstructuredGrid* out = filter->GetOutput();
  CHECK(FieldValue(out, "FeatureEdges") == 12 && FieldValue(out, "Corners") == 8);
  CHECK(FieldValue(out, "FeatureAngle") == 30);
  // PointType: the corners (0) are the cube's, the feature points (1) lie on its edges.
  vtkDataArray* type = out->GetPointData()->GetArray("PointType");
  int corners = 0;
  for (vtkIdType i = 0; type && i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    const double t = type->GetComponent(i, 0);
    corners += t == 0 ? 1 : 0;
    CHECK(t != 0 || onFaces(p) == 3);
    CHECK(t != 1 || onFaces(p) == 2);
  }
  CHECK(corners == 8);

  filter->SetFeatureAngle(0);
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(FieldValue(filter->GetOutput(), "FeatureEdges") == 0);
  const double rounded = Sum(filter->GetOutput()->GetCellData()->GetArray("Volume"));
  // 0.06% short here: the 8 corners, all in the initial sample, stay; the edges do not.
  CHECK(rounded > 0.99 && rounded < 1 - 1e-4);
}

void TestOutOfRange()
{
  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  CHECK(filter->GetFacetAngle() == 30 && filter->GetFacetSize() == -1 &&
    filter->GetFacetDistance() == -1);
  CHECK(filter->GetCellRadiusEdgeRatio() == 2 && filter->GetCellSize() == -1);
  CHECK(filter->GetMeshVolume() == 1 && filter->GetMaximumSteinerPoints() == -1);
  CHECK(filter->GetFeatureAngle() == 0 && filter->GetSliverAngle() == 0);
  CHECK(filter->GetBackend() == vtkGPURestrictedDelaunay3D::AUTO);
  filter->SetBackend(9);
  CHECK(filter->GetBackend() == vtkGPURestrictedDelaunay3D::CPU);

  EventLog log;
  log.Watch(filter);
  filter->SetInputData(ReadHollowSphere());
  filter->SetFacetSize(0.3);
  filter->SetFacetAngle(40);
  CHECK(filter->GetFacetAngle() == 40); // kept as set, refused when run
  filter->Update();
  CHECK(log.ErrorContains("InvalidInput: facet angle must be in [0, 30]"));
  CHECK(filter->GetErrorCode() != 0);
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  CHECK(SurfaceOutput(filter)->GetNumberOfCells() == 0);
  CHECK(HistogramOutput(filter)->GetNumberOfRows() == 0);

  const std::pair<std::function<void()>, const char*> cases[] = {
    { [&] { filter->SetFacetAngle(-5); }, "facet angle must be in [0, 30]" },
    { [&] { filter->SetCellRadiusEdgeRatio(0.5); }, "cell radius-edge ratio must be at least 1" },
    { [&] { filter->SetCellRadiusEdgeRatio(-2); }, "cell radius-edge ratio must be at least 1" },
    { [&] { filter->SetMaximumSteinerPoints(-7); }, "maximum Steiner points" },
    { [&] { filter->SetFeatureAngle(180); }, "feature angle must be in [0, 180)" },
    { [&] { filter->SetSliverAngle(31); }, "sliver angle must be in [0, 30]" },
    { [&] { filter->SetSliverAngle(-1); }, "sliver angle must be in [0, 30]" },
    { [&] { filter->SetCellSize(std::numeric_limits<double>::quiet_NaN()); }, "must be finite" },
    { [&]
      {
        filter->SetFacetAngle(0);
        filter->SetFacetSize(0);
        filter->SetFacetDistance(0);
      },
      "at least one facet criterion" },
  };
  for (const auto& c : cases)
  {
    filter->SetFacetAngle(30);
    filter->SetFacetSize(0.3);
    filter->SetFacetDistance(-1);
    filter->SetCellRadiusEdgeRatio(2);
    filter->SetCellSize(-1);
    filter->SetMaximumSteinerPoints(-1);
    filter->SetFeatureAngle(0);
    filter->SetSliverAngle(0);
    c.first();
    log.Clear();
    filter->Update();
    CHECK(log.ErrorContains(c.second));
    CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
    CHECK(SurfaceOutput(filter)->GetNumberOfCells() == 0);
  }

  // A good run afterwards clears the error code.
  filter->SetFacetAngle(30);
  filter->SetFacetSize(0.3);
  filter->SetFacetDistance(-1);
  log.Clear();
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(filter->GetErrorCode() == 0);
  CHECK(filter->GetOutput()->GetNumberOfCells() > 0);
}

void TestEmptyInput()
{
  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetBackendToCPU();
  vtkNew<vtkPolyData> empty;
  filter->SetInputData(empty);
  filter->Update();
  CHECK(log.Errors.empty() && log.Warnings.empty());
  CHECK(filter->GetOutput()->GetNumberOfPoints() == 0);
  CHECK(SurfaceOutput(filter)->GetNumberOfPoints() == 0);
  CHECK(HistogramOutput(filter)->GetNumberOfRows() == 0);

  // Points without polygons: nothing to mesh, and the filter says so.
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(ReadHollowSphere()->GetPoints());
  filter->SetInputData(cloud);
  filter->Update();
  CHECK(log.Errors.empty());
  CHECK(log.WarningContains("no polygons"));
  CHECK(SurfaceOutput(filter)->GetNumberOfCells() == 0);
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
  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(sphere);
  filter->SetBackendToCPU();
  filter->Update();
  CHECK(log.ErrorContains("SelfIntersectingInput"));
  CHECK(log.ErrorContains("intersects itself: triangle pairs"));
  CHECK(filter->GetErrorCode() != 0);
  CHECK(filter->GetOutput()->GetNumberOfCells() == 0);
  CHECK(SurfaceOutput(filter)->GetNumberOfCells() == 0);
}

void TestAbort()
{
  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(ReadHollowSphere());
  filter->SetBackendToCPU();
  filter->SetFacetSize(0.1);
  vtkNew<vtkCallbackCommand> abortOnProgress;
  abortOnProgress->SetCallback(
    [](vtkObject* caller, unsigned long, void*, void* data)
    {
      // Let the checks and the initial triangulation pass, abort in the refinement.
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
  CHECK(SurfaceOutput(filter)->GetNumberOfCells() == 0);
  CHECK(HistogramOutput(filter)->GetNumberOfRows() == 0);
}

void TestBackends()
{
  vtkNew<vtkGPURestrictedDelaunay3D> filter;
  EventLog log;
  log.Watch(filter);
  filter->SetInputData(ReadHollowSphere());
  filter->SetFacetSize(0.3);
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
    { "OpenSurface", TestOpenSurface },
    { "SurfaceOnly", TestSurfaceOnly },
    { "Manifold", TestManifold },
    { "Polygons", TestPolygons },
    { "Features", TestFeatures },
    { "OutOfRange", TestOutOfRange },
    { "EmptyInput", TestEmptyInput },
    { "SelfIntersecting", TestSelfIntersecting },
    { "Abort", TestAbort },
    { "Backends", TestBackends },
  };
  return gdr_test::RunNamedTest(argc, argv, tests);
}
