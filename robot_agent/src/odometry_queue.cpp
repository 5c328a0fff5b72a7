#include "mrslam/robot/odometry_queue.hpp"

#include <cmath>

namespace mrslam::robot {

namespace {

// ∂u/∂(left, right) of the arc increment, by central differences.
Eigen::Matrix<double, 3, 2> arcJacobian(double left_m, double right_m, double track_m) {
  constexpr double h = 1e-6;
  const auto column = [&](double dl, double dr) {
    const SE2 plus = diffDriveIncrement(left_m + dl, right_m + dr, track_m);
    const SE2 minus = diffDriveIncrement(left_m - dl, right_m - dr, track_m);
    return Eigen::Vector3d((plus.x() - minus.x()) / (2 * h), (plus.y() - minus.y()) / (2 * h),
                           wrapAngle(plus.theta() - minus.theta()) / (2 * h));
  };
  Eigen::Matrix<double, 3, 2> J;
  J.col(0) = column(h, 0.0);
  J.col(1) = column(0.0, h);
  return J;
}

bool sameKind(const OdometryReading& a, const OdometryReading& b) {
  return a.value.index() == b.value.index();
}

// The reading at a fraction f of the way from a to b (same kind).
OdometryReading interpolate(const OdometryReading& a, const OdometryReading& b, Stamp stamp,
                            double f) {
  if (const auto* wa = std::get_if<WheelTravel>(&a.value)) {
    const auto& wb = std::get<WheelTravel>(b.value);
    return {stamp, WheelTravel{wa->left_m + f * (wb.left_m - wa->left_m),
                               wa->right_m + f * (wb.right_m - wa->right_m)}};
  }
  const SE2& pa = std::get<SE2>(a.value);
  const SE2& pb = std::get<SE2>(b.value);
  return {stamp, SE2(pa.x() + f * (pb.x() - pa.x()), pa.y() + f * (pb.y() - pa.y()),
                     pa.theta() + f * wrapAngle(pb.theta() - pa.theta()))};
}

}  // namespace

OdometryQueue::OdometryQueue(double track_width_m, const MotionNoise& noise)
    : track_width_m_(track_width_m), noise_(noise) {}

MotionIncrement OdometryQueue::increment(const OdometryReading& from,
                                         const OdometryReading& to) const {
  MotionIncrement motion;
  motion.stamp = to.stamp;
  if (const auto* wheels = std::get_if<WheelTravel>(&to.value)) {
    const auto& before = std::get<WheelTravel>(from.value);
    const double left = wheels->left_m - before.left_m;
    const double right = wheels->right_m - before.right_m;
    // σ of each wheel's travel ∝ that travel, mapped through the arc: Q_u = J Q_w Jᵀ; plus the
    // turn's own slip, σ_θ = wheel_turn_noise_per_rad |Δθ| (skid, encoder-to-scan timing).
    const double k = noise_.wheel_noise_fraction;
    const Eigen::Vector2d wheel_variance(k * k * left * left, k * k * right * right);
    const Eigen::Matrix<double, 3, 2> J = arcJacobian(left, right, track_width_m_);
    motion.T_before_after = diffDriveIncrement(left, right, track_width_m_);
    motion.covariance = J * wheel_variance.asDiagonal() * J.transpose();
    const double sigma_turn =
        noise_.wheel_turn_noise_per_rad * std::abs(motion.T_before_after.theta());
    motion.covariance(2, 2) += sigma_turn * sigma_turn;
    return motion;
  }
  // An odometry pose increment: σ_t ∝ distance, σ_θ ∝ turn and distance (OdometryNoise).
  motion.T_before_after = std::get<SE2>(from.value).inverse() * std::get<SE2>(to.value);
  const double distance = motion.T_before_after.translation().norm();
  const double sigma_t = noise_.odometry.translation_per_m * distance;
  const double sigma_r =
      noise_.odometry.rotation_per_rad * std::abs(motion.T_before_after.theta()) +
      noise_.odometry.rotation_per_m * distance;
  motion.covariance.diagonal() << sigma_t * sigma_t, sigma_t * sigma_t, sigma_r * sigma_r;
  return motion;
}

void OdometryQueue::push(const OdometryReading& reading) {
  if (newest_ && sameKind(*newest_, reading)) {
    dead_reckoning_ = dead_reckoning_ * increment(*newest_, reading).T_before_after;
  }
  trail_.add(reading.stamp, dead_reckoning_);
  newest_ = reading;
  if (!released_) {
    released_ = reading;  // the first reading is the reference
    return;
  }
  pending_.push_back(reading);
}

std::vector<MotionIncrement> OdometryQueue::releaseUpTo(Stamp stamp) {
  std::vector<MotionIncrement> increments;
  while (!pending_.empty()) {
    const OdometryReading& next = pending_.front();
    if (!sameKind(*released_, next)) {
      released_ = next;  // a new reference for the other kind
    } else if (next.stamp <= stamp) {
      increments.push_back(increment(*released_, next));
      released_ = next;
    } else {
      if (released_->stamp < stamp) {
        const double f =
            secondsBetween(released_->stamp, stamp) / secondsBetween(released_->stamp, next.stamp);
        const OdometryReading at_stamp = interpolate(*released_, next, stamp, f);
        increments.push_back(increment(*released_, at_stamp));
        released_ = at_stamp;
      }
      break;
    }
    pending_.pop_front();
  }
  return increments;
}

}  // namespace mrslam::robot
