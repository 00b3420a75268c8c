// 2D validator: orientation, manifold edges, conformity to the PSLG, constrained Delaunay.
#include <algorithm>
#include <cmath>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include "gdr/validate.h"
#include "validate/conformity.h"
#include "validate/incidence.h"

namespace gdr {
namespace {

using validate::Incidence;
using validate::Keyed;
using validate::Problems;

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// Items are numbered as the files they come from or go to count (Triangle's 0 or 1):
// mesh items by the mesh's first_index, input items by the input's.
std::string tri_text(const TriMesh& m, std::size_t t) {
  const auto& v = m.triangles[t];
  const long long o = m.first_index;
  return "triangle " + std::to_string(t + o) + " (" + std::to_string(v[0] + o) + ", " +
         std::to_string(v[1] + o) + ", " + std::to_string(v[2] + o) + ")";
}

enum EdgeStatus : std::uint8_t { kEdgeOk = 0, kEdgeNonmanifold, kEdgeOverlap, kEdgeNonDelaunay };

// The orientation and incircle tests are CGAL's filtered exact predicates, not the mesher's
// own: they are exact for any finite doubles (their filters fall back to exact arithmetic
// where products would overflow or underflow), so the check does not share the mesher's
// assumptions about the coordinate range.
using Cgal = CGAL::Exact_predicates_inexact_constructions_kernel;
Cgal::Point_2 cgal(const Point2& p) { return {p.x, p.y}; }

// Each input segment must be one chain of subsegments from its first to its last vertex:
// the subsegments the mesher says come from it (subsegment_source), each of its interior
// vertices on two of them, its ends on one, and in order along the segment (the coordinate
// in which the segment is longer never goes back; no arithmetic, so an edge one ulp long or a
// neighbouring segment 1e-15 rad away cannot confuse it). Vertices must also lie on the
// segment up to rounding: within `tolerance` of its length, or a few ulps of the largest
// coordinate magnitude (intersection points are rounded and merged within 2^-40 of the extent).
bool follow_sourced_chain(const FilledVector<Point2>& P, const std::vector<std::array<int, 2>>& chain,
                          int a, int b, double tolerance, double extent) {
  const std::vector<int> path = validate::chain_path(chain, a, b);
  if (path.empty()) return false;
  const Point2 &pa = P[a], &pb = P[b];
  const bool along_x = std::fabs(pb.x - pa.x) >= std::fabs(pb.y - pa.y);
  const double dir = along_x ? pb.x - pa.x : pb.y - pa.y;
  const auto key = [&](int v) { return (along_x ? P[v].x : P[v].y) * (dir > 0 ? 1 : -1); };
  // Distances on coordinates scaled by a power of two (exact) so that nothing overflows.
  const int k = -std::ilogb(std::max({std::fabs(pa.x), std::fabs(pa.y), std::fabs(pb.x), std::fabs(pb.y)}));
  const double dx = std::ldexp(pb.x, k) - std::ldexp(pa.x, k), dy = std::ldexp(pb.y, k) - std::ldexp(pa.y, k);
  const double len = std::hypot(dx, dy), slack = tolerance * len + std::ldexp(extent, k - 38);
  for (std::size_t i = 1; i < path.size(); ++i) {
    const int cur = path[i - 1], to = path[i];
    if (key(to) < key(cur)) return false;
    const double rx = std::ldexp(P[to].x, k) - std::ldexp(pa.x, k),
                 ry = std::ldexp(P[to].y, k) - std::ldexp(pa.y, k);
    if (to != b && !(std::fabs(rx * dy - ry * dx) <= slack * len)) return false;
  }
  return true;
}

}  // namespace

ValidationReport validate_trimesh(const TriMesh& mesh, const Pslg* input,
                                  const ValidateOptions& options) {
  ValidationReport r;
  Problems problems{r.problems, options.max_problems};
  const auto& P = mesh.points;
  const auto& T = mesh.triangles;
  const std::size_t nv = P.size();
  const std::int64_t nt = static_cast<std::int64_t>(T.size());

  // Per triangle: 0 ok, 1 bad index, 2 not counter-clockwise.
  std::vector<std::uint8_t> tri_status(T.size(), 0);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < nt; ++t) {
    bool in_range = true;
    for (int v : T[t]) in_range = in_range && v >= 0 && static_cast<std::size_t>(v) < nv;
    if (!in_range) tri_status[t] = 1;
    else if (CGAL::orientation(cgal(P[T[t][0]]), cgal(P[T[t][1]]), cgal(P[T[t][2]])) != CGAL::LEFT_TURN)
      tri_status[t] = 2;
  }
  for (std::size_t t = 0; t < T.size(); ++t) {
    if (tri_status[t] == 1) {
      ++r.invalid_indices;
      problems.add(tri_text(mesh, t) + " has a vertex index out of range [" + std::to_string(mesh.first_index) +
                   ", " + std::to_string(nv + mesh.first_index) + ")");
    } else if (tri_status[t] == 2) {
      ++r.inverted_elements;
      problems.add(tri_text(mesh, t) + " is not counter-clockwise");
    }
  }

  // Edges grouped by vertices; item = triangle * 3 + local edge (opposite that corner).
  const Incidence edges(nv, 3 * T.size(), [&](std::size_t i, int& a, int& b, int& c) {
    const std::size_t t = i / 3;
    if (tri_status[t] == 1) return false;
    const int k = static_cast<int>(i % 3);
    a = T[t][(k + 1) % 3];
    b = T[t][(k + 2) % 3];
    c = -1;
    if (a == b) return false;
    if (a > b) std::swap(a, b);
    return true;
  });

  // Subsegments: in range and mesh edges.
  std::vector<std::uint64_t> constrained;
  constrained.reserve(mesh.subsegments.size());
  for (std::size_t s = 0; s < mesh.subsegments.size(); ++s) {
    const int a = mesh.subsegments[s][0], b = mesh.subsegments[s][1];
    const bool in_range = a >= 0 && b >= 0 && static_cast<std::size_t>(a) < nv &&
                          static_cast<std::size_t>(b) < nv && a != b;
    if (in_range) {
      const auto run = edges.find(std::min(a, b), std::max(a, b), -1);
      if (run.first != run.second) {
        constrained.push_back(edge_key(a, b));
        continue;
      }
    }
    ++r.invalid_subsegments;
    const long long o = mesh.first_index;
    problems.add("subsegment " + std::to_string(s + o) + " (" + std::to_string(a + o) + ", " +
                 std::to_string(b + o) + ") is not an edge of the mesh");
  }
  std::sort(constrained.begin(), constrained.end());

  // Manifoldness and the constrained Delaunay property, one status per edge group (stored on
  // the group's first item so that the report below is deterministic).
  std::vector<std::uint8_t> edge_status(3 * T.size(), kEdgeOk);
  const bool delaunay = options.check_delaunay;
  edges.for_each_group([&](int a, const Keyed* first, const Keyed* last) {
    const std::int64_t item = first->item;
    if (last - first > 2) {
      edge_status[item] = kEdgeNonmanifold;
      return;
    }
    if (last - first == 1) return;
    const std::size_t t1 = first->item / 3, t2 = (first + 1)->item / 3;
    const int k1 = static_cast<int>(first->item % 3), k2 = static_cast<int>((first + 1)->item % 3);
    if (tri_status[t1] || tri_status[t2]) return;
    // Two ccw triangles on opposite sides traverse the shared edge in opposite directions.
    if ((T[t1][(k1 + 1) % 3] == a) == (T[t2][(k2 + 1) % 3] == a)) {
      edge_status[item] = kEdgeOverlap;
      return;
    }
    if (!delaunay || std::binary_search(constrained.begin(), constrained.end(), edge_key(a, first->b)))
      return;
    if (CGAL::side_of_oriented_circle(cgal(P[T[t1][0]]), cgal(P[T[t1][1]]), cgal(P[T[t1][2]]),
                                      cgal(P[T[t2][k2]])) == CGAL::ON_POSITIVE_SIDE)
      edge_status[item] = kEdgeNonDelaunay;
  });
  for (std::size_t i = 0; i < edge_status.size(); ++i) {
    if (edge_status[i] == kEdgeOk) continue;
    const int k = static_cast<int>(i % 3);
    const auto& tv = T[i / 3];
    const std::string edge = "edge (" + std::to_string(tv[(k + 1) % 3] + mesh.first_index) + ", " +
                             std::to_string(tv[(k + 2) % 3] + mesh.first_index) + ")";
    if (edge_status[i] == kEdgeNonDelaunay) {
      ++r.non_delaunay;
      problems.add(edge + " of " + tri_text(mesh, i / 3) +
                   " is not locally Delaunay and not a subsegment");
    } else {
      ++r.nonmanifold;
      problems.add(edge + (edge_status[i] == kEdgeNonmanifold
                               ? " is shared by more than two triangles"
                               : " has two triangles on the same side"));
    }
  }

  if (input && options.check_conformity) {
    std::vector<int> representative;
    const std::vector<int> found = validate::locate_input_points(input->points, P, representative);
    for (std::size_t i = 0; i < input->points.size(); ++i) {
      if (representative[i] != static_cast<int>(i) || found[i] >= 0) continue;
      ++r.missing_points;
      problems.add("input point " + std::to_string(i + input->first_index) + " (" + std::to_string(input->points[i].x) +
                   ", " + std::to_string(input->points[i].y) + ") is not a mesh vertex");
    }
    const validate::SubsegmentGraph graph(nv, mesh.subsegments);
    const auto& S = input->segments;
    // The mesher says which input segment each subsegment comes from: follow those chains.
    // Without that (a mesh read from a file), walk the subsegments geometrically.
    const bool sourced = mesh.subsegment_source.size() == mesh.subsegments.size() &&
                         !mesh.subsegments.empty();
    std::vector<std::vector<std::array<int, 2>>> chains(sourced ? S.size() : 0);
    double extent = 0;
    if (sourced) {
      for (std::size_t k = 0; k < mesh.subsegments.size(); ++k) {
        const int s = mesh.subsegment_source[k];
        const auto& e = mesh.subsegments[k];
        if (s >= 0 && static_cast<std::size_t>(s) < S.size() && e[0] >= 0 && e[1] >= 0 &&
            static_cast<std::size_t>(e[0]) < nv && static_cast<std::size_t>(e[1]) < nv)
          chains[s].push_back(e);
      }
    }
    for (const Point2& p : P) extent = std::max({extent, std::fabs(p.x), std::fabs(p.y)});
    std::vector<std::uint8_t> seg_ok(S.size(), 1);
    const std::int64_t ns = static_cast<std::int64_t>(S.size());
    const std::int64_t ni = static_cast<std::int64_t>(input->points.size());
#pragma omp parallel for schedule(dynamic, 256)
    for (std::int64_t s = 0; s < ns; ++s) {
      const int ia = S[s][0], ib = S[s][1];
      if (ia < 0 || ib < 0 || ia >= ni || ib >= ni) {
        seg_ok[s] = 0;
        continue;
      }
      const int a = found[representative[ia]], b = found[representative[ib]];
      if (a < 0 || b < 0) seg_ok[s] = 0;
      // (A segment given twice, or overlapping another, is sourced to one of them only.)
      else if (a != b)
        seg_ok[s] = (sourced && follow_sourced_chain(P, chains[s], a, b, options.segment_tolerance, extent)) ||
                    // Overlapping segments are sourced to one of them: the other's chain is
                    // walked, with the same slack for rounded intersection points.
                    validate::follow_segment(P, graph, a, b, options.segment_tolerance, std::ldexp(extent, -38)) ||
                    std::binary_search(mesh.removed_segments.begin(), mesh.removed_segments.end(), int(s));
    }
    for (std::size_t s = 0; s < S.size(); ++s) {
      if (seg_ok[s]) continue;
      ++r.missing_segments;
      const long long o = input->first_index;
      problems.add("input segment " + std::to_string(s + o) + " (" + std::to_string(S[s][0] + o) + ", " +
                   std::to_string(S[s][1] + o) + ") is not recovered as a chain of subsegments");
    }
  }

  r.quality = triangle_quality(mesh, options.min_angle_deg);
  r.valid = r.inverted_elements + r.nonmanifold + r.missing_points + r.missing_segments +
                r.non_delaunay + r.invalid_indices + r.invalid_subsegments ==
            0;
  return r;
}

}  // namespace gdr
