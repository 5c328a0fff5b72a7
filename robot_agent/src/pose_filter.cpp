#include "mrslam/robot/pose_filter.hpp"

#include <cmath>

namespace mrslam::robot {

SE2 PoseFilter::pose() const {
  return SE2(x_(state::kAnchorX), x_(state::kAnchorY), x_(state::kAnchorTheta)) * relativePose();
}

Eigen::Matrix<double, 3, state::kSize> PoseFilter::composeJacobian() const {
  // p = p_a + R(θ_a) r_t,  θ = θ_a + θ_r.
  const double c = std::cos(x_(state::kAnchorTheta));
  const double s = std::sin(x_(state::kAnchorTheta));
  const double rx = x_(state::kX);
  const double ry = x_(state::kY);
  Eigen::Matrix<double, 3, state::kSize> J = Eigen::Matrix<double, 3, state::kSize>::Zero();
  J.block<2, 2>(0, state::kX) << c, -s, s, c;
  J(2, state::kTheta) = 1.0;
  J.block<3, 3>(0, state::kAnchorX).setIdentity();
  J(0, state::kAnchorTheta) = -s * rx - c * ry;
  J(1, state::kAnchorTheta) = c * rx - s * ry;
  return J;
}

Eigen::Matrix3d PoseFilter::poseCovariance() const {
  const Eigen::Matrix<double, 3, state::kSize> J = composeJacobian();
  return J * P_ * J.transpose();
}

void PoseFilter::addVariance(int index, double variance) {
  P_(index, index) += variance;
}

void PoseFilter::predict(const SE2& T_before_after, const Eigen::Matrix3d& Q_u) {
  const double c = std::cos(x_(state::kTheta));
  const double s = std::sin(x_(state::kTheta));
  const double ux = T_before_after.x();
  const double uy = T_before_after.y();
  StateMatrix F = StateMatrix::Identity();
  F(state::kX, state::kTheta) = -s * ux - c * uy;
  F(state::kY, state::kTheta) = c * ux - s * uy;
  Eigen::Matrix<double, state::kSize, 3> G = Eigen::Matrix<double, state::kSize, 3>::Zero();
  G.block<2, 2>(state::kX, 0) << c, -s, s, c;
  G(state::kTheta, 2) = 1.0;
  x_(state::kX) += c * ux - s * uy;
  x_(state::kY) += s * ux + c * uy;
  x_(state::kTheta) = wrapAngle(x_(state::kTheta) + T_before_after.theta());
  P_ = F * P_ * F.transpose() + G * Q_u * G.transpose();
}

void PoseFilter::resetAnchor() {
  StateMatrix J = StateMatrix::Identity();
  J.block<3, state::kSize>(state::kAnchorX, 0) = composeJacobian();
  J.block<3, 3>(state::kX, state::kX).setZero();
  const SE2 anchor = pose();
  x_.segment<3>(state::kX).setZero();
  x_.segment<3>(state::kAnchorX) << anchor.x(), anchor.y(), anchor.theta();
  P_ = J * P_ * J.transpose();
}

void PoseFilter::cloneHeading() {
  // θ_imu = θ_a + θ: the new row is the sum of those rows.
  StateMatrix J = StateMatrix::Identity();
  J.row(state::kImuTheta).setZero();
  J(state::kImuTheta, state::kAnchorTheta) = 1.0;
  J(state::kImuTheta, state::kTheta) = 1.0;
  x_(state::kImuTheta) = heading();
  P_ = J * P_ * J.transpose();
}

void PoseFilter::initialiseHeadingOffset(double yaw_rad, double yaw_variance) {
  // α = yaw − θ_a − θ: a linear function of the state plus the reading's own noise.
  StateMatrix J = StateMatrix::Identity();
  J.row(state::kImuHeadingOffset).setZero();
  J(state::kImuHeadingOffset, state::kAnchorTheta) = -1.0;
  J(state::kImuHeadingOffset, state::kTheta) = -1.0;
  x_(state::kImuHeadingOffset) = wrapAngle(yaw_rad - heading());
  P_ = J * P_ * J.transpose();
  P_(state::kImuHeadingOffset, state::kImuHeadingOffset) += yaw_variance;
}

void PoseFilter::wrapAngles() {
  for (const int index :
       {state::kTheta, state::kAnchorTheta, state::kImuTheta, state::kImuHeadingOffset}) {
    x_(index) = wrapAngle(x_(index));
  }
}

}  // namespace mrslam::robot
