#pragma once
// The cascaded EKF of the robot agent (seed paper: "data from the laser ranger and IMU are
// filtered sequentially"). Per sample, in arrival order:
//  1. Prediction (pose_filter.hpp) by the motion since the previous reading (odometry_queue.hpp):
//     wheel ticks through the differential-drive arc, σ of each wheel's travel ∝ that travel,
//     mapped to the pose by the arc's Jacobian (plus σ_θ ∝ the turn); or an odometry pose
//     increment (CARMEN) with OdometryNoise. No time step enters, so equal or backward stamps are
//     harmless. Laser only (no wheel ticks or odometry poses seen at all): each scan first
//     repeats the last scan-to-scan motion, with motion_model noise.
//  2. Scan update: point-to-line ICP against the previous scan or the local map (scan_matcher),
//     a measurement of T_anchor_robot (the filter's relative pose, pose_filter.hpp) with the fit
//     covariance, gated (3 dof), Joseph form; optionally a second one against the newest
//     keyframe alone, from the same prediction (match_newest_keyframe). A scan far enough from
//     the anchor becomes a keyframe: the filter's anchor moves to it.
//  3. IMU update: (a) heading: the stabilised yaw minus the mounting yaw measures θ_map + α, where
//     α, the IMU's heading of the map frame, is a state initialised from the first reading (so
//     that reading's noise is not frozen into every later one); (b) yaw rate:
//     the trapezoid ½(ω_{k−1} + ω_k) Δt (noise ½σ_ω²Δt² + (σ_α Δt²/2)², reading noise plus the
//     rule's error) measures θ_map − θ_imu + b Δt, the heading change since the
//     previous IMU sample (clone θ_imu) plus the integrated gyro bias b, a random-walk state.
//     Both gated (1 dof).
// Late samples: an IMU sample older than the newest stamp seen is dropped and counted (its rate
// interval would overlap motion already predicted). Odometry and scans are used in arrival order
// (their increments are cumulative; a scan is matched at the current estimate), so the intel
// log's backward stamps and csail's repeated stamps change nothing.
// Scan timing: with scan_delay_s > 0 (a scan taken that long before its stamp, relative to the
// odometry) the filter only takes odometry up to each scan's acquisition time, the rest waits in
// the queue: the filter (and pose()) runs scan_delay_s behind the odometry, and the map gets each
// scan at the pose it was taken from. IMU samples are not delayed. With scan_duration_s > 0 the
// beams are de-skewed: each point is moved by the dead-reckoned motion between its beam's time
// and the scan's middle beam (the reference time), beams being evenly spread over the duration.

#include <chrono>
#include <cstdint>
#include <optional>

#include "mrslam/common/platform.hpp"
#include "mrslam/robot/odometry_estimator.hpp"
#include "mrslam/robot/odometry_queue.hpp"
#include "mrslam/robot/pose_estimator.hpp"
#include "mrslam/robot/pose_filter.hpp"
#include "mrslam/robot/scan_matcher.hpp"

namespace mrslam::robot {

struct ImuSettings {
  bool use_heading = true;                     ///< update θ with the stabilised yaw
  bool use_yaw_rate = true;                    ///< update the heading change with the gyro
  double heading_sigma_rad = 0.02;             ///< σ of the stabilised yaw
  double yaw_rate_sigma_rad_s = 0.01;          ///< σ of one yaw-rate reading
  double yaw_acceleration_sigma_rad_s2 = 1.0;  ///< σ of the turn rate's change: the trapezoid's
                                               ///< error, σ_α Δt² / 2, joins the reading noise
  double initial_bias_sigma_rad_s = 0.01;      ///< prior σ of the gyro bias (mean 0)
  double bias_walk_rad_s_sqrt_s = 1e-4;        ///< random walk of the bias, σ per √s
  double max_gap_s = 0.5;                      ///< longer IMU gaps give no yaw-rate update
  /// After this long with every stabilised-yaw reading gated out, the estimate (not the
  /// compass) is taken to be wrong: its heading variance opens so the readings pull it back.
  double heading_recovery_s = 2.0;
};

struct EkfSettings {
  OdometryNoise odometry;                 ///< noise of an odometry pose increment (CARMEN ODOM)
  double wheel_noise_fraction = 0.03;     ///< σ of a wheel's travel per reading, fraction of it
  double wheel_turn_noise_per_rad = 0.0;  ///< extra σ of a reading's turn per radian turned
  double motion_model_sigma_xy_m = 0.2;   ///< no odometry: σ of the repeated motion (x, y)
  double motion_model_sigma_theta_rad = 0.1;  ///< no odometry: σ of the repeated turn
  double scan_delay_s = 0.0;     ///< the scan's middle beam was taken this long before its stamp
  double scan_duration_s = 0.0;  ///< time from the first beam to the last (0: no de-skewing)
  ImuSettings imu;
  ScanMatcherSettings scan_matching;
  double gate_probability = 0.999;  ///< innovations beyond this χ² quantile are rejected
};

struct EkfCounters {
  std::uint64_t predictions = 0;
  std::uint64_t scans = 0;
  std::uint64_t scan_updates = 0;  ///< ICP results accepted (two a scan: match_newest_keyframe)
  std::uint64_t scan_match_failures = 0;  ///< ICP did not converge or found too few pairs
  std::uint64_t scan_rejections = 0;      ///< ICP results gated out
  std::uint64_t keyframes = 0;
  std::uint64_t heading_updates = 0;
  std::uint64_t heading_rejections = 0;
  std::uint64_t yaw_rate_updates = 0;
  std::uint64_t yaw_rate_rejections = 0;
  std::uint64_t late_imu = 0;            ///< IMU samples older than the newest stamp: dropped
  std::uint64_t imu_gaps = 0;            ///< IMU intervals ≤ 0 or > max_gap_s: no yaw-rate update
  std::uint64_t heading_recoveries = 0;  ///< heading_recovery_s of gated yaw: variance opened
  /// Σ yᵀS⁻¹y of the accepted scan updates: ÷ scan_updates is near 3 when the noise is right.
  double scan_nis_sum = 0.0;
};

/// Time spent per stage (steady clock), for the benchmark's per-scan split.
struct EkfTimings {
  double scan_matching_s = 0.0;  ///< scan preparation, ICP and keyframe upkeep
  double filter_s = 0.0;         ///< predictions and corrections
};

class EkfEstimator : public PoseEstimator {
 public:
  EkfEstimator(const DiffDriveParams& platform, const SensorMounting& mounting,
               const EkfSettings& settings);

  void addWheelTicks(const WheelTicks& ticks) override;
  void addOdometry(const OdometryPose& odometry) override;
  void addImu(const ImuSample& imu) override;
  void addScan(const LaserScan& scan, const OccupancyGrid& map) override;

  SE2 pose() const override { return filter_.pose(); }
  Eigen::Matrix3d covariance() const override { return filter_.poseCovariance(); }

  /// A scan update from outside (a scan-to-submap match): T_map_robot measured with
  /// `covariance`, Joseph form, gated (3 dof) unless `gated` is false. Meant for a filter whose
  /// own scan matching is off (its anchor then stays at the map origin).
  Correction updateWithScanPose(const SE2& T_map_robot, const Eigen::Matrix3d& covariance,
                                bool gated = true);

  double gyroBias() const { return filter_.state()(state::kGyroBias); }
  const PoseFilter& filter() const { return filter_; }
  const EkfCounters& counters() const { return counters_; }
  const EkfTimings& timings() const { return timings_; }
  /// The latest scan match (accepted or not), if any.
  const std::optional<ScanMatch>& lastScanMatch() const { return last_match_; }
  /// The filter's verdict on the latest converged scan match, if any.
  const std::optional<Correction>& lastScanCorrection() const { return last_correction_; }

 private:
  void predict(const SE2& T_before_after, const Eigen::Matrix3d& Q_u);
  /// Queues an odometry reading and predicts with what is released up to the filter's time.
  void addOdometryReading(const OdometryReading& reading);
  /// Predicts with the queued odometry up to `stamp`.
  void releaseOdometryUpTo(Stamp stamp);
  /// The scan's middle-beam time: its stamp minus scan_delay_s.
  Stamp acquisitionTime(Stamp stamp) const;
  /// T_scan_beam of each beam from the dead reckoning (empty without de-skewing).
  ScanMatcher::BeamMotion beamMotion(const LaserScan& scan) const;
  void predictWithoutOdometry();
  void updateWithScanMatch(const ScanMatch& match, double gate_sq);
  void updateHeading(const ImuSample& imu);
  void updateYawRate(const ImuSample& imu);
  /// Notes a stamp; true when it is older than the newest seen.
  bool isLate(Stamp stamp);

  const DiffDriveParams platform_;
  const SensorMounting mounting_;
  const EkfSettings settings_;
  const double gate_1dof_sq_;
  const double gate_3dof_sq_;
  PoseFilter filter_;
  ScanMatcher matcher_;
  EkfCounters counters_;
  EkfTimings timings_;
  std::optional<ScanMatch> last_match_;
  std::optional<Correction> last_correction_;

  OdometryQueue odometry_;
  bool has_odometry_ = false;          ///< wheel ticks or odometry poses have been seen
  std::optional<SE2> last_scan_pose_;  ///< T_map_robot at the previous scan
  SE2 last_scan_motion_;               ///< between the two previous scans
  std::optional<ImuSample> last_imu_;
  bool heading_aligned_ = false;              ///< the IMU heading offset α is initialised
  std::optional<Stamp> gated_heading_since_;  ///< first of the yaw readings gated in a row
  std::optional<Stamp> newest_stamp_;
};

}  // namespace mrslam::robot
