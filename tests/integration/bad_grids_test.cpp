// Wrong grids from the network: a fusion agent (its own process) refuses, counts and never
// merges a local map whose header disagrees with its data, whose origin is not a number, whose
// cells are out of range or whose robot is not on the allow-list; good maps still get through,
// and the agent's health on mrslam/fusion_status counts what it refused.

#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>

#include "agent_processes.hpp"
#include "mrslam/dds/convert.hpp"
#include "mrslam/dds/participant.hpp"
#include "mrslam/dds/topics.hpp"
#include "mrslam_msgsPubSubTypes.h"

namespace mrslam::test {
namespace {

msg::LocalMap goodMap(const std::string& robot, std::uint64_t sequence) {
  GridMap grid;
  grid.geometry.resolution_m = 0.05;
  grid.geometry.width = 60;
  grid.geometry.height = 40;
  grid.cells.assign(60 * 40, 0);
  grid.cells[5] = 100;
  msg::LocalMap map;
  map.robot_id(robot);
  map.sequence_number(sequence);
  map.stamp(dds::toMsg(Stamp::fromSeconds(static_cast<double>(sequence))));
  map.is_final(true);
  dds::gridToMsg(grid, map.info(), map.data());
  return map;
}

TEST(BadGridsTest, WrongGridsAreRefusedCountedAndNeverMerged) {
  const auto out = scratchFolder("bad");
  const int domain = privateDomain();
  const std::string config = (out / "fusion.yaml").string();
  std::ofstream(config)
      << "fusion_id: guard\nreference_robot: robot1\nlimits:\n"
      << "  allowed_robots:\n    - id: robot1\n    - id: robot2\n    - id: robot3\n"
      << "    - id: robot4\n    - id: robot5\n"
      << "output:\n  folder: " << (out / "fusion").string() << "\n"
      << "dds:\n  domain_id: " << domain
      << "\n  profiles_file: " << sourcePath("config/dds/profiles.xml") << "\n";
  auto fusion = startAgent("fusion_agent/fusion_agent", {"--config", config, "--max-runtime", "60"},
                           (out / "fusion.log").string());
  DdsSettings settings;
  settings.domain_id = domain;
  settings.profiles_file = sourcePath("config/dds/profiles.xml");
  dds::Participant participant(settings, "bad grid sender");
  auto* writer = participant.createWriter<msg::LocalMapPubSubType>(dds::kLocalMapTopic,
                                                                   dds::kMapWriterProfile);
  auto* status_reader = participant.createReader<msg::FusionStatusPubSubType>(
      dds::kFusionStatusTopic, dds::kStateReaderProfile, nullptr);
  ASSERT_TRUE(dds::waitForReaders(writer, 1, 30.0)) << logOf(*fusion);

  msg::LocalMap short_data = goodMap("robot2", 1);
  short_data.data().pop_back();  // width × height says one cell more
  msg::LocalMap nan_origin = goodMap("robot3", 2);
  nan_origin.info().origin().x(std::numeric_limits<double>::quiet_NaN());
  msg::LocalMap bad_resolution = goodMap("robot4", 3);
  bad_resolution.info().resolution(-0.05);
  msg::LocalMap bad_cell = goodMap("robot5", 4);
  bad_cell.data()[7] = 101;
  msg::LocalMap outsider = goodMap("intruder", 1);  // not on the allow-list
  msg::LocalMap good = goodMap("robot1", 1);
  // One robot each (the writer keeps the newest sample of every robot).
  for (msg::LocalMap* map : {&short_data, &nan_origin, &bad_resolution, &bad_cell, &outsider}) {
    ASSERT_TRUE(writer->write(map));
  }
  ASSERT_TRUE(writer->write(&good));
  ASSERT_TRUE(waitForLog(out / "fusion.log", "first map of robot1 received", 1, 30.0))
      << logOf(*fusion);
  // The agent's health on DDS says the same (the global map with robot1 carries it).
  msg::FusionStatus status;
  bool counted = false;
  for (int wait = 0; wait < 300 && !counted; ++wait) {
    eprosima::fastdds::dds::SampleInfo info;
    status_reader->wait_for_unread_message({0, 100'000'000});
    while (status_reader->take_next_sample(&status, &info) ==
           eprosima::fastrtps::types::ReturnCode_t::RETCODE_OK) {
      counted = counted || (info.valid_data && status.maps_received() == 6);
    }
  }
  ASSERT_TRUE(counted) << logOf(*fusion);
  EXPECT_EQ(status.fusion_id(), "guard");
  EXPECT_EQ(status.maps_refused(), 5u);
  ASSERT_EQ(status.refusals().size(), 2u);
  EXPECT_EQ(status.refusals()[0].kind(), "bad grid");
  EXPECT_EQ(status.refusals()[0].count(), 4u);
  EXPECT_EQ(status.refusals()[1].kind(), "robot not allowed");
  EXPECT_EQ(status.robots_known(), 1u);
  EXPECT_EQ(status.robots_placed(), 1u);
  fusion->signal(SIGINT);
  ASSERT_EQ(finish(*fusion, 60.0), 0) << logOf(*fusion);

  // Each refusal counted by its kind (the first of a kind is logged with its reason); only
  // the good map in the outputs.
  EXPECT_TRUE(
      waitForLog(out / "fusion.log", "(5 maps refused: bad grid 4, robot not allowed 1)", 1, 0.0))
      << logOf(*fusion);
  EXPECT_TRUE(waitForLog(out / "fusion.log", "robot 'intruder' is not in allowed_robots", 1, 0.0));
  EXPECT_TRUE(waitForLog(out / "fusion.log",
                         "map of 'robot2': header says 60 x 40 cells, data holds 2399", 1, 0.0));
  std::ifstream robots_file(out / "fusion" / "robots.json");
  const nlohmann::json robots = nlohmann::json::parse(robots_file);
  ASSERT_EQ(robots["robots"].size(), 1u) << robots.dump();
  EXPECT_EQ(robots["robots"][0]["id"], "robot1");
}

}  // namespace
}  // namespace mrslam::test
