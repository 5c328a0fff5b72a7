// Sightings that arrive after the final maps: a robot's map and its sightings travel on two
// topics with no order between them, so a fusion agent (its own process) that holds every final
// map waits for the sightings those maps count before it finishes; the late rendezvous is
// checked against the maps and places the robot. Sightings that never come end the wait with a
// warning, and the robot stays unplaced.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <thread>

#include "agent_processes.hpp"
#include "map_window.hpp"
#include "mrslam/common/map_loaders.hpp"
#include "mrslam/dds/convert.hpp"
#include "mrslam/dds/participant.hpp"
#include "mrslam/dds/topics.hpp"
#include "mrslam_msgsPubSubTypes.h"
#include "test_data.hpp"

namespace mrslam::test {
namespace {

namespace fs = std::filesystem;

constexpr double kResolutionM = 0.05;

msg::LocalMap finalMap(const std::string& robot, const GridMap& grid, std::uint64_t sightings) {
  msg::LocalMap map;
  map.robot_id(robot);
  map.sequence_number(1);
  map.stamp(dds::toMsg(Stamp::fromSeconds(10.0)));
  map.is_final(true);
  map.sightings_published(sightings);
  dds::gridToMsg(grid, map.info(), map.data());
  return map;
}

/// The sighting `observer` (at T_map_observer in its own map frame) makes of a robot at
/// p_map_observed (the same map frame).
msg::RobotSightingMsg sightingOf(const std::string& observer, const std::string& observed,
                                 const SE2& T_map_observer, const Eigen::Vector2d& p_map_observed) {
  const Eigen::Vector2d p = T_map_observer.inverse() * p_map_observed;
  msg::RobotSightingMsg message;
  message.observer_id(observer);
  message.observed_id(observed);
  message.stamp(dds::toMsg(Stamp::fromSeconds(8.0)));
  message.range_m(p.norm());
  message.bearing_rad(std::atan2(p.y(), p.x()));
  message.T_map_observer(dds::toMsg(T_map_observer));
  return message;
}

/// Two robots' final maps (overlapping crops of the intel map, robot2's frame shifted by
/// T_robot1_robot2), each counting one sighting, and the two sightings sent `delay_s` later
/// (none when `send_sightings` is false).
class LateSightingsTest : public ::testing::Test {
 protected:
  const SE2 T_robot1_robot2{80 * kResolutionM, 50 * kResolutionM, 0.0};

  void runTeam(const std::string& name, bool send_sightings, double delay_s) {
    out_ = scratchFolder(name);
    const int domain = privateDomain();
    const fs::path config = out_ / "fusion.yaml";
    std::ofstream(config) << "fusion_id: fusion\nreference_robot: robot1\n"
                             "expected_robots:\n  - id: robot1\n  - id: robot2\n"
                             "exit_when_final: true\npublish_period_s: 0.5\n"
                             "merge:\n  method: none\n"
                             "output:\n  folder: "
                          << (out_ / "fusion").string() << "\ndds:\n  domain_id: " << domain
                          << "\n  profiles_file: " << sourcePath("config/dds/profiles.xml") << "\n";
    auto fusion = startAgent("fusion_agent/fusion_agent",
                             {"--config", config.string(), "--max-runtime", "60"},
                             (out_ / "fusion.log").string());
    DdsSettings settings;
    settings.domain_id = domain;
    settings.profiles_file = sourcePath("config/dds/profiles.xml");
    dds::Participant participant(settings, "late sightings");
    auto* map_writer = participant.createWriter<msg::LocalMapPubSubType>(dds::kLocalMapTopic,
                                                                         dds::kMapWriterProfile);
    auto* sighting_writer = participant.createWriter<msg::RobotSightingMsgPubSubType>(
        dds::kRendezvousTopic, dds::kSightingWriterProfile);
    ASSERT_TRUE(dds::waitForReaders(map_writer, 1, 30.0)) << logOf(*fusion);
    ASSERT_TRUE(dds::waitForReaders(sighting_writer, 1, 30.0)) << logOf(*fusion);

    const GridMap intel = loadMapFile(sharedDataPath("maps/freiburg-intel.pgm"));
    msg::LocalMap map1 = finalMap("robot1", cropWindow(intel, 250, 250, 300), 1);
    msg::LocalMap map2 = finalMap("robot2", cropWindow(intel, 330, 300, 300), 1);
    ASSERT_TRUE(map_writer->write(&map1));
    ASSERT_TRUE(map_writer->write(&map2));
    ASSERT_TRUE(waitForLog(out_ / "fusion.log", "first map of robot2 received", 1, 30.0))
        << logOf(*fusion);
    std::this_thread::sleep_for(std::chrono::duration<double>(delay_s));
    if (send_sightings) {
      // Robot1 at (6.0, 5.0) of its map sees robot2 1.3 m away; robot2 sees it back.
      const SE2 T_robot1_at1(6.0, 5.0, 0.3);
      const SE2 T_robot1_at2(7.2, 5.5, 2.0);
      const SE2 T_robot2_at2 = T_robot1_robot2.inverse() * T_robot1_at2;
      const Eigen::Vector2d p_robot2_at1 = T_robot1_robot2.inverse() * T_robot1_at1.translation();
      msg::RobotSightingMsg seen_by1 =
          sightingOf("robot1", "robot2", T_robot1_at1, T_robot1_at2.translation());
      msg::RobotSightingMsg seen_by2 = sightingOf("robot2", "robot1", T_robot2_at2, p_robot2_at1);
      ASSERT_TRUE(sighting_writer->write(&seen_by1));
      ASSERT_TRUE(sighting_writer->write(&seen_by2));
    }
    exit_code_ = finish(*fusion, 60.0);
    log_ = logOf(*fusion);
    std::ifstream file(out_ / "fusion" / "transforms.json");
    transforms_ = nlohmann::json::parse(file);
  }

  /// robot2's entry of transforms.json.
  nlohmann::json robot2() const {
    for (const auto& robot : transforms_["robots"]) {
      if (robot["id"] == "robot2") {
        return robot;
      }
    }
    return {};
  }

  fs::path out_;
  int exit_code_ = -1;
  std::string log_;
  nlohmann::json transforms_;
};

TEST_F(LateSightingsTest, SightingsAfterTheFinalMapsStillPlaceTheRobot) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  ASSERT_NO_FATAL_FAILURE(runTeam("late_sightings", true, 1.5));
  ASSERT_EQ(exit_code_, 0) << log_;
  EXPECT_NE(log_.find("waiting up to 5 s for the sightings they count: robot1 (0 of 1), robot2 "
                      "(0 of 1)"),
            std::string::npos)
      << log_;
  const nlohmann::json robot = robot2();
  ASSERT_TRUE(robot["placed"].get<bool>()) << log_;
  EXPECT_EQ(robot["methods"], "rendezvous");
  EXPECT_NEAR(robot["x"].get<double>(), T_robot1_robot2.x(), 0.1);
  EXPECT_NEAR(robot["y"].get<double>(), T_robot1_robot2.y(), 0.1);
  EXPECT_NEAR(wrapAngle(robot["theta"].get<double>()), 0.0, M_PI / 180.0);
  EXPECT_EQ(log_.find("finishing without them"), std::string::npos) << log_;
}

TEST_F(LateSightingsTest, SightingsThatNeverComeEndTheWaitWithAWarning) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  ASSERT_NO_FATAL_FAILURE(runTeam("lost_sightings", false, 0.0));
  ASSERT_EQ(exit_code_, 0) << log_;
  EXPECT_NE(log_.find("sightings the robots wrote are still missing after 5 s: robot1 (0 of 1), "
                      "robot2 (0 of 1) (received of written); finishing without them"),
            std::string::npos)
      << log_;
  EXPECT_FALSE(robot2()["placed"].get<bool>()) << log_;
}

}  // namespace
}  // namespace mrslam::test
