#include "mrslam/robot/scan_matcher.hpp"

#include <cmath>

namespace mrslam::robot {

namespace {

// The smallest eigenvalue of a symmetric 2 × 2 matrix: (a + c)/2 − √(((a − c)/2)² + b²).
double smallestEigenvalue(const Eigen::Matrix2d& m) {
  return 0.5 * (m(0, 0) + m(1, 1)) - std::hypot(0.5 * (m(0, 0) - m(1, 1)), m(0, 1));
}

// The fit covariance (icp.hpp eq. 4) turned into the measurement's, before the floor is added.
// Its scale (σ̂² / n) ignores correlated errors and is far too small; its shape, the inverse of the
// pairs' information, tells which directions the scan constrains.
Eigen::Matrix3d scaledFitCovariance(const Eigen::Matrix3d& fit,
                                    const ScanMatcherSettings& settings) {
  if (settings.covariance_shape_scale <= 0.0) {
    return settings.covariance_scale * fit;
  }
  const double best_variance = smallestEigenvalue(fit.topLeftCorner<2, 2>());
  if (!(best_variance > 0.0)) {
    return settings.covariance_scale * fit;
  }
  const double floor_variance = settings.min_sigma_xy_m * settings.min_sigma_xy_m;
  return (settings.covariance_shape_scale * floor_variance / best_variance) * fit;
}

}  // namespace

ScanMatcher::ScanMatcher(const ScanMatcherSettings& settings, const SensorMounting& mounting)
    : settings_(settings), mounting_(mounting) {}

PreparedScan ScanMatcher::prepare(const LaserScan& scan, const BeamMotion& motion) const {
  ScanHits hits = scanHits(scan, mounting_.T_robot_laser, settings_.points);
  if (motion) {
    for (std::size_t i = 0; i < hits.points.size(); ++i) {
      hits.points[i] = motion(hits.beams[i]) * hits.points[i];
    }
  }
  return {thinned(hits, settings_.points), orientedHits(hits, settings_.points)};
}

bool ScanMatcher::matchesTwice() const {
  return settings_.match_newest_keyframe && settings_.mode == MatchMode::kScanToMap;
}

ScanMatch ScanMatcher::matchAgainst(const IcpTarget& target, const PreparedScan& scan,
                                    const SE2& T_map_robot_guess) const {
  ScanMatch match;
  match.icp = alignPointToLine(target, scan.source, T_map_robot_guess, settings_.icp);
  match.T_anchor_robot = T_map_anchor_.inverse() * match.icp.T_target_source;
  // (x, y) of T_anchor_robot = R_aᵀ (t − t_a), θ − θ_a: the covariance turns with R_aᵀ.
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
  A.topLeftCorner<2, 2>() = T_map_anchor_.rotation().transpose();
  match.covariance = A * scaledFitCovariance(match.icp.covariance, settings_) * A.transpose();
  match.covariance(0, 0) += settings_.min_sigma_xy_m * settings_.min_sigma_xy_m;
  match.covariance(1, 1) += settings_.min_sigma_xy_m * settings_.min_sigma_xy_m;
  match.covariance(2, 2) += settings_.min_sigma_theta_rad * settings_.min_sigma_theta_rad;
  if (matchesTwice()) {
    match.covariance *= settings_.two_match_covariance_factor;
  }
  return match;
}

std::optional<ScanMatch> ScanMatcher::match(const PreparedScan& scan,
                                            const SE2& T_map_robot_guess) const {
  if (!hasMap()) {
    return std::nullopt;
  }
  return matchAgainst(target_, scan, T_map_robot_guess);
}

std::optional<ScanMatch> ScanMatcher::matchNewestKeyframe(const PreparedScan& scan,
                                                          const SE2& T_map_robot_guess) const {
  if (!hasMap() || !matchesTwice()) {
    return std::nullopt;
  }
  return matchAgainst(newest_target_, scan, T_map_robot_guess);
}

bool ScanMatcher::isKeyframe(const SE2& T_map_robot) const {
  if (!hasMap() || settings_.mode == MatchMode::kScanToScan) {
    return true;
  }
  const SE2 T_anchor_robot = T_map_anchor_.inverse() * T_map_robot;
  return T_anchor_robot.translation().norm() >= settings_.keyframe_distance_m ||
         std::abs(T_anchor_robot.theta()) >= settings_.keyframe_angle_rad;
}

void ScanMatcher::addKeyframe(const PreparedScan& scan, const SE2& T_map_robot) {
  const std::size_t capacity = settings_.mode == MatchMode::kScanToScan
                                   ? 1
                                   : std::max<std::size_t>(1, settings_.local_map_keyframes);
  keyframes_.push_back(transformed(scan.oriented, T_map_robot));
  while (keyframes_.size() > capacity) {
    keyframes_.pop_front();
  }
  OrientedPoints local_map;
  for (const OrientedPoints& keyframe : keyframes_) {
    local_map.points.insert(local_map.points.end(), keyframe.points.begin(), keyframe.points.end());
    local_map.normals.insert(local_map.normals.end(), keyframe.normals.begin(),
                             keyframe.normals.end());
  }
  target_ = IcpTarget(std::move(local_map));
  if (matchesTwice()) {
    newest_target_ = IcpTarget(keyframes_.back());
  }
  T_map_anchor_ = T_map_robot;
}

}  // namespace mrslam::robot
