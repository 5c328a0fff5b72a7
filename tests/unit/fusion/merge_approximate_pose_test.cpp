#include <gtest/gtest.h>

#include "mrslam/fusion/merge/approximate_pose.hpp"

namespace mrslam::fusion {
namespace {

Segment lSegment() {
  std::vector<cv::Point> chain{{10, 10}};
  for (int i = 0; i < 30; ++i) {
    chain.push_back(chain.back() + cv::Point(1, 0));
  }
  for (int i = 0; i < 30; ++i) {
    chain.push_back(chain.back() + cv::Point(0, 1));
  }
  SegmentSettings settings;
  settings.segment_points_n = 48;
  return makeSegment(chain, settings).value();
}

Segment transformed(const Segment& segment, const GridTransform& T) {
  Segment moved = segment;
  for (Eigen::Vector2d& p : moved.points) {
    p = T.apply(p);
  }
  moved.line = fitLine(moved.points, 0, moved.points.size());
  return moved;
}

double angleGap(double a, double b) {
  return std::abs(std::remainder(a - b, 2.0 * M_PI));
}

TEST(MergeApproximatePoseTest, LinesGiveBothHalfTurnsAndMatchTheCentroids) {
  FittedLine from;
  from.centroid = Eigen::Vector2d(10.0, 5.0);
  from.angle_rad = 0.2;
  FittedLine to;
  to.centroid = Eigen::Vector2d(40.0, 30.0);
  to.angle_rad = 0.9;
  const std::array<GridTransform, 2> poses = posesFromLines(from, to);
  EXPECT_NEAR(angleGap(poses[0].theta_rad, 0.7), 0.0, 1e-12);
  EXPECT_NEAR(angleGap(poses[1].theta_rad, 0.7 + M_PI), 0.0, 1e-12);
  for (const GridTransform& pose : poses) {
    EXPECT_NEAR((pose.apply(from.centroid) - to.centroid).norm(), 0.0, 1e-9);
  }
}

TEST(MergeApproximatePoseTest, RecoversTheTransformOfAMovedSegment) {
  GridTransform truth;
  truth.theta_rad = 2.3;
  truth.t_cells = Eigen::Vector2d(120.0, -35.0);
  const Segment from = lSegment();
  const Segment to = transformed(from, truth);
  SegmentMatch match;  // point i ↔ point i, same direction
  const std::array<GridTransform, 2> poses = approximatePoses(from, to, match);
  const GridTransform& right =
      angleGap(poses[0].theta_rad, truth.theta_rad) < 0.1 ? poses[0] : poses[1];
  EXPECT_NEAR(angleGap(right.theta_rad, truth.theta_rad), 0.0, 1e-9);
  EXPECT_NEAR((right.t_cells - truth.t_cells).norm(), 0.0, 1e-6);
}

TEST(MergeApproximatePoseTest, UsesOnlyTheMatchedSpanOfReversedSegments) {
  GridTransform truth;
  truth.theta_rad = -0.4;
  truth.t_cells = Eigen::Vector2d(5.0, 60.0);
  const Segment from = lSegment();
  const Segment to = reversedSegment(transformed(from, truth));
  SegmentMatch match;
  match.reversed = true;
  match.offset = 0;
  const std::array<GridTransform, 2> poses = approximatePoses(from, to, match);
  const GridTransform& right =
      angleGap(poses[0].theta_rad, truth.theta_rad) < 0.1 ? poses[0] : poses[1];
  EXPECT_NEAR(angleGap(right.theta_rad, truth.theta_rad), 0.0, 1e-9);
  EXPECT_NEAR((right.t_cells - truth.t_cells).norm(), 0.0, 1e-6);

  SegmentMatch shifted;
  shifted.offset = 10;  // point i of `from` ↔ point i + 10 of `to` walked backwards
  shifted.reversed = true;
  const auto [line_from, line_to] = matchedLines(from, to, shifted);
  EXPECT_NEAR((line_from.centroid - fitLine(from.points, 0, 38).centroid).norm(), 0.0, 1e-9);
  EXPECT_NEAR((line_to.centroid - truth.apply(fitLine(from.points, 10, 38).centroid)).norm(), 0.0,
              1e-6);
}

TEST(MergeApproximatePoseTest, TranslationFromCentroidsMapsOneOntoTheOther) {
  const Eigen::Vector2d from(3.0, 4.0);
  const Eigen::Vector2d to(-7.0, 12.0);
  GridTransform T;
  T.theta_rad = 1.1;
  T.t_cells = translationFromCentroids(T.theta_rad, from, to);
  EXPECT_NEAR((T.apply(from) - to).norm(), 0.0, 1e-12);
}

}  // namespace
}  // namespace mrslam::fusion
