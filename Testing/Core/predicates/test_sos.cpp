// Symbolic perturbation: never zero on distinct indices, antisymmetric under every argument
// permutation, agrees with the exact predicate, and yields consistent Delaunay triangulations
// of highly degenerate lattices.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <numeric>
#include <vector>

#include "cases.h"

namespace gdr::test {
namespace {

int permutation_parity(const int* perm, int n) {
  int inv = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) inv += perm[i] > perm[j];
  return inv % 2 ? -1 : 1;
}

class SosInvariants : public ::testing::TestWithParam<Pred> {};

TEST_P(SosInvariants, NonzeroAntisymmetricAndConsistentWithExactSign) {
  const Pred p = GetParam();
  // insphere checks 120 argument orders per case; fewer cases keep it fast.
  CaseSet set = adversarial_cases(p, p == Pred::Insphere ? 3000 : 20000, 303 + int(p));
  compute_reference(set);
  const int np = set.npts;
  const long long n = static_cast<long long>(set.size());
  long long zero = 0, disagree = 0, asym = 0, degenerate_seen = 0;
#pragma omp parallel for reduction(+ : zero, disagree, asym, degenerate_seen) schedule(dynamic, 64)
  for (long long c = 0; c < n; ++c) {
    const double* q[5];
    int idx[5];
    for (int i = 0; i < np; ++i) {
      q[i] = set.point(std::size_t(c), i);
      idx[i] = int((c * 7919 + i * 104729) % 1000003);  // distinct, scrambled global indices
    }
    const int s = eval_sos(p, q, idx);
    const int ref = set.ref[std::size_t(c)];
    degenerate_seen += ref == 0;
    zero += s == 0;
    disagree += ref != 0 && s != ref;
    int perm[5] = {0, 1, 2, 3, 4};
    while (std::next_permutation(perm, perm + np)) {
      const double* pq[5];
      int pi[5];
      for (int i = 0; i < np; ++i) {
        pq[i] = q[perm[i]];
        pi[i] = idx[perm[i]];
      }
      asym += eval_sos(p, pq, pi) != permutation_parity(perm, np) * s;
    }
  }
  EXPECT_EQ(zero, 0);
  EXPECT_EQ(disagree, 0);
  EXPECT_EQ(asym, 0);
  EXPECT_GT(degenerate_seen, n / 10);  // the ties are really exercised
}

TEST_P(SosInvariants, RepeatedIndexIsZero) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {2, 0, 0}, d[3] = {3, 0, 0};
  const double* q[5] = {a, b, c, d, a};
  const int idx[5] = {4, 1, 2, 3, 4};
  const int np = pred_points(GetParam());
  const double* last[5];
  int lidx[5];
  for (int i = 0; i < np; ++i) {
    last[i] = q[5 - np + i];
    lidx[i] = idx[5 - np + i];
  }
  last[0] = last[np - 1];
  lidx[0] = lidx[np - 1];
  EXPECT_EQ(eval_sos(GetParam(), last, lidx), 0);
}

INSTANTIATE_TEST_SUITE_P(All, SosInvariants,
                         ::testing::Values(Pred::Orient2d, Pred::Incircle, Pred::Orient3d,
                                           Pred::Insphere),
                         [](const auto& info) { return std::string(pred_name(info.param)); });

// Brute-force Delaunay triangulation of a point set with the SoS predicates: a simplex (with
// positive orientation) is kept when no other point is inside its circumball. A consistent
// perturbation makes these simplices a triangulation of the convex hull: every facet is
// shared by two kept simplices on opposite sides or lies on the hull, and the volumes add
// up to the hull volume.
TEST(SosConsistency, DelaunayOfSquareLatticeIsATriangulation) {
  std::vector<std::array<double, 2>> pts;
  for (int y = 0; y < 5; ++y)
    for (int x = 0; x < 5; ++x) pts.push_back({double(x), double(y)});
  const int n = int(pts.size());
  std::vector<std::array<int, 3>> tris;
  double area2 = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        std::array<int, 3> t = {i, j, k};
        if (pred::orient2d_sos(pts[i].data(), pts[j].data(), pts[k].data(), i, j, k) < 0)
          std::swap(t[1], t[2]);
        bool empty = true;
        for (int l = 0; l < n && empty; ++l) {
          if (l == i || l == j || l == k) continue;
          empty = pred::incircle_sos(pts[t[0]].data(), pts[t[1]].data(), pts[t[2]].data(),
                                     pts[l].data(), t[0], t[1], t[2], l) < 0;
        }
        if (!empty) continue;
        tris.push_back(t);
        area2 += pred::orient2d(pts[t[0]].data(), pts[t[1]].data(), pts[t[2]].data());
      }
  EXPECT_EQ(area2, 2.0 * 16.0);  // twice the area of the 4 x 4 square, exactly
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : tris)
    for (int e = 0; e < 3; ++e) ++directed[{t[e], t[(e + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << edge.first << "-" << edge.second;
    const bool twin = directed.count({edge.second, edge.first}) > 0;
    const auto& a = pts[edge.first];
    const auto& b = pts[edge.second];
    const bool on_hull = (a[0] == b[0] && (a[0] == 0 || a[0] == 4)) ||
                         (a[1] == b[1] && (a[1] == 0 || a[1] == 4));
    EXPECT_TRUE(twin || on_hull) << edge.first << "-" << edge.second;
  }
}

TEST(SosConsistency, DelaunayOfCubicLatticeIsATetrahedralization) {
  std::vector<std::array<double, 3>> pts;
  for (int z = 0; z < 2; ++z)
    for (int y = 0; y < 3; ++y)
      for (int x = 0; x < 3; ++x) pts.push_back({double(x), double(y), double(z)});
  const int n = int(pts.size());
  std::vector<std::array<int, 4>> tets;
  double vol6 = 0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k)
        for (int m = k + 1; m < n; ++m) {
          std::array<int, 4> t = {i, j, k, m};
          if (pred::orient3d_sos(pts[i].data(), pts[j].data(), pts[k].data(), pts[m].data(), i,
                                 j, k, m) < 0)
            std::swap(t[2], t[3]);
          bool empty = true;
          for (int l = 0; l < n && empty; ++l) {
            if (l == i || l == j || l == k || l == m) continue;
            empty = pred::insphere_sos(pts[t[0]].data(), pts[t[1]].data(), pts[t[2]].data(),
                                       pts[t[3]].data(), pts[l].data(), t[0], t[1], t[2], t[3],
                                       l) < 0;
          }
          if (!empty) continue;
          tets.push_back(t);
          vol6 += pred::orient3d(pts[t[0]].data(), pts[t[1]].data(), pts[t[2]].data(),
                                 pts[t[3]].data());
        }
  EXPECT_EQ(vol6, 6.0 * 4.0);  // the 2 x 2 x 1 box, exactly
  // Oriented faces: each face of a kept tet appears once with this orientation; its reverse
  // appears in the neighbour unless the face lies on the box boundary.
  std::map<std::array<int, 3>, int> faces;
  auto key = [](int a, int b, int c) {
    std::array<int, 3> f = {a, b, c};
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    return f;
  };
  for (const auto& t : tets) {
    // The boundary of the oriented simplex, all faces reversed alike.
    ++faces[key(t[0], t[1], t[2])];
    ++faces[key(t[0], t[3], t[1])];
    ++faces[key(t[1], t[3], t[2])];
    ++faces[key(t[0], t[2], t[3])];
  }
  for (const auto& [f, count] : faces) {
    EXPECT_EQ(count, 1);
    const bool twin = faces.count(key(f[0], f[2], f[1])) > 0;
    bool boundary = false;
    for (int axis = 0; axis < 3; ++axis) {
      const double v = pts[f[0]][axis];
      const double lim = axis == 2 ? 1 : 2;
      if ((v == 0 || v == lim) && pts[f[1]][axis] == v && pts[f[2]][axis] == v) boundary = true;
    }
    EXPECT_TRUE(twin || boundary) << f[0] << " " << f[1] << " " << f[2];
  }
}

}  // namespace
}  // namespace gdr::test
