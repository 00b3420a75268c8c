// CGAL Mesh_2 baseline (one thread): constrained Delaunay triangulation of a .poly PSLG, then
// Delaunay refinement with the same bounds as `gdr 2d`. Prints one JSON line for gdr_bench.
//
// CGAL's shape bound B is on the squared sine of a triangle's smallest angle (a face is bad
// when sin^2(min angle) < B), so B = sin^2(theta). Its size bound is a bound on the longest
// edge of a face, the same meaning as --max-edge of gdr 2d.
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesh_vertex_base_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <utility>
#include <vector>

#include "gdr/error.h"
#include "gdr/io.h"
#include "json_line.h"

namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Vb = CGAL::Delaunay_mesh_vertex_base_2<K>;
using Fb = CGAL::Delaunay_mesh_face_base_2<K>;
using Tds = CGAL::Triangulation_data_structure_2<Vb, Fb>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<K, Tds>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Clock = std::chrono::steady_clock;

const double kPi = 3.14159265358979323846;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

double smallest_angle_deg(const K::Point_2& a, const K::Point_2& b, const K::Point_2& c) {
  const double la = std::sqrt(CGAL::squared_distance(b, c));
  const double lb = std::sqrt(CGAL::squared_distance(c, a));
  const double lc = std::sqrt(CGAL::squared_distance(a, b));
  // The smallest angle faces the shortest edge; atan2 of (2*area, dot) is accurate near 0.
  const double area2 = std::abs(CGAL::to_double(CGAL::area(a, b, c))) * 2.0;
  double opp_dot;
  if (la <= lb && la <= lc) opp_dot = (b - a) * (c - a);
  else if (lb <= lc) opp_dot = (a - b) * (c - b);
  else opp_dot = (a - c) * (b - c);
  return std::atan2(area2, opp_dot) * 180.0 / kPi;
}

// Hull mode: the convex hull edges become constraints, as gdr 2d keeps hull edges as
// subsegments when the exterior is kept (Triangle's -c). Mesh_2 needs a constrained boundary.
void constrain_convex_hull(Cdt& cdt) {
  std::vector<std::pair<Cdt::Vertex_handle, Cdt::Vertex_handle>> hull;
  auto fc = cdt.incident_faces(cdt.infinite_vertex()), done = fc;
  do {
    const int i = fc->index(cdt.infinite_vertex());
    if (!fc->is_constrained(i)) {
      // The finite edge opposite the infinite vertex is a hull edge.
      hull.emplace_back(fc->vertex(Cdt::cw(i)), fc->vertex(Cdt::ccw(i)));
    }
  } while (++fc != done);
  for (const auto& e : hull) cdt.insert_constraint(e.first, e.second);
}

void usage() {
  std::cerr << "usage: bench_cgal_mesh2 INPUT.poly [--min-angle DEG] [--max-edge L]"
               " [--domain hull|enclosed]\n"
               "  hull: mesh the convex hull (gdr 2d default); enclosed: only faces enclosed by"
               " segments (CGAL's default, gdr 2d --remove-exterior)\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string input, domain = "hull";
  double min_angle = 20.0, max_edge = 0.0;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--min-angle" && has_value) min_angle = std::atof(argv[++i]);
    else if (a == "--max-edge" && has_value) max_edge = std::atof(argv[++i]);
    else if (a == "--domain" && has_value) domain = argv[++i];
    else if (a == "-h" || a == "--help") { usage(); return 0; }
    else if (input.empty() && a[0] != '-') input = a;
    else { usage(); return 2; }
  }
  if (input.empty() || (domain != "hull" && domain != "enclosed") || min_angle < 0 ||
      min_angle > 34) {
    usage();
    return 2;
  }

  gdr_bench::JsonLine out;
  out.add("runner", "cgal-mesh2").add("input", input);
  try {
    const gdr::Pslg pslg = gdr::io::read_poly(input);
    std::vector<K::Point_2> points;
    points.reserve(pslg.points.size());
    for (const auto& p : pslg.points) points.emplace_back(p.x, p.y);
    std::vector<std::pair<std::size_t, std::size_t>> segments;
    segments.reserve(pslg.segments.size());
    for (const auto& s : pslg.segments) segments.emplace_back(s[0], s[1]);

    Cdt cdt;
    const auto t_cdt = Clock::now();
    cdt.insert_constraints(points.begin(), points.end(), segments.begin(), segments.end());
    if (domain == "hull") constrain_convex_hull(cdt);
    const double cdt_seconds = seconds_since(t_cdt);
    const long long cdt_points = static_cast<long long>(cdt.number_of_vertices());

    const double sine = std::sin(min_angle * kPi / 180.0);
    const Criteria criteria(sine * sine, max_edge);
    const auto t_refine = Clock::now();
    if (domain == "hull") {
      for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f)
        f->set_in_domain(true);
      CGAL::refine_Delaunay_mesh_2(cdt, criteria, true);
    } else {
      CGAL::refine_Delaunay_mesh_2(cdt, criteria);
    }
    const double refine_seconds = seconds_since(t_refine);

    long long triangles = 0;
    double min_deg = 180.0, area = 0.0, bad_area = 0.0;
    for (auto f = cdt.finite_faces_begin(); f != cdt.finite_faces_end(); ++f) {
      if (!f->is_in_domain()) continue;
      const auto& a = f->vertex(0)->point();
      const auto& b = f->vertex(1)->point();
      const auto& c = f->vertex(2)->point();
      const double deg = smallest_angle_deg(a, b, c);
      const double fa = std::abs(CGAL::to_double(CGAL::area(a, b, c)));
      ++triangles;
      min_deg = std::min(min_deg, deg);
      area += fa;
      // A hair of slack so rounding of the angle itself does not count a good face as bad.
      if (deg < min_angle - 1e-9) bad_area += fa;
    }
    const long long points_out = static_cast<long long>(cdt.number_of_vertices());
    out.add("status", "ok")
        .add("input_points", static_cast<long long>(pslg.points.size()))
        .add("input_segments", static_cast<long long>(pslg.segments.size()))
        .add("min_angle_bound", min_angle)
        .add("max_edge", max_edge)
        .add("domain", domain)
        .add("cdt_seconds", cdt_seconds)
        .add("refine_seconds", refine_seconds)
        .add("total_seconds", cdt_seconds + refine_seconds)
        .add("points", points_out)
        .add("triangles", triangles)
        .add("steiner_points", points_out - cdt_points)
        .add("min_angle_deg", triangles ? min_deg : 0.0)
        .add("bad_area_percent", area > 0 ? 100.0 * bad_area / area : 0.0);
    out.print();
    return 0;
  } catch (const std::exception& e) {
    out.add("status", "error").add("message", e.what());
  }
  out.print();
  return 1;
}
