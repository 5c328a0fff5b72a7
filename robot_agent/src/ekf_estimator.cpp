#include "mrslam/robot/ekf_estimator.hpp"

#include <limits>

#include <cmath>

#include "mrslam/robot/chi_square.hpp"

namespace mrslam::robot {

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

EkfEstimator::EkfEstimator(const DiffDriveParams& platform, const SensorMounting& mounting,
                           const EkfSettings& settings)
    : platform_(platform),
      mounting_(mounting),
      settings_(settings),
      gate_1dof_sq_(chiSquareQuantile(settings.gate_probability, 1)),
      gate_3dof_sq_(chiSquareQuantile(settings.gate_probability, 3)),
      matcher_(settings.scan_matching, mounting),
      odometry_(platform.track_width_m,
                MotionNoise{settings.odometry, settings.wheel_noise_fraction,
                            settings.wheel_turn_noise_per_rad}) {
  const double bias_sigma = settings.imu.initial_bias_sigma_rad_s;
  filter_.addVariance(state::kGyroBias, bias_sigma * bias_sigma);
}

bool EkfEstimator::isLate(Stamp stamp) {
  if (newest_stamp_ && stamp < *newest_stamp_) {
    return true;
  }
  newest_stamp_ = stamp;
  return false;
}

void EkfEstimator::predict(const SE2& T_before_after, const Eigen::Matrix3d& Q_u) {
  const auto start = Clock::now();
  filter_.predict(T_before_after, Q_u);
  ++counters_.predictions;
  timings_.filter_s += secondsSince(start);
}

Stamp EkfEstimator::acquisitionTime(Stamp stamp) const {
  return Stamp{stamp.ns - static_cast<std::int64_t>(std::llround(settings_.scan_delay_s * 1e9))};
}

void EkfEstimator::releaseOdometryUpTo(Stamp stamp) {
  for (const MotionIncrement& motion : odometry_.releaseUpTo(stamp)) {
    predict(motion.T_before_after, motion.covariance);
  }
}

void EkfEstimator::addOdometryReading(const OdometryReading& reading) {
  isLate(reading.stamp);
  has_odometry_ = true;
  odometry_.push(reading);
  releaseOdometryUpTo(acquisitionTime(reading.stamp));
}

void EkfEstimator::addWheelTicks(const WheelTicks& ticks) {
  addOdometryReading({ticks.stamp, WheelTravel{platform_.ticksToMetres(double(ticks.left)),
                                               platform_.ticksToMetres(double(ticks.right))}});
}

void EkfEstimator::addOdometry(const OdometryPose& odometry) {
  addOdometryReading({odometry.stamp, odometry.T_odom_robot});
}

ScanMatcher::BeamMotion EkfEstimator::beamMotion(const LaserScan& scan) const {
  const std::size_t beams = scan.ranges_m.size();
  if (settings_.scan_duration_s <= 0.0 || beams < 2 || !odometry_.hasReadings()) {
    return {};
  }
  const Stamp reference = acquisitionTime(scan.stamp);
  const SE2 T_reference_odom = odometry_.trail().poseAt(reference)->inverse();
  const double duration_ns = settings_.scan_duration_s * 1e9;
  return [this, reference, T_reference_odom, duration_ns, beams](std::size_t beam) {
    const double offset = static_cast<double>(beam) / static_cast<double>(beams - 1) - 0.5;
    const Stamp t{reference.ns + static_cast<std::int64_t>(std::llround(offset * duration_ns))};
    return T_reference_odom * *odometry_.trail().poseAt(t);
  };
}

void EkfEstimator::predictWithoutOdometry() {
  if (has_odometry_ || !last_scan_pose_) {
    return;
  }
  const double sxy = settings_.motion_model_sigma_xy_m;
  const double sth = settings_.motion_model_sigma_theta_rad;
  predict(last_scan_motion_, Eigen::Vector3d(sxy * sxy, sxy * sxy, sth * sth).asDiagonal());
}

void EkfEstimator::addScan(const LaserScan& scan, const OccupancyGrid&) {
  isLate(scan.stamp);
  ++counters_.scans;
  releaseOdometryUpTo(acquisitionTime(scan.stamp));
  predictWithoutOdometry();
  if (settings_.scan_matching.enabled) {
    auto start = Clock::now();
    const PreparedScan prepared = matcher_.prepare(scan, beamMotion(scan));
    last_match_ = matcher_.match(prepared, pose());
    // Both matches start from the prediction and are fused one after the other.
    const std::optional<ScanMatch> newest = matcher_.matchNewestKeyframe(prepared, pose());
    last_correction_.reset();
    timings_.scan_matching_s += secondsSince(start);
    if (last_match_) {
      updateWithScanMatch(*last_match_, gate_3dof_sq_);
    }
    if (newest) {
      const std::optional<Correction> map_correction = last_correction_;
      updateWithScanMatch(*newest, gate_3dof_sq_);
      last_correction_ = map_correction;  // lastScanCorrection() stays the local map's
    }
    start = Clock::now();
    if (matcher_.isKeyframe(pose())) {
      filter_.resetAnchor();
      matcher_.addKeyframe(prepared, pose());
      ++counters_.keyframes;
    }
    timings_.scan_matching_s += secondsSince(start);
  }
  if (last_scan_pose_) {
    last_scan_motion_ = last_scan_pose_->inverse() * pose();
  }
  last_scan_pose_ = pose();
}

void EkfEstimator::updateWithScanMatch(const ScanMatch& match, double gate_sq) {
  const bool usable = match.icp.converged || (settings_.scan_matching.accept_unconverged &&
                                              match.icp.status == IcpStatus::kNotConverged);
  if (!usable) {
    ++counters_.scan_match_failures;
    return;
  }
  const auto start = Clock::now();
  // z = T_anchor_robot measures the relative pose directly: h(x) = (x, y, θ), H = [I 0].
  const SE2 r = filter_.relativePose();
  Eigen::Vector3d y(match.T_anchor_robot.x() - r.x(), match.T_anchor_robot.y() - r.y(),
                    wrapAngle(match.T_anchor_robot.theta() - r.theta()));
  Eigen::Matrix<double, 3, state::kSize> H = Eigen::Matrix<double, 3, state::kSize>::Zero();
  H.block<3, 3>(0, state::kX).setIdentity();
  last_correction_ = filter_.correct<3>(y, H, match.covariance, gate_sq);
  if (last_correction_->accepted) {
    ++counters_.scan_updates;
    counters_.scan_nis_sum += last_correction_->mahalanobis_sq;
  } else {
    ++counters_.scan_rejections;
  }
  timings_.filter_s += secondsSince(start);
}

Correction EkfEstimator::updateWithScanPose(const SE2& T_map_robot,
                                            const Eigen::Matrix3d& covariance, bool gated) {
  const StateVector& x = filter_.state();
  const SE2 T_map_anchor(x(state::kAnchorX), x(state::kAnchorY), x(state::kAnchorTheta));
  ScanMatch match;
  match.T_anchor_robot = T_map_anchor.inverse() * T_map_robot;
  match.covariance = covariance;
  match.icp.converged = true;
  updateWithScanMatch(match, gated ? gate_3dof_sq_ : std::numeric_limits<double>::infinity());
  return last_correction_ ? *last_correction_ : Correction{};
}

void EkfEstimator::addImu(const ImuSample& imu) {
  if (isLate(imu.stamp)) {
    ++counters_.late_imu;
    return;
  }
  const auto start = Clock::now();
  if (settings_.imu.use_heading && imu.has_orientation) {
    updateHeading(imu);
  }
  if (settings_.imu.use_yaw_rate) {
    updateYawRate(imu);
  }
  last_imu_ = imu;
  timings_.filter_s += secondsSince(start);
}

void EkfEstimator::updateHeading(const ImuSample& imu) {
  const double yaw_robot = wrapAngle(imu.yaw_rad - mounting_.imu_yaw_offset_rad);
  const double sigma = settings_.imu.heading_sigma_rad;
  if (!heading_aligned_) {
    filter_.initialiseHeadingOffset(yaw_robot, sigma * sigma);
    heading_aligned_ = true;
    return;  // the first reading defines the IMU's heading of the map frame, α
  }
  // h(x) = θ_a + θ + α.
  Eigen::Matrix<double, 1, 1> y;
  y(0) = wrapAngle(yaw_robot - filter_.heading() - filter_.state()(state::kImuHeadingOffset));
  Eigen::Matrix<double, 1, state::kSize> H = Eigen::Matrix<double, 1, state::kSize>::Zero();
  H(0, state::kTheta) = 1.0;
  H(0, state::kAnchorTheta) = 1.0;
  H(0, state::kImuHeadingOffset) = 1.0;
  const Correction correction =
      filter_.correct<1>(y, H, Eigen::Matrix<double, 1, 1>(sigma * sigma), gate_1dof_sq_);
  ++(correction.accepted ? counters_.heading_updates : counters_.heading_rejections);
  if (correction.accepted) {
    gated_heading_since_.reset();
  } else if (!gated_heading_since_) {
    gated_heading_since_ = imu.stamp;
  } else if (secondsBetween(*gated_heading_since_, imu.stamp) >= settings_.imu.heading_recovery_s) {
    // A stabilised heading that disagrees this long is a heading estimate gone astray (a wrong
    // scan match): open its variance by the disagreement so the next readings pull it back.
    filter_.addVariance(state::kTheta, y(0) * y(0) + sigma * sigma);
    ++counters_.heading_recoveries;
    gated_heading_since_.reset();
  }
}

void EkfEstimator::updateYawRate(const ImuSample& imu) {
  const double dt = last_imu_ ? secondsBetween(last_imu_->stamp, imu.stamp) : 0.0;
  if (last_imu_ && (dt <= 0.0 || dt > settings_.imu.max_gap_s)) {
    ++counters_.imu_gaps;
  } else if (last_imu_) {
    const double walk = settings_.imu.bias_walk_rad_s_sqrt_s;
    filter_.addVariance(state::kGyroBias, walk * walk * dt);
    // z = ½(ω_{k−1} + ω_k) Δt,  h = θ_a + θ − θ_imu + b Δt.
    const double z = 0.5 * (last_imu_->angular_rate_rad_s.z() + imu.angular_rate_rad_s.z()) * dt;
    const StateVector& x = filter_.state();
    Eigen::Matrix<double, 1, 1> y;
    y(0) = wrapAngle(z - (filter_.heading() - x(state::kImuTheta) + x(state::kGyroBias) * dt));
    Eigen::Matrix<double, 1, state::kSize> H = Eigen::Matrix<double, 1, state::kSize>::Zero();
    H(0, state::kTheta) = 1.0;
    H(0, state::kAnchorTheta) = 1.0;
    H(0, state::kImuTheta) = -1.0;
    H(0, state::kGyroBias) = dt;
    const double sigma_reading = settings_.imu.yaw_rate_sigma_rad_s * dt;
    const double sigma_rule = 0.5 * settings_.imu.yaw_acceleration_sigma_rad_s2 * dt * dt;
    const double variance = 0.5 * sigma_reading * sigma_reading + sigma_rule * sigma_rule;
    const Correction correction =
        filter_.correct<1>(y, H, Eigen::Matrix<double, 1, 1>(variance), gate_1dof_sq_);
    ++(correction.accepted ? counters_.yaw_rate_updates : counters_.yaw_rate_rejections);
  }
  filter_.cloneHeading();
}

}  // namespace mrslam::robot
