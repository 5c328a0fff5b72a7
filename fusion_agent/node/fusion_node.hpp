#pragma once
// The fusion agent's DDS glue: receives every robot's local map (checked before it is stored),
// publishes the global map and the robots' placements.

#include <atomic>
#include <map>
#include <mutex>
#include <string>

#include "mrslam/common/error_counter.hpp"
#include "mrslam/dds/participant.hpp"
#include "mrslam/fusion/fusion_config.hpp"
#include "mrslam/fusion/global_map_builder.hpp"
#include "mrslam/fusion/merge_scheduler.hpp"
#include "mrslam/fusion/rendezvous.hpp"
#include "mrslam/fusion/robot_map_store.hpp"
#include "mrslam/fusion/viewer_model.hpp"

namespace mrslam::fusion {

class FusionNode : public eprosima::fastdds::dds::DataReaderListener {
 public:
  /// `viewer` (may be null) is told each robot's status.
  FusionNode(const FusionConfig& config, RobotMapStore& store, ViewerModel* viewer = nullptr);
  ~FusionNode() override;

  /// The global map, and with it the agent's health on mrslam/fusion_status.
  void publish(const GlobalMapResult& result, std::uint64_t sequence);
  /// One pairwise merge, accepted or refused, on the transforms topic.
  void publishAttempt(const MergeAttempt& attempt);

  /// Waits (up to timeout_s) until every matched reader acknowledged what was last published,
  /// so that a fusion agent about to exit does not take its last global map with it.
  void flush(double timeout_s);

  /// Maps refused, by reason.
  const ErrorCounter& rejected() const { return rejected_; }
  /// The robots' sightings of each other received so far, paired into rendezvous.
  RendezvousBook& rendezvous() { return rendezvous_; }
  /// Sightings received from `observer_id` (refused ones too), each counted once the book has
  /// taken it: a robot's final map says how many it wrote.
  std::uint64_t sightingsReceived(const std::string& observer_id) const;

  void on_data_available(eprosima::fastdds::dds::DataReader* reader) override;
  void on_liveliness_changed(
      eprosima::fastdds::dds::DataReader* reader,
      const eprosima::fastdds::dds::LivelinessChangedStatus& status) override;
  void on_subscription_matched(
      eprosima::fastdds::dds::DataReader* reader,
      const eprosima::fastdds::dds::SubscriptionMatchedStatus& status) override;

 private:
  void receiveMaps(eprosima::fastdds::dds::DataReader* reader);
  void receiveStatus(eprosima::fastdds::dds::DataReader* reader);
  void receiveSightings(eprosima::fastdds::dds::DataReader* reader);
  void countSightingOf(const std::string& observer_id);
  void publishStatus(const GlobalMapResult& result, std::uint64_t sequence);
  /// Remembers which writer sends a robot's maps; true when it is a new one (a restart).
  bool noteWriter(const std::string& robot_id,
                  const eprosima::fastrtps::rtps::InstanceHandle_t& writer);

  const FusionConfig& config_;
  RobotMapStore& store_;
  ViewerModel* const viewer_;
  ErrorCounter rejected_{"fusion: local map refused"};
  dds::Participant participant_;
  eprosima::fastdds::dds::DataReader* map_reader_ = nullptr;
  eprosima::fastdds::dds::DataReader* status_reader_ = nullptr;
  eprosima::fastdds::dds::DataReader* sighting_reader_ = nullptr;
  RendezvousBook rendezvous_;
  ErrorCounter rejected_sightings_{"fusion: sighting refused"};
  mutable std::mutex sightings_mutex_;
  std::map<std::string, std::uint64_t> sightings_received_;  ///< by observer
  eprosima::fastdds::dds::DataWriter* global_map_writer_ = nullptr;
  eprosima::fastdds::dds::DataWriter* transforms_writer_ = nullptr;
  eprosima::fastdds::dds::DataWriter* status_writer_ = nullptr;
  std::atomic<std::uint64_t> maps_received_{0};
  eprosima::fastdds::dds::DataWriter* ros_map_writer_ = nullptr;  ///< rt/map, when configured
  std::mutex writers_mutex_;  ///< guards the two maps below (listener and liveliness callbacks)
  std::map<std::string, eprosima::fastrtps::rtps::InstanceHandle_t> writer_of_robot_;
  std::map<eprosima::fastrtps::rtps::InstanceHandle_t, std::string> robot_of_writer_;
};

}  // namespace mrslam::fusion
