// Tests of the Triangle / TetGen readers: what they read, and that the meshing filters take
// their output as it is (holes and regions of the files included). Named tests, one ctest
// entry each.
#include "FilterTestSupport.h"
#include "vtkGPUConstrainedDelaunay2D.h"
#include "vtkGPUQualityTetMesh.h"
#include "vtkTriangleTetGenMeshReader.h"
#include "vtkTriangleTetGenReader.h"

#include "vtkCellData.h"
#include "vtkCellType.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkUnstructuredGrid.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <string>

namespace
{
using gdr_test::EventLog;
const std::string kData = GDR_TEST_DATA;     // Data/
const std::string kCliData = GDR_TEST_CLI_DATA; // Testing/CLI/data
const std::string kOut = GDR_TEST_OUTPUT;

double SumOf(vtkDataArray* a)
{
  double s = 0;
  for (vtkIdType i = 0; a && i < a->GetNumberOfTuples(); ++i)
  {
    s += a->GetComponent(i, 0);
  }
  return s;
}

// The 2D filter on a reader's output, on the CPU, with no error reported.
vtkSmartPointer<vtkGPUConstrainedDelaunay2D> Mesh2D(vtkAlgorithm* reader, bool removeExterior)
{
  auto mesher = vtkSmartPointer<vtkGPUConstrainedDelaunay2D>::New();
  EventLog log;
  log.Watch(mesher);
  mesher->SetInputConnection(reader->GetOutputPort());
  mesher->SetBackendToCPU();
  mesher->SetRemoveExterior(removeExterior);
  mesher->Update();
  CHECK(log.Errors.empty());
  mesher->RemoveObservers(vtkCommand::ErrorEvent); // they point to this function's log
  mesher->RemoveObservers(vtkCommand::WarningEvent);
  return mesher;
}

// Triangle .poly: segments as lines, the holes section as HoleSeeds, and the 2D filter
// honours the hole without a HoleSeeds input.
void TestTrianglePoly()
{
  vtkNew<vtkTriangleTetGenReader> reader;
  reader->SetFileName((kData + "/square_hole.poly").c_str());
  reader->Update();
  vtkPolyData* pslg = reader->GetOutput();
  CHECK(pslg->GetNumberOfPoints() == 8);
  CHECK(pslg->GetNumberOfLines() == 8);
  CHECK(pslg->GetNumberOfVerts() == 0);
  double bounds[6];
  pslg->GetBounds(bounds);
  CHECK(bounds[1] == 4.0 && bounds[3] == 4.0 && bounds[4] == 0.0 && bounds[5] == 0.0);
  vtkDataArray* holes = pslg->GetFieldData()->GetArray("HoleSeeds");
  CHECK(holes && holes->GetNumberOfTuples() == 1 && holes->GetComponent(0, 0) == 2.0);

  vtkSmartPointer<vtkGPUConstrainedDelaunay2D> mesher = Mesh2D(reader, true);
  const double area = SumOf(mesher->GetOutput()->GetCellData()->GetArray("Area"));
  CHECK(std::abs(area - 12.0) < 1e-9); // 4 x 4 minus the 2 x 2 hole
}

// Triangle's regions reach the filter through the field data: attributes as the cell
// array Region, the left region's area bound applied there only.
void TestTriangleRegions()
{
  vtkNew<vtkTriangleTetGenReader> reader;
  reader->SetFileName((kCliData + "/two_regions.poly").c_str());
  reader->Update();
  vtkDataArray* seeds = reader->GetOutput()->GetFieldData()->GetArray("RegionSeeds");
  CHECK(seeds && seeds->GetNumberOfTuples() == 2 && seeds->GetComponent(1, 0) == 1.5);

  vtkSmartPointer<vtkGPUConstrainedDelaunay2D> mesher = Mesh2D(reader, false);
  vtkCellData* cd = mesher->GetOutput()->GetCellData();
  vtkDataArray* region = cd->GetArray("Region");
  vtkDataArray* area = cd->GetArray("Area");
  CHECK(region && area && region->GetNumberOfTuples() == mesher->GetOutput()->GetNumberOfCells());
  double left = 0, right = 0, largestLeft = 0, largestRight = 0;
  for (vtkIdType t = 0; region && area && t < region->GetNumberOfTuples(); ++t)
  {
    const double r = region->GetComponent(t, 0), a = area->GetComponent(t, 0);
    CHECK(r == 10 || r == 20);
    (r == 10 ? left : right) += a;
    double& largest = r == 10 ? largestLeft : largestRight;
    largest = std::max(largest, a);
  }
  CHECK(std::abs(left - 1.0) < 1e-9 && std::abs(right - 1.0) < 1e-9);
  CHECK(largestLeft <= 0.001 * (1 + 1e-12) && largestRight > 0.001);
}

// Triangle's boundary markers and point attributes as arrays that the 2D filter reads
// (its test FileMarkers meshes this file): point and line cell data BoundaryMarker, point
// data PointAttributes.
void TestTriangleMarkers()
{
  vtkNew<vtkTriangleTetGenReader> reader;
  reader->SetFileName((kCliData + "/two_regions.poly").c_str());
  reader->Update();
  vtkPolyData* pslg = reader->GetOutput();
  CHECK(pslg->GetNumberOfLines() == 7 && pslg->GetNumberOfCells() == 7);
  vtkDataArray* pointMarkers = pslg->GetPointData()->GetArray("BoundaryMarker");
  vtkDataArray* segmentMarkers = pslg->GetCellData()->GetArray("BoundaryMarker");
  vtkDataArray* attributes = pslg->GetPointData()->GetArray("PointAttributes");
  CHECK(pointMarkers && pointMarkers->GetNumberOfTuples() == 6);
  CHECK(segmentMarkers && segmentMarkers->GetNumberOfTuples() == 7);
  CHECK(attributes && attributes->GetNumberOfComponents() == 1 &&
    attributes->GetNumberOfTuples() == 6);
  if (!pointMarkers || !segmentMarkers || !attributes)
  {
    return;
  }
  const int expected[6] = { 5, 0, 5, 5, 0, 5 };
  for (vtkIdType i = 0; i < 6; ++i)
  {
    double p[3];
    pslg->GetPoint(i, p);
    CHECK(pointMarkers->GetComponent(i, 0) == expected[i]);
    CHECK(attributes->GetComponent(i, 0) == p[0] + 2 * p[1]); // x + 2y in the file
  }
  for (vtkIdType c = 0; c < 7; ++c)
  {
    CHECK(segmentMarkers->GetComponent(c, 0) == (c == 6 ? 7 : 5));
  }

  // A .node without markers or attributes gives no such arrays.
  reader->SetFileName((kData + "/points_only.node").c_str());
  reader->Update();
  CHECK(reader->GetOutput()->GetPointData()->GetArray("BoundaryMarker") == nullptr);
  CHECK(reader->GetOutput()->GetPointData()->GetArray("PointAttributes") == nullptr);
}

// A .node alone: isolated points become vertex cells.
void TestTriangleNode()
{
  vtkNew<vtkTriangleTetGenReader> reader;
  reader->SetFileName((kData + "/points_only.node").c_str());
  reader->Update();
  CHECK(reader->GetOutput()->GetNumberOfPoints() == 3);
  CHECK(reader->GetOutput()->GetNumberOfVerts() == 3);
}

// TetGen .poly: quadrilateral facets become triangles grouped by FacetId; the region seed
// (attribute 7, maximum volume 0.001) reaches the 3D filter through the field data.
void TestTetGenPoly()
{
  vtkNew<vtkTriangleTetGenReader> reader;
  reader->SetFileName((kCliData + "/box_region_volume.poly").c_str());
  reader->Update();
  vtkPolyData* surface = reader->GetOutput();
  CHECK(surface->GetNumberOfPolys() == 12);
  vtkDataArray* facet = surface->GetCellData()->GetArray("FacetId");
  CHECK(facet != nullptr);
  std::set<double> facets;
  for (vtkIdType i = 0; facet && i < facet->GetNumberOfTuples(); ++i)
  {
    facets.insert(facet->GetComponent(i, 0));
  }
  CHECK(facets.size() == 6);
  vtkDataArray* seeds = surface->GetFieldData()->GetArray("RegionSeeds");
  vtkDataArray* attribute = surface->GetFieldData()->GetArray("RegionAttribute");
  CHECK(seeds && seeds->GetNumberOfTuples() == 1 && attribute &&
    attribute->GetComponent(0, 0) == 7);

  vtkNew<vtkGPUQualityTetMesh> mesher;
  EventLog log;
  log.Watch(mesher);
  mesher->SetInputConnection(reader->GetOutputPort());
  mesher->SetBackendToCPU();
  mesher->Update();
  CHECK(log.Errors.empty());
  vtkUnstructuredGrid* tets = mesher->GetOutput();
  CHECK(tets->GetNumberOfCells() >= 2000);
  vtkDataArray* region = tets->GetCellData()->GetArray("Region");
  vtkDataArray* volume = tets->GetCellData()->GetArray("Volume");
  CHECK(region && region->GetRange()[0] == 7 && region->GetRange()[1] == 7);
  CHECK(volume && volume->GetRange()[1] <= 0.001);
  CHECK(std::abs(SumOf(volume) - 2.0) < 1e-9);
}

// .off through the same reader; the 2D and 3D kinds of .poly are told apart by content.
void TestOff()
{
  vtkNew<vtkTriangleTetGenReader> reader;
  reader->SetFileName((kData + "/cube.off").c_str());
  reader->Update();
  CHECK(reader->GetOutput()->GetNumberOfPolys() == 12);
  CHECK(vtkTriangleTetGenReader::CanReadFile("x.POLY") == 1);
  CHECK(vtkTriangleTetGenReader::CanReadFile("x.vtp") == 0);
}

// .ele: TetGen tetrahedra and Triangle triangles, with the .node beside the .ele.
void TestMeshFiles()
{
  vtkNew<vtkTriangleTetGenMeshReader> reader;
  reader->SetFileName((kData + "/lshape_tetgen.ele").c_str());
  reader->Update();
  vtkUnstructuredGrid* tets = reader->GetOutput();
  CHECK(tets->GetNumberOfCells() == 12);
  CHECK(tets->GetCellType(0) == VTK_TETRA);
  double volume = 0;
  for (vtkIdType c = 0; c < tets->GetNumberOfCells(); ++c)
  {
    double p[4][3];
    for (int k = 0; k < 4; ++k)
    {
      tets->GetPoint(tets->GetCell(c)->GetPointId(k), p[k]);
    }
    // VTK's orientation: (p1 - p0) x (p2 - p0) points towards p3, a positive volume.
    double u[3], v[3], w[3];
    for (int i = 0; i < 3; ++i)
    {
      u[i] = p[1][i] - p[0][i];
      v[i] = p[2][i] - p[0][i];
      w[i] = p[3][i] - p[0][i];
    }
    const double det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
      u[2] * (v[0] * w[1] - v[1] * w[0]);
    CHECK(det > 0);
    volume += det / 6;
  }
  CHECK(std::abs(volume - 3.0) < 1e-12); // the L-shaped prism

  std::ofstream(kOut + "/two_triangles.node") << "4 2 0 0\n1 0 0\n2 1 0\n3 1 1\n4 0 1\n";
  std::ofstream(kOut + "/two_triangles.ele") << "2 3 0\n1 1 2 3\n2 1 3 4\n";
  reader->SetFileName((kOut + "/two_triangles.ele").c_str());
  reader->Update();
  CHECK(reader->GetOutput()->GetNumberOfCells() == 2);
  CHECK(reader->GetOutput()->GetCellType(0) == VTK_TRIANGLE);
  CHECK(reader->GetOutput()->GetPointData()->GetArray("BoundaryMarker") == nullptr);

  // What Triangle's output carries: point markers and attributes, the regional attribute.
  std::ofstream(kOut + "/marked.node") << "4 2 1 1\n1 0 0 0.5 1\n2 1 0 1.5 2\n3 1 1 2.5 0\n4 0 1 3.5 4\n";
  std::ofstream(kOut + "/marked.ele") << "2 3 1\n1 1 2 3 10\n2 1 3 4 20\n";
  reader->SetFileName((kOut + "/marked.ele").c_str());
  reader->Update();
  vtkUnstructuredGrid* marked = reader->GetOutput();
  vtkDataArray* markers = marked->GetPointData()->GetArray("BoundaryMarker");
  vtkDataArray* attributes = marked->GetPointData()->GetArray("PointAttributes");
  vtkDataArray* region = marked->GetCellData()->GetArray("Region");
  CHECK(markers && markers->GetNumberOfTuples() == 4 && markers->GetComponent(1, 0) == 2 &&
    markers->GetComponent(2, 0) == 0);
  CHECK(attributes && attributes->GetNumberOfTuples() == 4 && attributes->GetComponent(3, 0) == 3.5);
  CHECK(region && region->GetComponent(0, 0) == 10 && region->GetComponent(1, 0) == 20);
}

// Malformed or missing files: an error naming the file and line, and an empty output.
void TestBrokenFiles()
{
  vtkNew<vtkTriangleTetGenReader> reader;
  EventLog log;
  log.Watch(reader);
  reader->SetFileName((kData + "/broken_truncated.poly").c_str());
  reader->Update();
  CHECK(log.ErrorContains("IoError"));
  CHECK(log.ErrorContains("broken_truncated.poly:5"));
  CHECK(reader->GetOutput()->GetNumberOfPoints() == 0);
  log.Clear();
  reader->SetFileName((kOut + "/no_such_file.poly").c_str());
  reader->Update();
  CHECK(log.ErrorContains("no_such_file.poly"));

  vtkNew<vtkTriangleTetGenMeshReader> meshReader;
  log.Clear();
  log.Watch(meshReader);
  meshReader->SetFileName((kData + "/broken_tet.ele").c_str());
  meshReader->Update();
  CHECK(!log.Errors.empty());
  CHECK(meshReader->GetOutput()->GetNumberOfCells() == 0);
}
}

int main(int argc, char* argv[])
{
  const std::map<std::string, std::function<void()>> tests = {
    { "TrianglePoly", TestTrianglePoly },
    { "TriangleRegions", TestTriangleRegions },
    { "TriangleMarkers", TestTriangleMarkers },
    { "TriangleNode", TestTriangleNode },
    { "TetGenPoly", TestTetGenPoly },
    { "Off", TestOff },
    { "MeshFiles", TestMeshFiles },
    { "BrokenFiles", TestBrokenFiles },
  };
  return gdr_test::RunNamedTest(argc, argv, tests);
}
