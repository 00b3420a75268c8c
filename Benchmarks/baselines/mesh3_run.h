// CGAL Mesh_3 run shared by the sequential and the parallel translation unit. Each unit
// instantiates one concurrency tag: a Mesh_3 unit costs ~1 min and 3 GB to compile, so the
// two instantiations are kept apart and built one at a time.
#pragma once
#include <string>

#include "gdr/pslg.h"

namespace gdr_bench {

struct Mesh3Params {
  double facet_angle = 25, facet_size = 0, facet_distance = 0;
  double cell_radius_edge_ratio = 3, cell_size = 0;
  bool optimize = true;  // CGAL's default perturbation and exudation after refinement
  bool manifold = false;  // CGAL's manifold() topological criterion (gdr rdt's default)
  double feature_angle = 0;  // > 0: sharp edges detected at this angle are protected
                             // (Polyhedral_mesh_domain_with_features_3, edge size = facet size)
  int threads = 0;       // parallel only; 0 = all cores
};

struct Mesh3Result {
  double domain_seconds = 0;  // building the polyhedral domain (AABB tree)
  double mesh_seconds = 0;    // make_mesh_3: refinement plus optimisation
  long long points = 0, cells = 0, facets = 0;
  double min_dihedral_deg = 0, max_dihedral_deg = 0, max_radius_edge = 0, volume = 0;
  int threads = 1;
};

Mesh3Result run_mesh3_sequential(const gdr::Surface& surface, const Mesh3Params& params);
// Throws std::runtime_error when CGAL was built without TBB.
Mesh3Result run_mesh3_parallel(const gdr::Surface& surface, const Mesh3Params& params);

}  // namespace gdr_bench
