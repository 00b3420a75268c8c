// TetGen 1.5 baseline through libtet: tetrahedralizes a closed surface (.off, .stl, TetGen
// .poly/.smesh read by gdr::io) with TetGen's own switches (e.g. "pq1.4a0.01").
// Prints one JSON line for gdr_bench.
#define TETLIBRARY
#include <tetgen.h>

#include <array>
#include <chrono>
#include <iostream>
#include <string>
#include <vector>

#include "gdr/error.h"
#include "gdr/io.h"
#include "json_line.h"
#include "tet_quality.h"

namespace {

gdr::Surface read_surface(const std::string& path) {
  const auto dot = path.rfind('.');
  const std::string ext = dot == std::string::npos ? "" : path.substr(dot);
  if (ext == ".off") return gdr::io::read_off(path);
  if (ext == ".stl") return gdr::io::read_stl(path);
  return gdr::io::read_tetgen_poly(path);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3 || std::string(argv[1]) == "--help") {
    std::cerr << "usage: bench_tetgen SURFACE.(off|stl|poly|smesh) [SWITCHES]\n"
                 "  SWITCHES are TetGen's, without '-' (default pq1.4); Q is added\n";
    return argc == 2 ? 0 : 2;
  }
  const std::string input = argv[1];
  std::string switches = argc == 3 ? argv[2] : "pq1.4";
  if (!switches.empty() && switches[0] == '-') switches.erase(0, 1);

  gdr_bench::JsonLine out;
  out.add("runner", "tetgen").add("input", input).add("switches", switches);
  try {
    const gdr::Surface surface = read_surface(input);
    tetgenio in, result;
    in.firstnumber = 0;
    in.numberofpoints = static_cast<int>(surface.points.size());
    in.pointlist = new REAL[3 * surface.points.size()];
    for (std::size_t i = 0; i < surface.points.size(); ++i) {
      in.pointlist[3 * i] = surface.points[i].x;
      in.pointlist[3 * i + 1] = surface.points[i].y;
      in.pointlist[3 * i + 2] = surface.points[i].z;
    }
    in.numberoffacets = static_cast<int>(surface.triangles.size());
    in.facetlist = new tetgenio::facet[surface.triangles.size()];
    for (std::size_t i = 0; i < surface.triangles.size(); ++i) {
      tetgenio::facet& f = in.facetlist[i];
      tetgenio::init(&f);
      f.numberofpolygons = 1;
      f.polygonlist = new tetgenio::polygon[1];
      tetgenio::init(&f.polygonlist[0]);
      f.polygonlist[0].numberofvertices = 3;
      f.polygonlist[0].vertexlist = new int[3];
      for (int k = 0; k < 3; ++k) f.polygonlist[0].vertexlist[k] = surface.triangles[i][k];
    }

    tetgenbehavior behavior;
    std::string all = switches + "Q";
    std::vector<char> buffer(all.begin(), all.end());
    buffer.push_back('\0');
    if (!behavior.parse_commandline(buffer.data()))
      throw gdr::Error(gdr::Status::InvalidInput, "TetGen rejected switches '" + switches + "'");

    const auto t0 = std::chrono::steady_clock::now();
    tetrahedralize(&behavior, &in, &result);
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

    gdr_bench::TetQuality q;
    const int corners = result.numberofcorners;
    auto point = [&](int i) {
      const int k = i - result.firstnumber;
      return std::array<double, 3>{result.pointlist[3 * k], result.pointlist[3 * k + 1],
                                   result.pointlist[3 * k + 2]};
    };
    for (int t = 0; t < result.numberoftetrahedra; ++t) {
      const int* v = result.tetrahedronlist + static_cast<std::size_t>(t) * corners;
      q.add(point(v[0]), point(v[1]), point(v[2]), point(v[3]));
    }
    out.add("status", "ok")
        .add("input_points", static_cast<long long>(surface.points.size()))
        .add("input_triangles", static_cast<long long>(surface.triangles.size()))
        .add("total_seconds", seconds)
        .add("refine_seconds", seconds)
        .add("points", static_cast<long long>(result.numberofpoints))
        .add("tets", static_cast<long long>(result.numberoftetrahedra))
        .add("steiner_points",
             static_cast<long long>(result.numberofpoints) -
                 static_cast<long long>(surface.points.size()))
        .add("min_dihedral_deg", q.tets ? q.min_dihedral_deg : 0.0)
        .add("max_dihedral_deg", q.max_dihedral_deg)
        .add("max_radius_edge", q.max_radius_edge)
        .add("volume", q.volume);
    out.print();
    return 0;
  } catch (int code) {
    // TetGen's library mode reports failures by throwing its exit code.
    out.add("status", "error").add("message", "TetGen failed with code " + std::to_string(code));
  } catch (const std::exception& e) {
    out.add("status", "error").add("message", e.what());
  }
  out.print();
  return 1;
}
