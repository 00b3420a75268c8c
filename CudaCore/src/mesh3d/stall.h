// Stall detection for the 3D engines (gQM3d, gDP3d): what is left to split can no longer be
// split by the method when, over kWindow iterations, the elements left to split did not
// shrink by a fiftieth, the mesh did not grow by a quarter (refinement to a size bound
// first multiplies the elements to split) and the volume of the bad tetrahedra (where the
// engine reports it) did not shrink by a fiftieth either, or when the same backlog comes back
// kSame iterations in a row (the same elements failing again). The volume matters while the
// interior is still empty: each point then replaces large bad tetrahedra by many smaller
// ones, so the backlog grows while a few dozen points go in per iteration; without it a
// 1M-tetrahedron run stopped with a quarter of its volume bad (H100, 2026-11-24). With
// `turnover` (gDP3d), a window in which at least as many points went in as there were
// elements to split at its start is progress too: its end game near narrow slots and
// features inserts a few points per iteration while the few elements left change, and was
// stopped there with the surface unresolved (a CAD part, 1 run in 8, issue 12). Host code,
// one per run.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

namespace gdr::m3d {

class StallDetector {
 public:
  explicit StallDetector(bool turnover = false) : turnover_(turnover) {}

  // Records one iteration: elements left to split, points in the mesh and the volume of the
  // bad tetrahedra (0 where not measured). True: stalled.
  bool stalled(std::size_t backlog, long long points, double bad_volume = 0) {
    backlog_.push_back(backlog);
    points_.push_back(points);
    volume_.push_back(bad_volume);
    const std::size_t n = backlog_.size();
    const bool shrinking = n <= kWindow || 50 * backlog <= 49 * backlog_[n - 1 - kWindow] ||
                           4 * points >= 5 * points_[n - 1 - kWindow] ||
                           50 * bad_volume < 49 * volume_[n - 1 - kWindow] ||
                           (turnover_ && points - points_[n - 1 - kWindow] >=
                                             static_cast<long long>(std::max(backlog_[n - 1 - kWindow], kWindow)));
    bool unchanged = n > kSame;
    for (std::size_t k = 1; unchanged && k <= kSame; ++k) unchanged = backlog_[n - 1 - k] == backlog;
    return !shrinking || unchanged;
  }

  // A new kind of work begins (gDP3d's manifold rounds): the backlog jumps, not a stall.
  void restart() {
    backlog_.clear();
    points_.clear();
    volume_.clear();
  }

 private:
  static constexpr std::size_t kWindow = 40, kSame = 6;
  bool turnover_;
  std::vector<std::size_t> backlog_;
  std::vector<long long> points_;
  std::vector<double> volume_;
};

}  // namespace gdr::m3d
