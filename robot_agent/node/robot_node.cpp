#include "robot_node.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <vector>

#include "mrslam/dds/convert.hpp"
#include "mrslam/dds/ros2_convert.hpp"
#include "mrslam/dds/topics.hpp"
#include "mrslam_msgsPubSubTypes.h"
#include "ros2_msgsPubSubTypes.h"

namespace mrslam::robot {

using eprosima::fastrtps::types::ReturnCode_t;

namespace {

msg::RobotState toMsgState(RobotState state) {
  switch (state) {
    case RobotState::kStarting:
      return msg::ROBOT_STARTING;
    case RobotState::kRunning:
      return msg::ROBOT_RUNNING;
    case RobotState::kFinished:
      return msg::ROBOT_FINISHED;
    case RobotState::kFailed:
      return msg::ROBOT_FAILED;
  }
  return msg::ROBOT_FAILED;
}

}  // namespace

RobotNode::RobotNode(const DdsSettings& settings, const std::string& robot_id)
    : robot_id_(robot_id),
      participant_(settings, "robot_agent " + robot_id),
      pose_writer_(participant_.createWriter<msg::RobotPosePubSubType>(dds::kRobotPoseTopic,
                                                                       dds::kPoseWriterProfile)),
      map_writer_(participant_.createWriter<msg::LocalMapPubSubType>(dds::kLocalMapTopic,
                                                                     dds::kMapWriterProfile)),
      status_writer_(participant_.createWriter<msg::RobotStatusPubSubType>(
          dds::kRobotStatusTopic, dds::kStateWriterProfile)),
      ros_pose_writer_(
          participant_.createWriter<geometry_msgs::msg::dds_::PoseWithCovarianceStamped_PubSubType>(
              dds::rosPoseTopic(robot_id), dds::kRosPoseWriterProfile)),
      sighting_writer_(participant_.createWriter<msg::RobotSightingMsgPubSubType>(
          dds::kRendezvousTopic, dds::kSightingWriterProfile)) {
  map_message_.robot_id(robot_id_);
}

void RobotNode::publishPose(Stamp stamp, const SE2& T_map_robot,
                            const Eigen::Matrix3d& covariance) {
  msg::RobotPose message;
  message.robot_id(robot_id_);
  message.stamp(dds::toMsg(stamp));
  message.sequence_number(++pose_sequence_);
  message.pose(dds::toMsg(T_map_robot));
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      message.covariance()[static_cast<std::size_t>(row * 3 + col)] = covariance(row, col);
    }
  }
  pose_writer_->write(&message);
  // The same pose for ROS 2 tools, in the frame of the robot's own map.
  geometry_msgs::msg::dds_::PoseWithCovarianceStamped_ ros_pose;
  dds::toRosPose(T_map_robot, covariance, stamp, robot_id_ + "/map", ros_pose);
  ros_pose_writer_->write(&ros_pose);
}

void RobotNode::publishSighting(const SightingReport& report) {
  msg::RobotSightingMsg message;
  message.observer_id(robot_id_);
  message.observed_id(report.observed_id);
  message.stamp(dds::toMsg(report.stamp));
  message.range_m(report.range_m);
  message.bearing_rad(report.bearing_rad);
  message.T_map_observer(dds::toMsg(report.T_map_robot));
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) {
      message.covariance()[static_cast<std::size_t>(row * 3 + col)] = report.covariance(row, col);
    }
  }
  sighting_writer_->write(&message);
}

void RobotNode::publishMap(const MapSnapshot& snapshot) {
  map_message_.stamp(dds::toMsg(snapshot.stamp));
  map_message_.sequence_number(snapshot.sequence);
  map_message_.scans_inserted(static_cast<std::uint32_t>(snapshot.scans_inserted));
  map_message_.is_final(snapshot.is_final);
  map_message_.sightings_published(snapshot.sightings_published);
  dds::gridToMsg(snapshot.map, map_message_.info(), map_message_.data());
  map_message_.trajectory().clear();
  for (const SE2& pose : snapshot.trajectory) {
    map_message_.trajectory().push_back(dds::toMsg(pose));
  }
  if (!map_writer_->write(&map_message_)) {
    spdlog::error("{}: the local map {} could not be written to DDS", robot_id_, snapshot.sequence);
  }
}

void RobotNode::publishStatus(const StatusReport& report) {
  msg::RobotStatus message;
  message.robot_id(robot_id_);
  message.stamp(dds::toMsg(report.stamp));
  message.state(toMsgState(report.state));
  message.message(report.message);
  msg::SensorHealth source;
  source.name("samples");
  source.source(report.source);
  source.healthy(report.state != RobotState::kFailed);
  source.samples(report.source_counters.samples);
  source.errors(report.source_counters.malformed_records);
  message.sensors().push_back(source);
  for (const drivers::SensorStatus& sensor : report.sensors) {
    msg::SensorHealth health;
    health.name(sensor.name);
    health.source(sensor.source);
    health.healthy(sensor.healthy);
    health.samples(sensor.samples);
    health.errors(sensor.errors);
    message.sensors().push_back(health);
  }
  message.scans_processed(report.pipeline_counters.scans);
  message.malformed_records(report.source_counters.malformed_records);
  message.maps_published(report.maps_published);
  status_writer_->write(&message);
}

namespace {

eprosima::fastrtps::Duration_t durationOf(double seconds) {
  const auto whole = static_cast<std::int32_t>(seconds);
  return {whole, static_cast<std::uint32_t>((seconds - whole) * 1e9)};
}

}  // namespace

bool RobotNode::waitForDelivery(int readers, double timeout_s, bool with_sightings) {
  const auto start = std::chrono::steady_clock::now();
  const auto secondsLeft = [&] {
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    return std::max(0.0, timeout_s - elapsed.count());
  };
  // The sightings go to the same fusion agents on a topic of their own, whose readers match apart
  // from the map readers: a robot that left once its final map was taken could leave before the
  // fusion agent's sighting reader matched, and its sightings were lost.
  std::vector<eprosima::fastdds::dds::DataWriter*> writers{map_writer_};
  if (with_sightings) {
    writers.push_back(sighting_writer_);
  }
  for (eprosima::fastdds::dds::DataWriter* writer : writers) {
    if (!dds::waitForReaders(writer, readers, secondsLeft())) {
      return false;
    }
  }
  for (eprosima::fastdds::dds::DataWriter* writer : writers) {
    if (writer->wait_for_acknowledgments(durationOf(secondsLeft())) != ReturnCode_t::RETCODE_OK) {
      return false;
    }
  }
  return true;
}

}  // namespace mrslam::robot
