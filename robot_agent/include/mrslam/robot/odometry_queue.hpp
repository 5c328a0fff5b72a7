#pragma once
// Odometry readings on their way into the EKF: each reading (cumulative wheel travel, or the pose
// of an integrating odometry) is queued, and released as motion increments with their noise up
// to a given time, a reading interpolated at that time when it falls between two. Releasing up to
// "now" passes every reading at once (arrival order, whatever the stamps); releasing up to a
// scan's acquisition time lets the filter stand where the robot was when the scan was taken.
// The dead reckoning of every queued reading is kept by stamp (for de-skewing scans).

#include <Eigen/Core>
#include <deque>
#include <optional>
#include <variant>
#include <vector>

#include "mrslam/common/platform.hpp"
#include "mrslam/robot/odometry_estimator.hpp"
#include "mrslam/robot/odometry_trail.hpp"

namespace mrslam::robot {

/// Cumulative wheel travel in metres.
struct WheelTravel {
  double left_m = 0.0;
  double right_m = 0.0;
};

struct OdometryReading {
  Stamp stamp;
  std::variant<WheelTravel, SE2> value;  ///< wheel travel, or T_odom_robot
};

/// Noise of the released increments.
struct MotionNoise {
  OdometryNoise odometry;                 ///< of an odometry pose increment
  double wheel_noise_fraction = 0.03;     ///< σ of a wheel's travel per increment, fraction of it
  double wheel_turn_noise_per_rad = 0.0;  ///< extra σ of an increment's turn per radian turned
};

/// A motion increment T_before_after with the covariance of its (x, y, θ).
struct MotionIncrement {
  Stamp stamp;
  SE2 T_before_after;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
};

class OdometryQueue {
 public:
  OdometryQueue(double track_width_m, const MotionNoise& noise);

  /// Queues a reading (the first only sets the reference). A wheel reading after a pose reading
  /// (or the other way) starts a new reference.
  void push(const OdometryReading& reading);

  /// The increments from the last released reading up to `stamp`, in arrival order: every queued
  /// reading not newer than `stamp`, then one interpolated at `stamp` when the next reading is
  /// newer and the last released one older.
  std::vector<MotionIncrement> releaseUpTo(Stamp stamp);

  /// Dead reckoning of every reading pushed, by stamp.
  const OdometryTrail& trail() const { return trail_; }
  bool hasReadings() const { return released_.has_value(); }

 private:
  MotionIncrement increment(const OdometryReading& from, const OdometryReading& to) const;

  const double track_width_m_;
  const MotionNoise noise_;
  std::optional<OdometryReading> released_;  ///< the reference of the next increment
  std::deque<OdometryReading> pending_;
  std::optional<OdometryReading> newest_;
  SE2 dead_reckoning_;
  OdometryTrail trail_;
};

}  // namespace mrslam::robot
