#pragma once
// Loop closure search (Hess et al., ICRA 2016, section V): a scan node is searched for in the
// finished submaps near its current estimate by the branch-and-bound matcher
// (fast_correlative_matcher.hpp) in a window that grows with the drift distance between the node
// and the submap (drift_graph.hpp), then refined by least squares against the same
// submap. A match below min_score is no closure; an accepted one is a constraint of the pose graph
// (under its Huber loss, and refused there when the solution leaves it far off).

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "mrslam/robot/slam/ceres_scan_matcher.hpp"
#include "mrslam/robot/slam/fast_correlative_matcher.hpp"
#include "mrslam/robot/slam/submaps.hpp"

namespace mrslam::robot::slam {

struct LoopClosureSettings {
  bool enabled = true;                      ///< false: local SLAM only, no closures
  double sampling_ratio = 0.3;              ///< share of (node, submap) pairs searched
  double max_constraint_distance_m = 15.0;  ///< farther submaps are not searched
  double min_score = 0.55;                  ///< a closure's branch-and-bound score at least this
  double min_window_m = 1.0;              ///< the search window right after a closure (half-width)
  double min_window_rad = 0.17;           ///< ... and its angular half-width
  double window_growth_per_m = 0.1;       ///< the window widens by this per metre of drift
  double window_growth_rad_per_m = 0.01;  ///< ... and turns by this per metre
  double max_range_m = 20.0;              ///< scan points farther are left out of the search
  FastCorrelativeSettings search;         ///< its windows are the widest searched
  CeresScanMatcherSettings refine;        ///< the least-squares refinement of a found closure
};

struct LoopClosure {
  int submap = 0;
  SE2 T_submap_node;
  double score = 0.0;
};

struct LoopClosureCounters {
  std::uint64_t searches = 0;
  std::uint64_t found = 0;
};

class LoopCloser {
 public:
  explicit LoopCloser(const LoopClosureSettings& settings);

  /// A finished submap becomes searchable (its grids are precomputed once here).
  void addFinishedSubmap(const std::shared_ptr<const Submap>& submap);
  bool isSearchable(int submap) const;

  /// Searches the finished submap for a node whose robot-frame points are `points` and whose
  /// estimated pose in that submap's frame is T_submap_node_guess; `drift_m` is the drift distance
  /// between them (drift_graph.hpp). Sampled: most calls return nullopt without a search.
  std::optional<LoopClosure> search(int submap, const SE2& T_submap_node_guess,
                                    const std::vector<Eigen::Vector2d>& points, double drift_m);
  /// The drift at which both windows have grown to their widest: farther is all the same.
  double saturatingDrift() const;

  const LoopClosureCounters& counters() const { return counters_; }
  const LoopClosureSettings& settings() const { return settings_; }

 private:
  struct Searchable {
    std::shared_ptr<const Submap> submap;
    std::unique_ptr<FastCorrelativeMatcher> matcher;
    double sampled = 0.0;  ///< sampling accumulator: a search runs each time it passes 1
  };

  const LoopClosureSettings settings_;
  const CeresScanMatcher refiner_;
  std::vector<Searchable> submaps_;  ///< by submap id (null matcher: not finished yet)
  LoopClosureCounters counters_;
};

}  // namespace mrslam::robot::slam
