#pragma once
// Time-stamped sensor samples: what driver adapters (devices, log readers, the simulator)
// produce and the robot pipeline consumes. Units: metres, radians, seconds.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "mrslam/common/se2.hpp"
#include "mrslam/common/stamp.hpp"

namespace mrslam {

/// One planar laser scan in the laser's own frame (x forward, counter-clockwise angles).
/// Beam i points at angle_min_rad + i * angle_increment_rad.
struct LaserScan {
  /// A beam that saw nothing within range (free space up to the clearing range).
  static constexpr float kNoReturn = std::numeric_limits<float>::infinity();
  /// A beam whose reading is invalid (error code, dazzle): it says nothing.
  static constexpr float kInvalid = std::numeric_limits<float>::quiet_NaN();

  Stamp stamp;
  double angle_min_rad = 0.0;
  double angle_increment_rad = 0.0;
  double range_min_m = 0.0;
  double range_max_m = 0.0;
  /// Finite values are hits in metres; kNoReturn or kInvalid otherwise.
  std::vector<float> ranges_m;
  /// The pose a log recorded with this scan (CARMEN's corrected laser pose), if any.
  std::optional<SE2> logged_pose;

  double beamAngle(std::size_t i) const {
    return angle_min_rad + static_cast<double>(i) * angle_increment_rad;
  }
};

/// Cumulative wheel encoder counts of a differential-drive robot.
struct WheelTicks {
  Stamp stamp;
  std::int64_t left = 0;
  std::int64_t right = 0;
};

/// A pose from an odometry source that integrates by itself (CARMEN ODOM), in its own frame.
struct OdometryPose {
  Stamp stamp;
  SE2 T_odom_robot;
};

/// One reading of an attitude and heading unit (MicroStrain 3DM-GX1 class).
struct ImuSample {
  Stamp stamp;
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rad = 0.0;  ///< stabilised heading, counter-clockwise positive
  bool has_orientation = true;
  Eigen::Vector3d angular_rate_rad_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration_g = Eigen::Vector3d::Zero();
};

/// This robot saw another one (a rendezvous, seed 003 §3.2): its range and its bearing in this
/// robot's frame (x forward, counter-clockwise), as a camera or a fiducial detector gives them.
struct RobotSighting {
  Stamp stamp;
  std::string observed_id;  ///< the robot seen
  double range_m = 0.0;
  double bearing_rad = 0.0;
};

using Sample = std::variant<LaserScan, WheelTicks, OdometryPose, ImuSample, RobotSighting>;

/// The time stamp of any sample.
inline Stamp stampOf(const Sample& sample) {
  return std::visit([](const auto& s) { return s.stamp; }, sample);
}

}  // namespace mrslam
