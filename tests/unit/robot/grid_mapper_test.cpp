#include "mrslam/robot/grid_mapper.hpp"

#include <gtest/gtest.h>

namespace mrslam::robot {
namespace {

// A scan with `count` beams over ±90°, every range the same.
LaserScan uniformScan(std::size_t count, float range) {
  LaserScan scan;
  scan.angle_min_rad = -M_PI / 2;
  scan.angle_increment_rad = M_PI / static_cast<double>(count - 1);
  scan.range_min_m = 0.02;
  scan.range_max_m = 4.0;
  scan.ranges_m.assign(count, range);
  return scan;
}

std::int8_t valueAt(const OccupancyGrid& grid, const Eigen::Vector2d& point) {
  const Eigen::Vector2i cell = grid.cellOf(point);
  return grid.occupancy(cell.x(), cell.y());
}

TEST(GridMapperTest, HitsAreOccupiedAndTheWayThereIsFree) {
  MappingSettings settings;
  settings.resolution_m = 0.05;
  GridMapper mapper(settings, SensorMounting{});
  mapper.insertScan(uniformScan(181, 2.0f), SE2());
  const OccupancyGrid& grid = mapper.grid();
  EXPECT_GT(valueAt(grid, {2.0, 0.0}), 50);
  EXPECT_GT(valueAt(grid, {0.0, 2.0}), 50);
  EXPECT_LT(valueAt(grid, {1.0, 0.0}), 50);
  EXPECT_LT(valueAt(grid, {0.0, -1.5}), 50);
  EXPECT_EQ(valueAt(grid, {-1.0, 0.0}), GridMap::kUnknown);  // behind the laser
  EXPECT_EQ(valueAt(grid, {3.0, 0.0}), GridMap::kUnknown);   // beyond the wall
}

TEST(GridMapperTest, ScanIsPlacedAtThePoseAndTheMounting) {
  MappingSettings settings;
  SensorMounting mounting;
  mounting.T_robot_laser = SE2(0.5, 0.0, 0.0);
  GridMapper mapper(settings, mounting);
  LaserScan scan = uniformScan(3, 1.0f);  // beams at -90°, 0°, +90°
  mapper.insertScan(scan, SE2(10.0, 0.0, M_PI / 2));
  // The robot at (10, 0) faces +y; its laser sits at (10, 0.5); the middle beam hits (10, 1.5).
  EXPECT_GT(valueAt(mapper.grid(), {10.0, 1.5}), 50);
  EXPECT_GT(valueAt(mapper.grid(), {9.0, 0.5}), 50);   // left beam
  EXPECT_GT(valueAt(mapper.grid(), {11.0, 0.5}), 50);  // right beam
}

TEST(GridMapperTest, NoReturnClearsOnlyUpToTheClearingRange) {
  LaserScan scan = uniformScan(3, LaserScan::kNoReturn);
  MappingSettings without_clearing;
  GridMapper silent(without_clearing, SensorMounting{});
  silent.insertScan(scan, SE2());
  EXPECT_EQ(silent.grid().knownCellCount(), 0u);

  MappingSettings with_clearing;
  with_clearing.clearing_range_m = 1.0;
  GridMapper clearing(with_clearing, SensorMounting{});
  clearing.insertScan(scan, SE2());
  EXPECT_LT(valueAt(clearing.grid(), {0.5, 0.0}), 50);
  EXPECT_LT(valueAt(clearing.grid(), {0.97, 0.0}), 50);  // the end cell is free, not a hit
  EXPECT_EQ(valueAt(clearing.grid(), {1.2, 0.0}), GridMap::kUnknown);
}

TEST(GridMapperTest, InvalidAndTooFarReadingsMarkNothingOccupied) {
  LaserScan scan = uniformScan(3, 1.0f);
  scan.ranges_m[0] = LaserScan::kInvalid;
  scan.ranges_m[1] = 0.01f;  // below range_min: an error code
  scan.ranges_m[2] = 3.5f;   // beyond max_range_m below
  MappingSettings settings;
  settings.max_range_m = 3.0;
  GridMapper mapper(settings, SensorMounting{});
  mapper.insertScan(scan, SE2());
  EXPECT_EQ(mapper.grid().knownCellCount(), 0u);
}

TEST(GridMapperTest, GridGrowsWhereTheRobotGoes) {
  GridMapper mapper(MappingSettings{}, SensorMounting{});
  mapper.insertScan(uniformScan(91, 2.0f), SE2());
  const int width_before = mapper.grid().geometry().width;
  mapper.insertScan(uniformScan(91, 2.0f), SE2(40.0, -25.0, 0.0));
  EXPECT_GT(mapper.grid().geometry().width, width_before);
  EXPECT_GT(valueAt(mapper.grid(), {42.0, -25.0}), 50);
  EXPECT_GT(valueAt(mapper.grid(), {2.0, 0.0}), 50);  // the first scan is still there
}

}  // namespace
}  // namespace mrslam::robot
