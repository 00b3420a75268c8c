// Triangulation storage for gDP2d as structures of arrays.
//
// Triangle t has vertices tv[3t..3t+2] (counter-clockwise). Edge i of t joins
// tv[3t+(i+1)%3] and tv[3t+(i+2)%3]; it is opposite vertex i. tn[3t+i] is the neighbour
// across edge i encoded as 3*t'+i' (so back-pointers are O(1)), or -1 on the domain
// boundary. On the host, ts[3t+i] is the segment that edge i lies on (index into the segment
// table: input segments first, then convex-hull edges), or -1 for an unconstrained edge. On
// the device one flag bit per edge says "subsegment" instead (12 bytes less per triangle);
// the segment follows from the edge's endpoints when needed (kernels.h, segment_of).
#pragma once
#include <cstdint>
#include <vector>

#include "exec/buffer.h"
#include "exec/hd.h"
#include "exec/host_vector.h"
#include "gdr/pslg.h"

namespace gdr::r2d {

// Per-triangle flag bits.
enum : int {
  kDead = 1u,        // removed by an insertion; compacted away later
  kInCavity = 2u,    // part of a winning cavity during insertion
  kSplitEdge0 = 4u,  // edge i (bit 2+i) is a subsegment that must be split (a rejected
                     // circumcentre encroached it, or a walk ran into it)
  kCollectShift = 5,  // bits 5-8: the triangle's own collect mask (kernels.h, collect_mask)
  kCollectBits = 15 << kCollectShift,
  kSubseg0 = 1 << 9,  // edge i (bit 9+i) lies on a segment
  kFresh = 1 << 12,   // new triangle: its collect bits are not computed yet
  kRegionShift = 13,  // bits 13-30: the triangle's region number (0: none), kept by every
                      // new triangle of a cavity from the old one it replaces on that side
  kMaxRegions = (1 << (31 - kRegionShift)) - 1,
};

// Per-point types (same values as gdr::PointType).
enum : std::uint8_t { kInputPoint = 0, kSegmentPoint = 1, kFreePoint = 2 };

// Host copy of what the initial CDT produces: the engine's input.
// (Uninitialised on resize: a 1M-segment CDT's arrays were zeroed by one thread, 0.05 s.)
struct HostMesh {
  exec::HostVector<double> xy;          // 2 per point
  exec::HostVector<std::uint8_t> ptype; // per point
  exec::HostVector<int> pseg;           // per point: segment it lies on (segment points), else -1
  exec::HostVector<int> tv, tn, ts;     // 3 per triangle
  exec::HostVector<int> seg;            // 2 per segment: endpoint vertex ids
  exec::HostVector<int> tregion;        // per triangle: region number (empty: no regions)
  int input_segments = 0;            // segments [0, input_segments) come from the input
  int triangles() const { return static_cast<int>(tv.size() / 3); }
  int points() const { return static_cast<int>(ptype.size()); }
};

// The engine's output: the final mesh (live triangles only) in the forms the facade reports,
// built on the device so that no neighbour or segment links need to be copied.
struct MeshResult {
  // Triangles and point types in the output's own types (TriMesh takes them over).
  exec::HostVector<double> xy;           // 2 per point
  FilledVector<PointType> ptype;         // per point
  FilledVector<std::array<int, 3>> tv;   // per triangle
  exec::HostVector<int> subseg;          // 4 per subsegment: its two vertices, its segment,
                                         // and 1 on the mesh boundary (one triangle), else 0
  exec::HostVector<int> bad;             // triangles left bad: 2t, or 2t+1 where the
                                         // small-input-angle rule protects them
  exec::HostVector<int> tregion;         // per triangle: region number (empty: no regions)
  double area = 0;                       // the mesh's area (in the engine's coordinates)
  double min_sin2 = 1;                   // the least sin^2 of an angle of its triangles
  int triangles() const { return static_cast<int>(tv.size()); }
  int points() const { return static_cast<int>(ptype.size()); }
};

// Trivially copyable view passed to kernels by value.
struct MeshView {
  double* xy;
  std::uint8_t* ptype;
  int* pseg;
  int* tv;
  int* tn;
  int* tflag;
  int* mark;  // cavity claims: candidate + 1 (exec/priority.h)
  int* aux;
  const int* seg;
  const int* vseg_begin;  // segments at input vertex v: vseg[vseg_begin[v] .. vseg_begin[v+1])
  const int* vseg;
  int ntri;
  int npts;
};

template <class Space>
struct DeviceMesh {
  template <class T>
  using Buf = exec::Buffer<Space, T>;
  Buf<double> xy;
  Buf<std::uint8_t> ptype;
  Buf<int> pseg;
  Buf<int> tv, tn;
  Buf<int> tflag;
  Buf<int> mark;  // priority marks (S3 filter, cavity claims)
  Buf<int> aux;         // scratch per triangle (new-triangle slot base during insertion)
  Buf<int> seg, vseg_begin, vseg;
  int ntri = 0, npts = 0;

  MeshView view() {
    return MeshView{xy.data(),   ptype.data(), pseg.data(), tv.data(),         tn.data(),
                    tflag.data(), mark.data(), aux.data(), seg.data(),        vseg_begin.data(),
                    vseg.data(),  ntri,        npts};
  }

  void upload(const HostMesh& h) {
    npts = h.points();
    ntri = h.triangles();
    xy.upload(h.xy);
    ptype.upload(h.ptype);
    pseg.upload(h.pseg);
    tv.upload(h.tv);
    tn.upload(h.tn);
    seg.upload(h.seg);
    upload_segments_at_vertices(h);
    Buf<int> ts, tr;
    ts.upload(h.ts);
    tr.upload(h.tregion);
    tflag.resize_discard(ntri);
    int* f = tflag.data();
    const int* s = ts.data();
    const int* r = h.tregion.empty() ? nullptr : tr.data();
    exec::Ops<Space>::for_each(ntri, [=] GDR_HD(long long t) {
      int bits = kFresh;
      for (int i = 0; i < 3; ++i)
        if (s[3 * t + i] >= 0) bits |= kSubseg0 << i;
      if (r) bits |= r[t] << kRegionShift;
      f[t] = bits;
    });
    mark.resize_discard(ntri);
    mark.zero();
    aux.resize_discard(ntri);
  }

  // Segments at each input vertex (all endpoints are input vertices), to name the segment of
  // a subsegment that joins two input vertices.
  void upload_segments_at_vertices(const HostMesh& h) {
    const int ns = static_cast<int>(h.seg.size() / 2);
    std::vector<int> begin(std::size_t(npts) + 1, 0), list(h.seg.size());
    for (int v : h.seg) ++begin[v + 1];
    for (int v = 0; v < npts; ++v) begin[v + 1] += begin[v];
    std::vector<int> fill(begin.begin(), begin.end() - 1);
    for (int s = 0; s < ns; ++s)
      for (int k = 0; k < 2; ++k) list[fill[h.seg[2 * s + k]]++] = s;
    vseg_begin.upload(begin);
    vseg.upload(list);
  }

  // Memory held, as the space's counter counts it.
  std::size_t bytes() const {
    return xy.capacity() * sizeof(double) + ptype.capacity() + pseg.capacity() * sizeof(int) +
           (tv.capacity() + tn.capacity() + tflag.capacity() + mark.capacity() + aux.capacity() +
            seg.capacity() + vseg_begin.capacity() + vseg.capacity()) *
               sizeof(int);
  }

  // Room for `tris` triangles and `pts` points, keeping contents.
  // Room for tris triangles and pts points, sizes unchanged (Buffer::reserve).
  void reserve_room(int tris, int pts) {
    for (auto* b : {&tv, &tn}) b->reserve(3 * std::size_t(tris));
    for (auto* b : {&tflag, &mark, &aux}) b->reserve(tris);
    xy.reserve(2 * std::size_t(pts));
    ptype.reserve(pts);
    pseg.reserve(pts);
  }
  void reserve(int tris, int pts) {
    if (tris > ntri) {
      tv.resize(3 * std::size_t(tris));
      tn.resize(3 * std::size_t(tris));
      tflag.resize(tris);
      mark.resize(tris);
      aux.resize(tris);
    }
    if (pts > npts) {
      xy.resize(2 * std::size_t(pts));
      ptype.resize(pts);
      pseg.resize(pts);
    }
  }
};

}  // namespace gdr::r2d
