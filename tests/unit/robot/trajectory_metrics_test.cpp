#include "mrslam/robot/trajectory_metrics.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace mrslam::robot {
namespace {

std::vector<SE2> square() {
  return {SE2(0, 0, 0), SE2(1, 0, M_PI / 2), SE2(1, 1, M_PI), SE2(0, 1, -M_PI / 2), SE2(0, 0, 0)};
}

TEST(TrajectoryMetricsTest, IdenticalTrajectoriesHaveNoError) {
  const ErrorStats rpe = relativePoseError(square(), square(), 1);
  EXPECT_EQ(rpe.count, 4u);
  EXPECT_NEAR(rpe.translation_rms_m, 0.0, 1e-12);
  EXPECT_NEAR(rpe.rotation_rms_deg, 0.0, 1e-12);
  EXPECT_NEAR(absoluteTrajectoryError(square(), square()).translation_rms_m, 0.0, 1e-12);
}

TEST(TrajectoryMetricsTest, RelativeErrorIgnoresTheFrameAndSeesOneBadStep) {
  std::vector<SE2> estimate;
  const SE2 elsewhere(10.0, -3.0, 1.0);
  for (const SE2& pose : square()) {
    estimate.push_back(elsewhere * pose);
  }
  EXPECT_NEAR(relativePoseError(estimate, square(), 1).translation_max_m, 0.0, 1e-12);
  // Every pose from the third on shifted by 0.1 m: only the pair (1, 2) is off, by 0.1 m.
  estimate = square();
  for (std::size_t i = 2; i < estimate.size(); ++i) {
    estimate[i] = SE2(0.0, 0.1, 0.0) * estimate[i];
  }
  const ErrorStats rpe = relativePoseError(estimate, square(), 1);
  EXPECT_NEAR(rpe.translation_max_m, 0.1, 1e-12);
  EXPECT_NEAR(rpe.translation_mean_m, 0.1 / 4, 1e-12);
  EXPECT_EQ(relativePoseError(estimate, square(), 2).count, 3u);
}

TEST(TrajectoryMetricsTest, AlignmentRecoversARigidTransform) {
  const SE2 S(2.0, -1.0, 0.7);
  std::vector<SE2> estimate;
  for (const SE2& pose : square()) {
    estimate.push_back(S.inverse() * pose);
  }
  const SE2 found = alignTrajectory(estimate, square());
  EXPECT_NEAR(found.x(), S.x(), 1e-12);
  EXPECT_NEAR(found.y(), S.y(), 1e-12);
  EXPECT_NEAR(found.theta(), S.theta(), 1e-12);
  EXPECT_NEAR(absoluteTrajectoryError(estimate, square()).translation_max_m, 0.0, 1e-12);
  EXPECT_NEAR(absoluteTrajectoryError(estimate, square()).rotation_max_deg, 0.0, 1e-9);
}

TEST(TrajectoryMetricsTest, NeesWeighsTheErrorByTheCovariance) {
  const Eigen::Matrix3d P = Eigen::Vector3d(0.01, 0.04, 0.0001).asDiagonal();
  EXPECT_NEAR(nees(SE2(0.1, 0.2, 0.01), P, SE2()), 1.0 + 1.0 + 1.0, 1e-9);
  EXPECT_NEAR(nees(SE2(0, 0, M_PI - 0.005), P, SE2(0, 0, -M_PI + 0.005)), 1.0, 1e-9);
}

TEST(TrajectoryMetricsTest, LengthsMustAgree) {
  EXPECT_THROW(relativePoseError(square(), {SE2()}, 1), std::invalid_argument);
  EXPECT_THROW(absoluteTrajectoryError(square(), {SE2()}), std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::robot
