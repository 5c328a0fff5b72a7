#include "mrslam/robot/pose_filter.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

namespace mrslam::robot {
namespace {

using Vector1 = Eigen::Matrix<double, 1, 1>;
using Row = Eigen::Matrix<double, 1, state::kSize>;

Row unitRow(int index) {
  Row H = Row::Zero();
  H(0, index) = 1.0;
  return H;
}

void expectSymmetricPositive(const StateMatrix& P) {
  EXPECT_NEAR((P - P.transpose()).norm(), 0.0, 1e-12);
  const Eigen::SelfAdjointEigenSolver<StateMatrix> solver(P);
  EXPECT_GE(solver.eigenvalues().minCoeff(), -1e-12);
}

TEST(PoseFilterTest, PredictionComposesIncrementsInTheRobotFrame) {
  PoseFilter filter;
  filter.predict(SE2(1.0, 0.0, M_PI / 2), Eigen::Matrix3d::Zero());
  filter.predict(SE2(1.0, 0.0, 0.0), Eigen::Matrix3d::Zero());
  EXPECT_NEAR(filter.pose().x(), 1.0, 1e-12);
  EXPECT_NEAR(filter.pose().y(), 1.0, 1e-12);
  EXPECT_NEAR(filter.pose().theta(), M_PI / 2, 1e-12);
  EXPECT_EQ(filter.poseCovariance(), Eigen::Matrix3d::Zero());
}

TEST(PoseFilterTest, PredictionCovarianceMatchesTheJacobianOfComposition) {
  // After a turn with heading uncertainty, a 2 m drive spreads y by 2 σ_θ.
  PoseFilter filter;
  filter.predict(SE2(0.0, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, 0.01).asDiagonal());
  filter.predict(SE2(2.0, 0.0, 0.0), Eigen::Matrix3d::Zero());
  const Eigen::Matrix3d P = filter.poseCovariance();
  EXPECT_NEAR(P(1, 1), 4.0 * 0.01, 1e-12);
  EXPECT_NEAR(P(1, 2), 2.0 * 0.01, 1e-12);
  EXPECT_NEAR(P(0, 0), 0.0, 1e-12);
}

TEST(PoseFilterTest, ResetAnchorKeepsThePoseAndItsCovariance) {
  PoseFilter filter;
  filter.predict(SE2(1.0, 0.5, 0.3), Eigen::Vector3d(0.01, 0.02, 0.003).asDiagonal());
  filter.resetAnchor();
  filter.predict(SE2(2.0, -0.5, -0.8), Eigen::Vector3d(0.02, 0.01, 0.004).asDiagonal());
  const SE2 pose = filter.pose();
  const Eigen::Matrix3d P = filter.poseCovariance();
  filter.resetAnchor();
  EXPECT_NEAR(filter.pose().x(), pose.x(), 1e-12);
  EXPECT_NEAR(filter.pose().y(), pose.y(), 1e-12);
  EXPECT_NEAR(filter.pose().theta(), pose.theta(), 1e-12);
  EXPECT_NEAR((filter.poseCovariance() - P).norm(), 0.0, 1e-12);
  EXPECT_EQ(filter.relativePose().translation().norm(), 0.0);
  const Eigen::Matrix3d relative = filter.covariance().block<3, 3>(state::kX, state::kX);
  EXPECT_EQ(relative, Eigen::Matrix3d::Zero());
  expectSymmetricPositive(filter.covariance());
}

TEST(PoseFilterTest, CorrectionMovesTowardTheMeasurementByTheVarianceRatio) {
  PoseFilter filter;
  filter.predict(SE2(0.0, 0.0, 0.0), Eigen::Vector3d(0.04, 0.04, 0.01).asDiagonal());
  // z = 0.2 with the same variance as the prior: the posterior is half way, variance halved.
  const Correction c = filter.correct<1>(Vector1(0.2), unitRow(state::kX), Vector1(0.04), 100.0);
  EXPECT_TRUE(c.accepted);
  EXPECT_NEAR(c.mahalanobis_sq, 0.2 * 0.2 / 0.08, 1e-12);
  EXPECT_NEAR(filter.pose().x(), 0.1, 1e-12);
  EXPECT_NEAR(filter.poseCovariance()(0, 0), 0.02, 1e-12);
  expectSymmetricPositive(filter.covariance());
}

TEST(PoseFilterTest, GatedCorrectionChangesNothing) {
  PoseFilter filter;
  filter.predict(SE2(0.0, 0.0, 0.0), Eigen::Vector3d(0.01, 0.01, 0.01).asDiagonal());
  const StateMatrix before = filter.covariance();
  const Correction c = filter.correct<1>(Vector1(5.0), unitRow(state::kX), Vector1(0.01), 9.0);
  EXPECT_FALSE(c.accepted);
  EXPECT_GT(c.mahalanobis_sq, 9.0);
  EXPECT_EQ(filter.pose().x(), 0.0);
  EXPECT_EQ(filter.covariance(), before);
}

TEST(PoseFilterTest, AnglesStayWrappedAfterACorrection) {
  PoseFilter filter;
  filter.predict(SE2(0.0, 0.0, M_PI - 0.01), Eigen::Vector3d(0.0, 0.0, 0.04).asDiagonal());
  filter.correct<1>(Vector1(0.05), unitRow(state::kTheta), Vector1(1e-6), 100.0);
  EXPECT_LE(filter.pose().theta(), M_PI);
  EXPECT_NEAR(filter.pose().theta(), -M_PI + 0.04, 1e-5);
}

TEST(PoseFilterTest, HeadingCloneAndOffsetAreLinearFunctionsOfTheState) {
  PoseFilter filter;
  filter.predict(SE2(0.0, 0.0, 0.2), Eigen::Vector3d(0.0, 0.0, 0.01).asDiagonal());
  filter.resetAnchor();
  filter.predict(SE2(0.0, 0.0, 0.1), Eigen::Vector3d(0.0, 0.0, 0.02).asDiagonal());
  filter.cloneHeading();
  EXPECT_NEAR(filter.state()(state::kImuTheta), 0.3, 1e-12);
  EXPECT_NEAR(filter.covariance()(state::kImuTheta, state::kImuTheta), 0.03, 1e-12);
  filter.initialiseHeadingOffset(1.0, 0.0004);
  EXPECT_NEAR(filter.state()(state::kImuHeadingOffset), 0.7, 1e-12);
  // Var(α) = Var(θ_map) + the reading's; α and θ_map are anti-correlated.
  EXPECT_NEAR(filter.covariance()(state::kImuHeadingOffset, state::kImuHeadingOffset), 0.0304,
              1e-12);
  EXPECT_NEAR(filter.covariance()(state::kImuHeadingOffset, state::kImuTheta), -0.03, 1e-12);
  expectSymmetricPositive(filter.covariance());
}

}  // namespace
}  // namespace mrslam::robot
