#include "mrslam/drivers/odometry_noise.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <stdexcept>

namespace mrslam::drivers {
namespace {

// Hands out a fixed list of samples.
class ListSource final : public SampleSource {
 public:
  explicit ListSource(std::vector<Sample> samples) : samples_(samples.begin(), samples.end()) {}
  std::optional<Sample> next() override {
    if (samples_.empty()) {
      return std::nullopt;
    }
    Sample sample = samples_.front();
    samples_.pop_front();
    return sample;
  }
  std::string describe() const override { return "list"; }
  SourceCounters counters() const override { return {}; }

 private:
  std::deque<Sample> samples_;
};

// A straight drive along x in 0.5 m steps, each pose followed by a scan.
std::vector<Sample> straightDrive(int steps) {
  std::vector<Sample> samples;
  for (int i = 0; i <= steps; ++i) {
    samples.emplace_back(OdometryPose{Stamp{i}, SE2(10.0 + 0.5 * i, 5.0, 0.0)});
    LaserScan scan;
    scan.stamp = Stamp{i};
    scan.logged_pose = SE2(0.5 * i, 0.0, 0.0);
    samples.emplace_back(scan);
  }
  return samples;
}

std::vector<SE2> noisyPoses(const OdometryNoiseSettings& settings, int steps) {
  OdometryNoiseSource source(std::make_unique<ListSource>(straightDrive(steps)), settings);
  std::vector<SE2> poses;
  while (auto sample = source.next()) {
    if (const auto* odometry = std::get_if<OdometryPose>(&*sample)) {
      poses.push_back(odometry->T_odom_robot);
    } else {
      const auto& scan = std::get<LaserScan>(*sample);
      EXPECT_NEAR(scan.logged_pose->x(), 0.5 * scan.stamp.ns, 1e-12) << "scans pass unchanged";
    }
  }
  return poses;
}

TEST(OdometryNoiseTest, ParsesFractionAndDegreesPerMetre) {
  const OdometryNoiseSettings settings = parseOdometryNoise("0.1,2");
  EXPECT_DOUBLE_EQ(settings.distance_fraction, 0.1);
  EXPECT_DOUBLE_EQ(settings.deg_per_m, 2.0);
  EXPECT_TRUE(settings.enabled());
  EXPECT_FALSE(parseOdometryNoise("0,0").enabled());
  for (const char* bad : {"0.1", "0.1,2,3", "a,2", "0.1,-2", "", "0.1,2x"}) {
    EXPECT_THROW(parseOdometryNoise(bad), std::invalid_argument) << bad;
  }
}

TEST(OdometryNoiseTest, TheFirstPoseIsKeptAndTheRestDrift) {
  OdometryNoiseSettings settings;
  settings.distance_fraction = 0.1;
  settings.deg_per_m = 2.0;
  const std::vector<SE2> poses = noisyPoses(settings, 20);
  ASSERT_EQ(poses.size(), 21u);
  EXPECT_EQ(poses[0].x(), 10.0);
  EXPECT_EQ(poses[0].y(), 5.0);
  double drift = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    drift += std::abs(poses[i].y() - 5.0);
  }
  EXPECT_GT(drift, 0.0);
}

TEST(OdometryNoiseTest, SameSeedSameNoiseOtherSeedOtherNoise) {
  OdometryNoiseSettings settings;
  settings.distance_fraction = 0.1;
  settings.deg_per_m = 2.0;
  settings.seed = 7;
  const std::vector<SE2> a = noisyPoses(settings, 10);
  const std::vector<SE2> b = noisyPoses(settings, 10);
  settings.seed = 8;
  const std::vector<SE2> c = noisyPoses(settings, 10);
  EXPECT_EQ(a.back().x(), b.back().x());
  EXPECT_EQ(a.back().theta(), b.back().theta());
  EXPECT_NE(a.back().x(), c.back().x());
}

TEST(OdometryNoiseTest, IncrementNoiseHasTheConfiguredSpread) {
  // 0.5 m steps: σ of x and y 0.05 m, σ of the turn 2°/m · 0.5 m = 1°.
  OdometryNoiseSettings settings;
  settings.distance_fraction = 0.1;
  settings.deg_per_m = 2.0;
  const std::vector<SE2> poses = noisyPoses(settings, 4000);
  double sum_x = 0.0;
  double sum_y = 0.0;
  double sum_theta = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    const SE2 increment = poses[i - 1].inverse() * poses[i];
    sum_x += std::pow(increment.x() - 0.5, 2);
    sum_y += std::pow(increment.y(), 2);
    sum_theta += std::pow(increment.theta(), 2);
  }
  const double n = static_cast<double>(poses.size() - 1);
  EXPECT_NEAR(std::sqrt(sum_x / n), 0.05, 0.003);
  EXPECT_NEAR(std::sqrt(sum_y / n), 0.05, 0.003);
  EXPECT_NEAR(std::sqrt(sum_theta / n), M_PI / 180.0, 0.06 * M_PI / 180.0);
}

TEST(OdometryNoiseTest, DescribesItselfAndRejectsBadSetUps) {
  OdometryNoiseSettings settings;
  settings.distance_fraction = 0.1;
  OdometryNoiseSource source(std::make_unique<ListSource>(std::vector<Sample>{}), settings);
  EXPECT_NE(source.describe().find("odometry noise 0.1,0"), std::string::npos);
  EXPECT_FALSE(source.next().has_value());
  EXPECT_THROW(OdometryNoiseSource(nullptr, settings), std::invalid_argument);
  settings.deg_per_m = -1.0;
  EXPECT_THROW(OdometryNoiseSource(std::make_unique<ListSource>(std::vector<Sample>{}), settings),
               std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::drivers
