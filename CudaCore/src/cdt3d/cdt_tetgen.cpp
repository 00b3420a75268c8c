// initial_cdt: the constrained Delaunay tetrahedralization of a checked PLC by TetGen's
// library, mapped once (no text files) into the engines' HostTetMesh.
//
// What goes to TetGen: the PLC points; one TetGen facet per PLC triangle with marker
// facet + 1 (F = facet count), so subfaces and facet Steiner points come back with their
// facet; Plc::segments as TetGen edges with marker F + 1 + segment, so Steiner points on
// segments come back with their segment. Holes and regions are not passed: check_surface
// has already decided, exactly, which cells form the domain (TetGen cannot express the
// cavity rule), so TetGen meshes everything the surface encloses and the cells outside the
// domain are removed here, by flooding tets from their subfaces.
//
// Switches: "pcnnO0JQ": p (PLC: TetGen's constrained Delaunay tetrahedralization, which may
// split segments and facets with Steiner points to recover them; TetGen merges triangles of
// one marker, i.e. of one facet, that meet within its default 0.1 degree of flat. A facet
// that check_surface merged across bends larger than that (coplanar_angle) keeps TetGen
// segments inside, whose Steiner points come back marked with the facet: refinement flips
// those edges. Asking TetGen to merge them too, at 2-5 degrees, crashed it or gave
// inconsistent subfaces on boat.off), c (keep the convex hull:
// TetGen's own removal of the exterior cost 0.8 s of 5.5 s on a 370k-triangle surface and is
// redundant with ours, which also removes the cells outside), nn (neighbours, and the
// tetrahedra on either side of each subface: no search of the faces for them), O0 (no
// mesh optimisation: its flips and smoothing would leave a mesh that is not constrained
// Delaunay), J (keep the point numbering), Q (quiet). Measured on ../shared/data: Y (keep
// the input surface unsplit) leaves faces that are not locally Delaunay (2958 on boat.off,
// 318 on fandisk.off, 148 on penguin_hr.off) because TetGen then recovers the boundary with
// interior Steiner points and flips; the refinement engine's cavities need a constrained
// Delaunay mesh, so Y is only the last attempt when "p" fails in every order (TetGen 1.5 on
// many turned cylinders of fuzz3d), with a warning that counts the faces left not locally
// Delaunay.
#define TETLIBRARY
#include <tetgen.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <csignal>
#include <random>
#include <numeric>

#include "cdt3d/bodies.h"
#include "cdt3d/cdt3d.h"
#include "cdt3d/geometry.h"
#include "cdt3d/internal.h"
#include "cdt3d/tet_edits.h"
#include "cdt3d/tetgen_process.h"
#include "gdr/error.h"
#include "mesh3d/tet_topology.h"
#include "predicates/predicates.h"

namespace gdr::cdt3d {
namespace {

using m3d::HostTetMesh;

std::string str(long long v) { return std::to_string(v); }

[[noreturn]] void internal(const std::string& what) {
  throw Error(Status::InternalError, "initial CDT: " + what);
}

// Fills TetGen's input, the PLC points and the seeds in `order` (TetGen's point k is our
// point order[k]; TetGen's insertion order follows from it). TetGen frees these arrays
// itself (tetgenio's destructor).
void fill_input(const Plc& plc, const std::vector<double>& seeds, const std::vector<int>& order, tetgenio& in) {
  const int nin = static_cast<int>(plc.points.size());
  const int np = static_cast<int>(order.size());
  const int nt = static_cast<int>(plc.triangles.size());
  const int nf = static_cast<int>(plc.facet_origin.size());
  std::vector<int> at(np);  // TetGen's number of our point i
  for (int k = 0; k < np; ++k) at[order[k]] = k;
  in.firstnumber = 0;
  in.numberofpoints = np;
  in.pointlist = new REAL[3 * static_cast<std::size_t>(np)];
  in.pointmarkerlist = new int[np];  // zeros: asks TetGen for Steiner point markers
  for (int k = 0; k < np; ++k) {
    const int i = order[k];
    const double* seed = i < nin ? nullptr : &seeds[3 * static_cast<std::size_t>(i - nin)];
    in.pointlist[3 * k] = seed ? seed[0] : plc.points[i].x;
    in.pointlist[3 * k + 1] = seed ? seed[1] : plc.points[i].y;
    in.pointlist[3 * k + 2] = seed ? seed[2] : plc.points[i].z;
  }
  std::fill(in.pointmarkerlist, in.pointmarkerlist + np, 0);
  in.numberoffacets = nt;
  in.facetlist = new tetgenio::facet[nt];
  in.facetmarkerlist = new int[nt];
  for (int t = 0; t < nt; ++t) {
    tetgenio::facet& f = in.facetlist[t];
    tetgenio::init(&f);
    f.numberofpolygons = 1;
    f.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&f.polygonlist[0]);
    f.polygonlist[0].numberofvertices = 3;
    f.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) f.polygonlist[0].vertexlist[k] = at[plc.triangles[t][k]];
    in.facetmarkerlist[t] = plc.triangle_facet[t] + 1;
  }
  const int ns = static_cast<int>(plc.segments.size());
  in.numberofedges = ns;
  in.edgelist = new int[2 * static_cast<std::size_t>(ns)];
  in.edgemarkerlist = new int[ns];
  for (int g = 0; g < ns; ++g) {
    in.edgelist[2 * g] = at[plc.segments[g][0]];
    in.edgelist[2 * g + 1] = at[plc.segments[g][1]];
    in.edgemarkerlist[g] = nf + 1 + g;
  }
}

// Back to our numbering after fill_input's `order`: TetGen's points 0..n-1 (n = order's
// size) become ours, in the point arrays and in every tetrahedron and subface.
void restore_order(const std::vector<int>& order, tetgenio& out) {
  const int n = static_cast<int>(order.size());
  std::vector<REAL> xyz(out.pointlist, out.pointlist + 3 * static_cast<std::size_t>(n));
  std::vector<int> mark(n, 0);
  for (int k = 0; k < n; ++k) {
    for (int c = 0; c < 3; ++c) out.pointlist[3 * order[k] + c] = xyz[3 * static_cast<std::size_t>(k) + c];
    if (out.pointmarkerlist) mark[order[k]] = out.pointmarkerlist[k];
  }
  if (out.pointmarkerlist) std::copy(mark.begin(), mark.end(), out.pointmarkerlist);
  const auto renumber = [&](int* v, std::size_t count) {
    for (std::size_t j = 0; j < count; ++j)
      if (v[j] >= 0 && v[j] < n) v[j] = order[v[j]];
  };
  renumber(out.tetrahedronlist, static_cast<std::size_t>(out.numberoftetrahedra) * out.numberofcorners);
  renumber(out.trifacelist, 3 * static_cast<std::size_t>(out.numberoftrifaces));
}

// The face of tet t (corners tv[4t..]) whose corners are {a, b, c}: the corner not among
// them; -1 if t has no such face.
int face_index(const std::vector<int>& tv, int t, int a, int b, int c) {
  int face = -1, hits = 0;
  for (int i = 0; i < 4; ++i) {
    const int v = tv[4 * t + i];
    if (v == a || v == b || v == c) ++hits;
    else face = i;
  }
  return hits == 3 ? face : -1;
}

// +1 when (a, b, c) (a face of t) is a rotation of face i's outside-counter-clockwise corners, -1 when
// reversed.
int face_orientation(const std::vector<int>& tv, int t, int i, int a, int b) {
  const int f0 = tv[4 * t + m3d::face_corner(i, 0)], f1 = tv[4 * t + m3d::face_corner(i, 1)],
            f2 = tv[4 * t + m3d::face_corner(i, 2)];
  if ((a == f0 && b == f1) || (a == f1 && b == f2) || (a == f2 && b == f0)) return 1;
  return -1;
}

// TetGen's tetrahedra and their neighbours in our numbering (tet_topology.h).
void convert_tets(const tetgenio& out, HostTetMesh& m) {
  const int nt = out.numberoftetrahedra;
  // Tets: TetGen's have orient3d < 0; swapping corners 0 and 1 (and their neighbour
  // entries: TetGen's neighbour i is across the face opposite corner i) makes them positive.
  m.tv.resize(4 * static_cast<std::size_t>(nt));
  for (int t = 0; t < nt; ++t) {
    const int* v = out.tetrahedronlist + 4 * static_cast<std::size_t>(t);
    m.tv[4 * t] = v[1];
    m.tv[4 * t + 1] = v[0];
    m.tv[4 * t + 2] = v[2];
    m.tv[4 * t + 3] = v[3];
  }
  m.tn.assign(4 * static_cast<std::size_t>(nt), -1);
  int bad_tet = -1;  // exceptions cannot leave an OpenMP loop: the first bad tet is kept
#pragma omp parallel for schedule(static) if (nt > 20000)
  for (int t = 0; t < nt; ++t) {
    for (int i = 0; i < 4; ++i) {
      const int tg = i < 2 ? 1 - i : i;  // TetGen's corner index of our corner i
      const int u = out.neighborlist[4 * static_cast<std::size_t>(t) + tg];
      if (u < 0) continue;
      // Our face i of t must be a face of u; the corner of u off it gives u's face index.
      const int a = m.tv[4 * t + m3d::face_corner(i, 0)], b = m.tv[4 * t + m3d::face_corner(i, 1)],
                c = m.tv[4 * t + m3d::face_corner(i, 2)];
      const int j = u < nt ? face_index(m.tv, u, a, b, c) : -1;
      if (j < 0) {
#pragma omp critical(gdr_cdt_bad_tet)
        if (bad_tet < 0 || t < bad_tet) bad_tet = t;
        continue;
      }
      m.tn[4 * t + i] = 4 * u + j;
    }
  }
  if (bad_tet >= 0) internal("TetGen's neighbours of tet " + str(bad_tet) + " do not share its faces");
}

// Builds the mesh of everything TetGen meshed (the cells the surface encloses).
HostTetMesh convert(const Plc& plc, const tetgenio& out) {
  const int nin = static_cast<int>(plc.points.size());
  const int nf = static_cast<int>(plc.facet_origin.size());
  const int ng = static_cast<int>(plc.segments.size());
  if (out.numberofcorners != 4) internal("TetGen returned " + str(out.numberofcorners) + " corners per tet");
  if (out.numberofpoints < nin) internal("TetGen returned fewer points than it was given");
  if (!out.neighborlist || (out.numberoftrifaces > 0 && !out.trifacemarkerlist) ||
      !out.pointmarkerlist)
    internal("TetGen did not return neighbours, subface markers or point markers");
  HostTetMesh m;
  const int np = out.numberofpoints, nt = out.numberoftetrahedra;
  m.xyz.assign(out.pointlist, out.pointlist + 3 * static_cast<std::size_t>(np));
  for (int i = 0; i < nin; ++i)
    if (m.xyz[3 * i] != plc.points[i].x || m.xyz[3 * i + 1] != plc.points[i].y || m.xyz[3 * i + 2] != plc.points[i].z)
      internal("TetGen moved or renumbered input point " + str(i));
  m.input_points = nin;

  // Points: TetGen's markers say what an added point lies on (see fill_input).
  m.ptype.assign(np, m3d::kInputPoint);
  m.pseg.assign(np, -1);
  m.pfacet.assign(np, -1);
  for (int v = nin; v < np; ++v) {
    const int mark = out.pointmarkerlist[v];
    if (mark >= 1 && mark <= nf) {
      m.ptype[v] = m3d::kFacetPoint;
      m.pfacet[v] = mark - 1;
    } else if (mark > nf && mark <= nf + ng) {
      m.ptype[v] = m3d::kSegmentPoint;
      m.pseg[v] = mark - nf - 1;
    } else {
      m.ptype[v] = m3d::kFreePoint;
    }
  }

  convert_tets(out, m);
  // Every PLC point is a corner of a PLC triangle or segment, so of some tetrahedron and
  // subface: a result without one counts as a failed attempt, not a mesh missing a corner.
  std::vector<char> used(nin, 0);
  for (const int v : m.tv)
    if (v < nin) used[v] = 1;
  for (int v = 0; v < nin; ++v)
    if (!used[v]) internal("TetGen left out input point " + str(v));

  // Subfaces: TetGen names the tets on either side of each (-nn), but on the hull side
  // TetGen 1.5.0 may name tet 0: the first named tet that has the subface as a face gives
  // it, its neighbour across it the other side; the side comes from the corners. Each
  // check records its first failure (no exceptions inside OpenMP).
  const int nsf = out.numberoftrifaces;
  if (nsf > 0 && !out.adjtetlist) internal("TetGen did not return the tetrahedra of its subfaces");
  m.tsub.assign(4 * static_cast<std::size_t>(nt), -1);
  m.sv.resize(3 * static_cast<std::size_t>(nsf));
  m.st.assign(2 * static_cast<std::size_t>(nsf), -1);
  m.sfacet.resize(nsf);
  int bad_marker = -1, not_a_face = -1, twice = -1, two_on_one_side = -1;
  const auto first = [](int& into, int s) {
#pragma omp critical(gdr_cdt_bad_subface)
    if (into < 0 || s < into) into = s;
  };
#pragma omp parallel for schedule(static) if (nsf > 20000)
  for (int s = 0; s < nsf; ++s) {
    for (int k = 0; k < 3; ++k) m.sv[3 * s + k] = out.trifacelist[3 * s + k];
    const int mark = out.trifacemarkerlist[s];
    if (mark < 1 || mark > nf) first(bad_marker, s);
    m.sfacet[s] = mark - 1;
    const int a = m.sv[3 * s], b = m.sv[3 * s + 1], c = m.sv[3 * s + 2];
    int x = -1;
    for (int k = 0; k < 2 && x < 0; ++k) {
      const int t = out.adjtetlist[2 * s + k];
      const int i = t >= 0 && t < nt ? face_index(m.tv, t, a, b, c) : -1;
      if (i >= 0) x = 4 * t + i;
    }
    if (x < 0) {
      first(not_a_face, s);
      continue;
    }
    for (const int y : {x, m.tn[x]}) {
      if (y < 0) continue;
      int& side = m.st[2 * s + (face_orientation(m.tv, y / 4, y % 4, a, b) == 1 ? 0 : 1)];
      if (side >= 0) first(two_on_one_side, s);
      side = y;
      int before;
#pragma omp atomic capture
      { before = m.tsub[y]; m.tsub[y] = s; }
      if (before >= 0) first(twice, s);
    }
  }
  if (bad_marker >= 0) internal("subface " + str(bad_marker) + " has marker " + str(out.trifacemarkerlist[bad_marker]));
  if (not_a_face >= 0) internal("subface " + str(not_a_face) + " is not a face of the tets TetGen gives for it");
  if (twice >= 0) internal("TetGen returned subface " + str(twice) + " twice");
  if (two_on_one_side >= 0) internal("subface " + str(two_on_one_side) + " has two tets on one side");
  std::vector<char> on_surface(nin, 0);
  for (int s = 0; s < nsf; ++s)
    for (int k = 0; k < 3; ++k)
      if (m.sv[3 * s + k] < nin) on_surface[m.sv[3 * s + k]] = 1;
  for (const auto& t : plc.triangles)
    for (const int v : t)
      if (!on_surface[v]) internal("TetGen's subfaces leave out input point " + str(v));
  for (int s = 0; s < nsf; ++s)
    if (m.st[2 * s] < 0 && m.st[2 * s + 1] < 0) internal("subface " + str(s) + " is not a face of any tet");
  m.tseg.assign(nt, 0);
  return m;
}

// The cell on each side of every subface (from the PLC triangle or facet it lies in), then
// the cell of every tet by flooding across faces that are not subfaces.
std::vector<int> tet_cells(const Plc& plc, const HostTetMesh& m) {
  const int nt = m.tets(), ns = m.subfaces();
  const auto& P = plc.points;
  // Each facet's first triangle is its reference for "front".
  std::vector<int> facet_ref(plc.facet_origin.size(), -1);
  for (int t = static_cast<int>(plc.triangles.size()) - 1; t >= 0; --t) facet_ref[plc.triangle_facet[t]] = t;

  UnionFind uf(nt);
  for (int x = 0; x < 4 * nt; ++x)
    if (m.tn[x] >= 0 && m.tsub[x] < 0) uf.unite(x / 4, m.tn[x] / 4);
  std::vector<int> label(nt, -1);  // per flood root: its cell
  auto point = [&](int v) { return Point3{m.xyz[3 * v], m.xyz[3 * v + 1], m.xyz[3 * v + 2]}; };
  for (int s = 0; s < ns; ++s) {
    const int ref = facet_ref[m.sfacet[s]];
    const auto& r = plc.triangles[ref];
    const Point3 a = point(m.sv[3 * s]), b = point(m.sv[3 * s + 1]), c = point(m.sv[3 * s + 2]);
    // Does the subface turn the same way as its facet's reference triangle?
    bool same;
    if (plc.facet_planar[m.sfacet[s]] && m.sv[3 * s] < m.input_points && m.sv[3 * s + 1] < m.input_points &&
        m.sv[3 * s + 2] < m.input_points) {
      const int axis = geom::projection_axis(P[r[0]], P[r[1]], P[r[2]]);  // exact: coplanar
      same = geom::orient2d(axis, a, b, c) == geom::orient2d(axis, P[r[0]], P[r[1]], P[r[2]]);
    } else {  // rounded Steiner points, or a facet that bends: compare normals, nearly (anti)parallel
      auto normal = [](const Point3& p, const Point3& q, const Point3& w, double n[3]) {
        const double u[3] = {q.x - p.x, q.y - p.y, q.z - p.z}, v[3] = {w.x - p.x, w.y - p.y, w.z - p.z};
        n[0] = u[1] * v[2] - u[2] * v[1];
        n[1] = u[2] * v[0] - u[0] * v[2];
        n[2] = u[0] * v[1] - u[1] * v[0];
      };
      double n1[3], n2[3];
      normal(a, b, c, n1);
      normal(P[r[0]], P[r[1]], P[r[2]], n2);
      same = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2] > 0;
    }
    for (int k = 0; k < 2; ++k) {
      const int x = m.st[2 * s + k];
      if (x < 0) continue;
      // Side 0's tet lies behind (sv0, sv1, sv2); "front" is Plc's triangle_cell[.][0].
      const bool front_of_sub = k == 1;
      const int cell = plc.triangle_cell[ref][front_of_sub == same ? 0 : 1];
      const int root = uf.find(x / 4);
      if (label[root] < 0) {
        label[root] = cell;
      } else if (label[root] != cell &&
                 (plc.cell_in_domain[label[root]] || plc.cell_in_domain[cell])) {
        internal("tets of one flood region lie in cells " + str(label[root]) + " and " + str(cell));
      }
    }
  }
  std::vector<int> cell(nt);
  for (int t = 0; t < nt; ++t) {
    const int l = label[uf.find(t)];
    if (l < 0) internal("tet " + str(t) + " touches no subface through its flood region");
    cell[t] = l;
  }
  // A hull face that is not a subface lies outside (cell 0). TetGen has returned a hull
  // whose faces cut nearly coplanar input triangles along their other diagonal (a tiny
  // turned cylinder), the input triangles then half covered: refinement crashed on it.
  for (int x = 0; x < 4 * nt; ++x)
    if (m.tn[x] < 0 && m.tsub[x] < 0 && plc.cell_in_domain[cell[x / 4]])
      internal("tet " + str(x / 4) + " of the domain has a hull face that is not a subface");
  return cell;
}

// Keeps the tets in domain cells, the subfaces next to them, the input points and the
// added points still in use; renumbers all links.
HostTetMesh keep_domain(const Plc& plc, const HostTetMesh& full, const std::vector<int>& cell) {
  const int nt = full.tets(), ns = full.subfaces(), np = full.points();
  std::vector<int> new_tet(nt, -1);
  int kt = 0;
  for (int t = 0; t < nt; ++t)
    if (plc.cell_in_domain[cell[t]]) new_tet[t] = kt++;
  auto map_face = [&](int x) { return x < 0 || new_tet[x / 4] < 0 ? -1 : 4 * new_tet[x / 4] + x % 4; };
  std::vector<int> new_sub(ns, -1);
  int ks = 0;
  for (int s = 0; s < ns; ++s)
    if (map_face(full.st[2 * s]) >= 0 || map_face(full.st[2 * s + 1]) >= 0) new_sub[s] = ks++;
  std::vector<char> used(np, 0);
  for (int v = 0; v < full.input_points; ++v) used[v] = 1;
#pragma omp parallel for schedule(static) if (nt > 20000)
  for (int t = 0; t < nt; ++t)
    if (new_tet[t] >= 0)
      for (int k = 0; k < 4; ++k) {
#pragma omp atomic write
        used[full.tv[4 * t + k]] = 1;
      }
  std::vector<int> new_point(np, -1);
  int kp = 0;
  for (int v = 0; v < np; ++v)
    if (used[v]) new_point[v] = kp++;

  HostTetMesh m;
  m.input_points = full.input_points;
  m.xyz.resize(3 * static_cast<std::size_t>(kp));
  m.ptype.resize(kp);
  m.pseg.resize(kp);
  m.pfacet.resize(kp);
#pragma omp parallel for schedule(static) if (np > 20000)
  for (int v = 0; v < np; ++v) {
    const int w = new_point[v];
    if (w < 0) continue;
    for (int d = 0; d < 3; ++d) m.xyz[3 * w + d] = full.xyz[3 * v + d];
    m.ptype[w] = full.ptype[v];
    m.pseg[w] = full.pseg[v];
    m.pfacet[w] = full.pfacet[v];
  }
  m.tv.resize(4 * static_cast<std::size_t>(kt));
  m.tn.resize(4 * static_cast<std::size_t>(kt));
  m.tsub.resize(4 * static_cast<std::size_t>(kt));
  m.tseg.assign(kt, 0);
  const bool regions = !plc.regions.empty();
  if (regions) m.tregion.resize(kt);
#pragma omp parallel for schedule(static) if (nt > 20000)
  for (int t = 0; t < nt; ++t) {
    const int u = new_tet[t];
    if (u < 0) continue;
    for (int k = 0; k < 4; ++k) {
      m.tv[4 * u + k] = new_point[full.tv[4 * t + k]];
      m.tn[4 * u + k] = map_face(full.tn[4 * t + k]);
      const int s = full.tsub[4 * t + k];
      m.tsub[4 * u + k] = s < 0 ? -1 : new_sub[s];
    }
    if (regions) {
      const int seed = plc.cell_region[cell[t]];
      m.tregion[u] = seed < 0 ? 0 : plc.regions[seed].attribute;
    }
  }
  m.sv.resize(3 * static_cast<std::size_t>(ks));
  m.st.resize(2 * static_cast<std::size_t>(ks));
  m.sfacet.resize(ks);
#pragma omp parallel for schedule(static) if (ns > 20000)
  for (int s = 0; s < ns; ++s) {
    const int u = new_sub[s];
    if (u < 0) continue;
    for (int k = 0; k < 3; ++k) m.sv[3 * u + k] = new_point[full.sv[3 * s + k]];
    m.st[2 * u] = map_face(full.st[2 * s]);
    m.st[2 * u + 1] = map_face(full.st[2 * s + 1]);
    m.sfacet[u] = full.sfacet[s];
  }
  return m;
}

// Per planar facet its largest triangle: the best conditioned plane to put its Steiner
// points on (-1 for a facet merged across near-flat edges: points go on their subface).
void set_facet_planes(const Plc& plc, HostTetMesh& m) {
  const std::size_t nf = plc.facet_origin.size();
  m.fplane.assign(3 * nf, -1);
  std::vector<double> best(nf, -1.0);
  for (std::size_t t = 0; t < plc.triangles.size(); ++t) {
    const auto& r = plc.triangles[t];
    const Point3 &a = plc.points[r[0]], &b = plc.points[r[1]], &c = plc.points[r[2]];
    const double u[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, v[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
    const double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double area2 = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    const int f = plc.triangle_facet[t];
    if (!plc.facet_planar[f]) continue;
    if (area2 > best[f]) {
      best[f] = area2;
      for (int k = 0; k < 3; ++k) m.fplane[3 * f + k] = r[k];
    }
  }
}

// tseg: an edge is a subsegment iff both ends lie on one segment (its input endpoints, or
// points that TetGen put on it).
void mark_subsegments(const Plc& plc, HostTetMesh& m) {
  const int ng = static_cast<int>(plc.segments.size()), nin = m.input_points;
  m.seg.resize(2 * static_cast<std::size_t>(ng));
  // Per input point the other ends of its segments (a counted array): a few to scan.
  std::vector<int> start(nin + 1, 0), other(2 * static_cast<std::size_t>(ng));
  for (int g = 0; g < ng; ++g) {
    m.seg[2 * g] = plc.segments[g][0];
    m.seg[2 * g + 1] = plc.segments[g][1];
    ++start[plc.segments[g][0] + 1];
    ++start[plc.segments[g][1] + 1];
  }
  for (int v = 0; v < nin; ++v) start[v + 1] += start[v];
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int g = 0; g < ng; ++g) {
      other[fill[plc.segments[g][0]]++] = plc.segments[g][1];
      other[fill[plc.segments[g][1]]++] = plc.segments[g][0];
    }
  }
  const auto joined = [&](int a, int b) {
    for (int i = start[a]; i < start[a + 1]; ++i)
      if (other[i] == b) return true;
    return false;
  };
  auto on = [&](int v, int g) {
    return v < m.input_points ? (m.seg[2 * g] == v || m.seg[2 * g + 1] == v)
                              : (m.ptype[v] == m3d::kSegmentPoint && m.pseg[v] == g);
  };
  const int nt = m.tets();
#pragma omp parallel for schedule(static) if (nt > 20000)
  for (int t = 0; t < nt; ++t) {
    std::uint8_t bits = 0;
    for (int e = 0; e < 6; ++e) {
      const int a = m.tv[4 * t + m3d::edge_corner(e, 0)], b = m.tv[4 * t + m3d::edge_corner(e, 1)];
      bool sub;
      if (a < m.input_points && b < m.input_points) sub = joined(a, b);
      else if (a >= m.input_points) sub = m.ptype[a] == m3d::kSegmentPoint && on(b, m.pseg[a]);
      else sub = m.ptype[b] == m3d::kSegmentPoint && on(a, m.pseg[b]);
      if (sub) bits |= static_cast<std::uint8_t>(m3d::edge_bit(e));
    }
    m.tseg[t] = bits;
  }
}

// Faces between two tetrahedra that are not subfaces and not locally Delaunay (exact
// insphere). TetGen's -M result on two parts 1e-12 apart had one.
long long non_delaunay_faces(const HostTetMesh& m) {
  const long long n4 = 4LL * m.tets();
  long long count = 0;
  auto at = [&](int v) { return &m.xyz[3 * static_cast<std::size_t>(v)]; };
#pragma omp parallel for reduction(+ : count) schedule(static) if (n4 > 80000)
  for (long long x = 0; x < n4; ++x) {
    const int y = m.tn[x];
    if (y < 0 || y < x || m.tsub[x] >= 0) continue;  // each interior face once
    const int* t = &m.tv[4 * (x / 4)];
    count += pred::insphere(at(t[0]), at(t[1]), at(t[2]), at(t[3]), at(m.tv[4 * (y / 4) + y % 4])) > 0;
  }
  return count;
}

// Why TetGen may have failed: triangles that share no vertex yet come closer than its
// tolerance can separate (1e-8 of the bounding box diagonal), e.g. parts 1e-12 apart.
double box_diagonal(const Plc& plc) {
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const Point3& p : plc.points) {
    const double* x = geom::xyz(p);
    for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], x[d]), hi[d] = std::max(hi[d], x[d]);
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

// Do triangles of two bodies come within TetGen's tolerance of each other?
bool bodies_nearly_touch(const Plc& plc, const Bodies& bodies) {
  std::vector<std::array<int, 2>> pairs;
  find_close_triangles(plc.points, plc.triangles, 1e-8 * box_diagonal(plc), 1000, pairs);
  for (const auto& p : pairs)
    if (bodies.of_triangle[p[0]] != bodies.of_triangle[p[1]]) return true;
  return false;
}

std::string close_parts(const Plc& plc) {
  std::vector<std::array<int, 2>> pairs;
  const long long count = find_close_triangles(plc.points, plc.triangles, 1e-8 * box_diagonal(plc), 5, pairs);
  if (count == 0) return "";
  std::vector<std::string> items;
  for (const auto& p : pairs) {
    int a = plc.triangle_origin[p[0]], b = plc.triangle_origin[p[1]];
    if (a > b) std::swap(a, b);
    items.push_back(std::to_string(a) + " and " + std::to_string(b));
  }
  return "; input triangles that share no corner lie within 1e-8 of the bounding box of each other (parts "
         "nearly touching?): pairs " +
         list_items(items, count);
}

constexpr const char* kOtherMesher =
    ". The restricted Delaunay mesher (gdr rdt; GPU Restricted Delaunay 3D in ParaView) meshes such "
    "surfaces without TetGen, approximating them";

// GDR_TRACE: the time of each step on stderr (TetGen against our conversions).
struct Trace {
  const bool on = std::getenv("GDR_TRACE") != nullptr;
  std::chrono::steady_clock::time_point last = std::chrono::steady_clock::now();
  void operator()(const char* what) {
    if (!on) return;
    const auto now = std::chrono::steady_clock::now();
    std::fprintf(stderr, "gdr-trace cdt %s: %.3f s\n", what, std::chrono::duration<double>(now - last).count());
    last = now;
  }
};

// TetGen's tetrahedralization of the domain of `plc` (cells outside removed, flat boundary
// tetrahedra dropped), in the attempts below; the last, -Y, only where `last_resort`.
// `unsplit` says whether -Y made it. Throws TetGenAborted (the last failure's reason).
HostTetMesh domain_cdt(const Plc& plc, const Callbacks& callbacks, const std::vector<double>& seeds,
                       bool last_resort, bool& unsplit, Trace& stamp, const std::function<void()>& meanwhile) {
  // TetGen's facet recovery stops on an assertion, or loops, on some inputs (parts turned
  // to an angle, scan-like surfaces, nearly coplanar fans) for some point orders only: a
  // failure is retried without TetGen's merging of coplanar facets (M: every triangle
  // stays a facet of its own, which TetGen's own tetgen -pM got through on fuzzed
  // cylinders and slabs where plain -p failed in every order), then in two other orders.
  // The time limit is far beyond TetGen's own time (at most about 20 microseconds per
  // point and triangle, typically 6).
  const int np = static_cast<int>(plc.points.size() + seeds.size() / 3);
  const char* limit_env = std::getenv("GDR_TETGEN_SECONDS");  // tests: forces the time limit
  const double limit = limit_env ? std::atof(limit_env) : 10.0 + 1e-4 * (np + static_cast<double>(plc.triangles.size()));
  std::vector<int> order(np);
  std::iota(order.begin(), order.end(), 0);
  const bool shuffle_first = std::getenv("GDR_TETGEN_SHUFFLE") != nullptr;  // tests: restore_order
  // Polled every 50 ms while TetGen runs: the progress hook too, where ParaView's GUI takes a
  // press on its abort button.
  bool started = false;
  const auto waiting = [&callbacks, &meanwhile, &started]() {
    if (!started && meanwhile) meanwhile();
    started = true;
    if (callbacks.progress) callbacks.progress(0.0, "constrained Delaunay tetrahedralization (TetGen)");
    return callbacks.abort && callbacks.abort();
  };
  tetgenio out;
  HostTetMesh full;
  std::vector<int> cells;
  struct Attempt {
    const char* switches;
    unsigned shuffle;  // 0: the points in their order, else a shuffle (seed shuffle + 1)
    const char* next;  // what the warning says comes next, should this attempt fail
  };
  static constexpr Attempt kAttempts[] = {
      {"pcnnO0JQ", 0, "trying again without merging coplanar facets (-M)"},
      {"pcnnO0JQM", 0, "trying again with the points in another order"},
      {"pcnnO0JQM", 2, "trying again with the points in another order"},
      {"pcnnO0JQM", 3, "trying again with the input surface kept unsplit (-Y)"},
      {"pcYnnO0JQ", 0, nullptr},
  };
  const int count = static_cast<int>(sizeof(kAttempts) / sizeof(kAttempts[0])) - (last_resort ? 0 : 1);
  for (int attempt = 0;; ++attempt) {
    const Attempt& a = kAttempts[attempt];
    std::iota(order.begin(), order.end(), 0);
    if (a.shuffle || shuffle_first) std::shuffle(order.begin(), order.end(), std::mt19937(a.shuffle + 1));
    tetgenio in;
    fill_input(plc, seeds, order, in);
    if (attempt == 0) stamp("fill TetGen input");
    TetGenOutcome outcome;
    unsplit = std::strchr(a.switches, 'Y') != nullptr;
    try {
      outcome = run_tetgen_process(a.switches, in, out, limit, waiting);
    } catch (const Error& e) {
      if (e.status() == Status::OutOfDeviceMemory || e.status() == Status::Aborted) throw;
      if (callbacks.warning)
        callbacks.warning(std::string("TetGen's constrained Delaunay tetrahedralization failed (") + e.what() +
                          "); retrying with the input surface kept unsplit (-Y)");
      outcome = run_tetgen_process("pcYnnO0JQ", in, out, limit, waiting);
      unsplit = true;
    }
    std::string what;
    if (outcome.kind == TetGenOutcome::Done) {
      if (!std::is_sorted(order.begin(), order.end())) restore_order(order, out);
      stamp("TetGen");
      if (callbacks.abort && callbacks.abort()) throw Error(Status::Aborted, "aborted after the initial CDT");
      // TetGen may also end normally with a surface it did not keep (a subface missing, so
      // that the inside floods into the outside): that counts as a failed attempt too.
      try {
        full = convert(plc, out);
        stamp("convert");
        cells = tet_cells(plc, full);
        stamp("cells");
        // The retries' results are checked for the Delaunay property too (the first
        // attempt's, on large inputs, is not: its cost is then a tenth of TetGen's).
        const long long bad = attempt > 0 && !unsplit ? non_delaunay_faces(full) : 0;
        if (bad == 0) break;
        what = "TetGen's tetrahedralization is not constrained Delaunay (" + std::to_string(bad) + " faces)";
      } catch (const Error& e) {
        if (e.status() != Status::InternalError) throw;
        what = std::string("TetGen's tetrahedralization does not keep the input surface (") + e.what() + ")";
      }
    } else {
      what = outcome.kind == TetGenOutcome::TimedOut
                 ? "TetGen did not finish its tetrahedralization within " + std::to_string(static_cast<int>(limit)) + " s"
             : outcome.signal == SIGABRT
                 ? std::string("TetGen stopped on one of its internal assertions (printed on the standard error)")
                 : "TetGen's process ended on signal " + std::to_string(outcome.signal);
    }
    if (attempt + 1 == count) throw TetGenAborted(what + ", in " + std::to_string(count) + " attempts" + close_parts(plc));
    // Before the last resort, say why TetGen may have failed (parts nearly touching).
    if (callbacks.warning) callbacks.warning(what + (attempt + 2 == count ? close_parts(plc) : "") + "; " + a.next);
  }
  HostTetMesh m = keep_domain(plc, full, cells);
  stamp("keep domain");
  const int flat = drop_flat_boundary_tets(plc, m);
  if (stamp.on) std::fprintf(stderr, "gdr-trace cdt flat boundary tets dropped: %d\n", flat);
  return m;
}

}  // namespace

m3d::HostTetMesh initial_cdt(const Plc& plc, const Callbacks& callbacks, const std::vector<double>& seeds,
                             const std::function<void()>& meanwhile) {
  if (plc.triangle_cell.size() != plc.triangles.size() || plc.cell_in_domain.empty())
    throw Error(Status::InvalidInput, "initial_cdt needs a closed surface checked with require_closed");
  if (callbacks.progress) callbacks.progress(0.0, "constrained Delaunay tetrahedralization (TetGen)");
  Trace stamp;
  // Bodies that share no cell are meshed one by one where TetGen fails on them together
  // (parts nearly touching: its tolerance cannot separate them), before -Y.
  // Bodies closer than TetGen's tolerance are meshed one by one from the start: TetGen failed
  // on them together, some attempts only after its time limit (two boxes 1e-12 apart).
  const Bodies bodies = find_bodies(plc);
  const bool together = std::getenv("GDR_TETGEN_TOGETHER") != nullptr;  // tests: the retries on such input
  const bool one_by_one = !together && bodies.count > 1 && bodies_nearly_touch(plc, bodies);
  bool unsplit = false;
  HostTetMesh m;
  try {
    if (one_by_one) throw TetGenAborted("bodies nearly touching");
    m = domain_cdt(plc, callbacks, seeds, bodies.count < 2, unsplit, stamp, meanwhile);
  } catch (const TetGenAborted& e) {
    if (bodies.count < 2) throw TetGenAborted(std::string(e.what()) + kOtherMesher);
    if (callbacks.warning && !one_by_one)
      callbacks.warning(std::string(e.what()) + "; meshing the input's " + std::to_string(bodies.count) +
                        " bodies (parts that share no space) one by one");
    std::vector<BodyPlc> subs;
    std::vector<HostTetMesh> parts;
    for (int b = 0; b < bodies.count; ++b) {
      subs.push_back(body_plc(plc, bodies, b, seeds));
      bool body_unsplit = false;
      try {
        parts.push_back(domain_cdt(subs.back().plc, callbacks, subs.back().seeds, true, body_unsplit, stamp, meanwhile));
      } catch (const TetGenAborted& eb) {
        throw TetGenAborted("body " + std::to_string(b + 1) + " of " + std::to_string(bodies.count) + ": " +
                            eb.what() + kOtherMesher);
      }
      unsplit = unsplit || body_unsplit;
    }
    m = merge_bodies(plc, subs, parts);
    stamp("bodies merged");
  }
  mark_subsegments(plc, m);
  set_facet_planes(plc, m);
  stamp("subsegments, facet planes");
  if (unsplit && callbacks.warning) {
    // Where the surface's own triangles are not Delaunay, no flip mends it (tried: Lawson's
    // 2-3 and 3-2 flips mended none of 148-2959 such faces on the data set's surfaces):
    // refinement splits them away; a mesh with them left fails --check.
    const long long bad = non_delaunay_faces(m);
    if (bad > 0)
      callbacks.warning("the initial tetrahedralization (TetGen -Y) is not constrained Delaunay at " +
                        std::to_string(bad) + " faces next to the surface; refinement removes them, "
                        "a mesh with them left (--cdt-only, loose bounds) fails --check");
  }
#ifndef NDEBUG
  m3d::check_host_mesh(m);
#endif
  if (callbacks.progress) callbacks.progress(1.0, "constrained Delaunay tetrahedralization done");
  return m;
}

m3d::HostTetMesh delaunay_tetrahedralization(const std::vector<double>& xyz) {
  const int np = static_cast<int>(xyz.size() / 3);
  tetgenio out;
  // Plain Delaunay: n (neighbours), J (keep numbering), Q (quiet). No constraints, so none
  // of the facet recovery that can loop: no time limit. Its point location still stopped on
  // an assertion for one order of a box's points (fuzz3d, seed 4001684): two more orders.
  std::vector<int> order(np);
  std::iota(order.begin(), order.end(), 0);
  for (int attempt = 0;; ++attempt) {
    if (attempt > 0) std::shuffle(order.begin(), order.end(), std::mt19937(attempt));
    tetgenio in;
    in.firstnumber = 0;
    in.numberofpoints = np;
    in.pointlist = new REAL[3 * static_cast<std::size_t>(np)];
    for (int k = 0; k < np; ++k)
      for (int c = 0; c < 3; ++c) in.pointlist[3 * k + c] = xyz[3 * static_cast<std::size_t>(order[k]) + c];
    if (run_tetgen_process("nJQ", in, out, 1e9, {}).kind == TetGenOutcome::Done) break;
    if (attempt == 2) internal("TetGen's Delaunay tetrahedralization ended without a result, with the points in 3 orders");
  }
  if (out.numberofcorners != 4 || !out.neighborlist || out.numberofpoints != np)
    internal("TetGen's Delaunay tetrahedralization returned an unexpected mesh");
  for (int k = 0; k < 4 * out.numberoftetrahedra; ++k) out.tetrahedronlist[k] = order[out.tetrahedronlist[k]];
  HostTetMesh m;
  m.xyz = xyz;
  m.input_points = np;
  m.ptype.assign(np, m3d::kInputPoint);
  m.pseg.assign(np, -1);
  m.pfacet.assign(np, -1);
  convert_tets(out, m);
  m.tsub.assign(m.tv.size(), -1);
  m.tseg.assign(m.tets(), 0);
  return m;
}

}  // namespace gdr::cdt3d
