#include "mrslam/robot/odometry_trail.hpp"

#include <gtest/gtest.h>

namespace mrslam::robot {
namespace {

TEST(OdometryTrailTest, InterpolatesBetweenStampsAndClampsOutside) {
  OdometryTrail trail;
  EXPECT_FALSE(trail.poseAt(Stamp{0}).has_value());
  trail.add(Stamp{1'000'000'000}, SE2(0.0, 0.0, 0.0));
  trail.add(Stamp{2'000'000'000}, SE2(1.0, 2.0, 0.4));
  const SE2 middle = *trail.poseAt(Stamp{1'250'000'000});
  EXPECT_NEAR(middle.x(), 0.25, 1e-12);
  EXPECT_NEAR(middle.y(), 0.5, 1e-12);
  EXPECT_NEAR(middle.theta(), 0.1, 1e-12);
  EXPECT_EQ(trail.poseAt(Stamp{0})->x(), 0.0);
  EXPECT_EQ(trail.poseAt(Stamp{5'000'000'000})->x(), 1.0);
  EXPECT_EQ(trail.latest().y(), 2.0);
}

TEST(OdometryTrailTest, InterpolatesAnglesAcrossTheWrap) {
  OdometryTrail trail;
  trail.add(Stamp{0}, SE2(0.0, 0.0, M_PI - 0.1));
  trail.add(Stamp{100}, SE2(0.0, 0.0, -M_PI + 0.1));
  EXPECT_NEAR(std::abs(trail.poseAt(Stamp{50})->theta()), M_PI, 1e-9);
}

TEST(OdometryTrailTest, ForgetsOldPosesAndKeepsArrivalOrder) {
  OdometryTrail trail(1.0);
  for (int i = 0; i <= 30; ++i) {
    trail.add(Stamp{i * 100'000'000LL}, SE2(0.1 * i, 0.0, 0.0));
  }
  EXPECT_NEAR(trail.poseAt(Stamp{0})->x(), 1.9, 1e-9);  // older than the span: the oldest kept
  trail.add(Stamp{0}, SE2(5.0, 0.0, 0.0));              // a stamp going back counts as the newest
  EXPECT_EQ(trail.latest().x(), 5.0);
  EXPECT_EQ(trail.poseAt(Stamp{3'000'000'000LL})->x(), 5.0);
}

}  // namespace
}  // namespace mrslam::robot
