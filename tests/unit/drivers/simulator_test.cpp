// The simulator as a sample source: settings, time stamps, determinism and the built-in routes.

#include "mrslam/drivers/simulator.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <set>
#include <utility>
#include <vector>

namespace mrslam::drivers {
namespace {

using ::testing::StartsWith;

SimulatorSettings settingsFor(int robot, double duration_s = 60.0, bool noise = true) {
  SimulatorSettings settings;
  settings.robot_index = robot;
  settings.duration_s = duration_s;
  settings.noise_enabled = noise;
  return settings;
}

std::vector<Sample> runAll(Simulator& simulator) {
  std::vector<Sample> samples;
  while (std::optional<Sample> sample = simulator.next()) {
    samples.push_back(std::move(*sample));
  }
  return samples;
}

std::vector<Sample> runAll(const SimulatorSettings& settings) {
  Simulator simulator(settings, DiffDriveParams{}, SensorMounting{});
  return runAll(simulator);
}

bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool samePose(const SE2& a, const SE2& b) {
  return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.theta(), b.theta());
}

// Bit-for-bit equality (NaN ranges compare equal to themselves).
bool identical(const Sample& a, const Sample& b) {
  if (a.index() != b.index() || stampOf(a) != stampOf(b)) {
    return false;
  }
  if (const auto* scan = std::get_if<LaserScan>(&a)) {
    const auto& other = std::get<LaserScan>(b);
    return scan->ranges_m.size() == other.ranges_m.size() &&
           std::memcmp(scan->ranges_m.data(), other.ranges_m.data(),
                       scan->ranges_m.size() * sizeof(float)) == 0 &&
           samePose(*scan->logged_pose, *other.logged_pose);
  }
  if (const auto* ticks = std::get_if<WheelTicks>(&a)) {
    const auto& other = std::get<WheelTicks>(b);
    return ticks->left == other.left && ticks->right == other.right;
  }
  const auto& imu = std::get<ImuSample>(a);
  const auto& other = std::get<ImuSample>(b);
  return sameBits(imu.roll_rad, other.roll_rad) && sameBits(imu.pitch_rad, other.pitch_rad) &&
         sameBits(imu.yaw_rad, other.yaw_rad) &&
         imu.angular_rate_rad_s == other.angular_rate_rad_s &&
         imu.acceleration_g == other.acceleration_g;
}

// Tie order of samples at one stamp: wheel ticks, then IMU, then laser.
int tieRank(const Sample& sample) {
  if (std::holds_alternative<WheelTicks>(sample)) {
    return 0;
  }
  return std::holds_alternative<ImuSample>(sample) ? 1 : 2;
}

std::string configErrorOf(const std::string& yaml) {
  try {
    loadSimulatorSettings(Config::loadString(yaml, "sim.yaml").section("simulator"));
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "no error";
}

TEST(SimulatorTest, ProgressIsTheSimulatedTimeOverTheDuration) {
  Simulator simulator(settingsFor(0, 10.0), DiffDriveParams{}, SensorMounting{});
  ASSERT_TRUE(simulator.progress().has_value());
  EXPECT_DOUBLE_EQ(*simulator.progress(), 0.0);
  double before = 0.0;
  while (std::optional<Sample> sample = simulator.next()) {
    const double progress = *simulator.progress();
    EXPECT_GE(progress, before);
    EXPECT_NEAR(progress, stampOf(*sample).seconds() / 10.0, 1e-9);
    before = progress;
  }
  EXPECT_GT(before, 0.99);
}

TEST(SimulatorTest, SameSeedGivesBitIdenticalSamples) {
  SimulatorSettings settings = settingsFor(1, 20.0);
  settings.seed = 7;
  const std::vector<Sample> first = runAll(settings);
  const std::vector<Sample> second = runAll(settings);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    ASSERT_TRUE(identical(first[i], second[i])) << "sample " << i;
  }
}

TEST(SimulatorTest, DifferentSeedsGiveDifferentNoiseOnTheSameTrueMotion) {
  SimulatorSettings settings = settingsFor(1, 20.0);
  settings.seed = 7;
  const std::vector<Sample> first = runAll(settings);
  settings.seed = 8;
  const std::vector<Sample> second = runAll(settings);
  ASSERT_EQ(first.size(), second.size());
  int differing[3] = {0, 0, 0};  // ticks, IMU, laser
  for (std::size_t i = 0; i < first.size(); ++i) {
    ASSERT_EQ(first[i].index(), second[i].index());
    differing[tieRank(first[i])] += identical(first[i], second[i]) ? 0 : 1;
    if (const auto* scan = std::get_if<LaserScan>(&first[i])) {
      EXPECT_TRUE(samePose(*scan->logged_pose, *std::get<LaserScan>(second[i]).logged_pose));
    }
  }
  EXPECT_GT(differing[0], 500);  // of 1000 tick readings
  EXPECT_GT(differing[1], 900);  // of 1000 IMU readings
  EXPECT_GT(differing[2], 190);  // of 200 scans
}

TEST(SimulatorTest, StampsStartAtTheStartTimeAndComeInOrderWithTiesBroken) {
  SimulatorSettings settings = settingsFor(2, 10.0);
  settings.start_time_s = 1000.25;
  const std::vector<Sample> samples = runAll(settings);
  ASSERT_GE(samples.size(), 3u);
  const Stamp start = Stamp::fromNanoseconds(1000250000000);
  EXPECT_EQ(stampOf(samples[0]), start);
  EXPECT_TRUE(std::holds_alternative<WheelTicks>(samples[0]));
  EXPECT_TRUE(std::holds_alternative<ImuSample>(samples[1]));
  EXPECT_TRUE(std::holds_alternative<LaserScan>(samples[2]));
  EXPECT_EQ(stampOf(samples[2]), start);
  int ties = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const Stamp before = stampOf(samples[i - 1]);
    const Stamp now = stampOf(samples[i]);
    ASSERT_LE(before, now) << "sample " << i;
    if (before == now) {
      ++ties;
      EXPECT_LT(tieRank(samples[i - 1]), tieRank(samples[i])) << "sample " << i;
    }
  }
  EXPECT_GT(ties, 500);  // at 50/50/10 Hz most stamps are shared
  EXPECT_LT(stampOf(samples.back()), Stamp::fromNanoseconds(start.ns + 10'000'000'000));
}

TEST(SimulatorTest, SampleCountsFollowTheRates) {
  const auto count = [](const SimulatorSettings& settings) {
    int counts[3] = {0, 0, 0};
    for (const Sample& sample : runAll(settings)) {
      ++counts[tieRank(sample)];
    }
    return std::vector<int>(counts, counts + 3);
  };
  EXPECT_EQ(count(settingsFor(0)), (std::vector<int>{3000, 3000, 600}));  // 50, 50, 10 Hz × 60 s
  SimulatorSettings settings = settingsFor(0, 7.5);
  settings.encoder_rate_hz = 40.0;
  settings.imu_rate_hz = 25.0;
  settings.laser_rate_hz = 4.0;
  // Stamps k / rate for k / rate < 7.5 s: 300, 188 (187.5 rounded up) and 30.
  EXPECT_EQ(count(settings), (std::vector<int>{300, 188, 30}));
}

TEST(SimulatorTest, DescribesItselfAndCountsSamples) {
  SimulatorSettings settings = settingsFor(1, 2.0);
  settings.seed = 7;
  Simulator simulator(settings, DiffDriveParams{}, SensorMounting{});
  EXPECT_EQ(simulator.describe(), "simulator robot 1 (seed 7, 2 s)");
  EXPECT_EQ(Simulator(settingsFor(0), DiffDriveParams{}, SensorMounting{}).describe(),
            "simulator robot 0 (seed 1, 60 s)");
  const std::size_t samples = runAll(simulator).size();
  EXPECT_EQ(samples, 100u + 100u + 20u);
  EXPECT_EQ(simulator.counters().samples, samples);
  EXPECT_EQ(simulator.counters().malformed_records, 0u);
  EXPECT_EQ(simulator.counters().out_of_order_stamps, 0u);
  EXPECT_FALSE(simulator.next().has_value());  // stays at the end
}

TEST(SimulatorTest, EachRobotStartsAtItsOwnBuiltInStartPose) {
  for (int robot = 0; robot < kBuiltInRouteCount; ++robot) {
    Simulator simulator(settingsFor(robot, 1.0), DiffDriveParams{}, SensorMounting{});
    const std::vector<Sample> samples = runAll(simulator);
    const auto& scan = std::get<LaserScan>(samples.at(2));
    EXPECT_TRUE(samePose(*scan.logged_pose, builtInStartPose(robot))) << robot;
    EXPECT_EQ(builtInRoute(robot).front(), builtInStartPose(robot).translation());
    for (int other = robot + 1; other < kBuiltInRouteCount; ++other) {
      const SE2 a = builtInStartPose(robot);
      const SE2 b = builtInStartPose(other);
      EXPECT_GT((a.translation() - b.translation()).norm(), 2.0) << robot << " " << other;
      EXPECT_GT(std::abs(wrapAngle(a.theta() - b.theta())), 0.5) << robot << " " << other;
    }
  }
  EXPECT_THROW(builtInStartPose(3), std::invalid_argument);
  EXPECT_THROW(builtInRoute(-1), std::invalid_argument);
}

// True poses after every sample (about 110 per second) of a noise-free run.
std::vector<SE2> truePath(int robot, double duration_s) {
  Simulator simulator(settingsFor(robot, duration_s, false), DiffDriveParams{}, SensorMounting{});
  std::vector<SE2> path;
  while (simulator.next()) {
    path.push_back(simulator.truePose());
  }
  return path;
}

TEST(SimulatorTest, RoutesKeepTheRobotRadiusClearOfWallsAndStayInside) {
  const FloorPlan plan = builtInFloorPlan();
  const PlanBounds bounds = plan.bounds();
  for (int robot = 0; robot < kBuiltInRouteCount; ++robot) {
    double least = 1e9;
    for (const SE2& pose : truePath(robot, 200.0)) {  // more than one full loop
      least = std::min(least, plan.distanceToNearestWall(pose.translation()));
      ASSERT_GT(pose.x(), bounds.min.x());
      ASSERT_LT(pose.x(), bounds.max.x());
      ASSERT_GT(pose.y(), bounds.min.y());
      ASSERT_LT(pose.y(), bounds.max.y());
    }
    EXPECT_GE(least, kSimulatedRobotRadiusM) << "robot " << robot;
  }
}

TEST(SimulatorTest, RoutesAreClosedLoopsCoveringTheCorridor) {
  for (int robot = 0; robot < kBuiltInRouteCount; ++robot) {
    const Eigen::Vector2d start = builtInStartPose(robot).translation();
    double farthest = 0.0;
    double closest_after_leaving = 1e9;
    double corridor_min_x = 1e9;
    double corridor_max_x = -1e9;
    for (const SE2& pose : truePath(robot, 200.0)) {
      const double distance = (pose.translation() - start).norm();
      farthest = std::max(farthest, distance);
      if (farthest > 5.0) {
        closest_after_leaving = std::min(closest_after_leaving, distance);
      }
      if (pose.y() > 4.2 && pose.y() < 6.0) {
        corridor_min_x = std::min(corridor_min_x, pose.x());
        corridor_max_x = std::max(corridor_max_x, pose.x());
      }
    }
    EXPECT_GT(farthest, 5.0) << robot;
    EXPECT_LT(closest_after_leaving, 0.1) << robot;  // back at the start: the loop closes
    EXPECT_GT(corridor_max_x - corridor_min_x, 4.0) << robot;
  }
}

TEST(SimulatorTest, SpeedAndTurnRateStayWithinTheLimits) {
  SimulatorSettings settings = settingsFor(0, 60.0, false);
  settings.max_speed_m_s = 0.3;
  settings.max_turn_rate_rad_s = 0.8;
  Simulator simulator(settings, DiffDriveParams{}, SensorMounting{});
  SE2 previous = simulator.truePose();
  Stamp previous_stamp;
  bool first = true;
  double top_speed = 0.0;
  double top_turn_rate = 0.0;
  while (const std::optional<Sample> sample = simulator.next()) {
    if (const auto* imu = std::get_if<ImuSample>(&*sample)) {
      top_turn_rate = std::max(top_turn_rate, std::abs(imu->angular_rate_rad_s.z()));
      if (!first) {
        const double dt = secondsBetween(previous_stamp, imu->stamp);
        top_speed = std::max(
            top_speed, (simulator.truePose().translation() - previous.translation()).norm() / dt);
      }
      previous = simulator.truePose();
      previous_stamp = imu->stamp;
      first = false;
    }
  }
  EXPECT_LE(top_speed, 0.3 + 1e-9);
  EXPECT_GT(top_speed, 0.29);
  EXPECT_LE(top_turn_rate, 0.8 + 1e-9);
  EXPECT_GT(top_turn_rate, 0.79);
}

// World cells (0.1 m) of the noise-free laser hits of one robot's default 60 s run.
std::set<std::pair<int, int>> wallCellsSeen(int robot) {
  std::set<std::pair<int, int>> cells;
  for (const Sample& sample : runAll(settingsFor(robot, 60.0, false))) {
    const auto* scan = std::get_if<LaserScan>(&sample);
    if (scan == nullptr) {
      continue;
    }
    for (std::size_t i = 0; i < scan->ranges_m.size(); ++i) {
      if (std::isfinite(scan->ranges_m[i])) {
        const double angle = scan->logged_pose->theta() + scan->beamAngle(i);
        const Eigen::Vector2d hit =
            scan->logged_pose->translation() +
            scan->ranges_m[i] * Eigen::Vector2d(std::cos(angle), std::sin(angle));
        cells.emplace(static_cast<int>(std::floor(hit.x() / 0.1)),
                      static_cast<int>(std::floor(hit.y() / 0.1)));
      }
    }
  }
  return cells;
}

TEST(SimulatorTest, EveryPairOfRoutesOverlapsAndEachSeesSomethingOfItsOwn) {
  std::vector<std::set<std::pair<int, int>>> seen;
  for (int robot = 0; robot < kBuiltInRouteCount; ++robot) {
    seen.push_back(wallCellsSeen(robot));
    EXPECT_GT(seen.back().size(), 400u) << robot;
  }
  for (int a = 0; a < kBuiltInRouteCount; ++a) {
    std::size_t own = 0;
    for (const auto& cell : seen[a]) {
      bool elsewhere = false;
      for (int b = 0; b < kBuiltInRouteCount; ++b) {
        elsewhere = elsewhere || (b != a && seen[b].count(cell) > 0);
      }
      own += elsewhere ? 0 : 1;
    }
    EXPECT_GT(own, seen[a].size() / 10) << "robot " << a << " sees little of its own";
    for (int b = a + 1; b < kBuiltInRouteCount; ++b) {
      std::size_t common = 0;
      for (const auto& cell : seen[a]) {
        common += seen[b].count(cell);
      }
      EXPECT_GT(common, std::min(seen[a].size(), seen[b].size()) / 4)
          << "robots " << a << " and " << b << " share little";
    }
  }
}

TEST(SimulatorSettingsTest, LoadsEveryKeyOfTheSimulatorSection) {
  const Config config = Config::loadString(
      "simulator:\n"
      "  robot_index: 2\n  seed: 42\n  duration_s: 12.5\n  start_time_s: 100\n"
      "  noise_enabled: false\n  max_speed_m_s: 0.3\n  max_turn_rate_rad_s: 0.7\n"
      "  max_acceleration_m_s2: 0.4\n  max_angular_acceleration_rad_s2: 2\n"
      "  laser_rate_hz: 5\n  laser_range_sigma_m: 0.02\n  encoder_rate_hz: 40\n"
      "  encoder_scale_sigma: 0.004\n  encoder_slip_sigma: 0.05\n  imu_rate_hz: 100\n"
      "  imu_yaw_sigma_rad: 0.03\n  imu_rate_sigma_rad_s: 0.006\n  imu_rate_bias_rad_s: -0.01\n"
      "  imu_tilt_sigma_rad: 0.004\n  imu_acceleration_sigma_g: 0.02\n",
      "sim.yaml");
  const SimulatorSettings s = loadSimulatorSettings(config.section("simulator"));
  EXPECT_NO_THROW(config.checkNoUnknownKeys());
  EXPECT_EQ(s.robot_index, 2);
  EXPECT_EQ(s.seed, 42u);
  EXPECT_EQ(s.duration_s, 12.5);
  EXPECT_EQ(s.start_time_s, 100.0);
  EXPECT_FALSE(s.noise_enabled);
  EXPECT_EQ(s.max_speed_m_s, 0.3);
  EXPECT_EQ(s.max_turn_rate_rad_s, 0.7);
  EXPECT_EQ(s.max_acceleration_m_s2, 0.4);
  EXPECT_EQ(s.max_angular_acceleration_rad_s2, 2.0);
  EXPECT_EQ(s.laser_rate_hz, 5.0);
  EXPECT_EQ(s.laser_range_sigma_m, 0.02);
  EXPECT_EQ(s.encoder_rate_hz, 40.0);
  EXPECT_EQ(s.encoder_scale_sigma, 0.004);
  EXPECT_EQ(s.encoder_slip_sigma, 0.05);
  EXPECT_EQ(s.imu_rate_hz, 100.0);
  EXPECT_EQ(s.imu_yaw_sigma_rad, 0.03);
  EXPECT_EQ(s.imu_rate_sigma_rad_s, 0.006);
  EXPECT_EQ(s.imu_rate_bias_rad_s, -0.01);
  EXPECT_EQ(s.imu_tilt_sigma_rad, 0.004);
  EXPECT_EQ(s.imu_acceleration_sigma_g, 0.02);
}

TEST(SimulatorSettingsTest, AnAbsentSectionGivesTheDefaults) {
  const SimulatorSettings s =
      loadSimulatorSettings(Config::loadString("other: 1\n", "sim.yaml").section("simulator"));
  const SimulatorSettings defaults;
  EXPECT_EQ(s.robot_index, defaults.robot_index);
  EXPECT_EQ(s.seed, defaults.seed);
  EXPECT_EQ(s.duration_s, 60.0);
  EXPECT_EQ(s.laser_rate_hz, 10.0);
  EXPECT_EQ(s.encoder_rate_hz, 50.0);
  EXPECT_EQ(s.imu_rate_hz, 50.0);
  EXPECT_EQ(s.laser_range_sigma_m, 0.01);
  EXPECT_TRUE(s.noise_enabled);
}

TEST(SimulatorSettingsTest, BadValuesNameFileLineAndKey) {
  EXPECT_EQ(configErrorOf("simulator:\n  seed: 3\n  robot_index: 3\n"),
            "sim.yaml:3: simulator.robot_index: 3 is out of range: must be in [0, 2]");
  EXPECT_THAT(configErrorOf("simulator:\n  duration_s: -5\n"),
              StartsWith("sim.yaml:2: simulator.duration_s: -5 is out of range"));
  EXPECT_THAT(configErrorOf("simulator:\n  laser_rate_hz: 0\n"),
              StartsWith("sim.yaml:2: simulator.laser_rate_hz: 0 is out of range"));
  EXPECT_THAT(configErrorOf("simulator:\n  seed: -1\n"),
              StartsWith("sim.yaml:2: simulator.seed: -1 is out of range"));
  EXPECT_EQ(configErrorOf("simulator:\n  robot_index: 1.5\n"),
            "sim.yaml:2: simulator.robot_index: must be an integer, not '1.5'");
  EXPECT_EQ(configErrorOf("simulator:\n  noise_enabled: sometimes\n"),
            "sim.yaml:2: simulator.noise_enabled: must be true or false");
  EXPECT_THAT(configErrorOf("simulator:\n  encoder_slip_sigma: -0.1\n"),
              StartsWith("sim.yaml:2: simulator.encoder_slip_sigma: -0.1 is out of range"));
}

TEST(SimulatorSettingsTest, TheConstructorRejectsBadSettingsMadeInCode) {
  const auto make = [](const SimulatorSettings& settings, const DiffDriveParams& drive) {
    Simulator simulator(settings, drive, SensorMounting{});
  };
  SimulatorSettings settings;
  settings.robot_index = 3;
  EXPECT_THROW(make(settings, DiffDriveParams{}), std::invalid_argument);
  settings = SimulatorSettings{};
  settings.duration_s = -1.0;
  EXPECT_THROW(make(settings, DiffDriveParams{}), std::invalid_argument);
  settings = SimulatorSettings{};
  settings.imu_rate_hz = std::nan("");
  EXPECT_THROW(make(settings, DiffDriveParams{}), std::invalid_argument);
  DiffDriveParams drive;
  drive.ticks_per_revolution = 0.0;
  EXPECT_THROW(make(SimulatorSettings{}, drive), std::invalid_argument);
  EXPECT_NO_THROW(make(SimulatorSettings{}, DiffDriveParams{}));
}

}  // namespace
}  // namespace mrslam::drivers
