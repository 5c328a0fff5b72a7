#include "mrslam/robot/estimator_config.hpp"

#include <stdexcept>

#include "mrslam/robot/slam/slam_config.hpp"

namespace mrslam::robot {

namespace {

ImuSettings loadImu(const Config& section) {
  ImuSettings imu;
  imu.use_heading = section.getBool("use_heading", imu.use_heading);
  imu.use_yaw_rate = section.getBool("use_yaw_rate", imu.use_yaw_rate);
  imu.heading_sigma_rad = section.getDouble("heading_sigma_rad", imu.heading_sigma_rad, {1e-6, 10});
  imu.yaw_rate_sigma_rad_s =
      section.getDouble("yaw_rate_sigma_rad_s", imu.yaw_rate_sigma_rad_s, {1e-6, 10});
  imu.yaw_acceleration_sigma_rad_s2 = section.getDouble(
      "yaw_acceleration_sigma_rad_s2", imu.yaw_acceleration_sigma_rad_s2, {0, 1000});
  imu.initial_bias_sigma_rad_s =
      section.getDouble("initial_bias_sigma_rad_s", imu.initial_bias_sigma_rad_s, {0, 10});
  imu.bias_walk_rad_s_sqrt_s =
      section.getDouble("bias_walk_rad_s_sqrt_s", imu.bias_walk_rad_s_sqrt_s, {0, 1});
  imu.max_gap_s = section.getDouble("max_gap_s", imu.max_gap_s, {1e-3, 60});
  imu.heading_recovery_s =
      section.getDouble("heading_recovery_s", imu.heading_recovery_s, {0.1, 3600});
  return imu;
}

IcpSettings loadIcp(const Config& section, IcpSettings icp) {
  icp.max_iterations =
      static_cast<int>(section.getInt("max_iterations", icp.max_iterations, {1, 1000}));
  icp.max_correspondence_m =
      section.getDouble("max_correspondence_m", icp.max_correspondence_m, {1e-3, 100});
  icp.min_correspondence_m =
      section.getDouble("min_correspondence_m", icp.min_correspondence_m, {1e-3, 100});
  if (icp.min_correspondence_m > icp.max_correspondence_m) {
    section.fail("min_correspondence_m", "must not exceed max_correspondence_m");
  }
  icp.gate_decay = section.getDouble("gate_decay", icp.gate_decay, {0.05, 1.0});
  icp.kernel_fraction = section.getDouble("kernel_fraction", icp.kernel_fraction, {0.0, 10.0});
  icp.min_inliers = static_cast<std::size_t>(
      section.getInt("min_inliers", static_cast<long long>(icp.min_inliers), {4, 1e6}));
  icp.min_inlier_fraction =
      section.getDouble("min_inlier_fraction", icp.min_inlier_fraction, {0.0, 1.0});
  icp.prior_sigma_xy_m = section.getDouble("prior_sigma_xy_m", icp.prior_sigma_xy_m, {0.0, 100});
  icp.prior_sigma_theta_rad =
      section.getDouble("prior_sigma_theta_rad", icp.prior_sigma_theta_rad, {0.0, 10});
  icp.residual_sigma_m = section.getDouble("residual_sigma_m", icp.residual_sigma_m, {1e-4, 10});
  return icp;
}

ScanPointSettings loadPoints(const Config& section, ScanPointSettings points) {
  points.min_range_m = section.getDouble("min_range_m", points.min_range_m, {0, 1000});
  points.max_range_m = section.getDouble("max_range_m", points.max_range_m, {0.01, 1000});
  points.min_spacing_m = section.getDouble("min_spacing_m", points.min_spacing_m, {0, 10});
  points.normal_half_window =
      static_cast<int>(section.getInt("normal_half_window", points.normal_half_window, {1, 50}));
  points.max_step_m = section.getDouble("max_step_m", points.max_step_m, {1e-3, 10});
  points.max_step_beam_factor =
      section.getDouble("max_step_beam_factor", points.max_step_beam_factor, {0, 100});
  points.max_line_ratio = section.getDouble("max_line_ratio", points.max_line_ratio, {0.0, 1.0});
  return points;
}

ScanMatcherSettings loadScanMatching(const Config& section) {
  ScanMatcherSettings matching;
  matching.enabled = section.getBool("enabled", matching.enabled);
  matching.mode =
      section.getChoice("mode", "scan_to_map", {"scan_to_map", "scan_to_scan"}) == "scan_to_scan"
          ? MatchMode::kScanToScan
          : MatchMode::kScanToMap;
  matching.local_map_keyframes = static_cast<std::size_t>(section.getInt(
      "local_map_keyframes", static_cast<long long>(matching.local_map_keyframes), {1, 1000}));
  matching.keyframe_distance_m =
      section.getDouble("keyframe_distance_m", matching.keyframe_distance_m, {0, 100});
  matching.keyframe_angle_rad =
      section.getDouble("keyframe_angle_rad", matching.keyframe_angle_rad, {0, M_PI});
  matching.points = loadPoints(section, matching.points);
  matching.icp = loadIcp(section, matching.icp);
  matching.covariance_scale =
      section.getDouble("covariance_scale", matching.covariance_scale, {1e-3, 1e6});
  matching.covariance_shape_scale =
      section.getDouble("covariance_shape_scale", matching.covariance_shape_scale, {0, 1e6});
  matching.min_sigma_xy_m = section.getDouble("min_sigma_xy_m", matching.min_sigma_xy_m, {0, 10});
  matching.min_sigma_theta_rad =
      section.getDouble("min_sigma_theta_rad", matching.min_sigma_theta_rad, {0, 10});
  matching.accept_unconverged = section.getBool("accept_unconverged", matching.accept_unconverged);
  matching.match_newest_keyframe =
      section.getBool("match_newest_keyframe", matching.match_newest_keyframe);
  matching.two_match_covariance_factor = section.getDouble(
      "two_match_covariance_factor", matching.two_match_covariance_factor, {1.0, 100});
  return matching;
}

}  // namespace

const char* estimatorTypeName(EstimatorType type) {
  switch (type) {
    case EstimatorType::kOdometry:
      return "odometry";
    case EstimatorType::kEkf:
      return "ekf";
    case EstimatorType::kSlam:
      return "slam";
  }
  return "ekf";
}

EstimatorType parseEstimatorType(const std::string& name) {
  if (name == "odometry") {
    return EstimatorType::kOdometry;
  }
  if (name == "ekf") {
    return EstimatorType::kEkf;
  }
  if (name == "slam") {
    return EstimatorType::kSlam;
  }
  throw std::invalid_argument("estimator '" + name + "' is not odometry, ekf or slam");
}

EstimatorSettings loadEstimatorSettings(const Config& section) {
  EstimatorSettings settings;
  settings.type = parseEstimatorType(section.getChoice("type", "ekf", {"odometry", "ekf", "slam"}));
  EkfSettings& ekf = settings.ekf;
  ekf.gate_probability =
      section.getDouble("gate_probability", ekf.gate_probability, {0.5, 1.0 - 1e-12});
  ekf.wheel_noise_fraction =
      section.getDouble("wheel_noise_fraction", ekf.wheel_noise_fraction, {0.0, 10.0});
  ekf.wheel_turn_noise_per_rad =
      section.getDouble("wheel_turn_noise_per_rad", ekf.wheel_turn_noise_per_rad, {0.0, 10.0});
  const Config motion = section.section("motion_model");
  ekf.motion_model_sigma_xy_m =
      motion.getDouble("sigma_xy_m", ekf.motion_model_sigma_xy_m, {1e-4, 100});
  ekf.motion_model_sigma_theta_rad =
      motion.getDouble("sigma_theta_rad", ekf.motion_model_sigma_theta_rad, {1e-4, 10});
  ekf.scan_delay_s = section.getDouble("scan_delay_s", ekf.scan_delay_s, {0.0, 10.0});
  ekf.scan_duration_s = section.getDouble("scan_duration_s", ekf.scan_duration_s, {0.0, 10.0});
  ekf.imu = loadImu(section.section("imu"));
  ekf.scan_matching = loadScanMatching(section.section("scan_matching"));
  settings.slam = slam::loadSlamSettings(section.section("slam"));
  return settings;
}

}  // namespace mrslam::robot
