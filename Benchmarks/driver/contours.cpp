// Generated contour-like PSLGs, and the small geometry the driver needs about its inputs.
//
// Each cell of a g x g grid holds one "hill": J nested closed curves r_k(phi) = R t_k (1 + a h)
// with h(phi, t) = sum_m w_m sin(m phi + p_m + v_m t), sum w_m = 1, |v_m| <= 1, a = 0.3. Then
// d/dt [t (1 + a h)] >= 1 - 2a > 0, so at every sampled angle the radius grows strictly from
// one curve to the next. All curves of a cell are sampled at the same n angles, and a chord
// between two samples moves outward when either end does, so the polygons are strictly nested
// and never cross; each is star-shaped about its centre, hence simple.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>

#include "bench.h"
#include "gdr/error.h"

namespace gdr_bench {

bool is_generator_spec(const std::string& input) { return input.rfind("gen:", 0) == 0; }

gdr::Pslg generate_pslg(const std::string& spec) {
  std::istringstream parts(spec);
  std::string part, kind;
  std::getline(parts, part, ':');  // "gen"
  std::getline(parts, kind, ':');
  if (kind != "contours") {
    throw gdr::Error(gdr::Status::InvalidInput,
                     "unknown generator '" + kind + "' in '" + spec + "' (known: contours)");
  }
  double segments = 1e6, amplitude = 0.3;
  unsigned seed = 1;
  while (std::getline(parts, part, ':')) {
    const auto eq = part.find('=');
    const std::string key = part.substr(0, eq);
    const std::string value = eq == std::string::npos ? "" : part.substr(eq + 1);
    if (key == "segments") segments = std::atof(value.c_str());
    else if (key == "seed") seed = static_cast<unsigned>(std::atol(value.c_str()));
    else if (key == "amplitude") amplitude = std::atof(value.c_str());
    else throw gdr::Error(gdr::Status::InvalidInput, "unknown key '" + key + "' in '" + spec + "'");
  }
  if (!(segments >= 16) || !(amplitude >= 0 && amplitude <= 0.45)) {
    throw gdr::Error(gdr::Status::InvalidInput,
                     "'" + spec + "': need segments >= 16 and 0 <= amplitude <= 0.45");
  }

  const int grid = std::max(1, static_cast<int>(std::lround(std::sqrt(segments / 60000.0))));
  const double per_cell = segments / (grid * grid);
  const int curves = std::max(2, static_cast<int>(std::lround(std::sqrt(per_cell / 16.0))));
  const int samples = std::max(8, static_cast<int>(per_cell / curves));
  const double pi = 3.14159265358979323846;
  const double jitter = 0.02;
  // Largest radius is R (1 + a) plus the centre's jitter; keep it inside the half cell.
  const double radius = (0.49 - jitter) / (1.0 + amplitude);
  const int harmonics = 6;

  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  gdr::Pslg pslg;
  pslg.points.reserve(static_cast<std::size_t>(grid) * grid * curves * samples + 4);
  pslg.segments.reserve(pslg.points.capacity());
  for (int cy = 0; cy < grid; ++cy) {
    for (int cx = 0; cx < grid; ++cx) {
      const double ox = cx + 0.5 + jitter * (2 * unit(rng) - 1);
      const double oy = cy + 0.5 + jitter * (2 * unit(rng) - 1);
      double w[harmonics], phase[harmonics], drift[harmonics], total = 0;
      for (int m = 0; m < harmonics; ++m) {
        w[m] = unit(rng) / (m + 1);
        phase[m] = 2 * pi * unit(rng);
        drift[m] = 2 * unit(rng) - 1;
        total += w[m];
      }
      for (int m = 0; m < harmonics; ++m) w[m] /= total;
      for (int k = 0; k < curves; ++k) {
        const double t = 0.15 + 0.85 * (k + 1) / curves;
        const int first = static_cast<int>(pslg.points.size());
        for (int i = 0; i < samples; ++i) {
          const double phi = 2 * pi * i / samples;
          double h = 0;
          for (int m = 0; m < harmonics; ++m) h += w[m] * std::sin((m + 2) * phi + phase[m] + drift[m] * t);
          const double r = radius * t * (1 + amplitude * h);
          pslg.points.push_back({ox + r * std::cos(phi), oy + r * std::sin(phi)});
          pslg.segments.push_back({first + i, first + (i + 1) % samples});
        }
      }
    }
  }
  const int corner = static_cast<int>(pslg.points.size());
  pslg.points.push_back({0, 0});
  pslg.points.push_back({double(grid), 0});
  pslg.points.push_back({double(grid), double(grid)});
  pslg.points.push_back({0, double(grid)});
  for (int i = 0; i < 4; ++i) pslg.segments.push_back({corner + i, corner + (i + 1) % 4});
  return pslg;
}

void write_poly(const std::string& path, const gdr::Pslg& pslg) {
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw gdr::Error(gdr::Status::IoError, path + ": cannot write");
  std::fprintf(f, "%zu 2 0 0\n", pslg.points.size());
  for (std::size_t i = 0; i < pslg.points.size(); ++i)
    std::fprintf(f, "%zu %.17g %.17g\n", i + 1, pslg.points[i].x, pslg.points[i].y);
  std::fprintf(f, "%zu 0\n", pslg.segments.size());
  for (std::size_t i = 0; i < pslg.segments.size(); ++i)
    std::fprintf(f, "%zu %d %d\n", i + 1, pslg.segments[i][0] + 1, pslg.segments[i][1] + 1);
  std::fprintf(f, "%zu\n", pslg.holes.size());
  for (std::size_t i = 0; i < pslg.holes.size(); ++i)
    std::fprintf(f, "%zu %.17g %.17g\n", i + 1, pslg.holes[i].x, pslg.holes[i].y);
  const bool ok = std::fclose(f) == 0;
  if (!ok) throw gdr::Error(gdr::Status::IoError, path + ": write failed");
}

double convex_hull_area(const std::vector<gdr::Point2>& input) {
  std::vector<gdr::Point2> p = input;
  std::sort(p.begin(), p.end(), [](const gdr::Point2& a, const gdr::Point2& b) {
    return a.x < b.x || (a.x == b.x && a.y < b.y);
  });
  if (p.size() < 3) return 0;
  auto cross = [](const gdr::Point2& o, const gdr::Point2& a, const gdr::Point2& b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<gdr::Point2> hull(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {  // lower hull
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, lower = k + 1; i-- > 0;) {  // upper hull
    while (k >= lower && cross(hull[k - 2], hull[k - 1], p[i]) <= 0) --k;
    hull[k++] = p[i];
  }
  double area2 = 0;
  for (std::size_t i = 0; i + 1 < k; ++i) area2 += hull[i].x * hull[i + 1].y - hull[i + 1].x * hull[i].y;
  return std::abs(area2) / 2;
}

double smallest_input_angle(const gdr::Pslg& pslg) {
  std::vector<std::vector<double>> directions(pslg.points.size());
  for (const auto& seg : pslg.segments) {
    const gdr::Point2& a = pslg.points[seg[0]];
    const gdr::Point2& b = pslg.points[seg[1]];
    directions[seg[0]].push_back(std::atan2(b.y - a.y, b.x - a.x));
    directions[seg[1]].push_back(std::atan2(a.y - b.y, a.x - b.x));
  }
  const double pi = 3.14159265358979323846;
  double smallest = pi;
  for (auto& d : directions) {
    if (d.size() < 2) continue;
    std::sort(d.begin(), d.end());
    for (std::size_t i = 0; i + 1 < d.size(); ++i) smallest = std::min(smallest, d[i + 1] - d[i]);
    smallest = std::min(smallest, d.front() + 2 * pi - d.back());
  }
  return smallest * 180 / pi;
}

}  // namespace gdr_bench
