// A robot agent killed mid-run (no goodbye): the fusion agent notices it after the map writer's
// lease, keeps its last map in the global map flagged as stale; a new agent of the same robot,
// numbering its maps from 1 again, is taken back.

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "agent_processes.hpp"
#include "mrslam/common/map_io.hpp"

namespace mrslam::test {
namespace {

TEST(StaleRobotTest, AKilledRobotIsMarkedStaleKeptInTheMapAndTakenBackWhenRestarted) {
  const auto out = scratchFolder("out");
  const std::string domain = std::to_string(privateDomain());
  const auto fusion_log = out / "fusion.log";
  auto fusion = startAgent("fusion_agent/fusion_agent",
                           {"--config", sourcePath("config/sim_fusion.yaml"), "--domain", domain,
                            "--out", out.string(), "--max-runtime", "120"},
                           fusion_log.string());
  // Real-time replay: the run lasts a minute, long enough to be cut short.
  const std::vector<std::string> robot_arguments = {
      "--config", sourcePath("config/sim_robot1.yaml"), "--domain", domain, "--speed", "1"};
  auto robot =
      startAgent("robot_agent/robot_agent", robot_arguments, (out / "robot1.log").string());
  ASSERT_TRUE(waitForLog(fusion_log, "first map of robot1 received")) << logOf(*fusion);
  robot->signal(SIGKILL);
  ASSERT_TRUE(waitForLog(fusion_log, "robot1 fell silent")) << logOf(*fusion);

  auto restarted =
      startAgent("robot_agent/robot_agent", robot_arguments, (out / "robot1-again.log").string());
  ASSERT_TRUE(waitForLog(fusion_log, "robot1 sends from a new agent")) << logOf(*fusion);
  restarted->signal(SIGKILL);
  ASSERT_TRUE(waitForLog(fusion_log, "robot1 fell silent", 2)) << logOf(*fusion);

  fusion->signal(SIGINT);  // it writes its files and stops
  ASSERT_EQ(finish(*fusion, 60.0), 0) << logOf(*fusion);
  std::ifstream file(out / "robots.json");
  const nlohmann::json robots = nlohmann::json::parse(file);
  ASSERT_EQ(robots["robots"].size(), 1u);
  EXPECT_EQ(robots["robots"][0]["id"], "robot1");
  EXPECT_TRUE(robots["robots"][0]["stale"].get<bool>());
  EXPECT_FALSE(robots["robots"][0]["final"].get<bool>());
  const GridMap global = loadMapYaml((out / "global_map.yaml").string());
  std::size_t known = 0;
  for (const std::int8_t cell : global.cells) {
    known += cell != GridMap::kUnknown;
  }
  EXPECT_GT(known, 100u) << "the stale robot's last map stays in the global map";
}

}  // namespace
}  // namespace mrslam::test
