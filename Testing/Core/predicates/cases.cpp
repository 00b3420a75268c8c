#include "cases.h"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <random>

namespace gdr::test {

const char* pred_name(Pred p) {
  switch (p) {
    case Pred::Orient2d: return "orient2d";
    case Pred::Incircle: return "incircle";
    case Pred::Orient3d: return "orient3d";
    case Pred::Insphere: return "insphere";
    case Pred::DiametralCircle: return "in_diametral_circle";
    default: return "in_diametral_sphere";
  }
}

namespace {

using Rng = std::mt19937_64;

long long uniform_int(Rng& rng, long long lo, long long hi) {
  return std::uniform_int_distribution<long long>(lo, hi)(rng);
}

double uniform(Rng& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

// Integer points on the circle x^2 + y^2 = R^2 (R = 5^2 * 13 * 17 has 180 of them).
const std::vector<std::array<long long, 2>>& circle_points() {
  static const std::vector<std::array<long long, 2>> pts = [] {
    const long long r = 5525;
    std::vector<std::array<long long, 2>> out;
    for (long long x = -r; x <= r; ++x) {
      const long long y2 = r * r - x * x;
      const long long y = std::llround(std::sqrt(double(y2)));
      if (y * y != y2) continue;
      out.push_back({x, y});
      if (y != 0) out.push_back({x, -y});
    }
    return out;
  }();
  return pts;
}

// Integer points on the sphere x^2 + y^2 + z^2 = R^2.
const std::vector<std::array<long long, 3>>& sphere_points() {
  static const std::vector<std::array<long long, 3>> pts = [] {
    const long long r = 105;
    std::vector<std::array<long long, 3>> out;
    for (long long x = -r; x <= r; ++x)
      for (long long y = -r; y <= r; ++y) {
        const long long z2 = r * r - x * x - y * y;
        if (z2 < 0) continue;
        const long long z = std::llround(std::sqrt(double(z2)));
        if (z * z != z2) continue;
        out.push_back({x, y, z});
        if (z != 0) out.push_back({x, y, -z});
      }
    return out;
  }();
  return pts;
}

// An exactly degenerate configuration with integer coordinates (< 2^40, exact in doubles).
void lattice_case(Pred p, Rng& rng, double* out) {
  const int np = pred_points(p);
  const int dim = pred_dim(p);
  long long off[3];
  const int bits = int(uniform_int(rng, 0, 30));
  for (int k = 0; k < 3; ++k) off[k] = uniform_int(rng, -(1LL << bits), 1LL << bits);
  switch (p) {
    case Pred::Orient2d: {  // collinear lattice points
      const long long dx = uniform_int(rng, -50, 50), dy = uniform_int(rng, -50, 50);
      for (int i = 0; i < np; ++i) {
        const long long t = uniform_int(rng, -1000, 1000);
        out[i * 2] = double(off[0] + t * dx);
        out[i * 2 + 1] = double(off[1] + t * dy);
      }
      break;
    }
    case Pred::Orient3d: {  // coplanar lattice points
      long long u[3], v[3];
      for (int k = 0; k < 3; ++k) {
        u[k] = uniform_int(rng, -30, 30);
        v[k] = uniform_int(rng, -30, 30);
      }
      for (int i = 0; i < np; ++i) {
        const long long s = uniform_int(rng, -100, 100), t = uniform_int(rng, -100, 100);
        for (int k = 0; k < 3; ++k) out[i * 3 + k] = double(off[k] + s * u[k] + t * v[k]);
      }
      break;
    }
    case Pred::Incircle: {  // cocircular: Pythagorean points on one circle
      const auto& c = circle_points();
      for (int i = 0; i < np; ++i) {
        const auto& q = c[std::size_t(uniform_int(rng, 0, static_cast<long long>(c.size()) - 1))];
        out[i * 2] = double(off[0] + q[0]);
        out[i * 2 + 1] = double(off[1] + q[1]);
      }
      break;
    }
    case Pred::Insphere: {  // cospherical: integer points on one sphere
      const auto& s = sphere_points();
      for (int i = 0; i < np; ++i) {
        const auto& q = s[std::size_t(uniform_int(rng, 0, static_cast<long long>(s.size()) - 1))];
        for (int k = 0; k < 3; ++k) out[i * 3 + k] = double(off[k] + q[k]);
      }
      break;
    }
    default: {  // p on the diametral ball of ab: (a - p) orthogonal to (b - p)
      long long u[3] = {0, 0, 0}, v[3] = {0, 0, 0};
      for (int k = 0; k < dim; ++k) u[k] = uniform_int(rng, -1000, 1000);
      if (dim == 2) {
        const long long m = uniform_int(rng, -5, 5);
        v[0] = -m * u[1];
        v[1] = m * u[0];
      } else {
        long long w[3];
        for (int k = 0; k < 3; ++k) w[k] = uniform_int(rng, -30, 30);
        v[0] = u[1] * w[2] - u[2] * w[1];
        v[1] = u[2] * w[0] - u[0] * w[2];
        v[2] = u[0] * w[1] - u[1] * w[0];
      }
      for (int k = 0; k < dim; ++k) {
        out[k] = double(off[k] + u[k]);
        out[dim + k] = double(off[k] + v[k]);
        out[2 * dim + k] = double(off[k]);
      }
      break;
    }
  }
}

void unit_vector(Rng& rng, int dim, double* u) {
  std::normal_distribution<double> g;
  double n2 = 0;
  do {
    n2 = 0;
    for (int k = 0; k < dim; ++k) {
      u[k] = g(rng);
      n2 += u[k] * u[k];
    }
  } while (n2 < 1e-6);
  for (int k = 0; k < dim; ++k) u[k] /= std::sqrt(n2);
}

// A nearly degenerate configuration built with rounded arithmetic (its exact sign is anything).
void rounded_case(Pred p, Rng& rng, double* out) {
  const int np = pred_points(p);
  const int dim = pred_dim(p);
  double c[3], u[3], v[3];
  for (int k = 0; k < 3; ++k) {
    c[k] = uniform(rng, -1, 1);
    u[k] = uniform(rng, -1, 1);
    v[k] = uniform(rng, -1, 1);
  }
  switch (p) {
    case Pred::Orient2d:
    case Pred::Orient3d:  // points on a rounded line / plane (slivers when s, t are close)
      for (int i = 0; i < np; ++i) {
        const double s = uniform(rng, -1, 2), t = p == Pred::Orient3d ? uniform(rng, -1, 2) : 0.0;
        for (int k = 0; k < dim; ++k) out[i * dim + k] = c[k] + s * u[k] + t * v[k];
      }
      break;
    case Pred::Incircle:
    case Pred::Insphere: {  // points on a rounded circle / sphere
      const double r = uniform(rng, 0.01, 1);
      for (int i = 0; i < np; ++i) {
        double w[3];
        unit_vector(rng, dim, w);
        for (int k = 0; k < dim; ++k) out[i * dim + k] = c[k] + r * w[k];
      }
      break;
    }
    default: {  // p on the rounded diametral ball of ab
      double w[3], r2 = 0;
      for (int k = 0; k < dim; ++k) {
        out[k] = c[k];
        out[dim + k] = u[k];
        r2 += (u[k] - c[k]) * (u[k] - c[k]);
      }
      unit_vector(rng, dim, w);
      for (int k = 0; k < dim; ++k)
        out[2 * dim + k] = 0.5 * (c[k] + u[k]) + 0.5 * std::sqrt(r2) * w[k];
      break;
    }
  }
}

// Moves a few nonzero coordinates by 1 to 3 ulps.
void perturb(Rng& rng, int n, double* x) {
  bool any = std::all_of(x, x + n, [](double v) { return v == 0.0; });
  while (!any)
    for (int i = 0; i < n; ++i) {
      if (x[i] == 0.0 || uniform_int(rng, 0, 3) != 0) continue;  // keep zeros in range
      any = true;
      const double dir = uniform_int(rng, 0, 1) ? INFINITY : -INFINITY;
      for (long long k = uniform_int(rng, 1, 3); k > 0; --k) x[i] = std::nextafter(x[i], dir);
    }
}

template <class T>
int det_sign(Pred p, T v[5][3]) {
  switch (p) {
    case Pred::Orient2d: {
      const T acx = v[0][0] - v[2][0], acy = v[0][1] - v[2][1];
      const T bcx = v[1][0] - v[2][0], bcy = v[1][1] - v[2][1];
      return sgn(T(acx * bcy - acy * bcx));
    }
    case Pred::Incircle: {
      T d[3][3];
      for (int i = 0; i < 3; ++i) {
        d[i][0] = v[i][0] - v[3][0];
        d[i][1] = v[i][1] - v[3][1];
        d[i][2] = d[i][0] * d[i][0] + d[i][1] * d[i][1];
      }
      const T det = d[0][0] * (d[1][1] * d[2][2] - d[2][1] * d[1][2]) -
                    d[1][0] * (d[0][1] * d[2][2] - d[2][1] * d[0][2]) +
                    d[2][0] * (d[0][1] * d[1][2] - d[1][1] * d[0][2]);
      return sgn(det);
    }
    case Pred::Orient3d: {
      T d[3][3];
      for (int i = 0; i < 3; ++i)
        for (int k = 0; k < 3; ++k) d[i][k] = v[i][k] - v[3][k];
      const T det = d[0][0] * (d[1][1] * d[2][2] - d[2][1] * d[1][2]) -
                    d[1][0] * (d[0][1] * d[2][2] - d[2][1] * d[0][2]) +
                    d[2][0] * (d[0][1] * d[1][2] - d[1][1] * d[0][2]);
      return sgn(det);
    }
    case Pred::Insphere: {
      T d[4][4];
      for (int i = 0; i < 4; ++i) {
        for (int k = 0; k < 3; ++k) d[i][k] = v[i][k] - v[4][k];
        d[i][3] = d[i][0] * d[i][0] + d[i][1] * d[i][1] + d[i][2] * d[i][2];
      }
      // Laplace along the lift column over the 3x3 minors of the xyz columns.
      T det = 0;
      for (int i = 0; i < 4; ++i) {
        const T* r[3];
        for (int j = 0, m = 0; j < 4; ++j)
          if (j != i) r[m++] = d[j];
        const T m3 = r[0][0] * (r[1][1] * r[2][2] - r[2][1] * r[1][2]) -
                     r[1][0] * (r[0][1] * r[2][2] - r[2][1] * r[0][2]) +
                     r[2][0] * (r[0][1] * r[1][2] - r[1][1] * r[0][2]);
        if ((i + 3) % 2 == 0)
          det += d[i][3] * m3;
        else
          det -= d[i][3] * m3;
      }
      return sgn(det);
    }
    default: {
      const int dim = pred_dim(p);
      T dot = 0;
      for (int k = 0; k < dim; ++k) dot += (v[0][k] - v[2][k]) * (v[1][k] - v[2][k]);
      return -sgn(dot);
    }
  }
}

}  // namespace

int reference_sign(Pred p, const double* const* q) {
  const int np = pred_points(p), dim = pred_dim(p);
  int emin = INT_MAX;
  for (int i = 0; i < np; ++i)
    for (int k = 0; k < dim; ++k) {
      if (q[i][k] == 0.0) continue;
      int e;
      std::frexp(q[i][k], &e);
      emin = std::min(emin, e - 53);
    }
  mpz_class v[5][3];
  for (int i = 0; i < np; ++i)
    for (int k = 0; k < dim; ++k) {
      if (q[i][k] == 0.0) continue;
      int e;
      const double f = std::frexp(q[i][k], &e);
      v[i][k] = static_cast<long>(std::ldexp(f, 53));  // exact 53-bit integer mantissa
      mpz_mul_2exp(v[i][k].get_mpz_t(), v[i][k].get_mpz_t(), e - 53 - emin);
    }
  return det_sign(p, v);
}

int rational_sign(Pred p, const double* const* q) {
  mpq_class v[5][3];
  for (int i = 0; i < pred_points(p); ++i)
    for (int k = 0; k < pred_dim(p); ++k) v[i][k] = q[i][k];
  return det_sign(p, v);
}

void compute_reference(CaseSet& set) {
  const long long n = static_cast<long long>(set.size());
  set.ref.assign(std::size_t(n), 0);
#pragma omp parallel for schedule(dynamic, 4096)
  for (long long c = 0; c < n; ++c) {
    const double* q[5];
    for (int i = 0; i < set.npts; ++i) q[i] = set.point(std::size_t(c), i);
    set.ref[std::size_t(c)] = reference_sign(set.pred, q);
  }
}

CaseSet random_cases(Pred p, std::size_t n, std::uint64_t seed) {
  CaseSet s;
  s.pred = p;
  s.npts = pred_points(p);
  s.dim = pred_dim(p);
  s.coords.resize(n * s.npts * s.dim);
  s.degenerate.assign(n, 0);
  Rng rng(seed);
  for (double& x : s.coords) x = uniform(rng, -1, 1);
  return s;
}

CaseSet adversarial_cases(Pred p, std::size_t n, std::uint64_t seed) {
  CaseSet s;
  s.pred = p;
  s.npts = pred_points(p);
  s.dim = pred_dim(p);
  const int per = s.npts * s.dim;
  s.coords.resize(n * per);
  s.degenerate.assign(n, 0);
  Rng rng(seed);
  for (std::size_t c = 0; c < n; ++c) {
    double* x = &s.coords[c * per];
    const int family = int(c % 4);
    if (family == 2) {
      rounded_case(p, rng, x);
      // Cancellation can leave tiny values; flush them so scaled cases stay in range.
      for (int k = 0; k < per; ++k)
        if (std::fabs(x[k]) < 0x1p-30) x[k] = 0.0;
    } else {
      lattice_case(p, rng, x);
      if (family == 3) {  // a duplicated point
        const int i = int(uniform_int(rng, 0, s.npts - 1));
        const int j = (i + int(uniform_int(rng, 1, s.npts - 1))) % s.npts;
        std::copy(x + j * s.dim, x + (j + 1) * s.dim, x + i * s.dim);
      }
    }
    // Scale by an exact power of two: unit, huge (~1e30) or tiny (~1e-30 and below).
    const long long mode = uniform_int(rng, 0, 3);
    const int shift = mode <= 1 ? 0 : mode == 2 ? 100 : -110;
    for (int k = 0; k < per; ++k) x[k] = std::ldexp(x[k], shift);
    const bool exact = family != 2;
    if (uniform_int(rng, 0, 1)) {
      perturb(rng, per, x);
    } else if (exact) {
      s.degenerate[c] = 1;
    }
  }
  return s;
}

}  // namespace gdr::test
