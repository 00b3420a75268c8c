// Compaction (S1) of the tetrahedra and subfaces, in place: the live elements of the tail
// move into the dead slots of the head, so no second copy of the mesh is ever held (device
// memory per element). Links into moved elements are fixed afterwards: tetrahedron
// neighbours and subface sides for tetrahedra, tetrahedron faces for subfaces.
#pragma once
#include "exec/algorithms.h"
#include "mesh3d/mesh3d.h"

namespace gdr::m3d {

// aux/saux hold the exclusive scan of the live flags, `base` the number of live elements in
// the head, `live` the number of live elements.
struct Moves {
  const int* hole;
  const int* rank;
  int live, base;
  GDR_HD_INLINE int destination(int t) const { return t < live ? t : hole[rank[t] - base]; }
};

struct MoveTets {
  TetView m;
  Moves mv;
  GDR_HD void operator()(long long i) const {
    const int s = mv.live + static_cast<int>(i);
    if (m.tflag[s] & kDead) return;
    const int d = mv.destination(s);
    for (int f = 0; f < 4; ++f) {
      m.tv[4 * d + f] = m.tv[4 * s + f];
      const int nb = m.tn[4 * s + f];
      m.tn[4 * d + f] = nb < 0 ? -1 : 4 * mv.destination(nb >> 2) + (nb & 3);
      m.tsub[4 * d + f] = m.tsub[4 * s + f];
    }
    m.tflag[d] = m.tflag[s] & ~kInCavity;
    if (m.tregion) m.tregion[d] = m.tregion[s];
  }
};

// Then every neighbour of a moved tetrahedron points back at its new slot, and so does every
// subface on one of its faces.
struct FixTetLinks {
  TetView m;
  Moves mv;
  GDR_HD void operator()(long long i) const {
    const int s = mv.live + static_cast<int>(i);
    if (m.tflag[s] & kDead) return;
    const int d = mv.destination(s);
    for (int f = 0; f < 4; ++f) {
      const int nb = m.tn[4 * d + f];
      if (nb >= 0) m.tn[nb] = 4 * d + f;
      const int sub = m.tsub[4 * d + f];
      if (sub >= 0)
        for (int side = 0; side < 2; ++side)
          if (m.st[2 * sub + side] == 4 * s + f) m.st[2 * sub + side] = 4 * d + f;
    }
  }
};

struct MoveSubfaces {
  TetView m;
  Moves mv;
  GDR_HD void operator()(long long i) const {
    const int s = mv.live + static_cast<int>(i);
    if (m.sflag[s] & kSubDead) return;
    const int d = mv.destination(s);
    for (int k = 0; k < 3; ++k) m.sv[3 * d + k] = m.sv[3 * s + k];
    for (int side = 0; side < 2; ++side) {
      const int tf = m.st[2 * s + side];
      m.st[2 * d + side] = tf;
      if (tf >= 0) m.tsub[tf] = d;
    }
    m.sfacet[d] = m.sfacet[s];
    m.sflag[d] = m.sflag[s] & ~kSubInCavity;
  }
};

template <class Space>
void compact_subfaces(DeviceTetMesh<Space>& dm) {
  using Ops = exec::Ops<Space>;
  const int n = dm.nsub;
  int* rank = dm.saux.data();  // free between iterations
  const int* flag = dm.sflag.data();
  Ops::for_each(n, [=] GDR_HD(long long s) { rank[s] = (flag[s] & kSubDead) ? 0 : 1; });
  const int live = static_cast<int>(Ops::exclusive_scan(rank, rank, n));
  exec::Buffer<Space, int> holes(std::size_t(n - live) + 1);
  int* hole = holes.data();
  Ops::for_each(live, [=] GDR_HD(long long s) {
    if (flag[s] & kSubDead) hole[s - rank[s]] = static_cast<int>(s);
  });
  const int base = live < n ? dm.saux.get(live) : live;
  Ops::for_each(n - live, MoveSubfaces{dm.view(), Moves{hole, rank, live, base}});
  dm.nsub = live;
  dm.sv.resize(3 * std::size_t(live));
  dm.st.resize(2 * std::size_t(live));
  dm.sfacet.resize(live);
  dm.sflag.resize(live);
  dm.smark.resize(live);
  dm.saux.resize(live);
}

template <class Space>
void compact_tets(DeviceTetMesh<Space>& dm) {
  using Ops = exec::Ops<Space>;
  const int n = dm.ntet;
  int* rank = dm.aux.data();  // free between iterations
  const int* flag = dm.tflag.data();
  Ops::for_each(n, [=] GDR_HD(long long t) { rank[t] = (flag[t] & kDead) ? 0 : 1; });
  const int live = static_cast<int>(Ops::exclusive_scan(rank, rank, n));
  exec::Buffer<Space, int> holes(std::size_t(n - live) + 1);
  int* hole = holes.data();
  Ops::for_each(live, [=] GDR_HD(long long t) {
    if (flag[t] & kDead) hole[t - rank[t]] = static_cast<int>(t);
  });
  const int base = live < n ? dm.aux.get(live) : live;
  const Moves mv{hole, rank, live, base};
  Ops::for_each(n - live, MoveTets{dm.view(), mv});
  Ops::for_each(n - live, FixTetLinks{dm.view(), mv});
  dm.ntet = live;
  dm.tv.resize(4 * std::size_t(live));
  dm.tn.resize(4 * std::size_t(live));
  dm.tsub.resize(4 * std::size_t(live));
  dm.tflag.resize(live);
  if (dm.regions) dm.tregion.resize(live);
  dm.mark.resize(live);
  dm.aux.resize(live);
}

// Subfaces first: their moves fix tsub through st, which the tetrahedra's moves then fix.
template <class Space>
void compact(DeviceTetMesh<Space>& dm) {
  compact_subfaces(dm);
  compact_tets(dm);
}

}  // namespace gdr::m3d
