#pragma once
// The robot's body: differential-drive geometry and where the sensors sit on it.

#include <cmath>

#include "mrslam/common/se2.hpp"

namespace mrslam {

/// A differential-drive base with wheel encoders.
struct DiffDriveParams {
  double wheel_radius_m = 0.077;       ///< radius of both drive wheels
  double track_width_m = 0.33;         ///< distance between the wheels' contact points
  double ticks_per_revolution = 4000;  ///< encoder counts per wheel turn

  /// Distance a wheel rolls for `ticks` counts.
  double ticksToMetres(double ticks) const {
    return ticks * 2.0 * M_PI * wheel_radius_m / ticks_per_revolution;
  }
};

/// Mounting of the sensors in the robot frame (x forward, y left).
struct SensorMounting {
  SE2 T_robot_laser;                ///< pose of the laser in the robot frame
  double imu_yaw_offset_rad = 0.0;  ///< heading of the IMU's x axis in the robot frame
};

}  // namespace mrslam
