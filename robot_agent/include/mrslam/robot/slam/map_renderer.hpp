#pragma once
// The robot's published map drawn from its submaps at their optimised poses: every global cell
// that a submap covers takes the log-odds of the submap cell under its centre (nearest cell),
// summed over the submaps and clamped, so a closure that moves submaps moves their walls.

#include <memory>
#include <vector>

#include "mrslam/common/occupancy_grid.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/robot/slam/submaps.hpp"

namespace mrslam::robot::slam {

struct PlacedSubmap {
  std::shared_ptr<const Submap> submap;
  SE2 T_map_submap;
};

/// An occupancy grid at `resolution_m` (log-odds bounds of `params`) drawn from `submaps`.
OccupancyGrid renderSubmaps(const std::vector<PlacedSubmap>& submaps, double resolution_m,
                            const LogOddsParams& params);

}  // namespace mrslam::robot::slam
