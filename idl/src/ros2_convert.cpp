#include "mrslam/dds/ros2_convert.hpp"

#include <array>
#include <cmath>

namespace mrslam::dds {

namespace {

constexpr std::int64_t kNanosecondsPerSecond = 1000000000;

geometry_msgs::msg::dds_::Pose_ toRosPose2D(double x, double y, double theta) {
  geometry_msgs::msg::dds_::Pose_ pose;
  pose.position().x(x);
  pose.position().y(y);
  pose.position().z(0.0);
  pose.orientation().x(0.0);
  pose.orientation().y(0.0);
  pose.orientation().z(std::sin(0.5 * theta));
  pose.orientation().w(std::cos(0.5 * theta));
  return pose;
}

}  // namespace

std::string rosPoseTopic(const std::string& robot_id) {
  return "rt/" + robot_id + "/pose";
}

builtin_interfaces::msg::dds_::Time_ toRosTime(Stamp stamp) {
  // Floor division, so that nanosec is always in [0, 1e9) as ROS 2 requires.
  std::int64_t seconds = stamp.ns / kNanosecondsPerSecond;
  std::int64_t nanoseconds = stamp.ns % kNanosecondsPerSecond;
  if (nanoseconds < 0) {
    nanoseconds += kNanosecondsPerSecond;
    --seconds;
  }
  builtin_interfaces::msg::dds_::Time_ time;
  time.sec(static_cast<std::int32_t>(seconds));
  time.nanosec(static_cast<std::uint32_t>(nanoseconds));
  return time;
}

void toRosOccupancyGrid(const GridMap& map, Stamp stamp, const std::string& frame_id,
                        nav_msgs::msg::dds_::OccupancyGrid_& message) {
  message.header().stamp(toRosTime(stamp));
  message.header().frame_id(frame_id);
  nav_msgs::msg::dds_::MapMetaData_& info = message.info();
  info.map_load_time(toRosTime(stamp));
  info.resolution(static_cast<float>(map.geometry.resolution_m));
  info.width(static_cast<std::uint32_t>(map.geometry.width));
  info.height(static_cast<std::uint32_t>(map.geometry.height));
  info.origin(toRosPose2D(map.geometry.origin_m.x(), map.geometry.origin_m.y(), 0.0));
  message.data().resize(map.cells.size());
  for (std::size_t i = 0; i < map.cells.size(); ++i) {
    message.data()[i] = static_cast<std::uint8_t>(map.cells[i]);  // int8 on the wire
  }
}

void toRosPose(const SE2& T_frame_robot, const Eigen::Matrix3d& covariance, Stamp stamp,
               const std::string& frame_id,
               geometry_msgs::msg::dds_::PoseWithCovarianceStamped_& message) {
  message.header().stamp(toRosTime(stamp));
  message.header().frame_id(frame_id);
  message.pose().pose(toRosPose2D(T_frame_robot.x(), T_frame_robot.y(), T_frame_robot.theta()));
  // Rows and columns of x, y, θ in ROS's (x, y, z, roll, pitch, yaw) order.
  constexpr int kRosIndex[3] = {0, 1, 5};
  std::array<double, 36>& ros_covariance = message.pose().covariance();
  ros_covariance.fill(0.0);
  for (int row = 0; row < 3; ++row) {
    for (int column = 0; column < 3; ++column) {
      ros_covariance[static_cast<std::size_t>(6 * kRosIndex[row] + kRosIndex[column])] =
          covariance(row, column);
    }
  }
}

}  // namespace mrslam::dds
