// Grouping of edges and faces by their vertices without a global sort: items are bucketed by
// their smallest vertex (a counting sort, linear), then each small bucket is sorted by the
// remaining vertices. Equal edges/faces end up adjacent; lookups are a binary search in one
// bucket. This keeps the validators linear and parallel on 10M-element meshes.
#pragma once
#include <omp.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gdr::validate {

struct Keyed {
  int b = 0, c = 0;        // the other vertices of the edge (c = -1) or face, sorted
  std::int64_t item = 0;   // caller's id, e.g. element * 4 + local face
  bool operator<(const Keyed& o) const {
    return b != o.b ? b < o.b : c != o.c ? c < o.c : item < o.item;
  }
};

class Incidence {
 public:
  // `key(i, a, b, c)` gives item i's sorted vertices (a < b < c, c = -1 for edges), or
  // returns false to leave the item out.
  template <class KeyFn>
  Incidence(std::size_t vertices, std::size_t items, KeyFn key) : start_(vertices + 1, 0) {
    for (std::size_t i = 0; i < items; ++i) {
      int a, b, c;
      if (key(i, a, b, c)) ++start_[a + 1];
    }
    for (std::size_t v = 0; v < vertices; ++v) start_[v + 1] += start_[v];
    entries_.resize(start_[vertices]);
    std::vector<std::size_t> fill(start_.begin(), start_.end() - 1);
    for (std::size_t i = 0; i < items; ++i) {
      int a, b, c;
      if (key(i, a, b, c)) entries_[fill[a]++] = {b, c, static_cast<std::int64_t>(i)};
    }
#pragma omp parallel for schedule(dynamic, 4096)
    for (std::int64_t v = 0; v < static_cast<std::int64_t>(vertices); ++v)
      std::sort(entries_.begin() + start_[v], entries_.begin() + start_[v + 1]);
  }

  std::size_t vertices() const { return start_.size() - 1; }
  const Keyed* begin(int a) const { return entries_.data() + start_[a]; }
  const Keyed* end(int a) const { return entries_.data() + start_[a + 1]; }

  // The run of entries equal to (a, b, c); empty when absent.
  std::pair<const Keyed*, const Keyed*> find(int a, int b, int c) const {
    const Keyed probe{b, c, INT64_MIN};
    const Keyed* lo = std::lower_bound(begin(a), end(a), probe);
    const Keyed* hi = lo;
    while (hi != end(a) && hi->b == b && hi->c == c) ++hi;
    return {lo, hi};
  }

  // Calls f(a, first, last) for every group of equal keys, in parallel over vertices.
  template <class F>
  void for_each_group(F f) const {
    const std::int64_t n = static_cast<std::int64_t>(vertices());
#pragma omp parallel for schedule(dynamic, 4096)
    for (std::int64_t a = 0; a < n; ++a) {
      const Keyed* e = begin(static_cast<int>(a));
      const Keyed* stop = end(static_cast<int>(a));
      while (e != stop) {
        const Keyed* g = e + 1;
        while (g != stop && g->b == e->b && g->c == e->c) ++g;
        f(static_cast<int>(a), e, g);
        e = g;
      }
    }
  }

 private:
  std::vector<std::size_t> start_;
  std::vector<Keyed> entries_;
};

inline void sort3(int& a, int& b, int& c) {
  if (a > b) std::swap(a, b);
  if (b > c) std::swap(b, c);
  if (a > b) std::swap(a, b);
}

// Problem messages: the first `cap` are kept, all are counted by the caller.
struct Problems {
  std::vector<std::string>& list;
  std::size_t cap;
  void add(const std::string& message) {
    if (list.size() < cap) list.push_back(message);
  }
};

}  // namespace gdr::validate
