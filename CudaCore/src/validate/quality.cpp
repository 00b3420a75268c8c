// Element quality measures and their statistics (angles, radius-edge ratio, histograms).
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "gdr/validate.h"
#include "validate/vec3.h"

namespace gdr {
namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;
constexpr double kInf = std::numeric_limits<double>::infinity();

using detail::V3;
using detail::cross;
using detail::dot;
using detail::norm;
using detail::sub;

double angle_deg(double ux, double uy, double vx, double vy) {
  return std::atan2(std::fabs(ux * vy - uy * vx), ux * vx + uy * vy) * kDeg;
}

// Per-thread partial statistics, merged at the end.
struct Accumulator {
  std::size_t elements = 0, bad = 0;
  double min_a = kInf, max_a = -kInf, max_re = 0, sum_re = 0, measure = 0, bad_measure = 0;
  std::vector<std::size_t> histogram;
  explicit Accumulator(std::size_t bins) : histogram(bins, 0) {}
  void merge(const Accumulator& o) {
    elements += o.elements;
    bad += o.bad;
    min_a = std::min(min_a, o.min_a);
    max_a = std::max(max_a, o.max_a);
    max_re = std::max(max_re, o.max_re);
    sum_re += o.sum_re;
    measure += o.measure;
    bad_measure += o.bad_measure;
    for (std::size_t i = 0; i < histogram.size(); ++i) histogram[i] += o.histogram[i];
  }
  void bin(double deg) {
    const double b = std::floor(deg);
    const std::size_t i = b < 0 ? 0 : std::min(static_cast<std::size_t>(b), histogram.size() - 1);
    ++histogram[i];
  }
};

template <class Cell, class A, class Measure>
QualityStats run(std::size_t points, const std::vector<Cell, A>& cells, std::size_t bins,
                 Measure measure, bool dihedral) {
  Accumulator total(bins);
  const std::int64_t n = static_cast<std::int64_t>(cells.size());
#pragma omp parallel
  {
    Accumulator local(bins);
#pragma omp for schedule(static) nowait
    for (std::int64_t i = 0; i < n; ++i) {
      bool ok = true;
      for (int v : cells[i]) ok = ok && v >= 0 && static_cast<std::size_t>(v) < points;
      if (ok) measure(cells[i], local);  // elements with bad indices are the validator's business
    }
#pragma omp critical
    total.merge(local);
  }
  QualityStats q;
  q.elements = total.elements;
  if (total.elements) {
    (dihedral ? q.min_dihedral_deg : q.min_angle_deg) = total.min_a;
    (dihedral ? q.max_dihedral_deg : q.max_angle_deg) = total.max_a;
    q.max_radius_edge = total.max_re;
    q.mean_radius_edge = total.sum_re;  // a sum of re / elements: no overflow
  }
  q.bad_elements = total.bad;
  q.total_measure = total.measure;
  q.bad_measure_percent = total.measure > 0 ? 100.0 * total.bad_measure / total.measure : 0.0;
  q.histogram = std::move(total.histogram);
  return q;
}

}  // namespace

void triangle_angles(const Point2& a, const Point2& b, const Point2& c, double& min_deg,
                     double& max_deg) {
  const double A = angle_deg(b.x - a.x, b.y - a.y, c.x - a.x, c.y - a.y);
  const double B = angle_deg(c.x - b.x, c.y - b.y, a.x - b.x, a.y - b.y);
  const double C = angle_deg(a.x - c.x, a.y - c.y, b.x - c.x, b.y - c.y);
  min_deg = std::min({A, B, C});
  max_deg = std::max({A, B, C});
}

double triangle_area(const Point2& a, const Point2& b, const Point2& c) {
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
}

double triangle_radius_edge(const Point2& a, const Point2& b, const Point2& c) {
  const double la = std::hypot(b.x - c.x, b.y - c.y), lb = std::hypot(a.x - c.x, a.y - c.y),
               lc = std::hypot(a.x - b.x, a.y - b.y);
  const double area = std::fabs(triangle_area(a, b, c));
  const double shortest = std::min({la, lb, lc});
  if (area == 0 || shortest == 0) return kInf;
  return la * lb * lc / (4 * area) / shortest;  // circumradius R = abc / 4A
}

double tet_volume(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  return dot(sub(a, d), cross(sub(b, d), sub(c, d))) / 6.0;
}

double tet_radius_edge(const Point3& a, const Point3& b, const Point3& c, const Point3& d) {
  const V3 u = sub(a, d), v = sub(b, d), w = sub(c, d);
  const double det = dot(u, cross(v, w));
  const Point3* p[4] = {&a, &b, &c, &d};
  double shortest = kInf;
  for (int i = 0; i < 4; ++i)
    for (int j = i + 1; j < 4; ++j) shortest = std::min(shortest, norm(sub(*p[i], *p[j])));
  if (det == 0 || shortest == 0) return kInf;
  const V3 vw = cross(v, w), wu = cross(w, u), uv = cross(u, v);
  const double lu = dot(u, u), lv = dot(v, v), lw = dot(w, w);
  const V3 center{(lu * vw.x + lv * wu.x + lw * uv.x) / (2 * det),
                  (lu * vw.y + lv * wu.y + lw * uv.y) / (2 * det),
                  (lu * vw.z + lv * wu.z + lw * uv.z) / (2 * det)};
  return norm(center) / shortest;
}

void tet_dihedral_angles(const Point3& a, const Point3& b, const Point3& c, const Point3& d,
                         double angles_deg[6]) {
  const Point3* p[4] = {&a, &b, &c, &d};
  // n[k]: normal of the face opposite vertex k, pointing towards k.
  V3 n[4];
  for (int k = 0; k < 4; ++k) {
    const Point3& f0 = *p[(k + 1) % 4];
    const Point3& f1 = *p[(k + 2) % 4];
    const Point3& f2 = *p[(k + 3) % 4];
    n[k] = cross(sub(f1, f0), sub(f2, f0));
    if (dot(n[k], sub(*p[k], f0)) < 0) n[k] = {-n[k].x, -n[k].y, -n[k].z};
  }
  // The dihedral angle at edge (i,j) is between the faces opposite the other two vertices.
  static const int edge[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (int e = 0; e < 6; ++e) {
    int k = -1, l = -1;
    for (int v = 0; v < 4; ++v)
      if (v != edge[e][0] && v != edge[e][1]) (k < 0 ? k : l) = v;
    const double len = norm(n[k]) * norm(n[l]);
    const double cosine = len > 0 ? std::clamp(dot(n[k], n[l]) / len, -1.0, 1.0) : 1.0;
    angles_deg[e] = 180.0 - std::acos(cosine) * kDeg;
  }
}

TetQualityArrays tet_quality_arrays(const std::vector<Point3>& points,
                                    const std::vector<std::array<int, 4>>& tets) {
  const int nt = static_cast<int>(tets.size());
  TetQualityArrays q;
  q.radius_edge.resize(nt);
  q.min_dihedral.resize(nt);
  q.max_dihedral.resize(nt);
  q.volume.resize(nt);
  q.dihedral_histogram.assign(180, 0);
  double total = 0, min_d = 180, max_d = 0, max_re = 0;
#pragma omp parallel
  {
    std::vector<long long> hist(180, 0);
#pragma omp for reduction(+ : total) reduction(min : min_d) reduction(max : max_d, max_re)
    for (int t = 0; t < nt; ++t) {
      const auto& v = tets[t];
      const Point3 &a = points[v[0]], &b = points[v[1]], &c = points[v[2]], &d = points[v[3]];
      double angles[6];
      tet_dihedral_angles(a, b, c, d, angles);
      double lo = 180, hi = 0;
      for (double x : angles) {
        lo = std::min(lo, x);
        hi = std::max(hi, x);
        ++hist[std::min(179, std::max(0, static_cast<int>(x)))];
      }
      const double re = tet_radius_edge(a, b, c, d);
      q.radius_edge[t] = static_cast<float>(re);
      q.min_dihedral[t] = static_cast<float>(lo);
      q.max_dihedral[t] = static_cast<float>(hi);
      q.volume[t] = tet_volume(a, b, c, d);
      total += q.volume[t];
      min_d = std::min(min_d, lo);
      max_d = std::max(max_d, hi);
      if (std::isfinite(re)) max_re = std::max(max_re, re);
    }
#pragma omp critical
    for (int k = 0; k < 180; ++k) q.dihedral_histogram[k] += hist[k];
  }
  q.total_volume = total;
  q.min_dihedral_deg = nt ? min_d : 0;
  q.max_dihedral_deg = nt ? max_d : 0;
  q.max_radius_edge = max_re;
  return q;
}

// Statistics stay finite and agree with the mesher's at any scale: angles and radius-edge
// ratios on each triangle scaled by a power of two into [-2, 2] (exact, nothing overflows),
// areas summed at the mesh's own power-of-two scale and scaled back once. A flat triangle
// counts with the largest double as its radius-edge ratio.
QualityStats triangle_quality(const TriMesh& mesh, double min_angle_deg) {
  const auto& P = mesh.points;
  const auto exponent = [](double m) { return m > 0 && std::isfinite(m) ? -std::ilogb(m) : 0; };
  double largest = 0;
  for (const Point2& p : P) largest = std::max({largest, std::fabs(p.x), std::fabs(p.y)});
  const int mesh_k = exponent(largest);
  const double share = 1.0 / std::max<std::size_t>(1, mesh.triangles.size());
  const auto scaled = [](const Point2& p, int k) { return Point2{std::ldexp(p.x, k), std::ldexp(p.y, k)}; };
  QualityStats q = run(P.size(), mesh.triangles, 60,
             [&](const std::array<int, 3>& t, Accumulator& acc) {
               const int k = exponent(std::max({std::fabs(P[t[0]].x), std::fabs(P[t[0]].y),
                                                std::fabs(P[t[1]].x), std::fabs(P[t[1]].y),
                                                std::fabs(P[t[2]].x), std::fabs(P[t[2]].y)}));
               const Point2 a = scaled(P[t[0]], k), b = scaled(P[t[1]], k), c = scaled(P[t[2]], k);
               double lo, hi;
               triangle_angles(a, b, c, lo, hi);
               const double re = std::min(triangle_radius_edge(a, b, c), DBL_MAX);
               const double area = std::fabs(triangle_area(scaled(P[t[0]], mesh_k),
                                                           scaled(P[t[1]], mesh_k),
                                                           scaled(P[t[2]], mesh_k)));
               ++acc.elements;
               acc.min_a = std::min(acc.min_a, lo);
               acc.max_a = std::max(acc.max_a, hi);
               acc.max_re = std::max(acc.max_re, re);
               acc.sum_re += re * share;
               acc.measure += area;
               if (min_angle_deg > 0 && lo < min_angle_deg) ++acc.bad, acc.bad_measure += area;
               acc.bin(lo);
             },
             false);
  q.total_measure = std::ldexp(q.total_measure, -2 * mesh_k);
  return q;
}

QualityStats tet_quality(const TetMesh& mesh, double max_radius_edge) {
  const auto& P = mesh.points;
  const double share = 1.0 / std::max<std::size_t>(1, mesh.tets.size());
  return run(P.size(), mesh.tets, 180,
             [&](const std::array<int, 4>& t, Accumulator& acc) {
               double angles[6];
               tet_dihedral_angles(P[t[0]], P[t[1]], P[t[2]], P[t[3]], angles);
               const double re = tet_radius_edge(P[t[0]], P[t[1]], P[t[2]], P[t[3]]);
               const double volume = std::fabs(tet_volume(P[t[0]], P[t[1]], P[t[2]], P[t[3]]));
               ++acc.elements;
               for (double a : angles) {
                 acc.min_a = std::min(acc.min_a, a);
                 acc.max_a = std::max(acc.max_a, a);
                 acc.bin(a);
               }
               acc.max_re = std::max(acc.max_re, re);
               acc.sum_re += re * share;
               acc.measure += volume;
               if (max_radius_edge > 0 && re > max_radius_edge) ++acc.bad, acc.bad_measure += volume;
             },
             true);
}

}  // namespace gdr
