// What Triangle's output carries besides the mesh: boundary markers, point attributes and
// regional attributes, carried from the input to the refined mesh (input.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "refine2d/input.h"

namespace gdr::r2d {
namespace {

// Where a point added by splitting lies along the input segment s, in [0, 1].
double along(const Pslg& in, int s, const Point2& p) {
  const Point2 &a = in.points[in.segments[s][0]], &b = in.points[in.segments[s][1]];
  const double dx = b.x - a.x, dy = b.y - a.y;
  return std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / (dx * dx + dy * dy), 0.0, 1.0);
}

}  // namespace

void carry_input_data(const Pslg& in, const CleanPslg& g, const double* xy, const int* subseg,
                      const int* tregion, bool region_attributes, TriMesh& out) {
  const std::size_t np = out.points.size(), nclean = g.points.size();
  const bool point_marked = in.point_markers.size() == in.points.size();
  const bool segment_marked = in.segment_markers.size() == in.segments.size();

  // Markers, as Triangle assigns them.
  out.subsegment_markers.resize(out.subsegments.size());
  const long long nsubsegments = static_cast<long long>(out.subsegments.size());
#pragma omp parallel for
  for (long long k = 0; k < nsubsegments; ++k) {
    const int s = out.subsegment_source[k];
    const int marker = s >= 0 && segment_marked ? in.segment_markers[s] : 0;
    out.subsegment_markers[k] = marker == 0 && subseg[4 * k + 3] ? 1 : marker;
  }
  out.point_markers.resize(np);
  // An unmarked point takes the marker of the first marked segment through it in input
  // order (hull edges last), as Triangle inserts its segments: the least (segment, subsegment)
  // key among the marked subsegments at each point.
  FilledVector<unsigned long long> first(np);
  const long long npl = static_cast<long long>(np);
#pragma omp parallel for
  for (long long v = 0; v < npl; ++v) {
    out.point_markers[v] = 0;
    first[v] = ~0ull;
  }
  if (point_marked)
    for (std::size_t v = 0; v < nclean; ++v)
      if (g.point_origin[v] >= 0) out.point_markers[v] = in.point_markers[g.point_origin[v]];
  const long long nsub = static_cast<long long>(out.subsegments.size());
#pragma omp parallel for
  for (long long k = 0; k < nsub; ++k) {
    if (out.subsegment_markers[k] == 0) continue;
    const int s = out.subsegment_source[k];
    const unsigned long long key =
        (static_cast<unsigned long long>(s < 0 ? 0xffffffffu : static_cast<unsigned>(s)) << 32) |
        static_cast<unsigned>(k);
    for (const int v : out.subsegments[k]) {
      unsigned long long old = __atomic_load_n(&first[v], __ATOMIC_RELAXED);
      while (key < old && !__atomic_compare_exchange_n(&first[v], &old, key, true, __ATOMIC_RELAXED,
                                                       __ATOMIC_RELAXED)) {
      }
    }
  }
#pragma omp parallel for
  for (long long v = 0; v < npl; ++v)
    if (out.point_markers[v] == 0 && first[v] != ~0ull)
      out.point_markers[v] = out.subsegment_markers[first[v] & 0xffffffffu];

  // Point attributes: the input's own; along its segment for a point where segments were
  // split; over the input's constrained Delaunay triangulation for a Steiner point.
  const int na = in.point_attribute_count;
  if (na > 0 && in.point_attributes.size() == in.points.size() * na) {
    std::vector<double> clean(nclean * na, 0.0);
    std::vector<int> segment_at(nclean, -1);  // an input segment through each point
    for (std::size_t s = 0; s < g.segments.size(); ++s)
      for (const int v : g.segments[s]) segment_at[v] = g.segment_origin[s];
    for (std::size_t v = 0; v < nclean; ++v) {
      const int o = g.point_origin[v];
      if (o >= 0) {
        std::copy_n(&in.point_attributes[std::size_t(o) * na], na, &clean[v * na]);
      } else if (segment_at[v] >= 0) {  // an intersection point
        const int s = segment_at[v];
        const double t = along(in, s, g.points[v]);
        const double* a = &in.point_attributes[std::size_t(in.segments[s][0]) * na];
        const double* b = &in.point_attributes[std::size_t(in.segments[s][1]) * na];
        for (int j = 0; j < na; ++j) clean[v * na + j] = (1 - t) * a[j] + t * b[j];
      }
    }
    std::vector<Point2> steiner(np - std::min(np, nclean));
    for (std::size_t i = 0; i < steiner.size(); ++i)
      steiner[i] = {xy[2 * (nclean + i)], xy[2 * (nclean + i) + 1]};
    const std::vector<double> interpolated = interpolate_over_cdt(g, clean, na, steiner);
    out.point_attribute_count = na;
    out.point_attributes = std::move(clean);
    out.point_attributes.insert(out.point_attributes.end(), interpolated.begin(), interpolated.end());
  }

  // Regional attributes (Triangle's -A): 0 outside every seeded region.
  if (region_attributes && tregion && !in.regions.empty()) {
    out.triangle_region.resize(out.triangles.size());
    for (std::size_t t = 0; t < out.triangles.size(); ++t)
      out.triangle_region[t] = tregion[t] > 0 ? in.regions[tregion[t] - 1].attribute : 0.0;
  }
}

}  // namespace gdr::r2d
