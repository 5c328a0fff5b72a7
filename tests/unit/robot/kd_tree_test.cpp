#include "mrslam/robot/kd_tree.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace mrslam::robot {
namespace {

std::vector<Eigen::Vector2d> randomPoints(std::mt19937& rng, std::size_t count) {
  std::uniform_real_distribution<double> coordinate(-10.0, 10.0);
  std::vector<Eigen::Vector2d> points(count);
  for (Eigen::Vector2d& point : points) {
    point = {coordinate(rng), coordinate(rng)};
  }
  return points;
}

// Squared distances of every point to the query, ascending, with their indices.
std::vector<std::pair<double, int>> bruteForce(const std::vector<Eigen::Vector2d>& points,
                                               const Eigen::Vector2d& query) {
  std::vector<std::pair<double, int>> all;
  for (std::size_t i = 0; i < points.size(); ++i) {
    all.emplace_back((points[i] - query).squaredNorm(), static_cast<int>(i));
  }
  std::sort(all.begin(), all.end());
  return all;
}

TEST(KdTree2dTest, NearestMatchesBruteForce) {
  std::mt19937 rng(42);
  const std::vector<Eigen::Vector2d> points = randomPoints(rng, 1000);
  const KdTree2d tree(points);
  ASSERT_EQ(tree.size(), points.size());
  for (const Eigen::Vector2d& query : randomPoints(rng, 200)) {
    const auto expected = bruteForce(points, query).front();
    const KdTree2d::Neighbour found = tree.nearest(query, 100.0);
    EXPECT_EQ(found.index, expected.second);
    EXPECT_DOUBLE_EQ(found.distance_sq, expected.first);
  }
}

TEST(KdTree2dTest, NearestRespectsTheSearchRadius) {
  const KdTree2d tree({{0.0, 0.0}, {5.0, 0.0}});
  EXPECT_EQ(tree.nearest({2.0, 0.0}, 1.0).index, -1);
  EXPECT_EQ(tree.nearest({2.0, 0.0}, 2.5).index, 0);
  EXPECT_EQ(tree.nearest({4.0, 0.0}, 2.5).index, 1);
  EXPECT_EQ(KdTree2d().nearest({0.0, 0.0}, 10.0).index, -1);
}

TEST(KdTree2dTest, NearestKMatchesBruteForce) {
  std::mt19937 rng(7);
  const std::vector<Eigen::Vector2d> points = randomPoints(rng, 500);
  const KdTree2d tree(points);
  for (const Eigen::Vector2d& query : randomPoints(rng, 50)) {
    const auto expected = bruteForce(points, query);
    const auto found = tree.nearestK(query, 6, 100.0);
    ASSERT_EQ(found.size(), 6u);
    for (std::size_t i = 0; i < found.size(); ++i) {
      EXPECT_EQ(found[i].index, expected[i].second) << i;
    }
  }
}

TEST(KdTree2dTest, NearestKStopsAtTheRadiusAndAtTheSetSize) {
  const KdTree2d tree({{0.0, 0.0}, {1.0, 0.0}, {2.0, 0.0}, {3.0, 0.0}});
  const auto within = tree.nearestK({0.1, 0.0}, 10, 1.5);
  ASSERT_EQ(within.size(), 2u);
  EXPECT_EQ(within[0].index, 0);
  EXPECT_EQ(within[1].index, 1);
  EXPECT_EQ(tree.nearestK({0.0, 0.0}, 10, 100.0).size(), 4u);
  EXPECT_TRUE(tree.nearestK({0.0, 0.0}, 0, 100.0).empty());
}

TEST(KdTree2dTest, DuplicatePointsAreAllFound) {
  const std::vector<Eigen::Vector2d> points(20, Eigen::Vector2d(1.0, 1.0));
  const KdTree2d tree(points);
  EXPECT_EQ(tree.nearestK({1.0, 1.0}, 20, 0.1).size(), 20u);
  EXPECT_EQ(tree.nearest({1.0, 1.0}, 0.1).distance_sq, 0.0);
}

}  // namespace
}  // namespace mrslam::robot
