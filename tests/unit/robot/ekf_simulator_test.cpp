// The EKF on the simulator, whose scans carry the true pose: accuracy with every sensor and with
// each one missing, an injected wrong scan, and the consistency of the covariance (NEES).

#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

#include "mrslam/robot/chi_square.hpp"
#include "mrslam/robot/evaluation.hpp"
#include "test_data.hpp"

namespace mrslam::robot {
namespace {

constexpr double kDeg = M_PI / 180.0;

RobotConfig simulatorConfig(int route, std::uint64_t seed, double duration_s = 60.0) {
  RobotConfig config = loadRobotConfig(test::sourcePath("config/sim_robot1.yaml"));
  config.simulator.robot_index = route;
  config.sightings.robots.clear();  // robot1's teammates drive the other routes
  config.simulator.seed = seed;
  config.simulator.duration_s = duration_s;
  return config;
}

std::vector<Sample> simulate(const RobotConfig& config,
                             const std::function<bool(const Sample&)>& keep = {}) {
  auto source = openSource(config);
  std::vector<Sample> samples;
  for (Sample& sample : readAllSamples(*source)) {
    if (!keep || keep(sample)) {
      samples.push_back(std::move(sample));
    }
  }
  return samples;
}

// The true pose of every scan in the map frame (the pose at the first scan).
std::vector<SE2> truthInMapFrame(const std::vector<Sample>& samples) {
  std::vector<SE2> truth = *groundTruth(samples);
  const SE2 T_map_world = truth.front().inverse();
  for (SE2& pose : truth) {
    pose = T_map_world * pose;
  }
  return truth;
}

struct Outcome {
  AccuracyReport report;
  double final_error_m = 0.0;
  double final_heading_error_rad = 0.0;
  EkfCounters counters;
};

Outcome runEkf(const RobotConfig& config, const std::vector<Sample>& samples) {
  const PipelineRun run = runPipeline(config, EstimatorType::kEkf, samples);
  const std::vector<SE2> truth = truthInMapFrame(samples);
  Outcome outcome;
  outcome.report = evaluateRun(run, truth);
  const SE2 error = truth.back().inverse() * run.pipeline->trajectory().back().T_map_robot;
  outcome.final_error_m = error.translation().norm();
  outcome.final_heading_error_rad = std::abs(error.theta());
  outcome.counters = *run.ekf_counters;
  return outcome;
}

template <typename T>
bool isA(const Sample& sample) {
  return std::holds_alternative<T>(sample);
}

TEST(EkfSimulatorTest, AllSensorsTrackTheTruthAndBeatOdometry) {
  const RobotConfig config = simulatorConfig(0, 11);
  const std::vector<Sample> samples = simulate(config);
  const Outcome ekf = runEkf(config, samples);
  const AccuracyReport odometry =
      evaluateRun(runPipeline(config, EstimatorType::kOdometry, samples), truthInMapFrame(samples));
  EXPECT_LT(ekf.final_error_m, 0.05);
  EXPECT_LT(ekf.final_heading_error_rad, 0.5 * kDeg);
  EXPECT_LT(ekf.report.rpe_10.rotation_mean_deg, 0.5 * odometry.rpe_10.rotation_mean_deg);
  EXPECT_LT(ekf.report.ate.translation_rms_m, odometry.ate.translation_rms_m);
  EXPECT_GT(ekf.counters.scan_updates, 590u);
  EXPECT_GT(ekf.counters.heading_updates, 2900u);
  EXPECT_GT(ekf.counters.yaw_rate_updates, 2900u);
}

TEST(EkfSimulatorTest, EachSensorMissingInTurn) {
  const RobotConfig config = simulatorConfig(1, 22);
  struct Case {
    const char* name;
    std::function<bool(const Sample&)> keep;
    double max_final_error_m;
    double max_final_heading_error_deg;
  };
  // Every scan is still kept (the trajectory has one pose per scan); without the laser the
  // scan matcher is switched off instead.
  const std::vector<Case> cases = {
      {"no IMU", [](const Sample& s) { return !isA<ImuSample>(s); }, 0.15, 2.5},
      {"no wheel ticks", [](const Sample& s) { return !isA<WheelTicks>(s); }, 0.1, 0.5},
      {"no IMU, no wheel ticks (laser only)", [](const Sample& s) { return isA<LaserScan>(s); },
       0.3, 3.0},
  };
  for (const Case& c : cases) {
    const Outcome outcome = runEkf(config, simulate(config, c.keep));
    EXPECT_LT(outcome.final_error_m, c.max_final_error_m) << c.name;
    EXPECT_LT(outcome.final_heading_error_rad, c.max_final_heading_error_deg * kDeg) << c.name;
    std::printf("%s: final error %.4f m %.3f deg, RPE10 %.4f m %.3f deg\n", c.name,
                outcome.final_error_m, outcome.final_heading_error_rad / kDeg,
                outcome.report.rpe_10.translation_mean_m, outcome.report.rpe_10.rotation_mean_deg);
  }
  RobotConfig no_laser = config;
  no_laser.estimator.ekf.scan_matching.enabled = false;
  const Outcome outcome = runEkf(no_laser, simulate(no_laser));
  EXPECT_LT(outcome.final_error_m, 0.5) << "no laser";
  EXPECT_LT(outcome.final_heading_error_rad, 1.0 * kDeg) << "no laser";
  EXPECT_EQ(outcome.counters.scan_updates, 0u);
}

TEST(EkfSimulatorTest, AScanFromElsewhereIsGatedOutOrFails) {
  const RobotConfig config = simulatorConfig(2, 33, 30.0);
  std::vector<Sample> samples = simulate(config);
  // Replace the 200th scan's ranges by those of the 20th (another room, another heading),
  // keeping its stamp and true pose.
  std::vector<LaserScan*> scans;
  for (Sample& sample : samples) {
    if (auto* scan = std::get_if<LaserScan>(&sample)) {
      scans.push_back(scan);
    }
  }
  ASSERT_GT(scans.size(), 200u);
  scans[200]->ranges_m = scans[20]->ranges_m;
  const Outcome outcome = runEkf(config, samples);
  EXPECT_GE(outcome.counters.scan_rejections + outcome.counters.scan_match_failures, 1u);
  EXPECT_LT(outcome.report.rpe_consecutive.translation_max_m, 0.05);
  EXPECT_LT(outcome.final_error_m, 0.05);
}

// Average NEES over M independent runs (3 routes × 3 seeds): with a consistent filter each
// run's time-averaged NEES has mean 3; the average over the M runs must lie within the 95 %
// bounds of χ²(3M)/M (Bar-Shalom, Li & Kirubarajan 2001, §5.4).
TEST(EkfSimulatorTest, AverageNeesIsWithinItsChiSquareBounds) {
  double sum = 0.0;
  int runs = 0;
  for (int route = 0; route < 3; ++route) {
    for (std::uint64_t seed : {101u, 202u, 303u}) {
      const RobotConfig config = simulatorConfig(route, seed);
      const double nees = runEkf(config, simulate(config)).report.mean_nees;
      EXPECT_TRUE(std::isfinite(nees));
      sum += nees;
      ++runs;
    }
  }
  const double average = sum / runs;
  const double low = chiSquareQuantile(0.025, 3 * runs) / runs;
  const double high = chiSquareQuantile(0.975, 3 * runs) / runs;
  EXPECT_GT(average, low);
  EXPECT_LT(average, high);
}

TEST(EkfSimulatorTest, ImuMountedAtAnAngleChangesNothing) {
  RobotConfig config = simulatorConfig(0, 44, 30.0);
  const Outcome straight = runEkf(config, simulate(config));
  config.mounting.imu_yaw_offset_rad = 0.7;  // the simulator's IMU reports this much more yaw
  const Outcome turned = runEkf(config, simulate(config));
  EXPECT_NEAR(turned.final_error_m, straight.final_error_m, 0.01);
  EXPECT_EQ(turned.counters.heading_rejections, straight.counters.heading_rejections);
}

}  // namespace
}  // namespace mrslam::robot
