// The simulator's sensors against the ground truth it reports.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "mrslam/drivers/simulator.hpp"

namespace mrslam::drivers {
namespace {

SimulatorSettings settingsFor(int robot, double duration_s, bool noise) {
  SimulatorSettings settings;
  settings.robot_index = robot;
  settings.duration_s = duration_s;
  settings.noise_enabled = noise;
  return settings;
}

std::vector<Sample> runAll(const SimulatorSettings& settings, const SensorMounting& mounting = {},
                           const DiffDriveParams& drive = {}) {
  Simulator simulator(settings, drive, mounting);
  std::vector<Sample> samples;
  while (std::optional<Sample> sample = simulator.next()) {
    samples.push_back(std::move(*sample));
  }
  return samples;
}

template <typename T>
std::vector<T> only(const std::vector<Sample>& samples) {
  std::vector<T> picked;
  for (const Sample& sample : samples) {
    if (const T* value = std::get_if<T>(&sample)) {
      picked.push_back(*value);
    }
  }
  return picked;
}

struct MeanAndSigma {
  double mean = 0.0;
  double sigma = 0.0;
};

MeanAndSigma statistics(const std::vector<double>& values) {
  MeanAndSigma result;
  for (double value : values) {
    result.mean += value;
  }
  result.mean /= static_cast<double>(values.size());
  for (double value : values) {
    result.sigma += (value - result.mean) * (value - result.mean);
  }
  result.sigma = std::sqrt(result.sigma / static_cast<double>(values.size() - 1));
  return result;
}

SensorMounting offsetLaser() {
  SensorMounting mounting;
  mounting.T_robot_laser = SE2(0.145, 0.02, 0.05);
  return mounting;
}

TEST(SimulatorLaserTest, GeometryIsTheHokuyoOfTheSeedPaper) {
  const std::vector<LaserScan> scans = only<LaserScan>(runAll(settingsFor(0, 1.0, true)));
  ASSERT_EQ(scans.size(), 10u);
  for (const LaserScan& scan : scans) {
    ASSERT_EQ(scan.ranges_m.size(), 513u);
    EXPECT_NEAR(scan.angle_increment_rad, 0.36 * M_PI / 180.0, 1e-15);
    EXPECT_NEAR(scan.angle_min_rad, -256 * 0.36 * M_PI / 180.0, 1e-15);
    EXPECT_NEAR(scan.beamAngle(256), 0.0, 1e-15);  // centred on the laser's x axis
    EXPECT_NEAR(scan.beamAngle(512), 256 * 0.36 * M_PI / 180.0, 1e-14);
    EXPECT_EQ(scan.range_min_m, 0.02);
    EXPECT_EQ(scan.range_max_m, 4.5);
    ASSERT_TRUE(scan.logged_pose.has_value());
  }
}

TEST(SimulatorLaserTest, NoiseFreeRangesEqualRayCastsFromTheTrueLaserPose) {
  const FloorPlan plan = builtInFloorPlan();
  const SensorMounting mounting = offsetLaser();
  int hits = 0;
  int no_returns = 0;
  for (int robot = 0; robot < kBuiltInRouteCount; ++robot) {
    for (const LaserScan& scan :
         only<LaserScan>(runAll(settingsFor(robot, 20.0, false), mounting))) {
      const SE2 T_world_laser = *scan.logged_pose * mounting.T_robot_laser;
      for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
        const std::optional<double> expected = plan.castRay(
            T_world_laser.translation(), T_world_laser.theta() + scan.beamAngle(i), 4.5);
        if (expected) {
          ASSERT_FLOAT_EQ(scan.ranges_m[i], static_cast<float>(*expected)) << robot << " " << i;
          ++hits;
        } else {
          ASSERT_EQ(scan.ranges_m[i], LaserScan::kNoReturn) << robot << " " << i;
          ++no_returns;
        }
      }
    }
  }
  EXPECT_GT(hits, 3 * 200 * 513 / 2);  // most beams see a wall in this building
  EXPECT_GT(no_returns, 1000);         // and some look down the corridor, out of range
}

TEST(SimulatorLaserTest, RangeNoiseHasTheConfiguredSigma) {
  SimulatorSettings settings = settingsFor(1, 30.0, false);
  settings.laser_range_sigma_m = 0.02;
  const std::vector<LaserScan> clean = only<LaserScan>(runAll(settings));
  settings.noise_enabled = true;
  const std::vector<LaserScan> noisy = only<LaserScan>(runAll(settings));
  ASSERT_EQ(clean.size(), noisy.size());
  std::vector<double> errors;
  for (std::size_t k = 0; k < clean.size(); ++k) {
    for (std::size_t i = 0; i < clean[k].ranges_m.size(); ++i) {
      if (std::isfinite(clean[k].ranges_m[i]) && std::isfinite(noisy[k].ranges_m[i])) {
        errors.push_back(double{noisy[k].ranges_m[i]} - double{clean[k].ranges_m[i]});
      }
    }
  }
  ASSERT_GT(errors.size(), 50000u);
  const MeanAndSigma error = statistics(errors);
  EXPECT_NEAR(error.mean, 0.0, 0.0005);
  EXPECT_NEAR(error.sigma, 0.02, 0.001);
}

// Differential-drive dead reckoning from cumulative wheel ticks.
class TickOdometry {
 public:
  TickOdometry(const SE2& start, const DiffDriveParams& drive) : pose_(start), drive_(drive) {}

  void add(const WheelTicks& ticks) {
    if (started_) {
      const double left = drive_.ticksToMetres(static_cast<double>(ticks.left - previous_.left));
      const double right = drive_.ticksToMetres(static_cast<double>(ticks.right - previous_.right));
      const double ds = 0.5 * (left + right);
      const double dtheta = (right - left) / drive_.track_width_m;
      pose_ = pose_ * SE2(ds * std::cos(0.5 * dtheta), ds * std::sin(0.5 * dtheta), dtheta);
      distance_ += std::abs(ds);
    }
    previous_ = ticks;
    started_ = true;
  }
  const SE2& pose() const { return pose_; }
  double distance() const { return distance_; }

 private:
  SE2 pose_;
  DiffDriveParams drive_;
  WheelTicks previous_;
  bool started_ = false;
  double distance_ = 0.0;
};

struct OdometryErrors {
  double largest_position_m = 0.0;
  double largest_heading_rad = 0.0;
  double final_position_m = 0.0;
  double odometry_distance_m = 0.0;
  double true_distance_m = 0.0;
};

// Dead reckoning against the true pose of every scan (ticks at a scan's stamp come before it).
OdometryErrors odometryErrors(const SimulatorSettings& settings, const DiffDriveParams& drive) {
  TickOdometry odometry(builtInStartPose(settings.robot_index), drive);
  OdometryErrors errors;
  std::optional<SE2> previous_truth;
  for (const Sample& sample : runAll(settings, SensorMounting{}, drive)) {
    if (const auto* ticks = std::get_if<WheelTicks>(&sample)) {
      odometry.add(*ticks);
    } else if (const auto* scan = std::get_if<LaserScan>(&sample)) {
      const SE2& truth = *scan->logged_pose;
      const double position = (truth.translation() - odometry.pose().translation()).norm();
      errors.largest_position_m = std::max(errors.largest_position_m, position);
      errors.largest_heading_rad = std::max(
          errors.largest_heading_rad, std::abs(wrapAngle(truth.theta() - odometry.pose().theta())));
      errors.final_position_m = position;
      errors.odometry_distance_m = odometry.distance();
      if (previous_truth) {
        errors.true_distance_m += (truth.translation() - previous_truth->translation()).norm();
      }
      previous_truth = truth;
    }
  }
  return errors;
}

TEST(SimulatorEncoderTest, NoiseFreeTicksReproduceTheTrueTrajectory) {
  DiffDriveParams drive;
  drive.ticks_per_revolution = 2000;  // coarser counts: fractions lost would show at once
  for (int robot = 0; robot < kBuiltInRouteCount; ++robot) {
    const OdometryErrors errors = odometryErrors(settingsFor(robot, 60.0, false), drive);
    EXPECT_LT(errors.largest_position_m, 0.002) << robot;
    EXPECT_LT(errors.largest_heading_rad, 0.002) << robot;
    EXPECT_GT(errors.true_distance_m, 15.0) << robot;
  }
}

TEST(SimulatorEncoderTest, NoisyTicksDriftButStayPlausible) {
  for (int robot = 0; robot < kBuiltInRouteCount; ++robot) {
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      SimulatorSettings settings = settingsFor(robot, 60.0, true);
      settings.seed = seed;
      const OdometryErrors errors = odometryErrors(settings, DiffDriveParams{});
      EXPECT_GT(errors.final_position_m, 0.02) << robot << " " << seed;  // it drifts
      // ... like real wheel odometry: within 15 % of the distance and half a radian of heading,
      // and the distance itself within a few per cent.
      EXPECT_LT(errors.largest_position_m, 0.15 * errors.true_distance_m) << robot << " " << seed;
      EXPECT_LT(errors.largest_heading_rad, 0.5) << robot << " " << seed;
      EXPECT_NEAR(errors.odometry_distance_m / errors.true_distance_m, 1.0, 0.03);
    }
  }
}

TEST(SimulatorImuTest, NoiseFreeReadingsAreTheTrueHeadingTurnRateAndGravity) {
  for (const double yaw_offset : {0.0, 0.1}) {
    SensorMounting mounting;
    mounting.imu_yaw_offset_rad = yaw_offset;
    const std::vector<Sample> samples = runAll(settingsFor(2, 60.0, false), mounting);
    std::optional<ImuSample> previous;
    int compared = 0;
    for (std::size_t k = 0; k < samples.size(); ++k) {
      const auto* imu = std::get_if<ImuSample>(&samples[k]);
      if (imu == nullptr) {
        continue;
      }
      ASSERT_TRUE(imu->has_orientation);
      EXPECT_EQ(imu->roll_rad, 0.0);
      EXPECT_EQ(imu->pitch_rad, 0.0);
      EXPECT_EQ(imu->acceleration_g.z(), 1.0);
      EXPECT_EQ(imu->angular_rate_rad_s.x(), 0.0);
      // Turned back into the robot frame: forward acceleration within the braking limit, sideways
      // the centripetal v·ω within top speed times top turn rate.
      const Eigen::Vector2d robot_g =
          SE2(0.0, 0.0, yaw_offset) * Eigen::Vector2d(imu->acceleration_g.head<2>());
      EXPECT_LE(std::abs(robot_g.x()), 0.5 / 9.80665 + 1e-9);
      EXPECT_LE(std::abs(robot_g.y()), 0.4 * 1.0 / 9.80665 + 1e-9);
      // A scan at the same stamp follows the IMU reading: it carries the true heading.
      if (k + 1 < samples.size() && std::holds_alternative<LaserScan>(samples[k + 1])) {
        const SE2& truth = *std::get<LaserScan>(samples[k + 1]).logged_pose;
        EXPECT_NEAR(imu->yaw_rad, wrapAngle(truth.theta() + yaw_offset), 1e-12);
        ++compared;
      }
      if (previous) {
        // The rate is the turn rate now; the mean over the last 20 ms differs by at most the
        // change one 10 ms command may make (3 rad/s² × 10 ms).
        const double dt = secondsBetween(previous->stamp, imu->stamp);
        const double mean_rate = wrapAngle(imu->yaw_rad - previous->yaw_rad) / dt;
        EXPECT_NEAR(imu->angular_rate_rad_s.z(), mean_rate, 0.03 + 1e-9);
      }
      previous = *imu;
    }
    EXPECT_EQ(compared, 600);
  }
}

TEST(SimulatorImuTest, NoiseHasTheConfiguredSigmasAndBias) {
  SimulatorSettings settings = settingsFor(0, 60.0, false);
  settings.imu_yaw_sigma_rad = 0.02;
  settings.imu_rate_sigma_rad_s = 0.004;
  settings.imu_rate_bias_rad_s = 0.01;
  settings.imu_tilt_sigma_rad = 0.003;
  settings.imu_acceleration_sigma_g = 0.02;
  const std::vector<ImuSample> clean = only<ImuSample>(runAll(settings));
  settings.noise_enabled = true;
  const std::vector<ImuSample> noisy = only<ImuSample>(runAll(settings));
  ASSERT_EQ(clean.size(), 3000u);
  ASSERT_EQ(noisy.size(), clean.size());
  std::vector<double> yaw, rate, roll, acceleration;
  for (std::size_t k = 0; k < clean.size(); ++k) {
    yaw.push_back(wrapAngle(noisy[k].yaw_rad - clean[k].yaw_rad));
    rate.push_back(noisy[k].angular_rate_rad_s.z() - clean[k].angular_rate_rad_s.z());
    roll.push_back(noisy[k].roll_rad);
    acceleration.push_back(noisy[k].acceleration_g.z());
  }
  EXPECT_NEAR(statistics(yaw).mean, 0.0, 0.002);
  EXPECT_NEAR(statistics(yaw).sigma, 0.02, 0.002);
  EXPECT_NEAR(statistics(rate).mean, 0.01, 0.0004);
  EXPECT_NEAR(statistics(rate).sigma, 0.004, 0.0004);
  EXPECT_NEAR(statistics(roll).mean, 0.0, 0.0003);
  EXPECT_NEAR(statistics(roll).sigma, 0.003, 0.0003);
  EXPECT_NEAR(statistics(acceleration).mean, 1.0, 0.002);
  EXPECT_NEAR(statistics(acceleration).sigma, 0.02, 0.002);
}

}  // namespace
}  // namespace mrslam::drivers
