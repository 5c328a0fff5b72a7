#include "mrslam/robot/robot_pipeline.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

#include "mrslam/robot/odometry_estimator.hpp"
#include "mrslam/robot/trajectory_io.hpp"
#include "test_data.hpp"

namespace mrslam::robot {
namespace {

std::unique_ptr<RobotPipeline> odometryPipeline() {
  return std::make_unique<RobotPipeline>(
      MappingSettings{}, SensorMounting{},
      std::make_unique<OdometryEstimator>(DiffDriveParams{}, OdometryNoise{}));
}

LaserScan scanAt(std::int64_t ns) {
  LaserScan scan;
  scan.stamp = Stamp{ns};
  scan.angle_increment_rad = 0.1;
  scan.range_min_m = 0.02;
  scan.range_max_m = 4.0;
  scan.ranges_m = {1.0f};
  return scan;
}

TEST(RobotPipelineTest, ScansAreInsertedAtTheEstimatedPose) {
  auto pipeline = odometryPipeline();
  EXPECT_EQ(pipeline->process(OdometryPose{Stamp{0}, SE2(5, 5, 0)}), RobotPipeline::Update::kPose);
  pipeline->process(OdometryPose{Stamp{1}, SE2(7, 5, 0)});
  EXPECT_EQ(pipeline->process(scanAt(2)), RobotPipeline::Update::kScan);
  ASSERT_EQ(pipeline->trajectory().size(), 1u);
  EXPECT_NEAR(pipeline->trajectory()[0].T_map_robot.x(), 2.0, 1e-12);
  const Eigen::Vector2i hit = pipeline->grid().cellOf({3.0, 0.0});
  EXPECT_GT(pipeline->grid().occupancy(hit.x(), hit.y()), 50);
  EXPECT_EQ(pipeline->counters().odometry, 2u);
  EXPECT_EQ(pipeline->counters().scans, 1u);
}

TEST(RobotPipelineTest, LateSamplesAreCountedAndKeptInOrderOfArrival) {
  auto pipeline = odometryPipeline();
  pipeline->process(scanAt(100));
  pipeline->process(scanAt(90));
  pipeline->process(scanAt(100));
  EXPECT_EQ(pipeline->counters().late_samples, 1u);
  EXPECT_EQ(pipeline->latestStamp().ns, 100);
  EXPECT_EQ(pipeline->trajectory()[1].stamp.ns, 90);
}

TEST(TrajectoryIoTest, WritesTumLines) {
  const auto folder = test::scratchFolder("tum");
  const std::string path = (folder / "trajectory.txt").string();
  writeTumTrajectory({{Stamp{1234567890123456789}, SE2(1.5, -2.0, M_PI / 2)}}, path);
  std::ifstream file(path);
  std::string line;
  std::getline(file, line);
  EXPECT_EQ(line, "1234567890.123456789 1.500000000 -2.000000000 0 0 0 0.707106781 0.707106781");
  EXPECT_FALSE(std::getline(file, line));
}

}  // namespace
}  // namespace mrslam::robot
