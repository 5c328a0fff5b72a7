#pragma once
// The robot agent's DDS glue: publishes pose, local map and status of one robot.

#include <cstdint>
#include <string>

#include "mrslam/dds/participant.hpp"
#include "mrslam/robot/robot_runner.hpp"
#include "mrslam_msgs.h"

namespace mrslam::robot {

class RobotNode : public RobotOutput {
 public:
  RobotNode(const DdsSettings& settings, const std::string& robot_id);

  void publishPose(Stamp stamp, const SE2& T_map_robot, const Eigen::Matrix3d& covariance) override;
  void publishMap(const MapSnapshot& snapshot) override;
  void publishStatus(const StatusReport& report) override;
  void publishSighting(const SightingReport& report) override;

  /// Waits (up to timeout_s) for `readers` map readers to match, and as many sighting readers
  /// `with_sightings` (the robot wrote some), and then for all matched readers to acknowledge
  /// every map and sighting sent. False when that did not happen in time.
  bool waitForDelivery(int readers, double timeout_s, bool with_sightings);

 private:
  std::string robot_id_;
  dds::Participant participant_;
  eprosima::fastdds::dds::DataWriter* pose_writer_;
  eprosima::fastdds::dds::DataWriter* map_writer_;
  eprosima::fastdds::dds::DataWriter* status_writer_;
  eprosima::fastdds::dds::DataWriter* ros_pose_writer_;  ///< rt/<robot>/pose for ROS 2 tools
  eprosima::fastdds::dds::DataWriter* sighting_writer_;  ///< mrslam/rendezvous
  std::uint64_t pose_sequence_ = 0;
  msg::LocalMap map_message_;  ///< reused: maps are large
};

}  // namespace mrslam::robot
