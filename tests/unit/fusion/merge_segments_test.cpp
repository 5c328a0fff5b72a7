#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <opencv2/imgproc.hpp>

#include "mrslam/fusion/merge/segments.hpp"

namespace mrslam::fusion {
namespace {

std::vector<cv::Point> straightChain(cv::Point from, cv::Point step, int count) {
  std::vector<cv::Point> chain;
  for (int i = 0; i < count; ++i) {
    chain.push_back(from + i * step);
  }
  return chain;
}

// Right then up: a left turn of 90° at (30, 10).
std::vector<cv::Point> lChain() {
  std::vector<cv::Point> chain = straightChain({0, 10}, {1, 0}, 30);
  const std::vector<cv::Point> up = straightChain({30, 10}, {0, 1}, 31);
  chain.insert(chain.end(), up.begin(), up.end());
  return chain;
}

bool isConnected(const std::vector<cv::Point>& chain, int gap) {
  for (std::size_t i = 1; i < chain.size(); ++i) {
    const cv::Point d = chain[i] - chain[i - 1];
    if (std::max(std::abs(d.x), std::abs(d.y)) > gap) {
      return false;
    }
  }
  return true;
}

TEST(MergeSegmentsTest, FitLineFindsCentroidAndDirection) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 11; ++i) {
    points.emplace_back(i, 2.0 * i + 1.0);
  }
  const FittedLine line = fitLine(points, 0, points.size());
  EXPECT_NEAR(line.centroid.x(), 5.0, 1e-9);
  EXPECT_NEAR(line.centroid.y(), 11.0, 1e-9);
  EXPECT_NEAR(line.angle_rad, std::atan(2.0), 1e-9);
  const FittedLine part = fitLine(points, 8, 3);  // points 8, 9, 10
  EXPECT_NEAR(part.centroid.x(), 9.0, 1e-9);
}

TEST(MergeSegmentsTest, FitLineAnglesLieInHalfTurn) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i < 5; ++i) {
    points.emplace_back(-i, i);  // direction 135°
  }
  EXPECT_NEAR(fitLine(points, 0, points.size()).angle_rad, 0.75 * M_PI, 1e-9);
}

TEST(MergeSegmentsTest, FollowsAStraightEdgeForTheAskedLength) {
  cv::Mat edges(50, 120, CV_8U, cv::Scalar(0));
  cv::line(edges, {5, 20}, {110, 30}, cv::Scalar(255));
  EdgeFollower follower(edges, 2);
  const std::vector<cv::Point> chain = follower.follow({60, 25}, 30.0);
  EXPECT_GE(chain.size(), 29u);
  EXPECT_LE(chain.size(), 32u);
  EXPECT_TRUE(isConnected(chain, 1));
  for (const cv::Point& cell : chain) {
    EXPECT_NE(edges.at<std::uint8_t>(cell.y, cell.x), 0);
  }
}

TEST(MergeSegmentsTest, WalksTheOtherWayFromADeadEnd) {
  cv::Mat edges(20, 60, CV_8U, cv::Scalar(0));
  cv::line(edges, {5, 10}, {50, 10}, cv::Scalar(255));
  EdgeFollower follower(edges, 2);
  const std::vector<cv::Point> chain = follower.follow({47, 10}, 30.0);
  EXPECT_GE(chain.size(), 30u);
  EXPECT_TRUE(isConnected(chain, 1));
  EXPECT_NE(std::find(chain.begin(), chain.end(), cv::Point(47, 10)), chain.end());
}

TEST(MergeSegmentsTest, JumpsSmallBreaksOfTheEdge) {
  cv::Mat edges(20, 60, CV_8U, cv::Scalar(0));
  cv::line(edges, {5, 10}, {25, 10}, cv::Scalar(255));
  cv::line(edges, {27, 10}, {55, 10}, cv::Scalar(255));  // one missing cell at x = 26
  EdgeFollower follower(edges, 2);
  const std::vector<cv::Point> chain = follower.follow({6, 10}, 40.0);
  EXPECT_GE(chain.size(), 40u);
  EXPECT_TRUE(isConnected(chain, 2));
}

TEST(MergeSegmentsTest, StraightSegmentHasUnitSpacingNoDistanceAndNoTurn) {
  SegmentSettings settings;
  settings.segment_points_n = 40;
  const std::optional<Segment> segment = makeSegment(straightChain({0, 0}, {1, 1}, 60), settings);
  ASSERT_TRUE(segment);
  ASSERT_EQ(segment->points.size(), 40u);
  for (std::size_t i = 1; i < segment->points.size(); ++i) {
    EXPECT_NEAR((segment->points[i] - segment->points[i - 1]).norm(), 1.0, 1e-6);
  }
  EXPECT_EQ(segment->turns.size(), 40u - 2u * 3u);
  for (const double d : segment->distances) {
    EXPECT_LT(d, 1e-6);
  }
  for (const double turn : segment->turns) {
    EXPECT_NEAR(turn, 0.0, 1e-6);
  }
  EXPECT_NEAR(segment->line.angle_rad, M_PI / 4.0, 1e-6);
}

TEST(MergeSegmentsTest, LCornerTurnsLeftByARightAngleAndBendsAwayFromItsLine) {
  SegmentSettings settings;
  settings.segment_points_n = 48;
  const std::optional<Segment> segment = makeSegment(lChain(), settings);
  ASSERT_TRUE(segment);
  // The chords of Δ overlap, so the sum of Δ is k times the total turn.
  const double total = std::accumulate(segment->turns.begin(), segment->turns.end(), 0.0);
  EXPECT_NEAR(total / settings.turn_chord_k, M_PI / 2.0, 0.1);
  EXPECT_GT(*std::max_element(segment->distances.begin(), segment->distances.end()), 5.0);
  const std::vector<cv::Point> chain = lChain();
  const Segment reversed =
      makeSegment(std::vector<cv::Point>(chain.rbegin(), chain.rend()), settings).value();
  const double reversed_total = std::accumulate(reversed.turns.begin(), reversed.turns.end(), 0.0);
  EXPECT_NEAR(reversed_total / settings.turn_chord_k, -M_PI / 2.0, 0.1);
}

TEST(MergeSegmentsTest, ChainShorterThanNGivesNoSegment) {
  SegmentSettings settings;
  settings.segment_points_n = 48;
  EXPECT_FALSE(makeSegment(straightChain({0, 0}, {1, 0}, 30), settings));
  EXPECT_FALSE(makeSegment({}, settings));
}

}  // namespace
}  // namespace mrslam::fusion
