#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "mrslam/fusion/merge/edges.hpp"

namespace mrslam::fusion {
namespace {

std::vector<int> edgeColumns(const cv::Mat& edges, int row) {
  std::vector<int> columns;
  for (int x = 0; x < edges.cols; ++x) {
    if (edges.at<std::uint8_t>(row, x) != 0) {
      columns.push_back(x);
    }
  }
  return columns;
}

TEST(MergeEdgesTest, OccupiedImageMarksCellsAtOrAboveTheThreshold) {
  GridGeometry geometry;
  geometry.width = 3;
  geometry.height = 2;
  GridMap map(geometry, GridMap::kUnknown);
  map.at(0, 0) = 100;
  map.at(1, 0) = 64;
  map.at(2, 1) = 65;
  const cv::Mat occupied = occupiedImage(map, 65);
  EXPECT_EQ(occupied.at<std::uint8_t>(0, 0), 255);  // (row 0, column 0) = cell (0, 0)
  EXPECT_EQ(occupied.at<std::uint8_t>(0, 1), 0);
  EXPECT_EQ(occupied.at<std::uint8_t>(1, 2), 255);
  EXPECT_EQ(cv::countNonZero(occupied), 2);
}

TEST(MergeEdgesTest, ScanLinePairsARisingAndAFallingFaceIntoTheirMiddle) {
  std::vector<Face> faces(20, Face::kNone);
  faces[4] = Face::kRising;
  faces[9] = Face::kFalling;  // 5 apart: one obstacle with dt = 8
  const ScanLineResult result = smoothScanLine(faces, 8);
  EXPECT_TRUE(result.paired[4]);
  EXPECT_TRUE(result.paired[9]);
  EXPECT_TRUE(result.middles[7]);  // 6.5 rounds up
  EXPECT_EQ(std::count(result.middles.begin(), result.middles.end(), true), 1);
}

TEST(MergeEdgesTest, ScanLineKeepsAdjacentDistantAndOutwardFacingCells) {
  std::vector<Face> faces(40, Face::kNone);
  faces[2] = Face::kRising;  // adjacent pair: both kept
  faces[3] = Face::kFalling;
  faces[10] = Face::kRising;  // dt or more apart: distinct obstacles
  faces[18] = Face::kFalling;
  faces[25] = Face::kFalling;  // falling then rising: free space between two walls
  faces[28] = Face::kRising;
  const ScanLineResult result = smoothScanLine(faces, 8);
  EXPECT_EQ(std::count(result.paired.begin(), result.paired.end(), true), 0);
  EXPECT_EQ(std::count(result.middles.begin(), result.middles.end(), true), 0);
}

TEST(MergeEdgesTest, ScanLineTreatsATwoCellFaceAsOneFace) {
  std::vector<Face> faces(20, Face::kNone);
  faces[4] = Face::kRising;
  faces[5] = Face::kRising;
  faces[9] = Face::kFalling;
  faces[10] = Face::kFalling;
  const ScanLineResult result = smoothScanLine(faces, 8);
  for (const int cell : {4, 5, 9, 10}) {
    EXPECT_TRUE(result.paired[static_cast<std::size_t>(cell)]) << cell;
  }
  EXPECT_TRUE(result.middles[7]);  // between centres 4.5 and 9.5
}

TEST(MergeEdgesTest, ThickVerticalWallBecomesOneLineAtItsMiddle) {
  cv::Mat occupied(40, 40, CV_8U, cv::Scalar(0));
  occupied(cv::Rect(18, 5, 4, 30)).setTo(255);  // columns 18..21, centre 19.5
  const DetectedEdges detected = detectEdges(occupied, EdgeSettings{});
  ASSERT_GE(edgeColumns(detected.edges, 20).size(), 2u);  // Canny outlines both faces
  const cv::Mat smoothed = smoothEdges(detected, 8);
  for (int row = 10; row < 30; ++row) {
    const std::vector<int> columns = edgeColumns(smoothed, row);
    ASSERT_EQ(columns.size(), 1u) << "row " << row;
    EXPECT_GE(columns[0], 19);
    EXPECT_LE(columns[0], 20);
  }
}

TEST(MergeEdgesTest, ThickHorizontalWallBecomesOneLineAtItsMiddle) {
  cv::Mat occupied(40, 40, CV_8U, cv::Scalar(0));
  occupied(cv::Rect(5, 10, 30, 5)).setTo(255);  // rows 10..14, centre 12
  const cv::Mat smoothed = smoothEdges(detectEdges(occupied, EdgeSettings{}), 8);
  for (int column = 10; column < 30; ++column) {
    int count = 0;
    for (int row = 0; row < smoothed.rows; ++row) {
      if (smoothed.at<std::uint8_t>(row, column) != 0) {
        ++count;
        EXPECT_EQ(row, 12) << "column " << column;
      }
    }
    EXPECT_EQ(count, 1) << "column " << column;
  }
}

TEST(MergeEdgesTest, WallsFartherApartThanDtStaySeparate) {
  cv::Mat occupied(40, 60, CV_8U, cv::Scalar(0));
  occupied(cv::Rect(10, 5, 12, 30)).setTo(255);  // 12 cells thick: faces 12 apart > dt
  const cv::Mat smoothed = smoothEdges(detectEdges(occupied, EdgeSettings{}), 8);
  EXPECT_EQ(edgeColumns(smoothed, 20).size(), 2u);
}

TEST(MergeEdgesTest, NonZeroCellsListsCellsRowByRow) {
  cv::Mat image(3, 4, CV_8U, cv::Scalar(0));
  image.at<std::uint8_t>(2, 1) = 255;
  image.at<std::uint8_t>(0, 3) = 255;
  const std::vector<cv::Point> cells = nonZeroCells(image);
  ASSERT_EQ(cells.size(), 2u);
  EXPECT_EQ(cells[0], cv::Point(3, 0));
  EXPECT_EQ(cells[1], cv::Point(1, 2));
}

}  // namespace
}  // namespace mrslam::fusion
