#include "fusion_node.hpp"

#include <spdlog/spdlog.h>

#include <cmath>

#include <algorithm>
#include <fastdds/dds/subscriber/SampleInfo.hpp>

#include "mrslam/dds/convert.hpp"
#include "mrslam/dds/ros2_convert.hpp"
#include "mrslam/dds/topics.hpp"
#include "mrslam_msgsPubSubTypes.h"
#include "ros2_msgsPubSubTypes.h"

namespace mrslam::fusion {

using eprosima::fastdds::dds::DataReader;
using eprosima::fastdds::dds::DataWriter;
using eprosima::fastdds::dds::SampleInfo;
using eprosima::fastrtps::types::ReturnCode_t;

namespace {

constexpr std::size_t kMaxCountedObservers = 1024;  // robots whose sightings are counted

const char* stateName(msg::RobotState state) {
  switch (state) {
    case msg::ROBOT_STARTING:
      return "starting";
    case msg::ROBOT_RUNNING:
      return "running";
    case msg::ROBOT_FINISHED:
      return "finished";
    case msg::ROBOT_FAILED:
      return "failed";
  }
  return "unknown";
}

}  // namespace

FusionNode::FusionNode(const FusionConfig& config, RobotMapStore& store, ViewerModel* viewer)
    : config_(config),
      store_(store),
      viewer_(viewer),
      participant_(config.dds, "fusion_agent " + config.fusion_id) {
  global_map_writer_ = participant_.createWriter<msg::GlobalMapPubSubType>(
      dds::kGlobalMapTopic, dds::kStateWriterProfile);
  transforms_writer_ = participant_.createWriter<msg::PairwiseTransformPubSubType>(
      dds::kTransformsTopic, dds::kStateWriterProfile);
  status_writer_ = participant_.createWriter<msg::FusionStatusPubSubType>(dds::kFusionStatusTopic,
                                                                          dds::kStateWriterProfile);
  if (config.ros2_map) {
    ros_map_writer_ = participant_.createWriter<nav_msgs::msg::dds_::OccupancyGrid_PubSubType>(
        dds::kRosMapTopic, dds::kStateWriterProfile);
  }
  status_reader_ = participant_.createReader<msg::RobotStatusPubSubType>(
      dds::kRobotStatusTopic, dds::kStateReaderProfile, this);
  map_reader_ = participant_.createReader<msg::LocalMapPubSubType>(dds::kLocalMapTopic,
                                                                   dds::kMapReaderProfile, this);
  sighting_reader_ = participant_.createReader<msg::RobotSightingMsgPubSubType>(
      dds::kRendezvousTopic, dds::kSightingReaderProfile, this);
}

FusionNode::~FusionNode() {
  // Stop callbacks before the members they use go away.
  map_reader_->set_listener(nullptr);
  status_reader_->set_listener(nullptr);
  sighting_reader_->set_listener(nullptr);
}

void FusionNode::on_subscription_matched(
    DataReader* reader, const eprosima::fastdds::dds::SubscriptionMatchedStatus& status) {
  if (reader == map_reader_ && status.current_count_change > 0) {
    spdlog::info("fusion: a robot's map writer joined ({} matched)", status.current_count);
  }
}

bool FusionNode::noteWriter(const std::string& robot_id,
                            const eprosima::fastrtps::rtps::InstanceHandle_t& writer) {
  std::lock_guard<std::mutex> lock(writers_mutex_);
  const auto known = writer_of_robot_.find(robot_id);
  const bool first = known == writer_of_robot_.end();
  const bool restarted = !first && known->second != writer;
  writer_of_robot_[robot_id] = writer;
  robot_of_writer_[writer] = robot_id;
  if (first) {
    spdlog::info("fusion: first map of {} received", robot_id);
  } else if (restarted) {
    spdlog::warn("fusion: {} sends from a new agent (restarted?): its new map replaces the old",
                 robot_id);
  }
  return restarted;
}

void FusionNode::on_liveliness_changed(
    DataReader* reader, const eprosima::fastdds::dds::LivelinessChangedStatus& status) {
  if (reader != map_reader_) {
    return;
  }
  std::string robot_id;
  {
    std::lock_guard<std::mutex> lock(writers_mutex_);
    const auto found = robot_of_writer_.find(status.last_publication_handle);
    if (found == robot_of_writer_.end()) {
      return;  // a writer that never sent a map
    }
    robot_id = found->second;
  }
  if (status.not_alive_count_change > 0 && !store_.isFinal(robot_id)) {
    if (store_.setStale(robot_id, true)) {
      spdlog::warn("fusion: {} fell silent (its lease ran out); its last map stays, marked stale",
                   robot_id);
    }
  } else if (status.alive_count_change > 0 && store_.setStale(robot_id, false)) {
    spdlog::info("fusion: {} is back", robot_id);
  }
}

void FusionNode::on_data_available(DataReader* reader) {
  if (reader == map_reader_) {
    receiveMaps(reader);
  } else if (reader == status_reader_) {
    receiveStatus(reader);
  } else if (reader == sighting_reader_) {
    receiveSightings(reader);
  }
}

std::uint64_t FusionNode::sightingsReceived(const std::string& observer_id) const {
  std::lock_guard<std::mutex> lock(sightings_mutex_);
  const auto found = sightings_received_.find(observer_id);
  return found == sightings_received_.end() ? 0 : found->second;
}

void FusionNode::countSightingOf(const std::string& observer_id) {
  std::lock_guard<std::mutex> lock(sightings_mutex_);
  const auto found = sightings_received_.find(observer_id);
  if (found != sightings_received_.end()) {
    ++found->second;
  } else if (isValidRobotId(observer_id) && sightings_received_.size() < kMaxCountedObservers) {
    sightings_received_.emplace(observer_id, 1);  // refused ones too: the robot counted them
  }
}

void FusionNode::receiveSightings(DataReader* reader) {
  msg::RobotSightingMsg message;
  SampleInfo info;
  while (reader->take_next_sample(&message, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) {
      continue;
    }
    Sighting sighting;
    sighting.observer = message.observer_id();
    sighting.observed = message.observed_id();
    sighting.stamp = dds::fromMsg(message.stamp());
    sighting.range_m = message.range_m();
    sighting.bearing_rad = message.bearing_rad();
    sighting.T_map_observer = dds::fromMsg(message.T_map_observer());
    const auto& pose = message.T_map_observer();
    if (!isValidRobotId(sighting.observer) || !isValidRobotId(sighting.observed)) {
      rejected_sightings_.report("robot id", "a sighting names no valid robot id");
    } else if (!std::isfinite(sighting.range_m) || sighting.range_m <= 0.0 ||
               !std::isfinite(sighting.bearing_rad) || !std::isfinite(pose.x()) ||
               !std::isfinite(pose.y()) || !std::isfinite(pose.theta())) {
      rejected_sightings_.report("values",
                                 "a sighting from " + sighting.observer +
                                     " has a range, bearing or pose that is not a number");
    } else if (!rendezvous_.add(sighting)) {
      rejected_sightings_.report("self", sighting.observer + " saw itself");
    } else {
      spdlog::info("fusion: {} saw {} at {:.2f} m, bearing {:.1f} deg", sighting.observer,
                   sighting.observed, sighting.range_m, sighting.bearing_rad * 180.0 / M_PI);
    }
    countSightingOf(sighting.observer);  // after the book holds it: the loop may stop on the count
  }
}

void FusionNode::receiveMaps(DataReader* reader) {
  msg::LocalMap message;
  SampleInfo info;
  while (reader->take_next_sample(&message, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) {
      continue;
    }
    ++maps_received_;
    const std::string& robot_id = message.robot_id();
    if (!isValidRobotId(robot_id)) {
      rejected_.report("bad robot id", "a map with an invalid robot id was refused");
      continue;
    }
    if (!config_.allowed_robots.empty() &&
        std::find(config_.allowed_robots.begin(), config_.allowed_robots.end(), robot_id) ==
            config_.allowed_robots.end()) {
      rejected_.report("robot not allowed", "robot '" + robot_id + "' is not in allowed_robots");
      continue;
    }
    Result<GridMap> grid = dds::gridFromMsg(message.info(), message.data(), config_.max_cells);
    if (!grid) {
      rejected_.report("bad grid", "map of '" + robot_id + "': " + grid.reason());
      continue;
    }
    RobotMap map;
    map.robot_id = robot_id;
    map.stamp = dds::fromMsg(message.stamp());
    map.sequence = message.sequence_number();
    map.scans_inserted = message.scans_inserted();
    map.is_final = message.is_final();
    map.sightings_published = message.sightings_published();
    map.map = std::move(grid.value());
    for (const msg::Pose2D& pose : message.trajectory()) {
      map.trajectory.push_back(dds::fromMsg(pose));
    }
    const bool is_final = map.is_final;
    const std::uint64_t sequence = map.sequence;
    const bool restarted = noteWriter(robot_id, info.publication_handle);
    if (store_.update(std::move(map), restarted) == RobotMapStore::Outcome::kOutdated) {
      rejected_.report("outdated", "an older map of '" + robot_id + "' arrived late");
    } else if (is_final) {
      spdlog::info("fusion: final map {} of {} received", sequence, robot_id);
    }
  }
}

namespace {

RobotHealth healthOf(const msg::RobotStatus& message) {
  RobotHealth health;
  health.state = stateName(message.state());
  health.message = message.message();
  health.scans_processed = message.scans_processed();
  health.malformed_records = message.malformed_records();
  health.maps_published = message.maps_published();
  for (const msg::SensorHealth& sensor : message.sensors()) {
    health.sensors.push_back({sensor.name(), sensor.source(), sensor.healthy(), sensor.rate_hz(),
                              sensor.samples(), sensor.errors()});
  }
  return health;
}

}  // namespace

void FusionNode::receiveStatus(DataReader* reader) {
  msg::RobotStatus message;
  SampleInfo info;
  while (reader->take_next_sample(&message, &info) == ReturnCode_t::RETCODE_OK) {
    if (!info.valid_data) {
      continue;
    }
    spdlog::debug("fusion: {} is {}: {} ({} scans)", message.robot_id(), stateName(message.state()),
                  message.message(), message.scans_processed());
    if (viewer_ && isValidRobotId(message.robot_id())) {
      viewer_->setHealth(message.robot_id(), healthOf(message));
    }
  }
}

void FusionNode::publishStatus(const GlobalMapResult& result, std::uint64_t sequence) {
  msg::FusionStatus status;
  status.fusion_id(config_.fusion_id);
  status.stamp(dds::toMsg(result.stamp));
  status.maps_received(maps_received_.load());
  status.maps_refused(rejected_.total());
  for (const auto& [kind, count] : rejected_.counts()) {
    msg::RefusalCount refusal;
    refusal.kind(kind);
    refusal.count(count);
    status.refusals().push_back(refusal);
  }
  std::uint32_t placed = 0;
  for (const Placement& placement : result.placements) {
    placed += placement.placed ? 1 : 0;
  }
  status.robots_known(static_cast<std::uint32_t>(result.placements.size()));
  status.robots_placed(placed);
  status.robots_stale(static_cast<std::uint32_t>(store_.staleCount()));
  status.global_maps_published(sequence);
  status_writer_->write(&status);
}

void FusionNode::publish(const GlobalMapResult& result, std::uint64_t sequence) {
  publishStatus(result, sequence);
  msg::GlobalMap message;
  message.sequence_number(sequence);
  message.stamp(dds::toMsg(result.stamp));
  message.reference_robot(result.reference_robot);
  dds::gridToMsg(result.map, message.info(), message.data());
  for (const Placement& placement : result.placements) {
    msg::RobotPlacement robot;
    robot.robot_id(placement.robot_id);
    robot.placed(placement.placed);
    robot.T_reference_robot(dds::toMsg(placement.T_reference_robot));
    robot.verification(placement.verification.value_or(0.0));
    message.robots().push_back(robot);
  }
  global_map_writer_->write(&message);
  if (ros_map_writer_ != nullptr) {
    nav_msgs::msg::dds_::OccupancyGrid_ ros_map;
    dds::toRosOccupancyGrid(result.map, result.stamp, config_.ros2_frame_id, ros_map);
    ros_map_writer_->write(&ros_map);
  }
}

}  // namespace mrslam::fusion

namespace mrslam::fusion {

void FusionNode::publishAttempt(const MergeAttempt& attempt) {
  msg::PairwiseTransform transform;
  transform.from_robot(attempt.from);
  transform.to_robot(attempt.to);
  transform.accepted(attempt.result.accepted);
  transform.T_to_from(dds::toMsg(attempt.T_to_from));
  transform.verification(attempt.result.verification);
  transform.entropy(attempt.result.entropy);
  transform.trials(static_cast<std::uint32_t>(attempt.result.trials));
  transform.method(attempt.result.method);
  transform.reason(attempt.result.reason);
  transforms_writer_->write(&transform);
}

void FusionNode::flush(double timeout_s) {
  const eprosima::fastrtps::Duration_t timeout(timeout_s);
  for (DataWriter* writer : {global_map_writer_, transforms_writer_, ros_map_writer_}) {
    if (writer != nullptr &&
        writer->wait_for_acknowledgments(timeout) != ReturnCode_t::RETCODE_OK) {
      spdlog::warn("fusion: a reader of {} did not acknowledge within {} s",
                   writer->get_topic()->get_name(), timeout_s);
    }
  }
}

}  // namespace mrslam::fusion
