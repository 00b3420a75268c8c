// Generated closed surfaces for the 3D benchmarks, so that no large file is committed:
//   gen:surface:base=FILE:subdiv=K[:turn=1][:noise=S[:seed=N]]
//                                    midpoint subdivision of a closed surface, K times;
//                                    turn=1 then turns it (0.7 rad about z, 0.4 about x) and
//                                    rounds it to single precision, as a CAD part exported to
//                                    binary STL at an angle is; noise=S moves every point
//                                    along its normal by S mean edge lengths times a normal
//                                    deviate (seed N, default 1), as a raw scan's noise: its
//                                    triangles no longer meet nearly flat
//   gen:torus:triangles=N:bump=A     a bumpy torus of about N triangles
// Both are checked by the mesher's own surface checks when a case runs (an invalid surface
// is an error of that case, before anything is timed).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <sstream>
#include <unordered_map>

#include "bench.h"
#include "cdt3d/surfaces.h"
#include "gdr/error.h"
#include "gdr/io.h"

namespace gdr_bench {
namespace {

// The key=value parts after "gen:KIND:".
std::map<std::string, std::string> spec_parts(const std::string& spec, std::string& kind) {
  std::istringstream parts(spec);
  std::string part;
  std::getline(parts, part, ':');  // "gen"
  std::getline(parts, kind, ':');
  std::map<std::string, std::string> out;
  while (std::getline(parts, part, ':')) {
    const auto eq = part.find('=');
    if (eq == std::string::npos)
      throw gdr::Error(gdr::Status::InvalidInput, "'" + spec + "': expected key=value, got '" + part + "'");
    out[part.substr(0, eq)] = part.substr(eq + 1);
  }
  return out;
}

double spec_number(const std::map<std::string, std::string>& parts, const std::string& key,
                   double fallback, const std::string& spec) {
  const auto it = parts.find(key);
  if (it == parts.end()) return fallback;
  char* end = nullptr;
  const double v = std::strtod(it->second.c_str(), &end);
  if (it->second.empty() || *end != '\0')
    throw gdr::Error(gdr::Status::InvalidInput, "'" + spec + "': " + key + " is not a number");
  return v;
}

// Scanner-like noise (gen:surface's noise=S): each point moves along its area-weighted
// normal by `scale` mean edge lengths times a standard normal deviate (Box-Muller on
// mt19937, the same numbers with every standard library).
void add_normal_noise(gdr::Surface& s, double scale, unsigned seed) {
  std::vector<gdr::Point3> normal(s.points.size(), gdr::Point3{0, 0, 0});
  double edges = 0;
  for (const auto& t : s.triangles) {
    const gdr::Point3 &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
    const double u[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, v[3] = {c.x - a.x, c.y - a.y, c.z - a.z};
    const gdr::Point3 n{u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    for (int k = 0; k < 3; ++k) {
      normal[t[k]].x += n.x;
      normal[t[k]].y += n.y;
      normal[t[k]].z += n.z;
    }
    edges += std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  }
  const double step = scale * edges / std::max<std::size_t>(1, s.triangles.size());
  std::mt19937 rng(seed);
  const double two_pi = 6.283185307179586;
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const double u1 = (rng() + 1.0) / 4294967297.0, u2 = rng() / 4294967296.0;
    const double g = std::sqrt(-2 * std::log(u1)) * std::cos(two_pi * u2);
    const gdr::Point3& n = normal[i];
    const double len = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    if (len == 0) continue;
    const double d = step * g / len;
    s.points[i] = {s.points[i].x + d * n.x, s.points[i].y + d * n.y, s.points[i].z + d * n.z};
  }
}

// Each triangle becomes four, the new corners at the edge midpoints. One midpoint per edge,
// shared by both triangles of the edge, keeps the surface closed and manifold; the new
// triangles lie in their parent's plane (up to the rounding of the midpoints), so the
// surface keeps its shape and cannot start to intersect itself.
gdr::Surface midpoint_subdivide(const gdr::Surface& in) {
  gdr::Surface out;
  out.points = in.points;
  out.holes = in.holes;
  out.regions = in.regions;
  out.triangles.reserve(4 * in.triangles.size());
  std::unordered_map<unsigned long long, int> midpoint;
  midpoint.reserve(2 * in.triangles.size());
  auto mid = [&](int a, int b) {
    const unsigned long long key = (static_cast<unsigned long long>(std::min(a, b)) << 32) |
                                   static_cast<unsigned>(std::max(a, b));
    const auto [it, added] = midpoint.emplace(key, static_cast<int>(out.points.size()));
    if (added) {
      const gdr::Point3 &p = in.points[a], &q = in.points[b];
      out.points.push_back({0.5 * (p.x + q.x), 0.5 * (p.y + q.y), 0.5 * (p.z + q.z)});
    }
    return it->second;
  };
  for (const auto& t : in.triangles) {
    const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({ab, t[1], bc});
    out.triangles.push_back({ca, bc, t[2]});
    out.triangles.push_back({ab, bc, ca});
  }
  // Segments are split at the same midpoints.
  for (const auto& s : in.segments) {
    const int m = mid(s[0], s[1]);
    out.segments.push_back({s[0], m});
    out.segments.push_back({m, s[1]});
  }
  return out;
}

// Torus around the z axis, major radius 1, tube radius 0.35 (1 + bump f(u, v)), f in [-1, 1].
// Each cross-section at angle u is star-shaped around its tube centre and stays within
// 0.35 (1 + bump) < 1 of it, and two cross-sections meet only on the z axis, so the smooth
// surface is embedded; the triangulation is fine enough to follow it. The bumps keep the
// vertices off common circles and spheres (a plain torus grid is full of cospherical points).
gdr::Surface bumpy_torus(double triangles, double bump) {
  const double R = 1.0, r = 0.35, pi = 3.14159265358979323846;
  // Rings of nv points around the tube, nu rings around the axis, quads roughly square.
  // nu even: every ring pairs with a ring of the other half-step offset, also across the seam.
  const int nu = 2 * std::max(4, static_cast<int>(std::lround(std::sqrt(triangles / 2 * R / r) / 2)));
  const int nv = std::max(6, static_cast<int>(std::lround(triangles / (2.0 * nu))));
  gdr::Surface s;
  s.points.reserve(static_cast<std::size_t>(nu) * nv);
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      // Alternate rings turn by half a step: triangles closer to equilateral.
      const double u = 2 * pi * i / nu, v = 2 * pi * (j + 0.5 * (i % 2)) / nv;
      const double f = std::sin(3 * u) * std::cos(2 * v) * 0.7 + std::sin(5 * u + 3 * v) * 0.3;
      const double rr = r * (1 + bump * f);
      s.points.push_back({(R + rr * std::cos(v)) * std::cos(u), (R + rr * std::cos(v)) * std::sin(u),
                          rr * std::sin(v)});
    }
  }
  auto id = [&](int i, int j) { return ((i % nu + nu) % nu) * nv + ((j % nv + nv) % nv); };
  for (int i = 0; i < nu; ++i) {
    for (int j = 0; j < nv; ++j) {
      // Ring i+1 is shifted by half a step against ring i when i is even, back when odd.
      const int shift = i % 2 == 0 ? 0 : 1;
      const int a = id(i, j), b = id(i, j + 1), c = id(i + 1, j + shift), d = id(i + 1, j + 1 + shift);
      s.triangles.push_back({a, c, b});
      s.triangles.push_back({b, c, d});
    }
  }
  // Outward normals (positive enclosed volume), as the data set's surfaces.
  double signed_volume = 0;
  for (const auto& t : s.triangles) {
    const gdr::Point3 &p = s.points[t[0]], &q = s.points[t[1]], &w = s.points[t[2]];
    signed_volume += p.x * (q.y * w.z - q.z * w.y) - p.y * (q.x * w.z - q.z * w.x) + p.z * (q.x * w.y - q.y * w.x);
  }
  if (signed_volume < 0)
    for (auto& t : s.triangles) std::swap(t[1], t[2]);
  return s;
}

}  // namespace

bool is_surface_spec(const std::string& input) {
  return input.rfind("gen:surface:", 0) == 0 || input.rfind("gen:torus:", 0) == 0 ||
         input.rfind("gen:lathe:", 0) == 0;
}

gdr::Surface generate_surface(const std::string& spec, const std::string& data_dir) {
  std::string kind;
  const auto parts = spec_parts(spec, kind);
  auto refuse_unknown = [&](std::initializer_list<const char*> known) {
    for (const auto& [key, value] : parts) {
      if (std::none_of(known.begin(), known.end(), [&](const char* k) { return key == k; }))
        throw gdr::Error(gdr::Status::InvalidInput, "unknown key '" + key + "' in '" + spec + "'");
    }
  };
  if (kind == "surface") {
    refuse_unknown({"base", "subdiv", "turn", "noise", "seed"});
    const auto base = parts.find("base");
    if (base == parts.end())
      throw gdr::Error(gdr::Status::InvalidInput, "'" + spec + "': base=FILE is required");
    namespace fs = std::filesystem;
    const std::string path = fs::path(base->second).is_absolute() || fs::exists(base->second)
                                 ? base->second
                                 : (fs::path(data_dir) / base->second).string();
    const double k = spec_number(parts, "subdiv", 1, spec);
    if (!(k >= 0 && k <= 6 && k == std::floor(k)))
      throw gdr::Error(gdr::Status::InvalidInput, "'" + spec + "': subdiv must be 0..6");
    gdr::Surface s = gdr::io::read_surface(path);
    for (int i = 0; i < static_cast<int>(k); ++i) s = midpoint_subdivide(s);
    const double noise = spec_number(parts, "noise", 0, spec);
    if (!(noise >= 0 && noise <= 1))
      throw gdr::Error(gdr::Status::InvalidInput, "'" + spec + "': noise must be 0..1 (mean edge lengths)");
    if (noise > 0) add_normal_noise(s, noise, static_cast<unsigned>(spec_number(parts, "seed", 1, spec)));
    if (spec_number(parts, "turn", 0, spec) != 0) {
      const double c = std::cos(0.7), sn = std::sin(0.7), c2 = std::cos(0.4), s2 = std::sin(0.4);
      for (gdr::Point3& p : s.points) {
        const double x = c * p.x - sn * p.y, y = sn * p.x + c * p.y;
        p = {double(float(x)), double(float(c2 * y - s2 * p.z)), double(float(s2 * y + c2 * p.z))};
      }
    }
    return s;
  }
  if (kind == "torus") {
    refuse_unknown({"triangles", "bump"});
    const double n = spec_number(parts, "triangles", 100000, spec);
    const double bump = spec_number(parts, "bump", 0.15, spec);
    if (!(n >= 96 && n <= 1e8) || !(bump >= 0 && bump <= 0.5))
      throw gdr::Error(gdr::Status::InvalidInput,
                       "'" + spec + "': need 96 <= triangles <= 1e8 and 0 <= bump <= 0.5");
    return bumpy_torus(n, bump);
  }
  if (kind == "lathe") {  // the bundled bushing's profile with a polygonal bore (tests' turned_bushing)
    refuse_unknown({"sectors", "height"});
    const double n = spec_number(parts, "sectors", 32, spec);
    const double h = spec_number(parts, "height", 1.2, spec);
    if (!(n >= 3 && n <= 1e5 && n == std::floor(n)) || !(h >= 0.4 && h <= 1e3))
      throw gdr::Error(gdr::Status::InvalidInput, "'" + spec + "': need 3 <= sectors (an integer) and height >= 0.4");
    return gdr::test::turned_bushing(static_cast<int>(n), h);
  }
  throw gdr::Error(gdr::Status::InvalidInput,
                   "unknown surface generator '" + kind + "' in '" + spec + "' (known: surface, torus, lathe)");
}

void write_off(const std::string& path, const gdr::Surface& s) {
  FILE* f = std::fopen(path.c_str(), "w");
  if (!f) throw gdr::Error(gdr::Status::IoError, path + ": cannot write");
  std::fprintf(f, "OFF\n%zu %zu 0\n", s.points.size(), s.triangles.size());
  for (const auto& p : s.points) std::fprintf(f, "%.17g %.17g %.17g\n", p.x, p.y, p.z);
  for (const auto& t : s.triangles) std::fprintf(f, "3 %d %d %d\n", t[0], t[1], t[2]);
  if (std::fclose(f) != 0) throw gdr::Error(gdr::Status::IoError, path + ": write failed");
}

double enclosed_volume(const gdr::Surface& s) {
  // Divergence theorem: the signed volumes of the tetrahedra (origin, triangle) add up to
  // the enclosed volume. Relative to the first point, to keep the terms small.
  if (s.points.empty()) return 0;
  const gdr::Point3 o = s.points[0];
  double six = 0;
  for (const auto& t : s.triangles) {
    const gdr::Point3 &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
    const double ax = a.x - o.x, ay = a.y - o.y, az = a.z - o.z;
    const double bx = b.x - o.x, by = b.y - o.y, bz = b.z - o.z;
    const double cx = c.x - o.x, cy = c.y - o.y, cz = c.z - o.z;
    six += ax * (by * cz - bz * cy) - ay * (bx * cz - bz * cx) + az * (bx * cy - by * cx);
  }
  return std::abs(six) / 6.0;
}

}  // namespace gdr_bench
