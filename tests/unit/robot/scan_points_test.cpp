#include "mrslam/robot/scan_points.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mrslam::robot {
namespace {

// A laser at the origin looking at the wall x = 2 with 91 beams over ±45°.
LaserScan wallScan() {
  LaserScan scan;
  scan.angle_min_rad = -M_PI / 4;
  scan.angle_increment_rad = M_PI / 2 / 90;
  scan.range_min_m = 0.02;
  scan.range_max_m = 30.0;
  for (int i = 0; i <= 90; ++i) {
    scan.ranges_m.push_back(static_cast<float>(2.0 / std::cos(scan.beamAngle(i))));
  }
  return scan;
}

TEST(ScanPointsTest, HitsAreInTheRobotFrameAndFilteredByRange) {
  LaserScan scan = wallScan();
  scan.ranges_m[0] = LaserScan::kNoReturn;
  scan.ranges_m[1] = LaserScan::kInvalid;
  ScanPointSettings settings;
  settings.max_range_m = 2.5;  // drops the beams beyond ±36.9°
  const ScanHits hits = scanHits(scan, SE2(0.5, 0.0, 0.0), settings);
  ASSERT_FALSE(hits.points.empty());
  for (const Eigen::Vector2d& point : hits.points) {
    EXPECT_NEAR(point.x(), 2.5, 1e-6);  // the wall, 0.5 m further in the robot frame
    EXPECT_LE(std::abs(point.y()), 2.0 * std::tan(std::acos(2.0 / 2.5)) + 1e-6);
  }
  EXPECT_EQ(hits.points.size(), hits.ranges.size());
  EXPECT_LT(hits.points.size(), scan.ranges_m.size() - 2);
}

TEST(ScanPointsTest, ThinningKeepsPointsApart) {
  ScanPointSettings settings;
  settings.min_spacing_m = 0.2;
  const std::vector<Eigen::Vector2d> kept =
      thinned(scanHits(wallScan(), SE2(), settings), settings);
  ASSERT_GT(kept.size(), 5u);
  for (std::size_t i = 1; i < kept.size(); ++i) {
    EXPECT_GE((kept[i] - kept[i - 1]).norm(), 0.2 - 1e-9);
  }
}

TEST(ScanPointsTest, NormalsOfAWallPointAcrossIt) {
  ScanPointSettings settings;
  settings.min_spacing_m = 0.0;
  const OrientedPoints oriented = orientedHits(scanHits(wallScan(), SE2(), settings), settings);
  ASSERT_GT(oriented.points.size(), 80u);
  ASSERT_EQ(oriented.normals.size(), oriented.points.size());
  for (const Eigen::Vector2d& normal : oriented.normals) {
    EXPECT_NEAR(std::abs(normal.x()), 1.0, 1e-6);
  }
}

TEST(ScanPointsTest, CornersAndIsolatedHitsGetNoNormal) {
  // Two hits far from everything else, and a wall.
  LaserScan scan = wallScan();
  scan.ranges_m[45] = 10.0f;
  ScanPointSettings settings;
  settings.min_spacing_m = 0.0;
  const OrientedPoints oriented = orientedHits(scanHits(scan, SE2(), settings), settings);
  for (const Eigen::Vector2d& point : oriented.points) {
    EXPECT_LT(point.x(), 3.0) << "the isolated hit has no surface";
  }
}

TEST(ScanPointsTest, TransformedMovesPointsAndTurnsNormals) {
  OrientedPoints points{{{1.0, 0.0}}, {{1.0, 0.0}}};
  const OrientedPoints moved = transformed(points, SE2(1.0, 2.0, M_PI / 2));
  EXPECT_NEAR(moved.points[0].x(), 1.0, 1e-12);
  EXPECT_NEAR(moved.points[0].y(), 3.0, 1e-12);
  EXPECT_NEAR(moved.normals[0].x(), 0.0, 1e-12);
  EXPECT_NEAR(moved.normals[0].y(), 1.0, 1e-12);
}

TEST(ScanPointsTest, LineFitRatioSeparatesLinesFromBlobs) {
  EXPECT_NEAR(fitLine({{0, 0}, {1, 0}, {2, 0}, {3, 0}}).ratio, 0.0, 1e-12);
  EXPECT_GT(fitLine({{0, 0}, {1, 0}, {0, 1}, {1, 1}}).ratio, 0.9);
  EXPECT_EQ(fitLine({{0, 0}, {1, 0}}).ratio, 1.0);
}

}  // namespace
}  // namespace mrslam::robot
