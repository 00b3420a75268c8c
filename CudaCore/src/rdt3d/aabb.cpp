#include "rdt3d/aabb.h"

#include <algorithm>
#include <numeric>

namespace gdr::rdt3d {

HostAabb build_aabb(const std::vector<double>& xyz, const std::vector<int>& tri) {
  HostAabb t;
  const int n = static_cast<int>(tri.size() / 3);
  if (n == 0) return t;
  std::vector<double> lo(3 * std::size_t(n)), hi(3 * std::size_t(n)), mid(3 * std::size_t(n));
  double scene = 0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) {
      double a = xyz[3 * tri[3 * i] + k], b = a;
      for (int c = 1; c < 3; ++c) {
        a = std::min(a, xyz[3 * tri[3 * i + c] + k]);
        b = std::max(b, xyz[3 * tri[3 * i + c] + k]);
      }
      lo[3 * i + k] = a;
      hi[3 * i + k] = b;
      mid[3 * i + k] = 0.5 * (a + b);
      scene = std::max({scene, std::abs(a), std::abs(b)});
    }
  const double pad = std::ldexp(scene, -30);  // widening: rounded slab tests never prune a hit
  t.order.resize(n);
  std::iota(t.order.begin(), t.order.end(), 0);
  struct Job {
    int node, first, count;
  };
  std::vector<Job> jobs{{0, 0, n}};
  t.box.resize(6);
  t.kids.resize(2);
  while (!jobs.empty()) {
    const Job j = jobs.back();
    jobs.pop_back();
    double b[6] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    double c[6] = {1e300, 1e300, 1e300, -1e300, -1e300, -1e300};
    for (int i = j.first; i < j.first + j.count; ++i) {
      const int s = t.order[i];
      for (int k = 0; k < 3; ++k) {
        b[k] = std::min(b[k], lo[3 * s + k]);
        b[3 + k] = std::max(b[3 + k], hi[3 * s + k]);
        c[k] = std::min(c[k], mid[3 * s + k]);
        c[3 + k] = std::max(c[3 + k], mid[3 * s + k]);
      }
    }
    for (int k = 0; k < 3; ++k) {
      t.box[6 * j.node + k] = b[k] - pad;
      t.box[6 * j.node + 3 + k] = b[3 + k] + pad;
    }
    if (j.count <= 4) {
      t.kids[2 * j.node] = -1 - j.first;
      t.kids[2 * j.node + 1] = j.count;
      continue;
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (c[3 + k] - c[k] > c[3 + axis] - c[axis]) axis = k;
    const int half = j.count / 2;
    std::nth_element(t.order.begin() + j.first, t.order.begin() + j.first + half,
                     t.order.begin() + j.first + j.count, [&](int x, int y) {
                       return mid[3 * x + axis] < mid[3 * y + axis] ||
                              (mid[3 * x + axis] == mid[3 * y + axis] && x < y);
                     });
    const int l = static_cast<int>(t.kids.size() / 2);
    t.kids.resize(t.kids.size() + 4);
    t.box.resize(t.box.size() + 12);
    t.kids[2 * j.node] = l;
    t.kids[2 * j.node + 1] = l + 1;
    jobs.push_back({l, j.first, half});
    jobs.push_back({l + 1, j.first + half, j.count - half});
  }
  return t;
}

}  // namespace gdr::rdt3d
