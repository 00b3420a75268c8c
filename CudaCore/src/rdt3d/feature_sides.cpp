// Feature subsegments brought back onto the surface by relabelling (see feature_sides.h).
#include "rdt3d/feature_sides.h"

#include <algorithm>
#include <numeric>

namespace gdr::rdt3d {
namespace {

bool inside(const m3d::TetView& m, int t) { return (m.tflag[t] & kInterior) != 0; }

// The tetrahedra around edge ab of t, in order round it; false if the ring is open (hull).
bool ring_of(const m3d::TetView& m, int t, int a, int b, std::vector<int>& ring) {
  int f = 0;  // a face of t that holds ab
  while (m.tv[4 * t + f] == a || m.tv[4 * t + f] == b) ++f;
  ring.clear();
  return turn_around_edge(m, t, f, a, b, [&](int u, int) {
           ring.push_back(u);
           return false;
         }) == 0;
}

// The tetrahedra that changed side: those committed, and those of the change being tried.
struct Changed {
  const std::vector<char>& moved;
  const std::vector<int>& trying;
  bool operator()(int t) const { return moved[t] || std::find(trying.begin(), trying.end(), t) != trying.end(); }
};

// Faces of the output surface through edge ab of t, as restricted_delaunay.cpp emits them: a
// face next to a tetrahedron that changed side where the two sides differ, any other where
// it is a surface facet. -1 if the ring round ab is open (the hull).
int emitted_at_edge(const m3d::TetView& m, const Criteria& c, int t, int a, int b, const Changed& changed) {
  int f = 0;  // a face of t that holds ab
  while (m.tv[4 * t + f] == a || m.tv[4 * t + f] == b) ++f;
  int faces = 0;
  const int r = turn_around_edge(m, t, f, a, b, [&](int u, int g) {
    const int w = m.tn[4 * u + g] >> 2;
    faces += changed(u) || changed(w) ? inside(m, u) != inside(m, w) : surface_facet(m, c, u, g);
    return false;
  });
  return r == 0 ? faces : -1;
}

// Is the surface a manifold at vertex v of t: the tetrahedra round v on each side one group,
// joined across faces through v? (At most two groups in all, one per side.)
bool manifold_at_vertex(const m3d::TetView& m, int t, int v, std::vector<int>& star, std::vector<int>& group) {
  star.assign(1, t);
  for (std::size_t i = 0; i < star.size(); ++i)
    for (int f = 0; f < 4; ++f) {
      const int u = star[i];
      const int nb = m.tn[4 * u + f];
      if (m.tv[4 * u + f] == v || nb < 0) continue;  // only faces through v
      if (std::find(star.begin(), star.end(), nb >> 2) == star.end()) star.push_back(nb >> 2);
    }
  const int n = static_cast<int>(star.size());
  group.resize(n);
  std::iota(group.begin(), group.end(), 0);
  auto root = [&](int i) {
    while (group[i] != i) i = group[i] = group[group[i]];
    return i;
  };
  for (int i = 0; i < n; ++i)
    for (int f = 0; f < 4; ++f) {
      const int u = star[i], nb = m.tn[4 * u + f];
      if (m.tv[4 * u + f] == v || nb < 0 || inside(m, nb >> 2) != inside(m, u)) continue;
      const int j = static_cast<int>(std::find(star.begin(), star.end(), nb >> 2) - star.begin());
      group[root(i)] = root(j);
    }
  int groups = 0;
  for (int i = 0; i < n; ++i) groups += root(i) == i;
  return groups <= 2;
}

// Non-manifold edges and vertices of the tetrahedra in `ts`; an edge counts with faces as
// the output emits them (faces, but not two: a pinch or a hole).
int non_manifold_places(const m3d::TetView& m, const Criteria& c, const std::vector<int>& ts,
                        const Changed& changed, std::vector<int>& s1, std::vector<int>& s2) {
  int bad = 0;
  for (const int t : ts) {
    for (int q = 0; q < 4; ++q) bad += !manifold_at_vertex(m, t, m.tv[4 * t + q], s1, s2);
    for (int e = 0; e < 6; ++e) {
      const int faces = emitted_at_edge(m, c, t, m.tv[4 * t + m3d::edge_corner(e, 0)],
                                        m.tv[4 * t + m3d::edge_corner(e, 1)], changed);
      bad += faces > 0 && faces != 2;
    }
  }
  return bad;
}

// Calls visit(t, a, b, f) once per feature subsegment ab, from the lowest tetrahedron t round
// it (f: a face of t through ab), with `ring` holding the tetrahedra round it in order. A
// ring open at the hull has the outside beyond it and is skipped.
template <class Visit>
void for_each_subsegment(const m3d::TetView& m, std::vector<int>& ring, Visit visit) {
  for (int t = 0; t < m.ntet; ++t) {
    const int flags = m.tflag[t];
    if (!(flags & m3d::kSegBits)) continue;
    for (int e = 0; e < 6; ++e) {
      if (!(flags & (m3d::kSeg0 << e))) continue;
      const int a = m.tv[4 * t + m3d::edge_corner(e, 0)], b = m.tv[4 * t + m3d::edge_corner(e, 1)];
      if (!ring_of(m, t, a, b, ring) || *std::min_element(ring.begin(), ring.end()) != t) continue;
      int f = 0;
      while (m.tv[4 * t + f] == a || m.tv[4 * t + f] == b) ++f;
      visit(t, a, b, f);
    }
  }
}

// A change round a subsegment that pinches the surface (the tetrahedra that changed side
// meet the rest of their new side at an edge or a vertex only): their neighbours whose
// centroids lie on the side they took change too, layer by layer (at most 3 layers and 64
// tetrahedra), until no edge or vertex round them is a pinch. Appends what changed to
// `changed` and returns true then; else undoes the growth and returns false.
bool grow(const m3d::TetView& m, const Criteria& c, const AabbView& tree, const std::vector<char>& moved,
          std::vector<int>& changed, std::vector<int>& s1, std::vector<int>& s2) {
  const std::size_t first = changed.size();
  std::size_t from = 0;
  for (int layer = 0; layer < 3 && changed.size() < 64; ++layer) {
    const std::size_t to = changed.size();
    for (std::size_t i = from; i < to; ++i)
      for (int f = 0; f < 4; ++f) {
        const int u = changed[i], nb = m.tn[4 * u + f];
        if (nb < 0) continue;
        const int w = nb >> 2;
        if (inside(m, w) == inside(m, u) || std::find(changed.begin(), changed.end(), w) != changed.end()) continue;
        double g[3] = {0, 0, 0};
        for (int q = 0; q < 4; ++q)
          for (int k = 0; k < 3; ++k) g[k] += 0.25 * pt(m, m.tv[4 * w + q])[k];
        if (inside_surface(tree, g, c.reach) != inside(m, u)) continue;
        m.tflag[w] ^= kInterior;
        changed.push_back(w);
      }
    from = to;
    if (changed.size() == to) break;  // nothing more to take
    if (non_manifold_places(m, c, changed, Changed{moved, changed}, s1, s2) == 0) return true;
  }
  for (std::size_t i = first; i < changed.size(); ++i) m.tflag[changed[i]] ^= kInterior;
  changed.resize(first);
  return false;
}

}  // namespace

FeatureSides mend_lost_features(const m3d::TetView& m, const Criteria& c, const AabbView& tree,
                                std::vector<char>& moved) {
  FeatureSides r;
  std::vector<int> ring, changed, s1, s2;
  std::vector<char> in;
  for_each_subsegment(m, ring, [&](int t, int a, int b, int f) {
    int facets = 0;
    turn_around_edge(m, t, f, a, b, [&](int u, int g) {
      facets += surface_facet(m, c, u, g);
      return false;
    });
    if (facets != 0) return;
    ++r.lost;
    // The probes: 1/64 of the way from the subsegment's midpoint to the midpoint of the
    // opposite edge, inside each tetrahedron and close to the subsegment.
    const double* pa = pt(m, a);
    const double* pb = pt(m, b);
    const int n = static_cast<int>(ring.size());
    in.resize(n);
    for (int i = 0; i < n; ++i) {
      int o[2], k = 0;
      for (int q = 0; q < 4; ++q) {
        const int v = m.tv[4 * ring[i] + q];
        if (v != a && v != b) o[k++] = v;
      }
      const double* pc = pt(m, o[0]);
      const double* pd = pt(m, o[1]);
      double p[3];
      for (int q = 0; q < 3; ++q) {
        const double mid = 0.5 * (pa[q] + pb[q]);
        p[q] = mid + (0.5 * (pc[q] + pd[q]) - mid) / 64;
      }
      in[i] = inside_surface(tree, p, c.reach);
    }
    int changes = 0;
    for (int i = 0; i < n; ++i) changes += in[i] != in[(i + 1) % n];
    if (changes != 2) {  // all on one side, or several wedges: left as it is
      ++(changes == 0 ? r.one_side : r.wedges);
      return;
    }
    changed.clear();
    for (int i = 0; i < n; ++i)
      if (inside(m, ring[i]) != (in[i] != 0)) changed.push_back(ring[i]);
    // Kept only where the surface round the changed tetrahedra is no less a manifold.
    const std::vector<int> none;
    const int before = non_manifold_places(m, c, changed, Changed{moved, none}, s1, s2);
    for (const int u : changed) m.tflag[u] ^= kInterior;
    if (non_manifold_places(m, c, changed, Changed{moved, changed}, s1, s2) > before &&
        !grow(m, c, tree, moved, changed, s1, s2)) {
      for (const int u : changed) m.tflag[u] ^= kInterior;
      ++r.pinching;
      return;
    }
    ++r.mended;
    for (const int u : changed) moved[u] = 1;
    r.relabelled += static_cast<long long>(changed.size());
  });
  // What is left, counted on the output's surface (a change round one subsegment can bring
  // back another): faces next to a tetrahedron that changed side bound the volume when the
  // two sides differ, the others when they are surface facets.
  const std::vector<int> none;
  for_each_subsegment(m, ring, [&](int t, int a, int b, int) {
    r.left += emitted_at_edge(m, c, t, a, b, Changed{moved, none}) == 0;
  });
  return r;
}

}  // namespace gdr::rdt3d
