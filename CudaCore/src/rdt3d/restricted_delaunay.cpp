// gDP3d facade: the paper's Algorithm 5 end to end.
//   1. check the surface (cdt3d's checks; an open surface is meshed as a surface only) and
//      find its sharp features (rdt3d/features.h);
//   2. the Delaunay triangulation of the feature vertices, a sample of the other points and a
//      bounding box (TetGen), all tetrahedra kept (line 1), feature edges split until each
//      piece is an edge of it (a feature subsegment);
//   3. refine on the chosen backend (lines 2-10, engine.h), then, with a sliver angle, smooth
//      the slivers inside the surface (engine.h, mesh3d/smooth.h);
//   4. the restricted surface and the tetrahedra inside it, with their quality.
#include <algorithm>
#include <cstdio>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <map>
#include <new>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <utility>

#include "cdt3d/cdt3d.h"
#include "cdt3d/internal.h"
#include "common/trace.h"
#include "gdr/rdt3d.h"
#include "gdr/validate.h"
#include "mesh3d/orient_surface.h"
#include "mesh3d/scale.h"
#include "mesh3d/tet_topology.h"
#include "qm3d/engine_dispatch.h"
#include "rdt3d/engine_dispatch.h"
#include "rdt3d/feature_sides.h"
#include "rdt3d/features.h"
#include "rdt3d/pinches.h"

namespace gdr {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kSamplePerPart = 32;  // initial points per connected part of the surface
using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

std::uint64_t edge_key(int a, int b) {
  if (a > b) std::swap(a, b);
  return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}

// Whether every edge has two triangles; throws for an edge of three or more (the inside of
// such a surface is not defined by parity).
bool closed_manifold(const cdt3d::Plc& plc) {
  if (plc.first_branching_edge[0] >= 0) {
    auto input_id = [&](int v) {
      for (std::size_t i = 0; i < plc.point_map.size(); ++i)
        if (plc.point_map[i] == v) return static_cast<long long>(i);
      return static_cast<long long>(v);
    };
    throw Error(Status::InvalidInput, "the surface is not manifold: the edge (" +
                                          std::to_string(input_id(plc.first_branching_edge[0])) + ", " +
                                          std::to_string(input_id(plc.first_branching_edge[1])) + ") has " +
                                          std::to_string(plc.first_branching_triangles) + " triangles");
  }
  return plc.open_edges == 0;
}

// Connected parts of the surface (triangles sharing a vertex), for the initial sample.
std::vector<std::vector<int>> components(const cdt3d::Plc& plc) {
  const int np = static_cast<int>(plc.points.size());
  cdt3d::UnionFind sets(np);
  std::vector<char> used(np, 0);
  for (const auto& t : plc.triangles)
    for (int k = 0; k < 3; ++k) {
      used[t[k]] = 1;
      sets.unite(t[k], t[(k + 1) % 3]);
    }
  std::map<int, std::vector<int>> parts;
  for (int v = 0; v < np; ++v)
    if (used[v]) parts[sets.find(v)].push_back(v);
  std::vector<std::vector<int>> out;
  for (auto& [root, vs] : parts) out.push_back(std::move(vs));
  return out;
}

double automatic(double value, double fallback) { return value < 0 ? fallback : value; }

struct Piece {
  int a, b, segment;
};

// Features meeting at a small angle would undo each other's splits: a point splitting one
// lies in the diametral ball of the other's subsegment beside it, and takes it away. Their
// edges are split first at distances from the corner in a geometric sequence of ratio q, the
// same on every edge there, down to feature_min: a piece [r, q r] split at its midpoint then
// stays out of the ball of its neighbour [r, q r] on the other edge when
// q <= (1 + 2 sin(a/2)) / (1 - 2 sin(a/2)) for the angle a between them. At 60 degrees and
// above nothing is needed; below 3 degrees q stays 1.1 (at most about 80 points per edge),
// and what that leaves is left to the exceptions. Appends the points to xyz and returns the
// pieces.
std::vector<Piece> grade_small_angles(std::vector<double>& xyz, const std::vector<std::array<int, 2>>& ends,
                                      double feature_min, std::vector<int>& point_segment) {
  auto at = [&](int v) { return &xyz[3 * std::size_t(v)]; };
  auto length = [&](int s) { return std::sqrt(m3d::dist2(at(ends[s][0]), at(ends[s][1]))); };
  std::map<int, std::vector<int>> around;  // feature vertex -> its edges
  for (std::size_t s = 0; s < ends.size(); ++s)
    for (int v : ends[s]) around[v].push_back(static_cast<int>(s));
  std::vector<double> ratio(xyz.size() / 3, 0), base(xyz.size() / 3, 0);  // per acute corner
  for (const auto& [v, edges] : around) {
    double smallest = kPi;
    for (std::size_t i = 0; i < edges.size(); ++i)
      for (std::size_t j = i + 1; j < edges.size(); ++j) {
        const int* e = ends[edges[i]].data();
        const int* f = ends[edges[j]].data();
        const double* o = at(v);
        const double* p = at(e[0] == v ? e[1] : e[0]);
        const double* q = at(f[0] == v ? f[1] : f[0]);
        const double u[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]}, w[3] = {q[0] - o[0], q[1] - o[1], q[2] - o[2]};
        double n[3];
        m3d::cross3(u, w, n);
        smallest = std::min(smallest, std::atan2(std::sqrt(m3d::dot3(n, n)), m3d::dot3(u, w)));
      }
    const double sine = std::sin(smallest / 2);
    if (sine >= 0.5) continue;
    ratio[v] = std::max(1.1, (1 + 2 * sine) / (1 - 2 * sine));
    for (int s : edges) base[v] = std::max(base[v], length(s));
  }
  std::vector<Piece> pieces;
  for (std::size_t s = 0; s < ends.size(); ++s) {
    const int a = ends[s][0], b = ends[s][1];
    const double len = length(static_cast<int>(s));
    std::vector<double> params;  // along ab, from a
    for (int end = 0; end < 2; ++end) {
      const int v = ends[s][end], w = ends[s][1 - end];
      if (ratio[v] == 0) continue;
      const double reach = ratio[w] > 0 ? len / 2 : len;  // two graded ends share the edge
      for (double r = base[v] / ratio[v]; r >= feature_min; r /= ratio[v])
        if (r < reach) params.push_back(end == 0 ? r / len : 1 - r / len);
    }
    std::sort(params.begin(), params.end());
    int prev = a;
    for (double t : params) {
      const int m = static_cast<int>(xyz.size() / 3);
      for (int k = 0; k < 3; ++k) xyz.push_back(at(a)[k] + t * (at(b)[k] - at(a)[k]));
      point_segment.push_back(static_cast<int>(s));
      pieces.push_back({prev, m, static_cast<int>(s)});
      prev = m;
    }
    pieces.push_back({prev, b, static_cast<int>(s)});
  }
  return pieces;
}

// The splits of the feature edges before refinement stop at max_points points (a facet size
// far below the features' lengths would need millions per edge) with an error, and at the
// caller's abort.
struct SplitGuard {
  std::size_t first_point;  // xyz's points before the splits
  long long max_points;
  double facet_size;        // as the user gave it, for the message
  std::function<bool()> aborted;
  void operator()(const std::vector<double>& xyz) const {
    if (aborted()) throw Error(Status::Aborted, "aborted by the caller");
    if (static_cast<long long>(xyz.size() / 3 - first_point) > max_points)
      throw Error(Status::InvalidInput,
                  "the sharp features would need more than " + std::to_string(max_points) +
                      " points at the facet size " + std::to_string(facet_size) +
                      " before refinement: give a larger facet size (or a larger maximum of Steiner points), "
                      "or mesh without sharp features (feature angle 0)");
  }
};

// Splits piece p at its midpoint (appended to xyz, its feature edge to point_segment) into
// two pieces appended to `out`; returns the midpoint's id.
int split_at_midpoint(std::vector<double>& xyz, const Piece& p, std::vector<int>& point_segment,
                      std::vector<Piece>& out) {
  const int m = static_cast<int>(xyz.size() / 3);
  for (int k = 0; k < 3; ++k) xyz.push_back(0.5 * (xyz[3 * std::size_t(p.a) + k] + xyz[3 * std::size_t(p.b) + k]));
  point_segment.push_back(p.segment);
  out.push_back({p.a, m, p.segment});
  out.push_back({m, p.b, p.segment});
  return m;
}

// Feature edges that pass close by each other without meeting (the two sides of a slot
// narrower than their edges are long) would each be taken away by the other's splits, and
// refinement would block one of them, leaving the slot unresolved and the surface wrong
// there. Pieces are split at midpoints until no piece's diametral ball meets a piece of a
// feature edge that shares no corner with its own (those at a corner are graded above), down
// to pieces of 2 feature_min; a point splitting one later then stays out of the other's ball.
void split_pieces_near_other_features(std::vector<double>& xyz, const std::vector<std::array<int, 2>>& ends,
                                      double feature_min, std::vector<Piece>& pieces,
                                      std::vector<int>& point_segment, const SplitGuard& guard) {
  auto at = [&](int v) { return &xyz[3 * std::size_t(v)]; };
  auto touching = [&](int s, int u) {
    return s == u || ends[s][0] == ends[u][0] || ends[s][0] == ends[u][1] || ends[s][1] == ends[u][0] ||
           ends[s][1] == ends[u][1];
  };
  for (int round = 0; round < 64; ++round) {
    // A uniform grid, cells as long as the median piece. Each piece is listed in the cells of
    // points along it at most a cell apart (not its whole box: a long diagonal piece would
    // fill a cube of cells), so a piece that meets a ball has a listed point within half a
    // cell of it.
    std::vector<double> lengths(pieces.size());
    for (std::size_t i = 0; i < pieces.size(); ++i) lengths[i] = std::sqrt(m3d::dist2(at(pieces[i].a), at(pieces[i].b)));
    if (pieces.empty()) return;
    std::vector<double> sorted = lengths;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    // At least the mean length over 8: the cells listed stay within 8 per piece plus one when
    // most pieces are graded ones a small angle left tiny (a long piece would be listed in
    // 10^9 cells of a tiny median).
    const double total = std::accumulate(lengths.begin(), lengths.end(), 0.0);
    const double h = std::max({sorted[sorted.size() / 2], 2 * feature_min, total / (8.0 * lengths.size())});
    using Cell = std::array<long long, 3>;
    std::map<Cell, std::vector<int>> grid;
    auto cell_of = [&](const double* x) {
      return Cell{static_cast<long long>(std::floor(x[0] / h)), static_cast<long long>(std::floor(x[1] / h)),
                  static_cast<long long>(std::floor(x[2] / h))};
    };
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const double *p = at(pieces[i].a), *q = at(pieces[i].b);
      const int n = static_cast<int>(std::min(std::ceil(lengths[i] / h), 1e6));
      Cell last{};
      for (int k = 0; k <= n; ++k) {
        const double t = n > 0 ? double(k) / n : 0.0;
        const double x[3] = {p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1]), p[2] + t * (q[2] - p[2])};
        const Cell c = cell_of(x);
        if (k > 0 && c == last) continue;
        std::vector<int>& list = grid[c];
        if (list.empty() || list.back() != static_cast<int>(i)) list.push_back(static_cast<int>(i));
        last = c;
      }
    }
    // The cells a ball of radius r about c may meet a listed point of a piece through: its
    // box grown by half a cell, or, when that box holds more cells than are listed, the
    // listed cells inside it.
    auto for_cells_near = [&](const double* c, double r, auto&& visit) {
      const double g = r + h / 2;
      const double lo[3] = {c[0] - g, c[1] - g, c[2] - g}, hi[3] = {c[0] + g, c[1] + g, c[2] + g};
      const Cell a = cell_of(lo), b = cell_of(hi);
      const double cells = double(b[0] - a[0] + 1) * double(b[1] - a[1] + 1) * double(b[2] - a[2] + 1);
      if (cells > double(grid.size())) {
        for (const auto& [k, list] : grid)
          if (k[0] >= a[0] && k[0] <= b[0] && k[1] >= a[1] && k[1] <= b[1] && k[2] >= a[2] && k[2] <= b[2])
            if (!visit(list)) return;
        return;
      }
      for (long long i = a[0]; i <= b[0]; ++i)
        for (long long j = a[1]; j <= b[1]; ++j)
          for (long long k = a[2]; k <= b[2]; ++k) {
            const auto found = grid.find(Cell{i, j, k});
            if (found != grid.end() && !visit(found->second)) return;
          }
    };
    std::vector<Piece> next;
    next.reserve(pieces.size());
    for (std::size_t i = 0; i < pieces.size(); ++i) {
      const Piece& pc = pieces[i];
      bool split = false;
      if (lengths[i] >= 2 * feature_min) {
        const double *p = at(pc.a), *q = at(pc.b);
        const double c[3] = {(p[0] + q[0]) / 2, (p[1] + q[1]) / 2, (p[2] + q[2]) / 2};
        const double r = lengths[i] / 2;
        for_cells_near(c, r, [&](const std::vector<int>& list) {
          for (const int j : list) {
            if (touching(pc.segment, pieces[j].segment)) continue;
            // Squared distance from c to the piece j.
            const double *a = at(pieces[j].a), *b = at(pieces[j].b);
            const double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, w[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
            const double dd = m3d::dot3(d, d);
            const double t = dd > 0 ? std::clamp(m3d::dot3(w, d) / dd, 0.0, 1.0) : 0.0;
            const double x[3] = {a[0] + t * d[0], a[1] + t * d[1], a[2] + t * d[2]};
            if (m3d::dist2(c, x) < r * r) {
              split = true;
              return false;
            }
          }
          return true;
        });
      }
      if (!split) {
        next.push_back(pc);
        continue;
      }
      split_at_midpoint(xyz, pc, point_segment, next);
    }
    const bool done = next.size() == pieces.size();
    pieces = std::move(next);
    if (done) return;
    guard(xyz);
  }
}

// The initial triangulation with feature subsegments: each feature edge (a segment of the
// mesh, its ends given as point ids of xyz) is graded at small angles, then split at
// midpoints until every piece is an edge of the Delaunay triangulation of all the points;
// refinement keeps them (rdt3d::KeepFeatures). The points added are appended to xyz, typed
// kSegmentPoint.
m3d::HostTetMesh triangulate_with_features(std::vector<double>& xyz, const std::vector<std::array<int, 2>>& ends,
                                          double feature_min, const m3d::PowerOfTwoScale& scale,
                                          const SplitGuard& guard) {
  const int given = static_cast<int>(xyz.size() / 3);
  std::vector<int> midpoint_segment;  // per appended point
  std::vector<Piece> pieces = grade_small_angles(xyz, ends, feature_min, midpoint_segment);
  split_pieces_near_other_features(xyz, ends, feature_min, pieces, midpoint_segment, guard);
  for (;;) {  // ends: pieces shorter than their distance to any other point are edges
    guard(xyz);
    m3d::HostTetMesh mesh = cdt3d::delaunay_tetrahedralization(xyz);
    std::set<std::uint64_t> edges;
    for (int t = 0; t < mesh.tets(); ++t)
      for (int e = 0; e < 6; ++e)
        edges.insert(edge_key(mesh.tv[4 * t + m3d::edge_corner(e, 0)], mesh.tv[4 * t + m3d::edge_corner(e, 1)]));
    std::vector<Piece> next;
    for (const Piece& p : pieces) {
      if (edges.count(edge_key(p.a, p.b))) {
        next.push_back(p);
        continue;
      }
      // Another point within a piece of feature_min: halving on would go on down to
      // rounding, the pieces doubling each time (two parts 1e-12 apart hung here).
      const double* a = &xyz[3 * std::size_t(p.a)];
      const double* b = &xyz[3 * std::size_t(p.b)];
      if (m3d::dist2(a, b) < 4 * feature_min * feature_min) {
        const Point3 at = scale.apply(Point3{a[0], a[1], a[2]}, -1);  // as the user gave it
        char text[160];
        std::snprintf(text, sizeof text, "a sharp feature edge near (%.9g, %.9g, %.9g) passes within %.3g", at.x,
                      at.y, at.z, scale.length(feature_min, -1));
        throw Error(Status::InvalidInput,
                    std::string(text) +
                        " (1/64 of the facet size) of other input points, too close to be kept apart "
                        "(parts nearly touching, or a needle triangle?): mesh without sharp features "
                        "(feature angle 0), or with a smaller facet size");
      }
      const int m = split_at_midpoint(xyz, p, midpoint_segment, next);
      const double* q = &xyz[3 * std::size_t(m)];
      for (int v : {p.a, p.b})
        if (q[0] == xyz[3 * v] && q[1] == xyz[3 * v + 1] && q[2] == xyz[3 * v + 2])
          throw Error(Status::InternalError, "a feature edge could not be recovered in the initial triangulation");
    }
    if (next.size() == pieces.size()) {
      for (std::size_t k = 0; k < midpoint_segment.size(); ++k) {
        mesh.ptype[given + k] = m3d::kSegmentPoint;
        mesh.pseg[given + k] = midpoint_segment[k];
      }
      for (const auto& e : ends) mesh.seg.insert(mesh.seg.end(), {e[0], e[1]});
      std::set<std::uint64_t> subsegments;
      for (const Piece& p : pieces) subsegments.insert(edge_key(p.a, p.b));
      for (int t = 0; t < mesh.tets(); ++t)
        for (int e = 0; e < 6; ++e)
          if (subsegments.count(edge_key(mesh.tv[4 * t + m3d::edge_corner(e, 0)], mesh.tv[4 * t + m3d::edge_corner(e, 1)])))
            mesh.tseg[t] |= static_cast<std::uint8_t>(1 << e);
      return mesh;
    }
    pieces = std::move(next);
  }
}

}  // namespace

void validate_restricted_delaunay_options(const RestrictedDelaunayOptions& o) {
  auto bad = [](const std::string& what) { throw Error(Status::InvalidInput, what); };
  if (!(o.facet_angle >= 0 && o.facet_angle <= 30))
    bad("facet angle must be in [0, 30] degrees (above 30 the refinement need not terminate), got " +
        std::to_string(o.facet_angle));
  if (!std::isfinite(o.facet_size) || !std::isfinite(o.facet_distance) || !std::isfinite(o.cell_size))
    bad("facet size, facet distance and cell size must be finite");
  if (!(o.cell_radius_edge_ratio == 0 || (o.cell_radius_edge_ratio >= 1.0 && std::isfinite(o.cell_radius_edge_ratio))))
    bad("cell radius-edge ratio must be at least 1 (or 0 to turn it off), got " +
        std::to_string(o.cell_radius_edge_ratio));
  if (o.max_steiner_points < -1) bad("maximum Steiner points must be >= 0 (or -1: automatic)");
  if (!(o.feature_angle >= 0 && o.feature_angle < 180))
    bad("feature angle must be in [0, 180) degrees (0: no sharp features detected), got " +
        std::to_string(o.feature_angle));
  if (!(o.sliver_angle >= 0 && o.sliver_angle <= 30))
    bad("sliver angle must be in [0, 30] degrees (0: off), got " + std::to_string(o.sliver_angle));
  if (o.facet_angle == 0 && o.facet_size == 0 && o.facet_distance == 0)
    bad("at least one facet criterion (angle, size or distance) is needed");
}

RestrictedDelaunayResult restricted_delaunay_3d(const Surface& unscaled, const RestrictedDelaunayOptions& user_options,
                                                const Callbacks& cb) {
  const auto t_start = Clock::now();
  validate_restricted_delaunay_options(user_options);
  prewarm_gpu(user_options.backend, unscaled.triangles.size(), 10000);  // backend.h
  // Meshed at a power-of-two scale (exact) where the predicates cannot overflow or underflow.
  const m3d::PowerOfTwoScale scale(unscaled);
  const Surface input = scale.scaled(unscaled);
  RestrictedDelaunayOptions options = user_options;
  for (double* size : {&options.facet_size, &options.facet_distance, &options.cell_size})
    if (*size > 0) *size = scale.length(*size, 1);
  RestrictedDelaunayResult result;
  RestrictedDelaunayStats& st = result.stats;
  auto aborted = [&] { return cb.abort && cb.abort(); };
  auto progress = [&](double f, const std::string& what) {
    if (cb.progress) cb.progress(f, what);
  };
  st.input_points = static_cast<long long>(input.points.size());
  st.input_triangles = static_cast<long long>(input.triangles.size());

  progress(0.0, "checking input");
  cdt3d::CheckOptions check;
  check.require_closed = false;
  check.facets = false;
  check.keep_edges = options.feature_angle > 0;
  cdt3d::Plc plc = cdt3d::check_surface(input, check, cb);
  st.closed_input = closed_manifold(plc);
  st.volume_meshed = options.mesh_volume && st.closed_input;
  if (options.mesh_volume && !st.closed_input && cb.warning)
    cb.warning("the surface is open: only the surface is meshed (a volume needs a closed surface)");
  std::vector<std::array<int, 2>> input_segments;
  for (const auto& g : input.segments) input_segments.push_back({plc.point_map[g[0]], plc.point_map[g[1]]});
  const rdt3d::Features features = rdt3d::find_features(plc, input_segments, options.feature_angle);
  plc.edges.reset();  // read only by the feature search
  st.feature_edges = static_cast<long long>(features.edges.size());
  st.corners = features.corners;
  st.feature_angle = options.feature_angle;
  st.input_seconds = since(t_start);
  if (aborted()) throw Error(Status::Aborted, "aborted by the caller");

  // The box: the input's, and a margin of half its diagonal for the corners of the initial
  // triangulation (every inserted point lies in the input's box: surface centres on the
  // surface, circumcentres inside it).
  double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
  for (const auto& t : plc.triangles)
    for (int v : t) {
      const double p[3] = {plc.points[v].x, plc.points[v].y, plc.points[v].z};
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
  const double diag = std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const double facet_size = automatic(options.facet_size, diag / 20);
  const double facet_distance = automatic(options.facet_distance, diag / 500);
  const double cell_size = automatic(options.cell_size, facet_size);
  st.facet_angle = options.facet_angle;
  st.facet_size = facet_size;
  st.facet_distance = facet_distance;
  st.cell_radius_edge_ratio = options.cell_radius_edge_ratio;
  st.cell_size = cell_size;

  // Line 1: the initial Delaunay triangulation of the feature vertices, a sample of every
  // connected part and the box corners. The sample is random (fixed seed): points spread by
  // index can all lie on one curve (a row of a parametric grid), whose Voronoi edges may all
  // miss the surface (a torus sampled along its outer equator crosses each Voronoi facet in a
  // closed loop).
  progress(0.02, "initial Delaunay triangulation");
  auto t0 = Clock::now();
  std::vector<double> xyz;
  std::vector<int> mesh_id(plc.points.size(), -1);  // Plc point -> initial point
  std::vector<char> corner;                         // per initial feature vertex
  for (std::size_t v = 0; v < plc.points.size(); ++v)
    if (features.kind[v] != rdt3d::kNotFeature) {
      mesh_id[v] = static_cast<int>(xyz.size() / 3);
      corner.push_back(features.kind[v] == rdt3d::kCorner);
      xyz.insert(xyz.end(), {plc.points[v].x, plc.points[v].y, plc.points[v].z});
    }
  const int feature_vertices = static_cast<int>(xyz.size() / 3);
  std::mt19937 random(12345);
  for (auto part : components(plc)) {
    part.erase(std::remove_if(part.begin(), part.end(), [&](int v) { return mesh_id[v] >= 0; }), part.end());
    const std::size_t n = part.size(), take = std::min<std::size_t>(n, kSamplePerPart);
    for (std::size_t k = 0; k < take; ++k) {
      std::swap(part[k], part[k + random() % (n - k)]);
      const Point3& p = plc.points[part[k]];
      xyz.insert(xyz.end(), {p.x, p.y, p.z});
    }
  }
  const int sample = static_cast<int>(xyz.size() / 3);
  st.initial_points = sample;
  // Margins of 0.5-0.72 diagonals, different at every corner and axis: an exact box of
  // corners around a turned box's points made TetGen's Delaunay point location stop on an
  // assertion in every point order (fuzz3d, seed 4001684); a generic octahedron does not.
  for (int c = 0; c < 8; ++c)
    for (int k = 0; k < 3; ++k) {
      const double margin = diag * (0.5 + 0.0371 * ((3 * c + k) % 7));
      xyz.push_back((c >> k) & 1 ? hi[k] + margin : lo[k] - margin);
    }
  std::vector<std::array<int, 2>> feature_ends;
  for (const auto& e : features.edges) feature_ends.push_back({mesh_id[e[0]], mesh_id[e[1]]});
  // Feature subsegments are split down to 1/64 of the facet size; below, what cannot
  // be met next to a feature (a small angle) is left and reported.
  st.feature_min_length = (facet_size > 0 ? facet_size : diag / 20) / 64;
  const SplitGuard guard{xyz.size() / 3,
                         std::max<long long>({1000000, 200LL * static_cast<long long>(plc.points.size()),
                                              options.max_steiner_points}),
                         scale.length(facet_size > 0 ? facet_size : diag / 20, -1), aborted};
  m3d::HostTetMesh mesh = triangulate_with_features(xyz, feature_ends, st.feature_min_length, scale, guard);
  for (int v = sample; v < sample + 8; ++v) mesh.ptype[v] = m3d::kFreePoint;  // box corners
  st.initial_seconds = since(t0);
  if (aborted()) throw Error(Status::Aborted, "aborted by the caller");

  // The refinement's stage starts with the surface's search tree (its build is the first
  // step of every query structure the engine uses).
  t0 = Clock::now();
  rdt3d::SurfaceInput surface;
  const long long n_points = static_cast<long long>(plc.points.size()), n_tris = static_cast<long long>(plc.triangles.size());
  surface.xyz.resize(3 * n_points);
  surface.tri.resize(3 * n_tris);
#pragma omp parallel
  {
#pragma omp for schedule(static) nowait
    for (long long v = 0; v < n_points; ++v) {
      surface.xyz[3 * v] = plc.points[v].x;
      surface.xyz[3 * v + 1] = plc.points[v].y;
      surface.xyz[3 * v + 2] = plc.points[v].z;
    }
#pragma omp for schedule(static)
    for (long long t = 0; t < n_tris; ++t)
      for (int k = 0; k < 3; ++k) surface.tri[3 * t + k] = plc.triangles[t][k];
  }
  surface.tree = rdt3d::build_aabb(surface.xyz, surface.tri);

  // Six times the enclosed volume, signed: the input's orientation (for facets whose dual does
  // not separate inside from outside) and the domain the stall detector measures against.
  double signed_volume = 0;
  for (const auto& t : plc.triangles) {
    const Point3 &a = plc.points[t[0]], &b = plc.points[t[1]], &d = plc.points[t[2]];
    signed_volume += a.x * (b.y * d.z - b.z * d.y) - a.y * (b.x * d.z - b.z * d.x) + a.z * (b.x * d.y - b.y * d.x);
  }

  rdt3d::EngineParams params;
  params.domain_six_volume = std::fabs(signed_volume);
  rdt3d::Criteria& c = params.criteria;
  const double s = std::sin(options.facet_angle * kPi / 180.0);
  c.sin2_facet_angle = s * s;
  c.facet_size2 = facet_size * facet_size;
  c.facet_distance2 = facet_distance * facet_distance;
  c.radius_edge2 = options.cell_radius_edge_ratio * options.cell_radius_edge_ratio;
  c.cell_size2 = cell_size * cell_size;
  // A closed input's surface is the boundary of what lies inside, with a volume or without.
  c.inside = st.closed_input ? 1 : 0;
  c.volume = st.volume_meshed ? 1 : 0;
  c.reach = 8 * diag;  // beyond the corners' box from anywhere in it
  c.feature_min2 = st.feature_min_length * st.feature_min_length;
  c.manifold = st.closed_input ? rdt3d::kManifold : rdt3d::kManifoldBoundary;
  params.manifold = options.manifold;
  st.manifold_min_size = options.manifold ? std::min(diag / 1000, facet_size > 0 ? facet_size / 8 : diag) : 0.0;
  c.manifold_min2 = st.manifold_min_size * st.manifold_min_size;
  st.sliver_angle = st.volume_meshed ? options.sliver_angle : 0.0;
  params.sliver_sin = std::sin(st.sliver_angle * kPi / 180.0);
  params.insertion.strategies = qm3d::strategies_from_environment();
  params.insertion.max_steiner = options.max_steiner_points;
  if (options.max_steiner_points < 0 && st.volume_meshed && options.cell_radius_edge_ratio > 0 &&
      options.cell_radius_edge_ratio < 2)
    params.insertion.max_steiner = std::max<long long>(1000000, 200LL * static_cast<long long>(plc.points.size()));
  st.steiner_cap = params.insertion.max_steiner;

  // Rough output size for Auto: the surface area over the facet size squared, and the volume
  // over the cell size cubed.
  const double area_est = diag * diag, vol_est = diag * diag * diag / 10;
  double est = 4 * area_est / std::max(facet_size * facet_size, 1e-300 * diag * diag);
  if (st.volume_meshed && cell_size > 0) est += 6 * vol_est / (cell_size * cell_size * cell_size);
  const std::size_t estimated = est > 1e12 ? std::size_t(1e12) : static_cast<std::size_t>(est);
  // Sharp features run on both backends. They were refused on the GPU until 2026-11-28: on
  // the H100 (2026-11-24) thingi10k_65778 failed --check there. The fault was the feature
  // path's, not the GPU's (the CPU path failed it too, in about 1 run of 8: the narrow slots
  // that split_pieces_near_other_features now resolves and a stall detector that stopped
  // while points still went in); on the H200 the cube, thingi10k_65778 and fandisk then
  // passed --check on the GPU in 4 runs of 4.
  const Backend requested = options.backend;
  st.backend_used = resolve_backend(requested, estimated, 20000 * std::size_t(std::max(1, cpu_threads())));
  // Every CPU thread from the start: unlike gQM3d's (backend.h, cpu_threads_for), a limit
  // that follows the mesh bought nothing measurable here (H200 machine, 2026-11-28: six
  // parts and spot at 2M cells, all threads against 1 per 400-2,500 tetrahedra, within
  // the +-10% between calls).
  if (st.backend_used == Backend::Gpu) st.device_name = device_info().name;
  else st.device_name = cpu_device_name(cpu_threads());

  Callbacks engine_cb = cb;
  if (cb.progress)
    engine_cb.progress = [&cb, n = 0](double, const std::string& what) mutable {
      ++n;
      cb.progress(0.05 + 0.85 * (1.0 - 1.0 / (1.0 + 0.05 * n)), what);
    };
  if (std::getenv("GDR_TRACE")) std::fprintf(stderr, "gdr-trace rdt surface tree: %.3f s\n", since(t0));
  rdt3d::MeshResult out;
  rdt3d::EngineResult er;
  try {
    if (st.backend_used == Backend::Gpu) {
#if defined(GDR_HAVE_CUDA)
      er = rdt3d::refine_restricted_cuda(mesh, surface, out, params, engine_cb);
      mark_gpu_warm();
#endif
    } else {
      er = rdt3d::refine_restricted_cpu(mesh, surface, out, params, engine_cb);
    }
  } catch (const std::bad_alloc&) {
    throw Error(Status::OutOfDeviceMemory, "out of memory during refinement");
  }
  st.refine_seconds = since(t0);
  st.iterations = er.iterations;
  st.steiner_cap_reached = er.cap_reached;
  st.stalled = er.stalled;
  st.phases = er.phases;
  st.steiner_points = er.inserted;
  st.manifold_splits = er.manifold_splits;
  st.non_manifold_facets = er.non_manifold;
  st.features_off_surface = er.lost_features;
  st.slivers_before = er.slivers.slivers_before;
  st.slivers_after = er.slivers.slivers_after;
  st.sliver_moves = er.slivers.moves;
  if (st.backend_used == Backend::Gpu) st.peak_device_bytes = er.peak_bytes;
  if (er.cap_reached && cb.warning)
    cb.warning("refinement stopped at the Steiner point cap (" + std::to_string(st.steiner_cap) + ")");
  if (aborted()) throw Error(Status::Aborted, "aborted by the caller");

  // The output, read off the final triangulation with the engine's own predicates.
  progress(0.92, "restricted surface and volume");
  const auto t_output = Clock::now();
  TraceSteps steps("rdt output");
  m3d::TetView m{};
  m.xyz = out.xyz.data();
  m.ptype = out.ptype.data();
  m.tv = out.tv.data();
  m.tn = out.tn.data();
  m.tflag = out.tflag.data();
  m.ntet = out.tets();
  m.npts = static_cast<int>(out.ptype.size());
  m3d::TetView ms = m;
  if (!out.xyz_refined.empty()) ms.xyz = out.xyz_refined.data();
  const rdt3d::AabbView tree = surface.view();
  // Point types as the output reports them: corners Input, the other feature vertices
  // Segment, the sample Facet (the engine typed all of them input points).
  for (int v = 0; v < sample; ++v)
    out.ptype[v] = v >= feature_vertices ? m3d::kFacetPoint : (corner[v] ? m3d::kInputPoint : m3d::kSegmentPoint);
  st.triangulation_points = m.npts;
  st.triangulation_tets = m.ntet;
  // A closed input's surface is the boundary of the tetrahedra inside: the pinches that
  // refinement leaves where the input is rough at the mesh's scale are undone (pinches.h).
  // Not with sharp features, whose pinches come from the features (README, "Restricted
  // Delaunay: thin parts and features"): there it made thingi10k_288351 worse (83 -> 108-328
  // non-manifold edges at --feature-angle 30).
  rdt3d::PinchRepair pinches;
  bool pinch_pass = false;
  // Only where the engine's count (the same surface) found pinches: nothing to pay elsewhere.
  if (c.inside && options.manifold && st.non_manifold_facets > 0 &&
      std::none_of(out.tflag.begin(), out.tflag.end(), [](int f) { return (f & m3d::kSegBits) != 0; })) {
    pinches = rdt3d::undo_pinches(out.xyz.data(), out.ptype.data(), m.npts, m.tv, m.tn, out.tflag.data(), m.ntet,
                                  rdt3d::kInterior, m3d::kSegBits);
    st.pinch_relabelled = pinches.relabelled;
    pinch_pass = true;
  }
  // Feature subsegments the surface cuts across: the tetrahedra round them take the sides
  // of the input's solid next to them (feature_sides.h).
  if (c.inside && st.features_off_surface > 0) {
    pinches.moved.assign(m.ntet, 0);
    const rdt3d::FeatureSides fs = rdt3d::mend_lost_features(m, c, tree, pinches.moved);
    st.features_off_surface = fs.left;
    st.feature_relabelled = fs.relabelled;
    if (std::getenv("GDR_TRACE"))
      std::fprintf(stderr,
                   "gdr-trace rdt features off the surface: %lld, mended %lld (not: %lld one side, %lld wedges, "
                   "%lld pinching), %lld left\n",
                   fs.lost, fs.mended, fs.one_side, fs.wedges, fs.pinching, fs.left);
  }
  if (st.features_off_surface > 0 && cb.warning)
    cb.warning(std::to_string(st.features_off_surface) +
               " feature subsegment(s) are not edges of the surface: it cuts across the sharp edges there "
               "(next to corners and acute creases)");

  std::vector<int> new_id(m.npts, -1);
  TetMesh& tm = result.mesh;
  auto use = [&](int v) {
    if (new_id[v] < 0) {
      new_id[v] = static_cast<int>(tm.points.size());
      tm.points.push_back({out.xyz[3 * v], out.xyz[3 * v + 1], out.xyz[3 * v + 2]});
      tm.point_type.push_back(static_cast<PointType>(out.ptype[v]));
    }
    return new_id[v];
  };
  // Restricted facets, each from the tetrahedron that owns its face: measured in parallel
  // (the surface centre is an AABB query), then numbered in tetrahedron order. They are
  // measured on the refined triangulation (`ms`: where the sliver pass moved points, the
  // points before it; the facets' corners did not move, the circumcentres at the ends of their
  // duals may have). With a volume, the surface is the boundary of the tetrahedra inside:
  // a restricted facet between two tetrahedra on the same side (rdt3d::same_side: its dual
  // touches the surface without crossing it, or crosses it twice) bounds nothing and is left
  // out and counted. Refining such facets instead (as bad facets) was tried: on
  // thingi10k_65778, where they come from circumcentres exactly on the input's planes, it
  // made refinement stall in 6 runs of 10 (0 of 10 without), so they are only left out.
  // Faces of tetrahedra that changed side at a pinch bound the volume whether restricted or not.
  auto emitted = [&](int t, int f) {
    if (!rdt3d::owns_face(m, t, f)) return false;
    const int nb = m.tn[4 * t + f];
    const bool moved = !pinches.moved.empty() && (pinches.moved[t] || (nb >= 0 && pinches.moved[nb >> 2]));
    if (!moved) return (out.tflag[t] & (rdt3d::kRestricted0 << f)) && !rdt3d::same_side(m, c, t, f);
    return ((out.tflag[t] & rdt3d::kInterior) != 0) != (nb >= 0 && (out.tflag[nb >> 2] & rdt3d::kInterior) != 0);
  };
  long long unbounding = 0;
#pragma omp parallel for reduction(+ : unbounding)
  for (int t = 0; t < m.ntet; ++t)
    for (int f = 0; f < 4; ++f)
      unbounding += (out.tflag[t] & (rdt3d::kRestricted0 << f)) && rdt3d::owns_face(m, t, f) && rdt3d::same_side(m, c, t, f);
  st.facets_left_out = unbounding;
  struct Facet {
    int v[3];
    double angle, size, dist, area;
    unsigned char bad;
    bool ok;
    m3d::OrientVote vote;  // how sure its orientation is (mesh3d/orient_surface.h)
  };
  std::vector<long long> first(static_cast<std::size_t>(m.ntet) + 1, 0);
#pragma omp parallel for
  for (int t = 0; t < m.ntet; ++t) {
    int n = 0;
    for (int f = 0; f < 4; ++f) n += emitted(t, f);
    first[t + 1] = n;
  }
  for (int t = 0; t < m.ntet; ++t) first[t + 1] += first[t];
  std::vector<Facet> facets(static_cast<std::size_t>(first[m.ntet]));
#pragma omp parallel for schedule(dynamic, 1024)
  for (int t = 0; t < m.ntet; ++t) {
    long long k = first[t];
    for (int f = 0; f < 4; ++f) {
      if (!emitted(t, f)) continue;
      Facet& fc = facets[k++];
      double x[3];
      int tri = -1;
      fc.ok = rdt3d::surface_centre(ms, tree, c, t, f, x, &tri);
      bool off_surface = false;
      if (!fc.ok && c.inside) {
        // A face between inside and outside whose dual misses the surface (one that changed
        // side at a pinch): the surface point on its normal line through its circumcentre
        // (within four circumradii), else the circumcentre itself, counted bad.
        const double* p0 = m3d::pt(ms, m.tv[4 * t + m3d::face_corner(f, 0)]);
        const double* p1 = m3d::pt(ms, m.tv[4 * t + m3d::face_corner(f, 1)]);
        const double* p2 = m3d::pt(ms, m.tv[4 * t + m3d::face_corner(f, 2)]);
        double cc[3] = {(p0[0] + p1[0] + p2[0]) / 3, (p0[1] + p1[1] + p2[1]) / 3, (p0[2] + p1[2] + p2[2]) / 3}, n[3];
        double o[3];
        if (m3d::tri_circumcenter(p0, p1, p2, o))  // else the centroid (a degenerate face)
          for (int k = 0; k < 3; ++k) cc[k] = o[k];
        const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]},
                     e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        m3d::cross3(e1, e2, n);
        const double scale_n = 4 * std::sqrt(m3d::dist2(cc, p0) / std::max(m3d::dot3(n, n), 1e-300));
        const double lo[3] = {cc[0] - scale_n * n[0], cc[1] - scale_n * n[1], cc[2] - scale_n * n[2]};
        const double hi[3] = {cc[0] + scale_n * n[0], cc[1] + scale_n * n[1], cc[2] + scale_n * n[2]};
        if (!rdt3d::surface_point_on_segment(tree, lo, hi, p0, x, &tri)) {
          for (int k = 0; k < 3; ++k) x[k] = cc[k];
          off_surface = true;
        }
        fc.ok = true;
      }
      if (!fc.ok) continue;
      int* v = fc.v;
      for (int q = 0; q < 3; ++q) v[q] = m.tv[4 * t + m3d::face_corner(f, q)];
      // Face order is counter-clockwise seen from outside t: keep it when t is the inside.
      const int nb = m.tn[4 * t + f];
      const bool in_t = (out.tflag[t] & rdt3d::kInterior) != 0;
      const bool in_u = nb >= 0 && (out.tflag[nb >> 2] & rdt3d::kInterior) != 0;
      bool flip;
      if (c.inside && in_t != in_u) {
        flip = !in_t;
        fc.vote.certain = true;
      } else {
        // Along the input triangle's normal (outward when the input's volume is positive).
        const double* a = rdt3d::corner(tree, tri, 0);
        const double* b = rdt3d::corner(tree, tri, 1);
        const double* d = rdt3d::corner(tree, tri, 2);
        const double u1[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, u2[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
        double n[3], w[3];
        m3d::cross3(u1, u2, n);
        const double* p0 = m3d::pt(ms, v[0]);
        const double* p1 = m3d::pt(ms, v[1]);
        const double* p2 = m3d::pt(ms, v[2]);
        const double e1[3] = {p1[0] - p0[0], p1[1] - p0[1], p1[2] - p0[2]},
                     e2[3] = {p2[0] - p0[0], p2[1] - p0[1], p2[2] - p0[2]};
        m3d::cross3(e1, e2, w);
        flip = (m3d::dot3(n, w) < 0) != (c.inside && signed_volume < 0);
        fc.vote.weight = std::fabs(m3d::dot3(n, w)) / std::max(std::sqrt(m3d::dot3(n, n)), 1e-300);  // area x cosine
      }
      if (flip) std::swap(v[1], v[2]);
      const Point3 a{out.xyz[3 * v[0]], out.xyz[3 * v[0] + 1], out.xyz[3 * v[0] + 2]};
      const Point3 b{out.xyz[3 * v[1]], out.xyz[3 * v[1] + 1], out.xyz[3 * v[1] + 2]};
      const Point3 d{out.xyz[3 * v[2]], out.xyz[3 * v[2] + 1], out.xyz[3 * v[2] + 2]};
      double cc[3] = {x[0], x[1], x[2]};  // kept for a degenerate facet
      const double* pa = m3d::pt(ms, v[0]);
      m3d::tri_circumcenter(pa, m3d::pt(ms, v[1]), m3d::pt(ms, v[2]), cc);
      fc.size = std::sqrt(m3d::dist2(x, pa));
      fc.dist = std::sqrt(m3d::dist2(x, cc));
      // Angles from the edge lengths (law of cosines), smallest opposite the shortest edge.
      auto len = [](const Point3& p, const Point3& q) {
        return std::sqrt((p.x - q.x) * (p.x - q.x) + (p.y - q.y) * (p.y - q.y) + (p.z - q.z) * (p.z - q.z));
      };
      const double la = len(b, d), lb = len(a, d), lc = len(a, b);
      const double lmin = std::min({la, lb, lc});
      const double o1 = lmin == la ? lb : la, o2 = lmin == lc ? lb : lc;
      const double cosine = std::clamp((o1 * o1 + o2 * o2 - lmin * lmin) / (2 * o1 * o2), -1.0, 1.0);
      fc.angle = std::acos(cosine) * 180 / kPi;
      const double ux[3] = {b.x - a.x, b.y - a.y, b.z - a.z}, vx[3] = {d.x - a.x, d.y - a.y, d.z - a.z};
      double nx[3];
      m3d::cross3(ux, vx, nx);
      fc.area = 0.5 * std::sqrt(m3d::dot3(nx, nx));
      fc.bad = off_surface || rdt3d::facet_is_bad(ms, c, t, f, x) ? 1 : 0;
    }
  }
  // Facets oriented by the input's normals: the same way across each patch of the surface.
  steps("facets");
  if (std::any_of(facets.begin(), facets.end(), [](const Facet& fc) { return fc.ok && !fc.vote.certain; })) {
    std::vector<int> tri;
    std::vector<m3d::OrientVote> votes;
    for (const Facet& fc : facets)
      if (fc.ok) {
        tri.insert(tri.end(), fc.v, fc.v + 3);
        votes.push_back(fc.vote);
      }
    const m3d::OrientResult o = m3d::orient_consistently(tri, votes);
    std::size_t k = 0;
    for (Facet& fc : facets)
      if (fc.ok) std::copy(tri.begin() + 3 * k, tri.begin() + 3 * k + 3, fc.v), ++k;
    if (o.non_orientable > 0 && cb.warning)
      cb.warning("the surface cannot be oriented consistently: " + std::to_string(o.non_orientable) +
                 " edge(s) join triangles that face opposite ways (the input touches itself or is not orientable there)");
    steps("orientation");
  }
  result.facet_angle_histogram.assign(61, 0);
  double min_angle = 180, max_size = 0, max_dist = 0, area = 0;
  for (const Facet& fc : facets) {
    if (!fc.ok) continue;
    tm.subfaces.push_back({use(fc.v[0]), use(fc.v[1]), use(fc.v[2])});
    result.facet_min_angle.push_back(static_cast<float>(fc.angle));
    result.facet_size.push_back(fc.size);
    result.facet_distance.push_back(fc.dist);
    result.facet_is_bad.push_back(fc.bad);
    ++result.facet_angle_histogram[std::min(60, std::max(0, static_cast<int>(fc.angle)))];
    min_angle = std::min(min_angle, fc.angle);
    max_size = std::max(max_size, fc.size);
    max_dist = std::max(max_dist, fc.dist);
    area += fc.area;
  }
  st.output_triangles = static_cast<long long>(tm.subfaces.size());
  if (pinch_pass) {  // what the relabelling left: facets at its places
    std::vector<char> left(m.npts, 0);
    for (const int v : pinches.left_at) left[v] = 1;
    st.non_manifold_facets = 0;
    for (const Facet& fc : facets)
      st.non_manifold_facets += fc.ok && (left[fc.v[0]] || left[fc.v[1]] || left[fc.v[2]]);
  }
  if (st.non_manifold_facets > 0 && cb.warning)
    cb.warning("the surface is not a manifold at " + std::to_string(st.non_manifold_facets) + " facet(s)" +
               (options.manifold ? ": the input is thinner there than facets of " +
                                       std::to_string(scale.length(st.manifold_min_size, -1)) +
                                       " (the manifold criterion's smallest) can resolve, or they are next to "
                                       "features at small angles"
                                 : std::string(" (the manifold criterion is off)")));
  for (unsigned char b : result.facet_is_bad) st.bad_facets += b;
  st.min_facet_angle_deg = tm.subfaces.empty() ? 0 : min_angle;
  st.max_facet_size = max_size;
  st.max_facet_distance = max_dist;
  st.area = area;

  result.dihedral_histogram.assign(180, 0);
  if (st.volume_meshed) {
    std::vector<int> interior;  // the engine's number of each output tetrahedron
    for (int t = 0; t < m.ntet; ++t) {
      if (!(out.tflag[t] & rdt3d::kInterior)) continue;
      const int* q = m.tv + 4 * t;
      tm.tets.push_back({use(q[0]), use(q[1]), use(q[2]), use(q[3])});
      interior.push_back(t);
    }
    TetQualityArrays q = tet_quality_arrays(tm.points, tm.tets);
    move_tet_quality(q, result);
    const int n = static_cast<int>(interior.size());
    result.is_bad.resize(n);
    long long bad = 0;
#pragma omp parallel for reduction(+ : bad)
    for (int i = 0; i < n; ++i) {
      const int t = interior[i];
      result.is_bad[i] = rdt3d::classify_cell(m, c, t, rdt3d::tet_size(m, t)) != rdt3d::kCellGood;
      bad += result.is_bad[i];
    }
    st.bad_tets = bad;
    st.volume = q.total_volume;
    st.min_dihedral_deg = q.min_dihedral_deg;
    st.max_dihedral_deg = q.max_dihedral_deg;
    st.max_radius_edge = q.max_radius_edge;
  }
  // Feature subsegments (each edge once) and the input's feature edges, on output points.
  std::set<std::uint64_t> seen;
  for (int t = 0; t < m.ntet; ++t)
    for (int e = 0; e < 6; ++e) {
      if (!(out.tflag[t] & (m3d::kSeg0 << e))) continue;
      const int a = m.tv[4 * t + m3d::edge_corner(e, 0)], b = m.tv[4 * t + m3d::edge_corner(e, 1)];
      if (seen.insert(edge_key(a, b)).second) tm.subsegments.push_back({use(a), use(b)});
    }
  for (const auto& e : feature_ends) result.features.push_back({use(e[0]), use(e[1])});
  for (PointType t : tm.point_type) st.feature_points += t == PointType::Input || t == PointType::Segment;
  if (options.keep_triangulation) {
    TetMesh& all = result.triangulation;
    all.points.resize(m.npts);
    all.point_type.resize(m.npts);
    for (int v = 0; v < m.npts; ++v) {
      all.points[v] = {out.xyz[3 * v], out.xyz[3 * v + 1], out.xyz[3 * v + 2]};
      all.point_type[v] = static_cast<PointType>(out.ptype[v]);
    }
    all.tets.resize(m.ntet);
    for (int t = 0; t < m.ntet; ++t) all.tets[t] = {m.tv[4 * t], m.tv[4 * t + 1], m.tv[4 * t + 2], m.tv[4 * t + 3]};
  }
  // Back to the input's scale.
  for (Point3& p : tm.points) p = scale.apply(p, -1);
  for (Point3& p : result.triangulation.points) p = scale.apply(p, -1);
  for (double& v : result.volume) v = scale.volume(v, -1);
  for (double& v : result.facet_size) v = scale.length(v, -1);
  for (double& v : result.facet_distance) v = scale.length(v, -1);
  st.volume = scale.volume(st.volume, -1);
  st.area = scale.area(st.area, -1);
  for (double* v : {&st.max_facet_size, &st.max_facet_distance, &st.facet_size, &st.facet_distance, &st.cell_size,
                    &st.feature_min_length, &st.manifold_min_size})
    *v = scale.length(*v, -1);
  st.output_points = static_cast<long long>(tm.points.size());
  st.output_tets = static_cast<long long>(tm.tets.size());
  if (st.stalled && cb.warning)
    cb.warning("refinement stopped: the elements left cannot be split further; " +
               std::to_string(st.bad_facets) + " facets and " + std::to_string(st.bad_tets) +
               " tetrahedra remain above the bounds");
  st.output_seconds = since(t_output);
  st.total_seconds = since(t_start);
  progress(1.0, "done");
  return result;
}

}  // namespace gdr
