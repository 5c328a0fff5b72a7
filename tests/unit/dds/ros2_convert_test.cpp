#include "mrslam/dds/ros2_convert.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace mrslam::dds {
namespace {

TEST(Ros2ConvertTest, TimesSplitIntoSecondsAndNanosecondsBelowOneSecond) {
  const auto positive = toRosTime(Stamp{12'345'678'901});
  EXPECT_EQ(positive.sec(), 12);
  EXPECT_EQ(positive.nanosec(), 345'678'901u);
  const auto negative = toRosTime(Stamp{-1'500'000'000});  // -1.5 s = -2 s + 0.5 s
  EXPECT_EQ(negative.sec(), -2);
  EXPECT_EQ(negative.nanosec(), 500'000'000u);
}

TEST(Ros2ConvertTest, GridCellsKeepTheirOrderAndValues) {
  GridGeometry geometry;
  geometry.resolution_m = 0.05;
  geometry.width = 3;
  geometry.height = 2;
  geometry.origin_m = Eigen::Vector2d(-1.0, 2.5);
  GridMap map(geometry, GridMap::kUnknown);
  map.cells = {-1, 0, 100, 37, -1, 51};
  nav_msgs::msg::dds_::OccupancyGrid_ message;
  toRosOccupancyGrid(map, Stamp{2'000'000'001}, "map", message);
  EXPECT_EQ(message.header().frame_id(), "map");
  EXPECT_EQ(message.header().stamp().sec(), 2);
  EXPECT_EQ(message.header().stamp().nanosec(), 1u);
  EXPECT_FLOAT_EQ(message.info().resolution(), 0.05f);
  EXPECT_EQ(message.info().width(), 3u);
  EXPECT_EQ(message.info().height(), 2u);
  EXPECT_DOUBLE_EQ(message.info().origin().position().x(), -1.0);
  EXPECT_DOUBLE_EQ(message.info().origin().position().y(), 2.5);
  EXPECT_DOUBLE_EQ(message.info().origin().orientation().w(), 1.0);
  ASSERT_EQ(message.data().size(), 6u);
  for (std::size_t i = 0; i < map.cells.size(); ++i) {
    EXPECT_EQ(static_cast<std::int8_t>(message.data()[i]), map.cells[i]) << i;
  }
}

TEST(Ros2ConvertTest, PlanarPoseAndCovarianceFillRosLayout) {
  Eigen::Matrix3d covariance;
  covariance << 0.01, 0.002, 0.003, 0.002, 0.04, 0.005, 0.003, 0.005, 0.09;
  geometry_msgs::msg::dds_::PoseWithCovarianceStamped_ message;
  toRosPose(SE2(1.0, -2.0, M_PI / 2), covariance, Stamp{0}, "robot1/map", message);
  EXPECT_EQ(message.header().frame_id(), "robot1/map");
  const auto& pose = message.pose().pose();
  EXPECT_DOUBLE_EQ(pose.position().x(), 1.0);
  EXPECT_DOUBLE_EQ(pose.position().y(), -2.0);
  EXPECT_DOUBLE_EQ(pose.position().z(), 0.0);
  EXPECT_NEAR(pose.orientation().z(), std::sqrt(0.5), 1e-12);
  EXPECT_NEAR(pose.orientation().w(), std::sqrt(0.5), 1e-12);
  const auto& ros = message.pose().covariance();
  EXPECT_DOUBLE_EQ(ros[0], 0.01);           // x x
  EXPECT_DOUBLE_EQ(ros[1], 0.002);          // x y
  EXPECT_DOUBLE_EQ(ros[5], 0.003);          // x yaw
  EXPECT_DOUBLE_EQ(ros[7], 0.04);           // y y
  EXPECT_DOUBLE_EQ(ros[6 * 5 + 1], 0.005);  // yaw y
  EXPECT_DOUBLE_EQ(ros[35], 0.09);          // yaw yaw
  EXPECT_DOUBLE_EQ(ros[14], 0.0);           // z z: not estimated
  EXPECT_EQ(rosPoseTopic("robot1"), "rt/robot1/pose");
}

}  // namespace
}  // namespace mrslam::dds
