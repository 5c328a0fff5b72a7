#include "mrslam/robot/odometry_estimator.hpp"

#include <cmath>

namespace mrslam::robot {

SE2 diffDriveIncrement(double left_m, double right_m, double track_width_m) {
  const double distance = 0.5 * (left_m + right_m);
  const double dtheta = (right_m - left_m) / track_width_m;
  // Exact arc: the chord of length 2 (d / dθ) sin(dθ / 2) at half the turn.
  const double chord =
      std::abs(dtheta) < 1e-9 ? distance : 2.0 * distance / dtheta * std::sin(0.5 * dtheta);
  return SE2(chord * std::cos(0.5 * dtheta), chord * std::sin(0.5 * dtheta), dtheta);
}

OdometryEstimator::OdometryEstimator(const DiffDriveParams& platform, const OdometryNoise& noise)
    : platform_(platform), noise_(noise) {}

void OdometryEstimator::addWheelTicks(const WheelTicks& ticks) {
  if (last_ticks_) {
    const double left_m =
        platform_.ticksToMetres(static_cast<double>(ticks.left - last_ticks_->left));
    const double right_m =
        platform_.ticksToMetres(static_cast<double>(ticks.right - last_ticks_->right));
    applyIncrement(diffDriveIncrement(left_m, right_m, platform_.track_width_m));
  }
  last_ticks_ = ticks;
}

void OdometryEstimator::addOdometry(const OdometryPose& odometry) {
  if (last_T_odom_robot_) {
    applyIncrement(last_T_odom_robot_->inverse() * odometry.T_odom_robot);
  }
  last_T_odom_robot_ = odometry.T_odom_robot;
}

void OdometryEstimator::applyIncrement(const SE2& T_before_after) {
  const double c = std::cos(T_map_robot_.theta());
  const double s = std::sin(T_map_robot_.theta());
  const double dx = T_before_after.x();
  const double dy = T_before_after.y();
  // x' = x ⊕ u; F = ∂x'/∂x, G = ∂x'/∂u.
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(0, 2) = -s * dx - c * dy;
  F(1, 2) = c * dx - s * dy;
  Eigen::Matrix3d G = Eigen::Matrix3d::Identity();
  G.topLeftCorner<2, 2>() << c, -s, s, c;
  const double distance = std::hypot(dx, dy);
  const double turn = std::abs(T_before_after.theta());
  const double sigma_translation = noise_.translation_per_m * distance;
  const double sigma_rotation = noise_.rotation_per_rad * turn + noise_.rotation_per_m * distance;
  const Eigen::Vector3d variances(sigma_translation * sigma_translation,
                                  sigma_translation * sigma_translation,
                                  sigma_rotation * sigma_rotation);
  covariance_ = F * covariance_ * F.transpose() + G * variances.asDiagonal() * G.transpose();
  T_map_robot_ = T_map_robot_ * T_before_after;
}

}  // namespace mrslam::robot
