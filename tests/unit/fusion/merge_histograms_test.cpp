#include <gtest/gtest.h>

#include <numeric>

#include "mrslam/fusion/merge/histograms.hpp"

namespace mrslam::fusion {
namespace {

std::vector<cv::Point> path(cv::Point start, const std::vector<std::pair<cv::Point, int>>& legs) {
  std::vector<cv::Point> chain{start};
  for (const auto& [step, count] : legs) {
    for (int i = 0; i < count; ++i) {
      chain.push_back(chain.back() + step);
    }
  }
  return chain;
}

Segment segmentOf(const std::vector<cv::Point>& chain) {
  SegmentSettings settings;
  settings.segment_points_n = 48;
  return makeSegment(chain, settings).value();
}

SegmentVerdict verdictOf(const Segment& segment) {
  const SegmentVerificationSettings settings;
  return verifySegment(segment, segmentHistograms(segment, settings), settings);
}

TEST(MergeHistogramsTest, HistogramsAreNormalised) {
  const SegmentVerificationSettings settings;
  const SegmentHistograms histograms =
      segmentHistograms(segmentOf(path({0, 0}, {{{1, 0}, 30}, {{0, 1}, 30}})), settings);
  ASSERT_EQ(histograms.distance.size(), static_cast<std::size_t>(settings.distance_bins));
  ASSERT_EQ(histograms.arc.size(), static_cast<std::size_t>(settings.arc_bins));
  EXPECT_NEAR(std::accumulate(histograms.distance.begin(), histograms.distance.end(), 0.0), 1.0,
              1e-12);
  EXPECT_NEAR(std::accumulate(histograms.arc.begin(), histograms.arc.end(), 0.0), 1.0, 1e-12);
}

TEST(MergeHistogramsTest, FlatWallIsRefused) {
  EXPECT_EQ(verdictOf(segmentOf(path({0, 0}, {{{1, 0}, 70}}))), SegmentVerdict::kFlat);
  EXPECT_EQ(verdictOf(segmentOf(path({0, 0}, {{{1, 1}, 70}}))), SegmentVerdict::kFlat);
}

TEST(MergeHistogramsTest, LCornerIsAccepted) {
  EXPECT_EQ(verdictOf(segmentOf(path({0, 0}, {{{1, 0}, 30}, {{0, 1}, 30}}))),
            SegmentVerdict::kAccepted);
  EXPECT_EQ(verdictOf(segmentOf(path({0, 0}, {{{0, -1}, 20}, {{-1, 0}, 40}}))),
            SegmentVerdict::kAccepted);
}

TEST(MergeHistogramsTest, SpikeIsRefusedForItsSharpTurn) {
  // Out along a wall and back at 27° to it: a 153° turn, sharper than ωc (115°).
  EXPECT_EQ(verdictOf(segmentOf(path({0, 0}, {{{1, 0}, 30}, {{-2, 1}, 25}}))),
            SegmentVerdict::kSharpTurn);
  SegmentVerificationSettings blunt;
  blunt.max_turn_omega_c = 3.0;  // the same spike passes a looser ωc
  const Segment spike = segmentOf(path({0, 0}, {{{1, 0}, 30}, {{-2, 1}, 25}}));
  EXPECT_EQ(verifySegment(spike, segmentHistograms(spike, blunt), blunt),
            SegmentVerdict::kAccepted);
}

TEST(MergeHistogramsTest, NarrowHairpinIsRefused) {
  // Both arms lie at the same distance from the fitted line: no spread to fix a pose.
  EXPECT_NE(verdictOf(segmentOf(path({0, 0}, {{{1, 0}, 30}, {{0, 1}, 2}, {{-1, 0}, 30}}))),
            SegmentVerdict::kAccepted);
}

TEST(MergeHistogramsTest, PointsInTwoSeparateClustersLeaveAnEmptyDistanceBin) {
  Segment segment = segmentOf(path({0, 0}, {{{1, 0}, 30}, {{0, 1}, 30}}));
  std::fill(segment.distances.begin(), segment.distances.end(), 0.0);
  std::fill(segment.distances.begin(), segment.distances.begin() + 8, 10.0);
  EXPECT_EQ(verdictOf(segment), SegmentVerdict::kEmptyDistanceBin);
}

TEST(MergeHistogramsTest, SpreadThresholdHdDecides) {
  const Segment segment = segmentOf(path({0, 0}, {{{1, 0}, 40}, {{1, 1}, 3}, {{1, 0}, 30}}));
  const double spread = *std::max_element(segment.distances.begin(), segment.distances.end()) -
                        *std::min_element(segment.distances.begin(), segment.distances.end());
  SegmentVerificationSettings settings;
  settings.histogram_spread_hd = spread + 0.1;
  EXPECT_EQ(verifySegment(segment, segmentHistograms(segment, settings), settings),
            SegmentVerdict::kFlat);
  settings.histogram_spread_hd = spread - 0.1;
  EXPECT_NE(verifySegment(segment, segmentHistograms(segment, settings), settings),
            SegmentVerdict::kFlat);
}

}  // namespace
}  // namespace mrslam::fusion
