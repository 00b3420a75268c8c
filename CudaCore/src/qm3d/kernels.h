// The per-element work of gQM3d that is its own (criteria, collecting the elements to split,
// their splitting points and where they lie), as host+device functors. Cavities and
// insertion are mesh3d's (cavity.h).
#pragma once
#include <cmath>

#include "exec/hd.h"
#include "exec/priority.h"
#include "mesh3d/cavity.h"

namespace gdr::qm3d {

using exec::u64;
using m3d::Candidate;
using m3d::TetView;
using m3d::pt;

// Quality criteria, in forms without square roots or trigonometry.
struct Criteria {
  double max_radius_edge2 = 0;  // B^2; 0 = off
  double max_volume6 = 0;       // 6 x the volume bound; 0 = off
  double cos_min_dihedral = 0;  // cos of the dihedral bound; used when dihedral is on
  int dihedral = 0;             // 1: a dihedral angle below the bound makes a tetrahedron bad
  // Set by the engine (Engine::compute_splitting_points): a tetrahedron bad by the dihedral
  // bound alone is split only if its squared circumradius is at least this times its squared
  // shortest edge.
  double sliver_split_ratio2 = 0;
  int step_limit = 4096;        // point-location walk bound (dropped beyond it)
  // Volume bounds of regions (by region attribute; TetGen's regional -a), kept by value so
  // that kernels on either backend read them without device buffers.
  static constexpr int kMaxRegionBounds = 32;
  int region_bounds = 0;
  int region_attribute[kMaxRegionBounds] = {};
  double region_volume6[kMaxRegionBounds] = {};
};

// Classification of a tetrahedron against the criteria.
enum : int { kGood = 0, kBad = 1, kTooBig = 2 };

struct TetShape {
  double r2 = 0;      // squared circumradius (inf when degenerate)
  double lmin2 = 0;   // squared shortest edge
  double volume6 = 0; // 6 x volume
  double center[3] = {0, 0, 0};
  bool ok = false;    // circumcentre computable
};

GDR_HD_INLINE TetShape tet_shape_of(const double* a, const double* b, const double* c, const double* d) {
  TetShape s;
  s.lmin2 = fmin(fmin(m3d::dist2(a, b), m3d::dist2(a, c)),
                 fmin(fmin(m3d::dist2(a, d), m3d::dist2(b, c)), fmin(m3d::dist2(b, d), m3d::dist2(c, d))));
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ad[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  double n[3];
  m3d::cross3(ac, ad, n);
  s.volume6 = fabs(m3d::dot3(ab, n));
  s.ok = m3d::tet_circumcenter(a, b, c, d, s.center);
  s.r2 = s.ok ? m3d::dist2(s.center, a) : INFINITY;
  return s;
}

GDR_HD_INLINE TetShape tet_shape(const TetView& m, int t) {
  const int* v = m.tv + 4 * t;
  return tet_shape_of(pt(m, v[0]), pt(m, v[1]), pt(m, v[2]), pt(m, v[3]));
}

// Is any dihedral angle of t smaller than the bound? The dihedral angle at an edge has
// cosine -n1.n2 / (|n1| |n2|) for the outward normals n1, n2 of the two faces there.
GDR_HD_INLINE bool small_dihedral_of(const double* const p[4], double cos_bound) {
  double n[4][3], len[4];
  for (int f = 0; f < 4; ++f) {
    const double* a = p[m3d::face_corner(f, 0)];
    const double* b = p[m3d::face_corner(f, 1)];
    const double* c = p[m3d::face_corner(f, 2)];
    const double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    m3d::cross3(u, w, n[f]);
    len[f] = sqrt(m3d::dot3(n[f], n[f]));
  }
  for (int e = 0; e < 6; ++e) {
    // The faces at edge e are those opposite its two other corners.
    int f[2], k = 0;
    for (int c = 0; c < 4; ++c)
      if (c != m3d::edge_corner(e, 0) && c != m3d::edge_corner(e, 1)) f[k++] = c;
    if (-m3d::dot3(n[f[0]], n[f[1]]) > cos_bound * len[f[0]] * len[f[1]]) return true;
  }
  return false;
}

// Tetrahedron t with its corners at p (its own, or where a vertex would move to).
GDR_HD_INLINE int classify_corners(const TetView& m, int t, const Criteria& c, const TetShape& s,
                                   const double* const p[4]) {
  double v6 = c.max_volume6;
  if (c.region_bounds && m.tregion)
    for (int k = 0; k < c.region_bounds; ++k)
      if (c.region_attribute[k] == m.tregion[t]) v6 = v6 > 0 ? fmin(v6, c.region_volume6[k]) : c.region_volume6[k];
  if (v6 > 0 && s.volume6 > v6) return kTooBig;
  if (c.max_radius_edge2 > 0 && s.r2 > c.max_radius_edge2 * s.lmin2) return kBad;
  if (c.dihedral && small_dihedral_of(p, c.cos_min_dihedral)) return kBad;
  return kGood;
}

GDR_HD_INLINE int classify_tet(const TetView& m, int t, const Criteria& c, const TetShape& s) {
  const int* v = m.tv + 4 * t;
  const double* p[4] = {pt(m, v[0]), pt(m, v[1]), pt(m, v[2]), pt(m, v[3])};
  return classify_corners(m, t, c, s, p);
}

// Sliver smoothing keeps every tetrahedron that meets the criteria meeting them
// (mesh3d/smooth.h).
struct MeetsCriteria {
  Criteria c;
  GDR_HD bool operator()(const TetView& m, int t, const double* const p[4]) const {
    return classify_corners(m, t, c, tet_shape_of(p[0], p[1], p[2], p[3]), p) == kGood;
  }
};

// ---------------------------------------------------------------------------------------
// Collect (Algorithm 3 line 4, S4): an 11-bit mask per tetrahedron: bit 0 the tetrahedron
// itself when bad, bits 1-4 the subface on face i when vertex i (the apex across it)
// encroaches it, bits 5-10 the subsegment on edge e when one of the two other vertices
// encroaches it. These never change while the tetrahedron lives: computed once when it is
// new (kFresh) and kept in its flags; subsegments and subfaces flagged for splitting by
// rejected points since are added each time. A subface or subsegment is listed from every
// tetrahedron that sees it encroached; the splitting points name one canonical tetrahedron so
// the S3 filter keeps one.
//
// Which encroachments count follows TetGen, so that meshes come out as small as its: in the
// initial CDT every subsegment and subface is checked against its apexes (`all`); later only
// the subsegments and subfaces a boundary split creates (those at the new point, corner 3 of
// its new tetrahedra), and any that a point to be inserted would encroach (rejection, in
// GrowCavity). An old subsegment that a new point merely comes near is not split for it:
// checking those too made every edge of a fine input surface split once (spot: 22k Steiner
// points on segments against TetGen's 4.9k).
enum : int { kSlotTet = 0, kSlotFace0 = 1, kSlotEdge0 = 5, kSlots = 11 };

GDR_HD_INLINE int static_collect_mask(const TetView& m, const Criteria& c, int t, bool all) {
  const TetShape s = tet_shape(m, t);
  int mask = classify_tet(m, t, c, s) != kGood ? 1 : 0;
  const int* v = m.tv + 4 * t;
  const int newest = m.ptype[v[3]];
  const bool boundary_split = newest == m3d::kSegmentPoint || newest == m3d::kFacetPoint;
  if (!all && !boundary_split) return mask;
  for (int f = 0; f < 4; ++f) {
    if (m.tsub[4 * t + f] < 0 || (!all && f == 3)) continue;
    if (m3d::in_diametral_ball(pt(m, v[m3d::face_corner(f, 0)]), pt(m, v[m3d::face_corner(f, 1)]),
                               pt(m, v[m3d::face_corner(f, 2)]), pt(m, v[f])))
      mask |= 1 << (kSlotFace0 + f);
  }
  const int flags = m.tflag[t];
  for (int e = 0; e < 6; ++e) {
    if (!(flags & (m3d::kSeg0 << e))) continue;
    const int ca = m3d::edge_corner(e, 0), cb = m3d::edge_corner(e, 1);
    if ((!all && cb != 3) || m3d::is_sharp_subseg(m, v[ca], v[cb])) continue;
    for (int k = 0; k < 4; ++k) {
      if (k == ca || k == cb) continue;
      if (pred::in_diametral_sphere(pt(m, v[ca]), pt(m, v[cb]), pt(m, v[k])) > 0) {
        mask |= 1 << (kSlotEdge0 + e);
        break;
      }
    }
  }
  return mask;
}

// The static mask, with the split requests since, less what is left as it is: protected
// tetrahedra and subfaces whose split was declined.
GDR_HD_INLINE int collect_mask(const TetView& m, int t) {
  const int flags = m.tflag[t];
  if (flags & m3d::kDead) return 0;
  const unsigned bits = static_cast<unsigned>(flags);  // kMakeRoom is the sign bit
  int mask = static_cast<int>(((bits & m3d::kCollectBits) >> m3d::kCollectShift) |
                              ((bits >> 15) & 15) << kSlotFace0 | ((bits >> 9) & 63) << kSlotEdge0);
  if (flags & m3d::kMakeRoom) mask |= 1 << kSlotTet;
  else if (flags & m3d::kProtected) mask &= ~(1 << kSlotTet);
  for (int f = 0; f < 4; ++f)
    if ((mask & (1 << (kSlotFace0 + f))) && (m.sflag[m.tsub[4 * t + f]] & m3d::kSubNoSplit))
      mask &= ~(1 << (kSlotFace0 + f));
  // Segments blocked since the requests (Engine::block_failing_segments) are not split.
  for (int e = 0; e < 6; ++e)
    if ((mask & (1 << (kSlotEdge0 + e))) &&
        m3d::is_sharp_subseg(m, m.tv[4 * t + m3d::edge_corner(e, 0)], m.tv[4 * t + m3d::edge_corner(e, 1)]))
      mask &= ~(1 << (kSlotEdge0 + e));
  return mask;
}

GDR_HD_INLINE int popcount11(int x) {
#ifdef __CUDA_ARCH__
  return __popc(x & ((1 << kSlots) - 1));
#else
  // Bit arithmetic: without -mpopcnt __builtin_popcount is a call into libgcc.
  unsigned v = static_cast<unsigned>(x) & ((1u << kSlots) - 1);
  v = v - ((v >> 1) & 0x55555555u);
  v = (v & 0x33333333u) + ((v >> 2) & 0x33333333u);
  return static_cast<int>((((v + (v >> 4)) & 0x0f0f0f0fu) * 0x01010101u) >> 24);
#endif
}

// The mask's entry count goes to aux, which the engine scans in place into list offsets.
struct CollectMask {
  TetView m;
  Criteria c;
  bool all;  // the first collect: every subsegment and subface is checked
  GDR_HD void operator()(long long i) const {
    const int t = static_cast<int>(i);
    int f = m.tflag[t];
    if ((f & m3d::kFresh) && !(f & m3d::kDead)) {
      f = (f & ~(m3d::kFresh | m3d::kCollectBits)) | (static_collect_mask(m, c, t, all) << m3d::kCollectShift);
      m.tflag[t] = f;
    }
    m.aux[t] = popcount11(collect_mask(m, t));
  }
};

// Expands the masks into the element list (t*16 + slot) at the scanned offsets (a
// tetrahedron with no entries, most of them, is passed over on its offsets alone).
struct ExpandElements {
  TetView m;
  int* list;
  int total;  // the list's length
  GDR_HD void operator()(long long i) const {
    const int t = static_cast<int>(i);
    int o = m.aux[t];
    if ((t + 1 < m.ntet ? m.aux[t + 1] : total) == o) return;
    const int mask = collect_mask(m, t);
    for (int k = 0; k < kSlots; ++k)
      if (mask & (1 << k)) list[o++] = 16 * t + k;
  }
};

// ---------------------------------------------------------------------------------------
// Splitting points and their priorities (Algorithm 3 lines 6-7). Lower dimensions first
// (termination): subsegments, then subfaces, then tetrahedra; within subsegments and
// subfaces larger first, by factor-of-two size classes (a pseudo-random order inside a
// class, as in 2D, so graded neighbourhoods do not chain); tetrahedra too big for the volume
// bound larger first, then those bad by shape alone worst first by radius-edge ratio.
enum : unsigned { kClassShape = 0, kClassTooBig = 1, kClassSubface = 2, kClassSegment = 3 };

using exec::shuffle_id;
using exec::size_class;

// The least tetrahedron around edge xy of t (so that every tetrahedron reporting a
// subsegment names the same one).
GDR_HD_INLINE int least_tet_around_edge(const TetView& m, int t, int x, int y) {
  int best = t;
  const int cx = m3d::corner_of(m, t, x), cy = m3d::corner_of(m, t, y);
  int faces[2], nf = 0;
  for (int f = 0; f < 4; ++f)
    if (f != cx && f != cy) faces[nf++] = f;
  for (int dir = 0; dir < 2; ++dir) {
    int u = t, g = faces[dir];
    for (int guard = 0; guard < 1000; ++guard) {
      const int nb = m.tn[4 * u + g];
      if (nb < 0) break;
      u = nb >> 2;
      if (u == t) return best;  // all the way round
      if (u < best) best = u;
      g = m3d::other_face_at_edge(m, u, nb & 3, x, y);
    }
  }
  return best;
}

GDR_HD_INLINE void make_segment_candidate(const TetView& m, int t, int e, unsigned id,
                                          Candidate& out) {
  const int a = m.tv[4 * t + m3d::edge_corner(e, 0)], b = m.tv[4 * t + m3d::edge_corner(e, 1)];
  m3d::segment_split_point(m, a, b, out.p);
  const int start = least_tet_around_edge(m, t, a, b);
  out.start = start;
  out.ek = static_cast<signed char>(m3d::edge_index(m3d::corner_of(m, start, a), m3d::corner_of(m, start, b)));
  out.a = a;
  out.b = b;
  out.sub = -1;
  out.origin = -1;
  out.kind = m3d::kSegmentSplit;
  out.prio = exec::make_priority(kClassSegment, size_class(m3d::dist2(pt(m, a), pt(m, b))), id);
  // A split point that rounds onto an endpoint would duplicate it: leave that subsegment.
  const double* pa = pt(m, a);
  const double* pb = pt(m, b);
  if ((out.p[0] == pa[0] && out.p[1] == pa[1] && out.p[2] == pa[2]) ||
      (out.p[0] == pb[0] && out.p[1] == pb[1] && out.p[2] == pb[2]))
    out.kind = m3d::kDropped;
}

// Splitting point of subface s: its circumcentre, located by walking in its facet. A walk
// that must cross a subsegment splits that subsegment instead when the circumcentre
// encroaches it; otherwise the circumcentre lies outside the facet and the subface is left
// as it is (kSubNoSplit), as TetGen does, and so is the bad tetrahedron `origin` (if any)
// that asked for it.
GDR_HD_INLINE void make_subface_candidate(const TetView& m, int s, unsigned id, int step_limit,
                                          int origin, Candidate& out) {
  out.kind = m3d::kDropped;
  const int* sv = m.sv + 3 * s;
  double p[3];
  if (!m3d::tri_circumcenter(pt(m, sv[0]), pt(m, sv[1]), pt(m, sv[2]), p)) return;
  const bool bends = m3d::facet_bends(m, m.sfacet[s]);
  if (m.fplane && !bends) {
    // The circumcentre of a needle subface can lie far off its plane in rounded arithmetic;
    // put it back on the facet's plane, spanned by input points.
    const int* f = m.fplane + 3 * m.sfacet[s];
    m3d::project_on_plane(pt(m, f[0]), pt(m, f[1]), pt(m, f[2]), p);
  }
  const double r2 = m3d::dist2(p, pt(m, sv[0]));
  // The walk decides sides in one projection of the facet (the coordinate plane its normal is
  // most nearly perpendicular to, fixed for the whole walk), with exact orient2d: the two
  // subfaces at an edge then always agree on which side p lies. (Planes through each
  // subface's own tetrahedron apex did not: with p a rounding off the facet, both could call
  // it beyond their shared edge, and the walk went to and fro up to its step bound.)
  const int drop = m3d::subface_normal_axis(m, s);
  const int ax = drop == 0 ? 1 : 0, ay = drop == 2 ? 1 : 2;
  const double pp[2] = {p[ax], p[ay]};
  int u = s;
  for (int step = 0; step < step_limit; ++step) {
    const int tf = m.st[2 * u] >= 0 ? m.st[2 * u] : m.st[2 * u + 1];
    const int t = tf >> 2;
    const int* v = m.sv + 3 * u;
    int exit = -1;
    for (int e0 = 0; e0 < 3 && exit < 0; ++e0) {
      const int e = (e0 + step) % 3;  // rotate the first edge tried: no cycling
      const double* x = pt(m, v[(e + 1) % 3]);
      const double* y = pt(m, v[(e + 2) % 3]);
      const double* z = pt(m, v[e]);
      const double x2[2] = {x[ax], x[ay]}, y2[2] = {y[ax], y[ay]}, z2[2] = {z[ax], z[ay]};
      const double side_p = pred::orient2d(x2, y2, pp);
      const double side_z = pred::orient2d(x2, y2, z2);
      if (side_p != 0 && (side_p > 0) != (side_z > 0)) exit = e;
    }
    if (exit < 0) {
      // Left as it is (TetGen): a circumcentre in the protecting ball of a corner, or one
      // that lands in a subface that is left as it is.
      bool refuse = (m.sflag[u] & m3d::kSubNoSplit) != 0;
      for (int k = 0; k < 3; ++k) refuse = refuse || m3d::in_protecting_ball(m, sv[k], p);
      if (refuse) {
        exec::atomic_or(&m.sflag[s], m3d::kSubNoSplit);
        if (origin >= 0) m3d::protect_tet(m.tflag, origin);
        return;
      }
      if (bends) {
        // A merged facet bends: the point goes on the plane of the subface it lies in,
        // moved along the walk's projection axis so that it stays inside that subface.
        const double* a = pt(m, v[0]);
        double u1[3], u2[3], n[3];
        for (int k = 0; k < 3; ++k) {
          u1[k] = pt(m, v[1])[k] - a[k];
          u2[k] = pt(m, v[2])[k] - a[k];
        }
        m3d::cross3(u1, u2, n);
        if (n[drop] == 0) return;
        p[drop] = a[drop] - (n[ax] * (p[ax] - a[ax]) + n[ay] * (p[ay] - a[ay])) / n[drop];
      }
      for (int k = 0; k < 3; ++k) out.p[k] = p[k];
      out.kind = m3d::kFacetSplit;
      out.sub = u;
      const int t2 = m.st[2 * u + 1] >= 0 ? m.st[2 * u + 1] >> 2 : t;
      out.start = t2 < t ? t2 : t;  // canonical: the lesser tetrahedron beside it
      out.ek = -1;
      out.a = out.b = -1;
      out.origin = origin;
      out.prio = exec::make_priority(kClassSubface, size_class(r2), id);
      return;
    }
    const int x = v[(exit + 1) % 3], y = v[(exit + 2) % 3];
    if (m3d::is_subseg(m, t, x, y)) {
      if (pred::in_diametral_sphere(pt(m, x), pt(m, y), p) > 0 && !m3d::is_sharp_subseg(m, x, y)) {
        const int e = m3d::edge_index(m3d::corner_of(m, t, x), m3d::corner_of(m, t, y));
        exec::atomic_or(&m.tflag[t], m3d::kSplitEdge0 << e);
        make_segment_candidate(m, t, e, id, out);
      } else {
        exec::atomic_or(&m.sflag[s], m3d::kSubNoSplit);
        if (origin >= 0) m3d::protect_tet(m.tflag, origin);
      }
      return;
    }
    u = m3d::subface_across(m, u, x, y);
    if (u < 0) return;
  }
}

// Sleeping elements (engine.h, Engine::sleep_failed): per tetrahedron, bit slot for each
// listed element whose last point failed for a reason of its own, bit kSlots + e for a
// subsegment (edge e) whose failure counts towards blocking it, and kSleptRoom when a
// tetrahedron's point was made while it asked for room. An element sleeps while its
// tetrahedron's request for room is what it was.
enum : int { kSleptRoom = 1 << (kSlots + 6) };

// The bit of a sleeping subsegment (slot >= kSlotEdge0) whose failure counts (blocking).
GDR_HD_INLINE int sleep_counts_bit(int slot) { return 1 << (kSlots + slot - kSlotEdge0); }

// Every bit an element of this slot owns in the sleep word.
GDR_HD_INLINE int sleep_bits(int slot) {
  return 1 << slot | (slot >= kSlotEdge0 ? sleep_counts_bit(slot) : 0) | (slot == kSlotTet ? kSleptRoom : 0);
}

GDR_HD_INLINE bool asleep(const TetView& m, const int* sleep, int e) {
  const int t = e >> 4, slot = e & 15, w = sleep[t];
  if (!(w & (1 << slot))) return false;
  return slot != kSlotTet || ((m.tflag[t] & m3d::kMakeRoom) != 0) == ((w & kSleptRoom) != 0);
}

struct ComputeSplittingPoints {
  TetView m;
  Criteria c;
  const int* list;
  Candidate* out;
  unsigned salt;     // changes every iteration
  bool worst_first;  // shape-bad tetrahedra by radius-edge ratio; false: all larger first
  bool shuffle;      // random order within each class, after an iteration without headway
  u64 keep_below;    // ids at or above this do not compete this iteration (engine.h filter)
  // Per input segment, its splits that found no valid fan (engine.h); null: none yet. A
  // segment that failed twice ranks last among segments, so that what it waits for (a
  // subsegment it encroaches, CheckCavity) is split before it tries again.
  const int* segment_failures;
  // Room is made at a tetrahedron's centroid where no subface split can make it (below);
  // only once no point has gone in for two iterations: on a scan (penguin, B = 2) it gave 5%
  // more tetrahedra and 40% more bad ones.
  bool centroid_room = false;
  const int* sleep = nullptr;  // per tetrahedron, its sleeping elements (engine.h); null: none
  GDR_HD void operator()(long long j) const {
    const int e = list[j];
    out[j].elem = e;
    out[j].room = (m.tflag[e >> 4] & m3d::kMakeRoom) != 0;
    if (shuffle_id(static_cast<unsigned>(j), salt) >= keep_below) {
      out[j].kind = m3d::kDropped;
      return;
    }
    if (sleep && asleep(m, sleep, e)) {
      // It would fail as before; a subsegment's split still counts as failing (blocking).
      out[j].kind = m3d::kDropped;
      if ((e & 15) >= kSlotEdge0 && (sleep[e >> 4] & sleep_counts_bit(e & 15))) {
        make_segment_candidate(m, e >> 4, (e & 15) - kSlotEdge0, 0, out[j]);
        if (out[j].kind == m3d::kSegmentSplit) out[j].kind = m3d::kSleeping;
      }
      return;
    }
    compute(j);
    const u64 p = out[j].prio;
    if (shuffle) out[j].prio = exec::make_priority(unsigned(p >> 62), 0.0f, exec::priority_id(p));
  }
  GDR_HD void compute(long long j) const {
    const int e = list[j];
    const int t = e >> 4, slot = e & 15;
    Candidate& cand = out[j];
    const unsigned id = shuffle_id(static_cast<unsigned>(j), salt);
    if (slot >= kSlotEdge0) {
      make_segment_candidate(m, t, slot - kSlotEdge0, id, cand);
      if (segment_failures && cand.kind == m3d::kSegmentSplit) {
        const int g = m3d::segment_of(m, cand.a, cand.b);
        if (g >= 0 && segment_failures[g] >= 2) cand.prio = exec::make_priority(kClassSegment, 0.0f, id);
      }
      return;
    }
    if (slot >= kSlotFace0) {
      make_subface_candidate(m, m.tsub[4 * t + slot - kSlotFace0], id, c.step_limit, -1, cand);
      return;
    }
    // A bad tetrahedron: its circumcentre, located by walking from it. A walk that meets a
    // subface splits that subface instead (the circumcentre lies beyond it).
    cand.kind = m3d::kDropped;
    const TetShape s = tet_shape(m, t);
    if (!s.ok) return;
    const double* p = s.center;
    const int klass = classify_tet(m, t, c, s);
    const bool make_room = klass == kGood || (m.tflag[t] & m3d::kMakeRoom);
    // (A tetrahedron bad with R < lmin meets the radius-edge bound, B >= 1: it is bad by
    // the dihedral bound alone.)
    if (klass == kBad && !make_room && s.r2 < c.sliver_split_ratio2 * s.lmin2) {
      m3d::protect_tet(m.tflag, t);
      return;
    }
    if (klass == kBad && !make_room)
      for (int k = 0; k < 4; ++k)
        if (m3d::in_protecting_ball(m, m.tv[4 * t + k], p)) {  // next to a sharp feature
          m3d::protect_tet(m.tflag, t);
          return;
        }
    int u = t;
    for (int step = 0; step < c.step_limit; ++step) {
      int exit = -1;
      for (int f0 = 0; f0 < 4 && exit < 0; ++f0) {
        const int f = (f0 + step) % 4;
        if (m3d::face_orient(m, u, f, p) < 0) exit = f;
      }
      if (exit < 0) {
        for (int k = 0; k < 3; ++k) cand.p[k] = p[k];
        cand.kind = m3d::kFreeSplit;
        cand.start = u;
        cand.sub = -1;
        cand.a = cand.b = -1;
        cand.origin = t;
        if (make_room) {
          // Room for a point on a segment or facet: first, and even if it comes near a
          // subsegment or subface (that one waits for it).
          cand.prio = exec::make_priority(kClassSegment, 1e38f, id);
          cand.ek = m3d::kMakeRoomPoint;
        } else if (klass == kTooBig || !worst_first) {
          cand.prio = exec::make_priority(kClassTooBig, size_class(s.volume6), id);
          cand.ek = klass == kTooBig ? m3d::kSizePoint : m3d::kShapePoint;
        } else {
          cand.prio = exec::make_priority(kClassShape, static_cast<float>(fmin(s.r2 / s.lmin2, 1e38)), id);
          cand.ek = m3d::kShapePoint;
        }
        return;
      }
      const int sub = m.tsub[4 * u + exit];
      if (sub >= 0) {
        if (m.sflag[sub] & m3d::kSubNoSplit) {  // the circumcentre lies beyond a subface left as it is
          m3d::protect_tet(m.tflag, t);
          return;
        }
        exec::atomic_or(&m.tflag[u], m3d::kSplitFace0 << exit);
        make_subface_candidate(m, sub, id, c.step_limit, t, cand);
        if (!(m.tflag[t] & m3d::kMakeRoom)) return;
        // Making room: the subface in the way goes first, even if it encroaches a subsegment
        // (m3d::makes_room). Where its circumcentre lies beyond a subsegment (the walk across
        // the facet turned it into that subsegment's split, most often the very split that
        // asked for room: a turned CAD part stalled so, 7% of its volume bad), the room is
        // made inside the tetrahedron itself, at its centroid, once refinement is stuck.
        if (cand.kind == m3d::kFacetSplit) {
          cand.prio = exec::make_priority(kClassSegment, 1e38f, id);
          cand.ek = m3d::kMakeRoomPoint;
          return;
        }
        if (!centroid_room) {
          if (cand.kind >= 0) cand.prio = exec::make_priority(kClassSegment, 1e38f, id);
          return;
        }
        for (int k = 0; k < 3; ++k) {
          cand.p[k] = 0;
          for (int q = 0; q < 4; ++q) cand.p[k] += 0.25 * pt(m, m.tv[4 * t + q])[k];
        }
        cand.kind = m3d::kFreeSplit;
        cand.start = t;
        cand.sub = -1;
        cand.a = cand.b = -1;
        cand.origin = t;
        cand.prio = exec::make_priority(kClassSegment, 1e38f, id);
        cand.ek = m3d::kMakeRoomPoint;
        return;
      }
      u = m.tn[4 * u + exit] >> 2;
    }
  }
};

// Filter (S3): one splitting point per neighbourhood, by atomic priority marks on the
// tetrahedron holding it and its four neighbours (a cavity holds them nearly always, so a
// point that loses one of them would lose its cavity anyway). Only candidates whose random
// id is below `keep_below` (of 2^32) compete.
struct ClaimStart {
  TetView m;
  const Candidate* cand;
  u64 keep_below;
  GDR_HD bool competes(const Candidate& c) const {
    return c.kind >= 0 && exec::priority_id(c.prio) < keep_below;
  }
  GDR_HD void operator()(long long j) const {
    const Candidate& c = cand[j];
    if (!competes(c)) return;
    const int me = static_cast<int>(j);
    exec::raise_mark(&m.mark[c.start], me, c.prio, m3d::PrioOf{cand});
    for (int f = 0; f < 4; ++f) {
      const int nb = m.tn[4 * c.start + f];
      if (nb >= 0) exec::raise_mark(&m.mark[nb >> 2], me, c.prio, m3d::PrioOf{cand});
    }
  }
};

// Did candidate j keep every mark ClaimStart raised?
struct KeptStart {
  TetView m;
  const Candidate* cand;
  u64 keep_below;
  GDR_HD bool operator()(long long j) const {
    const Candidate& c = cand[j];
    if (c.kind < 0 || exec::priority_id(c.prio) >= keep_below) return false;
    if (m.mark[c.start] != j + 1) return false;
    for (int f = 0; f < 4; ++f) {
      const int nb = m.tn[4 * c.start + f];
      if (nb >= 0 && m.mark[nb >> 2] != j + 1) return false;
    }
    return true;
  }
};

}  // namespace gdr::qm3d
