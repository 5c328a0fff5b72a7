// ROS 2 tools see the global map with no bridge: a participant in this test process subscribes
// to "rt/map" with ROS 2's exact type (nav_msgs::msg::dds_::OccupancyGrid_) while a fusion agent
// and two robot agents run as separate processes, and checks the content against the global
// map the fusion agent writes.

#include <gtest/gtest.h>

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <mutex>

#include "agent_processes.hpp"
#include "mrslam/common/map_io.hpp"
#include "mrslam/dds/participant.hpp"
#include "mrslam/dds/ros2_convert.hpp"
#include "mrslam/dds/topics.hpp"
#include "ros2_msgsPubSubTypes.h"

namespace mrslam::test {
namespace {

using namespace eprosima::fastdds::dds;

// Keeps the newest map received on rt/map.
class RosMapListener : public DataReaderListener {
 public:
  void on_data_available(DataReader* reader) override {
    nav_msgs::msg::dds_::OccupancyGrid_ message;
    SampleInfo info;
    while (reader->take_next_sample(&message, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) {
        std::lock_guard<std::mutex> lock(mutex_);
        newest_ = message;
        ++received_;
      }
    }
  }
  nav_msgs::msg::dds_::OccupancyGrid_ newest() {
    std::lock_guard<std::mutex> lock(mutex_);
    return newest_;
  }
  int received() {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }

 private:
  std::mutex mutex_;
  nav_msgs::msg::dds_::OccupancyGrid_ newest_;
  int received_ = 0;
};

TEST(Ros2TopicsTest, TheGlobalMapArrivesOnRtMapAsANavMsgsOccupancyGrid) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/breezyslam-exp1.dat");
  const auto out = scratchFolder("out");
  const int domain = privateDomain();
  DdsSettings settings;
  settings.domain_id = domain;
  settings.profiles_file = sourcePath("config/dds/profiles.xml");
  dds::Participant participant(settings, "ros2 tool");
  RosMapListener listener;
  DataReader* reader = participant.createReader<nav_msgs::msg::dds_::OccupancyGrid_PubSubType>(
      dds::kRosMapTopic, dds::kStateReaderProfile, &listener);
  ASSERT_EQ(reader->get_topicdescription()->get_type_name(), "nav_msgs::msg::dds_::OccupancyGrid_");

  auto fusion = startAgent("fusion_agent/fusion_agent",
                           {"--config", sourcePath("config/breezyslam_fusion.yaml"), "--domain",
                            std::to_string(domain), "--out", out.string(), "--max-runtime", "120"},
                           (out / "fusion.log").string());
  std::vector<std::unique_ptr<tools::ChildProcess>> robots;
  for (const std::string robot : {"exp1", "exp2"}) {
    robots.push_back(startAgent(
        "robot_agent/robot_agent",
        {"--config", sourcePath("config/breezyslam_" + robot + ".yaml"), "--log",
         sharedDataPath("logs/breezyslam-" + robot + ".dat"), "--domain", std::to_string(domain)},
        (out / (robot + ".log")).string()));
  }
  for (auto& robot : robots) {
    ASSERT_EQ(finish(*robot, 120.0), 0) << logOf(*robot);
  }
  ASSERT_EQ(finish(*fusion, 120.0), 0) << logOf(*fusion);
  reader->set_listener(nullptr);

  ASSERT_GT(listener.received(), 0) << "nothing arrived on rt/map";
  const nav_msgs::msg::dds_::OccupancyGrid_ message = listener.newest();
  const GridMap written = loadMapYaml((out / "global_map.yaml").string());
  EXPECT_EQ(message.header().frame_id(), "map");
  EXPECT_FLOAT_EQ(message.info().resolution(), static_cast<float>(written.geometry.resolution_m));
  ASSERT_EQ(message.info().width(), static_cast<std::uint32_t>(written.geometry.width));
  ASSERT_EQ(message.info().height(), static_cast<std::uint32_t>(written.geometry.height));
  EXPECT_NEAR(message.info().origin().position().x(), written.geometry.origin_m.x(), 1e-9);
  EXPECT_NEAR(message.info().origin().position().y(), written.geometry.origin_m.y(), 1e-9);
  EXPECT_DOUBLE_EQ(message.info().origin().orientation().w(), 1.0);
  ASSERT_EQ(message.data().size(), written.cells.size());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < written.cells.size(); ++i) {
    differing += static_cast<std::int8_t>(message.data()[i]) != written.cells[i];
  }
  EXPECT_EQ(differing, 0u) << "cells of rt/map differ from global_map.yaml";
}

}  // namespace
}  // namespace mrslam::test
