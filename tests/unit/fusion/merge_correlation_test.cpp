#include <gtest/gtest.h>

#include "mrslam/fusion/merge/correlation.hpp"

namespace mrslam::fusion {
namespace {

std::vector<cv::Point> walk(const std::vector<std::pair<cv::Point, int>>& legs) {
  std::vector<cv::Point> chain{{0, 0}};
  for (const auto& [step, count] : legs) {
    for (int i = 0; i < count; ++i) {
      chain.push_back(chain.back() + step);
    }
  }
  return chain;
}

// Three turns (left, left, right): no symmetry maps it onto itself walked backwards.
std::vector<cv::Point> hook() {
  return walk({{{1, 0}, 30}, {{0, 1}, 20}, {{-1, 0}, 20}, {{0, 1}, 25}});
}

Segment segmentFrom(const std::vector<cv::Point>& chain, std::size_t first) {
  SegmentSettings settings;
  settings.segment_points_n = 48;
  return makeSegment(std::vector<cv::Point>(chain.begin() + static_cast<long>(first), chain.end()),
                     settings)
      .value();
}

SegmentMatch match(const Segment& a, const Segment& b) {
  const SegmentVerificationSettings verification;
  return matchSegments(a, segmentHistograms(a, verification), b, segmentHistograms(b, verification),
                       CorrelationSettings{});
}

TEST(MergeCorrelationTest, NormalizedCorrelationOfIdenticalOppositeAndConstantSequences) {
  const std::vector<double> a = {1.0, 3.0, 2.0, 5.0};
  const std::vector<double> scaled = {12.0, 16.0, 14.0, 20.0};  // 2 a + 10
  const std::vector<double> negated = {-1.0, -3.0, -2.0, -5.0};
  const std::vector<double> constant = {4.0, 4.0, 4.0, 4.0};
  EXPECT_NEAR(normalizedCorrelation(a.data(), scaled.data(), a.size()), 1.0, 1e-12);
  EXPECT_NEAR(normalizedCorrelation(a.data(), negated.data(), a.size()), -1.0, 1e-12);
  EXPECT_EQ(normalizedCorrelation(a.data(), constant.data(), a.size()), 0.0);
}

TEST(MergeCorrelationTest, FindsTheOffsetBetweenShiftedSegmentsOfOneEdge) {
  const std::vector<cv::Point> chain = hook();
  const Segment a = segmentFrom(chain, 15);
  const Segment b = segmentFrom(chain, 23);  // starts 8 cells further along
  const SegmentMatch found = match(a, b);
  EXPECT_FALSE(found.reversed);
  EXPECT_NEAR(found.offset, -8, 1);  // point i of a is point i - 8 of b
  EXPECT_GT(found.sequence_score, 0.9);
}

TEST(MergeCorrelationTest, FindsASegmentWalkedTheOtherWay) {
  const std::vector<cv::Point> chain = hook();
  const Segment a = segmentFrom(chain, 15);  // chain cells 15 … 62
  const Segment b = segmentFrom(std::vector<cv::Point>(chain.rbegin(), chain.rend()), 20);
  const SegmentMatch found = match(a, b);  // b: cells 75 down to 28
  EXPECT_TRUE(found.reversed);
  // Point i of a (cell 15 + i) is point i + offset of b reversed (cell 28 + i + offset).
  EXPECT_NEAR(found.offset, -13, 3);  // smoothing cuts a little arc at every corner
}

TEST(MergeCorrelationTest, ReversingTwiceGivesTheSegmentBack) {
  const Segment a = segmentFrom(hook(), 10);
  const Segment twice = reversedSegment(reversedSegment(a));
  EXPECT_EQ(twice.distances, a.distances);
  EXPECT_EQ(twice.turns, a.turns);
  EXPECT_EQ(reversedSegment(a).turns.front(), -a.turns.back());
}

TEST(MergeCorrelationTest, TheSameWallScoresAboveOtherShapes) {
  const Segment a = segmentFrom(hook(), 15);
  const double same = match(a, segmentFrom(hook(), 19)).score;
  EXPECT_GT(same, 0.9);
  for (const std::vector<cv::Point>& other :
       {walk({{{1, 0}, 40}, {{0, 1}, 40}}),
        walk({{{1, 0}, 20}, {{0, 1}, 15}, {{1, 0}, 20}, {{0, 1}, 15}, {{1, 0}, 20}}),
        walk({{{1, 0}, 30}, {{1, 1}, 15}, {{0, 1}, 30}})}) {
    EXPECT_LT(match(a, segmentFrom(other, 5)).score, same);
  }
}

}  // namespace
}  // namespace mrslam::fusion
