// The virtual robot's likelihood field as a table of distinct costs: every cell's cost and every
// scan's sum equal, bit for bit, those worked out from the distance field itself.

#include "mrslam/fusion/merge/hit_costs.hpp"

#include <gtest/gtest.h>

#include <random>

#include "merge_test_maps.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

/// A point's cost from the field itself: the capped distance squared over 2σ².
double fieldCost(const cv::Mat& distance, int x, int y, double cap, double sigma) {
  double d = cap;
  if (x >= 0 && y >= 0 && x < distance.cols && y < distance.rows) {
    d = std::min(cap, static_cast<double>(distance.at<float>(y, x)));
  }
  return d * d / (2.0 * sigma * sigma);
}

/// A scan's log-likelihood from the field itself, each point placed by SE2.
double fieldLogLikelihood(const cv::Mat& distance, const std::vector<Eigen::Vector2d>& points,
                          const SE2& pose, double cap, double sigma) {
  double sum = 0.0;
  for (const Eigen::Vector2d& point : points) {
    const Eigen::Vector2d p = pose * point;
    sum -= fieldCost(distance, roundToInt(p.x()), roundToInt(p.y()), cap, sigma);
  }
  return sum;
}

void expectEveryCellAsTheField(const HitCosts& costs, const cv::Mat& distance, double cap,
                               double sigma) {
  for (int y = -2; y < distance.rows + 2; ++y) {
    for (int x = -2; x < distance.cols + 2; ++x) {
      ASSERT_EQ(costs.at(x, y), fieldCost(distance, x, y, cap, sigma)) << x << ", " << y;
    }
  }
}

TEST(MergeHitCostsTest, HandBuiltFieldKeepsOneCostPerDistinctCappedDistance) {
  cv::Mat distance = (cv::Mat_<float>(2, 4) << 0.0f, 1.0f, 1.41421354f, 9.0f,  //
                      4.5f, 1.0f, 6.0f, 2.0f);
  const HitCosts costs(distance, 4.5, 1.5);
  ASSERT_TRUE(costs.indexed());
  // 0, 1, √2, 2 and the cap (4.5, 6 and 9 all capped): five costs.
  ASSERT_EQ(costs.table().size(), 5u);
  EXPECT_EQ(costs.at(0, 0), 0.0);
  EXPECT_EQ(costs.at(1, 1), 1.0 / 4.5);
  EXPECT_EQ(costs.at(3, 0), 4.5 * 4.5 / 4.5);
  EXPECT_EQ(costs.at(2, 1), costs.at(0, 1));
  EXPECT_EQ(costs.at(-1, 0), 4.5);  // off the map: the cap's cost
  EXPECT_EQ(costs.at(0, 2), 4.5);
  EXPECT_EQ(costs.at(std::numeric_limits<int>::min(), 0), 4.5);
  expectEveryCellAsTheField(costs, distance, 4.5, 1.5);
}

TEST(MergeHitCostsTest, FieldOfManyDistinctDistancesKeepsEachCellsCost) {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> any(0.0f, 10.0f);
  cv::Mat distance(30, 40, CV_32F);
  for (int y = 0; y < distance.rows; ++y) {
    for (int x = 0; x < distance.cols; ++x) {
      distance.at<float>(y, x) = any(random);
    }
  }
  const HitCosts costs(distance, 4.5, 1.5);
  EXPECT_FALSE(costs.indexed());  // about 540 distinct values below the cap
  expectEveryCellAsTheField(costs, distance, 4.5, 1.5);
}

TEST(MergeHitCostsTest, MapWithoutWallsCostsTheCapEverywhereAndAnEmptyFieldOffTheMap) {
  GridGeometry geometry;
  geometry.width = 30;
  geometry.height = 20;
  const GridMap open_floor(geometry, GridMap::kFree);
  const HitCosts costs(wallDistance(open_floor, 65), 4.5, 1.5);
  ASSERT_TRUE(costs.indexed());
  ASSERT_EQ(costs.table().size(), 1u);
  EXPECT_EQ(costs.table().front(), 4.5);
  const std::vector<Eigen::Vector2d> scan = {{0.0, 0.0}, {3.0, -2.0}, {100.0, 0.0}};
  EXPECT_EQ(costs.scanLogLikelihood(scan, SE2(10.0, 10.0, 0.3)), -3.0 * 4.5);

  const HitCosts none(cv::Mat(), 4.5, 1.5);
  EXPECT_EQ(none.at(0, 0), 4.5);
  EXPECT_EQ(none.scanLogLikelihood(scan, SE2(0.0, 0.0, 0.0)), -3.0 * 4.5);
}

TEST(MergeHitCostsTest, RealMapScansSumAsTheFieldBitForBit) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const GridMap map = merge_test::loadMap(test::sharedDataPath("maps/freiburg-intel.pgm"));
  const cv::Mat distance = wallDistance(map, 65);
  const double sigma = 1.5;
  const double cap = 3.0 * sigma;
  const HitCosts costs(distance, cap, sigma);
  ASSERT_TRUE(costs.indexed());
  // An exact distance transform's values are square roots of integers: within 4.5 cells, 0, 1,
  // √2, 2, √5, √8, 3, √10, √13, 4, √17, √18, √20 and the cap.
  EXPECT_EQ(costs.table().size(), 14u);
  expectEveryCellAsTheField(costs, distance, cap, sigma);

  std::mt19937 random(11);
  std::uniform_real_distribution<double> across(-20.0, map.geometry.width + 20.0);
  std::uniform_real_distribution<double> down(-20.0, map.geometry.height + 20.0);
  std::uniform_real_distribution<double> turn(-M_PI, M_PI);
  std::uniform_real_distribution<double> reach(-160.0, 160.0);
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<Eigen::Vector2d> scan;
    for (int i = 0; i < 60; ++i) {
      scan.emplace_back(reach(random), reach(random));
    }
    scan.emplace_back(0.5, -0.5);  // a point whose rounding falls on the half
    const SE2 pose(across(random), down(random), turn(random));
    ASSERT_EQ(costs.scanLogLikelihood(scan, pose),
              fieldLogLikelihood(distance, scan, pose, cap, sigma))
        << "trial " << trial;
  }
}

}  // namespace
}  // namespace mrslam::fusion
