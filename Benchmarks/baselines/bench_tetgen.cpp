// TetGen 1.5 baseline through libtet: tetrahedralizes a closed surface (.off, .stl, TetGen
// .poly/.smesh read by gdr::io) with TetGen's own switches (e.g. "pq1.4a0.01").
// Timed twice: the CDT alone (the switches without q and a), then the whole run; refinement
// is the difference. The output is measured by gdr::tet_quality, the checker gdr_bench uses
// for our meshes: smallest dihedral angle, tets above the radius-edge bound, and the
// histogram of all dihedral angles. Prints one JSON line for gdr_bench.
#define TETLIBRARY
#include <tetgen.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "gdr/error.h"
#include "gdr/io.h"
#include "gdr/validate.h"
#include "json_line.h"

namespace {

// The switches of the CDT alone: q and a with their numbers left out.
std::string cdt_switches(const std::string& sw) {
  std::string out;
  for (std::size_t i = 0; i < sw.size(); ++i) {
    if (sw[i] != 'q' && sw[i] != 'a') {
      out += sw[i];
      continue;
    }
    while (i + 1 < sw.size() &&
           (std::isdigit(static_cast<unsigned char>(sw[i + 1])) || sw[i + 1] == '.' || sw[i + 1] == '/' ||
            ((sw[i + 1] == 'e' || sw[i + 1] == 'E') && i + 2 < sw.size() &&
             (std::isdigit(static_cast<unsigned char>(sw[i + 2])) || sw[i + 2] == '-'))))
      i += (sw[i + 1] == 'e' || sw[i + 1] == 'E') && sw[i + 2] == '-' ? 2 : 1;
  }
  return out;
}

// Runs TetGen on `in` with `switches` (+Q); returns wall seconds.
double tetrahedralize_timed(const std::string& switches, tetgenio& in, tetgenio& out) {
  tetgenbehavior behavior;
  std::string all = switches + "Q";
  std::vector<char> buffer(all.begin(), all.end());
  buffer.push_back('\0');
  if (!behavior.parse_commandline(buffer.data()))
    throw gdr::Error(gdr::Status::InvalidInput, "TetGen rejected switches '" + switches + "'");
  const auto t0 = std::chrono::steady_clock::now();
  tetrahedralize(&behavior, &in, &out);
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  std::string input, switches = "pq1.4";
  double radius_edge = -1;
  int positional = 0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--radius-edge" && i + 1 < argc) radius_edge = std::atof(argv[++i]);
    else if (a == "--help" || a == "-h") positional = -100;
    else if (positional == 0) input = a, ++positional;
    else if (positional == 1) switches = a, ++positional;
    else positional = -100;
  }
  if (positional < 1) {
    std::cerr << "usage: bench_tetgen SURFACE.(off|stl|poly|smesh) [SWITCHES] [--radius-edge B]\n"
                 "  SWITCHES are TetGen's, without '-' (default pq1.4); Q is added\n"
                 "  B: the radius-edge bound for counting bad tets (default: the q value, else 2)\n";
    return positional == -100 && argc == 2 ? 0 : 2;
  }
  if (!switches.empty() && switches[0] == '-') switches.erase(0, 1);
  if (radius_edge <= 0) {
    const auto q = switches.find('q');
    radius_edge = q != std::string::npos ? std::atof(switches.c_str() + q + 1) : 0;
    if (radius_edge <= 0) radius_edge = 2.0;
  }

  gdr_bench::JsonLine out;
  out.add("runner", "tetgen").add("input", input).add("switches", switches);
  try {
    const gdr::Surface surface = gdr::io::read_surface(input);
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

    // The CDT alone first, then the whole run (CDT again, refinement, TetGen's optimisation).
    const std::string cdt = cdt_switches(switches);
    double cdt_seconds = 0;
    long long cdt_points = -1;
    if (cdt != switches) {
      tetgenio cdt_result;
      cdt_seconds = tetrahedralize_timed(cdt, in, cdt_result);
      cdt_points = cdt_result.numberofpoints;
    }
    const double seconds = tetrahedralize_timed(switches, in, result);
    if (cdt == switches) cdt_seconds = seconds, cdt_points = result.numberofpoints;

    // TetGen's tets are negatively oriented; the measures below do not depend on it.
    gdr::TetMesh mesh;
    mesh.points.resize(result.numberofpoints);
    for (int i = 0; i < result.numberofpoints; ++i)
      mesh.points[i] = {result.pointlist[3 * i], result.pointlist[3 * i + 1], result.pointlist[3 * i + 2]};
    mesh.tets.resize(result.numberoftetrahedra);
    const int corners = result.numberofcorners;
    for (int t = 0; t < result.numberoftetrahedra; ++t) {
      const int* v = result.tetrahedronlist + static_cast<std::size_t>(t) * corners;
      for (int k = 0; k < 4; ++k) mesh.tets[t][k] = v[k] - result.firstnumber;
    }
    const gdr::QualityStats q = gdr::tet_quality(mesh, radius_edge);
    std::ostringstream histogram;
    for (std::size_t b = 0; b < q.histogram.size(); ++b) histogram << (b ? " " : "") << q.histogram[b];

    const long long input_points = static_cast<long long>(surface.points.size());
    out.add("status", "ok")
        .add("input_points", input_points)
        .add("input_triangles", static_cast<long long>(surface.triangles.size()))
        .add("cdt_seconds", cdt_seconds)
        .add("refine_seconds", std::max(0.0, seconds - cdt_seconds))
        .add("total_seconds", seconds)
        .add("cdt_steiner_points", cdt_points - input_points)
        .add("points", static_cast<long long>(result.numberofpoints))
        .add("tets", static_cast<long long>(result.numberoftetrahedra))
        .add("steiner_points", static_cast<long long>(result.numberofpoints) - input_points)
        .add("radius_edge_bound", radius_edge)
        .add("min_dihedral_deg", q.elements ? q.min_dihedral_deg : 0.0)
        .add("max_dihedral_deg", q.max_dihedral_deg)
        .add("max_radius_edge", q.max_radius_edge)
        .add("bad_tets", static_cast<long long>(q.bad_elements))
        .add("bad_tets_percent", q.elements ? 100.0 * double(q.bad_elements) / double(q.elements) : 0.0)
        .add("bad_volume_percent", q.bad_measure_percent)
        .add("volume", q.total_measure)
        .add("dihedral_histogram", histogram.str());
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
