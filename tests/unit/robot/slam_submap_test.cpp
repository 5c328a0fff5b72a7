// The probability grid, submaps and the least-squares scan-to-submap matcher, on synthetic rooms
// and on a real submap of the corrected intel log.

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <random>

#include "mrslam/drivers/carmen_reader.hpp"
#include "mrslam/robot/slam/ceres_scan_matcher.hpp"
#include "mrslam/robot/slam/submaps.hpp"
#include "test_data.hpp"

namespace mrslam::robot::slam {
namespace {

TEST(ProbabilityGridTest, HitsAndMissesMoveTheOddsOncePerScan) {
  ProbabilityGrid grid(ProbabilityGridSettings{});
  const Eigen::Vector2d origin(0.01, 0.01);
  // Two beams ending in one cell count once; a miss ray through the hit cell does not clear it.
  grid.insertScan(origin, {{1.01, 0.01}, {1.02, 0.02}}, {{2.01, 0.01}});
  const Eigen::Vector2i hit = grid.cellOf({1.01, 0.01});
  EXPECT_NEAR(grid.probability(hit), 0.55, 1e-6);
  EXPECT_NEAR(grid.probability(grid.cellOf({0.51, 0.01})), 0.49, 1e-6);
  EXPECT_NEAR(grid.probability(grid.cellOf({2.01, 0.01})), 0.49, 1e-6);
  EXPECT_FALSE(grid.isKnown(grid.cellOf({0.5, 1.0})));
  // odds(0.55)² = (11/9)²: p = 121 / 202.
  grid.insertScan(origin, {{1.01, 0.01}}, {});
  EXPECT_NEAR(grid.probability(hit), 121.0 / 202.0, 1e-5);
  for (int i = 0; i < 50; ++i) {
    grid.insertScan(origin, {{1.01, 0.01}}, {});
  }
  EXPECT_NEAR(grid.probability(hit), 0.9, 1e-6);  // clamped
}

TEST(ProbabilityGridTest, GrowingKeepsCellsWhereTheyWere) {
  ProbabilityGrid grid(ProbabilityGridSettings{});
  grid.insertScan({0, 0}, {{0.5, 0.5}}, {});
  const float before = grid.probability(grid.cellOf({0.5, 0.5}));
  grid.insertScan({0, 0}, {{-20.0, 15.0}}, {});
  EXPECT_FLOAT_EQ(grid.probability(grid.cellOf({0.5, 0.5})), before);
  EXPECT_TRUE(grid.isKnown(grid.cellOf({-20.0, 15.0})));
  EXPECT_NEAR(grid.centreOf(grid.cellOf({0.51, 0.52})).x(), 0.525, 1e-9);
}

TEST(ProbabilityGridTest, ShrinkingToTheKnownCellsKeepsEveryProbability) {
  ProbabilityGrid grid(ProbabilityGridSettings{});
  grid.insertScan({0, 0}, {{3.0, 1.0}, {-2.0, 0.5}}, {{0.0, 4.0}});
  grid.insertScan({0, 0}, {{-20.0, 15.0}}, {});  // grows the grid by more than it needs
  const std::vector<Eigen::Vector2d> probes = {
      {3.0, 1.0}, {-2.0, 0.5}, {0.0, 2.0}, {-20.0, 15.0}, {-10.0, 7.5}, {5.0, -5.0}, {-3.0, 14.0}};
  std::vector<float> before;
  for (const Eigen::Vector2d& probe : probes) {
    before.push_back(grid.probability(grid.cellOf(probe), 0.0f));
  }
  const std::size_t known = grid.knownCellCount();
  const int area_before = grid.width() * grid.height();
  grid.shrinkToKnown();
  EXPECT_LT(grid.width() * grid.height(), area_before);
  EXPECT_EQ(grid.knownCellCount(), known);
  for (std::size_t i = 0; i < probes.size(); ++i) {
    EXPECT_FLOAT_EQ(grid.probability(grid.cellOf(probes[i]), 0.0f), before[i]) << i;
  }
  // The box is tight: the hits at x = -20 and x = 3 are its first and last columns.
  EXPECT_EQ(grid.cellOf({-20.0, 15.0}).x(), 0);
  EXPECT_EQ(grid.cellOf({3.0, 1.0}).x(), grid.width() - 1);
  // Insertions still work after it, and count once per scan.
  grid.insertScan({0, 0}, {{3.0, 1.0}, {3.01, 1.01}, {8.0, 8.0}}, {});
  EXPECT_NEAR(grid.probability(grid.cellOf({3.0, 1.0})), 121.0 / 202.0, 1e-5);
  EXPECT_NEAR(grid.probability(grid.cellOf({8.0, 8.0})), 0.55, 1e-6);
  ProbabilityGrid empty(ProbabilityGridSettings{});
  empty.shrinkToKnown();
  EXPECT_EQ(empty.width(), 0);
  empty.insertScan({0, 0}, {{1.0, 1.0}}, {});
  EXPECT_NEAR(empty.probability(empty.cellOf({1.0, 1.0})), 0.55, 1e-6);
}

TEST(ProbabilityGridTest, BadSettingsAndExtentsAreRefused) {
  ProbabilityGridSettings bad;
  bad.hit_probability = 0.4;
  EXPECT_THROW(ProbabilityGrid{bad}, std::invalid_argument);
  ProbabilityGrid grid(ProbabilityGridSettings{});
  grid.insertScan({0, 0}, {{NAN, 0.0}, {INFINITY, 1.0}}, {{0.0, NAN}});
  EXPECT_EQ(grid.knownCellCount(), 0u);  // nothing inserted for non-finite points
  EXPECT_THROW(grid.insertScan({0, 0}, {{3e7, 0.0}}, {}), std::out_of_range);
}

TEST(ActiveSubmapsTest, TwoActiveSubmapsOverlapAndTheOlderFinishes) {
  SubmapSettings settings;
  settings.num_range_data = 3;
  ActiveSubmaps submaps(settings);
  RangeData data;
  data.hits = {{1.0, 0.0}};
  std::vector<int> finished;
  for (int scan = 0; scan < 9; ++scan) {
    data.origin = {0.1 * scan, 0.0};
    const auto inserted = submaps.insert(data);
    EXPECT_EQ(inserted.size(), scan < 3 ? 1u : 2u) << scan;
    if (submaps.finishedByLastInsert()) {
      finished.push_back(submaps.finishedByLastInsert()->id);
      EXPECT_EQ(submaps.finishedByLastInsert()->insertions, 6);
    }
  }
  EXPECT_EQ(finished, (std::vector<int>{0, 1}));  // by the 6th and the 9th scan
  ASSERT_TRUE(submaps.matchingSubmap());
  EXPECT_EQ(submaps.matchingSubmap()->id, 2);
  // A submap's frame starts where the scan that started it was: submap 2 after the 6th scan,
  // and took the 7th (x = 0.6) first.
  EXPECT_NEAR(submaps.matchingSubmap()->T_local_submap.x(), 0.5, 1e-12);
}

// A 6 m × 4 m room with a pillar, seen from `T_room_robot` by a 360-beam scan (robot frame).
std::vector<Eigen::Vector2d> roomScan(const SE2& T_room_robot) {
  const auto inside = [](const Eigen::Vector2d& p) {
    const bool walls = p.x() > 0.0 && p.x() < 6.0 && p.y() > 0.0 && p.y() < 4.0;
    const bool pillar = p.x() > 3.5 && p.x() < 4.0 && p.y() > 1.0 && p.y() < 1.6;
    return walls && !pillar;
  };
  std::vector<Eigen::Vector2d> points;
  for (int beam = 0; beam < 360; ++beam) {
    const double angle = beam * M_PI / 180.0;
    const Eigen::Vector2d direction(std::cos(angle), std::sin(angle));
    for (double range = 0.05; range < 8.0; range += 0.005) {
      const Eigen::Vector2d p = T_room_robot * (range * direction);
      if (!inside(p)) {
        points.push_back(range * direction);
        break;
      }
    }
  }
  return points;
}

TEST(CeresScanMatcherTest, RecoversAnOffsetInASyntheticRoom) {
  ProbabilityGrid grid(ProbabilityGridSettings{});
  const SE2 T_room_robot(2.0, 2.0, 0.3);
  for (int i = 0; i < 10; ++i) {
    std::vector<Eigen::Vector2d> hits;
    for (const auto& p : roomScan(T_room_robot)) {
      hits.push_back(T_room_robot * p);
    }
    grid.insertScan(T_room_robot.translation(), hits, {});
  }
  CeresScanMatcherSettings settings;
  settings.translation_weight = 0.0;
  settings.rotation_weight = 0.0;
  const CeresScanMatcher matcher(settings);
  const std::vector<Eigen::Vector2d> points = roomScan(T_room_robot);
  const auto match = matcher.match(grid, SE2(2.06, 1.95, 0.33), points);
  ASSERT_TRUE(match);
  EXPECT_NEAR(match->T_submap_robot.x(), 2.0, 0.01);
  EXPECT_NEAR(match->T_submap_robot.y(), 2.0, 0.01);
  EXPECT_NEAR(match->T_submap_robot.theta(), 0.3, 0.005);
  EXPECT_GT(match->score, 0.75);  // walls of p ≈ 0.88 after ten scans, hits spread over cells
  EXPECT_TRUE(match->covariance.allFinite());
  EXPECT_GT(match->covariance.determinant(), 0.0);
  EXPECT_FALSE(matcher.match(grid, T_room_robot, {}));
}

TEST(CeresScanMatcherTest, ACorridorsLengthStaysUncertain) {
  ProbabilityGrid grid(ProbabilityGridSettings{});
  // Two long walls along x, 2.05 m apart through cell centres (cells are 5 cm, centred at
  // (k + 0.5) · 5 cm): the fit fixes y and θ, not x.
  constexpr double kWallY = 1.025;
  std::vector<Eigen::Vector2d> walls;
  for (double x = -10.0; x <= 10.0; x += 0.02) {
    walls.push_back({x, -kWallY});
    walls.push_back({x, kWallY});
  }
  for (int i = 0; i < 10; ++i) {
    grid.insertScan({0.0, 0.0}, walls, {});
  }
  std::vector<Eigen::Vector2d> points;
  for (double x = -4.0; x <= 4.0; x += 0.1) {
    points.push_back({x, -kWallY});
    points.push_back({x, kWallY});
  }
  const CeresScanMatcher matcher(CeresScanMatcherSettings{});
  const auto match = matcher.match(grid, SE2(0.0, 0.03, 0.0), points);
  ASSERT_TRUE(match);
  EXPECT_NEAR(match->T_submap_robot.y(), 0.0, 0.01);
  EXPECT_GT(match->covariance(0, 0), 10.0 * match->covariance(1, 1));
}

}  // namespace
}  // namespace mrslam::robot::slam
