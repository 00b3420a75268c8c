// Tetrahedral mesh storage shared by the 3D meshers, as structures of arrays on one
// execution space, and the geometry and topology helpers their kernels use.
//
// Numbering (mesh3d/tet_topology.h): tetrahedron t has positive vertices tv[4t..4t+3], face
// i opposite vertex i, neighbour tn[4t+i] = 4t'+i' across face i (-1 outside the domain),
// subface tsub[4t+i] on face i (-1 if none), and edge bits in tflag saying which of its six
// edges are subsegments. Subface s has vertices sv[3s..3s+2], the tetrahedron faces on its
// two sides st[2s], st[2s+1] (host_mesh.h defines which is which), and its facet sfacet[s].
// Edge e of a subface is opposite its vertex e.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "exec/algorithms.h"
#include "exec/buffer.h"
#include "exec/hd.h"
#include "mesh3d/host_mesh.h"
#include "mesh3d/tet_topology.h"
#include "predicates/predicates.h"

namespace gdr::m3d {

// Per-tetrahedron flag bits.
enum : int {
  kDead = 1,
  kInCavity = 2,        // part of a winning cavity during insertion
  kFresh = 4,           // new: its collect bits are not computed yet
  kSeg0 = 1 << 3,       // bits 3-8: edge e is a subsegment
  kSegBits = 63 << 3,
  kSplitEdge0 = 1 << 9,   // bits 9-14: edge e is a subsegment that must be split
  kSplitFace0 = 1 << 15,  // bits 15-18: the subface on face i must be split
  kCollectShift = 19,     // bits 19-29: the tetrahedron's own collect mask (engine)
  kCollectBits = 2047 << 19,
  kProtected = 1 << 30,   // bad, but no point fixes it (its split was declined): not collected
  // Split first: a cavity it belongs to could not be made star-shaped (cavity.h).
  kMakeRoom = static_cast<int>(1u << 31),
};

// A bad tetrahedron that no point can fix is left as it is and reported.
GDR_HD_INLINE void protect_tet(int* tflag, int t) {
  exec::atomic_or(&tflag[t], kProtected);
  exec::atomic_and(&tflag[t], ~kMakeRoom);
}

// Per-subface flag bits.
enum : int {
  kSubDead = 1,
  kSubInCavity = 2,  // part of a winning subface cavity during insertion
  kSubFanEdge0 = 4,  // bits 2-4: edge e bounds that subface cavity (cavity.h)
  kSubNoSplit = 32,  // its circumcentre lies outside its facet and encroaches no subsegment:
                     // it is left as it is (TetGen does the same), and so are the bad
                     // tetrahedra whose circumcentres it blocks
  // During one insertion (cavity.h, MarkFlips): the boundary subface and its neighbour across
  // edge e trade that edge for the other diagonal of their quadrilateral. kSubFlipLo tells
  // which of the two it is; saux holds the neighbour's corner off the edge.
  kSubFlip = 64,
  kSubFlipLo = 128,
  kSubFlipEdge0 = 256,  // bits 8-10: the edge (opposite corner e)
  kSubFlipBits = kSubFlip | kSubFlipLo | 7 * kSubFlipEdge0,
};

struct TetView {
  double* xyz;
  std::uint8_t* ptype;
  int* pseg;
  int* pfacet;
  int* tv;
  int* tn;
  int* tsub;
  int* tflag;
  int* tregion;  // null without regions
  int* mark;     // cavity claims: candidate + 1 (exec/priority.h)
  int* aux;
  int* sv;
  int* st;
  int* sfacet;
  int* sflag;
  int* smark;
  int* saux;
  const int* seg;
  const int* vseg_begin;  // segments at input vertex v: vseg[vseg_begin[v] .. vseg_begin[v+1])
  const int* vseg;
  const std::uint8_t* sharp;  // per segment (host_mesh.h)
  const int* fplane;          // 3 per facet (host_mesh.h), null: none
  float* prad;                // per point: protecting-ball radius
  int ntet, npts, nsub;
};

template <class Space>
struct DeviceTetMesh {
  template <class T>
  using Buf = exec::Buffer<Space, T>;
  Buf<double> xyz;
  Buf<std::uint8_t> ptype;
  Buf<int> pseg, pfacet;
  Buf<int> tv, tn, tsub, tflag, tregion, mark, aux;
  Buf<int> sv, st, sfacet, sflag, smark, saux;
  Buf<int> seg, vseg_begin, vseg, fplane;
  Buf<std::uint8_t> sharp;
  Buf<float> prad;
  int ntet = 0, npts = 0, nsub = 0;
  bool regions = false;

  TetView view() {
    return TetView{xyz.data(),   ptype.data(),  pseg.data(),  pfacet.data(), tv.data(),
                   tn.data(),    tsub.data(),   tflag.data(), regions ? tregion.data() : nullptr,
                   mark.data(),  aux.data(),    sv.data(),    st.data(),     sfacet.data(),
                   sflag.data(), smark.data(),  saux.data(),  seg.data(),    vseg_begin.data(),
                   vseg.data(),  sharp.data(),  fplane.size() ? fplane.data() : nullptr,
                   prad.data(),  ntet,          npts,          nsub};
  }

  void upload(const HostTetMesh& h) {
    npts = h.points();
    ntet = h.tets();
    nsub = h.subfaces();
    regions = !h.tregion.empty();
    xyz.upload(h.xyz);
    ptype.upload(h.ptype);
    pseg.upload(h.pseg);
    pfacet.upload(h.pfacet);
    tv.upload(h.tv);
    tn.upload(h.tn);
    tsub.upload(h.tsub);
    if (regions) tregion.upload(h.tregion);
    {
      std::vector<int> flags(h.tseg.size());
      for (std::size_t t = 0; t < flags.size(); ++t) flags[t] = kFresh | (int(h.tseg[t]) << 3);
      tflag.upload(flags);
    }
    mark.resize_discard(ntet);
    mark.zero();
    aux.resize_discard(ntet);
    sv.upload(h.sv);
    st.upload(h.st);
    sfacet.upload(h.sfacet);
    sflag.resize_discard(nsub);
    sflag.zero();
    smark.resize_discard(nsub);
    smark.zero();
    saux.resize_discard(nsub);
    seg.upload(h.seg);
    // Segments at each input vertex, to name the segment of a subsegment that joins two
    // input vertices.
    const int ns = h.segments();
    std::vector<int> begin(std::size_t(npts) + 1, 0), list(h.seg.size());
    for (int v : h.seg) ++begin[v + 1];
    for (int v = 0; v < npts; ++v) begin[v + 1] += begin[v];
    std::vector<int> fill(begin.begin(), begin.end() - 1);
    for (int s = 0; s < ns; ++s)
      for (int k = 0; k < 2; ++k) list[fill[h.seg[2 * s + k]]++] = s;
    vseg_begin.upload(begin);
    vseg.upload(list);
    fplane.upload(h.fplane);
    sharp.upload(h.sharp.empty() ? std::vector<std::uint8_t>(std::size_t(ns), 0) : h.sharp);
    prad.upload(h.prad.empty() ? std::vector<float>(std::size_t(npts), 0.0f) : h.prad);
  }

  // The whole mesh back on the host, links included (for check_host_mesh in tests). The
  // caller compacts first: dead elements are not expected in a HostTetMesh.
  HostTetMesh to_host(int input_points) const {
    HostTetMesh h;
    h.input_points = input_points;
    auto get = [](const auto& buf, std::size_t n, auto& vec) {
      vec.resize(n);
      buf.download(vec.data(), n);
    };
    get(xyz, 3 * std::size_t(npts), h.xyz);
    get(ptype, npts, h.ptype);
    get(pseg, npts, h.pseg);
    get(pfacet, npts, h.pfacet);
    get(tv, 4 * std::size_t(ntet), h.tv);
    get(tn, 4 * std::size_t(ntet), h.tn);
    get(tsub, 4 * std::size_t(ntet), h.tsub);
    if (regions) get(tregion, ntet, h.tregion);
    std::vector<int> flags;
    get(tflag, ntet, flags);
    h.tseg.resize(ntet);
    for (int t = 0; t < ntet; ++t) h.tseg[t] = static_cast<std::uint8_t>((flags[t] & kSegBits) >> 3);
    get(sv, 3 * std::size_t(nsub), h.sv);
    get(st, 2 * std::size_t(nsub), h.st);
    get(sfacet, nsub, h.sfacet);
    get(seg, seg.size(), h.seg);
    get(sharp, sharp.size(), h.sharp);
    get(fplane, fplane.size(), h.fplane);
    get(prad, npts, h.prad);
    return h;
  }

  // Room for `tets` tetrahedra, `subs` subfaces and `pts` points, keeping contents.
  void reserve(int tets, int subs, int pts) {
    if (tets > ntet) {
      tv.resize(4 * std::size_t(tets));
      tn.resize(4 * std::size_t(tets));
      tsub.resize(4 * std::size_t(tets));
      tflag.resize(tets);
      if (regions) tregion.resize(tets);
      mark.resize(tets);
      aux.resize(tets);
    }
    if (subs > nsub) {
      sv.resize(3 * std::size_t(subs));
      st.resize(2 * std::size_t(subs));
      sfacet.resize(subs);
      sflag.resize(subs);
      smark.resize(subs);
      saux.resize(subs);
    }
    if (pts > npts) {
      xyz.resize(3 * std::size_t(pts));
      ptype.resize(pts);
      pseg.resize(pts);
      pfacet.resize(pts);
      prad.resize(pts);
    }
  }
};

// ---------------------------------------------------------------------------------------
// Geometry (constructions are rounded; every topological decision uses pred::).

GDR_HD_INLINE const double* pt(const TetView& m, int v) { return m.xyz + 3 * v; }

GDR_HD_INLINE double dist2(const double* a, const double* b) {
  const double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
  return dx * dx + dy * dy + dz * dz;
}

GDR_HD_INLINE void cross3(const double* u, const double* v, double* w) {
  w[0] = u[1] * v[2] - u[2] * v[1];
  w[1] = u[2] * v[0] - u[0] * v[2];
  w[2] = u[0] * v[1] - u[1] * v[0];
}

GDR_HD_INLINE double dot3(const double* u, const double* v) {
  return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
}

// Circumcentre of tetrahedron abcd; false when it is degenerate (or not representable).
GDR_HD_INLINE bool tet_circumcenter(const double* a, const double* b, const double* c,
                                    const double* d, double* out) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ad[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  double cd[3], db[3], bc[3];
  cross3(ac, ad, cd);
  cross3(ad, ab, db);
  cross3(ab, ac, bc);
  const double den = 2.0 * dot3(ab, cd);
  if (!(den != 0.0)) return false;
  const double la = dot3(ab, ab), lc = dot3(ac, ac), ld = dot3(ad, ad);
  for (int k = 0; k < 3; ++k) out[k] = a[k] + (la * cd[k] + lc * db[k] + ld * bc[k]) / den;
  return out[0] == out[0] && out[1] == out[1] && out[2] == out[2] && fabs(out[0]) < 1e300 &&
         fabs(out[1]) < 1e300 && fabs(out[2]) < 1e300;
}

// Circumcentre of triangle abc in its plane; false when degenerate.
GDR_HD_INLINE bool tri_circumcenter(const double* a, const double* b, const double* c,
                                    double* out) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  double n[3], nab[3], acn[3];
  cross3(ab, ac, n);
  const double den = 2.0 * dot3(n, n);
  if (!(den > 0.0)) return false;
  cross3(n, ab, nab);
  cross3(ac, n, acn);
  const double lb = dot3(ab, ab), lc = dot3(ac, ac);
  for (int k = 0; k < 3; ++k) out[k] = a[k] + (lc * nab[k] + lb * acn[k]) / den;
  return out[0] == out[0] && out[1] == out[1] && out[2] == out[2] && fabs(out[0]) < 1e300 &&
         fabs(out[1]) < 1e300 && fabs(out[2]) < 1e300;
}

// Moves p to the nearest point of the plane through a, b, c (unchanged when abc is flat).
GDR_HD_INLINE void project_on_plane(const double* a, const double* b, const double* c, double* p) {
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  double n[3];
  cross3(ab, ac, n);
  const double nn = dot3(n, n);
  if (!(nn > 0.0)) return;
  const double h = dot3(ap, n) / nn;
  for (int k = 0; k < 3; ++k) p[k] -= h * n[k];
}

// Does p lie strictly inside the diametral ball of triangle abc (the smallest sphere through
// a, b, c)? A refinement decision, not topology: rounded, with the ball shrunk by a relative
// 1e-12 so that points on its boundary (the triangle's own cocircular neighbours) do not
// encroach.
GDR_HD_INLINE bool in_diametral_ball(const double* a, const double* b, const double* c,
                                     const double* p) {
  double o[3];
  if (!tri_circumcenter(a, b, c, o)) return false;
  const double r2 = dist2(o, a);
  return dist2(o, p) < r2 * (1.0 - 1e-12);
}

// Does p lie in the protecting ball of vertex v (a sharp feature: qm3d/features.h)?
GDR_HD_INLINE bool in_protecting_ball(const TetView& m, int v, const double* p) {
  const double r = m.prad[v];
  return r > 0 && dist2(pt(m, v), p) <= r * r;
}

// ---------------------------------------------------------------------------------------
// Topology.

GDR_HD_INLINE int corner_of(const TetView& m, int t, int v) {
  const int* q = m.tv + 4 * t;
  return q[0] == v ? 0 : (q[1] == v ? 1 : (q[2] == v ? 2 : (q[3] == v ? 3 : -1)));
}

GDR_HD_INLINE bool is_subseg_edge(const TetView& m, int t, int e) {
  return (m.tflag[t] & (kSeg0 << e)) != 0;
}

// Is the tetrahedron edge joining vertices x and y a subsegment? (x, y must be vertices of t.)
GDR_HD_INLINE bool is_subseg(const TetView& m, int t, int x, int y) {
  return is_subseg_edge(m, t, edge_index(corner_of(m, t, x), corner_of(m, t, y)));
}

// The face of t, other than face `f`, that contains the edge xy (x, y on face f).
GDR_HD_INLINE int other_face_at_edge(const TetView& m, int t, int f, int x, int y) {
  const int cx = corner_of(m, t, x), cy = corner_of(m, t, y);
  for (int g = 0; g < 4; ++g)
    if (g != f && g != cx && g != cy) return g;
  return -1;
}

// The subface across edge xy (not a subsegment) of subface s in its facet, found by turning
// around xy through the tetrahedra on one side of s; -1 if the walk fails (broken mesh).
GDR_HD_INLINE int subface_across(const TetView& m, int s, int x, int y) {
  int tf = m.st[2 * s] >= 0 ? m.st[2 * s] : m.st[2 * s + 1];
  if (tf < 0) return -1;
  int t = tf >> 2, f = tf & 3;
  for (int guard = 0; guard < 1000; ++guard) {
    const int g = other_face_at_edge(m, t, f, x, y);
    const int sub = m.tsub[4 * t + g];
    if (sub >= 0) return sub;
    const int nb = m.tn[4 * t + g];
    if (nb < 0) return -1;
    t = nb >> 2;
    f = nb & 3;
  }
  return -1;
}

// The segment that subsegment xy lies on: that of a segment point among its endpoints, or,
// between two input vertices, the segment joining them.
GDR_HD_INLINE int segment_of(const TetView& m, int a, int b) {
  if (m.ptype[a] == kSegmentPoint) return m.pseg[a];
  if (m.ptype[b] == kSegmentPoint) return m.pseg[b];
  for (int k = m.vseg_begin[a]; k < m.vseg_begin[a + 1]; ++k) {
    const int s = m.vseg[k];
    if (m.seg[2 * s] == b || m.seg[2 * s + 1] == b) return s;
  }
  return -1;
}

// The coordinate axis most nearly along subface s's normal: dropping it projects s (and
// its facet's nearby subfaces) without degeneracy. Rounded, but only picks a projection.
GDR_HD_INLINE int subface_normal_axis(const TetView& m, int s) {
  const int* v = m.sv + 3 * s;
  double u1[3], u2[3], n[3];
  for (int k = 0; k < 3; ++k) {
    u1[k] = pt(m, v[1])[k] - pt(m, v[0])[k];
    u2[k] = pt(m, v[2])[k] - pt(m, v[0])[k];
  }
  cross3(u1, u2, n);
  return fabs(n[0]) >= fabs(n[1]) ? (fabs(n[0]) >= fabs(n[2]) ? 0 : 2) : (fabs(n[1]) >= fabs(n[2]) ? 1 : 2);
}

// Does facet f bend (merged across near-flat edges, cdt3d's coplanar_angle)? Its points go
// on the plane of their subface, not on one plane of the facet.
GDR_HD_INLINE bool facet_bends(const TetView& m, int f) { return m.fplane && m.fplane[3 * f] < 0; }

// Is the subsegment ab on a sharp segment (where facets meet at a small angle)?
GDR_HD_INLINE bool is_sharp_subseg(const TetView& m, int a, int b) {
  const int s = segment_of(m, a, b);
  return s >= 0 && (m.sharp[s] & kSharp);
}

// Orientation of the point p against face f of t: > 0 when p lies on the inner side (the
// tetrahedron (face corners, p) is positive), < 0 outside, 0 on the face's plane.
GDR_HD_INLINE double face_orient(const TetView& m, int t, int f, const double* p) {
  const int* q = m.tv + 4 * t;
  return pred::orient3d(pt(m, q[face_corner(f, 0)]), pt(m, q[face_corner(f, 1)]),
                        pt(m, q[face_corner(f, 2)]), p);
}

// Is the tetrahedron (a, b, c, p) of signed 6-volume vol6 flat up to rounding (its height
// below 1e-10 of its longest edge)? Points meant to lie on a facet or segment are rounded
// off it; a tetrahedron joining one to its own facet would be such a sliver of zero volume,
// and a surface folded over itself within the facet's plane.
GDR_HD_INLINE bool rounding_flat(const double* a, const double* b, const double* c, const double* p,
                                 double vol6) {
  const double* v[4] = {a, b, c, p};
  double l2 = 0;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) l2 = fmax(l2, dist2(v[i], v[j]));
  return fabs(vol6) < 1e-10 * l2 * sqrt(l2);
}

GDR_HD_INLINE double tet_insphere(const TetView& m, int t, const double* p) {
  const int* q = m.tv + 4 * t;
  return pred::insphere(pt(m, q[0]), pt(m, q[1]), pt(m, q[2]), pt(m, q[3]), p);
}

// Splitting point of subsegment ab. Concentric shells (Ruppert, Shewchuk, TetGen): when
// exactly one endpoint is an input vertex, split at a power-of-two distance from it, so that
// segments meeting at a small angle are cut at matching radii and do not encroach each
// other forever.
GDR_HD_INLINE void segment_split_point(const TetView& m, int va, int vb, double* out) {
  const double* a = pt(m, va);
  const double* b = pt(m, vb);
  const bool ia = m.ptype[va] == kInputPoint, ib = m.ptype[vb] == kInputPoint;
  double f = 0.5;
  if (ia != ib) {
    const double len = sqrt(dist2(a, b));
    const double d = exp2(floor(log2(0.5 * len) + 0.5));  // nearest power of two to len/2
    f = d / len;
    if (!(f > 0.25 && f < 0.75)) f = 0.5;
    if (ib) f = 1.0 - f;
  }
  for (int k = 0; k < 3; ++k) out[k] = f == 0.5 ? 0.5 * (a[k] + b[k]) : a[k] + f * (b[k] - a[k]);
}

}  // namespace gdr::m3d
