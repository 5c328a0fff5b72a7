#pragma once
// The state and covariance of the robot's EKF, in anchored form: the robot pose is kept relative
// to an anchor (the newest scan-matching keyframe), T_map_robot = T_map_anchor ⊕ T_anchor_robot.
//
// State (named indices, robot_localization style):
//   x, y, θ        T_anchor_robot: the robot relative to the anchor
//   x_a, y_a, θ_a  T_map_anchor: the anchor in the map frame
//   b              gyro yaw-rate bias (rad/s)
//   θ_imu          the map-frame heading θ_a + θ at the previous IMU sample (a clone: the yaw
//                  rate measures the heading change since then; Roumeliotis & Burdick, ICRA 2002)
//   α              the IMU's heading of the map frame's x axis (its stabilised yaw = θ_a + θ + α),
//                  initialised from its first reading with that reading's uncertainty
// Why anchored: scan matching measures T_anchor_robot, which is then linear in the state (H = I),
// and the odometry Jacobians are evaluated at the small, well-known relative pose. With the
// robot's map-frame pose as the state instead, the absolute uncertainty (metres, degrees after a
// long run) times the linearisation mismatch between prediction and update Jacobians leaks into
// the unobservable directions and drags the pose (Huang, Mourikis & Roumeliotis, "Observability-
// based rules for designing consistent EKF SLAM estimators", IJRR 2010, analyse this effect).
// At a new keyframe resetAnchor() moves the relative pose into the anchor.

#include <Eigen/Core>
#include <Eigen/LU>

#include "mrslam/common/se2.hpp"

namespace mrslam::robot {

namespace state {
constexpr int kX = 0;
constexpr int kY = 1;
constexpr int kTheta = 2;
constexpr int kAnchorX = 3;
constexpr int kAnchorY = 4;
constexpr int kAnchorTheta = 5;
constexpr int kGyroBias = 6;
constexpr int kImuTheta = 7;
constexpr int kImuHeadingOffset = 8;
constexpr int kSize = 9;
}  // namespace state

using StateVector = Eigen::Matrix<double, state::kSize, 1>;
using StateMatrix = Eigen::Matrix<double, state::kSize, state::kSize>;

/// What a correction did.
struct Correction {
  bool accepted = false;
  double mahalanobis_sq = 0.0;  ///< yᵀ S⁻¹ y of the innovation y
};

class PoseFilter {
 public:
  /// State zero, covariance zero: the robot is at its map frame's origin.
  PoseFilter() = default;

  const StateVector& state() const { return x_; }
  const StateMatrix& covariance() const { return P_; }
  /// T_anchor_robot.
  SE2 relativePose() const { return SE2(x_(state::kX), x_(state::kY), x_(state::kTheta)); }
  /// T_map_robot = T_map_anchor ⊕ T_anchor_robot.
  SE2 pose() const;
  /// Covariance of T_map_robot's (x, y, θ): J P Jᵀ with J = ∂(a ⊕ r)/∂(r, a).
  Eigen::Matrix3d poseCovariance() const;
  /// The map-frame heading θ_a + θ.
  double heading() const { return wrapAngle(x_(state::kAnchorTheta) + x_(state::kTheta)); }

  /// Adds `variance` to the diagonal element of `index` (a random walk step).
  void addVariance(int index, double variance);

  /// r ← r ⊕ u with u = T_before_after ~ N(u, Q_u) in the robot frame:
  ///   p' = p + R(θ) u_t,  θ' = θ + u_θ;  P' = F P Fᵀ + G Q_u Gᵀ,
  ///   F = ∂r'/∂r (I with ∂p'/∂θ = R'(θ) u_t),  G = ∂r'/∂u = blockdiag(R(θ), 1).
  void predict(const SE2& T_before_after, const Eigen::Matrix3d& Q_u);

  /// a ← a ⊕ r, r ← 0 (P ← J P Jᵀ): the current pose becomes the anchor.
  void resetAnchor();

  /// θ_imu ← θ_a + θ with its covariance rows and columns.
  void cloneHeading();

  /// α ← yaw − (θ_a + θ), with the variance of the heading plus `yaw_variance` (the reading's)
  /// and the covariance of −(θ_a + θ): the first IMU heading defines α.
  void initialiseHeadingOffset(double yaw_rad, double yaw_variance);

  /// The EKF update with innovation y = z − h(x) (angles wrapped by the caller), Jacobian H and
  /// noise R. Rejected (nothing changes) when yᵀ S⁻¹ y > gate_sq, S = H P Hᵀ + R. Otherwise
  ///   K = P Hᵀ S⁻¹,  x ← x + K y (angles wrapped),  P ← (I − K H) P (I − K H)ᵀ + K R Kᵀ
  /// (Joseph form: symmetric and positive whatever the rounding).
  template <int M>
  Correction correct(const Eigen::Matrix<double, M, 1>& y,
                     const Eigen::Matrix<double, M, state::kSize>& H,
                     const Eigen::Matrix<double, M, M>& R, double gate_sq);

 private:
  /// ∂(a ⊕ r)/∂x: 3 × kSize.
  Eigen::Matrix<double, 3, state::kSize> composeJacobian() const;
  void wrapAngles();

  StateVector x_ = StateVector::Zero();
  StateMatrix P_ = StateMatrix::Zero();
};

template <int M>
Correction PoseFilter::correct(const Eigen::Matrix<double, M, 1>& y,
                               const Eigen::Matrix<double, M, state::kSize>& H,
                               const Eigen::Matrix<double, M, M>& R, double gate_sq) {
  const Eigen::Matrix<double, M, M> S = H * P_ * H.transpose() + R;
  const Eigen::Matrix<double, M, M> S_inv = S.inverse();
  Correction correction;
  correction.mahalanobis_sq = y.dot(S_inv * y);
  if (!(correction.mahalanobis_sq <= gate_sq)) {
    return correction;
  }
  const Eigen::Matrix<double, state::kSize, M> K = P_ * H.transpose() * S_inv;
  x_ += K * y;
  wrapAngles();
  const StateMatrix I_KH = StateMatrix::Identity() - K * H;
  P_ = I_KH * P_ * I_KH.transpose() + K * R * K.transpose();
  P_ = 0.5 * (P_ + P_.transpose()).eval();
  correction.accepted = true;
  return correction;
}

}  // namespace mrslam::robot
