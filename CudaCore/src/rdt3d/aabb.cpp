#include "rdt3d/aabb.h"

#include <algorithm>
#include <numeric>
#include <unordered_map>

namespace gdr::rdt3d {

namespace {

constexpr int kLeaf = 4;  // at most this many triangles in a leaf

// Nodes of the subtree over `count` triangles (median splits down to leaves of kLeaf), by
// count: each level of the tree has at most two counts, so few are ever asked for.
int subtree_nodes(int count, std::unordered_map<int, int>& memo) {
  if (count <= kLeaf) return 1;
  const auto it = memo.find(count);
  if (it != memo.end()) return it->second;
  const int n = 1 + subtree_nodes(count / 2, memo) + subtree_nodes(count - count / 2, memo);
  memo[count] = n;
  return n;
}

// Triangles as they are split: centroid and number side by side, so that the median splits
// run over contiguous memory (by number they jumped across the whole surface).
struct Item {
  double mid[3];
  int id;
};

struct Builder {
  HostAabb& t;
  std::vector<Item>& items;
  const std::vector<double>& xyz;
  const std::vector<int>& tri;
  double pad;
  const std::unordered_map<int, int>& nodes;  // subtree_nodes, filled for every count met
  int subtree(int count) const { return count <= kLeaf ? 1 : nodes.at(count); }

  // Node `node` over items[first, first + count); its subtree takes the nodes that follow it
  // (pre-order: left child node + 1, right child after the left subtree), so that subtrees
  // are built in parallel into fixed places and the tree does not depend on the threads. A
  // leaf's box is its triangles', an inner node's the union of its children's.
  void build(int node, int first, int count) {
    double* box = &t.box[6 * std::size_t(node)];
    if (count <= kLeaf) {
      double b[6] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
      for (int i = first; i < first + count; ++i) {
        const int s = items[i].id;
        t.order[i] = s;
        for (int c = 0; c < 3; ++c)
          for (int k = 0; k < 3; ++k) {
            const double v = xyz[3 * std::size_t(tri[3 * std::size_t(s) + c]) + k];
            b[k] = std::min(b[k], v);
            b[3 + k] = std::max(b[3 + k], v);
          }
      }
      for (int k = 0; k < 3; ++k) {
        box[k] = b[k] - pad;
        box[3 + k] = b[3 + k] + pad;
      }
      t.kids[2 * node] = -1 - first;
      t.kids[2 * node + 1] = count;
      return;
    }
    double c[6] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (int i = first; i < first + count; ++i)
      for (int k = 0; k < 3; ++k) {
        c[k] = std::min(c[k], items[i].mid[k]);
        c[3 + k] = std::max(c[3 + k], items[i].mid[k]);
      }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (c[3 + k] - c[k] > c[3 + axis] - c[axis]) axis = k;
    const int half = count / 2;
    std::nth_element(items.begin() + first, items.begin() + first + half, items.begin() + first + count,
                     [axis](const Item& x, const Item& y) {
                       return x.mid[axis] < y.mid[axis] || (x.mid[axis] == y.mid[axis] && x.id < y.id);
                     });
    const int left = node + 1, right = left + subtree(half);
    t.kids[2 * node] = left;
    t.kids[2 * node + 1] = right;
    if (count > 16384) {
#pragma omp task default(shared) firstprivate(left, first, half)
      build(left, first, half);
      build(right, first + half, count - half);
#pragma omp taskwait
    } else {
      build(left, first, half);
      build(right, first + half, count - half);
    }
    const double *l = &t.box[6 * std::size_t(left)], *r = &t.box[6 * std::size_t(right)];
    for (int k = 0; k < 3; ++k) {
      box[k] = std::min(l[k], r[k]);
      box[3 + k] = std::max(l[3 + k], r[3 + k]);
    }
  }
};

}  // namespace

HostAabb build_aabb(const std::vector<double>& xyz, const std::vector<int>& tri) {
  HostAabb t;
  const int n = static_cast<int>(tri.size() / 3);
  if (n == 0) return t;
  std::vector<Item> items(n);
  double scene = 0;
#pragma omp parallel for reduction(max : scene) schedule(static) if (n > 20000)
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      double a = xyz[3 * tri[3 * i] + k], b = a;
      for (int c = 1; c < 3; ++c) {
        a = std::min(a, xyz[3 * tri[3 * i + c] + k]);
        b = std::max(b, xyz[3 * tri[3 * i + c] + k]);
      }
      items[i].mid[k] = 0.5 * (a + b);
      scene = std::max({scene, std::abs(a), std::abs(b)});
      items[i].id = i;
    }
  const double pad = std::ldexp(scene, -30);  // widening: rounded slab tests never prune a hit
  t.order.resize(n);
  std::unordered_map<int, int> memo;
  const int nodes = subtree_nodes(n, memo);
  t.box.resize(6 * std::size_t(nodes));
  t.kids.resize(2 * std::size_t(nodes));
  Builder builder{t, items, xyz, tri, pad, memo};
#pragma omp parallel if (n > 20000)
#pragma omp single
  builder.build(0, 0, n);
  return t;
}

}  // namespace gdr::rdt3d
