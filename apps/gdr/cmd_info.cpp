// `gdr info`: what an input file holds (kind, counts, bounding box) and whether the 2D
// mesher accepts it.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include "args.h"
#include "cli.h"
#include "gdr/io.h"
#include "gdr/refine2d.h"
#include "table.h"

namespace gdr::cli {

namespace {

const char* kHelpInfo = R"(gdr info - describe an input file

Usage:
  gdr info INPUT

Prints the kind of input (2D planar straight-line graph or 3D surface), its counts and
bounding box. For a 2D input it also says whether 'gdr 2d' accepts it as it is (crossing
segments, duplicate points and other problems are named).

Supported inputs: Triangle .poly/.node (2D), TetGen .poly/.smesh, .off, .stl, .ply, .obj
(3D surfaces).

Example:
  gdr info shape.poly
)";

double coord_z(const Point2&) { return 0.0; }
double coord_z(const Point3& p) { return p.z; }

template <typename P>
std::string bbox_line(const std::vector<P>& pts, bool three_d) {
  if (pts.empty()) return "(empty)";
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-lo[0], -lo[1], -lo[2]};
  for (const auto& p : pts) {
    const double c[3] = {p.x, p.y, three_d ? coord_z(p) : 0.0};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], c[k]);
      hi[k] = std::max(hi[k], c[k]);
    }
  }
  char buf[256];
  if (three_d)
    std::snprintf(buf, sizeof buf, "[%.6g, %.6g] x [%.6g, %.6g] x [%.6g, %.6g]", lo[0], hi[0], lo[1],
                  hi[1], lo[2], hi[2]);
  else
    std::snprintf(buf, sizeof buf, "[%.6g, %.6g] x [%.6g, %.6g]", lo[0], hi[0], lo[1], hi[1]);
  return buf;
}

}  // namespace

int run_info(const std::vector<std::string>& args) {
  bool help = false;
  const auto positional =
      parse_options("info", args, {{"help", 'h', false, [&](const std::string&) { help = true; }}});
  if (help) {
    std::fputs(kHelpInfo, stdout);
    return kExitOk;
  }
  if (positional.size() != 1)
    throw UsageError("info", positional.empty() ? "missing INPUT file"
                                                : "unexpected argument '" + positional[1] + "'");
  const std::string& path = positional[0];
  if (!std::filesystem::exists(path)) throw Error(Status::IoError, path + ": no such file");

  Table tab(Table::Align::Left);
  tab.row({path});
  if (io::detect_input_kind(path) == io::InputKind::Pslg2d) {
    const Pslg pslg = io::read_poly(path);
    std::vector<char> used(pslg.points.size(), 0);
    for (const auto& s : pslg.segments)
      for (const int v : s)
        if (v >= 0 && static_cast<std::size_t>(v) < used.size()) used[v] = 1;
    const auto isolated = std::count(used.begin(), used.end(), 0);
    tab.row({"kind", "2D planar straight-line graph"});
    tab.row({"points", with_commas(static_cast<long long>(pslg.points.size()))});
    tab.row({"  not on any segment", with_commas(isolated)});
    tab.row({"segments", with_commas(static_cast<long long>(pslg.segments.size()))});
    tab.row({"holes", with_commas(static_cast<long long>(pslg.holes.size()))});
    tab.row({"bounding box", bbox_line(pslg.points, false)});
    std::string verdict = "accepted by 'gdr 2d'";
    try {
      validate_refine2d_input(pslg, Refine2dOptions{});
    } catch (const Error& e) {
      verdict = std::string("refused (") + to_string(e.status()) + "): " + e.what();
    }
    tab.row({"mesher input check", verdict});
  } else {
    const Surface s = io::read_surface(path);
    tab.row({"kind", "3D surface (piecewise linear complex)"});
    tab.row({"points", with_commas(static_cast<long long>(s.points.size()))});
    tab.row({"triangles", with_commas(static_cast<long long>(s.triangles.size()))});
    tab.row({"segments", with_commas(static_cast<long long>(s.segments.size()))});
    tab.row({"bounding box", bbox_line(s.points, true)});
  }
  tab.print(std::cout);
  return kExitOk;
}

}  // namespace gdr::cli
