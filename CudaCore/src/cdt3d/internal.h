// Pieces of check_surface, split out to keep each file one job (and to test them alone).
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#include "cdt3d/cdt3d.h"
#include "gdr/pslg.h"

namespace gdr::cdt3d {

// An undirected edge's key: its two point numbers, smaller first.
inline std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// Disjoint sets of 0..n-1; the representative of a set is its smallest member.
struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Edges of a triangle set: edge k joins edge[k][0] < edge[k][1]; its triangles are
// tri[start[k] .. start[k+1]), in increasing order.
struct EdgeTable {
  std::vector<std::array<int, 2>> edge;
  std::vector<int> start;
  std::vector<int> tri;
  int size() const { return static_cast<int>(edge.size()); }
  int count(int k) const { return start[k + 1] - start[k]; }
};
EdgeTable build_edges(const std::vector<std::array<int, 3>>& triangles);

// Pairs of triangles that meet other than in a shared vertex or edge (exact), found through
// a uniform grid over their boxes, in parallel. `pairs` holds the first ones in (i, j)
// order, at most max_pairs; the return value counts them all.
long long find_clashing_triangles(const std::vector<Point3>& points,
                                  const std::vector<std::array<int, 3>>& triangles,
                                  std::size_t max_pairs, std::vector<std::array<int, 2>>& pairs);
// The same for pairs that share no vertex and come within `gap` of each other (floating
// point distances: a diagnosis of what TetGen's tolerances cannot separate, not a predicate).
long long find_close_triangles(const std::vector<Point3>& points, const std::vector<std::array<int, 3>>& triangles,
                               double gap, std::size_t max_pairs, std::vector<std::array<int, 2>>& pairs);

// Cells of a closed triangle set, the domain, and its volume (see Plc). Fills
// plc.triangle_cell, cell_in_domain, cell_region, cell_volume and volume from plc.points,
// plc.triangles, plc.holes and plc.regions. `input_triangle` names triangles in messages.
void classify_cells(Plc& plc, const EdgeTable& edges, const std::vector<int>& input_triangle,
                    const Callbacks& callbacks);

// "a, b, c, d, e (N in all)" from the first few of `items`.
std::string list_items(const std::vector<std::string>& items, long long total);

}  // namespace gdr::cdt3d
