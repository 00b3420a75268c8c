// The Mesh_3 pipeline as a template over CGAL's concurrency tag; included by exactly one
// translation unit per tag.
#pragma once
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Mesh_polyhedron_3.h>
#include <CGAL/Polyhedral_mesh_domain_3.h>
#include <CGAL/Polyhedral_mesh_domain_with_features_3.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/make_mesh_3.h>

#include <array>
#include <chrono>
#include <vector>

#include "mesh3_run.h"
#include "tet_quality.h"

namespace gdr_bench {

using Mesh3Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// The complex: with corners and curves for a domain with features (only such a domain names
// their index types).
template <class Tr, class Domain, bool kFeatures>
struct C3t3Of {
  using type = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
};
template <class Tr, class Domain>
struct C3t3Of<Tr, Domain, true> {
  using type = CGAL::Mesh_complex_3_in_triangulation_3<Tr, typename Domain::Corner_index, typename Domain::Curve_index>;
};

// One run with the domain type: plain, or with sharp features (detect_features(angle)).
template <class ConcurrencyTag, class Polyhedron, class Domain, bool kFeatures>
Mesh3Result run_mesh3_with(const gdr::Surface& surface, const Mesh3Params& p) {
  using K = Mesh3Kernel;
  using Tr = typename CGAL::Mesh_triangulation_3<Domain, CGAL::Default, ConcurrencyTag>::type;
  using C3t3 = typename C3t3Of<Tr, Domain, kFeatures>::type;
  using Criteria = CGAL::Mesh_criteria_3<Tr>;
  using Clock = std::chrono::steady_clock;
  namespace params = CGAL::parameters;

  std::vector<K::Point_3> points;
  points.reserve(surface.points.size());
  for (const auto& q : surface.points) points.emplace_back(q.x, q.y, q.z);
  std::vector<std::vector<std::size_t>> faces;
  faces.reserve(surface.triangles.size());
  for (const auto& t : surface.triangles)
    faces.push_back({static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]),
                     static_cast<std::size_t>(t[2])});
  Polyhedron polyhedron;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, faces, polyhedron);

  Mesh3Result r;
  const auto t0 = Clock::now();
  Domain domain(polyhedron);
  if constexpr (kFeatures) domain.detect_features(p.feature_angle);
  r.domain_seconds = std::chrono::duration<double>(Clock::now() - t0).count();

  // A zero bound means "no bound" in gdr's parameters; CGAL spells that by leaving it out.
  // Features are sampled at the facet size, as gdr rdt samples them.
  const Criteria criteria = [&] {
    if constexpr (kFeatures)
      return Criteria(params::edge_size = p.facet_size, params::facet_angle = p.facet_angle,
                      params::facet_size = p.facet_size, params::facet_distance = p.facet_distance,
                      params::cell_radius_edge_ratio = p.cell_radius_edge_ratio,
                      params::cell_size = p.cell_size);
    else
      return Criteria(params::facet_angle = p.facet_angle, params::facet_size = p.facet_size,
                      params::facet_distance = p.facet_distance,
                      params::cell_radius_edge_ratio = p.cell_radius_edge_ratio,
                      params::cell_size = p.cell_size);
  }();

  const auto t1 = Clock::now();
  const auto topology = p.manifold ? params::manifold() : params::non_manifold();
  C3t3 c3t3 = p.optimize ? CGAL::make_mesh_3<C3t3>(domain, criteria, topology)
                         : CGAL::make_mesh_3<C3t3>(domain, criteria, params::no_perturb(),
                                                   params::no_exude(), topology);
  r.mesh_seconds = std::chrono::duration<double>(Clock::now() - t1).count();

  TetQuality q;
  auto xyz = [](const K::Point_3& a) { return std::array<double, 3>{a.x(), a.y(), a.z()}; };
  for (auto c = c3t3.cells_in_complex_begin(); c != c3t3.cells_in_complex_end(); ++c) {
    q.add(xyz(c->vertex(0)->point().point()), xyz(c->vertex(1)->point().point()),
          xyz(c->vertex(2)->point().point()), xyz(c->vertex(3)->point().point()));
  }
  r.points = static_cast<long long>(c3t3.triangulation().number_of_vertices());
  r.cells = static_cast<long long>(c3t3.number_of_cells_in_complex());
  r.facets = static_cast<long long>(c3t3.number_of_facets_in_complex());
  r.min_dihedral_deg = q.tets ? q.min_dihedral_deg : 0.0;
  r.max_dihedral_deg = q.max_dihedral_deg;
  r.max_radius_edge = q.max_radius_edge;
  r.volume = q.volume;
  return r;
}

template <class ConcurrencyTag>
Mesh3Result run_mesh3(const gdr::Surface& surface, const Mesh3Params& p) {
  using K = Mesh3Kernel;
  if (p.feature_angle > 0) {
    using Polyhedron = typename CGAL::Mesh_polyhedron_3<K>::type;
    return run_mesh3_with<ConcurrencyTag, Polyhedron, CGAL::Polyhedral_mesh_domain_with_features_3<K>, true>(
        surface, p);
  }
  using Polyhedron = CGAL::Polyhedron_3<K>;
  return run_mesh3_with<ConcurrencyTag, Polyhedron, CGAL::Polyhedral_mesh_domain_3<Polyhedron, K>, false>(surface,
                                                                                                          p);
}

}  // namespace gdr_bench
