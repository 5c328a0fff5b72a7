#pragma once
// The interface of the robot's pose estimators: wheel odometry now, the cascaded EKF later.

#include <Eigen/Core>

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
  /// Covariance of (x, y, theta).
  virtual Eigen::Matrix3d covariance() const = 0;
};

}  // namespace mrslam::robot
