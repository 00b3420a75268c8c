// 2D validator: orientation, manifold edges, conformity to the PSLG, constrained Delaunay.
#include <algorithm>

#include "gdr/validate.h"
#include "predicates/predicates.h"
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

std::string tri_text(const TriMesh& m, std::size_t t) {
  const auto& v = m.triangles[t];
  return "triangle " + std::to_string(t) + " (" + std::to_string(v[0]) + ", " +
         std::to_string(v[1]) + ", " + std::to_string(v[2]) + ")";
}

enum EdgeStatus : std::uint8_t { kEdgeOk = 0, kEdgeNonmanifold, kEdgeOverlap, kEdgeNonDelaunay };

}  // namespace

ValidationReport validate_trimesh(const TriMesh& mesh, const Pslg* input,
                                  const ValidateOptions& options) {
  ValidationReport r;
  Problems problems{r.problems, options.max_problems};
  const auto& P = mesh.points;
  const auto& T = mesh.triangles;
  const std::size_t nv = P.size();
  const std::int64_t nt = static_cast<std::int64_t>(T.size());
  auto xy = [&](int v) { return &P[v].x; };  // Point2 is two adjacent doubles

  // Per triangle: 0 ok, 1 bad index, 2 not counter-clockwise.
  std::vector<std::uint8_t> tri_status(T.size(), 0);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < nt; ++t) {
    bool in_range = true;
    for (int v : T[t]) in_range = in_range && v >= 0 && static_cast<std::size_t>(v) < nv;
    if (!in_range) tri_status[t] = 1;
    else if (!(pred::orient2d(xy(T[t][0]), xy(T[t][1]), xy(T[t][2])) > 0)) tri_status[t] = 2;
  }
  for (std::size_t t = 0; t < T.size(); ++t) {
    if (tri_status[t] == 1) {
      ++r.invalid_indices;
      problems.add(tri_text(mesh, t) + " has a vertex index out of range [0, " +
                   std::to_string(nv) + ")");
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
    problems.add("subsegment " + std::to_string(s) + " (" + std::to_string(a) + ", " +
                 std::to_string(b) + ") is not an edge of the mesh");
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
    if (pred::incircle(xy(T[t1][0]), xy(T[t1][1]), xy(T[t1][2]), xy(T[t2][k2])) > 0)
      edge_status[item] = kEdgeNonDelaunay;
  });
  for (std::size_t i = 0; i < edge_status.size(); ++i) {
    if (edge_status[i] == kEdgeOk) continue;
    const int k = static_cast<int>(i % 3);
    const auto& tv = T[i / 3];
    const std::string edge = "edge (" + std::to_string(tv[(k + 1) % 3]) + ", " +
                             std::to_string(tv[(k + 2) % 3]) + ")";
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
      problems.add("input point " + std::to_string(i) + " (" + std::to_string(input->points[i].x) +
                   ", " + std::to_string(input->points[i].y) + ") is not a mesh vertex");
    }
    const validate::SubsegmentGraph graph(nv, mesh.subsegments);
    const auto& S = input->segments;
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
      else if (a != b) seg_ok[s] = validate::follow_segment(P, graph, a, b, options.segment_tolerance);
    }
    for (std::size_t s = 0; s < S.size(); ++s) {
      if (seg_ok[s]) continue;
      ++r.missing_segments;
      problems.add("input segment " + std::to_string(s) + " (" + std::to_string(S[s][0]) + ", " +
                   std::to_string(S[s][1]) + ") is not recovered as a chain of subsegments");
    }
  }

  r.quality = triangle_quality(mesh, options.min_angle_deg);
  r.valid = r.inverted_elements + r.nonmanifold + r.missing_points + r.missing_segments +
                r.non_delaunay + r.invalid_indices + r.invalid_subsegments ==
            0;
  return r;
}

}  // namespace gdr
