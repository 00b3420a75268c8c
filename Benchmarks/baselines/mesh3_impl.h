// The Mesh_3 pipeline as a template over CGAL's concurrency tag; included by exactly one
// translation unit per tag.
#pragma once
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polyhedral_mesh_domain_3.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/make_mesh_3.h>

#include <array>
#include <chrono>
#include <vector>

#include "mesh3_run.h"
#include "tet_quality.h"

namespace gdr_bench {

template <class ConcurrencyTag>
Mesh3Result run_mesh3(const gdr::Surface& surface, const Mesh3Params& p) {
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using Polyhedron = CGAL::Polyhedron_3<K>;
  using Domain = CGAL::Polyhedral_mesh_domain_3<Polyhedron, K>;
  using Tr = typename CGAL::Mesh_triangulation_3<Domain, CGAL::Default, ConcurrencyTag>::type;
  using C3t3 = CGAL::Mesh_complex_3_in_triangulation_3<Tr>;
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
  r.domain_seconds = std::chrono::duration<double>(Clock::now() - t0).count();

  // A zero bound means "no bound" in gdr's parameters; CGAL spells that by leaving it out.
  Criteria criteria(params::facet_angle = p.facet_angle,
                    params::facet_size = p.facet_size,
                    params::facet_distance = p.facet_distance,
                    params::cell_radius_edge_ratio = p.cell_radius_edge_ratio,
                    params::cell_size = p.cell_size);

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

}  // namespace gdr_bench
