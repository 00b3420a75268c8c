// check_surface: input checks and clean-up of a surface into a piecewise linear complex.
// Every decision is an exact predicate or an exact comparison of coordinates; big steps
// (sorting, degeneracy, the self-intersection search) run in parallel.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <numeric>
#include <parallel/algorithm>

#include "cdt3d/cdt3d.h"
#include "cdt3d/geometry.h"
#include "cdt3d/internal.h"
#include "gdr/error.h"

namespace gdr::cdt3d {

std::string list_items(const std::vector<std::string>& items, long long total) {
  std::string out;
  for (std::size_t i = 0; i < items.size() && i < 5; ++i) out += (i ? ", " : "") + items[i];
  if (total > static_cast<long long>(std::min<std::size_t>(items.size(), 5)))
    out += " (" + std::to_string(total) + " in all)";
  return out;
}

namespace {

constexpr int kShown = 5;  // items named in a message
constexpr double kNearlyFlat = 10.0;  // degrees: Plc::segment_flat

std::string str(long long v) { return std::to_string(v); }

void check_abort(const Callbacks& cb) {
  if (cb.abort && cb.abort()) throw Error(Status::Aborted, "aborted while checking the surface");
}

void progress(const Callbacks& cb, double f, const char* phase) {
  if (cb.progress) cb.progress(f, phase);
}

bool finite(const Point3& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

void check_finite(const Surface& s) {
  std::vector<std::string> bad;
  long long count = 0;
  auto look = [&](const Point3& p, const std::string& name) {
    if (finite(p)) return;
    if (count++ < kShown) bad.push_back(name);
  };
  for (std::size_t i = 0; i < s.points.size(); ++i) look(s.points[i], "point " + str(i));
  for (std::size_t i = 0; i < s.holes.size(); ++i) look(s.holes[i], "hole seed " + str(i));
  for (std::size_t i = 0; i < s.regions.size(); ++i) look(s.regions[i].point, "region seed " + str(i));
  if (count) throw Error(Status::InvalidInput, "non-finite coordinates (NaN or Inf): " + list_items(bad, count));
  for (std::size_t i = 0; i < s.regions.size(); ++i)
    if (!std::isfinite(s.regions[i].max_volume) || s.regions[i].max_volume < 0)
      throw Error(Status::InvalidInput, "region seed " + str(i) + " has an invalid maximum volume");
}

void check_ranges(const Surface& s) {
  const long long np = static_cast<long long>(s.points.size());
  std::vector<std::string> bad;
  long long count = 0;
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    for (int v : s.triangles[t])
      if (v < 0 || v >= np) {
        if (count++ < kShown) bad.push_back("triangle " + str(t) + " (vertex " + str(v) + ")");
        break;
      }
  for (std::size_t g = 0; g < s.segments.size(); ++g)
    for (int v : s.segments[g])
      if (v < 0 || v >= np) {
        if (count++ < kShown) bad.push_back("segment " + str(g) + " (vertex " + str(v) + ")");
        break;
      }
  if (count)
    throw Error(Status::InvalidInput, "vertex indices out of range [0, " + str(np - 1) + "]: " +
                                          list_items(bad, count));
  if (!s.triangle_facet.empty()) {
    if (s.triangle_facet.size() != s.triangles.size())
      throw Error(Status::InvalidInput, "triangle_facet has " + str(s.triangle_facet.size()) +
                                            " entries for " + str(s.triangles.size()) + " triangles");
    for (std::size_t t = 0; t < s.triangle_facet.size(); ++t)
      if (s.triangle_facet[t] < 0)
        throw Error(Status::InvalidInput, "triangle " + str(t) + " has facet id " + str(s.triangle_facet[t]));
  }
  if (s.triangles.empty()) throw Error(Status::InvalidInput, "the surface has no triangles");
}

// Exact duplicates merged into their first occurrence; points nothing uses dropped.
// Returns, per PLC point, its input point.
std::vector<int> merge_points(const Surface& s, const Callbacks& cb, Plc& plc) {
  const int np = static_cast<int>(s.points.size());
  std::vector<int> order(np);
  std::iota(order.begin(), order.end(), 0);
  const auto& p = s.points;
  // -0 and 0 compare equal, so they merge.
  __gnu_parallel::sort(order.begin(), order.end(), [&](int a, int b) {
    if (p[a].x != p[b].x) return p[a].x < p[b].x;
    if (p[a].y != p[b].y) return p[a].y < p[b].y;
    if (p[a].z != p[b].z) return p[a].z < p[b].z;
    return a < b;
  });
  std::vector<int> first(np);  // input point -> first input point with its coordinates
  for (int i = 0; i < np; ++i) {
    const int a = order[i];
    const bool same = i > 0 && p[order[i - 1]].x == p[a].x && p[order[i - 1]].y == p[a].y &&
                      p[order[i - 1]].z == p[a].z;
    first[a] = same ? first[order[i - 1]] : a;
  }
  std::vector<char> used(np, 0);
  for (const auto& t : s.triangles)
    for (int v : t) used[first[v]] = 1;
  for (const auto& g : s.segments)
    for (int v : g) used[first[v]] = 1;
  std::vector<int> origin;
  plc.point_map.assign(np, -1);
  for (int v = 0; v < np; ++v) {
    if (first[v] == v && used[v]) {
      plc.point_map[v] = static_cast<int>(origin.size());
      origin.push_back(v);
      plc.points.push_back({p[v].x + 0.0, p[v].y + 0.0, p[v].z + 0.0});
    }
  }
  for (int v = 0; v < np; ++v) {
    if (!used[first[v]]) {
      ++plc.unused_points;
    } else if (first[v] != v) {
      plc.point_map[v] = plc.point_map[first[v]];
      ++plc.duplicate_points_merged;
    }
  }
  if (plc.duplicate_points_merged && cb.warning)
    cb.warning("merged " + str(plc.duplicate_points_merged) +
               " duplicate points (exactly equal coordinates) into their first occurrence");
  if (plc.unused_points && cb.warning)
    cb.warning("ignored " + str(plc.unused_points) + " points that no triangle or segment uses");
  return origin;
}

void check_dimension(const std::vector<Point3>& p) {
  const std::size_t n = p.size();
  std::size_t c = 2, d;
  while (c < n && geom::projection_axis(p[0], p[1], p[c]) < 0) ++c;
  for (d = c + 1; c < n && d < n; ++d)
    if (geom::orient3d(p[0], p[1], p[c], p[d]) != 0) break;
  if (n < 4 || c >= n || d >= n)
    throw Error(Status::InvalidInput,
                n < 4 ? "fewer than 4 distinct points: there is no volume to mesh"
                      : "all points are coplanar: there is no volume to mesh");
}

// Triangles in PLC points; degenerate ones refused; exact duplicates (same vertex set)
// merged into the first.
// A triangle whose corner lies within a few units in the last place of its coordinates of
// the line through the other two: zero area but for rounding (a midpoint written out).
bool degenerate_up_to_rounding(const Point3& a, const Point3& b, const Point3& c) {
  const auto dot3 = [](const double* p, const double* q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; };
  const double u[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, v[3] = {c.x - a.x, c.y - a.y, c.z - a.z},
               w[3] = {c.x - b.x, c.y - b.y, c.z - b.z};
  const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
  const double longest2 = std::max({dot3(u, u), dot3(v, v), dot3(w, w)});
  const double height = std::sqrt(dot3(n, n) / longest2);
  const double magnitude = std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z), std::fabs(b.x),
                                     std::fabs(b.y), std::fabs(b.z), std::fabs(c.x), std::fabs(c.y),
                                     std::fabs(c.z), std::sqrt(longest2)});
  return height < 8 * std::numeric_limits<double>::epsilon() * magnitude;
}

void clean_triangles(const Surface& s, const CheckOptions& options, const Callbacks& cb, Plc& plc) {
  const long long nt = static_cast<long long>(s.triangles.size());
  std::vector<std::array<int, 3>> tri(nt);
  std::vector<char> degenerate(nt, 0);  // 1: exactly, 2: up to rounding
#pragma omp parallel for schedule(static) if (nt > 20000)
  for (long long t = 0; t < nt; ++t) {
    for (int k = 0; k < 3; ++k) tri[t][k] = plc.point_map[s.triangles[t][k]];
    const auto& v = tri[t];
    const Point3 &a = plc.points[v[0]], &b = plc.points[v[1]], &c = plc.points[v[2]];
    if (v[0] == v[1] || v[1] == v[2] || v[0] == v[2] || geom::projection_axis(a, b, c) < 0)
      degenerate[t] = 1;
    else if (options.refuse_rounding_degenerate && degenerate_up_to_rounding(a, b, c))
      degenerate[t] = 2;
  }
  for (const int kind : {1, 2}) {
    std::vector<std::string> bad;
    long long count = 0;
    for (long long t = 0; t < nt; ++t)
      if (degenerate[t] == kind && count++ < kShown) {
        const auto& v = s.triangles[t];
        bad.push_back(str(t) + " (" + str(v[0]) + ", " + str(v[1]) + ", " + str(v[2]) + ")");
      }
    if (count && kind == 1)
      throw Error(Status::InvalidInput,
                  "degenerate triangles (a repeated vertex, or zero area): " + list_items(bad, count));
    if (count)
      throw Error(Status::InvalidInput,
                  "triangles of zero area but for rounding (a corner within a few units in the last place "
                  "of its coordinates of the line through the other two): " +
                      list_items(bad, count) +
                      ". Remove them and join their neighbours; the restricted Delaunay mesher (gdr rdt, "
                      "GPU Restricted Delaunay 3D) accepts them");
  }

  std::vector<std::array<int, 4>> key(nt);  // sorted vertices, then the triangle
  for (long long t = 0; t < nt; ++t) {
    std::array<int, 3> v = tri[t];
    std::sort(v.begin(), v.end());
    key[t] = {v[0], v[1], v[2], static_cast<int>(t)};
  }
  __gnu_parallel::sort(key.begin(), key.end());
  std::vector<char> keep(nt, 1);
  std::vector<std::string> dups;
  for (long long i = 1; i < nt; ++i)
    if (key[i][0] == key[i - 1][0] && key[i][1] == key[i - 1][1] && key[i][2] == key[i - 1][2]) {
      keep[key[i][3]] = 0;
      ++plc.duplicate_triangles_merged;
    }
  for (long long i = 1, first = 0; i < nt; ++i) {
    const bool same = key[i][0] == key[i - 1][0] && key[i][1] == key[i - 1][1] && key[i][2] == key[i - 1][2];
    if (!same) first = i;
    else if (dups.size() < kShown) dups.push_back(str(key[i][3]) + " = " + str(key[first][3]));
  }
  for (long long t = 0; t < nt; ++t)
    if (keep[t]) {
      plc.triangles.push_back(tri[t]);
      plc.triangle_origin.push_back(static_cast<int>(t));
    }
  if (plc.duplicate_triangles_merged && cb.warning)
    cb.warning("merged " + str(plc.duplicate_triangles_merged) +
               " duplicate triangles (same three vertices) into their first occurrence: " +
               list_items(dups, plc.duplicate_triangles_merged));
}

void check_closed(const EdgeTable& edges, const std::vector<int>& origin) {
  std::vector<std::string> open;
  long long count = 0;
  for (int k = 0; k < edges.size(); ++k)
    if (edges.count(k) == 1 && count++ < kShown)
      open.push_back("(" + str(origin[edges.edge[k][0]]) + ", " + str(origin[edges.edge[k][1]]) + ")");
  if (count)
    throw Error(Status::InvalidInput,
                "the surface is open: edges with one triangle " + list_items(open, count) +
                    ". A tetrahedral mesh needs a closed surface: fill the holes first (ParaView's "
                    "Fill Holes filter, vtkFillHolesFilter), or mesh the surface itself with "
                    "'gdr rdt' (restricted Delaunay refinement)");
}

void check_self_intersections(const Plc& plc) {
  std::vector<std::array<int, 2>> pairs;
  const long long count = find_clashing_triangles(plc.points, plc.triangles, kShown, pairs);
  if (!count) return;
  std::vector<std::string> items;
  for (const auto& p : pairs) {
    int a = plc.triangle_origin[p[0]], b = plc.triangle_origin[p[1]];
    if (a > b) std::swap(a, b);
    items.push_back(str(a) + " and " + str(b));
  }
  throw Error(Status::SelfIntersectingInput,
              "the surface intersects itself: triangle pairs " + list_items(items, count));
}

// Keeps the triangles with a domain cell on at least one side.
void drop_outside_triangles(Plc& plc, const Callbacks& cb) {
  std::size_t n = 0;
  for (std::size_t t = 0; t < plc.triangles.size(); ++t) {
    const auto& c = plc.triangle_cell[t];
    if (!plc.cell_in_domain[c[0]] && !plc.cell_in_domain[c[1]]) continue;
    plc.triangles[n] = plc.triangles[t];
    plc.triangle_origin[n] = plc.triangle_origin[t];
    plc.triangle_cell[n] = plc.triangle_cell[t];
    ++n;
  }
  plc.outside_triangles = static_cast<long long>(plc.triangles.size() - n);
  plc.triangles.resize(n);
  plc.triangle_origin.resize(n);
  plc.triangle_cell.resize(n);
  if (plc.outside_triangles && cb.warning)
    cb.warning("ignored " + str(plc.outside_triangles) +
               " triangles with no meshed volume on either side (inside holes or cavities)");
}

// Normal (b - a) x (c - a) of triangle abc, rounded: for the near-flat tests only.
std::array<double, 3> normal_of(const Point3& a, const Point3& b, const Point3& c) {
  const double u[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, v[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

double dot3(const std::array<double, 3>& u, const std::array<double, 3>& v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

std::array<double, 3> unit_normal(const Plc& plc, int t) {
  const auto& r = plc.triangles[t];
  std::array<double, 3> n = normal_of(plc.points[r[0]], plc.points[r[1]], plc.points[r[2]]);
  const double l = std::sqrt(dot3(n, n));
  for (double& x : n) x /= l;
  return n;
}

// Facets: triangles joined across edges of exactly two triangles that are exactly coplanar
// and flat (on opposite sides of the edge), so their shared edge is not a segment. Then,
// with options.coplanar_angle > 0, these planar facets are merged across edges where they
// meet within that angle of flat (TetGen's facet separation tolerance), as long as every
// triangle of a merged facet stays within options.merge_cone of its first triangle's plane
// (so one projection serves the whole facet). A merged facet reports the input facet id of
// its first triangle (every polygon of polydata is a facet of its own: ids never stop it).
void make_facets(const Surface& s, const EdgeTable& edges, const CheckOptions& options, Plc& plc) {
  const int nt = static_cast<int>(plc.triangles.size());
  const auto& P = plc.points;
  // Each edge of two triangles: 1 when they are coplanar and flat (one facet), 2 when near
  // flat (a merge candidate), else 0. Exact tests, in parallel; the unions after.
  enum : signed char { kApart, kCoplanar, kNearlyFlat };
  const int ne = edges.size();
  std::vector<signed char> kind(ne, kApart);
  const double cos_flat = std::cos(options.coplanar_angle * 3.14159265358979323846 / 180.0);
#pragma omp parallel for schedule(static) if (ne > 20000)
  for (int k = 0; k < ne; ++k) {
    if (edges.count(k) != 2) continue;
    const int t1 = edges.tri[edges.start[k]], t2 = edges.tri[edges.start[k] + 1];
    const int a = edges.edge[k][0], b = edges.edge[k][1];
    const auto& v1 = plc.triangles[t1];
    const auto& v2 = plc.triangles[t2];
    const int c = v1[0] + v1[1] + v1[2] - a - b, d = v2[0] + v2[1] + v2[2] - a - b;
    if (geom::orient3d(P[a], P[b], P[c], P[d]) != 0) {
      if (options.coplanar_angle > 0) {
        // Flat: the two triangles' normals, turned the same way round the edge, nearly opposite.
        const auto n1 = normal_of(P[a], P[b], P[c]), n2 = normal_of(P[a], P[b], P[d]);
        if (-dot3(n1, n2) >= cos_flat * std::sqrt(dot3(n1, n1) * dot3(n2, n2))) kind[k] = kNearlyFlat;
      }
      continue;
    }
    const int axis = geom::projection_axis(P[a], P[b], P[c]);
    if (geom::orient2d(axis, P[a], P[b], P[c]) != geom::orient2d(axis, P[a], P[b], P[d])) kind[k] = kCoplanar;
  }
  UnionFind uf(nt);
  std::vector<int> flat_edges;  // near-flat but not coplanar: merge candidates
  for (int k = 0; k < ne; ++k) {
    if (kind[k] == kCoplanar) uf.unite(edges.tri[edges.start[k]], edges.tri[edges.start[k] + 1]);
    else if (kind[k] == kNearlyFlat) flat_edges.push_back(k);
  }
  plc.triangle_facet.assign(nt, -1);
  plc.facet_origin.clear();
  plc.facet_planar.clear();
  std::vector<int> id(nt, -1);
  for (int t = 0; t < nt; ++t) {
    const int root = uf.find(t);  // the smallest triangle of the facet
    if (id[root] < 0) {
      id[root] = static_cast<int>(plc.facet_origin.size());
      const int input = plc.triangle_origin[t];
      plc.facet_origin.push_back(s.triangle_facet.empty() ? input : s.triangle_facet[input]);
      plc.facet_planar.push_back(1);
    }
    plc.triangle_facet[t] = id[root];
  }
  if (flat_edges.empty()) return;

  // Merge planar facets across near-flat edges: grown from each facet in turn (breadth
  // first), taking a neighbour only when all its triangles lie within the cone. Per facet
  // its triangles and its neighbours across near-flat edges, as counted arrays.
  const int nf = static_cast<int>(plc.facet_origin.size());
  const auto counted = [nf](const std::vector<std::array<int, 2>>& pairs, std::vector<int>& start,
                            std::vector<int>& items) {
    start.assign(nf + 1, 0);
    for (const auto& p : pairs) ++start[p[0] + 1];
    for (int f = 0; f < nf; ++f) start[f + 1] += start[f];
    items.resize(pairs.size());
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (const auto& p : pairs) items[fill[p[0]]++] = p[1];
  };
  std::vector<std::array<int, 2>> pairs;
  pairs.reserve(nt);
  for (int t = 0; t < nt; ++t) pairs.push_back({plc.triangle_facet[t], t});
  std::vector<int> tri_start, tris;
  counted(pairs, tri_start, tris);
  pairs.clear();
  for (int k : flat_edges) {
    const int f1 = plc.triangle_facet[edges.tri[edges.start[k]]];
    const int f2 = plc.triangle_facet[edges.tri[edges.start[k] + 1]];
    if (f1 == f2) continue;
    pairs.push_back({f1, f2});
    pairs.push_back({f2, f1});
  }
  std::vector<int> across_start, across;
  counted(pairs, across_start, across);
  const double cos_cone = std::cos(options.merge_cone * 3.14159265358979323846 / 180.0);
  std::vector<int> group(nf, -1);
  std::vector<int> queue;
  int groups = 0;
  for (int f = 0; f < nf; ++f) {
    if (group[f] >= 0) continue;
    const auto n0 = unit_normal(plc, tris[tri_start[f]]);
    group[f] = groups;
    queue.assign(1, f);
    for (std::size_t q = 0; q < queue.size(); ++q)
      for (int i = across_start[queue[q]]; i < across_start[queue[q] + 1]; ++i) {
        const int g = across[i];
        if (group[g] >= 0) continue;
        bool in_cone = true;
        for (int j = tri_start[g]; in_cone && j < tri_start[g + 1]; ++j)
          in_cone = std::fabs(dot3(unit_normal(plc, tris[j]), n0)) >= cos_cone;
        if (!in_cone) continue;
        group[g] = groups;
        queue.push_back(g);
      }
    ++groups;
  }
  std::vector<int> origin(groups, -1);
  std::vector<unsigned char> planar(groups, 0), members(groups, 0);
  for (int f = 0; f < nf; ++f) {
    const int g = group[f];
    if (origin[g] < 0) origin[g] = plc.facet_origin[f];
    members[g] = static_cast<unsigned char>(std::min(2, members[g] + 1));
  }
  for (int g = 0; g < groups; ++g) planar[g] = members[g] == 1;
  for (int t = 0; t < nt; ++t) plc.triangle_facet[t] = group[plc.triangle_facet[t]];
  plc.facet_origin = std::move(origin);
  plc.facet_planar = std::move(planar);
}

// Segments: edges whose triangles are not all in one facet, and the input's segments.
void make_segments(const Surface& s, const EdgeTable& edges, const std::vector<int>& origin, bool facets, Plc& plc) {
  for (int k = 0; facets && k < edges.size(); ++k) {
    const int first = edges.tri[edges.start[k]];
    bool one_facet = edges.count(k) == 2;
    for (int i = edges.start[k]; one_facet && i < edges.start[k + 1]; ++i)
      one_facet = plc.triangle_facet[edges.tri[i]] == plc.triangle_facet[first];
    if (!one_facet) plc.segments.push_back(edges.edge[k]);
  }
  std::vector<std::string> bad;
  long long count = 0;
  for (std::size_t g = 0; g < s.segments.size(); ++g) {
    int a = plc.point_map[s.segments[g][0]], b = plc.point_map[s.segments[g][1]];
    if (a == b) {
      if (count++ < kShown) bad.push_back(str(g) + " (" + str(s.segments[g][0]) + ", " + str(s.segments[g][1]) + ": zero length)");
      continue;
    }
    if (a > b) std::swap(a, b);
    const std::array<int, 2> e = {a, b};
    if (!std::binary_search(edges.edge.begin(), edges.edge.end(), e)) {
      if (count++ < kShown) bad.push_back(str(g) + " (" + str(origin[a]) + ", " + str(origin[b]) + ")");
      continue;
    }
    plc.segments.push_back(e);
  }
  if (count)
    throw Error(Status::InvalidInput,
                "segments that are not edges of the surface: " + list_items(bad, count) +
                    ". Segments inside facets or free in the volume are not supported yet");
  // The edges' segments come sorted (EdgeTable's order); the input's own may not.
  if (!s.segments.empty() || !facets) {
    std::sort(plc.segments.begin(), plc.segments.end());
    plc.segments.erase(std::unique(plc.segments.begin(), plc.segments.end()), plc.segments.end());
  }
  if (!facets) return;
  // Nearly flat segments: two triangles meeting within kNearlyFlat degrees of flat.
  const double cos_flat = std::cos(kNearlyFlat * 3.14159265358979323846 / 180.0);
  const auto& P = plc.points;
  const long long ng = static_cast<long long>(plc.segments.size());
  plc.segment_flat.assign(ng, 0);
#pragma omp parallel for schedule(static) if (ng > 20000)
  for (long long g = 0; g < ng; ++g) {
    const auto it = std::lower_bound(edges.edge.begin(), edges.edge.end(), plc.segments[g]);
    const int k = static_cast<int>(it - edges.edge.begin());
    if (it == edges.edge.end() || *it != plc.segments[g] || edges.count(k) != 2) continue;
    const int a = plc.segments[g][0], b = plc.segments[g][1];
    const auto& v1 = plc.triangles[edges.tri[edges.start[k]]];
    const auto& v2 = plc.triangles[edges.tri[edges.start[k] + 1]];
    const int c = v1[0] + v1[1] + v1[2] - a - b, d = v2[0] + v2[1] + v2[2] - a - b;
    const auto n1 = normal_of(P[a], P[b], P[c]), n2 = normal_of(P[a], P[b], P[d]);
    plc.segment_flat[g] = -dot3(n1, n2) >= cos_flat * std::sqrt(dot3(n1, n1) * dot3(n2, n2));
  }
}

}  // namespace

Plc check_surface(const Surface& surface, const CheckOptions& options, const Callbacks& callbacks) {
  Plc plc;
  progress(callbacks, 0.0, "checking the surface");
  // GDR_TRACE: the time of each check on stderr.
  const bool trace = std::getenv("GDR_TRACE") != nullptr;
  auto last = std::chrono::steady_clock::now();
  auto stamp = [&](const char* what) {
    if (!trace) return;
    const auto now = std::chrono::steady_clock::now();
    std::fprintf(stderr, "gdr-trace check %s: %.3f s\n", what, std::chrono::duration<double>(now - last).count());
    last = now;
  };
  check_finite(surface);
  check_ranges(surface);
  const std::vector<int> origin = merge_points(surface, callbacks, plc);
  check_dimension(plc.points);
  clean_triangles(surface, options, callbacks, plc);
  stamp("finite, merge, clean");
  plc.holes = surface.holes;
  plc.regions = surface.regions;
  check_abort(callbacks);

  EdgeTable edges = build_edges(plc.triangles);
  if (options.require_closed) check_closed(edges, origin);
  stamp("edges, closed");
  progress(callbacks, 0.2, "self-intersections");
  check_self_intersections(plc);
  stamp("self-intersections");
  check_abort(callbacks);

  if (options.require_closed) {
    progress(callbacks, 0.6, "cells and volume");
    classify_cells(plc, edges, plc.triangle_origin, callbacks);
    bool any = false;
    for (unsigned char in : plc.cell_in_domain) any = any || in;
    if (!any) throw Error(Status::InvalidInput, "nothing to mesh: every enclosed volume is a hole");
      drop_outside_triangles(plc, callbacks);
    if (plc.outside_triangles) edges = build_edges(plc.triangles);
  }
  stamp("cells");
  for (int k = 0; k < edges.size(); ++k) {
    plc.open_edges += edges.count(k) == 1;
    if (edges.count(k) > 2 && plc.first_branching_edge[0] < 0) {
      plc.first_branching_edge = edges.edge[k];
      plc.first_branching_triangles = edges.count(k);
    }
  }
  progress(callbacks, 0.8, "facets and segments");
  if (options.facets) make_facets(surface, edges, options, plc);
  make_segments(surface, edges, origin, options.facets, plc);
  if (options.keep_edges) plc.edges = std::make_shared<const EdgeTable>(std::move(edges));
  stamp("facets, segments");
  progress(callbacks, 1.0, "surface checked");
  return plc;
}

}  // namespace gdr::cdt3d
