#include "mrslam/robot/odometry_estimator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

namespace mrslam::robot {
namespace {

constexpr double kTolerance = 1e-9;

TEST(DiffDriveIncrementTest, StraightLine) {
  const SE2 increment = diffDriveIncrement(0.5, 0.5, 0.3);
  EXPECT_NEAR(increment.x(), 0.5, kTolerance);
  EXPECT_NEAR(increment.y(), 0.0, kTolerance);
  EXPECT_NEAR(increment.theta(), 0.0, kTolerance);
}

TEST(DiffDriveIncrementTest, TurnOnTheSpot) {
  // Wheels 0.3 m apart roll ±0.15·π/2: a quarter turn counter-clockwise.
  const double arc = 0.15 * M_PI / 2;
  const SE2 increment = diffDriveIncrement(-arc, arc, 0.3);
  EXPECT_NEAR(increment.x(), 0.0, kTolerance);
  EXPECT_NEAR(increment.y(), 0.0, kTolerance);
  EXPECT_NEAR(increment.theta(), M_PI / 2, kTolerance);
}

TEST(DiffDriveIncrementTest, QuarterCircleArc) {
  // Centre of the robot on a circle of radius 1 m: after a quarter turn it is at (1, 1).
  const double track = 0.4;
  const double left = (1.0 - track / 2) * M_PI / 2;
  const double right = (1.0 + track / 2) * M_PI / 2;
  const SE2 increment = diffDriveIncrement(left, right, track);
  EXPECT_NEAR(increment.x(), 1.0, 1e-12);
  EXPECT_NEAR(increment.y(), 1.0, 1e-12);
  EXPECT_NEAR(increment.theta(), M_PI / 2, 1e-12);
}

TEST(OdometryEstimatorTest, WheelTicksDriveTheRobotAndGrowTheCovariance) {
  DiffDriveParams platform;
  platform.wheel_radius_m = 0.1;
  platform.track_width_m = 0.5;
  platform.ticks_per_revolution = 1000;
  OdometryEstimator estimator(platform, OdometryNoise{});
  estimator.addWheelTicks({Stamp{0}, 500, 700});  // first reading only sets the reference
  EXPECT_NEAR(estimator.pose().x(), 0.0, kTolerance);
  // One full wheel turn each: 2π·0.1 m straight ahead.
  estimator.addWheelTicks({Stamp{1}, 1500, 1700});
  EXPECT_NEAR(estimator.pose().x(), 2 * M_PI * 0.1, 1e-12);
  EXPECT_NEAR(estimator.pose().y(), 0.0, 1e-12);
  const Eigen::Matrix3d after_straight = estimator.covariance();
  EXPECT_GT(after_straight(0, 0), 0.0);
  // Then a turn on the spot by +90°: ticks for an arc of (0.25·π/2) m per wheel.
  const double ticks = 0.25 * M_PI / 2 / (2 * M_PI * 0.1) * 1000;
  estimator.addWheelTicks({Stamp{2}, 1500 - static_cast<std::int64_t>(std::lround(ticks)),
                           1700 + static_cast<std::int64_t>(std::lround(ticks))});
  EXPECT_NEAR(estimator.pose().theta(), M_PI / 2, 2e-3);
  EXPECT_GT(estimator.covariance()(2, 2), after_straight(2, 2));
}

TEST(OdometryEstimatorTest, OdometryPosesAreUsedAsIncrementsFromTheFirstOne) {
  OdometryEstimator estimator(DiffDriveParams{}, OdometryNoise{});
  estimator.addOdometry({Stamp{0}, SE2(10.0, 5.0, M_PI / 2)});
  EXPECT_NEAR(estimator.pose().x(), 0.0, kTolerance);
  // One metre "north" in the odometry frame is one metre straight ahead for the robot.
  estimator.addOdometry({Stamp{1}, SE2(10.0, 6.0, M_PI / 2)});
  EXPECT_NEAR(estimator.pose().x(), 1.0, kTolerance);
  EXPECT_NEAR(estimator.pose().y(), 0.0, kTolerance);
  EXPECT_NEAR(estimator.pose().theta(), 0.0, kTolerance);
}

TEST(OdometryEstimatorTest, CovarianceStaysSymmetricAndPositive) {
  OdometryEstimator estimator(DiffDriveParams{}, OdometryNoise{});
  for (int i = 0; i <= 200; ++i) {
    estimator.addOdometry({Stamp{i}, SE2(0.05 * i, 0.02 * i * std::sin(0.1 * i), 0.03 * i)});
  }
  const Eigen::Matrix3d covariance = estimator.covariance();
  EXPECT_NEAR((covariance - covariance.transpose()).norm(), 0.0, 1e-12);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(covariance);
  EXPECT_GT(solver.eigenvalues().minCoeff(), 0.0);
}

}  // namespace
}  // namespace mrslam::robot
