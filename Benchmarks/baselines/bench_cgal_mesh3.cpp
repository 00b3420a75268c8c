// CGAL Mesh_3 baseline: tetrahedral mesh of the volume bounded by a closed triangulated
// surface (polyhedral domain), with CGAL's criteria. --parallel selects the TBB version.
// Prints one JSON line for gdr_bench.
#include <cstdlib>
#include <iostream>
#include <string>

#include "gdr/error.h"
#include "gdr/io.h"
#include "json_line.h"
#include "mesh3_run.h"

namespace {

void usage() {
  std::cerr
      << "usage: bench_cgal_mesh3 SURFACE.(off|stl) [--parallel] [--threads N]\n"
         "         [--facet-angle DEG] [--facet-size S] [--facet-distance D]\n"
         "         [--cell-radius-edge-ratio B] [--cell-size S] [--no-optimize] [--manifold]\n"
         "         [--feature-angle DEG]\n"
         "  a bound of 0 is no bound; --no-optimize skips CGAL's perturbation and exudation;\n"
         "  --feature-angle protects edges sharper than DEG (sampled at the facet size);\n"
         "  --manifold refines until the surface is a manifold (CGAL's manifold())\n";
}

}  // namespace

int main(int argc, char** argv) {
  std::string input;
  bool parallel = false;
  gdr_bench::Mesh3Params p;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--parallel") parallel = true;
    else if (a == "--no-optimize") p.optimize = false;
    else if (a == "--manifold") p.manifold = true;
    else if (a == "--threads" && has_value) p.threads = std::atoi(argv[++i]);
    else if (a == "--facet-angle" && has_value) p.facet_angle = std::atof(argv[++i]);
    else if (a == "--facet-size" && has_value) p.facet_size = std::atof(argv[++i]);
    else if (a == "--facet-distance" && has_value) p.facet_distance = std::atof(argv[++i]);
    else if (a == "--cell-radius-edge-ratio" && has_value)
      p.cell_radius_edge_ratio = std::atof(argv[++i]);
    else if (a == "--cell-size" && has_value) p.cell_size = std::atof(argv[++i]);
    else if (a == "--feature-angle" && has_value) p.feature_angle = std::atof(argv[++i]);
    else if (a == "-h" || a == "--help") { usage(); return 0; }
    else if (input.empty() && a[0] != '-') input = a;
    else { usage(); return 2; }
  }
  if (input.empty()) {
    usage();
    return 2;
  }

  gdr_bench::JsonLine out;
  out.add("runner", parallel ? "cgal-mesh3-par" : "cgal-mesh3-seq").add("input", input);
  try {
    const bool stl = input.size() > 4 && input.compare(input.size() - 4, 4, ".stl") == 0;
    const gdr::Surface surface = stl ? gdr::io::read_stl(input) : gdr::io::read_off(input);
    const gdr_bench::Mesh3Result r = parallel ? gdr_bench::run_mesh3_parallel(surface, p)
                                              : gdr_bench::run_mesh3_sequential(surface, p);
    out.add("status", "ok")
        .add("threads", r.threads)
        .add("input_points", static_cast<long long>(surface.points.size()))
        .add("input_triangles", static_cast<long long>(surface.triangles.size()))
        .add("cdt_seconds", r.domain_seconds)
        .add("refine_seconds", r.mesh_seconds)
        .add("total_seconds", r.domain_seconds + r.mesh_seconds)
        .add("points", r.points)
        .add("tets", r.cells)
        .add("surface_triangles", r.facets)
        .add("min_dihedral_deg", r.min_dihedral_deg)
        .add("max_dihedral_deg", r.max_dihedral_deg)
        .add("max_radius_edge", r.max_radius_edge)
        .add("volume", r.volume);
    out.print();
    return 0;
  } catch (const std::exception& e) {
    out.add("status", "error").add("message", e.what());
  }
  out.print();
  return 1;
}
