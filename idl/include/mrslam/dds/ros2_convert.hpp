#pragma once
// The project's maps and poses as ROS 2 messages (ros2_msgs.idl), for RViz2 and the ROS 2
// command-line tools on the same DDS domain.

#include <Eigen/Core>
#include <string>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/common/stamp.hpp"
#include "ros2_msgs.h"

namespace mrslam::dds {

/// ROS 2 topic of the global map ("map" in ROS 2 names).
inline constexpr const char* kRosMapTopic = "rt/map";
/// ROS 2 topic of a robot's pose ("<robot>/pose" in ROS 2 names).
std::string rosPoseTopic(const std::string& robot_id);

builtin_interfaces::msg::dds_::Time_ toRosTime(Stamp stamp);

/// A grid as nav_msgs/OccupancyGrid: cells row by row from the origin cell, -1 unknown, 0..100.
void toRosOccupancyGrid(const GridMap& map, Stamp stamp, const std::string& frame_id,
                        nav_msgs::msg::dds_::OccupancyGrid_& message);

/// A planar pose with its 3 × 3 covariance (x, y, θ) as geometry_msgs/PoseWithCovarianceStamped:
/// z = 0, the heading as a quaternion about z, the covariance spread into ROS's 6 × 6 (x, y, z,
/// roll, pitch, yaw) with θ on yaw.
void toRosPose(const SE2& T_frame_robot, const Eigen::Matrix3d& covariance, Stamp stamp,
               const std::string& frame_id,
               geometry_msgs::msg::dds_::PoseWithCovarianceStamped_& message);

}  // namespace mrslam::dds
