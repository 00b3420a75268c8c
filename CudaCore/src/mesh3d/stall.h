// Stall detection for the 3D engines (gQM3d, gDP3d): what is left to split can no longer be
// split by the method when, over kWindow iterations, the elements left to split did not
// shrink by a fiftieth and the mesh did not grow by a quarter (refinement to a size bound
// first multiplies the elements to split), or when the same backlog comes back kSame
// iterations in a row (the same elements failing again). Host code, one per run.
#pragma once
#include <cstddef>
#include <vector>

namespace gdr::m3d {

class StallDetector {
 public:
  // Records one iteration: elements left to split and points in the mesh. True: stalled.
  bool stalled(std::size_t backlog, long long points) {
    backlog_.push_back(backlog);
    points_.push_back(points);
    const std::size_t n = backlog_.size();
    const bool shrinking = n <= kWindow || 50 * backlog <= 49 * backlog_[n - 1 - kWindow] ||
                           4 * points >= 5 * points_[n - 1 - kWindow];
    bool unchanged = n > kSame;
    for (std::size_t k = 1; unchanged && k <= kSame; ++k) unchanged = backlog_[n - 1 - k] == backlog;
    return !shrinking || unchanged;
  }

 private:
  static constexpr std::size_t kWindow = 40, kSame = 6;
  std::vector<std::size_t> backlog_;
  std::vector<long long> points_;
};

}  // namespace gdr::m3d
