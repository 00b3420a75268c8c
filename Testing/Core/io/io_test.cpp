#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <set>
#include <string>

#include "gdr/error.h"
#include "gdr/io.h"
#include "gdr/validate.h"

namespace {

using namespace gdr;
const std::string kData = GDR_DATA_DIR;
const std::string kShared = GDR_SHARED_DATA_DIR;
// The build's test folder, or a temporary one where the test program runs elsewhere (the GPU
// machine runs test programs built here).
const std::string kOut = [] {
  std::filesystem::path p = GDR_TEST_OUTPUT_DIR;
  if (!std::filesystem::is_directory(p)) {
    p = std::filesystem::temp_directory_path() / "gdr_io_test";
    std::filesystem::create_directories(p);
  }
  return p.string();
}();

bool exists(const std::string& p) { return std::ifstream(p).good(); }

// Signed volume enclosed by a closed triangulated surface (divergence theorem).
double enclosed_volume(const Surface& s) {
  double v = 0;
  for (const auto& t : s.triangles)
    v += tet_volume(s.points[t[0]], s.points[t[1]], s.points[t[2]], Point3{});
  return v;
}

// The IoError message of reading `path`, "" if it read fine.
template <class F>
std::string io_error(F read) {
  try {
    read();
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::IoError) << e.what();
    return e.what();
  }
  return "";
}

TEST(ReadPoly, SquareWithHoleOneBasedWithAttributesAndMarkers) {
  const Pslg p = io::read_poly(kData + "/square_hole.poly");
  ASSERT_EQ(p.points.size(), 8u);
  ASSERT_EQ(p.segments.size(), 8u);
  EXPECT_EQ(p.segments[0][0], 0);
  EXPECT_EQ(p.segments[0][1], 1);
  EXPECT_EQ(p.segments[7][0], 7);
  EXPECT_EQ(p.segments[7][1], 4);
  EXPECT_EQ(p.points[2].x, 4.0);
  EXPECT_EQ(p.points[2].y, 4.0);
  ASSERT_EQ(p.holes.size(), 1u);
  EXPECT_EQ(p.holes[0].x, 2.0);
}

TEST(ReadPoly, SharpAngleZeroBased) {
  const Pslg p = io::read_poly(kData + "/sharp_angle.poly");
  ASSERT_EQ(p.points.size(), 4u);
  ASSERT_EQ(p.segments.size(), 4u);
  EXPECT_EQ(p.segments[3][0], 3);
  EXPECT_EQ(p.segments[3][1], 0);
  const double angle = std::atan2(p.points[3].y, p.points[3].x) * 180 / M_PI;
  EXPECT_NEAR(angle, 5.0, 1e-9);
}

TEST(ReadPoly, EmptyPointSectionReadsNodeBeside) {
  const Pslg p = io::read_poly(kData + "/points_only.poly");
  EXPECT_EQ(p.points.size(), 3u);
  EXPECT_EQ(p.segments.size(), 2u);
  EXPECT_EQ(p.segments[1][1], 2);
  const Pslg n = io::read_poly(kData + "/points_only.node");
  EXPECT_EQ(n.points.size(), 3u);
  EXPECT_TRUE(n.segments.empty());
}

TEST(ReadSurface, OffQuadsAreTriangulatedWithTheirOrientation) {
  const Surface s = io::read_off(kData + "/cube.off");
  EXPECT_EQ(s.points.size(), 8u);
  EXPECT_EQ(s.triangles.size(), 12u);
  EXPECT_DOUBLE_EQ(enclosed_volume(s), 1.0);
}

TEST(ReadSurface, TetgenPolyNonConvexFacetsAreEarClipped) {
  const Surface s = io::read_tetgen_poly(kData + "/lshape.poly");
  EXPECT_EQ(s.points.size(), 12u);
  EXPECT_EQ(s.triangles.size(), 2u * 4 + 6u * 2);
  EXPECT_DOUBLE_EQ(enclosed_volume(s), 3.0);
}

TEST(ReadSurface, TetgenSmesh) {
  const Surface s = io::read_surface(kData + "/tet.smesh");
  EXPECT_EQ(s.points.size(), 4u);
  EXPECT_EQ(s.triangles.size(), 4u);
  EXPECT_DOUBLE_EQ(std::fabs(enclosed_volume(s)), 1.0 / 6);
}

TEST(ReadSurface, StlAsciiAndBinaryMergeIdenticalVertices) {
  for (const char* name : {"/tet_ascii.stl", "/tet_binary.stl"}) {
    const Surface s = io::read_stl(kData + name);
    EXPECT_EQ(s.points.size(), 4u) << name;  // -0 and 0 merge too
    EXPECT_EQ(s.triangles.size(), 4u) << name;
    EXPECT_DOUBLE_EQ(enclosed_volume(s), 1.0 / 6) << name;
  }
}

TEST(DetectInputKind, ByExtensionAndHeader) {
  EXPECT_EQ(io::detect_input_kind(kData + "/square_hole.poly"), io::InputKind::Pslg2d);
  EXPECT_EQ(io::detect_input_kind(kData + "/lshape.poly"), io::InputKind::Surface3d);
  EXPECT_EQ(io::detect_input_kind(kData + "/points_only.node"), io::InputKind::Pslg2d);
  EXPECT_EQ(io::detect_input_kind(kData + "/cube.off"), io::InputKind::Surface3d);
  EXPECT_EQ(io::detect_input_kind(kData + "/tet_binary.stl"), io::InputKind::Surface3d);
  EXPECT_EQ(io::detect_input_kind(kData + "/tet.smesh"), io::InputKind::Surface3d);
  EXPECT_NE(io_error([] { io::detect_input_kind("mesh.xyz"); }).find("unsupported"),
            std::string::npos);
  // A .node is Triangle's (2D) or TetGen's (3D) by its header, like a .poly.
  EXPECT_EQ(io::detect_input_kind(kData + "/lshape_tetgen.node"), io::InputKind::Surface3d);
}

TEST(ElementFileDimension, TriangleOrTetgenByNodesPerElement) {
  EXPECT_EQ(io::element_file_dimension(kData + "/lshape_tetgen.ele"), 3);
  const std::string tri = kOut + "/two_triangles.ele";
  std::ofstream(tri) << "2 3 0\n1 1 2 3\n2 1 3 4\n";
  EXPECT_EQ(io::element_file_dimension(tri), 2);
  const std::string bad = kOut + "/five_corners.ele";
  std::ofstream(bad) << "1 5 0\n1 1 2 3 4 5\n";
  EXPECT_NE(io_error([&] { io::element_file_dimension(bad); }).find("nodes per element"),
            std::string::npos);
}

TEST(ReadSurface, TetgenNodeGivesPointsWithoutFacets) {
  const Surface s = io::read_surface(kData + "/lshape_tetgen.node");
  EXPECT_EQ(s.points.size(), 12u);
  EXPECT_TRUE(s.triangles.empty());
  EXPECT_EQ(s.points[1].x, 2.0);
}

struct Broken {
  const char* file;
  int line;
  const char* reason;  // a fragment of the message
};

TEST(BrokenFiles, EveryOneIsAnIoErrorWithItsLine) {
  const Broken cases[] = {
      {"broken_truncated.poly", 5, "unexpected end of file"},
      {"broken_bad_number.node", 3, "bad number 'abc'"},
      {"broken_index_range.poly", 7, "out of range"},
      {"broken_nan.node", 4, "point 2"},
      {"broken_nonconsecutive.node", 4, "consecutively"},
      {"broken_count.off", 2, "larger than the file"},
      {"broken_face_index.off", 6, "out of range"},
      {"broken_inf.off", 5, "point 2"},
      {"broken_ascii.stl", 7, "expected 'endloop'"},
      {"broken_facet_hole.poly", 7, "holes"},
      {"broken_dimension.poly", 2, "dimension"},
      {"broken_tet.ele", 2, "out of range"},
  };
  for (const Broken& c : cases) {
    const std::string path = kData + "/" + c.file;
    const std::string ext = path.substr(path.rfind('.'));
    const std::string msg = io_error([&] {
      if (ext == ".off") io::read_off(path);
      else if (ext == ".stl") io::read_stl(path);
      else if (ext == ".ele") io::read_tetgen_mesh(kData + "/broken_tet.node", path);
      else if (std::string(c.file) == "broken_facet_hole.poly") io::read_tetgen_poly(path);
      else io::read_poly(path);
    });
    EXPECT_NE(msg.find(path + ":" + std::to_string(c.line) + ": "), std::string::npos)
        << c.file << ": " << msg;
    EXPECT_NE(msg.find(c.reason), std::string::npos) << c.file << ": " << msg;
  }
  const std::string stl = io_error([] { io::read_stl(kData + "/broken_binary_size.stl"); });
  EXPECT_NE(stl.find("does not match"), std::string::npos) << stl;
  EXPECT_NE(io_error([] { io::read_poly(kData + "/no_such_file.poly"); }).find("cannot open"),
            std::string::npos);
}

TEST(BrokenFiles, EveryTruncationOfAGoodFileFailsCleanly) {
  // Cutting a file anywhere must give an IoError (or a smaller valid file), never a crash.
  std::ifstream in(kData + "/lshape.poly", std::ios::binary);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string path = kOut + "/truncated.poly";
  int errors = 0;
  for (std::size_t n = 0; n < text.size(); n += 7) {
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text.substr(0, n);
    try {
      io::read_tetgen_poly(path);
    } catch (const Error& e) {
      EXPECT_EQ(e.status(), Status::IoError);
      ++errors;
    }
  }
  EXPECT_GT(errors, 0);
}

TEST(BrokenFiles, SingleByteCorruptionsGiveIoErrorsOnly) {
  // Every third byte of each good file replaced by troublesome characters: the readers
  // either accept the result or throw IoError, nothing else.
  const char* files[] = {"square_hole.poly", "sharp_angle.poly", "cube.off", "lshape.poly",
                         "tet.smesh", "tet_ascii.stl", "tet_binary.stl"};
  for (const char* name : files) {
    std::ifstream in(kData + "/" + name, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::string ext = std::string(name).substr(std::string(name).rfind('.'));
    const std::string path = kOut + "/corrupt" + ext;
    for (std::size_t i = 0; i < text.size(); i += 3) {
      for (char c : {'-', 'x', '\n'}) {
        std::string bad = text;
        bad[i] = c;
        std::ofstream(path, std::ios::binary | std::ios::trunc) << bad;
        try {
          if (ext == ".off") io::read_off(path);
          else if (ext == ".stl") io::read_stl(path);
          else if (io::detect_input_kind(path) == io::InputKind::Pslg2d) io::read_poly(path);
          else io::read_tetgen_poly(path);
        } catch (const Error& e) {
          ASSERT_EQ(e.status(), Status::IoError) << name << " byte " << i << ": " << e.what();
        }
      }
    }
  }
}

TEST(SharedData, AllPslgsAndSurfacesRead) {
  if (!exists(kShared + "/README.md")) GTEST_SKIP() << "no shared data at " << kShared;
  const struct {
    const char* name;
    std::size_t points, segments;
  } pslgs[] = {{"world_land_110m", 5002, 4999},
               {"us_counties_albers", 25227, 28377},
               {"contours_topobathy_200m", 30249, 30414}};
  for (const auto& c : pslgs) {
    const std::string path = kShared + "/pslg/" + c.name + ".poly";
    EXPECT_EQ(io::detect_input_kind(path), io::InputKind::Pslg2d);
    const Pslg p = io::read_poly(path);
    EXPECT_EQ(p.points.size(), c.points) << c.name;
    EXPECT_EQ(p.segments.size(), c.segments) << c.name;
  }
  const struct {
    const char* name;
    std::size_t points, triangles;
  } surfaces[] = {{"thingi10k_65778", 260, 480}, {"thingi10k_288351", 288, 552},
                  {"fandisk", 6475, 12946},      {"spot", 11533, 23062},
                  {"penguin_hr", 13442, 26880},  {"boat", 16210, 32416}};
  for (const auto& c : surfaces) {
    const Surface s = io::read_surface(kShared + "/surfaces/" + c.name + ".off");
    EXPECT_EQ(s.points.size(), c.points) << c.name;
    EXPECT_EQ(s.triangles.size(), c.triangles) << c.name;
    EXPECT_GT(enclosed_volume(s), 0) << c.name;  // outward normals, as the README says
  }
}

// A strip of ccw triangles; point i has x = 0.1 * i (read_vtk.py checks the last one).
TriMesh strip(int n) {
  TriMesh m;
  for (int i = 0; i < n; ++i) {
    m.points.push_back({0.1 * i, static_cast<double>(i % 2)});
    m.point_type.push_back(i < 2 ? PointType::Input : PointType::Free);
  }
  for (int i = 0; i + 2 < n; ++i)
    m.triangles.push_back(i % 2 == 0 ? std::array<int, 3>{i, i + 2, i + 1}
                                     : std::array<int, 3>{i, i + 1, i + 2});
  m.subsegments = {{0, 2}, {1, 3}};
  m.subsegment_source = {0, -1};
  m.subsegment_markers = {3, 1};
  return m;
}

TetMesh one_tet_pair() {
  TetMesh m;
  m.points = {{0, 0, 0}, {0.1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.4, 1, 1}};
  m.tets = {{1, 0, 2, 3}, {2, 1, 3, 4}};  // positive: orient3d > 0
  m.subfaces = {{0, 2, 1}};
  m.point_type.assign(5, PointType::Input);
  return m;
}

void check_with_vtk(const std::string& path, std::size_t points, std::size_t cells, int type,
                    const std::string& arrays) {
  const std::string cmd = "/usr/bin/python3 " + std::string(GDR_VTK_CHECK_SCRIPT) + " " + path +
                          " " + std::to_string(points) + " " + std::to_string(cells) + " " +
                          std::to_string(type) + " " + arrays;
  if (!exists("/usr/bin/python3")) GTEST_SKIP() << "no /usr/bin/python3";
  const int rc = std::system(cmd.c_str());
  if (WIFEXITED(rc) && WEXITSTATUS(rc) == 77) GTEST_SKIP() << "python3 has no vtk";
  EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << cmd;
}

TEST(Write, TriangleRoundTripIsExact) {
  const TriMesh m = strip(9);
  io::write_mesh(kOut + "/strip.ele", m);
  const TriMesh r = io::read_triangle_mesh(kOut + "/strip.node", kOut + "/strip.ele");
  ASSERT_EQ(r.points.size(), m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    EXPECT_EQ(r.points[i].x, m.points[i].x);
    EXPECT_EQ(r.points[i].y, m.points[i].y);
  }
  EXPECT_EQ(r.triangles, m.triangles);
  EXPECT_EQ(r.subsegments, m.subsegments);
  EXPECT_EQ(r.subsegment_markers, m.subsegment_markers);  // Triangle's boundary markers
  EXPECT_TRUE(validate_trimesh(r, nullptr).valid);
}

TEST(Write, TetgenRoundTripIsExact) {
  const TetMesh m = one_tet_pair();
  io::write_mesh(kOut + "/pair.node", m);
  const TetMesh r = io::read_tetgen_mesh(kOut + "/pair.node", kOut + "/pair.ele");
  ASSERT_EQ(r.points.size(), m.points.size());
  EXPECT_EQ(r.points[1].x, 0.1);
  EXPECT_EQ(r.tets, m.tets);
  EXPECT_EQ(r.subfaces, m.subfaces);
}

TEST(Write, TetgenFilesUseTetgensOrientation) {
  // Data/lshape_tetgen.* is TetGen 1.5's `tetgen -pq lshape.poly` output.
  const TetMesh m = io::read_tetgen_mesh(kData + "/lshape_tetgen.node", kData + "/lshape_tetgen.ele");
  EXPECT_EQ(m.tets.size(), 12u);
  EXPECT_FALSE(m.subfaces.empty());
  const Surface s = io::read_tetgen_poly(kData + "/lshape.poly");
  const ValidationReport r = validate_tetmesh(m, &s);
  EXPECT_TRUE(r.valid) << r.summary();
  EXPECT_DOUBLE_EQ(r.quality.total_measure, 3.0);
  io::write_tetgen(kOut + "/lshape_again", m);
  std::ifstream a(kData + "/lshape_tetgen.ele"), b(kOut + "/lshape_again.ele");
  std::string la, lb;
  std::getline(a, la), std::getline(a, la);  // skip the headers, compare the first tet
  std::getline(b, lb), std::getline(b, lb);
  auto corners = [](const std::string& line) {
    std::istringstream in(line);
    long long i, v[4];
    in >> i >> v[0] >> v[1] >> v[2] >> v[3];
    return std::vector<long long>(v, v + 4);
  };
  std::vector<long long> ca = corners(la), cb = corners(lb);
  for (auto& v : ca) v -= 1;  // TetGen wrote 1-based, we write 0-based
  EXPECT_EQ(ca, cb);
}

// Two unit cubes side by side along x, six Kuhn tetrahedra each, regions 1 and 2; the
// subfaces are the box sides (facets 0-5: x=0, x=2, y=0, y=1, z=0, z=1) and the internal
// facet x=1 (facet 6). x is scaled so that the last point has x = 0.1 * 11 (read_vtk.py).
TetMesh two_cubes() {
  TetMesh m;
  const double sx = 0.1 * 11 / 2;
  auto id = [](int i, int j, int k) { return (k * 2 + j) * 3 + i; };
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 3; ++i) {
        m.points.push_back({sx * i, 1.0 * j, 1.0 * k});
        m.point_type.push_back(i == 1 ? PointType::Facet : PointType::Input);
      }
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = 0; i < 2; ++i)
    for (const auto& p : perms) {
      int c[3] = {i, 0, 0};
      std::array<int, 4> t;
      t[0] = id(c[0], c[1], c[2]);
      for (int s = 0; s < 3; ++s) {
        ++c[p[s]];
        t[s + 1] = id(c[0], c[1], c[2]);
      }
      const auto& q = m.points;
      if (tet_volume(q[t[0]], q[t[1]], q[t[2]], q[t[3]]) < 0) std::swap(t[2], t[3]);
      m.tets.push_back(t);
      m.tet_region.push_back(i + 1);
    }
  // A face is a subface when its corners share a grid plane x = 0, 1, 2, y or z = 0, 1.
  std::set<std::array<int, 3>> seen;
  for (const auto& t : m.tets)
    for (int f = 0; f < 4; ++f) {
      std::array<int, 3> face;  // the corners other than corner f
      for (int k = 0, n = 0; k < 4; ++k)
        if (k != f) face[n++] = t[k];
      std::array<int, 3> key = face;
      std::sort(key.begin(), key.end());
      if (!seen.insert(key).second) continue;
      auto plane = [&](int axis, int value) {
        for (int v : face)
          if ((axis == 0 ? v % 3 : axis == 1 ? (v / 3) % 2 : v / 6) != value) return false;
        return true;
      };
      const int facet = plane(0, 0) ? 0 : plane(0, 2) ? 1 : plane(1, 0) ? 2 : plane(1, 1) ? 3
                      : plane(2, 0) ? 4 : plane(2, 1) ? 5 : plane(0, 1) ? 6 : -1;
      if (facet < 0) continue;
      m.subfaces.push_back(face);
      m.subface_facet.push_back(facet);
    }
  return m;
}

void expect_same_mesh(const TetMesh& a, const TetMesh& b) {
  ASSERT_EQ(a.points.size(), b.points.size());
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    EXPECT_EQ(a.points[i].x, b.points[i].x);
    EXPECT_EQ(a.points[i].y, b.points[i].y);
    EXPECT_EQ(a.points[i].z, b.points[i].z);
  }
  EXPECT_EQ(a.tets, b.tets);
  EXPECT_EQ(a.subfaces, b.subfaces);
  EXPECT_EQ(a.subface_facet, b.subface_facet);
  EXPECT_EQ(a.tet_region, b.tet_region);
}

TEST(Write, TwoCubesFixtureIsValid) {
  const TetMesh m = two_cubes();
  EXPECT_EQ(m.tets.size(), 12u);
  EXPECT_EQ(m.subfaces.size(), 2u * 10 + 2);  // 10 box squares and the internal one
  const ValidationReport r = validate_tetmesh(m, nullptr);
  EXPECT_TRUE(r.valid) << r.summary();
  EXPECT_DOUBLE_EQ(r.quality.total_measure, 1.1);
}

TEST(Write, TetgenRoundTripKeepsRegionsAndFacets) {
  const TetMesh m = two_cubes();
  io::write_mesh(kOut + "/cubes.face", m);
  for (const std::string& f : io::tetmesh_output_files(kOut + "/cubes.face"))
    EXPECT_TRUE(exists(f)) << f;
  TetMesh r = io::read_tetgen_mesh(kOut + "/cubes.node", kOut + "/cubes.ele");
  r.point_type = m.point_type;  // .node files carry no point types
  expect_same_mesh(m, r);
  EXPECT_TRUE(validate_tetmesh(r, nullptr).valid);
}

// A small Medit reader: the sections write_medit writes, each "Keyword count" then rows.
struct MeditMesh {
  TetMesh mesh;
  std::vector<int> vertex_ref, tet_ref, triangle_ref;
  int version = 0, dimension = 0;
  bool end = false;
};

MeditMesh read_medit(const std::string& path) {
  std::ifstream in(path);
  MeditMesh r;
  std::string keyword;
  auto rows = [&](int corners, auto add) {
    std::size_t n = 0;
    in >> n;
    for (std::size_t i = 0; i < n; ++i) {
      std::array<int, 4> v{};
      for (int k = 0; k < corners; ++k) {
        in >> v[k];
        --v[k];  // 1-based
      }
      int ref = 0;
      in >> ref;
      add(v, ref);
    }
  };
  while (in >> keyword) {
    if (keyword == "MeshVersionFormatted") {
      in >> r.version;
    } else if (keyword == "Dimension") {
      in >> r.dimension;
    } else if (keyword == "Vertices") {
      std::size_t n = 0;
      in >> n;
      for (std::size_t i = 0; i < n; ++i) {
        Point3 p;
        int ref = 0;
        in >> p.x >> p.y >> p.z >> ref;
        r.mesh.points.push_back(p);
        r.vertex_ref.push_back(ref);
      }
    } else if (keyword == "Tetrahedra") {
      rows(4, [&](const std::array<int, 4>& v, int ref) {
        r.mesh.tets.push_back(v);
        r.tet_ref.push_back(ref);
      });
    } else if (keyword == "Triangles") {
      rows(3, [&](const std::array<int, 4>& v, int ref) {
        r.mesh.subfaces.push_back({v[0], v[1], v[2]});
        r.triangle_ref.push_back(ref);
      });
    } else if (keyword == "End") {
      r.end = true;
    } else {
      ADD_FAILURE() << path << ": unexpected keyword " << keyword;
      break;
    }
  }
  return r;
}

TEST(Write, MeditReadsBackWithItsReferences) {
  const TetMesh m = two_cubes();
  io::write_mesh(kOut + "/cubes.mesh", m);
  MeditMesh r = read_medit(kOut + "/cubes.mesh");
  EXPECT_EQ(r.version, 2);
  EXPECT_EQ(r.dimension, 3);
  EXPECT_TRUE(r.end);
  // Medit's tetrahedra have a positive volume in the usual sense, ours orient3d > 0.
  for (const auto& t : r.mesh.tets) {
    const auto& p = r.mesh.points;
    const Point3 a = p[t[0]], b = p[t[1]], c = p[t[2]], d = p[t[3]];
    const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z;
    const double vx = c.x - a.x, vy = c.y - a.y, vz = c.z - a.z;
    const double wx = d.x - a.x, wy = d.y - a.y, wz = d.z - a.z;
    EXPECT_GT((uy * vz - uz * vy) * wx + (uz * vx - ux * vz) * wy + (ux * vy - uy * vx) * wz, 0);
  }
  for (auto& t : r.mesh.tets) std::swap(t[0], t[1]);
  for (int ref : r.triangle_ref) r.mesh.subface_facet.push_back(ref - 1);
  r.mesh.tet_region = r.tet_ref;
  expect_same_mesh(m, r.mesh);
  for (std::size_t i = 0; i < m.points.size(); ++i)
    EXPECT_EQ(r.vertex_ref[i], static_cast<int>(m.point_type[i]));
  EXPECT_TRUE(validate_tetmesh(r.mesh, nullptr).valid);

  // Without regions and facets: tetrahedra get 1, triangles 0.
  TetMesh plain = m;
  plain.tet_region.clear();
  plain.subface_facet.clear();
  io::write_medit(kOut + "/plain.mesh", plain);
  const MeditMesh p = read_medit(kOut + "/plain.mesh");
  EXPECT_EQ(p.tet_ref, std::vector<int>(12, 1));
  EXPECT_EQ(p.triangle_ref, std::vector<int>(m.subfaces.size(), 0));
}

// Files of more rows than one formatting block (they are formatted in parallel blocks)
// read back in order.
TEST(Write, LargeTetgenAndMeditFilesReadBackInOrder) {
  TetMesh m;
  const int n = 20;  // 20^3 cubes of 6 tetrahedra: 48,000 rows
  auto id = [&](int i, int j, int k) { return (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i) m.points.push_back({0.1 * i, 0.3 * j, 0.7 * k});
  const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (const auto& p : perms) {
          int c[3] = {i, j, k};
          std::array<int, 4> t;
          t[0] = id(c[0], c[1], c[2]);
          for (int s = 0; s < 3; ++s) {
            ++c[p[s]];
            t[s + 1] = id(c[0], c[1], c[2]);
          }
          const auto& q = m.points;
          if (tet_volume(q[t[0]], q[t[1]], q[t[2]], q[t[3]]) < 0) std::swap(t[2], t[3]);
          m.tets.push_back(t);
          m.tet_region.push_back(static_cast<int>(m.tets.size() % 7));
        }
  m.point_type.assign(m.points.size(), PointType::Free);
  io::write_mesh(kOut + "/large.ele", m);
  TetMesh r = io::read_tetgen_mesh(kOut + "/large.node", kOut + "/large.ele");
  expect_same_mesh(m, r);
  io::write_mesh(kOut + "/large.mesh", m);
  MeditMesh e = read_medit(kOut + "/large.mesh");
  for (auto& t : e.mesh.tets) std::swap(t[0], t[1]);
  e.mesh.tet_region = e.tet_ref;
  expect_same_mesh(m, e.mesh);
}

TEST(Write, TetVtuHasVtkOrientationAndRegions) {
  const TetMesh m = two_cubes();
  io::Attributes attr;
  attr.cell_data.push_back({"Volume", 1, std::vector<double>(12, 0.1)});
  attr.cell_data.push_back({"MinDihedralAngle", 1, std::vector<double>(12, 35.26), true});
  io::write_mesh(kOut + "/cubes.vtu", m, attr);
  std::ifstream in(kOut + "/cubes.vtu");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("type=\"Int32\" Name=\"Region\""), std::string::npos);
  EXPECT_NE(text.find("type=\"Float32\" Name=\"MinDihedralAngle\""), std::string::npos);
  // read_vtk.py also checks that every tetrahedron has a positive volume in VTK's convention.
  check_with_vtk(kOut + "/cubes.vtu", 12, 12, 10, "Volume MinDihedralAngle PointType Region");
}

// Raw appended blocks of several lengths, and empty ones, read back in VTK; no base64.
TEST(Write, VtkRawAppendedArraysReadBack) {
  for (int n = 0; n <= 7; n += n == 0 ? 4 : 1) {
    TetMesh m;
    for (int i = 0; i < n; ++i)
      m.points.push_back({0.1 * i, static_cast<double>(i % 2), static_cast<double>(i % 3)});
    io::Attributes attr;
    attr.point_data.push_back({"Id", 1, std::vector<double>(n, 1.0 / 3)});
    const std::string path = kOut + "/points" + std::to_string(n) + ".vtu";
    io::write_vtu(path, m, attr);
    std::ifstream in(path, std::ios::binary);
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("<AppendedData encoding=\"raw\">"), std::string::npos);
    EXPECT_EQ(text.find("format=\"binary\""), std::string::npos);
    check_with_vtk(path, n, 0, 10, "Id");
  }
}

TEST(Write, VtkXmlReadsBackInVtk) {
  const TriMesh m = strip(7);
  io::Attributes attr;
  attr.point_data.push_back({"Height", 1, std::vector<double>(7, 1.5)});
  attr.cell_data.push_back({"MinAngle", 1, std::vector<double>(5, 30.0)});
  attr.cell_data.push_back({"Vector", 3, std::vector<double>(15, 2.0)});
  io::write_mesh(kOut + "/strip.vtu", m, attr);
  io::write_mesh(kOut + "/strip.vtp", m, attr);
  const TetMesh t = one_tet_pair();
  io::Attributes tattr;
  tattr.cell_data.push_back({"Volume", 1, {1.0, 2.0}});
  io::write_mesh(kOut + "/pair.vtu", t, tattr);
  std::ifstream in(kOut + "/strip.vtu");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("Name=\"MinAngle\""), std::string::npos);
  EXPECT_FALSE(exists(kOut + "/strip.vtu.tmp"));
  check_with_vtk(kOut + "/strip.vtu", 7, 5, 5, "Height MinAngle Vector PointType");
  check_with_vtk(kOut + "/strip.vtp", 7, 5, 5, "Height MinAngle PointType");
  check_with_vtk(kOut + "/pair.vtu", 5, 2, 10, "Volume PointType");
}

// Legacy .vtk (issue 15), read back by VTK's own reader with every array: the caller's, the
// point type, and what the mesh carries from Triangle's input (markers, attributes, regions).
TEST(Write, LegacyVtkIsReadByVtk) {
  TriMesh m = strip(7);
  m.point_markers.assign(7, 1);
  m.point_attribute_count = 2;
  m.point_attributes.assign(14, 0.5);
  m.triangle_region.assign(5, 3.0);
  io::Attributes attr;
  attr.cell_data.push_back({"MinAngle", 1, std::vector<double>(5, 30.0)});
  io::write_mesh(kOut + "/strip.vtk", m, attr);
  check_with_vtk(kOut + "/strip.vtk", 7, 5, 5,
                 "MinAngle PointType BoundaryMarker PointAttributes Region");
}

TEST(Write, RefusesUnknownExtensionsAndWrongArraySizes) {
  const TriMesh m = strip(5);
  EXPECT_NE(io_error([&] { io::write_mesh(kOut + "/strip.obj", m); }).find("unsupported"),
            std::string::npos);
  EXPECT_FALSE(io_error([&] { io::write_mesh(kOut + "/pair.vtp", one_tet_pair()); }).empty());
  io::Attributes bad;
  bad.cell_data.push_back({"Short", 1, {1.0}});
  try {
    io::write_vtu(kOut + "/bad.vtu", m, bad);
    ADD_FAILURE() << "wrong array size accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.status(), Status::InvalidInput);
  }
  EXPECT_FALSE(exists(kOut + "/bad.vtu"));
  EXPECT_NE(io_error([&] { io::write_vtu("/nonexistent_dir/x.vtu", m); }).find("cannot open"),
            std::string::npos);
}

}  // namespace
