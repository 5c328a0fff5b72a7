#include "mrslam/robot/scan_matcher.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "full_turn_scan.hpp"

namespace mrslam::robot {
namespace {

constexpr double kEndWallX = 10.0;  // the corridor's only wall across it

// A laser at the origin of a corridor between the walls y = ±1, closed by a wall at x = 10 ahead
// and open behind: 360 beams over the full turn.
LaserScan corridorScan() {
  return test::fullTurnScan([](double angle) {
    double range = std::numeric_limits<double>::infinity();
    if (std::abs(std::sin(angle)) > 1e-9) {
      range = 1.0 / std::abs(std::sin(angle));
    }
    if (std::cos(angle) > 1e-9) {
      range = std::min(range, kEndWallX / std::cos(angle));
    }
    return range < test::kFullTurnRangeMaxM ? static_cast<float>(range) : LaserScan::kNoReturn;
  });
}

// The measurement of the corridor scan matched against itself from a guess off the truth.
std::optional<ScanMatch> matchCorridor(const ScanMatcherSettings& settings) {
  ScanMatcher matcher(settings, SensorMounting{});
  const PreparedScan scan = matcher.prepare(corridorScan());
  matcher.addKeyframe(scan, SE2());
  return matcher.match(scan, SE2(0.05, 0.02, 0.01));
}

ScanMatcherSettings corridorSettings(double covariance_shape_scale) {
  ScanMatcherSettings settings;
  settings.covariance_shape_scale = covariance_shape_scale;
  settings.min_sigma_xy_m = 0.02;
  return settings;
}

TEST(ScanMatcherTest, CorridorScanIsFoundFromAnOffsetGuess) {
  const std::optional<ScanMatch> match = matchCorridor(corridorSettings(0.3));
  ASSERT_TRUE(match.has_value());
  ASSERT_TRUE(match->icp.converged) << icpStatusName(match->icp.status);
  EXPECT_NEAR(match->T_anchor_robot.x(), 0.0, 0.01);
  EXPECT_NEAR(match->T_anchor_robot.y(), 0.0, 0.01);
  EXPECT_NEAR(match->T_anchor_robot.theta(), 0.0, 0.002);
}

TEST(ScanMatcherTest, FitScaleOnlyGivesAlmostTheFloorInEveryDirection) {
  const ScanMatcherSettings settings = corridorSettings(0.0);
  const std::optional<ScanMatch> match = matchCorridor(settings);
  ASSERT_TRUE(match.has_value());
  const double floor_variance = settings.min_sigma_xy_m * settings.min_sigma_xy_m;
  // σ̂² / n of a noise-free fit is far below the floor along and across the corridor alike.
  EXPECT_NEAR(match->covariance(0, 0), floor_variance, 0.1 * floor_variance);
  EXPECT_NEAR(match->covariance(1, 1), floor_variance, 0.1 * floor_variance);
}

TEST(ScanMatcherTest, ShapedCovarianceLeavesTheCorridorsAxisUncertain) {
  const ScanMatcherSettings settings = corridorSettings(0.3);
  const std::optional<ScanMatch> match = matchCorridor(settings);
  ASSERT_TRUE(match.has_value());
  const double floor_variance = settings.min_sigma_xy_m * settings.min_sigma_xy_m;
  // Across the corridor (its best direction): 0.3 floors from the fit plus the floor.
  EXPECT_NEAR(match->covariance(1, 1), 1.3 * floor_variance, 0.1 * floor_variance);
  // Along it only the far end wall constrains the match: several times less certain.
  EXPECT_GT(match->covariance(0, 0), 3.0 * match->covariance(1, 1));
}

TEST(ScanMatcherTest, TheNewestKeyframeAloneIsASecondMeasurement) {
  ScanMatcherSettings settings = corridorSettings(0.3);
  ScanMatcher single(settings, SensorMounting{});
  settings.match_newest_keyframe = true;
  settings.two_match_covariance_factor = 1.5;
  ScanMatcher twice(settings, SensorMounting{});
  const PreparedScan scan = twice.prepare(corridorScan());
  const SE2 guess(0.05, 0.02, 0.01);
  EXPECT_FALSE(twice.matchNewestKeyframe(scan, guess).has_value());  // no map yet
  // An older keyframe 2 m back, then the newest one (the anchor) at the origin.
  for (ScanMatcher* matcher : {&single, &twice}) {
    matcher->addKeyframe(scan, SE2(-2.0, 0.0, 0.0));
    matcher->addKeyframe(scan, SE2());
  }
  EXPECT_FALSE(single.matchNewestKeyframe(scan, guess).has_value());  // off
  const std::optional<ScanMatch> newest = twice.matchNewestKeyframe(scan, guess);
  const std::optional<ScanMatch> map = twice.match(scan, guess);
  ASSERT_TRUE(newest.has_value());
  ASSERT_TRUE(newest->icp.converged) << icpStatusName(newest->icp.status);
  EXPECT_NEAR(newest->T_anchor_robot.y(), 0.0, 0.01);
  EXPECT_NEAR(newest->T_anchor_robot.theta(), 0.0, 0.002);
  // Both measurements count σ² × the factor: they are not independent.
  const std::optional<ScanMatch> alone = single.match(scan, guess);
  ASSERT_TRUE(map.has_value() && alone.has_value());
  EXPECT_TRUE(map->covariance.isApprox(1.5 * alone->covariance, 1e-9));
}

TEST(ScanMatcherTest, ScanToScanHasNoSecondMeasurement) {
  ScanMatcherSettings settings = corridorSettings(0.3);
  settings.mode = MatchMode::kScanToScan;
  settings.match_newest_keyframe = true;
  ScanMatcher matcher(settings, SensorMounting{});
  const PreparedScan scan = matcher.prepare(corridorScan());
  matcher.addKeyframe(scan, SE2());
  EXPECT_FALSE(matcher.matchNewestKeyframe(scan, SE2()).has_value());
}

}  // namespace
}  // namespace mrslam::robot
