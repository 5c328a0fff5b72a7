#pragma once
// Laser odometry for the EKF: each scan is matched by point-to-line ICP either against the
// previous scan (scan-to-scan) or against a local map made of the last K keyframes' points in the
// map frame (scan-to-map). The result is a measurement of the robot pose relative to the newest
// keyframe (the anchor), whose pose the EKF keeps as a cloned state: the local map moves rigidly
// with the anchor, so the filter's covariance keeps growing between keyframes as it should.

#include <deque>
#include <functional>
#include <optional>

#include "mrslam/common/platform.hpp"
#include "mrslam/common/samples.hpp"
#include "mrslam/robot/icp.hpp"

namespace mrslam::robot {

enum class MatchMode {
  kScanToScan,  ///< the target is the previous scan; every scan is a keyframe
  kScanToMap,   ///< the target is the last local_map_keyframes keyframes
};

struct ScanMatcherSettings {
  bool enabled = true;                     ///< false: no laser update (odometry and IMU only)
  MatchMode mode = MatchMode::kScanToMap;  ///< what a scan is matched against
  std::size_t local_map_keyframes = 8;     ///< K: keyframes in the local map (scan-to-map)
  double keyframe_distance_m = 0.3;        ///< a scan this far from the anchor becomes a keyframe
  double keyframe_angle_rad = 0.25;        ///< ... or turned this much from it
  ScanPointSettings points;                ///< which hits are used, thinning, normals
  IcpSettings icp;                         ///< the registration
  double covariance_scale = 1.0;           ///< the fit covariance (icp.hpp eq. 4) times this
  /// > 0: the fit covariance is instead scaled so that its best-constrained translation direction
  /// has variance covariance_shape_scale · min_sigma_xy_m², its shape kept: a direction the scan
  /// hardly constrains (along a corridor) stays as many times less certain. 0: covariance_scale.
  double covariance_shape_scale = 0.0;
  double min_sigma_xy_m = 0.01;        ///< floor of the measurement's σ in x and y
  double min_sigma_theta_rad = 0.005;  ///< floor of the measurement's σ in θ
  /// An ICP that ran out of iterations with enough pairs (kNotConverged: its last steps were
  /// still creeping, typically by millimetres) is still a measurement, gated like any other;
  /// false: it counts as a failed match.
  bool accept_unconverged = false;
  /// scan_to_map: the scan is also matched against the newest keyframe alone, a second
  /// measurement of T_anchor_robot whose errors (another target) are only partly shared.
  bool match_newest_keyframe = false;
  /// With match_newest_keyframe, both measurements' covariances are multiplied by this: they
  /// share the scan and the newest keyframe, so they are not two independent measurements.
  double two_match_covariance_factor = 2.0;
};

/// A scan turned into the point sets matching needs (robot frame).
struct PreparedScan {
  std::vector<Eigen::Vector2d> source;  ///< thinned hits: what is aligned
  OrientedPoints oriented;              ///< hits with normals: what a keyframe adds to the map
};

/// One registration, as a measurement for the filter.
struct ScanMatch {
  IcpResult icp;               ///< icp.T_target_source is T_map_robot
  SE2 T_anchor_robot;          ///< the robot relative to the anchor keyframe
  Eigen::Matrix3d covariance;  ///< of T_anchor_robot's (x, y, θ): scaled fit + floor
};

class ScanMatcher {
 public:
  ScanMatcher(const ScanMatcherSettings& settings, const SensorMounting& mounting);

  /// T_scan_beam: the robot's pose when a beam was taken relative to its pose at the scan's
  /// reference time (de-skewing); empty: all beams at once.
  using BeamMotion = std::function<SE2(std::size_t beam)>;

  /// The scan's point sets in the robot frame (at the reference time, when de-skewed).
  PreparedScan prepare(const LaserScan& scan, const BeamMotion& motion = {}) const;

  /// True once a keyframe has been added.
  bool hasMap() const { return !keyframes_.empty(); }
  /// ICP of `scan` against the local map from `T_map_robot_guess`; nothing without a map.
  std::optional<ScanMatch> match(const PreparedScan& scan, const SE2& T_map_robot_guess) const;
  /// With match_newest_keyframe (scan_to_map): ICP of `scan` against the newest keyframe alone;
  /// otherwise, or without a map, nothing.
  std::optional<ScanMatch> matchNewestKeyframe(const PreparedScan& scan,
                                               const SE2& T_map_robot_guess) const;
  /// True when a scan at T_map_robot should become a keyframe (always without a map).
  bool isKeyframe(const SE2& T_map_robot) const;
  /// Adds a keyframe at T_map_robot; it becomes the anchor.
  void addKeyframe(const PreparedScan& scan, const SE2& T_map_robot);

  /// T_map_anchor: the newest keyframe's pose as it was added.
  const SE2& anchor() const { return T_map_anchor_; }
  const ScanMatcherSettings& settings() const { return settings_; }

 private:
  /// True when every scan is matched twice (local map and newest keyframe).
  bool matchesTwice() const;
  ScanMatch matchAgainst(const IcpTarget& target, const PreparedScan& scan,
                         const SE2& T_map_robot_guess) const;

  const ScanMatcherSettings settings_;
  const SensorMounting mounting_;
  std::deque<OrientedPoints> keyframes_;  ///< map frame, oldest first
  IcpTarget target_;
  IcpTarget newest_target_;  ///< the newest keyframe alone (match_newest_keyframe)
  SE2 T_map_anchor_;
};

}  // namespace mrslam::robot
