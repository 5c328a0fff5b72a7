#include "mrslam/robot/odometry_queue.hpp"

#include <gtest/gtest.h>

namespace mrslam::robot {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

OdometryReading wheels(std::int64_t t_ns, double left, double right) {
  return {Stamp{t_ns}, WheelTravel{left, right}};
}

TEST(OdometryQueueTest, ReleasesEveryReadingUpToNowInArrivalOrder) {
  OdometryQueue queue(0.5, MotionNoise{});
  queue.push(wheels(0, 0.0, 0.0));
  queue.push(wheels(kSecond, 1.0, 1.0));
  queue.push(wheels(kSecond, 2.0, 2.0));  // repeated stamp: still an increment
  const auto increments = queue.releaseUpTo(Stamp{kSecond});
  ASSERT_EQ(increments.size(), 2u);
  EXPECT_NEAR(increments[0].T_before_after.x(), 1.0, 1e-12);
  EXPECT_NEAR(increments[1].T_before_after.x(), 1.0, 1e-12);
  EXPECT_GT(increments[0].covariance(0, 0), 0.0);
  EXPECT_TRUE(queue.releaseUpTo(Stamp{2 * kSecond}).empty());
}

TEST(OdometryQueueTest, InterpolatesAReadingAtTheReleaseTime) {
  OdometryQueue queue(0.5, MotionNoise{});
  queue.push(wheels(0, 0.0, 0.0));
  queue.push(wheels(kSecond, 1.0, 1.0));
  const auto first = queue.releaseUpTo(Stamp{kSecond / 4});
  ASSERT_EQ(first.size(), 1u);
  EXPECT_NEAR(first[0].T_before_after.x(), 0.25, 1e-12);
  const auto rest = queue.releaseUpTo(Stamp{kSecond});
  ASSERT_EQ(rest.size(), 1u);
  EXPECT_NEAR(rest[0].T_before_after.x(), 0.75, 1e-12);
}

TEST(OdometryQueueTest, OdometryPosesGiveIncrementsInTheRobotFrame) {
  OdometryQueue queue(0.5, MotionNoise{});
  queue.push({Stamp{0}, SE2(3.0, 4.0, M_PI / 2)});
  queue.push({Stamp{kSecond}, SE2(3.0, 5.0, M_PI / 2)});
  const auto increments = queue.releaseUpTo(Stamp{kSecond});
  ASSERT_EQ(increments.size(), 1u);
  EXPECT_NEAR(increments[0].T_before_after.x(), 1.0, 1e-12);
  EXPECT_NEAR(increments[0].T_before_after.y(), 0.0, 1e-12);
  const double sigma = MotionNoise{}.odometry.translation_per_m;
  EXPECT_NEAR(increments[0].covariance(0, 0), sigma * sigma, 1e-12);
}

TEST(OdometryQueueTest, TheTrailDeadReckonsEveryPushedReading) {
  OdometryQueue queue(0.5, MotionNoise{});
  queue.push(wheels(0, 0.0, 0.0));
  queue.push(wheels(kSecond, 1.0, 1.0));
  queue.push(wheels(2 * kSecond, 2.0, 2.0));
  EXPECT_NEAR(queue.trail().latest().x(), 2.0, 1e-12);  // nothing released yet
  EXPECT_NEAR(queue.trail().poseAt(Stamp{kSecond / 2})->x(), 0.5, 1e-12);
}

TEST(OdometryQueueTest, TurnNoiseGrowsWithTheTurn) {
  MotionNoise noise;
  noise.wheel_noise_fraction = 0.0;
  noise.wheel_turn_noise_per_rad = 0.1;
  OdometryQueue queue(0.5, noise);
  queue.push(wheels(0, 0.0, 0.0));
  queue.push(wheels(kSecond, -0.25, 0.25));  // one radian on the spot
  const auto increments = queue.releaseUpTo(Stamp{kSecond});
  ASSERT_EQ(increments.size(), 1u);
  EXPECT_NEAR(increments[0].T_before_after.theta(), 1.0, 1e-12);
  EXPECT_NEAR(increments[0].covariance(2, 2), 0.01, 1e-12);
  EXPECT_NEAR(increments[0].covariance(0, 0), 0.0, 1e-12);
}

}  // namespace
}  // namespace mrslam::robot
