// 3D validator: orientation, manifold faces, closed boundary, conformity to the surface
// (points, segments, facets), Delaunay faces.
#include <algorithm>
#include <unordered_map>
#include <cmath>
#include <limits>
#include <unordered_set>

#include "gdr/validate.h"
#include "predicates/predicates.h"
#include "validate/conformity.h"
#include "validate/incidence.h"
#include "validate/vec3.h"

namespace gdr {
namespace {

using validate::Incidence;
using validate::Keyed;
using validate::Problems;

// Faces of a positive tetrahedron, counter-clockwise seen from outside; face k is opposite
// corner k.
constexpr int kFace[4][3] = {{1, 3, 2}, {0, 2, 3}, {0, 3, 1}, {0, 1, 2}};

std::string tet_text(const TetMesh& m, std::size_t t) {
  const auto& v = m.tets[t];
  return "tetrahedron " + std::to_string(t) + " (" + std::to_string(v[0]) + ", " +
         std::to_string(v[1]) + ", " + std::to_string(v[2]) + ", " + std::to_string(v[3]) + ")";
}

std::string tri_text(const std::array<int, 3>& f) {
  return "(" + std::to_string(f[0]) + ", " + std::to_string(f[1]) + ", " + std::to_string(f[2]) + ")";
}

// Parity of the rotation that sorts (x, y, z): true when (x, y, z) is an even permutation.
bool even_order(int x, int y, int z) { return (x < y) + (y < z) + (z < x) == 2; }

enum FaceStatus : std::uint8_t { kFaceOk = 0, kFaceNonmanifold, kFaceOverlap, kFaceNonDelaunay };

using detail::V3;
using detail::cross;
using detail::dot;
using detail::norm;
using detail::sub;

// Coverage of input triangle (a, b, c) by mesh triangles, measured in its own frame where
// it is the unit right triangle u, v >= 0, u + v <= 1: a mesh triangle counts when its
// corners are within `tol * longest edge` of the plane, for the area it shares with the
// input triangle (so coplanar input triangles may be retriangulated freely).
struct FacetTest {
  Point3 a;
  V3 e1, e2, n;
  double n2 = 0, plane_tol = 0, area = 0, longest = 0, bend_sin = 0;
  // `bend_deg`: subfaces may turn this far from the triangle (merged near-flat facets).
  FacetTest(const Point3& pa, const Point3& pb, const Point3& pc, double tolerance, double slack, double bend_deg)
      : a(pa), e1(sub(pb, pa)), e2(sub(pc, pa)), n(cross(e1, e2)) {
    n2 = dot(n, n);
    area = 0.5 * std::sqrt(n2);
    longest = std::sqrt(std::max({dot(e1, e1), dot(e2, e2), dot(sub(pc, pb), sub(pc, pb))}));
    plane_tol = tolerance * longest + slack;
    bend_sin = std::sin(bend_deg * 3.14159265358979323846 / 180.0);
  }
  // Area shared with the input triangle, in units of the input triangle's area (0 when
  // off the plane or disjoint), measured in the triangle's plane.
  double shared(const Point3& p, const Point3& q, const Point3& r) const {
    const double inv = 1.0 / std::sqrt(n2);
    double plane_tol = this->plane_tol;
    if (bend_sin > 0) {
      const double sub_longest = std::sqrt(std::max({dot(sub(q, p), sub(q, p)), dot(sub(r, q), sub(r, q)),
                                                     dot(sub(p, r), sub(p, r))}));
      plane_tol = std::max(plane_tol, bend_sin * (longest + sub_longest));
    }
    std::array<double, 2> poly[8], next[8];
    int count = 0;
    for (const Point3* v : {&p, &q, &r}) {
      const V3 g = sub(*v, a);
      if (std::fabs(dot(g, n)) * inv > plane_tol) return 0;
      poly[count++] = {dot(cross(g, e2), n) / n2, dot(cross(e1, g), n) / n2};
    }
    // Sutherland-Hodgman against u >= 0, v >= 0, 1 - u - v >= 0.
    for (int side = 0; side < 3 && count > 0; ++side) {
      auto dist = [side](const std::array<double, 2>& w) {
        return side == 0 ? w[0] : side == 1 ? w[1] : 1 - w[0] - w[1];
      };
      int m = 0;
      for (int i = 0; i < count; ++i) {
        const auto& s0 = poly[i];
        const auto& s1 = poly[(i + 1) % count];
        const double d0 = dist(s0), d1 = dist(s1);
        if (d0 >= 0) next[m++] = s0;
        if ((d0 >= 0) != (d1 >= 0)) {
          const double t = d0 / (d0 - d1);
          next[m++] = {s0[0] + t * (s1[0] - s0[0]), s0[1] + t * (s1[1] - s0[1])};
        }
      }
      count = m;
      std::copy(next, next + m, poly);
    }
    double twice = 0;
    for (int i = 0; i < count; ++i) {
      const auto& s0 = poly[i];
      const auto& s1 = poly[(i + 1) % count];
      twice += s0[0] * s1[1] - s1[0] * s0[1];
    }
    return std::fabs(twice);  // the unit right triangle has twice-area 1
  }
};

}  // namespace

ValidationReport validate_tetmesh(const TetMesh& mesh, const Surface* input,
                                  const ValidateOptions& options) {
  ValidationReport r;
  Problems problems{r.problems, options.max_problems};
  const auto& P = mesh.points;
  const double slack = validate::coordinate_slack(P);
  const auto& T = mesh.tets;
  const std::size_t nv = P.size();
  const std::int64_t nt = static_cast<std::int64_t>(T.size());
  auto xyz = [&](int v) { return &P[v].x; };  // Point3 is three adjacent doubles

  // Per tetrahedron: 0 ok, 1 bad index, 2 not positively oriented.
  std::vector<std::uint8_t> tet_status(T.size(), 0);
#pragma omp parallel for schedule(static)
  for (std::int64_t t = 0; t < nt; ++t) {
    bool in_range = true;
    for (int v : T[t]) in_range = in_range && v >= 0 && static_cast<std::size_t>(v) < nv;
    if (!in_range) tet_status[t] = 1;
    else if (!(pred::orient3d(xyz(T[t][0]), xyz(T[t][1]), xyz(T[t][2]), xyz(T[t][3])) > 0))
      tet_status[t] = 2;
  }
  for (std::size_t t = 0; t < T.size(); ++t) {
    if (tet_status[t] == 1) {
      ++r.invalid_indices;
      problems.add(tet_text(mesh, t) + " has a vertex index out of range [0, " + std::to_string(nv) + ")");
    } else if (tet_status[t] == 2) {
      ++r.inverted_elements;
      problems.add(tet_text(mesh, t) + " is not positively oriented (orient3d <= 0)");
    }
  }

  auto face_of = [&](std::size_t item) {
    const auto& t = T[item / 4];
    const int* f = kFace[item % 4];
    return std::array<int, 3>{t[f[0]], t[f[1]], t[f[2]]};
  };
  const Incidence faces(nv, 4 * T.size(), [&](std::size_t i, int& a, int& b, int& c) {
    if (tet_status[i / 4] == 1) return false;
    const auto f = face_of(i);
    a = f[0], b = f[1], c = f[2];
    validate::sort3(a, b, c);
    return a != b && b != c;
  });

  // Subfaces: in range and mesh faces.
  std::vector<std::array<int, 3>> constrained;
  for (std::size_t s = 0; s < mesh.subfaces.size(); ++s) {
    int a = mesh.subfaces[s][0], b = mesh.subfaces[s][1], c = mesh.subfaces[s][2];
    validate::sort3(a, b, c);
    if (a >= 0 && static_cast<std::size_t>(c) < nv && a != b && b != c) {
      const auto run = faces.find(a, b, c);
      if (run.first != run.second) {
        constrained.push_back({a, b, c});
        continue;
      }
    }
    ++r.invalid_subfaces;
    problems.add("subface " + std::to_string(s) + " " + tri_text(mesh.subfaces[s]) +
                 " is not a face of the mesh");
  }
  std::sort(constrained.begin(), constrained.end());
  auto is_subface = [&](int a, int b, int c) {
    return std::binary_search(constrained.begin(), constrained.end(), std::array<int, 3>{a, b, c});
  };

  // Face groups: manifoldness, Delaunay, and which faces are on the boundary.
  std::vector<std::uint8_t> face_status(4 * T.size(), kFaceOk);
  std::vector<std::uint8_t> on_boundary(4 * T.size(), 0);
  const bool delaunay = options.check_delaunay;
  faces.for_each_group([&](int a, const Keyed* first, const Keyed* last) {
    const std::int64_t item = first->item;
    if (last - first > 2) {
      face_status[item] = kFaceNonmanifold;
      return;
    }
    if (last - first == 1) {
      on_boundary[item] = 1;
      return;
    }
    const std::size_t t1 = first->item / 4, t2 = (first + 1)->item / 4;
    if (tet_status[t1] || tet_status[t2]) return;
    const auto f1 = face_of(first->item), f2 = face_of((first + 1)->item);
    if (even_order(f1[0], f1[1], f1[2]) == even_order(f2[0], f2[1], f2[2])) {
      face_status[item] = kFaceOverlap;
      return;
    }
    if (!delaunay || is_subface(a, first->b, first->c)) return;
    const int e = T[t2][(first + 1)->item % 4];
    if (pred::insphere(xyz(T[t1][0]), xyz(T[t1][1]), xyz(T[t1][2]), xyz(T[t1][3]), xyz(e)) > 0)
      face_status[item] = kFaceNonDelaunay;
  });
  std::vector<std::size_t> boundary;
  for (std::size_t i = 0; i < face_status.size(); ++i) {
    if (on_boundary[i]) boundary.push_back(i);
    if (face_status[i] == kFaceOk) continue;
    const std::string face = "face " + tri_text(face_of(i)) + " of " + tet_text(mesh, i / 4);
    if (face_status[i] == kFaceNonDelaunay) {
      ++r.non_delaunay;
      problems.add(face + " is not locally Delaunay and not a subface");
    } else {
      ++r.nonmanifold;
      problems.add(face + (face_status[i] == kFaceNonmanifold ? " is shared by more than two tetrahedra"
                                                               : " has two tetrahedra on the same side"));
    }
  }

  // The boundary must be a closed, consistently oriented 2-manifold.
  const Incidence boundary_edges(nv, 3 * boundary.size(), [&](std::size_t i, int& a, int& b, int& c) {
    const auto f = face_of(boundary[i / 3]);
    a = f[i % 3], b = f[(i + 1) % 3], c = -1;
    if (a > b) std::swap(a, b);
    return a != b;
  });
  std::vector<std::uint8_t> edge_bad(3 * boundary.size(), 0);
  boundary_edges.for_each_group([&](int a, const Keyed* first, const Keyed* last) {
    bool ok = last - first == 2;
    if (ok) {
      const auto f1 = face_of(boundary[first->item / 3]), f2 = face_of(boundary[(first + 1)->item / 3]);
      ok = (f1[first->item % 3] == a) != (f2[(first + 1)->item % 3] == a);
    }
    if (!ok) edge_bad[first->item] = 1;
  });
  for (std::size_t i = 0; i < edge_bad.size(); ++i) {
    if (!edge_bad[i]) continue;
    ++r.boundary_errors;
    const auto f = face_of(boundary[i / 3]);
    problems.add("boundary edge (" + std::to_string(f[i % 3]) + ", " + std::to_string(f[(i + 1) % 3]) +
                 ") is not shared by exactly two consistently oriented boundary faces");
  }
  if (!mesh.subfaces.empty()) {
    for (std::size_t i : boundary) {
      auto f = face_of(i);
      validate::sort3(f[0], f[1], f[2]);
      if (is_subface(f[0], f[1], f[2])) continue;
      ++r.boundary_errors;
      problems.add("boundary face " + tri_text(face_of(i)) + " is not a subface");
    }
  }

  if (input && options.check_conformity) {
    std::vector<int> representative;
    const std::vector<int> found = validate::locate_input_points(input->points, P, representative);
    const std::int64_t ni = static_cast<std::int64_t>(input->points.size());
    for (std::int64_t i = 0; i < ni; ++i) {
      if (representative[i] != i || found[i] >= 0) continue;
      ++r.missing_points;
      const Point3& p = input->points[i];
      problems.add("input point " + std::to_string(i) + " (" + std::to_string(p.x) + ", " +
                   std::to_string(p.y) + ", " + std::to_string(p.z) + ") is not a mesh vertex");
    }
    auto mesh_vertex = [&](int i) { return i < 0 || i >= ni ? -1 : found[representative[i]]; };

    const validate::SubsegmentGraph graph(nv, mesh.subsegments);
    const auto& S = input->segments;
    std::vector<std::uint8_t> seg_ok(S.size(), 1);
#pragma omp parallel for schedule(dynamic, 256)
    for (std::int64_t s = 0; s < static_cast<std::int64_t>(S.size()); ++s) {
      const int a = mesh_vertex(S[s][0]), b = mesh_vertex(S[s][1]);
      if (a < 0 || b < 0) seg_ok[s] = 0;
      else if (a != b) seg_ok[s] = validate::follow_segment(P, graph, a, b, options.segment_tolerance, slack);
    }
    for (std::size_t s = 0; s < S.size(); ++s) {
      if (seg_ok[s]) continue;
      ++r.missing_segments;
      problems.add("input segment " + std::to_string(s) + " (" + std::to_string(S[s][0]) + ", " +
                   std::to_string(S[s][1]) + ") is not recovered as a chain of subsegments");
    }

    // Facets: flood fill the subfaces sharing area with each input triangle, from those at
    // its first corner, and compare the area they cover with the triangle's area.
    const auto& F = mesh.subfaces;
    std::vector<std::size_t> vstart(nv + 1, 0);
    std::vector<int> vfaces;
    auto in_range = [&](const std::array<int, 3>& f) {
      for (int v : f)
        if (v < 0 || static_cast<std::size_t>(v) >= nv) return false;
      return true;
    };
    for (const auto& f : F)
      if (in_range(f))
        for (int v : f) ++vstart[v + 1];
    for (std::size_t v = 0; v < nv; ++v) vstart[v + 1] += vstart[v];
    vfaces.resize(vstart[nv]);
    {
      std::vector<std::size_t> fill(vstart.begin(), vstart.end() - 1);
      for (std::size_t i = 0; i < F.size(); ++i)
        if (in_range(F[i]))
          for (int v : F[i]) vfaces[fill[v]++] = static_cast<int>(i);
    }
    const Incidence sub_edges(nv, 3 * F.size(), [&](std::size_t i, int& a, int& b, int& c) {
      if (!in_range(F[i / 3])) return false;
      a = F[i / 3][i % 3], b = F[i / 3][(i + 1) % 3], c = -1;
      if (a > b) std::swap(a, b);
      return a != b;
    });
    const double area_tol = 1e-6;
    const auto& IT = input->triangles;
    // The precision the input was given in: float (binary STL) when every coordinate is a
    // float. A needle's plane is known only to that precision (below).
    const bool float_input = std::all_of(input->points.begin(), input->points.end(), [](const Point3& p) {
      return static_cast<float>(p.x) == p.x && static_cast<float>(p.y) == p.y && static_cast<float>(p.z) == p.z;
    });
    const double input_eps =
        float_input ? std::numeric_limits<float>::epsilon() : std::numeric_limits<double>::epsilon();
    // Needles: triangles so thin that the input's rounding leaves their planes uncertain by
    // a percent or more (below). One folded over its neighbour (a dihedral angle of 0 within
    // rounding, as float coordinates give) is covered by the neighbour's subfaces as well, and
    // covers part of the neighbour: a needle is checked for under-cover only, and each other
    // triangle may be over-covered by the needles at its edges, in units of its own area.
    const double kNeedle = 0.01;
    std::vector<double> tri_area(IT.size(), 0.0), tri_rounding(IT.size(), 0.0), needle_share(IT.size(), 0.0);
    auto edge = [&](std::size_t k, int e) {
      const std::uint64_t x = static_cast<std::uint32_t>(IT[k][e]), y = static_cast<std::uint32_t>(IT[k][(e + 1) % 3]);
      return std::min(x, y) << 32 | std::max(x, y);
    };
    std::unordered_map<std::uint64_t, std::vector<int>> needles_at;  // needles by edge (few)
#pragma omp parallel for
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(IT.size()); ++k) {
      const Point3 &pa = input->points[IT[k][0]], &pb = input->points[IT[k][1]], &pc = input->points[IT[k][2]];
      const double u[3] = {pb.x - pa.x, pb.y - pa.y, pb.z - pa.z}, v[3] = {pc.x - pa.x, pc.y - pa.y, pc.z - pa.z},
                   w[3] = {pc.x - pb.x, pc.y - pb.y, pc.z - pb.z};
      const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
      tri_area[k] = 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
      const double longest2 = std::max({u[0] * u[0] + u[1] * u[1] + u[2] * u[2], v[0] * v[0] + v[1] * v[1] + v[2] * v[2],
                                        w[0] * w[0] + w[1] * w[1] + w[2] * w[2]});
      tri_rounding[k] = tri_area[k] > 0 ? 64 * input_eps * longest2 / tri_area[k] : 0.0;
    }
    for (std::size_t j = 0; j < IT.size(); ++j)
      if (tri_rounding[j] >= kNeedle)
        for (int e = 0; e < 3; ++e) needles_at[edge(j, e)].push_back(static_cast<int>(j));
    if (!needles_at.empty())
      for (std::size_t k = 0; k < IT.size(); ++k)
        for (int e = 0; e < 3 && tri_area[k] > 0; ++e) {
          const auto it = needles_at.find(edge(k, e));
          if (it == needles_at.end()) continue;
          for (const int j : it->second)
            if (static_cast<std::size_t>(j) != k) needle_share[k] += tri_area[j] / tri_area[k];
        }
    std::vector<std::uint8_t> facet_ok(IT.size(), 1);
    std::vector<double> cover(IT.size(), 0.0);  // share of each triangle's area covered
#pragma omp parallel for schedule(dynamic, 64)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(IT.size()); ++k) {
      const int a = mesh_vertex(IT[k][0]), b = mesh_vertex(IT[k][1]), c = mesh_vertex(IT[k][2]);
      if (a < 0 || b < 0 || c < 0) {
        facet_ok[k] = 0;
        continue;
      }
      const FacetTest test(P[a], P[b], P[c], options.segment_tolerance, slack, options.facet_bend_deg);
      if (test.area == 0) continue;  // a degenerate input triangle covers nothing
      std::unordered_set<int> seen;
      std::vector<std::pair<int, double>> stack;
      auto visit = [&](int f) {
        if (seen.count(f)) return;
        const double part = test.shared(P[F[f][0]], P[F[f][1]], P[F[f][2]]);
        if (part > 0) {
          seen.insert(f);
          stack.push_back({f, part});
        }
      };
      for (std::size_t j = vstart[a]; j < vstart[a + 1]; ++j) visit(vfaces[j]);
      // With bent facets, subfaces of other facets near a corner can overlap the triangle's
      // plane within the tolerance (a saddle): the triangle must be covered by one facet.
      const bool per_facet = test.bend_sin > 0 && mesh.subface_facet.size() == F.size();
      std::unordered_map<int, double> by_facet;
      double covered = 0;
      while (!stack.empty()) {
        const int f = stack.back().first;
        if (per_facet) covered = std::max(covered, by_facet[mesh.subface_facet[f]] += stack.back().second);
        else covered += stack.back().second;
        stack.pop_back();
        for (int e = 0; e < 3; ++e) {
          const int u = std::min(F[f][e], F[f][(e + 1) % 3]), w = std::max(F[f][e], F[f][(e + 1) % 3]);
          const auto run = sub_edges.find(u, w, -1);
          for (const Keyed* g = run.first; g != run.second; ++g) visit(static_cast<int>(g->item / 3));
        }
      }
      cover[k] = covered;
      // A triangle degenerate up to rounding (an angle of 180 degrees within 1e-9 or so, or
      // a corner a float's rounding off the opposite edge in a binary STL) has a plane known
      // only to about eps * longest^2 / area, eps the input's precision: its cover too.
      const double rounding = 64 * input_eps * test.longest * test.longest / test.area;
      if (covered < 1.0 - area_tol - rounding ||
          (rounding < kNeedle && covered > 1.0 + area_tol + rounding + needle_share[k]))
        facet_ok[k] = 0;
    }
    for (std::size_t k = 0; k < IT.size(); ++k) {
      if (facet_ok[k]) continue;
      ++r.missing_facets;
      problems.add("input triangle " + std::to_string(k) + " " + tri_text(IT[k]) +
                   " is not covered by subfaces (they cover " + std::to_string(100.0 * cover[k]) +
                   "% of its area)");
    }
  }

  r.quality = tet_quality(mesh, options.max_radius_edge);
  r.valid = r.inverted_elements + r.nonmanifold + r.missing_points + r.missing_segments +
                r.missing_facets + r.non_delaunay + r.invalid_indices + r.invalid_subsegments +
                r.invalid_subfaces + r.boundary_errors ==
            0;
  return r;
}

}  // namespace gdr
