// The per-element work of gDP3d that is its own (paper section 7): which faces of the
// Delaunay triangulation are restricted to the input surface (their Voronoi dual meets it),
// which tetrahedra lie inside it, the facet and cell criteria, and the splitting points.
// Cavities and insertion are mesh3d's (cavity.h), run by the shared engine steps.
#pragma once
#include <cmath>

#include "exec/hd.h"
#include "exec/priority.h"
#include "mesh3d/cavity.h"
#include "mesh3d/locate.h"
#include "qm3d/kernels.h"  // make_segment_candidate
#include "rdt3d/aabb.h"
#include "rdt3d/circumcentre.h"

namespace gdr::rdt3d {

using exec::u64;
using m3d::Candidate;
using m3d::pt;
using m3d::TetView;

// The criteria, in forms without square roots or trigonometry (0: off).
struct Criteria {
  double sin2_facet_angle = 0;  // sin^2 of FacetAngle
  double facet_size2 = 0;       // FacetSize^2: the radius of the facet's surface Delaunay ball
  double facet_distance2 = 0;   // FacetDistance^2: facet circumcentre to surface centre
  double radius_edge2 = 0;      // CellRadiusEdgeRatio^2
  double cell_size2 = 0;        // CellSize^2: circumradius
  int inside = 1;               // 1: the input is closed: tetrahedra are classified inside or out
  int volume = 1;               // 1: and those inside refined (else the surface only)
  double reach = 0;             // longer than any segment from inside the box out of it
  double feature_min2 = 0;      // feature subsegments shorter than this (squared) are not split
  int step_limit = 1 << 20;     // point-location walk bound
  // What the surface should be (kManifold for a closed input; kManifoldBoundary: an open
  // input's boundary edges and fans are allowed), for the manifold criterion (CGAL Mesh_3's
  // manifold(), EngineParams::manifold) and the count of places where it is not. The
  // criterion leaves facets whose longest edge is below manifold_min (squared): thin parts
  // below it stay pinched, and are reported.
  int manifold = 1;
  double manifold_min2 = 0;
};

enum : int { kManifold = 1, kManifoldBoundary = 2 };

// Tetrahedron flag bits of this mesher. It has no subfaces, and runs its own collect phase, so
// it keeps its per-tetrahedron state in the bits gQM3d uses for its collect mask
// (m3d::kCollectBits; compaction moves them with the tetrahedron). Sharp features are
// subsegments as in gQM3d (m3d::kSeg0 edge bits; split requests in m3d::kSplitEdge0), and
// m3d::kProtected marks a tetrahedron whose bad facets and cell are left as they are
// (exceptions: their splitting point lies in the diametral ball of a feature subsegment that
// may not be split, see splittable).
enum : int {
  kRestricted0 = 1 << m3d::kCollectShift,  // bits 19-22: face i is a restricted facet
  kRestrictedBits = 15 << m3d::kCollectShift,
  kInterior = 1 << (m3d::kCollectShift + 4),  // the circumcentre lies inside the surface
  kBadFacet0 = 1 << (m3d::kCollectShift + 5),  // bits 24-27: restricted face i fails a criterion
  kBadCell = 1 << (m3d::kCollectShift + 9),    // inside, and fails a cell criterion
};

// Candidate::a of a point on the surface (a free point otherwise, a = -1): its point type is
// set to kFacetPoint after insertion.
enum : int { kSurfacePoint = 1 };

// Points on the surface: the sample of input points, feature points (kInputPoint at input
// vertices, kSegmentPoint between) and inserted surface centres (box corners and
// circumcentres are free points).
GDR_HD_INLINE bool on_surface(const TetView& m, int v) {
  return m.ptype[v] != m3d::kFreePoint;
}

GDR_HD_INLINE bool tet_center(const TetView& m, int t, double* c) {
  const int* v = m.tv + 4 * t;
  return accurate_tet_circumcenter(pt(m, v[0]), pt(m, v[1]), pt(m, v[2]), pt(m, v[3]), c);
}

// The Voronoi edge dual to face f of t, from t's circumcentre p (computed by the caller) to
// the neighbour's q; on the hull (no neighbour) a ray along the face's outward normal, cut at
// `reach`.
GDR_HD_INLINE bool dual_segment_from(const TetView& m, const Criteria& c, int t, int f, const double* p, double* q) {
  const int nb = m.tn[4 * t + f];
  if (nb >= 0) return tet_center(m, nb >> 2, q);
  const int* v = m.tv + 4 * t;
  const double* a = pt(m, v[m3d::face_corner(f, 0)]);
  const double* b = pt(m, v[m3d::face_corner(f, 1)]);
  const double* d = pt(m, v[m3d::face_corner(f, 2)]);
  const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  double n[3];
  // Corners counter-clockwise seen from outside (tet_topology.h): u x w points outward.
  m3d::cross3(u, w, n);
  const double len = sqrt(m3d::dot3(n, n));
  if (!(len > 0)) return false;
  for (int k = 0; k < 3; ++k) q[k] = p[k] + c.reach * n[k] / len;
  return true;
}

// The surface centre x of restricted face f of t (where its dual meets the surface; of
// several, the centre of the largest surface Delaunay ball) and the input triangle it lies on;
// p: t's circumcentre.
// `contacts` (optional): how the dual meets the surface, when it could be formed (dual).
GDR_HD_INLINE bool surface_centre_from(const TetView& m, const AabbView& s, const Criteria& c, int t, int f,
                                       const double* p, double* x, int* tri, SegmentContacts* contacts = nullptr,
                                       bool* dual = nullptr) {
  double q[3];
  if (!dual_segment_from(m, c, t, f, p, q)) return false;
  if (dual) *dual = true;
  const int a = m.tv[4 * t + m3d::face_corner(f, 0)];
  return surface_point_on_segment(s, p, q, pt(m, a), x, tri, contacts);
}

GDR_HD_INLINE bool surface_centre(const TetView& m, const AabbView& s, const Criteria& c, int t, int f,
                                  double* x, int* tri) {
  double p[3];
  return tet_center(m, t, p) && surface_centre_from(m, s, c, t, f, p, x, tri);
}

// Is the face listed from t? Each face is listed once: from the lesser of its two tetrahedra.
GDR_HD_INLINE bool owns_face(const TetView& m, int t, int f) {
  const int nb = m.tn[4 * t + f];
  return nb < 0 || t < (nb >> 2);
}

// With a volume, do the two tetrahedra of face f of t lie on the same side of the surface
// (beyond the hull: outside)? A restricted facet should separate the inside from the outside,
// but the two tests differ where its dual only touches the surface (a circumcentre exactly on
// a plane of the input: CAD parts with dyadic coordinates give it) or crosses it twice (clips
// a sharp edge or a thin part): such a facet bounds nothing (issue 12). False for an open
// input (no tetrahedron is inside then).
GDR_HD_INLINE bool same_side(const TetView& m, const Criteria& c, int t, int f) {
  if (!c.inside) return false;
  const int nb = m.tn[4 * t + f];
  const bool in_t = (m.tflag[t] & kInterior) != 0;
  const bool in_u = nb >= 0 && (m.tflag[nb >> 2] & kInterior) != 0;
  return in_t == in_u;
}

// Facet criteria (CGAL Mesh_3's names) for a restricted facet abc with surface centre x: a
// corner off the surface, the smallest angle below FacetAngle, the surface Delaunay ball's
// radius above FacetSize, the facet's circumcentre farther than FacetDistance from x.
GDR_HD_INLINE bool facet_is_bad(const TetView& m, const Criteria& c, int t, int f, const double* x) {
  const int* v = m.tv + 4 * t;
  const int ia = v[m3d::face_corner(f, 0)], ib = v[m3d::face_corner(f, 1)], ic = v[m3d::face_corner(f, 2)];
  if (!on_surface(m, ia) || !on_surface(m, ib) || !on_surface(m, ic)) return true;
  const double *a = pt(m, ia), *b = pt(m, ib), *d = pt(m, ic);
  if (c.facet_size2 > 0 && m3d::dist2(x, a) > c.facet_size2) return true;
  double cc[3];
  if (!m3d::tri_circumcenter(a, b, d, cc)) return true;
  const double r2 = m3d::dist2(cc, a);
  if (c.sin2_facet_angle > 0) {
    // The smallest angle lies opposite the shortest edge: sin = lmin / (2 r).
    const double lmin2 = fmin(m3d::dist2(a, b), fmin(m3d::dist2(b, d), m3d::dist2(a, d)));
    if (lmin2 < 4 * r2 * c.sin2_facet_angle) return true;
  }
  return c.facet_distance2 > 0 && m3d::dist2(cc, x) > c.facet_distance2;
}

struct TetSize {
  double r2 = 0, lmin2 = 0, center[3] = {0, 0, 0};
  bool ok = false;
};

// Of the tetrahedron with corners p (those of a tetrahedron of the mesh, or of one whose
// vertex the sliver pass tries somewhere else).
GDR_HD_INLINE TetSize tet_size_of(const double* const p[4]) {
  TetSize s;
  double l = INFINITY;
  for (int e = 0; e < 6; ++e) l = fmin(l, m3d::dist2(p[m3d::edge_corner(e, 0)], p[m3d::edge_corner(e, 1)]));
  s.lmin2 = l;
  s.ok = accurate_tet_circumcenter(p[0], p[1], p[2], p[3], s.center);
  s.r2 = s.ok ? m3d::dist2(s.center, p[0]) : INFINITY;
  return s;
}

GDR_HD_INLINE TetSize tet_size(const TetView& m, int t) {
  const int* v = m.tv + 4 * t;
  const double* p[4] = {pt(m, v[0]), pt(m, v[1]), pt(m, v[2]), pt(m, v[3])};
  return tet_size_of(p);
}

// CGAL Mesh_3's rule: a tetrahedron's circumcentre is not inserted where it would destroy a
// restricted facet whose surface Delaunay ball holds it (it would spoil the surface next to
// it, and the surface refinement could cascade); the facet is refined instead (the
// kSplitFace0 bit of its face: this mesher has no subfaces), unless that facet is an
// exception (its tetrahedron is protected): the cell is then left as it is too. Runs on the
// cavities that passed every other check, before the winners are numbered.
struct RefuseEncroachingCells {
  TetView m;
  AabbView s;
  Criteria c;
  const Candidate* cand;
  const m3d::CavityTuple* tuples;
  int* failed;
  GDR_HD void operator()(long long i) const {
    const m3d::CavityTuple& h = tuples[i];
    if (m3d::is_sub_tuple(h) || m3d::result_of(h) != m3d::kCavity || failed[h.pt]) return;
    const Candidate& p = cand[h.pt];
    if (p.kind != m3d::kFreeSplit || p.a == kSurfacePoint) return;
    const int t = h.elem, flags = m.tflag[t];
    if (!(flags & kRestrictedBits)) return;
    double o[3];
    if (!tet_center(m, t, o)) return;
    for (int f = 0; f < 4; ++f) {
      if (!(flags & (kRestricted0 << f))) continue;
      double x[3];
      int tri;
      if (!surface_centre_from(m, s, c, t, f, o, x, &tri)) continue;
      const double r2 = m3d::dist2(x, pt(m, m.tv[4 * t + m3d::face_corner(f, 0)]));
      if (m3d::dist2(p.p, x) < r2) {
        if (!(flags & m3d::kProtected)) exec::atomic_or(&m.tflag[t], m3d::kSplitFace0 << f);
        else if (p.origin >= 0) m3d::protect_tet(m.tflag, p.origin);
        failed[h.pt] = m3d::kFailEncroach;
      }
    }
  }
};

// Feature subsegments are split when a point would take them away, unless they are shorter
// than feature_min or blocked: a subsegment whose split point would take away a subsegment
// of another feature (two features at a small angle: each split would undo the other)
// blocks itself by giving both its ends a protecting radius (m.prad) at least its length.
// Left as they are, they let refinement next to small angles terminate.
GDR_HD_INLINE bool splittable(const TetView& m, const Criteria& c, int a, int b) {
  const double d2 = m3d::dist2(pt(m, a), pt(m, b));
  const double ra = m.prad[a], rb = m.prad[b];
  return d2 >= c.feature_min2 && !(ra * ra >= d2 && rb * rb >= d2);
}

GDR_HD_INLINE void block(const TetView& m, int a, int b) {
  // Rounded up, so that the radius is never below the length.
  const float r = static_cast<float>(sqrt(m3d::dist2(pt(m, a), pt(m, b))) * (1 + 1e-6));
  if (m.prad[a] < r) m.prad[a] = r;
  if (m.prad[b] < r) m.prad[b] = r;
}

// Turns around edge xy from face f of t (which holds it): visit(u, g) sees each face g that
// holds xy of the tetrahedra u beyond f, in order, ending with f itself (seen from the other
// side) when the ring is closed. Returns 1 if visit stopped it, 0 all the way round, -1 at
// the hull, -2 on a broken ring.
template <class Visit>
GDR_HD_INLINE int turn_around_edge(const TetView& m, int t, int f, int x, int y, Visit visit) {
  const int t0 = t;
  for (int guard = 0; guard < 1000; ++guard) {
    const int g = m3d::other_face_at_edge(m, t, f, x, y);
    if (g < 0) return -2;
    if (visit(t, g)) return 1;
    const int nb = m.tn[4 * t + g];
    if (nb < 0) return -1;
    t = nb >> 2;
    f = nb & 3;
    if (t == t0) return 0;
  }
  return -2;
}

// Does the cavity of point j hold every tetrahedron around edge ab of t? Bowyer-Watson then
// removes the edge.
GDR_HD_INLINE bool ring_in_cavity(const TetView& m, int t, int a, int b, int j) {
  int f = 0;  // a face of t that holds ab: opposite a corner other than a and b
  while (m.tv[4 * t + f] == a || m.tv[4 * t + f] == b) ++f;
  auto not_mine = [&](int u, int) { return !((m.tflag[u] & m3d::kInCavity) && m.mark[u] == j + 1); };
  return turn_around_edge(m, t, f, a, b, not_mine) == 0;  // all the way round, every one mine
}

// Sharp features stay: a point whose cavity would take a feature subsegment away (every
// tetrahedron around it; the one a point on a feature splits aside) is not inserted, and the
// subsegment is split instead. GrowCavity already refuses free points strictly inside a
// subsegment's diametral ball (Ruppert); this catches points on its sphere and points on a
// feature next to another one at a small angle (its subsegment is blocked). A subsegment
// that may not be split makes the free point that wanted it gone give up what asked for it:
// the two tetrahedra of the facet, or the bad cell, are protected, and reported as
// exceptions. Runs on the winning cavities
// (and on the free points GrowCavity refused for encroachment), before the winners are
// numbered.
struct KeepFeatures {
  TetView m;
  Criteria c;
  const Candidate* cand;
  const m3d::CavityTuple* tuples;
  int* failed;
  GDR_HD void operator()(long long i) const {
    const m3d::CavityTuple& h = tuples[i];
    if (m3d::is_sub_tuple(h) || m3d::result_of(h) != m3d::kCavity) return;
    const int t = h.elem, flags = m.tflag[t];
    if (!(flags & m3d::kSegBits)) return;
    const Candidate& p = cand[h.pt];
    const int why = failed[h.pt];
    for (int e = 0; e < 6; ++e) {
      if (!(flags & (m3d::kSeg0 << e))) continue;
      const int a = m.tv[4 * t + m3d::edge_corner(e, 0)], b = m.tv[4 * t + m3d::edge_corner(e, 1)];
      if (p.kind == m3d::kSegmentSplit && ((a == p.a && b == p.b) || (a == p.b && b == p.a))) continue;
      const bool can_split = splittable(m, c, a, b);
      if (why == 0 && ring_in_cavity(m, t, a, b, h.pt)) {
        failed[h.pt] = m3d::kFailEncroach;
        if (p.kind == m3d::kSegmentSplit) block(m, p.a, p.b);
        else if (can_split) exec::atomic_or(&m.tflag[t], m3d::kSplitEdge0 << e);
        else give_up(p);
      } else if (why == m3d::kFailEncroach && !can_split &&
                 pred::in_diametral_sphere(pt(m, a), pt(m, b), p.p) > 0) {
        give_up(p);
      }
    }
  }
  GDR_HD void give_up(const Candidate& p) const {
    if (p.kind != m3d::kFreeSplit) return;
    if (p.a == kSurfacePoint) {  // b: the facet, 4t + f
      m3d::protect_tet(m.tflag, p.b >> 2);
      const int nb = m.tn[p.b];
      if (nb >= 0) m3d::protect_tet(m.tflag, nb >> 2);
    } else if (p.origin >= 0) {
      m3d::protect_tet(m.tflag, p.origin);
    }
  }
};

// Cell criteria, for tetrahedra inside the surface: radius-edge ratio above
// CellRadiusEdgeRatio, circumradius above CellSize.
enum : int { kCellGood = 0, kCellShape = 1, kCellSize = 2 };
GDR_HD_INLINE int cell_class(const Criteria& c, const TetSize& s) {
  if (c.cell_size2 > 0 && s.r2 > c.cell_size2) return kCellSize;
  if (c.radius_edge2 > 0 && s.r2 > c.radius_edge2 * s.lmin2) return kCellShape;
  return kCellGood;
}

GDR_HD_INLINE int classify_cell(const TetView& m, const Criteria& c, int t, const TetSize& s) {
  if (!c.volume || !(m.tflag[t] & kInterior)) return kCellGood;
  return cell_class(c, s);
}

// The sliver pass after refinement (mesh3d/smooth.h) works on the tetrahedra inside the
// surface, and moves a free (interior Steiner) point only when every tetrahedron around it is
// inside the surface. Surface points stay, so the restricted facets (flags of the faces, kept
// as they are) keep their corners; their measures are those of the triangulation before the
// pass (MeshResult::xyz_refined: a moved point moves the circumcentres at the ends of the
// duals next to it), so the restricted surface stays exactly as it was. The tetrahedra keep
// their flags: a star tiles the same polyhedron, so the tetrahedra inside fill the same
// volume. Every cell that met the cell criteria still meets them (MeetsCellCriteria).
struct InteriorCells {
  static constexpr bool kEverywhere = false;
  GDR_HD bool counts(const TetView& m, int t) const { return (m.tflag[t] & kInterior) != 0; }
  GDR_HD bool in_star(const TetView& m, int t) const { return (m.tflag[t] & kInterior) != 0; }
};

struct MeetsCellCriteria {
  Criteria c;
  GDR_HD bool operator()(const TetView& m, int t, const double* const p[4]) const {
    return classify_cell(m, c, t, tet_size_of(p)) == kCellGood;
  }
};

// ---------------------------------------------------------------------------------------
// Reclassification of new tetrahedra (those flagged kFresh by insertion): whether each face
// is restricted and whether it fails a facet criterion, set on both of its sides (neither
// changes while the two tetrahedra live: the collect phase only reads the bits), and whether
// the tetrahedron lies inside the surface. A face between two new tetrahedra is decided by
// the lesser one. ClearFresh runs after, so that every thread sees the same fresh flags.
struct ClassifyFresh {
  TetView m;
  AabbView s;
  Criteria c;
  GDR_HD void operator()(long long i) const {
    const int t = static_cast<int>(i);
    const int flags = m.tflag[t];
    if ((flags & m3d::kDead) || !(flags & m3d::kFresh)) return;
    double o[3];  // the circumcentre, once for the four duals and the inside test
    const bool centred = tet_center(m, t, o);
    // Inside or not, from a neighbour that is not new (its flag is known) and the parity of
    // the crossings of the dual between the two circumcentres: exact, and a short segment
    // where the ray of inside_surface crosses the whole surface's box; the ray decides when
    // the dual touches the surface degenerately or there is no such neighbour.
    int known = -1;  // the neighbour
    SegmentContacts contacts;
    for (int f = 0; f < 4; ++f) {
      const int nb = m.tn[4 * t + f];
      const int u = nb >> 2;
      if (nb >= 0 && (m.tflag[u] & m3d::kFresh) && u < t) continue;
      double x[3];
      int tri;
      const bool from_known = c.inside && known < 0 && nb >= 0 && !(m.tflag[u] & m3d::kFresh);
      bool dual = false;
      SegmentContacts open_contacts;  // an open input's: the crossings of this face's dual
      bool r = centred && surface_centre_from(m, s, c, t, f, o, x, &tri,
                                              from_known ? &contacts : (c.inside ? nullptr : &open_contacts),
                                              from_known ? &dual : nullptr);
      if (dual) known = u;
      // Open input: a dual that crosses the surface an even number of times joins two points on
      // one side of it (near a crease of a rough scan, or a fold), and its face separates
      // nothing: not restricted, as same_side leaves such faces out of a closed input's surface.
      // On a scan-like open surface they made a third of the surface non-manifold.
      if (r && !c.inside && !open_contacts.touch && (open_contacts.crossings & 1) == 0) r = false;
      const bool bad = r && facet_is_bad(m, c, t, f, x);
      set_bit(t, kRestricted0 << f, r);
      set_bit(t, kBadFacet0 << f, bad);
      if (nb >= 0) {
        set_bit(u, kRestricted0 << (nb & 3), r);
        set_bit(u, kBadFacet0 << (nb & 3), bad);
      }
    }
    const bool inside =
        c.inside && centred &&
        (known >= 0 && !contacts.touch ? ((m.tflag[known] & kInterior) != 0) != ((contacts.crossings & 1) != 0)
                                       : inside_surface(s, o, c.reach));
    set_bit(t, kInterior, inside);
    // Kept while the tetrahedron lives (its corners do not move during refinement): the
    // collect phase reads the bit instead of measuring every cell in every iteration.
    set_bit(t, kBadCell, c.volume && inside && cell_class(c, tet_size(m, t)) != kCellGood);
  }
  GDR_HD void set_bit(int t, int bit, bool on) const {
    if (on) exec::atomic_or(&m.tflag[t], bit);
    else exec::atomic_and(&m.tflag[t], ~bit);
  }
};

// With `stamp`: the corners of the new tetrahedra get `epoch`, the manifold check that is
// to look at them next (MarkNonManifold).
struct ClearFresh {
  TetView m;
  int* stamp = nullptr;
  int epoch = 0;
  GDR_HD void operator()(long long i) const {
    if (!(m.tflag[i] & m3d::kFresh)) return;
    m.tflag[i] &= ~m3d::kFresh;
    if (stamp)
      for (int q = 0; q < 4; ++q) stamp[m.tv[4 * i + q]] = epoch;
  }
};

// ---------------------------------------------------------------------------------------
// Collect (S4: one list): feature subsegments to split, bad restricted facets and bad
// tetrahedra inside the surface, as 16t + slot (slot f < 4: face f; slot 4: the tetrahedron;
// slot 5 + e: edge e). The count per tetrahedron goes to aux, which the engine scans in place
// into list offsets. Facets and cells are read off the bits ClassifyFresh keeps; a protected
// tetrahedron lists no facet and no cell (exceptions).
enum : int { kSlotCell = 4, kSlotEdge0 = 5, kSlots = 11 };

GDR_HD_INLINE int collect_mask(const TetView& m, const Criteria& c, int t) {
  const int flags = m.tflag[t];
  if (flags & m3d::kDead) return 0;
  int mask = 0;
  for (int e = 0; e < 6; ++e)
    if ((flags & (m3d::kSplitEdge0 << e)) && (flags & (m3d::kSeg0 << e)) &&
        splittable(m, c, m.tv[4 * t + m3d::edge_corner(e, 0)], m.tv[4 * t + m3d::edge_corner(e, 1)]))
      mask |= 1 << (kSlotEdge0 + e);
  if (flags & m3d::kProtected) return mask;
  for (int f = 0; f < 4; ++f) {
    if (!(flags & (kRestricted0 << f))) continue;
    if (flags & (m3d::kSplitFace0 << f)) {  // a cell's circumcentre encroached it
      mask |= 1 << f;
      continue;
    }
    if ((flags & (kBadFacet0 << f)) && owns_face(m, t, f)) mask |= 1 << f;
  }
  if (c.volume && (flags & kBadCell)) mask |= 1 << kSlotCell;
  return mask;
}

// A collect mask's entries: their number, and the entries themselves (16 t + slot) from `out`.
GDR_HD_INLINE int mask_entries(int mask) {
  int n = 0;
  for (int k = 0; k < kSlots; ++k) n += (mask >> k) & 1;
  return n;
}
GDR_HD_INLINE void list_entries(int mask, int t, int* out) {
  for (int k = 0; k < kSlots; ++k)
    if (mask & (1 << k)) *out++ = 16 * t + k;
}

struct CountBad {
  TetView m;
  Criteria c;
  GDR_HD void operator()(long long i) const { m.aux[i] = mask_entries(collect_mask(m, c, static_cast<int>(i))); }
};

struct ListBad {
  TetView m;
  Criteria c;
  int* list;
  int total;  // entries in the list
  GDR_HD void operator()(long long i) const {
    const int t = static_cast<int>(i);
    const int next = t + 1 < m.ntet ? m.aux[t + 1] : total;
    if (next == m.aux[t]) return;  // nothing listed here (the scan did not step)
    list_entries(collect_mask(m, c, t), t, list + m.aux[t]);
  }
};

// ---------------------------------------------------------------------------------------
// Splitting points (Algorithm 5): the point of a feature subsegment that gQM3d splits it at,
// the surface centre of a bad facet, the circumcentre of a bad tetrahedron; located by
// walking from the element. Priorities: feature subsegments first (qm3d's segment class,
// larger first), then facets (larger surface balls first), then tetrahedra too big (larger
// first), then tetrahedra bad by shape (worst radius-edge ratio first); a pseudo-random id
// inside a size class. A facet's point keeps its face (b = 4t + f) and a cell's point its
// tetrahedron (origin), for KeepFeatures to give up.
enum : unsigned { kClassShape = 0, kClassCellSize = 1, kClassFacet = 2 };
static_assert(unsigned(qm3d::kClassSegment) > unsigned(kClassFacet), "feature subsegments are split first");

using exec::shuffle_id;
using exec::size_class;

struct ComputeSplittingPoints {
  TetView m;
  AabbView s;
  Criteria c;
  const int* list;
  Candidate* out;
  unsigned salt;
  u64 keep_below;  // ids at or above this do not compete this iteration
  bool shuffle;    // random order within each class (after an iteration without headway)
  GDR_HD void operator()(long long j) const {
    Candidate& cand = out[j];
    cand.kind = m3d::kDropped;
    const unsigned id = shuffle_id(static_cast<unsigned>(j), salt);
    if (id >= keep_below) return;
    const int e = list[j];
    const int t = e >> 4, slot = e & 15;
    if (slot >= kSlotEdge0) {
      qm3d::make_segment_candidate(m, t, slot - kSlotEdge0, id, cand);
      cand.ek = m3d::kDelaunayPoint;  // no constraints: only a star-shaped cavity is needed
      if (shuffle && cand.kind >= 0) cand.prio = exec::make_priority(unsigned(cand.prio >> 62), 0.0f, id);
      return;
    }
    double p[3];
    u64 prio;
    bool surface = false;
    if (slot < kSlotCell) {
      int tri;
      if (!surface_centre(m, s, c, t, slot, p, &tri)) return;
      const double r2 = m3d::dist2(p, pt(m, m.tv[4 * t + m3d::face_corner(slot, 0)]));
      prio = exec::make_priority(kClassFacet, size_class(r2), id);
      surface = true;
    } else {
      const TetSize sz = tet_size(m, t);
      if (!sz.ok) return;
      for (int k = 0; k < 3; ++k) p[k] = sz.center[k];
      prio = classify_cell(m, c, t, sz) == kCellSize
                 ? exec::make_priority(kClassCellSize, size_class(sz.r2), id)
                 : exec::make_priority(kClassShape, static_cast<float>(fmin(sz.r2 / sz.lmin2, 1e38)), id);
    }
    const int start = m3d::locate_point(m, t, p, c.step_limit);
    if (start < 0 || m3d::is_corner_point(m, start, p)) return;
    for (int k = 0; k < 3; ++k) cand.p[k] = p[k];
    cand.prio = shuffle ? exec::make_priority(unsigned(prio >> 62), 0.0f, id) : prio;
    cand.start = start;
    cand.sub = -1;
    cand.a = surface ? kSurfacePoint : -1;
    cand.b = surface ? 4 * t + slot : -1;
    cand.origin = surface ? -1 : t;
    cand.kind = m3d::kFreeSplit;
    cand.ek = m3d::kDelaunayPoint;
  }
};

// ---------------------------------------------------------------------------------------
// The manifold criterion. The surface is the output's: restricted facets that separate the
// inside from the outside (same_side). An edge of it must have two facets (one on an open
// input's boundary), and the facets at a vertex must form one cycle (one fan on the
// boundary). Both are read off the triangulation by turning around edges, without lists.

GDR_HD_INLINE bool surface_facet(const TetView& m, const Criteria& c, int t, int f) {
  return (m.tflag[t] & (kRestricted0 << f)) && !same_side(m, c, t, f);
}

// The face as its owner lists it (4t + f), the same from either side.
GDR_HD_INLINE int face_id(const TetView& m, int t, int f) {
  return owns_face(m, t, f) ? 4 * t + f : m.tn[4 * t + f];
}

// Surface facets at edge xy of surface facet f of t (f included); -1 on a broken ring.
GDR_HD_INLINE int facets_at_edge(const TetView& m, const Criteria& c, int t, int f, int x, int y) {
  int n = 0;
  auto count = [&](int u, int g) {
    n += surface_facet(m, c, u, g);
    return false;
  };
  const int r = turn_around_edge(m, t, f, x, y, count);
  if (r == 0) return n;
  if (r != -1) return -1;
  n += 1;  // f itself, which the walk to the hull did not reach
  const int nb = m.tn[4 * t + f];
  if (nb >= 0 && turn_around_edge(m, nb >> 2, nb & 3, x, y, count) != -1) return -1;
  return n;
}

// The next surface facet round edge xy from surface facet f of t, as (tetrahedron, face);
// false if there is none but f.
GDR_HD_INLINE bool next_facet_at_edge(const TetView& m, const Criteria& c, int t, int f, int x, int y, int* u,
                                      int* g) {
  auto found = [&](int w, int k) {
    if (!surface_facet(m, c, w, k)) return false;
    *u = w;
    *g = k;
    return true;
  };
  const int self = face_id(m, t, f);
  int r = turn_around_edge(m, t, f, x, y, found);
  if (r == -1) {
    const int nb = m.tn[4 * t + f];
    r = nb >= 0 ? turn_around_edge(m, nb >> 2, nb & 3, x, y, found) : -1;
  }
  return r == 1 && face_id(m, *u, *g) != self;
}

GDR_HD_INLINE int third_corner(const TetView& m, int t, int f, int x, int y) {
  for (int q = 0; q < 3; ++q) {
    const int v = m.tv[4 * t + m3d::face_corner(f, q)];
    if (v != x && v != y) return v;
  }
  return -1;
}

// Surface facets reached from surface facet f of t by turning round its corner v across
// edges; -1 if the walk breaks or runs past `limit`.
GDR_HD_INLINE int umbrella_at(const TetView& m, const Criteria& c, int t, int f, int v, int limit) {
  const int start = face_id(m, t, f);
  int ends[2] = {-1, -1};
  for (int q = 0, k = 0; q < 3; ++q) {
    const int w = m.tv[4 * t + m3d::face_corner(f, q)];
    if (w != v) ends[k++] = w;
  }
  int n = 1;
  for (int dir = 0; dir < 2; ++dir) {
    int u = t, g = f, x = ends[dir];
    for (;;) {
      int nu, ng;
      if (!next_facet_at_edge(m, c, u, g, v, x, &nu, &ng)) break;  // a boundary edge: the other way
      if (face_id(m, nu, ng) == start) return n;                    // all the way round
      if (++n > limit) return -1;
      x = third_corner(m, nu, ng, v, x);
      u = nu;
      g = ng;
    }
  }
  return n;
}

// Surface facets per vertex (deg, zeroed before).
struct CountSurfaceFacets {
  TetView m;
  Criteria c;
  int* deg;
  GDR_HD void operator()(long long i) const {
    const int t = static_cast<int>(i);
    if (m.tflag[t] & m3d::kDead) return;
    for (int f = 0; f < 4; ++f)
      if (owns_face(m, t, f) && surface_facet(m, c, t, f))
        for (int q = 0; q < 3; ++q) exec::atomic_add(&deg[m.tv[4 * t + m3d::face_corner(f, q)]], 1);
  }
};

// A surface facet at a non-manifold edge or vertex is split (kSplitFace0 on its owner), unless
// its tetrahedra are protected or it is below manifold_min. counts[0]: facets at such places,
// counts[1]: of those, marked for splitting. With `stamp` (a round of the criterion), only
// facets with a corner stamped `epoch` or later are looked at: the facets at an edge or round
// a vertex change only where new tetrahedra have it as a corner (ClearFresh stamps those), and
// the facets found at fault now are looked at again next time (epoch + 1). Without it, every
// facet (the count at the end).
struct MarkNonManifold {
  TetView m;
  Criteria c;
  const int* deg;
  int* counts;
  bool mark;  // false: count only
  int* stamp = nullptr;
  int epoch = 0;
  GDR_HD void operator()(long long i) const {
    const int t = static_cast<int>(i);
    if (m.tflag[t] & m3d::kDead) return;
    for (int f = 0; f < 4; ++f) {
      if (!owns_face(m, t, f) || !surface_facet(m, c, t, f)) continue;
      int v[3];
      for (int q = 0; q < 3; ++q) v[q] = m.tv[4 * t + m3d::face_corner(f, q)];
      if (stamp && stamp[v[0]] < epoch && stamp[v[1]] < epoch && stamp[v[2]] < epoch) continue;
      bool bad = false;
      for (int q = 0; q < 3 && !bad; ++q) {
        const int a = v[q], b = v[(q + 1) % 3];
        const int n = facets_at_edge(m, c, t, f, a, b);
        bad = n > 2 || (n == 1 && c.manifold == kManifold);
      }
      for (int q = 0; q < 3 && !bad; ++q) {
        const int n = umbrella_at(m, c, t, f, v[q], deg[v[q]]);
        bad = n >= 0 && n != deg[v[q]];
      }
      if (!bad) continue;
      exec::atomic_add(&counts[0], 1);
      if (stamp)
        for (int q = 0; q < 3; ++q) stamp[v[q]] = epoch + 1;
      double longest2 = 0;
      for (int q = 0; q < 3; ++q) longest2 = fmax(longest2, m3d::dist2(pt(m, v[q]), pt(m, v[(q + 1) % 3])));
      const int nb = m.tn[4 * t + f];
      if (!mark || (m.tflag[t] & m3d::kProtected) || (nb >= 0 && (m.tflag[nb >> 2] & m3d::kProtected)) ||
          longest2 < c.manifold_min2)
        continue;
      exec::atomic_or(&m.tflag[t], m3d::kSplitFace0 << f);
      exec::atomic_add(&counts[1], 1);
    }
  }
};

// Sharp features the surface does not follow: feature subsegments that no surface facet
// holds (next to an acute crease sampled unevenly on its two sides, a Voronoi edge cuts both
// sheets off the subsegment and no facet there bounds the volume; CGAL Mesh_3 avoids it with
// protecting balls). Counted once each, from the lowest-numbered tetrahedron around it.
struct CountLostFeatures {
  TetView m;
  Criteria c;
  int* count;
  GDR_HD void operator()(long long i) const {
    const int t = static_cast<int>(i), flags = m.tflag[t];
    if ((flags & m3d::kDead) || !(flags & m3d::kSegBits)) return;
    for (int e = 0; e < 6; ++e) {
      if (!(flags & (m3d::kSeg0 << e))) continue;
      const int a = m.tv[4 * t + m3d::edge_corner(e, 0)], b = m.tv[4 * t + m3d::edge_corner(e, 1)];
      int f = 0;  // a face of t that holds ab
      while (m.tv[4 * t + f] == a || m.tv[4 * t + f] == b) ++f;
      int facets = 0, lowest = t;
      auto visit = [&](int u, int g) {
        facets += surface_facet(m, c, u, g);
        lowest = u < lowest ? u : lowest;
        return false;
      };
      if (turn_around_edge(m, t, f, a, b, visit) == 0 && lowest == t && facets == 0) exec::atomic_add(count, 1);
    }
  }
};

}  // namespace gdr::rdt3d
