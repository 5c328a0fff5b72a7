#pragma once
// A laser scan as local SLAM uses it: hit points and no-return rays in the robot frame, and the
// thinned point set the scan matchers score against a submap.
//  1. Beams below range_min, invalid ones and those beyond max_range_m are dropped; a no-return
//     beam (or a hit beyond max_range_m) becomes a miss of missing_data_ray_length_m, which only
//     clears free space.
//  2. A voxel filter keeps one hit per voxel_m square (the first in beam order).
//  3. The matching set: an adaptive voxel filter (Hess et al. 2016, "adaptive voxel filter")
//     grows the voxel from match_voxel_m until at most match_max_points remain, keeping at least
//     match_min_points when the scan has that many.

#include <Eigen/Core>
#include <vector>

#include "mrslam/common/samples.hpp"
#include "mrslam/common/se2.hpp"

namespace mrslam::robot::slam {

struct RangeDataSettings {
  double min_range_m = 0.1;                ///< closer readings are the robot itself
  double max_range_m = 30.0;               ///< farther hits are too sparse to map
  double missing_data_ray_length_m = 5.0;  ///< a no-return beam clears this far (0: not at all)
  double voxel_m = 0.025;                  ///< one hit per voxel is inserted into submaps
  double match_voxel_m = 0.05;             ///< smallest voxel of the matching set
  int match_max_points = 250;              ///< the matching set's voxel grows until this many
  int match_min_points = 150;              ///< ... but stops growing below this many
};

struct RangeData {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< the laser's position
  std::vector<Eigen::Vector2d> hits;
  std::vector<Eigen::Vector2d> misses;  ///< ends of no-return rays
};

/// The scan's range data in the robot frame (steps 1–2).
RangeData rangeDataOf(const LaserScan& scan, const SE2& T_robot_laser,
                      const RangeDataSettings& settings);

/// One point per `voxel_m` square, the first in order.
std::vector<Eigen::Vector2d> voxelFiltered(const std::vector<Eigen::Vector2d>& points,
                                           double voxel_m);

/// The matching set (step 3).
std::vector<Eigen::Vector2d> matchingPoints(const std::vector<Eigen::Vector2d>& hits,
                                            const RangeDataSettings& settings);

/// Every point moved by T_b_a.
std::vector<Eigen::Vector2d> transformed(const std::vector<Eigen::Vector2d>& points_a,
                                         const SE2& T_b_a);
RangeData transformed(const RangeData& data_a, const SE2& T_b_a);

}  // namespace mrslam::robot::slam
