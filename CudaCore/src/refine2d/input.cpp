#include "refine2d/input.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <new>
#include <parallel/algorithm>
#include <sstream>

#include "predicates/predicates.h"
#include "common/trace.h"

namespace gdr::r2d {

[[noreturn]] void invalid(const std::string& msg) { throw Error(Status::InvalidInput, msg); }

std::string list_ints(const std::vector<long long>& v, std::size_t total) {
  std::ostringstream s;
  for (std::size_t i = 0; i < v.size(); ++i) s << (i ? ", " : "") << v[i];
  if (total > v.size()) s << ", ... (" << total << " in all)";
  return s.str();
}

namespace {

int sgn(double v) { return (v > 0) - (v < 0); }

const double* xy(const std::vector<Point2>& p, int i) { return &p[i].x; }

// Is c strictly between a and b, given that a, b, c are collinear?
bool strictly_between(const Point2& a, const Point2& b, const Point2& c) {
  if (a.x != b.x) return (a.x < c.x && c.x < b.x) || (b.x < c.x && c.x < a.x);
  return (a.y < c.y && c.y < b.y) || (b.y < c.y && c.y < a.y);
}

bool conflict(const std::vector<Point2>& P, const std::array<int, 2>& s,
              const std::array<int, 2>& t, SegmentConflict::Kind& kind) {
  const int a = s[0], b = s[1], c = t[0], d = t[1];
  const int o1 = sgn(pred::orient2d(xy(P, a), xy(P, b), xy(P, c)));
  const int o2 = sgn(pred::orient2d(xy(P, a), xy(P, b), xy(P, d)));
  if (o1 == 0 && o2 == 0) {  // collinear: overlap if the interiors share a point
    const bool shared = a == c || a == d || b == c || b == d;
    if (strictly_between(P[a], P[b], P[c]) || strictly_between(P[a], P[b], P[d]) ||
        strictly_between(P[c], P[d], P[a]) || strictly_between(P[c], P[d], P[b]) ||
        (shared && ((a == c && b == d) || (a == d && b == c)))) {
      kind = SegmentConflict::Overlap;
      return true;
    }
    return false;
  }
  const int o3 = sgn(pred::orient2d(xy(P, c), xy(P, d), xy(P, a)));
  const int o4 = sgn(pred::orient2d(xy(P, c), xy(P, d), xy(P, b)));
  if (o1 * o2 < 0 && o3 * o4 < 0) {
    kind = SegmentConflict::Cross;
    return true;
  }
  kind = SegmentConflict::Touch;
  if (o1 == 0 && c != a && c != b && strictly_between(P[a], P[b], P[c])) return true;
  if (o2 == 0 && d != a && d != b && strictly_between(P[a], P[b], P[d])) return true;
  if (o3 == 0 && a != c && a != d && strictly_between(P[c], P[d], P[a])) return true;
  if (o4 == 0 && b != c && b != d && strictly_between(P[c], P[d], P[b])) return true;
  return false;
}

// Indices 0..n-1 in order of key(i), ties by index: the (key, index) pairs are sorted in
// parallel as contiguous values, not indices compared through the keys (cache misses).
template <class Key>
std::vector<int> sorted_indices(std::size_t n, const Key& key) {
  using K = decltype(key(0));
  std::vector<std::pair<K, int>> kv(n);
  const long long nl = static_cast<long long>(n);
#pragma omp parallel for
  for (long long i = 0; i < nl; ++i) kv[i] = {key(static_cast<int>(i)), static_cast<int>(i)};
  __gnu_parallel::sort(kv.begin(), kv.end());
  std::vector<int> order(n);
#pragma omp parallel for
  for (long long i = 0; i < nl; ++i) order[i] = kv[i].second;
  return order;
}

void dedupe_segments(CleanPslg& g, const Callbacks& cb) {
  const std::size_t n = g.segments.size();
  const long long nl = static_cast<long long>(n);
  std::vector<long long> key(n);
#pragma omp parallel for
  for (long long s = 0; s < nl; ++s) {
    const int a = std::min(g.segments[s][0], g.segments[s][1]);
    const int b = std::max(g.segments[s][0], g.segments[s][1]);
    key[s] = (static_cast<long long>(a) << 32) | b;
  }
  const std::vector<int> order = sorted_indices(n, [&](int i) { return key[i]; });
  std::vector<char> repeat(n, 0);  // the same segment as an earlier one
  long long dropped = 0;
#pragma omp parallel for reduction(+ : dropped)
  for (long long k = 1; k < nl; ++k) {
    repeat[order[k]] = key[order[k]] == key[order[k - 1]];
    dropped += repeat[order[k]];
  }
  if (!dropped) return;
  std::vector<std::array<int, 2>> segs;
  std::vector<int> origin;
  segs.reserve(n - dropped);
  origin.reserve(n - dropped);
  for (std::size_t s = 0; s < n; ++s) {
    if (repeat[s]) continue;
    segs.push_back(g.segments[s]);
    origin.push_back(g.segment_origin[s]);
  }
  if (cb.warning) cb.warning(std::to_string(dropped) + " duplicate segment(s) ignored");
  g.segments.swap(segs);
  g.segment_origin.swap(origin);
}

}  // namespace

std::vector<SegmentConflict> find_segment_conflicts(const std::vector<Point2>& P,
                                                    const std::vector<std::array<int, 2>>& S,
                                                    std::size_t limit) {
  std::vector<SegmentConflict> found;
  if (S.size() < 2) return found;
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  const long long ns = static_cast<long long>(S.size());
#pragma omp parallel for reduction(min : x0, y0) reduction(max : x1, y1)
  for (long long i = 0; i < ns; ++i)
    for (int v : S[i]) {
      x0 = std::min(x0, P[v].x), x1 = std::max(x1, P[v].x);
      y0 = std::min(y0, P[v].y), y1 = std::max(y1, P[v].y);
    }
  // Uniform grid with about one segment per cell; each segment goes into the cells its
  // bounding box covers, and pairs are tested exactly within each cell.
  const int g = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(S.size()))), 1, 2048);
  const double w = std::max(x1 - x0, y1 - y0);
  const double h = w > 0 ? w / g : 1.0;
  auto cell = [&](double v, double o) {
    return std::clamp(static_cast<int>((v - o) / h), 0, g - 1);
  };
  // The cells as one array (counted, then filled): a vector per cell would be a million
  // small allocations for a million segments.
  const std::size_t ncells = static_cast<std::size_t>(g) * g;
  auto for_cells = [&](std::size_t i, auto&& f) {
    const Point2 &a = P[S[i][0]], &b = P[S[i][1]];
    const int cx0 = cell(std::min(a.x, b.x), x0), cx1 = cell(std::max(a.x, b.x), x0);
    const int cy0 = cell(std::min(a.y, b.y), y0), cy1 = cell(std::max(a.y, b.y), y0);
    for (int cy = cy0; cy <= cy1; ++cy)
      for (int cx = cx0; cx <= cx1; ++cx) f(static_cast<std::size_t>(cy) * g + cx);
  };
  // Counted and filled in parallel (atomics), then each cell's list sorted, so that what is
  // found does not depend on thread timing.
  std::vector<std::size_t> begin(ncells + 1, 0);
#pragma omp parallel for
  for (long long i = 0; i < ns; ++i)
    for_cells(i, [&](std::size_t c) { __atomic_fetch_add(&begin[c + 1], 1, __ATOMIC_RELAXED); });
  for (std::size_t c = 0; c < ncells; ++c) begin[c + 1] += begin[c];
  std::vector<int> in_cell(begin[ncells]);
  {
    std::vector<std::size_t> fill(begin.begin(), begin.end() - 1);
#pragma omp parallel for
    for (long long i = 0; i < ns; ++i)
      for_cells(i, [&](std::size_t c) {
        in_cell[__atomic_fetch_add(&fill[c], 1, __ATOMIC_RELAXED)] = static_cast<int>(i);
      });
    const long long nc = static_cast<long long>(ncells);
#pragma omp parallel for schedule(dynamic, 4096)
    for (long long c = 0; c < nc; ++c) std::sort(in_cell.begin() + begin[c], in_cell.begin() + begin[c + 1]);
  }
  // Points that end no segment may still lie on one (the CDT would split it silently).
  std::vector<char> is_end(P.size(), 0);
  for (const auto& s : S) is_end[s[0]] = is_end[s[1]] = 1;
  std::vector<std::pair<std::size_t, int>> loose;  // (cell, point)
  for (std::size_t v = 0; v < P.size(); ++v)
    if (!is_end[v] && P[v].x >= x0 && P[v].x <= x1 && P[v].y >= y0 && P[v].y <= y1)
      loose.push_back({static_cast<std::size_t>(cell(P[v].y, y0)) * g + cell(P[v].x, x0), int(v)});
  std::sort(loose.begin(), loose.end());
  const long long ncell = static_cast<long long>(ncells);
#pragma omp parallel
  {
    std::vector<SegmentConflict> local;
#pragma omp for schedule(dynamic, 64)
    for (long long c = 0; c < ncell; ++c) {
      const int* list = in_cell.data() + begin[c];
      const std::size_t len = begin[c + 1] - begin[c];
      for (std::size_t i = 0; i < len && local.size() < limit; ++i)
        for (std::size_t j = i + 1; j < len; ++j) {
          SegmentConflict::Kind kind;
          if (conflict(P, S[list[i]], S[list[j]], kind))
            local.push_back({std::min(list[i], list[j]), std::max(list[i], list[j]), kind});
        }
      auto lp = std::lower_bound(loose.begin(), loose.end(), std::make_pair(std::size_t(c), -1));
      for (; lp != loose.end() && lp->first == std::size_t(c); ++lp)
        for (std::size_t k = 0; k < len; ++k) {
          const int s = list[k], v = lp->second;
          if (pred::orient2d(xy(P, S[s][0]), xy(P, S[s][1]), xy(P, v)) == 0 &&
              strictly_between(P[S[s][0]], P[S[s][1]], P[v]))
            local.push_back({s, -1, SegmentConflict::Touch, v});
        }
    }
#pragma omp critical
    found.insert(found.end(), local.begin(), local.end());
  }
  std::sort(found.begin(), found.end(), [](const SegmentConflict& a, const SegmentConflict& b) {
    return a.s != b.s ? a.s < b.s : (a.t != b.t ? a.t < b.t : a.point < b.point);
  });
  found.erase(std::unique(found.begin(), found.end(),
                          [](const SegmentConflict& a, const SegmentConflict& b) {
                            return a.s == b.s && a.t == b.t && a.point == b.point;
                          }),
              found.end());
  if (found.size() > limit) found.resize(limit);
  return found;
}

}  // namespace gdr::r2d

namespace gdr {
using r2d::invalid;
using r2d::list_ints;

namespace {

std::string shown(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

bool normal(double v) { return v >= DBL_MIN && v <= DBL_MAX; }

// The kernels compare squared edge lengths, twice the area and sin^2 of the angle: a bound
// whose square (or double) leaves the normal doubles would become 0 (off) or infinity (never
// met), or lose its precision, and be ignored. Such a bound is refused, unless no element of
// the input's extent could exceed it anyway.
void check_bounds_representable(const Pslg& in, const Refine2dOptions& o) {
  double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
  for (const Point2& p : in.points) {
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
    y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
  }
  const double w = x1 - x0, h = y1 - y0;
  const double l = o.max_edge_length, a = o.max_area;
  if (l > 0 && l < std::hypot(w, h) && !normal(l * l))
    invalid("maximum edge length " + shown(l) + " cannot be honoured: its square " +
            (l * l > 1 ? "overflows" : "underflows") + " the range of doubles (rescale the input)");
  if (a > 0 && a < w * h && !normal(2 * a))
    invalid("maximum area " + shown(a) + " cannot be honoured: it " +
            (a > 1 ? "overflows" : "underflows") + " the range of doubles (rescale the input)");
  const double s = std::sin(o.min_angle * 3.14159265358979323846 / 180.0);
  if (o.min_angle > 0 && !normal(s * s))
    invalid("minimum angle " + shown(o.min_angle) +
            " degrees is too small to be honoured (its sine squared underflows); 0 turns the "
            "angle criterion off");
}

}  // namespace

void validate_refine2d_input(const Pslg& in, const Refine2dOptions& o) {
  if (!(o.min_angle >= 0) || o.min_angle > 34.0)
    invalid("minimum angle " + std::to_string(o.min_angle) +
            " is out of range [0, 34] degrees: above about 34 degrees Delaunay refinement "
            "cannot be guaranteed to terminate");
  if (!(o.max_edge_length >= 0) || !std::isfinite(o.max_edge_length))
    invalid("maximum edge length must be a finite number >= 0 (0 = off)");
  if (!(o.max_area >= 0) || !std::isfinite(o.max_area))
    invalid("maximum area must be a finite number >= 0 (0 = off)");
  if (o.max_steiner_points < -1) invalid("maximum Steiner points must be -1 (unlimited) or >= 0");
  if (in.points.empty()) invalid("the input has no points");
  // Counted in parallel (1M points took 10 ms on one thread); the offenders are listed
  // only when there are any.
  const long long np = static_cast<long long>(in.points.size());
  const long long ns = static_cast<long long>(in.segments.size());
  const auto point_bad = [&](long long i) { return !std::isfinite(in.points[i].x) || !std::isfinite(in.points[i].y); };
  const auto segment_bad = [&](long long s) {
    const auto& sg = in.segments[s];
    return sg[0] < 0 || sg[1] < 0 || sg[0] >= np || sg[1] >= np;
  };
  const auto listed = [](long long n, const auto& is_bad, int first_index, std::size_t& nbad) {
    std::vector<long long> bad;
    nbad = 0;
#pragma omp parallel for reduction(+ : nbad)
    for (long long i = 0; i < n; ++i) nbad += is_bad(i);
    for (long long i = 0; nbad && i < n && bad.size() < 10; ++i)
      if (is_bad(i)) bad.push_back(i + first_index);
    return bad;
  };
  std::size_t nbad = 0;
  std::vector<long long> bad = listed(np, point_bad, in.first_index, nbad);
  if (nbad) invalid("points with NaN or infinite coordinates: " + list_ints(bad, nbad));
  bad = listed(ns, segment_bad, in.first_index, nbad);
  if (nbad)
    invalid("segments referencing missing points (there are " + std::to_string(np) +
            " points): segment " + list_ints(bad, nbad));
  long long zero = ns;  // the first segment of zero length
#pragma omp parallel for reduction(min : zero)
  for (long long s = 0; s < ns; ++s) {
    const auto& sg = in.segments[s];
    const Point2 &a = in.points[sg[0]], &b = in.points[sg[1]];
    if (sg[0] == sg[1] || (a.x == b.x && a.y == b.y)) zero = std::min(zero, s);
  }
  if (zero < ns) {
    const auto& sg = in.segments[zero];
    invalid("segment " + std::to_string(zero + in.first_index) + " has zero length (points " +
            std::to_string(sg[0] + in.first_index) + " and " + std::to_string(sg[1] + in.first_index) +
            " coincide)");
  }
  for (std::size_t h = 0; h < in.holes.size(); ++h)
    if (!std::isfinite(in.holes[h].x) || !std::isfinite(in.holes[h].y))
      invalid("hole " + std::to_string(h + in.first_index) + " has NaN or infinite coordinates");
  if (in.regions.size() > static_cast<std::size_t>(r2d::kMaxRegions))
    invalid(std::to_string(in.regions.size()) + " regions: at most " + std::to_string(r2d::kMaxRegions) + " are supported");
  for (std::size_t r = 0; r < in.regions.size(); ++r) {
    const RegionSeed2& g = in.regions[r];
    if (!std::isfinite(g.point.x) || !std::isfinite(g.point.y) || !std::isfinite(g.attribute) ||
        !std::isfinite(g.max_area))
      invalid("region " + std::to_string(r + in.first_index) + " has a NaN or infinite value");
  }
  // Three non-collinear points are needed for any triangle.
  std::size_t i1 = 0;
  while (i1 < in.points.size() && in.points[i1].x == in.points[0].x &&
         in.points[i1].y == in.points[0].y)
    ++i1;
  bool area = false;
  for (std::size_t i = i1 + 1; i1 < in.points.size() && i < in.points.size() && !area; ++i)
    area = pred::orient2d(&in.points[0].x, &in.points[i1].x, &in.points[i].x) != 0;
  if (!area) invalid("the input needs at least three points that are not collinear");
  check_bounds_representable(in, o);
}

}  // namespace gdr

namespace gdr::r2d {
namespace {

// A few conflicts and their count, with segments and points numbered as in the input file.
std::string conflict_message(const CleanPslg& g, const std::vector<SegmentConflict>& conflicts,
                             std::size_t count_limit, bool after_split) {
  const int base = g.first_index;
  auto seg = [&](int s) {
    return "segment " + std::to_string(g.segment_origin[s] + base);
  };
  auto pt = [&](int v) {
    const int o = g.point_origin[v];
    if (o >= 0) return "point " + std::to_string(o + base);
    std::ostringstream s;
    s << "intersection point (" << g.points[v].x << ", " << g.points[v].y << ")";
    return s.str();
  };
  std::ostringstream msg;
  msg.precision(17);
  const std::size_t shown = 5;
  msg << (after_split ? "internal error: segments still intersect after splitting them: "
                      : "segments intersect other than at shared endpoints: ");
  for (std::size_t i = 0; i < conflicts.size() && i < shown; ++i) {
    const auto& c = conflicts[i];
    if (i) msg << "; ";
    if (c.t < 0) {
      msg << pt(c.point) << " lies on " << seg(c.s);
      continue;
    }
    msg << seg(c.s) << " and " << seg(c.t)
        << (c.kind == SegmentConflict::Cross   ? " cross"
            : c.kind == SegmentConflict::Touch ? " touch"
                                               : " overlap");
  }
  if (conflicts.size() > shown)
    msg << "; and " << conflicts.size() - shown << " more ("
        << (conflicts.size() >= count_limit ? "at least " : "") << conflicts.size()
        << " in all)";
  if (!after_split) msg << " (strict input refuses them; without it they are split)";
  return msg.str();
}

// Merges each intersection point (point_origin -1) into another point within `eps` in both
// coordinates (an input point first): nearly concurrent segments, whose rounded endpoints
// make them miss one point by a few ulps, would otherwise leave clusters of intersection
// points 1e-16 apart that no refinement can resolve. Returns whether anything moved.
bool merge_close_intersections(CleanPslg& g, double eps) {
  const std::size_t n = g.points.size();
  std::vector<int> order;
  for (std::size_t v = 0; v < n; ++v) order.push_back(static_cast<int>(v));
  // By x: a sweep over the points within eps in x.
  std::sort(order.begin(), order.end(), [&](int a, int b) { return g.points[a].x < g.points[b].x; });
  std::vector<int> to(n);
  for (std::size_t v = 0; v < n; ++v) to[v] = static_cast<int>(v);
  bool changed = false;
  for (std::size_t i = 0; i < order.size(); ++i) {
    const int v = order[i];
    if (g.point_origin[v] >= 0) continue;  // only intersection points move
    int best = -1;
    for (std::size_t j = i; j-- > 0;) {  // earlier in x within eps
      const int u = order[j];
      if (g.points[v].x - g.points[u].x > eps) break;
      if (std::fabs(g.points[v].y - g.points[u].y) > eps || to[u] != u) continue;
      if (best < 0 || (g.point_origin[u] >= 0 && g.point_origin[best] < 0)) best = u;
    }
    for (std::size_t j = i + 1; j < order.size(); ++j) {  // input points later in x
      const int u = order[j];
      if (g.points[u].x - g.points[v].x > eps) break;
      if (g.point_origin[u] >= 0 && std::fabs(g.points[v].y - g.points[u].y) <= eps &&
          (best < 0 || g.point_origin[best] < 0))
        best = u;
    }
    if (best >= 0) {
      to[v] = best;
      changed = true;
    }
  }
  if (!changed) return false;
  std::vector<std::array<int, 2>> segs;
  std::vector<int> origin;
  for (std::size_t s = 0; s < g.segments.size(); ++s) {
    const int a = to[g.segments[s][0]], b = to[g.segments[s][1]];
    if (a == b) continue;
    segs.push_back({a, b});
    origin.push_back(g.segment_origin[s]);
  }
  g.segments.swap(segs);
  g.segment_origin.swap(origin);
  // Drop the merged points (intersection points only: input numbering is kept).
  std::vector<int> renum(n, -1);
  std::vector<Point2> pts;
  std::vector<int> porig;
  for (std::size_t v = 0; v < n; ++v)
    if (to[v] == static_cast<int>(v)) {
      renum[v] = static_cast<int>(pts.size());
      pts.push_back(g.points[v]);
      porig.push_back(g.point_origin[v]);
    }
  for (auto& sg : g.segments) sg = {renum[sg[0]], renum[sg[1]]};
  g.points.swap(pts);
  g.point_origin.swap(porig);
  // Merging can make two segments the same: keep one.
  std::vector<long long> keys;
  std::vector<std::array<int, 2>> uniq;
  std::vector<int> uorigin;
  std::vector<char> keep(g.segments.size(), 1);
  {
    std::vector<std::pair<long long, int>> k;
    for (std::size_t s = 0; s < g.segments.size(); ++s) {
      const int a = std::min(g.segments[s][0], g.segments[s][1]);
      const int b = std::max(g.segments[s][0], g.segments[s][1]);
      k.push_back({(static_cast<long long>(a) << 32) | b, static_cast<int>(s)});
    }
    std::sort(k.begin(), k.end());
    for (std::size_t i = 1; i < k.size(); ++i)
      if (k[i].first == k[i - 1].first) keep[k[i].second] = 0;
  }
  for (std::size_t s = 0; s < g.segments.size(); ++s)
    if (keep[s]) {
      uniq.push_back(g.segments[s]);
      uorigin.push_back(g.segment_origin[s]);
    }
  g.segments.swap(uniq);
  g.segment_origin.swap(uorigin);
  return true;
}

// What splitting did, for the warning: how many input segments were cut, into how many
// pieces, and how many intersection points were added (points lying on segments add none).
std::string split_summary(const CleanPslg& g) {
  std::vector<int> pieces;  // per input segment
  for (const int s : g.segment_origin) {
    if (s >= static_cast<int>(pieces.size())) pieces.resize(s + 1, 0);
    ++pieces[s];
  }
  long long cut = 0, pieces_of_cut = 0;
  for (const int n : pieces)
    if (n > 1) ++cut, pieces_of_cut += n;
  long long added = 0;
  for (const int o : g.point_origin) added += o < 0;
  std::ostringstream m;
  m << "split " << cut << " segment(s) into " << pieces_of_cut
    << " pieces where they cross, touch or overlap other segments or pass through points ("
    << added << " intersection point(s) added; strict input refuses such input)";
  return m.str();
}

// Every piece must lie on the input segment it came from, within the rounding of the
// intersection points (merged within eps, in up to 8 rounds) and a relative 1e-9. CGAL's
// splitting with inexact intersections once routed a segment of a star of 36 crossing near
// one point through a far endpoint: its second half was missing from the mesh, silently.
// Such a split is refused.
void check_pieces_on_their_segments(const Pslg& in, const CleanPslg& g, double eps) {
  for (std::size_t k = 0; k < g.segments.size(); ++k) {
    const int o = g.segment_origin[k];
    const Point2 &a = in.points[in.segments[o][0]], &b = in.points[in.segments[o][1]];
    const double dx = b.x - a.x, dy = b.y - a.y, len = std::hypot(dx, dy);
    // eps: each of up to 8 merging rounds, at most the segment's own precision (its
    // coordinates' magnitude: a segment near the origin of an input whose extent is 1e13
    // times larger was routed through points 1.5 units away, within the extent's precision).
    const double own = std::ldexp(std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(b.x), std::fabs(b.y), len}), -40);
    const double slack = 16 * std::min(eps, own) + 1e-9 * len;
    for (const int v : g.segments[k]) {
      const Point2& p = g.points[v];
      const double along = ((p.x - a.x) * dx + (p.y - a.y) * dy) / len;
      const double off = std::fabs((p.x - a.x) * dy - (p.y - a.y) * dx) / len;
      if (off <= slack && along >= -slack && along <= len + slack) continue;
      const long long f = in.first_index;
      std::ostringstream m;
      m << "segment " << o + f << " (points " << in.segments[o][0] + f << " and " << in.segments[o][1] + f
        << ") could not be split consistently where it crosses others (many segments crossing within "
           "rounding of one another, or coordinates that span too many orders of magnitude): its "
           "pieces reach "
        << (g.point_origin[v] >= 0 ? "point " + std::to_string(g.point_origin[v] + f) : std::string("an intersection point"))
        << ", off the segment; give the segments one input point where they cross";
      throw Error(Status::InvalidInput, m.str());
    }
  }
}

}  // namespace

CleanPslg clean_input(const Pslg& in, const Refine2dOptions& o, const Callbacks& cb, bool on_gpu) {
  TraceSteps step("input");
  validate_refine2d_input(in, o);
  step("checks");
  CleanPslg g;
  g.holes = in.holes;
  g.regions = in.regions;
  g.first_index = in.first_index;
#if defined(GDR_HAVE_CUDA)
  // (A device that cannot run the checks, out of memory say, leaves them to the host.)
  bool clean = false;
  if (on_gpu) {
    try {
      clean = input_is_clean_cuda(in.points, in.segments);
    } catch (const Error&) {
    } catch (const std::bad_alloc&) {
    }
  }
  if (clean) {
    step("clean, on the GPU");
    g.points = in.points;
    g.segments = in.segments;
    g.point_origin.resize(in.points.size());
    g.segment_origin.resize(in.segments.size());
    const long long np = static_cast<long long>(in.points.size()), ns = static_cast<long long>(in.segments.size());
#pragma omp parallel for
    for (long long i = 0; i < np; ++i) g.point_origin[i] = static_cast<int>(i);
#pragma omp parallel for
    for (long long s = 0; s < ns; ++s) g.segment_origin[s] = static_cast<int>(s);
    return g;
  }
#else
  (void)on_gpu;
#endif
  // Duplicate points: sorted by coordinates (-0 == 0), each run of equal points maps to its
  // first in input order; the kept points stay in input order.
  const std::size_t np = in.points.size();
  const auto& P = in.points;
  // (-0 and 0 compare equal as doubles, and NaN was refused.)
  const std::vector<int> order = sorted_indices(np, [&](int i) { return std::make_pair(P[i].x, P[i].y); });
  step("points sorted");
  // Each run of equal points (sorted by index within the run) starts at its first in input
  // order; runs are handled by their starts in parallel, and the kept points are numbered by
  // a scan.
  const long long npl = static_cast<long long>(np);
  const auto same = [&](int a, int b) { return P[a].x == P[b].x && P[a].y == P[b].y; };
  std::vector<int> first(np);  // first input index with the same coordinates
#pragma omp parallel for
  for (long long k = 0; k < npl; ++k) {
    if (k > 0 && same(order[k - 1], order[k])) continue;  // not a run start
    for (long long j = k; j < npl && (j == k || same(order[k], order[j])); ++j) first[order[j]] = order[k];
  }
  std::vector<int> remap(np);
  long long kept = 0;
  for (long long i = 0; i < npl; ++i) remap[i] = first[i] == i ? static_cast<int>(kept++) : -1;
  g.points.resize(kept);
  g.point_origin.resize(kept);
  g.duplicates_merged = npl - kept;
#pragma omp parallel for
  for (long long i = 0; i < npl; ++i) {
    if (remap[i] >= 0) {
      g.points[remap[i]] = P[i];
      g.point_origin[remap[i]] = static_cast<int>(i);
    }
  }
#pragma omp parallel for
  for (long long i = 0; i < npl; ++i)
    if (remap[i] < 0) remap[i] = remap[first[i]];  // first[i] < i is kept
  if (g.duplicates_merged && cb.warning)
    cb.warning(std::to_string(g.duplicates_merged) + " duplicate point(s) merged");
  g.segments.resize(in.segments.size());
  g.segment_origin.resize(in.segments.size());
  const long long nseg = static_cast<long long>(in.segments.size());
#pragma omp parallel for
  for (long long s = 0; s < nseg; ++s) {
    g.segments[s] = {remap[in.segments[s][0]], remap[in.segments[s][1]]};
    g.segment_origin[s] = static_cast<int>(s);
  }
  step("duplicate points merged");
  dedupe_segments(g, cb);
  step("duplicate segments");

  // Conflicts: by default CGAL's constrained triangulation splits every segment at all of
  // them at once (exact predicates, consistent rounding), and the result is checked again.
  // With strict input they are refused, naming a few.
  const std::size_t count_limit = std::size_t(1) << 22;
  const bool split = !o.strict_input;
  // (With splitting, one conflict is enough to know that the segments must be split.)
  auto conflicts = find_segment_conflicts(g.points, g.segments, split ? 1 : count_limit);
  step("crossings");
  if (conflicts.empty()) return g;
  if (split) {
    // Intersection points closer than 2^-40 of the extent are merged (snap rounding) and
    // the result split again, until nothing moves (a few rounds).
    double x0 = INFINITY, y0 = INFINITY, x1 = -INFINITY, y1 = -INFINITY;
    for (const Point2& p : g.points) {
      x0 = std::min(x0, p.x), x1 = std::max(x1, p.x);
      y0 = std::min(y0, p.y), y1 = std::max(y1, p.y);
    }
    const double eps = std::ldexp(std::max(x1 - x0, y1 - y0), -40);
    for (int round = 0; round < 8; ++round) {
      split_segments_at_intersections(g);
      g.point_origin.resize(g.points.size(), -1);
      if (round == 7 || !merge_close_intersections(g, eps)) break;  // ends split
    }
    conflicts = find_segment_conflicts(g.points, g.segments, count_limit);
    if (conflicts.empty()) {
      check_pieces_on_their_segments(in, g, eps);
      if (cb.warning) cb.warning(split_summary(g));
      return g;
    }
  }
  throw Error(split ? Status::InternalError : Status::SelfIntersectingInput,
              conflict_message(g, conflicts, count_limit, split));
}

}  // namespace gdr::r2d
