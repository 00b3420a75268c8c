// Consistent orientation of a triangulated surface (see orient_surface.h).
#include "mesh3d/orient_surface.h"

#include <parallel/algorithm>
#include <cstdint>
#include <utility>

namespace gdr::m3d {

OrientResult orient_consistently(std::vector<int>& tri, const std::vector<OrientVote>& votes) {
  OrientResult r;
  const int n = static_cast<int>(tri.size() / 3);
  // Directed edges, sorted by their undirected key: the triangles at each edge side by side.
  struct Half {
    std::uint64_t key;
    int t;
    bool forward;  // the triangle runs low -> high
  };
  std::vector<Half> h(3 * static_cast<std::size_t>(n));
#pragma omp parallel for
  for (int t = 0; t < n; ++t)
    for (int q = 0; q < 3; ++q) {
      const int a = tri[3 * t + q], b = tri[3 * t + (q + 1) % 3];
      const std::uint64_t lo = static_cast<std::uint32_t>(std::min(a, b)), hi = static_cast<std::uint32_t>(std::max(a, b));
      h[3 * t + q] = Half{lo << 32 | hi, t, a < b};
    }
  __gnu_parallel::sort(h.begin(), h.end(), [](const Half& x, const Half& y) { return x.key < y.key; });
  // Manifold edges as links: (other triangle, 1 if the two must differ in flip to agree).
  std::vector<int> first(n + 1, 0);
  std::vector<std::pair<int, int>> pairs;  // indices into h
  for (std::size_t i = 0; i < h.size();) {
    std::size_t j = i;
    while (j < h.size() && h[j].key == h[i].key) ++j;
    if (j - i == 2 && h[i].t != h[i + 1].t) {
      pairs.emplace_back(static_cast<int>(i), static_cast<int>(i + 1));
      ++first[h[i].t + 1];
      ++first[h[i + 1].t + 1];
    }
    i = j;
  }
  for (int t = 0; t < n; ++t) first[t + 1] += first[t];
  std::vector<std::pair<int, char>> link(first[n]);
  std::vector<int> fill(first.begin(), first.end() - 1);
  for (const auto& [i, j] : pairs) {
    const char differ = h[i].forward == h[j].forward;  // same direction: one must turn
    link[fill[h[i].t]++] = {h[j].t, differ};
    link[fill[h[j].t]++] = {h[i].t, differ};
  }
  // Each patch: flips relative to its first triangle, then the side its votes favour.
  std::vector<signed char> flip(n, -1);
  std::vector<int> patch, stack;
  for (int s = 0; s < n; ++s) {
    if (flip[s] >= 0) continue;
    ++r.patches;
    patch.clear();
    flip[s] = 0;
    stack.push_back(s);
    while (!stack.empty()) {
      const int t = stack.back();
      stack.pop_back();
      patch.push_back(t);
      for (int k = first[t]; k < first[t + 1]; ++k) {
        const auto [u, differ] = link[k];
        const signed char want = static_cast<signed char>(flip[t] ^ differ);
        if (flip[u] < 0) {
          flip[u] = want;
          stack.push_back(u);
        } else if (flip[u] != want && t < u) {
          ++r.non_orientable;
        }
      }
    }
    double certain = 0, weighted = 0;  // > 0: the patch as it is (flip 0) is favoured
    for (const int t : patch) {
      const double sign = flip[t] ? -1.0 : 1.0;
      (votes[t].certain ? certain : weighted) += sign * (votes[t].certain ? 1.0 : votes[t].weight);
    }
    const bool turn = certain != 0 ? certain < 0 : weighted < 0;
    for (const int t : patch) {
      if (static_cast<bool>(flip[t]) != turn) {  // against the side the patch takes
        std::swap(tri[3 * t + 1], tri[3 * t + 2]);
        ++r.flipped;
      }
    }
  }
  return r;
}

}  // namespace gdr::m3d
