// 3D surface readers: PLY (ASCII, binary little and big endian), OBJ, TetGen .poly with hole
// and region lists, polygons as facets, letter case of extensions, malformed files. Every
// file is written here, into a temporary folder.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "gdr/error.h"
#include "gdr/io.h"
#include "gdr/validate.h"

namespace {

using namespace gdr;

const std::string kDir = [] {
  const auto p = std::filesystem::temp_directory_path() / ("gdr_read_surface_test_" + std::to_string(::getpid()));
  std::filesystem::create_directories(p);
  return p.string();
}();

// Removes the folder when the tests end.
const struct Cleanup {
  ~Cleanup() {
    std::error_code ec;
    std::filesystem::remove_all(kDir, ec);
  }
} cleanup;

std::string write(const std::string& name, const std::string& bytes) {
  const std::string path = kDir + "/" + name;
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

double volume(const Surface& s) {
  double v = 0;
  for (const auto& t : s.triangles) v += tet_volume(s.points[t[0]], s.points[t[1]], s.points[t[2]], Point3{});
  return v;
}

// The IoError message of `read`, "" if none.
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

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// The unit cube: 8 corners (bit 0 = x, 1 = y, 2 = z), 6 quads counter-clockwise from outside.
const double kCorner[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                              {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
const int kQuad[6][4] = {{0, 4, 6, 2}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 2, 3, 1}, {4, 5, 7, 6}};

// Checks a cube read from a file: 12 triangles, two per quad sharing the quad's facet id.
void expect_cube(const Surface& s) {
  ASSERT_EQ(s.points.size(), 8u);
  ASSERT_EQ(s.triangles.size(), 12u);
  ASSERT_EQ(s.triangle_facet.size(), 12u);
  for (int t = 0; t < 12; ++t) EXPECT_EQ(s.triangle_facet[t], t / 2);
  EXPECT_DOUBLE_EQ(volume(s), 1.0);
}

std::string ply_ascii_cube() {
  std::string s = "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 8\nproperty float x\n"
                  "property float y\nproperty float z\nproperty uchar red\nelement face 6\n"
                  "property list uchar int vertex_indices\nproperty int flags\nelement edge 1\n"
                  "property int vertex1\nproperty int vertex2\nend_header\n";
  for (const auto& c : kCorner)
    s += std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + " 255\n";
  for (const auto& q : kQuad)
    s += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " +
         std::to_string(q[3]) + " 7\n";
  return s + "0 1\n";
}

template <class T>
void put(std::string& out, T v, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

std::string ply_binary_cube(bool big) {
  std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 8\nproperty double x\nproperty float y\nproperty double z\n"
                  "property list uchar float texcoord\nelement face 6\n"
                  "property list ushort uint vertex_index\nend_header\n";
  for (const auto& c : kCorner) {
    put<double>(s, c[0], big);
    put<float>(s, static_cast<float>(c[1]), big);
    put<double>(s, c[2], big);
    put<std::uint8_t>(s, 2, big);
    put<float>(s, 0.5f, big);
    put<float>(s, 0.25f, big);
  }
  for (const auto& q : kQuad) {
    put<std::uint16_t>(s, 4, big);
    for (int k = 0; k < 4; ++k) put<std::uint32_t>(s, static_cast<std::uint32_t>(q[k]), big);
  }
  return s;
}

TEST(ReadPly, AsciiQuadsBecomeFacets) { expect_cube(io::read_ply(write("cube_ascii.ply", ply_ascii_cube()))); }

TEST(ReadPly, BinaryBothByteOrders) {
  const Surface a = io::read_ply(write("cube_ascii2.ply", ply_ascii_cube()));
  for (bool big : {false, true}) {
    const Surface b = io::read_ply(write(big ? "cube_be.ply" : "cube_le.ply", ply_binary_cube(big)));
    expect_cube(b);
    for (int i = 0; i < 8; ++i) {
      EXPECT_EQ(b.points[i].x, a.points[i].x);
      EXPECT_EQ(b.points[i].y, a.points[i].y);
      EXPECT_EQ(b.points[i].z, a.points[i].z);
    }
    EXPECT_EQ(b.triangles, a.triangles);
  }
}

TEST(ReadPly, TrianglesOnlyLeaveTriangleFacetEmpty) {
  const std::string s = "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                        "property double z\nelement face 4\nproperty list uchar int vertex_indices\nend_header\n"
                        "0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";
  const Surface t = io::read_ply(write("tet.ply", s));
  EXPECT_EQ(t.triangles.size(), 4u);
  EXPECT_TRUE(t.triangle_facet.empty());
  EXPECT_DOUBLE_EQ(volume(t), 1.0 / 6);
}

TEST(ReadPly, MalformedFilesGiveIoErrors) {
  std::string truncated = ply_binary_cube(false);
  truncated.resize(truncated.size() - 3);
  EXPECT_TRUE(has(io_error([&] { io::read_ply(write("trunc.ply", truncated)); }), "trunc.ply")) << "truncated";
  std::string bad_index = ply_ascii_cube();
  bad_index.replace(bad_index.find("4 0 4 6 2"), 9, "4 0 4 6 9");
  const std::string e1 = io_error([&] { io::read_ply(write("bad_index.ply", bad_index)); });
  EXPECT_TRUE(has(e1, "bad_index.ply:24: face 0 refers to vertex 9,")) << e1;
  const std::string e2 = io_error([&] { io::read_ply(write("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\n")); });
  EXPECT_TRUE(has(e2, "no_end.ply:4: unexpected end of file")) << e2;
  const std::string e3 = io_error([&] {
    io::read_ply(write("huge.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\n"
                                   "property float x\nproperty float y\nproperty float z\nelement face 0\n"
                                   "property list uchar int vertex_indices\nend_header\n"));
  });
  EXPECT_TRUE(has(e3, "larger than the file can hold")) << e3;
  const std::string e4 = io_error([&] { io::read_ply(write("noxyz.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nend_header\n0\n")); });
  EXPECT_TRUE(has(e4, "x, y and z")) << e4;
}

TEST(ReadObj, PolygonsIndexFormsAndNegativeIndices) {
  std::string s = "# a cube\nmtllib none.mtl\no cube\n";
  for (const auto& c : kCorner)
    s += "v " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
  s += "vt 0 0\nvn 0 0 1\ng faces\ns off\n";
  // Quad 0 with plain indices, quad 1 with v/vt, quad 2 with v//vn, quad 3 with v/vt/vn,
  // quads 4 and 5 with negative indices (-8 is the first vertex).
  auto idx = [](int v, int form) {
    const std::string i = std::to_string(v + 1);
    switch (form) {
      case 1: return i + "/1";
      case 2: return i + "//1";
      case 3: return i + "/1/1";
      case 4: return std::to_string(v - 8);
      default: return i;
    }
  };
  for (int f = 0; f < 6; ++f) {
    s += "f";
    for (int k = 0; k < 4; ++k) s += " " + idx(kQuad[f][k], f < 4 ? f : 4);
    s += "\n";
  }
  expect_cube(io::read_obj(write("cube.obj", s)));
}

TEST(ReadObj, MalformedFilesGiveIoErrors) {
  const std::string base = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n";
  std::string e = io_error([&] { io::read_obj(write("zero.obj", base + "f 0 1 2\n")); });
  EXPECT_TRUE(has(e, "zero.obj:5: face 0 refers to vertex 0")) << e;
  e = io_error([&] { io::read_obj(write("neg.obj", base + "f -1 -2 -5\n")); });
  EXPECT_TRUE(has(e, "neg.obj:5: face 0 refers to vertex -5")) << e;
  e = io_error([&] { io::read_obj(write("far.obj", base + "f 1 2 3\nf 1 2 9\n")); });
  EXPECT_TRUE(has(e, "far.obj:6: face 1 refers to vertex 9")) << e;
  e = io_error([&] { io::read_obj(write("short.obj", base + "f 1 2\n")); });
  EXPECT_TRUE(has(e, "short.obj:5: face 0 has fewer than 3 corners")) << e;
  e = io_error([&] { io::read_obj(write("nan.obj", "v 0 nan 0\n")); });
  EXPECT_TRUE(has(e, "nan.obj:1:")) << e;
  // A bow tie (its two halves cancel: no plane to clip it in).
  e = io_error([&] { io::read_obj(write("bowtie.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nv 2 2 0\nf 1 2 3\nf 1 4 2 3\n")); });
  EXPECT_TRUE(has(e, "bowtie.obj:6: face 1 cannot be triangulated")) << e;
}

TEST(ReadTetgenPoly, HolesAndRegions) {
  std::string s = "8 3 0 0\n";
  for (int i = 0; i < 8; ++i)
    s += std::to_string(i + 1) + " " + std::to_string(kCorner[i][0]) + " " + std::to_string(kCorner[i][1]) + " " +
         std::to_string(kCorner[i][2]) + "\n";
  s += "6 1\n";
  for (const auto& q : kQuad)
    s += "1 0 5\n4 " + std::to_string(q[0] + 1) + " " + std::to_string(q[1] + 1) + " " + std::to_string(q[2] + 1) +
         " " + std::to_string(q[3] + 1) + "\n";
  s += "1\n1 0.5 0.5 0.25\n";                               // one hole
  s += "2\n1 0.5 0.5 0.75 3 0.01\n2 0.1 0.1 0.1 -4\n";      // two regions, one without a bound
  const Surface p = io::read_tetgen_poly(write("box.poly", s));
  expect_cube(p);
  ASSERT_EQ(p.holes.size(), 1u);
  EXPECT_EQ(p.holes[0].z, 0.25);
  ASSERT_EQ(p.regions.size(), 2u);
  EXPECT_EQ(p.regions[0].attribute, 3);
  EXPECT_EQ(p.regions[0].max_volume, 0.01);
  EXPECT_EQ(p.regions[0].point.z, 0.75);
  EXPECT_EQ(p.regions[1].attribute, -4);
  EXPECT_EQ(p.regions[1].max_volume, 0);
  // Holes without regions, and neither.
  const std::string no_regions = s.substr(0, s.find("2\n1 0.5"));
  EXPECT_EQ(io::read_tetgen_poly(write("box_holes.poly", no_regions)).holes.size(), 1u);
  const Surface bare = io::read_tetgen_poly(write("box_bare.poly", s.substr(0, s.find("1\n1 0.5 0.5 0.25"))));
  EXPECT_TRUE(bare.holes.empty() && bare.regions.empty());
  // A fractional attribute is refused with its line.
  std::string bad = s;
  bad.replace(bad.find(" 3 0.01"), 7, " 3.5 0.01");
  const std::string e = io_error([&] { io::read_tetgen_poly(write("bad_region.poly", bad)); });
  EXPECT_TRUE(has(e, "bad_region.poly:26: the attribute of region 0 must be an integer")) << e;
}

TEST(ReadSurface, ExtensionsInAnyCase) {
  const std::string ply = write("CUBE.PLY", ply_ascii_cube());
  EXPECT_EQ(io::detect_input_kind(ply), io::InputKind::Surface3d);
  expect_cube(io::read_surface(ply));
  const std::string obj = write("Tet.Obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 1 4 3\n");
  EXPECT_EQ(io::detect_input_kind(obj), io::InputKind::Surface3d);
  EXPECT_DOUBLE_EQ(volume(io::read_surface(obj)), 1.0 / 6);
  const std::string off = write("quads.OFF", [] {
    std::string s = "OFF\n8 6 0\n";
    for (const auto& c : kCorner)
      s += std::to_string(c[0]) + " " + std::to_string(c[1]) + " " + std::to_string(c[2]) + "\n";
    for (const auto& q : kQuad)
      s += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " +
           std::to_string(q[3]) + "\n";
    return s;
  }());
  expect_cube(io::read_surface(off));
}

}  // namespace
