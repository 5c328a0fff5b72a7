// ROS 2 tools see the global map with no bridge: a participant in this test process subscribes
// to "rt/map" with ROS 2's exact type (nav_msgs::msg::dds_::OccupancyGrid_) while a fusion agent
// and two robot agents run as separate processes, and checks the content against the global
// map the fusion agent writes.

#include <gtest/gtest.h>

#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fstream>
#include <iterator>
#include <mutex>
#include <sstream>

#include "agent_processes.hpp"
#include "mrslam/common/map_io.hpp"
#include "mrslam/dds/participant.hpp"
#include "mrslam/dds/ros2_convert.hpp"
#include "mrslam/dds/topics.hpp"
#include "ros2_msgsPubSubTypes.h"

namespace mrslam::test {
namespace {

using namespace eprosima::fastdds::dds;

// Keeps the newest message received and counts them.
template <class Message>
class NewestListener : public DataReaderListener {
 public:
  void on_data_available(DataReader* reader) override {
    Message message;
    SampleInfo info;
    while (reader->take_next_sample(&message, &info) == ReturnCode_t::RETCODE_OK) {
      if (info.valid_data) {
        std::lock_guard<std::mutex> lock(mutex_);
        newest_ = message;
        ++received_;
      }
    }
  }
  Message newest() {
    std::lock_guard<std::mutex> lock(mutex_);
    return newest_;
  }
  int received() {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }

 private:
  std::mutex mutex_;
  Message newest_;
  int received_ = 0;
};

using RosMap = nav_msgs::msg::dds_::OccupancyGrid_;
using RosPose = geometry_msgs::msg::dds_::PoseWithCovarianceStamped_;

// The TUM trajectory line (timestamp x y ...) whose time stamp is `stamp`, or empty.
std::vector<double> trajectoryLineAt(const std::string& path, double stamp_s) {
  std::ifstream file(path);
  std::string line;
  while (std::getline(file, line)) {
    std::istringstream fields(line);
    std::vector<double> values{std::istream_iterator<double>(fields),
                               std::istream_iterator<double>()};
    if (values.size() == 8 && std::abs(values[0] - stamp_s) < 1e-6) {
      return values;
    }
  }
  return {};
}

TEST(Ros2TopicsTest, MapAndPosesArriveAsRos2MessagesOnRtTopics) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/breezyslam-exp1.dat");
  const auto out = scratchFolder("out");
  const int domain = privateDomain();
  DdsSettings settings;
  settings.domain_id = domain;
  settings.profiles_file = sourcePath("config/dds/profiles.xml");
  dds::Participant participant(settings, "ros2 tool");
  NewestListener<RosMap> listener;
  DataReader* reader = participant.createReader<nav_msgs::msg::dds_::OccupancyGrid_PubSubType>(
      dds::kRosMapTopic, dds::kStateReaderProfile, &listener);
  ASSERT_EQ(reader->get_topicdescription()->get_type_name(), "nav_msgs::msg::dds_::OccupancyGrid_");
  NewestListener<RosPose> pose_listener;
  DataReader* pose_reader =
      participant.createReader<geometry_msgs::msg::dds_::PoseWithCovarianceStamped_PubSubType>(
          dds::rosPoseTopic("exp1"), dds::kRosPoseReaderProfile, &pose_listener);
  ASSERT_EQ(pose_reader->get_topicdescription()->get_type_name(),
            "geometry_msgs::msg::dds_::PoseWithCovarianceStamped_");

  auto fusion = startAgent("fusion_agent/fusion_agent",
                           {"--config", sourcePath("config/breezyslam_fusion.yaml"), "--domain",
                            std::to_string(domain), "--out", out.string(), "--max-runtime", "120"},
                           (out / "fusion.log").string());
  std::vector<std::unique_ptr<tools::ChildProcess>> robots;
  // At 20× the log's clock (about 4 s a log): poses are volatile, so they reach only readers
  // matched while the robot replays; as fast as possible (0.1 s) that raced the discovery of
  // this test's reader under load.
  for (const std::string robot : {"exp1", "exp2"}) {
    robots.push_back(startAgent(
        "robot_agent/robot_agent",
        {"--config", sourcePath("config/breezyslam_" + robot + ".yaml"), "--log",
         sharedDataPath("logs/breezyslam-" + robot + ".dat"), "--domain", std::to_string(domain),
         "--speed", "20", "--trajectory-out", (out / (robot + ".tum")).string()},
        (out / (robot + ".log")).string()));
  }
  for (auto& robot : robots) {
    ASSERT_EQ(finish(*robot, 120.0), 0) << logOf(*robot);
  }
  ASSERT_EQ(finish(*fusion, 120.0), 0) << logOf(*fusion);
  reader->set_listener(nullptr);
  pose_reader->set_listener(nullptr);

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

  // The last pose of exp1 on rt/exp1/pose: in its own map frame, equal to the trajectory's pose
  // at that time stamp, with a covariance of positive variances.
  ASSERT_GT(pose_listener.received(), 0) << "nothing arrived on rt/exp1/pose";
  const RosPose pose = pose_listener.newest();
  EXPECT_EQ(pose.header().frame_id(), "exp1/map");
  const double stamp_s = pose.header().stamp().sec() + 1e-9 * pose.header().stamp().nanosec();
  const std::vector<double> tum = trajectoryLineAt((out / "exp1.tum").string(), stamp_s);
  ASSERT_EQ(tum.size(), 8u) << "no trajectory line at " << stamp_s;
  EXPECT_NEAR(pose.pose().pose().position().x(), tum[1], 1e-6);
  EXPECT_NEAR(pose.pose().pose().position().y(), tum[2], 1e-6);
  EXPECT_NEAR(pose.pose().pose().orientation().z(), tum[6], 1e-6);
  EXPECT_NEAR(pose.pose().pose().orientation().w(), tum[7], 1e-6);
  EXPECT_GT(pose.pose().covariance()[0], 0.0);
  EXPECT_GT(pose.pose().covariance()[7], 0.0);
  EXPECT_GT(pose.pose().covariance()[35], 0.0);
}

}  // namespace
}  // namespace mrslam::test
