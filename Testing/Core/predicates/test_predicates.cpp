// Signs of every predicate against exact GMP arithmetic, on random and adversarial inputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cases.h"

namespace gdr::test {
namespace {

constexpr std::size_t kRandom = 200000;
constexpr std::size_t kAdversarial = 1000000;

struct Outcome {
  std::size_t mismatches = 0;
  std::size_t exact_stage = 0;
  std::size_t first_bad = 0;
};

Outcome check(const CaseSet& set) {
  const long long n = static_cast<long long>(set.size());
  std::size_t bad = 0, exact = 0;
  long long first = n;
#pragma omp parallel for reduction(+ : bad, exact) reduction(min : first) schedule(static)
  for (long long c = 0; c < n; ++c) {
    const double* q[5];
    for (int i = 0; i < set.npts; ++i) q[i] = set.point(std::size_t(c), i);
    int stage = 0;
    const int s = eval_sign(set.pred, q, &stage);
    exact += stage == 2;
    if (s != set.ref[std::size_t(c)]) {
      ++bad;
      first = std::min(first, c);
    }
  }
  return {bad, exact, std::size_t(first)};
}

std::string describe(const CaseSet& set, std::size_t c) {
  std::string s;
  char buf[64];
  for (int i = 0; i < set.npts; ++i) {
    s += "(";
    for (int k = 0; k < set.dim; ++k) {
      std::snprintf(buf, sizeof buf, "%s%.17g", k ? ", " : "", set.point(c, i)[k]);
      s += buf;
    }
    s += ") ";
  }
  return s;
}

class PredicateSigns : public ::testing::TestWithParam<Pred> {};

TEST_P(PredicateSigns, RandomInputsMatchGmp) {
  CaseSet set = random_cases(GetParam(), kRandom, 11 + int(GetParam()));
  compute_reference(set);
  const Outcome o = check(set);
  std::printf("[stats] %s random: %zu cases, exact stage %.4f%%\n", pred_name(GetParam()),
              set.size(), 100.0 * double(o.exact_stage) / double(set.size()));
  EXPECT_EQ(o.mismatches, 0u) << "first wrong case: " << describe(set, o.first_bad);
}

TEST_P(PredicateSigns, AdversarialInputsMatchGmp) {
  CaseSet set = adversarial_cases(GetParam(), kAdversarial, 101 + int(GetParam()));
  compute_reference(set);
  const Outcome o = check(set);
  std::size_t zeros = 0;
  for (int r : set.ref) zeros += r == 0;
  std::printf("[stats] %s adversarial: %zu cases (%zu exactly degenerate), exact stage %.2f%%\n",
              pred_name(GetParam()), set.size(), zeros,
              100.0 * double(o.exact_stage) / double(set.size()));
  EXPECT_EQ(o.mismatches, 0u) << "first wrong case: " << describe(set, o.first_bad);
  // The generator must really produce ties and both signs, or the test proves little.
  EXPECT_GT(zeros, set.size() / 10);
  EXPECT_GT(std::count(set.ref.begin(), set.ref.end(), 1), std::ptrdiff_t(set.size() / 10));
  EXPECT_GT(std::count(set.ref.begin(), set.ref.end(), -1), std::ptrdiff_t(set.size() / 10));
}

// The scaled-integer reference is checked against plain rational determinants.
TEST_P(PredicateSigns, IntegerReferenceAgreesWithRationals) {
  CaseSet set = adversarial_cases(GetParam(), 4000, 7 + int(GetParam()));
  CaseSet rnd = random_cases(GetParam(), 1000, 8 + int(GetParam()));
  for (const CaseSet* s : {&set, &rnd})
    for (std::size_t c = 0; c < s->size(); ++c) {
      const double* q[5];
      for (int i = 0; i < s->npts; ++i) q[i] = s->point(c, i);
      ASSERT_EQ(reference_sign(s->pred, q), rational_sign(s->pred, q)) << describe(*s, c);
    }
}

INSTANTIATE_TEST_SUITE_P(All, PredicateSigns,
                         ::testing::Values(Pred::Orient2d, Pred::Incircle, Pred::Orient3d,
                                           Pred::Insphere, Pred::DiametralCircle,
                                           Pred::DiametralSphere),
                         [](const auto& info) { return std::string(pred_name(info.param)); });

TEST(Predicates, Conventions) {
  const double a[3] = {0, 0, 0}, b[3] = {1, 0, 0}, c[3] = {0, 1, 0};
  const double up[3] = {0.2, 0.2, 1}, mid[3] = {0.3, 0.3, 0}, far[3] = {3, 3, 0};
  EXPECT_GT(pred::orient2d(a, b, c), 0);  // counter-clockwise
  EXPECT_LT(pred::orient2d(a, c, b), 0);
  EXPECT_GT(pred::incircle(a, b, c, mid), 0);
  EXPECT_LT(pred::incircle(a, b, c, far), 0);
  EXPECT_LT(pred::orient3d(a, b, c, up), 0);  // a, b, c ccw seen from above, d above
  const double down[3] = {0.2, 0.2, -1};
  EXPECT_GT(pred::orient3d(a, b, c, down), 0);
  ASSERT_GT(pred::orient3d(a, b, c, down), 0);
  const double in[3] = {0.2, 0.2, -0.2}, out[3] = {5, 5, 5};
  EXPECT_GT(pred::insphere(a, b, c, down, in), 0);
  EXPECT_LT(pred::insphere(a, b, c, down, out), 0);
  const double p[2] = {0.5, 0.1}, q[2] = {0.5, 0.5}, r[2] = {0.5, 0.9};
  const double s0[2] = {0, 0}, s1[2] = {1, 0};
  EXPECT_EQ(pred::in_diametral_circle(s0, s1, p), 1);
  EXPECT_EQ(pred::in_diametral_circle(s0, s1, q), 0);
  EXPECT_EQ(pred::in_diametral_circle(s0, s1, r), -1);
  const double t[3] = {0.5, 0.1, 0.1};
  EXPECT_EQ(pred::in_diametral_sphere(a, b, t), 1);
  EXPECT_EQ(pred::in_diametral_sphere(a, b, up), -1);
}

TEST(Predicates, StageReportAndFilteredVariants) {
  const double a[2] = {0, 0}, b[2] = {1, 0}, c[2] = {0, 1};
  int stage = 0;
  EXPECT_GT(pred::orient2d(a, b, c, &stage), 0);
  EXPECT_EQ(stage, 1);
  EXPECT_GT(pred::orient2d_filtered(a, b, c), 0);
  // Shewchuk's classic: points near y = x with a sub-ulp offset need the exact stage.
  const double p[2] = {0.5, 0.5}, q[2] = {12, 12}, r[2] = {24, 24};
  const double s[2] = {std::nextafter(0.5, 1.0), 0.5};
  EXPECT_EQ(pred::orient2d(p, q, r, &stage), 0);
  EXPECT_EQ(stage, 2);
  EXPECT_EQ(pred::orient2d_filtered(p, q, r), 0);
  EXPECT_LT(pred::orient2d(s, q, r, &stage), 0);
  EXPECT_EQ(stage, 2);
  const double u[3] = {0, 0, 0}, v[3] = {1, 0, 0}, w[3] = {0, 1, 0}, x[3] = {1, 1, 0};
  const double y[3] = {0, 0, 1};
  EXPECT_EQ(pred::incircle_filtered(u, v, x, w), 0);
  EXPECT_EQ(pred::incircle(u, v, x, w), 0);
  EXPECT_EQ(pred::orient3d_filtered(u, v, w, x), 0);
  EXPECT_NE(pred::orient3d_filtered(u, v, w, y), 0);
  EXPECT_EQ(pred::insphere_filtered(u, v, w, y, x), 0);
}

// At the ends of the documented coordinate ranges (docs/predicates.md) every product stays
// exact: each case is rescaled so that its largest coordinate sits just below the upper end,
// or its smallest nonzero coordinate at the lower end.
TEST(Predicates, ExtremeMagnitudes) {
  struct Range {
    Pred pred;
    int lo, hi;  // nonzero |x| in [2^lo, 2^hi)
  };
  for (const Range& r : {Range{Pred::Orient2d, -485, 506}, Range{Pred::Incircle, -216, 252},
                         Range{Pred::Orient3d, -306, 337}, Range{Pred::Insphere, -162, 202},
                         Range{Pred::DiametralCircle, -485, 506},
                         Range{Pred::DiametralSphere, -485, 506}}) {
    for (bool top : {true, false}) {
      CaseSet set = adversarial_cases(r.pred, 20000, 5 + int(r.pred) + 10 * top);
      const int per = set.npts * set.dim;
      for (std::size_t c = 0; c < set.size(); ++c) {
        double* x = &set.coords[c * per];
        int emax = -100000, emin = 100000;
        for (int k = 0; k < per; ++k) {
          if (x[k] == 0.0) continue;
          int e;
          std::frexp(x[k], &e);
          emax = std::max(emax, e);
          emin = std::min(emin, e);
        }
        if (emax == -100000) continue;
        const int shift = top ? r.hi - emax : r.lo + 1 - emin;
        for (int k = 0; k < per; ++k) x[k] = std::ldexp(x[k], shift);
      }
      compute_reference(set);
      const Outcome o = check(set);
      EXPECT_EQ(o.mismatches, 0u) << pred_name(r.pred) << (top ? " top: " : " bottom: ")
                                  << describe(set, o.first_bad);
    }
  }
}

}  // namespace
}  // namespace gdr::test
