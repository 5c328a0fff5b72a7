#pragma once
// The simulator's waypoint follower (internal to mrslam_drivers).

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "mrslam/common/se2.hpp"

namespace mrslam::drivers {

/// Limits of the simulated base.
struct MotionLimits {
  double max_speed_m_s = 0.4;
  double max_turn_rate_rad_s = 1.0;
  double max_acceleration_m_s2 = 0.5;
  double max_angular_acceleration_rad_s2 = 3.0;
};

/// Velocities (v forward, ω counter-clockwise) commanded to the base.
struct VelocityCommand {
  double v_m_s = 0.0;
  double omega_rad_s = 0.0;
};

/// Drives round a closed loop of waypoints: steers at the current waypoint, drives only when
/// roughly facing it, brakes in time to take the corner at it (to a stop for a right angle or
/// more), and keeps every change of velocity within the limits.
class RouteFollower {
 public:
  /// `route` is a closed loop of at least two waypoints; the robot starts at route[0].
  RouteFollower(std::vector<Eigen::Vector2d> route, const MotionLimits& limits);

  /// The command for the next `dt` seconds, from the true pose and the velocities now.
  VelocityCommand update(const SE2& pose, const VelocityCommand& now, double dt);

  std::size_t targetIndex() const { return target_; }

 private:
  double cornerSpeed() const;

  std::vector<Eigen::Vector2d> route_;
  MotionLimits limits_;
  std::size_t target_ = 1;
};

}  // namespace mrslam::drivers
