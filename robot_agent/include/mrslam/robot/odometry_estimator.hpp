#pragma once
// Dead reckoning: wheel encoder ticks (differential drive) or an integrating odometry source
// (CARMEN ODOM) move the pose; the covariance grows with the distance travelled and the turn.

#include <optional>

#include "mrslam/common/platform.hpp"
#include "mrslam/robot/pose_estimator.hpp"

namespace mrslam::robot {

/// Odometry noise, proportional to the motion (standard deviations).
struct OdometryNoise {
  double translation_per_m = 0.05;  ///< σ of translation per metre driven
  double rotation_per_rad = 0.05;   ///< σ of rotation per radian turned
  double rotation_per_m = 0.02;     ///< σ of rotation (rad) per metre driven
};

/// The pose change of a differential-drive robot whose wheels rolled `left_m` and `right_m`,
/// as an arc: T_before_after.
SE2 diffDriveIncrement(double left_m, double right_m, double track_width_m);

class OdometryEstimator : public PoseEstimator {
 public:
  OdometryEstimator(const DiffDriveParams& platform, const OdometryNoise& noise);

  void addWheelTicks(const WheelTicks& ticks) override;
  void addOdometry(const OdometryPose& odometry) override;
  void addImu(const ImuSample&) override {}
  void addScan(const LaserScan&, const OccupancyGrid&) override {}

  SE2 pose() const override { return T_map_robot_; }
  Eigen::Matrix3d covariance() const override { return covariance_; }

 private:
  /// Moves the pose by T_before_after and propagates the covariance with the Jacobians.
  void applyIncrement(const SE2& T_before_after);

  DiffDriveParams platform_;
  OdometryNoise noise_;
  SE2 T_map_robot_;
  Eigen::Matrix3d covariance_ = Eigen::Matrix3d::Zero();
  std::optional<WheelTicks> last_ticks_;
  std::optional<SE2> last_T_odom_robot_;
};

}  // namespace mrslam::robot
