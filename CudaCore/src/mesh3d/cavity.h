// Concurrent point insertion into a constrained Delaunay tetrahedralization: the paper's
// section 6.3-6.5 (grow cavities with ExpandList, filter dependent points, remesh), written
// once as host+device functors for both execution spaces.
//
// A point p to insert comes with where it was located (`Candidate`). Its cavity is grown by
// the Bowyer-Watson rule (tetrahedra whose circumsphere strictly holds p) without crossing
// subfaces; the tetrahedra holding p, and for points on segments or facets those around the
// split subsegment or subface, are in by force. Points on a facet (or a segment) also grow a
// subface cavity in the facet: subfaces whose circumcircle holds p, across edges that are not
// subsegments; the tetrahedra on both sides of such a subface are in by force. Each element a
// cavity takes is claimed with an atomic priority mark (S3); a point that loses a claim
// waits for a later iteration. Then every cavity is checked exactly: each boundary face must
// see p strictly on its inner side, so that p joined to the boundary gives positive
// tetrahedra. Cavities that touch go in together when each shared face stays locally
// Delaunay.
#pragma once
#include "exec/priority.h"
#include "mesh3d/mesh3d.h"

namespace gdr::m3d {

using exec::u64;

// What a point splits. kSegmentSplit: the subsegment (a, b), which is edge ek of tetrahedron
// `start`; kFacetSplit: subface `sub` (face ek of `start`), p lies in it; kFreePoint: p lies
// in tetrahedron `start`.
// kSleeping: a subsegment whose split sleeps (qm3d/engine.h) but counts as failing again.
enum : signed char { kSleeping = -2, kDropped = -1, kSegmentSplit = 0, kFacetSplit = 1, kFreeSplit = 2 };
// Candidate::ek of a free point: a circumcentre asked for by a tetrahedron's shape
// (kShapePoint: refused in the protecting balls of sharp features), by its size
// (kSizePoint), or to make room for a split on a segment or facet whose cavity was not
// star-shaped (kMakeRoomPoint: it goes in even if it encroaches a subsegment or subface).
// kDelaunayPoint: a point of a triangulation without subfaces or subsegments (gDP3d), whose
// cavity needs only to be star-shaped, exactly: a new tetrahedron that is flat up to rounding
// but positive is kept (CheckCavity), as nothing constrains where the point lies.
enum : signed char { kShapePoint = -1, kMakeRoomPoint = 1, kSizePoint = 2, kDelaunayPoint = 3 };

struct Candidate {
  double p[3];
  u64 prio;
  int start;
  int sub;
  int a, b;
  int origin;  // the bad tetrahedron this point would fix, or -1
  int elem;    // the listed element that asked for it (qm3d: t * 16 + slot, for sleeping)
  signed char kind;
  signed char ek;
  signed char room;  // qm3d: its tetrahedron had asked for room (kMakeRoom) when it was made
};

// Why a point was not inserted this iteration (its `failed` word; 0: inserted).
enum : int {
  kFailLost = 1,      // a higher point claimed part of its cavity
  kFailEncroach = 2,  // it would encroach a subsegment or subface (split first)
  kFailTouch = 3,     // its cavity touches a higher one across a face that would not be Delaunay
  kFailStar = 4,      // a cavity face does not see it strictly inside (not star-shaped)
  kFailDeferred = 5,  // its cavity was still growing (S5)
  kFailCap = 6,       // the Steiner cap
  kFailDelaunay = 7,  // two of its new tetrahedra would not be locally Delaunay (CheckCavity)
  kFailReasons = 8,
};

// A point that makes room for a point on a segment or facet (kMakeRoomPoint: a free point,
// or the subface split its walk met instead) goes in even if it encroaches a subsegment:
// the subsegment it would wait for is often the one that asked for the room.
GDR_HD_INLINE bool makes_room(const Candidate& c) {
  return (c.kind == kFreeSplit || c.kind == kFacetSplit) && c.ek == kMakeRoomPoint;
}

struct PrioOf {
  const Candidate* cand;
  GDR_HD_INLINE u64 operator()(int k) const { return cand[k].prio; }
};

// ExpandList tuples: (point, element). The element is a tetrahedron, or a subface with
// kSubTuple set. The state's low bits are inputs; the result goes above kResultShift.
struct CavityTuple {
  int pt;
  int elem;
  int state;
};
enum : int { kForceIn = 1, kSubTuple = 2, kResultShift = 2 };
enum : int { kPending = 0, kCavity = 1, kRing = 2, kDup = 3, kLost = 4, kStale = 5 };

GDR_HD_INLINE int result_of(const CavityTuple& h) { return h.state >> kResultShift; }
GDR_HD_INLINE void set_result(CavityTuple& h, int r) {
  h.state = (h.state & ((1 << kResultShift) - 1)) | (r << kResultShift);
}
GDR_HD_INLINE bool is_sub_tuple(const CavityTuple& h) { return (h.state & kSubTuple) != 0; }

GDR_HD_INLINE bool face_has(const TetView& m, int t, int f, int v) {
  const int c = corner_of(m, t, v);
  return c >= 0 && c != f;
}

// A tetrahedron on one side of subface s (its face), for tests on s.
GDR_HD_INLINE int subface_tet(const TetView& m, int s) {
  return m.st[2 * s] >= 0 ? m.st[2 * s] >> 2 : m.st[2 * s + 1] >> 2;
}

// Is the edge xy of subface s a subsegment? (Read off a tetrahedron on one side.)
GDR_HD_INLINE bool subface_edge_is_subseg(const TetView& m, int s, int x, int y) {
  return is_subseg(m, subface_tet(m, s), x, y);
}

// p strictly inside the circumcircle of subface s, decided on a tetrahedron beside it (for
// p on the facet's plane the two agree: the sphere meets the plane in that circle).
GDR_HD_INLINE bool subface_conflict(const TetView& m, int s, const double* p) {
  return tet_insphere(m, subface_tet(m, s), p) > 0;
}

// ExpandList step (Algorithm 4 with the paper's growing rules). Writes up to 5 tuples.
struct GrowCavity {
  TetView m;
  const Candidate* cand;
  int* failed;
  static constexpr int K = 5;

  GDR_HD int operator()(long long, CavityTuple& h, CavityTuple* out) const {
    const Candidate& c = cand[h.pt];
    if (exec::volatile_load(&failed[h.pt])) {
      set_result(h, kStale);
      return 0;
    }
    return is_sub_tuple(h) ? grow_subface(h, c, out) : grow_tet(h, c, out);
  }

  GDR_HD int claim(int* slot, CavityTuple& h, const Candidate& c) const {
    const int r = exec::claim(slot, h.pt, c.prio, PrioOf{cand});
    if (r < 0) {
      failed[h.pt] = kFailLost;
      set_result(h, kLost);
    } else if (r == 0) {
      set_result(h, kDup);
    } else {
      set_result(h, kCavity);
    }
    return r;
  }

  // Ruppert / Shewchuk: a point that would encroach a subsegment is not inserted; the
  // subsegment is split first (flagged for the next iteration). Points on segments are
  // always inserted.
  // A sharp segment is never split for being encroached (it would cascade, TetGen): the
  // point that would encroach it is left out, and so is what asked for the point.
  GDR_HD bool encroaches_subsegment(int t, const Candidate& c) const {
    if (c.kind == kSegmentSplit || makes_room(c)) return false;
    const int flags = m.tflag[t];
    if (!(flags & kSegBits)) return false;
    for (int e = 0; e < 6; ++e) {
      if (!(flags & (kSeg0 << e))) continue;
      const int a = m.tv[4 * t + edge_corner(e, 0)], b = m.tv[4 * t + edge_corner(e, 1)];
      if (pred::in_diametral_sphere(pt(m, a), pt(m, b), c.p) > 0) {
        if (!is_sharp_subseg(m, a, b)) exec::atomic_or(&m.tflag[t], kSplitEdge0 << e);
        else give_up(c);
        return true;
      }
    }
    return false;
  }

  // What asked for a point that may not go in: the bad tetrahedron is protected, the subface
  // is left as it is.
  GDR_HD void give_up(const Candidate& c) const {
    if (c.kind == kFacetSplit) exec::atomic_or(&m.sflag[c.sub], kSubNoSplit);
    if (c.origin >= 0) protect_tet(m.tflag, c.origin);
  }

  // A shape-driven circumcentre in the protecting ball of a vertex of its cavity.
  GDR_HD bool in_protecting_balls(int t, const Candidate& c) const {
    if (c.kind != kFreeSplit || c.ek != kShapePoint) return false;
    for (int k = 0; k < 4; ++k)
      if (in_protecting_ball(m, m.tv[4 * t + k], c.p)) return true;
    return false;
  }

  // A point p on segment g is outside the circumsphere of every tetrahedron with an edge
  // between two other points of g (the line meets the sphere only there). Its rounded
  // coordinates may say otherwise for a flat tetrahedron; its fan would then join p to that
  // edge in a tetrahedron of (near) zero volume.
  GDR_HD bool holds_other_subsegment(int t, const Candidate& c) const {
    if (c.kind != kSegmentSplit || !(m.tflag[t] & kSegBits)) return false;
    const int g = segment_of(m, c.a, c.b);
    for (int e = 0; e < 6; ++e) {
      if (!(m.tflag[t] & (kSeg0 << e))) continue;
      const int x = m.tv[4 * t + edge_corner(e, 0)], y = m.tv[4 * t + edge_corner(e, 1)];
      const bool split_one = (x == c.a && y == c.b) || (x == c.b && y == c.a);
      if (!split_one && segment_of(m, x, y) == g) return true;
    }
    return false;
  }

  GDR_HD int grow_tet(CavityTuple& h, const Candidate& c, CavityTuple* out) const {
    const int t = h.elem;
    if (!(h.state & kForceIn) &&
        (!(tet_insphere(m, t, c.p) > 0) || holds_other_subsegment(t, c))) {
      set_result(h, kRing);
      return 0;
    }
    if (claim(&m.mark[t], h, c) <= 0) return 0;
    if ((h.state & kForceIn) && holds_other_subsegment(t, c)) {
      // A tetrahedron beside a split subface, flat on the facet along the segment: no fan.
      failed[h.pt] = kFailStar;
      return 0;
    }
    if (in_protecting_balls(t, c)) {
      give_up(c);
      failed[h.pt] = kFailEncroach;
      return 0;
    }
    if (encroaches_subsegment(t, c)) {
      failed[h.pt] = kFailEncroach;
      return 0;
    }
    int n = 0;
    for (int f = 0; f < 4; ++f) {
      const bool at_split = c.kind == kSegmentSplit && face_has(m, t, f, c.a) && face_has(m, t, f, c.b);
      const int s = m.tsub[4 * t + f];
      if (s >= 0) {
        // A free point that would encroach a subface is not inserted: the subface first.
        if (c.kind == kFreeSplit && c.ek != kMakeRoomPoint) {
          const int* q = m.tv + 4 * t;
          if (in_diametral_ball(pt(m, q[face_corner(f, 0)]), pt(m, q[face_corner(f, 1)]),
                                pt(m, q[face_corner(f, 2)]), c.p)) {
            // A subface that is not split leaves the tetrahedron as it is.
            if (m.sflag[s] & kSubNoSplit) {
              if (c.origin >= 0) protect_tet(m.tflag, c.origin);
            } else {
              exec::atomic_or(&m.tflag[t], kSplitFace0 << f);
            }
            failed[h.pt] = kFailEncroach;
            return n;
          }
        }
        if (at_split) out[n++] = CavityTuple{h.pt, s, kSubTuple | kForceIn};
        continue;  // subfaces are walls; the subface cavity crosses them
      }
      const int nb = m.tn[4 * t + f];
      if (nb >= 0) out[n++] = CavityTuple{h.pt, nb >> 2, at_split ? kForceIn : 0};
    }
    return n;
  }

  GDR_HD int grow_subface(CavityTuple& h, const Candidate& c, CavityTuple* out) const {
    const int s = h.elem;
    if (!(h.state & kForceIn) && !subface_conflict(m, s, c.p)) {
      set_result(h, kRing);
      return 0;
    }
    if (claim(&m.smark[s], h, c) <= 0) return 0;
    int n = 0;
    for (int side = 0; side < 2; ++side) {
      const int tf = m.st[2 * s + side];
      if (tf >= 0) out[n++] = CavityTuple{h.pt, tf >> 2, kForceIn};
    }
    const int st0 = subface_tet(m, s);
    for (int e = 0; e < 3; ++e) {
      const int x = m.sv[3 * s + (e + 1) % 3], y = m.sv[3 * s + (e + 2) % 3];
      const int ce = edge_index(corner_of(m, st0, x), corner_of(m, st0, y));
      if (is_subseg_edge(m, st0, ce)) {
        if (c.kind == kFacetSplit && !makes_room(c) && pred::in_diametral_sphere(pt(m, x), pt(m, y), c.p) > 0) {
          if (!is_sharp_subseg(m, x, y)) exec::atomic_or(&m.tflag[st0], kSplitEdge0 << ce);
          else give_up(c);
          failed[h.pt] = kFailEncroach;
          return n;
        }
        continue;
      }
      const int ns = subface_across(m, s, x, y);
      if (ns >= 0) out[n++] = CavityTuple{h.pt, ns, kSubTuple};
    }
    return n;
  }
};

// The new tetrahedron on face f of cavity tetrahedron t is (face corners, p): its insphere.
GDR_HD_INLINE double new_tet_insphere(const TetView& m, int t, int f, const double* p,
                                      const double* q) {
  const int* v = m.tv + 4 * t;
  return pred::insphere(pt(m, v[face_corner(f, 0)]), pt(m, v[face_corner(f, 1)]),
                        pt(m, v[face_corner(f, 2)]), p, q);
}

// Marks that did not survive mean a higher point overlaps: drop this one. A ring
// tetrahedron (just outside the cavity) held by a higher point's cavity means the two
// cavities touch: both fans then meet across the shared faces, and both points go in together
// only if each shared face that is not a subface stays locally Delaunay (the other point
// outside the sphere of our new tetrahedron on it).
struct VerifyClaims {
  TetView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  int* failed;
  bool touching;  // false: any contact with a higher cavity drops this point
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    const int r = result_of(h);
    if (is_sub_tuple(h)) {
      if (r == kCavity && m.smark[h.elem] != h.pt + 1) failed[h.pt] = kFailLost;
      return;
    }
    if (r == kCavity && m.mark[h.elem] != h.pt + 1) failed[h.pt] = kFailLost;
    if (r != kRing) return;
    const int u = h.elem, other = m.mark[u];
    if (!exec::held_above(other, h.pt, cand[h.pt].prio, PrioOf{cand})) return;
    if (!touching) {
      failed[h.pt] = kFailTouch;
      return;
    }
    const double* q = cand[other - 1].p;
    for (int g = 0; g < 4; ++g) {
      const int nb = m.tn[4 * u + g];
      if (nb < 0 || m.tsub[4 * u + g] >= 0 || m.mark[nb >> 2] != h.pt + 1) continue;
      if (new_tet_insphere(m, nb >> 2, nb & 3, cand[h.pt].p, q) > 0) failed[h.pt] = kFailTouch;
    }
  }
};

struct SetInCavity {
  TetView m;
  const CavityTuple* tuples;
  const int* failed;
  int value;  // 1: set for winners, 0: clear for points dropped after marking
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (result_of(h) != kCavity) return;
    int* flag = is_sub_tuple(h) ? &m.sflag[h.elem] : &m.tflag[h.elem];
    const int bit = is_sub_tuple(h) ? int(kSubInCavity) : int(kInCavity);
    const int* mark = is_sub_tuple(h) ? &m.smark[h.elem] : &m.mark[h.elem];
    if (value && !failed[h.pt]) *flag |= bit;
    // Only the owner of the mark may clear: a failed point's tuple can name an element that
    // a winner took over. A subface also loses its fan edges (MarkSubfaceFans).
    if (!value && failed[h.pt] && *mark == h.pt + 1) {
      *flag &= is_sub_tuple(h) ? ~(bit | (7 * kSubFanEdge0)) : ~bit;
      if (!is_sub_tuple(h))  // its boundary subfaces flip no more (MarkFlips)
        for (int f = 0; f < 4; ++f)
          if (m.tsub[4 * h.elem + f] >= 0) exec::atomic_and(&m.sflag[m.tsub[4 * h.elem + f]], ~int(kSubFlipBits));
    }
  }
};

// Face f of cavity tetrahedron t of point j: interior to the cavity, a face of the split
// subface cavity (replaced by new subfaces, no new tetrahedron on it), or a boundary face
// that gets a new tetrahedron (p, face).
enum : int { kFaceInterior = 0, kFaceFan = 1, kFaceSplit = 2 };

GDR_HD_INLINE int cavity_face(const TetView& m, int j, int t, int f) {
  const int s = m.tsub[4 * t + f];
  if (s >= 0)
    return (m.sflag[s] & kSubInCavity) && m.smark[s] == j + 1 ? kFaceSplit : kFaceFan;
  const int nb = m.tn[4 * t + f];
  if (nb >= 0 && (m.tflag[nb >> 2] & kInCavity) && m.mark[nb >> 2] == j + 1) return kFaceInterior;
  return kFaceFan;
}

// Edge e (opposite vertex e) of a subface in the split subface cavity of point j: does it
// bound the subface cavity, so that a new subface (p, edge) replaces the old one there?
// The split subsegment itself does not (p lies on it). Decided once by MarkSubfaceFans,
// before any link changes, and read back from the subface's flags.
GDR_HD_INLINE bool compute_subface_fan_edge(const TetView& m, const Candidate& c, int j, int s,
                                            int e) {
  const int x = m.sv[3 * s + (e + 1) % 3], y = m.sv[3 * s + (e + 2) % 3];
  if (c.kind == kSegmentSplit && ((x == c.a && y == c.b) || (x == c.b && y == c.a))) return false;
  if (subface_edge_is_subseg(m, s, x, y)) return true;
  const int ns = subface_across(m, s, x, y);
  return !(ns >= 0 && (m.sflag[ns] & kSubInCavity) && m.smark[ns] == j + 1);
}

// The index (0..2) of the vertex of subface s that is neither x nor y.
GDR_HD_INLINE int edge_opposite(const TetView& m, int s, int x, int y) {
  int e = 0;
  for (int q = 0; q < 3; ++q) {
    const int v = m.sv[3 * s + q];
    if (v != x && v != y) e = q;
  }
  return e;
}

GDR_HD_INLINE bool subface_fan_edge(const TetView& m, int s, int e) {
  return (m.sflag[s] & (kSubFanEdge0 << e)) != 0;
}

struct MarkSubfaceFans {
  TetView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  const int* failed;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (!is_sub_tuple(h) || result_of(h) != kCavity || failed[h.pt]) return;
    int bits = 0;
    for (int e = 0; e < 3; ++e)
      if (compute_subface_fan_edge(m, cand[h.pt], h.pt, h.elem, e)) bits |= kSubFanEdge0 << e;
    m.sflag[h.elem] |= bits;
  }
};

// Around the edge xy of fan face f of cavity tetrahedron t (of point j), through the
// cavity, to the next fan face at xy: the new tetrahedra on the two fan faces share the face
// (x, y, p). Returns false when the walk ends on the domain boundary instead (xy bounds a
// split boundary subface). `split` is the split subface crossed on the way (the face
// (x, y, p) is then a new subface), or -1; `broken` reports a walk that found no end.
struct FanNeighbour {
  int u = -1, g = -1, split = -1;
  bool broken = false;
};

GDR_HD_INLINE bool fan_neighbour(const TetView& m, int j, int t, int f, int x, int y, FanNeighbour& r) {
  int u = t, g = f;
  for (int guard = 0; guard < 4096; ++guard) {
    const int g2 = other_face_at_edge(m, u, g, x, y);
    const int kind = cavity_face(m, j, u, g2);
    if (kind == kFaceFan) {
      r.u = u;
      r.g = g2;
      return true;
    }
    if (kind == kFaceSplit) r.split = m.tsub[4 * u + g2];
    const int nb = m.tn[4 * u + g2];
    if (nb < 0) return false;  // the domain boundary: a split boundary subface
    u = nb >> 2;
    g = nb & 3;
  }
  r.broken = true;
  return false;
}

// ---------------------------------------------------------------------------------------
// Subface flips. On a facet planar only up to rounding (a part turned to an angle, a facet
// merged across near-flat edges, Steiner points rounded off their facet), four corners of two
// neighbouring boundary subfaces are nearly cocircular, and the diagonal between them can be
// the wrong one for a new point p: p's two new tetrahedra on the subfaces would meet across a
// face that is not locally Delaunay, for any point p there, and refinement stalls. The
// Delaunay tetrahedralization of those five points then has the other diagonal: the two
// subfaces (x, y, o), (y, x, w) become (o, w, x-or-y) and the two new tetrahedra (x, o, w, p)
// and (y, o, w, p), the flat tetrahedron (x, y, o, w) leaving the domain. The boundary moves
// by that flat tetrahedron, a rounding; every decision stays exact. The subface with the
// lower index (lo) keeps the smaller of x, y, the other keeps the larger.

// Decoded kSubFlip bits of subface s (sv not yet rewritten).
struct SubfaceFlip {
  int e = -1;          // the edge opposite corner e flips; -1: no flip
  bool valid = true;   // false: marked for two edges at once
  bool lo = false;
  int own = -1, other = -1, vmin = -1, vmax = -1;  // its corner off the edge, the neighbour's, the edge
  GDR_HD_INLINE int replaced() const { return lo ? vmax : vmin; }
  GDR_HD_INLINE bool on() const { return e >= 0; }
};

GDR_HD_INLINE SubfaceFlip subface_flip(const TetView& m, int s) {
  SubfaceFlip r;
  if (s < 0 || !(m.sflag[s] & kSubFlip)) return r;
  const int bits = (m.sflag[s] / kSubFlipEdge0) & 7;
  r.e = bits == 1 ? 0 : (bits == 2 ? 1 : 2);
  r.valid = bits == 1 || bits == 2 || bits == 4;
  r.lo = (m.sflag[s] & kSubFlipLo) != 0;
  r.own = m.sv[3 * s + r.e];
  const int x = m.sv[3 * s + (r.e + 1) % 3], y = m.sv[3 * s + (r.e + 2) % 3];
  r.vmin = x < y ? x : y;
  r.vmax = x < y ? y : x;
  r.other = m.saux[s];
  return r;
}

GDR_HD_INLINE bool one_sided(const TetView& m, int s) { return (m.st[2 * s] < 0) != (m.st[2 * s + 1] < 0); }

// The corners (besides p) of the new tetrahedron on fan face f of cavity tetrahedron t, in
// its slot's order: the face's corners, one of them replaced when the subface there flips.
GDR_HD_INLINE void fan_corners(const TetView& m, int t, int f, int* v) {
  for (int k = 0; k < 3; ++k) v[k] = m.tv[4 * t + face_corner(f, k)];
  const SubfaceFlip fl = subface_flip(m, m.tsub[4 * t + f]);
  if (fl.on() && fl.valid)
    for (int k = 0; k < 3; ++k)
      if (v[k] == fl.replaced()) v[k] = fl.other;
}

GDR_HD_INLINE bool holds(const int* v, int a) { return v[0] == a || v[1] == a || v[2] == a; }

// The fan face, (u, g) or its flip partner, whose new tetrahedron holds the face (a, b, p).
GDR_HD_INLINE bool fan_holder(const TetView& m, int j, int& u, int& g, int a, int b) {
  int v[3];
  fan_corners(m, u, g, v);
  if (holds(v, a) && holds(v, b)) return true;
  const SubfaceFlip fl = subface_flip(m, m.tsub[4 * u + g]);
  FanNeighbour r;
  if (!fl.on() || !fl.valid || !fan_neighbour(m, j, u, g, fl.vmin, fl.vmax, r) || r.split >= 0) return false;
  u = r.u;
  g = r.g;
  fan_corners(m, u, g, v);
  return holds(v, a) && holds(v, b);
}

// Across the face (a, b, p) of the new tetrahedron on fan face (t, f): as fan_neighbour, the
// fan face holding the other new tetrahedron there (flips included), or the boundary.
GDR_HD_INLINE bool fan_across(const TetView& m, int j, int t, int f, int a, int b, FanNeighbour& r) {
  const SubfaceFlip fl = subface_flip(m, m.tsub[4 * t + f]);
  int u = t, g = f;
  if (fl.on() && fl.valid) {
    FanNeighbour partner;
    if (!fan_neighbour(m, j, t, f, fl.vmin, fl.vmax, partner) || partner.split >= 0) {
      r.broken = true;
      return false;
    }
    if ((a == fl.own && b == fl.other) || (a == fl.other && b == fl.own)) {
      r = partner;  // the face between the two flipped tetrahedra
      return true;
    }
    if (a == fl.other || b == fl.other) {  // a face the partner's tetrahedron had
      u = partner.u;
      g = partner.g;
    }
  }
  const bool inside = fan_neighbour(m, j, u, g, a, b, r);
  if (inside && !fan_holder(m, j, r.u, r.g, a, b)) {
    r.broken = true;
    return false;
  }
  return inside;
}

// The corner of the new tetrahedron on fan face (u, g) that is neither a nor b.
GDR_HD_INLINE int fan_apex(const TetView& m, int u, int g, int a, int b) {
  int v[3];
  fan_corners(m, u, g, v);
  for (int k = 0; k < 3; ++k)
    if (v[k] != a && v[k] != b) return v[k];
  return -1;
}

// The flip of subfaces (o, x, y), (y, x, w) to (o, x, w), (o, w, y) keeps the surface from
// folding only if the quadrilateral o x w y is convex in the facet: x, y strictly on either
// side of ow and o, w on either side of xy, in the projection along subface `ref`'s dominant
// normal axis (both subfaces pass the lower index, so they decide alike). The tetrahedra
// with p do not show it: p lies on or next to the facet, and their signs are then roundings
// (the cap of a turned cylinder folded over itself so).
GDR_HD_INLINE bool flip_keeps_facet_flat(const TetView& m, int ref, int o, int x, int y, int w) {
  const int drop = subface_normal_axis(m, ref);
  const int ax = drop == 0 ? 1 : 0, ay = drop == 2 ? 1 : 2;
  double q[4][2];
  const int id[4] = {o, x, y, w};
  for (int k = 0; k < 4; ++k) {
    q[k][0] = pt(m, id[k])[ax];
    q[k][1] = pt(m, id[k])[ay];
  }
  const double before = pred::orient2d(q[0], q[1], q[2]);  // (o, x, y)
  const double left = pred::orient2d(q[0], q[1], q[3]);    // (o, x, w)
  const double right = pred::orient2d(q[0], q[3], q[2]);   // (o, w, y)
  const double partner = pred::orient2d(q[2], q[1], q[3]); // (y, x, w)
  return before > 0 ? (left > 0 && right > 0 && partner > 0)
                    : (before < 0 && left < 0 && right < 0 && partner < 0);
}

// Before CheckCavity: each boundary fan subface whose two new tetrahedra with its neighbour
// across a non-subsegment edge would not be locally Delaunay marks that edge to flip, when
// both flipped tetrahedra are positive and not flat. Both subfaces decide alike (the test
// is symmetric); CheckCavity then checks the result with the rest of the fan.
struct MarkFlips {
  TetView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  const int* failed;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (is_sub_tuple(h) || result_of(h) != kCavity || failed[h.pt]) return;
    const Candidate& c = cand[h.pt];
    const int t = h.elem;
    for (int f = 0; f < 4; ++f) {
      const int s = m.tsub[4 * t + f];
      if (s < 0 || !one_sided(m, s) || cavity_face(m, h.pt, t, f) != kFaceFan) continue;
      int v[3];
      for (int k = 0; k < 3; ++k) v[k] = m.tv[4 * t + face_corner(f, k)];
      for (int e = 0; e < 3; ++e) {
        const int o = m.sv[3 * s + e], x = m.sv[3 * s + (e + 1) % 3], y = m.sv[3 * s + (e + 2) % 3];
        if (is_subseg(m, t, x, y)) continue;
        FanNeighbour r;
        if (!fan_neighbour(m, h.pt, t, f, x, y, r) || r.split >= 0) continue;
        const int s2 = m.tsub[4 * r.u + r.g];
        if (s2 < 0 || s2 == s || m.sfacet[s2] != m.sfacet[s] || !one_sided(m, s2)) continue;
        int w = -1;
        for (int q = 0; q < 3; ++q) {
          const int z = m.tv[4 * r.u + face_corner(r.g, q)];
          if (z != x && z != y) w = z;
        }
        if (!(pred::insphere(pt(m, v[0]), pt(m, v[1]), pt(m, v[2]), c.p, pt(m, w)) > 0)) continue;
        const bool lo = s < s2;
        if (!flip_keeps_facet_flat(m, lo ? s : s2, o, x, y, w)) continue;
        const int vmin = x < y ? x : y, vmax = x < y ? y : x;
        // Own flipped tetrahedron: the face's corners with one of the edge's replaced by w;
        // the partner's: its corners with the other replaced by o.
        int a[3], b[3];
        for (int k = 0; k < 3; ++k) {
          a[k] = v[k] == (lo ? vmax : vmin) ? w : v[k];
          const int z = m.tv[4 * r.u + face_corner(r.g, k)];
          b[k] = z == (lo ? vmin : vmax) ? o : z;
        }
        const double va = pred::orient3d(pt(m, a[0]), pt(m, a[1]), pt(m, a[2]), c.p);
        const double vb = pred::orient3d(pt(m, b[0]), pt(m, b[1]), pt(m, b[2]), c.p);
        if (!(va > 0) || !(vb > 0) || rounding_flat(pt(m, a[0]), pt(m, a[1]), pt(m, a[2]), c.p, va) ||
            rounding_flat(pt(m, b[0]), pt(m, b[1]), pt(m, b[2]), c.p, vb))
          continue;
        m.saux[s] = w;
        exec::atomic_or(&m.sflag[s], kSubFlip | (lo ? int(kSubFlipLo) : 0) | (kSubFlipEdge0 << e));
      }
    }
  }
};

// A flip is kept only when both subfaces marked the same edge, each naming the other's corner.
GDR_HD_INLINE bool flip_consistent(const TetView& m, int j, int t, int f) {
  const SubfaceFlip fl = subface_flip(m, m.tsub[4 * t + f]);
  if (!fl.on()) return true;
  if (!fl.valid) return false;
  FanNeighbour r;
  if (!fan_neighbour(m, j, t, f, fl.vmin, fl.vmax, r) || r.split >= 0) return false;
  const SubfaceFlip other = subface_flip(m, m.tsub[4 * r.u + r.g]);
  return other.on() && other.valid && other.lo != fl.lo && other.own == fl.other && other.other == fl.own &&
         other.vmin == fl.vmin && other.vmax == fl.vmax;
}

// Last exact checks before anything is written: every new tetrahedron must be positive, a
// split subface must have its tetrahedra in the cavity, and every face two new tetrahedra
// share (unless it is a new subface) must be locally Delaunay. Bowyer-Watson guarantees the
// last in a Delaunay tetrahedralization; in a constrained one near a subsegment that is
// itself encroached it may fail (the constrained Delaunay tetrahedralization with p then
// needs a tetrahedron without p, which a fan cannot give): such a point waits, and the
// subsegment is split first.
struct CheckCavity {
  TetView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  int* failed;
  // Once no point has gone in for two iterations: a point on a segment that sees a subface
  // from behind asks for room there as well as for the subsegments it encroaches to be split
  // (those can be waiting on it in turn: the rings of a part turned on a lathe stalled so).
  // Not earlier: on a scan (penguin, B = 2) it cost 4% more tetrahedra and 30% more time.
  bool room_too = false;

  // Decided on exact data: p on a planar facet F lies on the plane of F's subfaces (on a
  // facet merged across near-flat edges, the orientation tests decide); p on segment g
  // lies on the plane of a subface that holds both input endpoints of g.
  GDR_HD bool on_plane_of_subface(const Candidate& c, int s) const {
    if (c.kind == kFacetSplit)
      return m.sfacet[s] == m.sfacet[c.sub] && !facet_bends(m, m.sfacet[s]);
    if (c.kind != kSegmentSplit) return false;
    const int g = segment_of(m, c.a, c.b);
    if (g < 0) return false;
    const int* v = m.sv + 3 * s;
    return pred::orient3d(pt(m, v[0]), pt(m, v[1]), pt(m, v[2]), pt(m, m.seg[2 * g])) == 0 &&
           pred::orient3d(pt(m, v[0]), pt(m, v[1]), pt(m, v[2]), pt(m, m.seg[2 * g + 1])) == 0;
  }
  // On a facet that bends, a subface cavity spans subfaces of slightly different planes: the
  // new subface (p, x, y) on each of its boundary edges xy must keep p on the side of xy
  // where the old subface's third corner z was (in the projection along the subface's
  // dominant normal axis, exact orient2d), or the surface would fold over itself there.
  GDR_HD bool folds(const Candidate& c, int j, int s) const {
    const int* v = m.sv + 3 * s;
    const int drop = subface_normal_axis(m, s);
    const int ax = drop == 0 ? 1 : 0, ay = drop == 2 ? 1 : 2;
    const double p2[2] = {c.p[ax], c.p[ay]};
    for (int e = 0; e < 3; ++e) {
      if (!compute_subface_fan_edge(m, c, j, s, e)) continue;
      const double* x = pt(m, v[(e + 1) % 3]);
      const double* y = pt(m, v[(e + 2) % 3]);
      const double* z = pt(m, v[e]);
      const double x2[2] = {x[ax], x[ay]}, y2[2] = {y[ax], y[ay]}, z2[2] = {z[ax], z[ay]};
      const double sz = pred::orient2d(x2, y2, z2), sp = pred::orient2d(x2, y2, p2);
      if (!(sz > 0 ? sp > 0 : sp < 0)) return true;
    }
    return false;
  }

  // A point on a segment that sees a subface of its cavity from behind (a bore's edge beside
  // the next face of the bore, a plate's edge beside a post standing on it) lies in the
  // diametral sphere of a subsegment there: with p, that subsegment is no longer strongly
  // Delaunay, so a constrained Delaunay tetrahedralization need not exist (Shewchuk) and no
  // fan from p is valid. Such subsegments of the hidden tetrahedron t are split first. Not
  // where facets meet nearly flat (a scanned surface, every edge a segment): there such
  // splits only add points (penguin_hr: 17% more, with more of its volume bad).
  GDR_HD bool nearly_flat(int a, int b) const {
    const int g = segment_of(m, a, b);
    return g < 0 || (m.sharp[g] & kNearlyFlat);
  }

  GDR_HD bool split_encroached_subsegments(const Candidate& c, int t) const {
    if (nearly_flat(c.a, c.b)) return false;
    bool any = false;
    for (int e = 0; e < 6; ++e) {
      if (!(m.tflag[t] & (kSeg0 << e))) continue;
      const int x = m.tv[4 * t + edge_corner(e, 0)], y = m.tv[4 * t + edge_corner(e, 1)];
      if ((x == c.a && y == c.b) || (x == c.b && y == c.a) || is_sharp_subseg(m, x, y) || nearly_flat(x, y)) continue;
      if (pred::in_diametral_sphere(pt(m, x), pt(m, y), c.p) > 0) {
        exec::atomic_or(&m.tflag[t], kSplitEdge0 << e);
        any = true;
      }
    }
    return any;
  }

  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (result_of(h) != kCavity || failed[h.pt]) return;
    const Candidate& c = cand[h.pt];
    if (is_sub_tuple(h)) {
      if (facet_bends(m, m.sfacet[h.elem]) && folds(c, h.pt, h.elem)) failed[h.pt] = kFailStar;
      return;
    }
    const int t = h.elem;
    for (int f = 0; f < 4; ++f) {
      const int k = cavity_face(m, h.pt, t, f);
      const int s = m.tsub[4 * t + f];
      const double side = k == kFaceFan ? face_orient(m, t, f, c.p) : 0.0;
      if (k == kFaceFan && s >= 0 && on_plane_of_subface(c, s)) {
        // A subface that p does not split but whose plane p lies on (up to rounding): the
        // new tetrahedron on it would be flat.
        failed[h.pt] = kFailStar;
      } else if (k == kFaceFan && side > 0) {
        const int* v = m.tv + 4 * t;
        const int a = v[face_corner(f, 0)], b = v[face_corner(f, 1)], d = v[face_corner(f, 2)];
        if (c.ek != kDelaunayPoint && rounding_flat(pt(m, a), pt(m, b), pt(m, d), c.p, side)) {
          failed[h.pt] = kFailStar;  // its tetrahedron on this face would be flat
          exec::atomic_or(&m.tflag[t], kMakeRoom);
        }
        if (!flip_consistent(m, h.pt, t, f)) failed[h.pt] = kFailDelaunay;
        int q[3];  // the new tetrahedron's corners besides p (a flip replaces one)
        fan_corners(m, t, f, q);
        for (int e = 0; e < 3; ++e) {
          const int x = q[(e + 1) % 3], y = q[(e + 2) % 3];  // the edge opposite corner e
          FanNeighbour r;
          const bool inside = fan_across(m, h.pt, t, f, x, y, r);
          if (r.broken) {
            failed[h.pt] = kFailStar;
            continue;
          }
          if (r.split >= 0 && !compute_subface_fan_edge(m, c, h.pt, r.split, edge_opposite(m, r.split, x, y))) {
            // The face (x, y, p) would lie in the facet across new subfaces: xy is inside the
            // subface cavity but a tetrahedron at xy is not in the cavity. It is split first.
            failed[h.pt] = kFailStar;
            exec::atomic_or(&m.tflag[t], kMakeRoom);
          }
          if (!inside || r.split >= 0) continue;
          const int w = fan_apex(m, r.u, r.g, x, y);  // the other new tetrahedron's corner off the shared face
          if (pred::insphere(pt(m, q[0]), pt(m, q[1]), pt(m, q[2]), c.p, pt(m, w)) > 0) {
            // Something must change before p can go in: the subsegment is split, or else the
            // tetrahedron is (for a point on a segment or facet), or the bad tetrahedron
            // asking for p is left as it is.
            failed[h.pt] = kFailDelaunay;
            if (corner_of(m, t, x) >= 0 && corner_of(m, t, y) >= 0 && is_subseg(m, t, x, y) && !is_sharp_subseg(m, x, y))
              exec::atomic_or(&m.tflag[t], kSplitEdge0 << edge_index(corner_of(m, t, x), corner_of(m, t, y)));
            else if (c.kind != kFreeSplit)
              exec::atomic_or(&m.tflag[t], kMakeRoom);
            else if (c.origin >= 0)
              protect_tet(m.tflag, c.origin);
          }
        }
      } else if (k == kFaceFan) {
        // No star from p: the tetrahedron that hides p is split first (its circumsphere
        // holds p, so smaller tetrahedra there make room), and p tries again later.
        failed[h.pt] = kFailStar;
        if (!(c.kind == kSegmentSplit && s >= 0 && split_encroached_subsegments(c, t)) || room_too)
          exec::atomic_or(&m.tflag[t], kMakeRoom);
      } else if (k == kFaceSplit) {
        const int nb = m.tn[4 * t + f];
        if (nb >= 0 && !((m.tflag[nb >> 2] & kInCavity) && m.mark[nb >> 2] == h.pt + 1))
          failed[h.pt] = kFailStar;
      }
    }
  }
};

// New elements: counted per cavity tetrahedron (its fan faces) and per split subface (its
// fan edges), in two counts so that two scans give each its first slot; StoreSlotBase
// keeps that slot in aux (tetrahedra) or saux (subfaces).
struct CountNew {
  TetView m;
  const CavityTuple* tuples;
  const int* failed;
  int* tet_count;
  int* sub_count;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    int nt = 0, ns = 0;
    if (result_of(h) == kCavity && !failed[h.pt]) {
      if (is_sub_tuple(h)) {
        for (int e = 0; e < 3; ++e) ns += subface_fan_edge(m, h.elem, e);
      } else {
        for (int f = 0; f < 4; ++f) nt += cavity_face(m, h.pt, h.elem, f) == kFaceFan;
      }
    }
    tet_count[i] = nt;
    sub_count[i] = ns;
  }
};

struct StoreSlotBase {
  TetView m;
  const CavityTuple* tuples;
  const int* failed;
  const int* tet_offset;
  const int* sub_offset;
  int old_ntet, old_nsub;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (result_of(h) != kCavity || failed[h.pt]) return;
    if (is_sub_tuple(h)) m.saux[h.elem] = old_nsub + sub_offset[i];
    else m.aux[h.elem] = old_ntet + tet_offset[i];
  }
};

GDR_HD_INLINE int fan_rank(const TetView& m, int j, int t, int f) {
  int r = 0;
  for (int g = 0; g < f; ++g) r += cavity_face(m, j, t, g) == kFaceFan;
  return r;
}

GDR_HD_INLINE int subfan_rank(const TetView& m, int s, int e) {
  int r = 0;
  for (int k = 0; k < e; ++k) r += subface_fan_edge(m, s, k);
  return r;
}

// Remesh (section 6.5): one new tetrahedron (a, b, c, p) per fan face (a, b, c), linked
// to the tetrahedron outside the cavity (or to the other winner's new tetrahedron there);
// the links between new tetrahedra come in LinkNew.
struct CreateTets {
  TetView m;
  const Candidate* cand;
  const CavityTuple* tuples;
  const int* failed;
  const int* point_id;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (is_sub_tuple(h) || result_of(h) != kCavity || failed[h.pt]) return;
    const Candidate& c = cand[h.pt];
    const int t = h.elem, p = point_id[h.pt];
    const int tflags = m.tflag[t];
    int r = 0;
    for (int f = 0; f < 4; ++f) {
      if (cavity_face(m, h.pt, t, f) != kFaceFan) continue;
      const int nt = m.aux[t] + r++;
      int* nv = m.tv + 4 * nt;
      int corner[3];
      for (int k = 0; k < 3; ++k) corner[k] = face_corner(f, k);
      fan_corners(m, t, f, nv);
      nv[3] = p;
      // A flip brings in the partner's corner: its edges come from the partner's tetrahedron.
      const SubfaceFlip fl = subface_flip(m, m.tsub[4 * t + f]);
      int pu = -1;
      if (fl.on()) {
        FanNeighbour partner;
        fan_neighbour(m, h.pt, t, f, fl.vmin, fl.vmax, partner);
        pu = partner.u;
      }
      const int outer = m.tn[4 * t + f];
      if (outer >= 0 && (m.tflag[outer >> 2] & kInCavity)) {
        // Another winner's cavity is across: link to its new tetrahedron on this face (it
        // links back the same way). Its slot: its new-index base + the face's fan rank.
        const int u = outer >> 2, q = m.mark[u] - 1;
        const int other = m.aux[u] + fan_rank(m, q, u, outer & 3);
        m.tn[4 * nt + 3] = 4 * other + 3;
      } else {
        m.tn[4 * nt + 3] = outer;
        if (outer >= 0) m.tn[outer] = 4 * nt + 3;
      }
      const int s = m.tsub[4 * t + f];
      m.tsub[4 * nt + 3] = s;
      if (s >= 0) {
        for (int side = 0; side < 2; ++side)
          if (m.st[2 * s + side] == 4 * t + f) m.st[2 * s + side] = 4 * nt + 3;
      }
      for (int k = 0; k < 3; ++k) {
        m.tn[4 * nt + k] = -1;
        m.tsub[4 * nt + k] = -1;
      }
      // Edges of the old face keep their subsegment and split flags; an edge (corner, p)
      // is a subsegment when p splits a subsegment ending at that corner.
      int flags = kFresh;
      for (int k = 0; k < 3; ++k) {
        const int e_new = edge_index(k, (k + 1) % 3);
        int from = tflags, e_old = edge_index(corner[k], corner[(k + 1) % 3]);
        if (pu >= 0 && (nv[k] == fl.other || nv[(k + 1) % 3] == fl.other)) {
          const int x = nv[k], y = nv[(k + 1) % 3];
          // The new diagonal lies inside the facet: no flags. Else an edge of the partner's.
          from = x == fl.own || y == fl.own ? 0 : m.tflag[pu];
          e_old = from ? edge_index(corner_of(m, pu, x), corner_of(m, pu, y)) : 0;
        }
        if (from & (kSeg0 << e_old)) flags |= kSeg0 << e_new;
        if (from & (kSplitEdge0 << e_old)) flags |= kSplitEdge0 << e_new;
        if (c.kind == kSegmentSplit && (nv[k] == c.a || nv[k] == c.b))
          flags |= kSeg0 << edge_index(k, 3);
      }
      if (tflags & (kSplitFace0 << f)) flags |= kSplitFace0 << 3;
      m.tflag[nt] = flags;
      m.mark[nt] = 0;
      if (m.tregion) m.tregion[nt] = m.tregion[t];
    }
  }
};

// New subfaces: (p replacing vertex e) of each split subface, per fan edge e; same facet.
// Their tetrahedron links are filled by LinkNew.
struct CreateSubfaces {
  TetView m;
  const CavityTuple* tuples;
  const int* failed;
  const int* point_id;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (!is_sub_tuple(h) || result_of(h) != kCavity || failed[h.pt]) return;
    const int s = h.elem, p = point_id[h.pt];
    int r = 0;
    for (int e = 0; e < 3; ++e) {
      if (!subface_fan_edge(m, s, e)) continue;
      const int ns = m.saux[s] + r++;
      for (int k = 0; k < 3; ++k) m.sv[3 * ns + k] = k == e ? p : m.sv[3 * s + k];
      m.st[2 * ns] = m.st[2 * ns + 1] = -1;
      m.sfacet[ns] = m.sfacet[s];
      m.sflag[ns] = 0;
      m.smark[ns] = 0;
    }
  }
};

// Which side of subface s the face (a, b, c) (outside-counter-clockwise for its tetrahedron)
// is on: 0 when it turns the same way as (sv0, sv1, sv2), else 1 (host_mesh.h).
GDR_HD_INLINE int subface_side(const TetView& m, int s, int a, int b) {
  const int* v = m.sv + 3 * s;
  const bool same = (a == v[0] && b == v[1]) || (a == v[1] && b == v[2]) || (a == v[2] && b == v[0]);
  return same ? 0 : 1;
}

// Links the three faces at p of every new tetrahedron: turning around the face's old edge
// xy through the cavity, from the cavity tetrahedron it was built on, to the next fan face at
// xy; crossing a split subface on the way means the face (x, y, p) is a new subface.
struct LinkNew {
  TetView m;
  const CavityTuple* tuples;
  const int* failed;
  int* error;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (is_sub_tuple(h) || result_of(h) != kCavity || failed[h.pt]) return;
    const int t = h.elem;
    int r = 0;
    for (int f = 0; f < 4; ++f) {
      if (cavity_face(m, h.pt, t, f) != kFaceFan) continue;
      const int nt = m.aux[t] + r++;
      for (int k = 0; k < 3; ++k) link_face(h.pt, t, f, nt, k);
    }
  }

  // Face k of new tetrahedron nt (opposite its corner k, so it holds p and the old edge
  // between the other two corners).
  GDR_HD void link_face(int j, int t, int f, int nt, int k) const {
    const int x = m.tv[4 * nt + (k + 1) % 3], y = m.tv[4 * nt + (k + 2) % 3];
    FanNeighbour r;
    const bool inside = fan_across(m, j, t, f, x, y, r);
    int new_sub = -1;
    if (r.split >= 0) {
      const int e = edge_opposite(m, r.split, x, y);
      new_sub = m.saux[r.split] + subfan_rank(m, r.split, e);
    }
    if (r.broken || (!inside && new_sub < 0)) {
      *error = 1;
      return;
    }
    if (inside) {
      const int other = m.aux[r.u] + fan_rank(m, j, r.u, r.g);
      // In the other new tetrahedron (corners of face g, p) the face at xy is opposite the
      // corner that is neither x nor y.
      int v[3], ko = 0;
      fan_corners(m, r.u, r.g, v);
      for (int q = 0; q < 3; ++q)
        if (v[q] != x && v[q] != y) ko = q;
      m.tn[4 * nt + k] = 4 * other + ko;
    } else {
      m.tn[4 * nt + k] = -1;
    }
    set_subface(nt, k, new_sub);
  }

  GDR_HD void set_subface(int nt, int k, int s) const {
    if (s < 0) return;
    m.tsub[4 * nt + k] = s;
    const int* v = m.tv + 4 * nt;
    const int side = subface_side(m, s, v[face_corner(k, 0)], v[face_corner(k, 1)]);
    m.st[2 * s + side] = 4 * nt + k;
  }
};

// After LinkNew: flipped subfaces take their new corner (in the place of the one they lost,
// so they turn as before) and drop their flip marks.
struct FinishFlips {
  TetView m;
  const CavityTuple* tuples;
  const int* failed;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (is_sub_tuple(h) || result_of(h) != kCavity || failed[h.pt]) return;
    for (int f = 0; f < 4; ++f) {
      const int s = m.tsub[4 * h.elem + f];
      const SubfaceFlip fl = subface_flip(m, s);
      if (!fl.on() || cavity_face(m, h.pt, h.elem, f) != kFaceFan) continue;
      for (int k = 0; k < 3; ++k)
        if (m.sv[3 * s + k] == fl.replaced()) m.sv[3 * s + k] = fl.other;
      m.sflag[s] &= ~int(kSubFlipBits);
    }
  }
};

struct KillCavity {
  TetView m;
  const CavityTuple* tuples;
  const int* failed;
  GDR_HD void operator()(long long i) const {
    const CavityTuple& h = tuples[i];
    if (result_of(h) != kCavity || failed[h.pt]) return;
    if (is_sub_tuple(h)) m.sflag[h.elem] = kSubDead;
    else m.tflag[h.elem] = kDead;
  }
};

struct WritePoints {
  TetView m;
  const Candidate* cand;
  const int* failed;
  const int* point_id;
  GDR_HD void operator()(long long j) const {
    if (failed[j]) return;
    const Candidate& c = cand[j];
    const int p = point_id[j];
    for (int k = 0; k < 3; ++k) m.xyz[3 * p + k] = c.p[k];
    m.ptype[p] = c.kind == kSegmentSplit ? kSegmentPoint : (c.kind == kFacetSplit ? kFacetPoint : kFreePoint);
    m.pseg[p] = c.kind == kSegmentSplit ? segment_of(m, c.a, c.b) : -1;
    m.pfacet[p] = c.kind == kFacetSplit ? m.sfacet[c.sub] : -1;
    // On a sharp segment the protecting ball's radius runs linearly between the ends.
    float r = 0;
    if (c.kind == kSegmentSplit && m.pseg[p] >= 0 && (m.sharp[m.pseg[p]] & kSharp)) {
      const float ra = m.prad[c.a], rb = m.prad[c.b];
      if (ra > 0 && rb > 0) {
        const double f = sqrt(dist2(pt(m, c.a), c.p) / dist2(pt(m, c.a), pt(m, c.b)));
        r = static_cast<float>(ra + f * (rb - ra));
      }
    }
    m.prad[p] = r;
  }
};

}  // namespace gdr::m3d
