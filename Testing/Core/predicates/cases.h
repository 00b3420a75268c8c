// Test inputs for the predicates: random and adversarial point tuples with exact reference
// signs from GMP (no CUDA types: shared by the CPU and GPU tests).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "eval.h"

namespace gdr::test {

const char* pred_name(Pred p);

struct CaseSet {
  Pred pred = Pred::Orient2d;
  int npts = 0;
  int dim = 0;
  std::vector<double> coords;  // case-major: npts points of dim coordinates each
  std::vector<int> ref;        // exact sign per case (after compute_reference)
  std::vector<int> degenerate; // 1 where the case was built exactly degenerate, unperturbed

  std::size_t size() const { return coords.size() / (npts * dim); }
  const double* point(std::size_t c, int i) const { return &coords[(c * npts + i) * dim]; }
};

// Uniform coordinates in [-1, 1].
CaseSet random_cases(Pred p, std::size_t n, std::uint64_t seed);

// Exactly degenerate configurations (lattice lines/planes, integer points on circles and
// spheres, right angles), some perturbed by a few ulps, scaled to huge or tiny magnitudes,
// rounded near-degenerate configurations, duplicated points.
CaseSet adversarial_cases(Pred p, std::size_t n, std::uint64_t seed);

// Fills set.ref with exact signs: integer arithmetic (mpz) on the coordinates scaled by a
// common power of two, in parallel.
void compute_reference(CaseSet& set);

int reference_sign(Pred p, const double* const* q);  // mpz on scaled integers
int rational_sign(Pred p, const double* const* q);   // mpq determinant, independent check

}  // namespace gdr::test
