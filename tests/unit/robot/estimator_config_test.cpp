#include "mrslam/robot/estimator_config.hpp"

#include <gtest/gtest.h>

#include "mrslam/robot/ekf_estimator.hpp"
#include "mrslam/robot/robot_config.hpp"
#include "mrslam/robot/slam/slam_estimator.hpp"
#include "test_data.hpp"

namespace mrslam::robot {
namespace {

EstimatorSettings load(const std::string& yaml) {
  return loadEstimatorSettings(Config::loadString(yaml, "robot.yaml").section("estimator"));
}

TEST(EstimatorConfigTest, DefaultsToTheEkf) {
  const EstimatorSettings settings = load("{}");
  EXPECT_EQ(settings.type, EstimatorType::kEkf);
  EXPECT_EQ(settings.ekf.scan_matching.mode, MatchMode::kScanToMap);
  EXPECT_TRUE(settings.ekf.scan_matching.enabled);
}

TEST(EstimatorConfigTest, ReadsEveryModule) {
  const EstimatorSettings settings = load(R"(
estimator:
  type: odometry
  gate_probability: 0.99
  wheel_noise_fraction: 0.1
  scan_delay_s: 0.05
  imu: {use_heading: false, heading_sigma_rad: 0.03, max_gap_s: 1.0}
  scan_matching: {mode: scan_to_scan, local_map_keyframes: 3, max_range_m: 8.0,
                  min_correspondence_m: 0.2, min_sigma_xy_m: 0.02, covariance_shape_scale: 0.3,
                  prior_sigma_xy_m: 0.03, prior_sigma_theta_rad: 0.02, residual_sigma_m: 0.01,
                  accept_unconverged: true, match_newest_keyframe: true,
                  two_match_covariance_factor: 1.5}
)");
  EXPECT_EQ(settings.type, EstimatorType::kOdometry);
  EXPECT_DOUBLE_EQ(settings.ekf.gate_probability, 0.99);
  EXPECT_DOUBLE_EQ(settings.ekf.wheel_noise_fraction, 0.1);
  EXPECT_DOUBLE_EQ(settings.ekf.scan_delay_s, 0.05);
  EXPECT_FALSE(settings.ekf.imu.use_heading);
  EXPECT_DOUBLE_EQ(settings.ekf.imu.heading_sigma_rad, 0.03);
  EXPECT_EQ(settings.ekf.scan_matching.mode, MatchMode::kScanToScan);
  EXPECT_EQ(settings.ekf.scan_matching.local_map_keyframes, 3u);
  EXPECT_DOUBLE_EQ(settings.ekf.scan_matching.points.max_range_m, 8.0);
  EXPECT_DOUBLE_EQ(settings.ekf.scan_matching.icp.min_correspondence_m, 0.2);
  EXPECT_DOUBLE_EQ(settings.ekf.scan_matching.min_sigma_xy_m, 0.02);
  EXPECT_DOUBLE_EQ(settings.ekf.scan_matching.covariance_shape_scale, 0.3);
  EXPECT_DOUBLE_EQ(settings.ekf.scan_matching.icp.prior_sigma_xy_m, 0.03);
  EXPECT_DOUBLE_EQ(settings.ekf.scan_matching.icp.prior_sigma_theta_rad, 0.02);
  EXPECT_DOUBLE_EQ(settings.ekf.scan_matching.icp.residual_sigma_m, 0.01);
  EXPECT_TRUE(settings.ekf.scan_matching.accept_unconverged);
  EXPECT_TRUE(settings.ekf.scan_matching.match_newest_keyframe);
  EXPECT_DOUBLE_EQ(settings.ekf.scan_matching.two_match_covariance_factor, 1.5);
}

TEST(EstimatorConfigTest, TheIcpPriorAndTheSecondMatchAreOffByDefault) {
  const EstimatorSettings settings = load("{}");
  EXPECT_EQ(settings.ekf.scan_matching.icp.prior_sigma_xy_m, 0.0);
  EXPECT_EQ(settings.ekf.scan_matching.icp.prior_sigma_theta_rad, 0.0);
  EXPECT_FALSE(settings.ekf.scan_matching.accept_unconverged);
  EXPECT_FALSE(settings.ekf.scan_matching.match_newest_keyframe);
}

TEST(EstimatorConfigTest, BadValuesStopWithTheirPlace) {
  EXPECT_THROW(load("estimator: {type: kalman}"), ConfigError);
  EXPECT_THROW(load("estimator: {gate_probability: 1.5}"), ConfigError);
  EXPECT_THROW(load("estimator: {scan_matching: {mode: sideways}}"), ConfigError);
  EXPECT_THROW(load("estimator: {scan_matching: {min_correspondence_m: 2.0, "
                    "max_correspondence_m: 1.0}}"),
               ConfigError);
  EXPECT_THROW(load("estimator: {scan_matching: {prior_sigma_xy_m: -0.1}}"), ConfigError);
  EXPECT_THROW(load("estimator: {scan_matching: {prior_sigma_theta_rad: 20}}"), ConfigError);
  EXPECT_THROW(load("estimator: {scan_matching: {residual_sigma_m: 0}}"), ConfigError);
  EXPECT_THROW(load("estimator: {scan_matching: {accept_unconverged: maybe}}"), ConfigError);
  EXPECT_THROW(load("estimator: {scan_matching: {two_match_covariance_factor: 0.5}}"), ConfigError);
  EXPECT_THROW(parseEstimatorType("kalman"), std::invalid_argument);
  EXPECT_EQ(parseEstimatorType("odometry"), EstimatorType::kOdometry);
  EXPECT_STREQ(estimatorTypeName(EstimatorType::kEkf), "ekf");
}

TEST(EstimatorConfigTest, ShippedRobotConfigsLoadAndPickTheirEstimator) {
  for (const char* name : {"breezyslam.yaml", "breezyslam_exp1.yaml", "breezyslam_exp2.yaml",
                           "sim_robot1.yaml", "sim_robot2.yaml", "sim_robot3.yaml"}) {
    const RobotConfig config = loadRobotConfig(test::sourcePath(std::string("config/") + name));
    EXPECT_EQ(config.estimator.type, EstimatorType::kEkf) << name;
    EXPECT_NE(dynamic_cast<EkfEstimator*>(makeEstimator(config, config.estimator.type).get()),
              nullptr)
        << name;
  }
  const RobotConfig carmen = loadRobotConfig(test::sourcePath("config/carmen.yaml"));
  EXPECT_EQ(carmen.estimator.type, EstimatorType::kSlam);  // a raw log needs loop closure
  EXPECT_NE(dynamic_cast<slam::SlamEstimator*>(makeEstimator(carmen, carmen.estimator.type).get()),
            nullptr);
  EXPECT_TRUE(carmen.source.path.empty());
  EXPECT_FALSE(carmen.source.odometry_noise.enabled());
  EXPECT_DOUBLE_EQ(carmen.mapping.max_range_m, 50.0);
  EXPECT_EQ(carmen.mounting.T_robot_laser.x(), 0.0);
  EXPECT_THROW(openSource(carmen), std::runtime_error);  // no log given
}

TEST(EstimatorConfigTest, OdometryNoiseOfTheSourceWrapsIt) {
  RobotConfig config = loadRobotConfig(test::sourcePath("config/carmen.yaml"));
  config.source.path = test::sourcePath("tests/fuzz/corpus/carmen_reader/small.log");
  config.source.odometry_noise.distance_fraction = 0.1;
  EXPECT_NE(openSource(config)->describe().find("odometry noise"), std::string::npos);
  config.source.odometry_noise.distance_fraction = 0.0;
  EXPECT_EQ(openSource(config)->describe().find("odometry noise"), std::string::npos);
}

}  // namespace
}  // namespace mrslam::robot
