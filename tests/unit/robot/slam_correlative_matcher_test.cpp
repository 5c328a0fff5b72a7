#include "mrslam/robot/slam/correlative_matcher.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "slam_matcher_cases.hpp"
#include "test_data.hpp"

namespace mrslam::robot::slam {
namespace {

using test::SyntheticRoom;

constexpr double kDegree = M_PI / 180.0;

/// Expects `pose` within one cell (per axis) and one angular step of `expected`.
void expectNear(const SE2& pose, const SE2& expected, double cell_m, double step_rad) {
  EXPECT_LE(std::abs(pose.x() - expected.x()), cell_m);
  EXPECT_LE(std::abs(pose.y() - expected.y()), cell_m);
  EXPECT_LE(std::abs(wrapAngle(pose.theta() - expected.theta())), step_rad);
}

/// Mean of probability(cell, p_min) over the cells of T_submap_robot · points.
double meanProbability(const ProbabilityGrid& grid, const SE2& T_submap_robot,
                       const std::vector<Eigen::Vector2d>& points_robot) {
  const auto p_min = static_cast<float>(grid.settings().min_probability);
  double sum = 0.0;
  for (const Eigen::Vector2d& point : points_robot) {
    sum += grid.probability(grid.cellOf(T_submap_robot * point), p_min);
  }
  return sum / static_cast<double>(points_robot.size());
}

// ---------------------------------------------------------------------------------------------
// The search discretisation

TEST(CorrelativeMatcherTest, AngularStepFollowsTheFarthestPoint) {
  const std::vector<Eigen::Vector2d> points = {{1.0, 0.0}, {0.0, -10.0}, {3.0, 4.0}};
  EXPECT_DOUBLE_EQ(angularSearchStep(0.05, points), std::acos(1.0 - 0.0025 / 200.0));
  EXPECT_NEAR(angularSearchStep(0.05, points), 0.005, 1e-5);  // ≈ r / d_max
  EXPECT_DOUBLE_EQ(angularSearchStep(0.05, {}), M_PI);
  EXPECT_DOUBLE_EQ(angularSearchStep(0.05, {{0.02, 0.0}}), M_PI);
}

TEST(CorrelativeMatcherTest, RotationOffsetsCoverTheWindow) {
  const std::vector<double> window = rotationOffsets(0.35, 0.1);
  ASSERT_EQ(window.size(), 9u);  // ⌈0.35 / 0.1⌉ = 4 each side
  EXPECT_DOUBLE_EQ(window.front(), -0.4);
  EXPECT_DOUBLE_EQ(window[4], 0.0);
  EXPECT_DOUBLE_EQ(window.back(), 0.4);
  EXPECT_EQ(rotationOffsets(0.3, 0.1).size(), 7u);  // a whole number of steps stays so
  EXPECT_EQ(rotationOffsets(0.0, 0.1).size(), 1u);

  for (const double step : {0.1, 0.0025, 2.0 * M_PI / 7.0}) {
    const std::vector<double> circle = rotationOffsets(M_PI, step);
    const auto n = static_cast<std::size_t>(std::ceil(2.0 * M_PI / step - 1e-9));
    ASSERT_EQ(circle.size(), n);
    EXPECT_GT(circle.front(), -M_PI);
    EXPECT_LE(circle.back(), M_PI + 1e-12);
    for (std::size_t i = 1; i < circle.size(); ++i) {
      EXPECT_NEAR(circle[i] - circle[i - 1], 2.0 * M_PI / static_cast<double>(n), 1e-12);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// Matching

TEST(CorrelativeMatcherTest, RecoversSyntheticOffset) {
  std::mt19937 random(42);
  std::uniform_real_distribution<double> offset_m(-0.1, 0.1);
  std::uniform_real_distribution<double> offset_rad(-15.0 * kDegree, 15.0 * kDegree);
  CorrelativeMatcherSettings settings;
  settings.linear_search_window_m = 0.3;
  const CorrelativeMatcher matcher(settings);
  for (int i = 0; i < 10; ++i) {
    const SyntheticRoom room = test::syntheticRoom(random);
    const SE2 guess(room.T_submap_robot.x() + offset_m(random),
                    room.T_submap_robot.y() + offset_m(random),
                    room.T_submap_robot.theta() + offset_rad(random));
    const std::optional<CorrelativeMatch> found = matcher.match(room.grid, guess, room.scan_robot);
    ASSERT_TRUE(found);
    SCOPED_TRACE(testing::Message() << "room " << i);
    // Within two angular steps: in these rooms a few metres across the score is flat over a
    // step's width, so the best candidate can be the one beside the truth's.
    expectNear(found->T_submap_robot, room.T_submap_robot, room.grid.resolution(),
               2.0 * angularSearchStep(room.grid.resolution(), room.scan_robot));
  }
}

TEST(CorrelativeMatcherTest, ScoreIsTheMeanProbabilityWeightedByThePrior) {
  std::mt19937 random(42);
  const SyntheticRoom room = test::syntheticRoom(random);
  const CorrelativeMatcherSettings settings;
  const CorrelativeMatcher matcher(settings);
  const SE2 guess = room.T_submap_robot * SE2(0.04, -0.03, 2.0 * kDegree);
  const std::optional<CorrelativeMatch> found = matcher.match(room.grid, guess, room.scan_robot);
  ASSERT_TRUE(found);
  EXPECT_NEAR(found->score, meanProbability(room.grid, found->T_submap_robot, room.scan_robot),
              1e-6);
  const double dt = (found->T_submap_robot.translation() - guess.translation()).norm();
  const double dtheta = std::abs(wrapAngle(found->T_submap_robot.theta() - guess.theta()));
  EXPECT_NEAR(found->weighted_score,
              found->score * std::exp(-(settings.translation_delta_cost_weight * dt +
                                        settings.rotation_delta_cost_weight * dtheta)),
              1e-9);
  EXPECT_GE(found->weighted_score, meanProbability(room.grid, guess, room.scan_robot) - 1e-6);
}

TEST(CorrelativeMatcherTest, PrefersTheGuessWhereNothingIsKnown) {
  const ProbabilityGrid empty{ProbabilityGridSettings{}};
  const CorrelativeMatcher matcher{CorrelativeMatcherSettings{}};
  const SE2 guess(1.0, 2.0, 0.5);
  const std::optional<CorrelativeMatch> found =
      matcher.match(empty, guess, {{1.0, 0.0}, {0.0, 3.0}});
  ASSERT_TRUE(found);
  EXPECT_NEAR(found->T_submap_robot.x(), guess.x(), 1e-12);
  EXPECT_NEAR(found->T_submap_robot.y(), guess.y(), 1e-12);
  EXPECT_NEAR(found->T_submap_robot.theta(), guess.theta(), 1e-12);
  EXPECT_FLOAT_EQ(found->score, empty.settings().min_probability);  // stored as float
  EXPECT_DOUBLE_EQ(found->weighted_score, found->score);
}

TEST(CorrelativeMatcherTest, RecoversOffsetOnIntelSubmap) {
  MRSLAM_REQUIRE_SHARED_DATA(test::kIntelLog);
  const std::vector<LaserScan> scans =
      test::carmenScans(::mrslam::test::sharedDataPath(test::kIntelLog), 30);
  ASSERT_EQ(scans.size(), 30u);
  const ProbabilityGrid grid = test::submapOf(scans);
  const CorrelativeMatcher matcher{CorrelativeMatcherSettings{}};
  for (const std::size_t index : {5u, 15u, 25u}) {
    SCOPED_TRACE(testing::Message() << "scan " << index);
    const SE2& T_submap_laser = *scans[index].logged_pose;
    const std::vector<Eigen::Vector2d> points = test::hitsOf(scans[index]);
    const SE2 guess(T_submap_laser.x() + 0.05, T_submap_laser.y() - 0.04,
                    T_submap_laser.theta() + 3.0 * kDegree);
    const std::optional<CorrelativeMatch> found = matcher.match(grid, guess, points);
    ASSERT_TRUE(found);
    expectNear(found->T_submap_robot, T_submap_laser, grid.resolution(),
               angularSearchStep(grid.resolution(), points));
  }
}

// ---------------------------------------------------------------------------------------------
// Edge cases

TEST(CorrelativeMatcherTest, NoPointsGiveNothing) {
  std::mt19937 random(42);
  const SyntheticRoom room = test::syntheticRoom(random);
  const CorrelativeMatcher matcher{CorrelativeMatcherSettings{}};
  EXPECT_FALSE(matcher.match(room.grid, room.T_submap_robot, {}));
}

TEST(CorrelativeMatcherTest, GuessFarOutsideTheGridScoresMinProbability) {
  std::mt19937 random(42);
  const SyntheticRoom room = test::syntheticRoom(random);
  const CorrelativeMatcher matcher{CorrelativeMatcherSettings{}};
  for (const SE2& guess : {SE2(100.0, -50.0, 0.3), SE2(1e12, 1e12, 0.0), SE2(-1e15, 3e14, 2.0)}) {
    const std::optional<CorrelativeMatch> found = matcher.match(room.grid, guess, room.scan_robot);
    ASSERT_TRUE(found);
    EXPECT_FLOAT_EQ(found->score, room.grid.settings().min_probability);  // stored as float
  }
}

TEST(CorrelativeMatcherTest, RejectsBadSettings) {
  CorrelativeMatcherSettings negative_window;
  negative_window.linear_search_window_m = -0.1;
  EXPECT_THROW(CorrelativeMatcher{negative_window}, std::invalid_argument);
  CorrelativeMatcherSettings infinite_window;
  infinite_window.angular_search_window_rad = INFINITY;
  EXPECT_THROW(CorrelativeMatcher{infinite_window}, std::invalid_argument);
  CorrelativeMatcherSettings negative_weight;
  negative_weight.rotation_delta_cost_weight = -1.0;
  EXPECT_THROW(CorrelativeMatcher{negative_weight}, std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::robot::slam
