#pragma once
// The interface of the robot's pose estimators: dead reckoning, the cascaded EKF, and the
// submap SLAM whose pose graph revises past poses and draws its own map.

#include <Eigen/Core>
#include <vector>

#include "mrslam/common/occupancy_grid.hpp"
#include "mrslam/common/samples.hpp"
#include "mrslam/common/se2.hpp"

namespace mrslam::robot {

/// Estimates T_map_robot, the robot's pose in its own map frame (its pose at the first sample).
class PoseEstimator {
 public:
  virtual ~PoseEstimator() = default;
  virtual void addWheelTicks(const WheelTicks& ticks) = 0;
  virtual void addOdometry(const OdometryPose& odometry) = 0;
  virtual void addImu(const ImuSample& imu) = 0;
  /// Called with every scan before it is inserted into `map`; may correct the pose.
  virtual void addScan(const LaserScan& scan, const OccupancyGrid& map) = 0;

  virtual SE2 pose() const = 0;

  /// True when the estimator draws the map itself (map()); the pipeline then maps nothing.
  virtual bool drawsItsOwnMap() const { return false; }
  /// The map this estimator draws itself (from submaps at their optimised poses), or null: the
  /// pipeline then inserts every scan at pose() into a grid of its own.
  virtual const OccupancyGrid* map() const { return nullptr; }
  /// T_map_robot at every scan given to addScan so far, as the estimator now believes them (loop
  /// closure moves past poses); empty when it never revises a pose once given.
  virtual std::vector<SE2> revisedScanPoses() const { return {}; }
  /// The source has ended: a last optimisation, where the estimator makes them.
  virtual void finish() {}
  /// Covariance of (x, y, theta).
  virtual Eigen::Matrix3d covariance() const = 0;
};

}  // namespace mrslam::robot
