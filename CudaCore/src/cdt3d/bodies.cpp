// Bodies of a PLC, each as a PLC of its own, and their meshes merged (bodies.h).
#include "cdt3d/bodies.h"

#include <algorithm>
#include <cmath>

#include "cdt3d/internal.h"

namespace gdr::cdt3d {

// Triangles are in one body when they share a point (so that no segment or point is meshed
// twice, differently) or bound one domain cell (a cavity's surface with the part around it).
Bodies find_bodies(const Plc& plc) {
  const std::size_t nt = plc.triangles.size();
  UnionFind uf(nt);
  std::vector<int> at_point(plc.points.size(), -1), at_cell(plc.cell_in_domain.size(), -1);
  const auto join = [&](std::vector<int>& first, int key, int t) {
    if (first[key] < 0) first[key] = t;
    else uf.unite(t, first[key]);
  };
  for (std::size_t t = 0; t < nt; ++t) {
    for (const int v : plc.triangles[t]) join(at_point, v, static_cast<int>(t));
    for (const int c : plc.triangle_cell[t])
      if (c >= 0 && plc.cell_in_domain[c]) join(at_cell, c, static_cast<int>(t));
  }
  Bodies b;
  b.of_triangle.assign(nt, -1);
  std::vector<int> body_of_root(nt, -1);
  for (std::size_t t = 0; t < nt; ++t) {
    int& r = body_of_root[uf.find(static_cast<int>(t))];
    if (r < 0) r = b.count++;
    b.of_triangle[t] = r;
  }
  return b;
}

BodyPlc body_plc(const Plc& plc, const Bodies& bodies, int body, const std::vector<double>& seeds) {
  BodyPlc r;
  Plc& q = r.plc;
  std::vector<int> local(plc.points.size(), -1);
  std::vector<char> cell_here(plc.cell_in_domain.size(), 0);
  for (std::size_t t = 0; t < plc.triangles.size(); ++t) {
    if (bodies.of_triangle[t] != body) continue;
    std::array<int, 3> tri;
    for (int k = 0; k < 3; ++k) {
      const int v = plc.triangles[t][k];
      if (local[v] < 0) {
        local[v] = static_cast<int>(r.point.size());
        r.point.push_back(v);
        q.points.push_back(plc.points[v]);
      }
      tri[k] = local[v];
    }
    q.triangles.push_back(tri);
    if (t < plc.triangle_origin.size()) q.triangle_origin.push_back(plc.triangle_origin[t]);
    q.triangle_facet.push_back(plc.triangle_facet[t]);
    q.triangle_cell.push_back(plc.triangle_cell[t]);
    for (const int c : plc.triangle_cell[t])
      if (c >= 0) cell_here[c] = 1;
  }
  // A segment is an edge of triangles, all of one body (they share its ends).
  for (std::size_t g = 0; g < plc.segments.size(); ++g) {
    const int a = local[plc.segments[g][0]], b = local[plc.segments[g][1]];
    if (a < 0 || b < 0) continue;
    q.segments.push_back({a, b});
    r.segment.push_back(static_cast<int>(g));
    if (g < plc.segment_flat.size()) q.segment_flat.push_back(plc.segment_flat[g]);
  }
  q.facet_origin = plc.facet_origin;
  q.facet_planar = plc.facet_planar;
  q.holes = plc.holes;
  q.regions = plc.regions;
  q.cell_in_domain = plc.cell_in_domain;
  q.cell_region = plc.cell_region;
  q.cell_volume = plc.cell_volume;
  for (std::size_t c = 0; c < cell_here.size(); ++c)
    if (cell_here[c] && plc.cell_in_domain[c]) q.volume += plc.cell_volume[c];
  // Interior seeds in the body's box: those outside its domain fall outside and are dropped.
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Point3& p : q.points) {
    const double c[3] = {p.x, p.y, p.z};
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], c[d]), hi[d] = std::max(hi[d], c[d]);
  }
  for (std::size_t i = 0; i + 2 < seeds.size(); i += 3) {
    bool inside = true;
    for (int d = 0; d < 3; ++d) inside = inside && seeds[i + d] > lo[d] && seeds[i + d] < hi[d];
    if (inside) r.seeds.insert(r.seeds.end(), seeds.begin() + i, seeds.begin() + i + 3);
  }
  return r;
}

m3d::HostTetMesh merge_bodies(const Plc& plc, const std::vector<BodyPlc>& bodies,
                              const std::vector<m3d::HostTetMesh>& parts) {
  const int nin = static_cast<int>(plc.points.size());
  std::size_t np = nin, nt = 0, ns = 0;
  for (const auto& p : parts) {
    np += p.points() - p.input_points;
    nt += p.tets();
    ns += p.subfaces();
  }
  m3d::HostTetMesh m;
  m.input_points = nin;
  m.xyz.reserve(3 * np);
  for (const Point3& p : plc.points) m.xyz.insert(m.xyz.end(), {p.x, p.y, p.z});
  m.ptype.assign(nin, m3d::kInputPoint);
  m.pseg.assign(nin, -1);
  m.pfacet.assign(nin, -1);
  m.tv.reserve(4 * nt);
  m.tn.reserve(4 * nt);
  m.tsub.reserve(4 * nt);
  m.tseg.assign(nt, 0);
  const bool regions = !plc.regions.empty();
  m.sv.reserve(3 * ns);
  m.st.reserve(2 * ns);
  m.sfacet.reserve(ns);
  int added = nin, toff = 0, soff = 0;
  for (std::size_t b = 0; b < parts.size(); ++b) {
    const m3d::HostTetMesh& p = parts[b];
    const BodyPlc& body = bodies[b];
    const int first_added = added;
    for (int v = p.input_points; v < p.points(); ++v) {
      m.xyz.insert(m.xyz.end(), {p.xyz[3 * v], p.xyz[3 * v + 1], p.xyz[3 * v + 2]});
      m.ptype.push_back(p.ptype[v]);
      m.pseg.push_back(p.pseg[v] >= 0 ? body.segment[p.pseg[v]] : -1);
      m.pfacet.push_back(p.pfacet[v]);
      ++added;
    }
    const auto point = [&](int v) { return v < p.input_points ? body.point[v] : first_added + v - p.input_points; };
    const auto face = [&](int x) { return x < 0 ? -1 : 4 * toff + x; };
    for (std::size_t k = 0; k < p.tv.size(); ++k) {
      m.tv.push_back(point(p.tv[k]));
      m.tn.push_back(face(p.tn[k]));
      m.tsub.push_back(p.tsub[k] < 0 ? -1 : soff + p.tsub[k]);
    }
    if (regions) m.tregion.insert(m.tregion.end(), p.tregion.begin(), p.tregion.end());
    for (const int v : p.sv) m.sv.push_back(point(v));
    for (const int x : p.st) m.st.push_back(face(x));
    m.sfacet.insert(m.sfacet.end(), p.sfacet.begin(), p.sfacet.end());
    toff += p.tets();
    soff += p.subfaces();
  }
  return m;
}

}  // namespace gdr::cdt3d
