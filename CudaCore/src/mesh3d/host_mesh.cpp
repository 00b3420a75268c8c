// check_host_mesh: every invariant of host_mesh.h, with exact predicates. Linear work plus a
// few sorts, so it runs on meshes of millions of tetrahedra.
#include "mesh3d/host_mesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>

#include "gdr/error.h"
#include "mesh3d/tet_topology.h"
#include "predicates/predicates.h"

namespace gdr::m3d {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw Error(Status::InternalError, "host mesh: " + what);
}

std::string str(long long v) { return std::to_string(v); }

std::string face_name(int x) {
  return "tet " + str(x / 4) + " face " + str(x % 4);
}

// The corners of face i of tet t, counter-clockwise seen from outside the tet.
std::array<int, 3> face_vertices(const HostTetMesh& m, int t, int i) {
  return {m.tv[4 * t + face_corner(i, 0)], m.tv[4 * t + face_corner(i, 1)],
          m.tv[4 * t + face_corner(i, 2)]};
}

// +1 when (a0,a1,a2) is a rotation of (b0,b1,b2), -1 when it is a rotation of the reverse,
// 0 when the two are not the same vertex set.
int cyclic_match(const std::array<int, 3>& a, const std::array<int, 3>& b) {
  for (int r = 0; r < 3; ++r) {
    if (a[0] == b[r] && a[1] == b[(r + 1) % 3] && a[2] == b[(r + 2) % 3]) return 1;
    if (a[0] == b[r] && a[1] == b[(r + 2) % 3] && a[2] == b[(r + 1) % 3]) return -1;
  }
  return 0;
}

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) |
         static_cast<std::uint32_t>(b);
}

void check_sizes(const HostTetMesh& m) {
  const std::size_t np = m.ptype.size(), nt = m.tv.size() / 4, ns = m.sv.size() / 3;
  if (m.xyz.size() != 3 * np) fail("xyz has " + str(m.xyz.size()) + " values for " + str(np) + " points");
  if (m.pseg.size() != np || m.pfacet.size() != np) fail("pseg/pfacet sizes differ from the point count");
  if (m.tv.size() % 4 != 0) fail("tv size is not a multiple of 4");
  if (m.tn.size() != 4 * nt || m.tsub.size() != 4 * nt) fail("tn/tsub sizes differ from 4 per tet");
  if (m.tseg.size() != nt) fail("tseg size differs from the tet count");
  if (!m.tregion.empty() && m.tregion.size() != nt) fail("tregion is neither empty nor one per tet");
  if (m.sv.size() % 3 != 0) fail("sv size is not a multiple of 3");
  if (m.st.size() != 2 * ns || m.sfacet.size() != ns) fail("st/sfacet sizes differ from the subface count");
  if (m.seg.size() % 2 != 0) fail("seg size is odd");
  if (m.input_points < 0 || static_cast<std::size_t>(m.input_points) > np)
    fail("input_points " + str(m.input_points) + " out of range");
}

void check_ranges(const HostTetMesh& m) {
  const int np = m.points(), nt = m.tets(), ns = m.subfaces();
  for (int t = 0; t < nt; ++t) {
    for (int k = 0; k < 4; ++k) {
      const int v = m.tv[4 * t + k];
      if (v < 0 || v >= np) fail("tet " + str(t) + " vertex " + str(v) + " out of range");
      for (int j = 0; j < k; ++j)
        if (m.tv[4 * t + j] == v) fail("tet " + str(t) + " repeats vertex " + str(v));
      const int n = m.tn[4 * t + k];
      if (n < -1 || n >= 4 * nt) fail(face_name(4 * t + k) + " neighbour " + str(n) + " out of range");
      if (n >= 0 && n / 4 == t) fail(face_name(4 * t + k) + " is its own neighbour");
      const int s = m.tsub[4 * t + k];
      if (s < -1 || s >= ns) fail(face_name(4 * t + k) + " subface " + str(s) + " out of range");
    }
    if (m.tseg[t] >> 6) fail("tet " + str(t) + " has tseg bits above edge 5");
  }
  for (int s = 0; s < ns; ++s) {
    for (int k = 0; k < 3; ++k) {
      const int v = m.sv[3 * s + k];
      if (v < 0 || v >= np) fail("subface " + str(s) + " vertex " + str(v) + " out of range");
      for (int j = 0; j < k; ++j)
        if (m.sv[3 * s + j] == v) fail("subface " + str(s) + " repeats vertex " + str(v));
    }
    for (int k = 0; k < 2; ++k) {
      const int x = m.st[2 * s + k];
      if (x < -1 || x >= 4 * nt) fail("subface " + str(s) + " side " + str(k) + " out of range");
    }
    if (m.st[2 * s] < 0 && m.st[2 * s + 1] < 0) fail("subface " + str(s) + " has no tet on either side");
    if (m.sfacet[s] < 0) fail("subface " + str(s) + " has facet " + str(m.sfacet[s]));
  }
  for (int g = 0; g < m.segments(); ++g) {
    const int a = m.seg[2 * g], b = m.seg[2 * g + 1];
    if (a < 0 || a >= m.input_points || b < 0 || b >= m.input_points || a == b)
      fail("segment " + str(g) + " (" + str(a) + ", " + str(b) + ") does not join two input points");
  }
}

void check_orientation(const HostTetMesh& m) {
  const int nt = m.tets();
  int bad = -1;
#pragma omp parallel for schedule(static) if (nt > 20000)
  for (int t = 0; t < nt; ++t) {
    const double* p[4];
    for (int k = 0; k < 4; ++k) p[k] = &m.xyz[3 * static_cast<std::size_t>(m.tv[4 * t + k])];
    if (!(pred::orient3d(p[0], p[1], p[2], p[3]) > 0)) {
#pragma omp critical
      if (bad < 0 || t < bad) bad = t;
    }
  }
  if (bad >= 0) fail("tet " + str(bad) + " is not positively oriented (orient3d <= 0)");
}

void check_neighbours(const HostTetMesh& m) {
  const int nt = m.tets();
  for (int t = 0; t < nt; ++t) {
    for (int i = 0; i < 4; ++i) {
      const int x = 4 * t + i, y = m.tn[x];
      if (y < 0) {
        if (m.tsub[x] < 0) fail(face_name(x) + " has no neighbour and no subface");
        continue;
      }
      if (m.tn[y] != x) fail(face_name(x) + " -> " + face_name(y) + " is not symmetric");
      // The shared face must be the same triangle, seen in opposite orders from the two sides.
      if (cyclic_match(face_vertices(m, t, i), face_vertices(m, y / 4, y % 4)) != -1)
        fail(face_name(x) + " and " + face_name(y) + " are neighbours but do not share that face "
             "in opposite orientations");
    }
  }
}

void check_subfaces(const HostTetMesh& m) {
  const int nt = m.tets(), ns = m.subfaces();
  auto sub_vertices = [&](int s) {
    return std::array<int, 3>{m.sv[3 * s], m.sv[3 * s + 1], m.sv[3 * s + 2]};
  };
  // Tet side: tsub points to a subface that lists this face on the side its orientation says.
  for (int t = 0; t < nt; ++t) {
    for (int i = 0; i < 4; ++i) {
      const int x = 4 * t + i, s = m.tsub[x];
      if (s < 0) continue;
      const int match = cyclic_match(sub_vertices(s), face_vertices(m, t, i));
      if (match == 0) fail(face_name(x) + " has subface " + str(s) + " with other vertices");
      // Same cyclic order: (sv0, sv1, sv2) turns counter-clockwise seen from outside this tet,
      // i.e. orient3d(sv0, sv1, sv2, apex) > 0: side 0.
      const int side = match == 1 ? 0 : 1;
      if (m.st[2 * s + side] != x)
        fail(face_name(x) + " holds subface " + str(s) + " but st[" + str(2 * s + side) + "] = " +
             str(m.st[2 * s + side]));
      const int y = m.tn[x];
      if (y >= 0 && m.tsub[y] != s)
        fail(face_name(x) + " holds subface " + str(s) + " but its neighbour " + face_name(y) +
             " holds " + str(m.tsub[y]));
    }
  }
  // Subface side: every listed tet face holds it back (sides were checked above from tets).
  for (int s = 0; s < ns; ++s) {
    for (int k = 0; k < 2; ++k) {
      const int x = m.st[2 * s + k];
      if (x >= 0 && m.tsub[x] != s)
        fail("subface " + str(s) + " side " + str(k) + " is " + face_name(x) + ", which holds " +
             str(m.tsub[x]));
    }
    const int a = m.st[2 * s], b = m.st[2 * s + 1];
    if (a >= 0 && b >= 0 && m.tn[a] != b)
      fail("subface " + str(s) + " sides " + face_name(a) + " and " + face_name(b) +
           " are not neighbours");
    if ((a >= 0 && b < 0 && m.tn[a] >= 0) || (b >= 0 && a < 0 && m.tn[b] >= 0))
      fail("subface " + str(s) + " has one side empty but its tet face has a neighbour");
  }
  // Geometry, exactly: side 0's apex lies where orient3d(sv0, sv1, sv2, apex) > 0.
  int bad = -1;
#pragma omp parallel for schedule(static) if (ns > 20000)
  for (int s = 0; s < ns; ++s) {
    const double* p[3];
    for (int k = 0; k < 3; ++k) p[k] = &m.xyz[3 * static_cast<std::size_t>(m.sv[3 * s + k])];
    for (int k = 0; k < 2; ++k) {
      const int x = m.st[2 * s + k];
      if (x < 0) continue;
      const double* apex = &m.xyz[3 * static_cast<std::size_t>(m.tv[x])];  // vertex x%4 of x/4
      const double o = pred::orient3d(p[0], p[1], p[2], apex);
      if (k == 0 ? !(o > 0) : !(o < 0)) {
#pragma omp critical
        if (bad < 0 || s < bad) bad = s;
      }
    }
  }
  if (bad >= 0) fail("subface " + str(bad) + ": a side's apex is on the wrong side by orient3d");
}

// Subsegments: an edge is one iff its two endpoints lie on a common segment (its input
// endpoints, or points with that pseg). Checks the tseg bits against that rule on every
// tet, and that every segment is one chain of subsegments from one endpoint to the other.
void check_segments(const HostTetMesh& m) {
  const int np = m.points(), nt = m.tets(), ng = m.segments();
  // Segments by input endpoint (CSR), and by their endpoint pair.
  std::vector<int> start(m.input_points + 1, 0), by_point(2 * ng);
  for (int g = 0; g < ng; ++g) {
    ++start[m.seg[2 * g] + 1];
    ++start[m.seg[2 * g + 1] + 1];
  }
  for (int v = 0; v < m.input_points; ++v) start[v + 1] += start[v];
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int g = 0; g < ng; ++g) {
      by_point[fill[m.seg[2 * g]]++] = g;
      by_point[fill[m.seg[2 * g + 1]]++] = g;
    }
  }
  auto on_segment = [&](int v, int g) {
    if (v >= m.input_points) return m.ptype[v] == kSegmentPoint && m.pseg[v] == g;
    return m.seg[2 * g] == v || m.seg[2 * g + 1] == v;
  };
  // The segment both a and b lie on, or -1.
  auto common_segment = [&](int a, int b) {
    if (a >= m.input_points) std::swap(a, b);
    if (b >= m.input_points) {  // b is not an input point: only its own segment can hold it
      if (m.ptype[b] != kSegmentPoint) return -1;
      return on_segment(a, m.pseg[b]) ? m.pseg[b] : -1;
    }
    for (int k = start[a]; k < start[a + 1]; ++k)
      if (on_segment(b, by_point[k])) return by_point[k];
    return -1;
  };

  std::vector<std::uint64_t> edges;  // subsegment edges, one per tet that has them
  for (int t = 0; t < nt; ++t) {
    for (int e = 0; e < 6; ++e) {
      const int a = m.tv[4 * t + edge_corner(e, 0)], b = m.tv[4 * t + edge_corner(e, 1)];
      const bool is_sub = common_segment(a, b) >= 0;
      const bool bit = (m.tseg[t] & edge_bit(e)) != 0;
      if (is_sub != bit)
        fail("tet " + str(t) + " edge " + str(e) + " (" + str(a) + ", " + str(b) + ") " +
             (bit ? "is marked a subsegment but its ends lie on no common segment"
                  : "joins two points of one segment but is not marked a subsegment"));
      if (is_sub) edges.push_back(edge_key(a, b));
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  // Chains: each segment's points have degree 2 along it, its endpoints degree 1, and the
  // subsegment count is the number of its points plus one.
  std::vector<int> count(ng, 0), points_on(ng, 0), degree(np, 0);
  for (std::uint64_t k : edges) {
    const int a = static_cast<int>(k >> 32), b = static_cast<int>(k & 0xffffffffu);
    const int g = common_segment(a, b);
    ++count[g];
    ++degree[a];
    ++degree[b];
  }
  for (int v = m.input_points; v < np; ++v)
    if (m.ptype[v] == kSegmentPoint) {
      ++points_on[m.pseg[v]];
      if (degree[v] != 2)
        fail("segment point " + str(v) + " (segment " + str(m.pseg[v]) + ") lies on " +
             str(degree[v]) + " subsegments instead of 2");
    }
  for (int g = 0; g < ng; ++g)
    if (count[g] != points_on[g] + 1)
      fail("segment " + str(g) + " (" + str(m.seg[2 * g]) + ", " + str(m.seg[2 * g + 1]) + ") has " +
           str(count[g]) + " subsegments for " + str(points_on[g]) + " points on it: not one chain");
}

void check_points(const HostTetMesh& m) {
  const int np = m.points(), ns = m.subfaces();
  // Facet ids that exist, and which points are subface corners of which facet.
  std::vector<std::uint64_t> corner_facet;  // (point << 32) | facet
  corner_facet.reserve(m.sv.size());
  for (int s = 0; s < ns; ++s)
    for (int k = 0; k < 3; ++k)
      corner_facet.push_back((static_cast<std::uint64_t>(m.sv[3 * s + k]) << 32) |
                             static_cast<std::uint32_t>(m.sfacet[s]));
  std::sort(corner_facet.begin(), corner_facet.end());
  std::vector<char> on_subface(np, 0);
  for (std::uint64_t k : corner_facet) on_subface[k >> 32] = 1;
  auto corner_of_facet = [&](int v, int f) {
    const std::uint64_t k = (static_cast<std::uint64_t>(v) << 32) | static_cast<std::uint32_t>(f);
    return std::binary_search(corner_facet.begin(), corner_facet.end(), k);
  };

  for (int v = 0; v < np; ++v) {
    const int type = m.ptype[v], g = m.pseg[v], f = m.pfacet[v];
    const std::string name = "point " + str(v);
    if (v < m.input_points) {
      if (type != kInputPoint || g != -1 || f != -1)
        fail(name + " is an input point but has type " + str(type) + ", pseg " + str(g) +
             ", pfacet " + str(f));
      continue;
    }
    switch (type) {
      case kSegmentPoint:
        if (g < 0 || g >= m.segments() || f != -1)
          fail(name + " is a segment point with pseg " + str(g) + " and pfacet " + str(f));
        break;
      case kFacetPoint:
        if (g != -1 || f < 0) fail(name + " is a facet point with pseg " + str(g) + " and pfacet " + str(f));
        if (!corner_of_facet(v, f)) fail(name + " is a facet point of facet " + str(f) +
                                         " but no subface of that facet has it as a corner");
        break;
      case kFreePoint:
        if (g != -1 || f != -1) fail(name + " is free but has pseg " + str(g) + " and pfacet " + str(f));
        if (on_subface[v]) fail(name + " is free but is a corner of a subface");
        break;
      default:
        fail(name + " has unknown type " + str(type));
    }
  }
}

}  // namespace

void check_host_mesh(const HostTetMesh& m) {
  check_sizes(m);
  check_ranges(m);
  check_orientation(m);
  check_neighbours(m);
  check_subfaces(m);
  check_segments(m);
  check_points(m);
}

}  // namespace gdr::m3d
