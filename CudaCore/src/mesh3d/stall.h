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
// stopped there with the surface unresolved (a CAD part, 1 run in 8, issue 12). With a
// `volume_floor` (gQM3d), growth counts only together with a shrinking bad volume once that
// volume is below the floor: late in a run, points that only make as many bad elements as
// they fix are a cascade (a turned CAD part's nearly planar cap, read as float32: the GPU,
// inserting more per iteration, kept growing by a quarter per window to 2M tetrahedra where
// the CPU stopped at 180k). With `balloon` (gQM3d without volume bounds), above the floor
// growth counts alone only until the mesh has grown kBalloon-fold since the bad volume last
// reached a new low (by a fiftieth): a needle spike 0.7 long on a torus 0.002 wide (fuzz3d
// seed 52002286) kept 15-20% of its volume bad while the mesh grew past 1.3M tetrahedra
// (TetGen: 19k), growing by a quarter per window. Not with a volume bound: there every
// tetrahedron is bad until it is small, and the mesh grows a hundredfold before the bad
// volume moves (a box at a volume bound of 1/2400 of it). Host code, one per run.
#pragma once
#include <algorithm>
#include <cstddef>
#include <vector>

namespace gdr::m3d {

class StallDetector {
 public:
  explicit StallDetector(bool turnover = false, double volume_floor = -1, bool balloon = false)
      : turnover_(turnover), balloon_(balloon), volume_floor_(volume_floor) {}

  // Records one iteration: elements left to split, points in the mesh and the volume of the
  // bad tetrahedra (0 where not measured). Without a volume floor the volume counts as given;
  // with one, a shrinking volume counts while it is above the floor. True: stalled.
  bool stalled(std::size_t backlog, long long points, double bad_volume = 0) {
    backlog_.push_back(backlog);
    points_.push_back(points);
    volume_.push_back(bad_volume);
    if (balloon_ && bad_volume > 0) {
      if (best_volume_ < 0 || 50 * bad_volume < 49 * best_volume_) {
        best_volume_ = bad_volume;
        points_at_best_ = points;
      } else if (points >= kBalloon * points_at_best_) {
        return true;  // ballooning: the mesh grows, the bad volume does not
      }
    }
    const std::size_t n = backlog_.size();
    bool shrinking = n <= kWindow;
    if (!shrinking) {
      const std::size_t w = n - 1 - kWindow;  // the window's start
      const bool volume_shrank = 50 * bad_volume < 49 * volume_[w];
      const bool end_game = volume_floor_ >= 0 && volume_[w] <= volume_floor_;
      const bool grew = 4 * points >= 5 * points_[w];
      shrinking = 50 * backlog <= 49 * backlog_[w] || (end_game ? grew && volume_shrank : grew || volume_shrank) ||
                  (turnover_ && points - points_[w] >= static_cast<long long>(std::max(backlog_[w], kWindow)));
    }
    bool unchanged = n > kSame;
    for (std::size_t k = 1; unchanged && k <= kSame; ++k) unchanged = backlog_[n - 1 - k] == backlog;
    return !shrinking || unchanged;
  }

  // A new kind of work begins (gDP3d's manifold rounds): the backlog jumps, not a stall.
  void restart() {
    backlog_.clear();
    points_.clear();
    volume_.clear();
    best_volume_ = -1;
  }

 private:
  static constexpr std::size_t kWindow = 40, kSame = 6;
  static constexpr long long kBalloon = 8;
  bool turnover_, balloon_;
  double volume_floor_;
  double best_volume_ = -1;  // the lowest bad volume so far (with `balloon`), and the points then
  long long points_at_best_ = 0;
  std::vector<std::size_t> backlog_;
  std::vector<long long> points_;
  std::vector<double> volume_;
};

}  // namespace gdr::m3d
