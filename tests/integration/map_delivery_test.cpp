// A robot agent leaves only once as many fusion agents as it waits for (--delivery-readers, the
// team launcher's count of the team's fusion agents) hold its final map: with two fusion agents
// and a robot that waited for one, the second could miss the robot altogether when it discovered
// it late. The robot's sightings are waited for alike.

#include <gtest/gtest.h>

#include <fstream>
#include <regex>

#include "agent_processes.hpp"

namespace mrslam::test {
namespace {

/// Simulated robot 1 with a short wait for the fusion agents at the end.
std::string robotConfig(const std::filesystem::path& folder) {
  std::string text = fileText(sourcePath("config/sim_robot1.yaml"));
  text = std::regex_replace(text, std::regex("delivery_timeout_s: 60"), "delivery_timeout_s: 6");
  text += "  profiles_file: " + sourcePath("config/dds/profiles.xml") + "\n";
  const std::string path = (folder / "robot1.yaml").string();
  std::ofstream(path) << text;
  return path;
}

/// The sequence number of robot1's final map a fusion log reports ("" when none).
std::string finalSequence(const std::filesystem::path& log) {
  std::smatch match;
  const std::string text = fileText(log);
  return std::regex_search(text, match, std::regex("final map ([0-9]+) of robot1 received"))
             ? match[1].str()
             : "";
}

struct DeliveryRun {
  int robot_exit = -1;
  std::string robot_log;
  std::vector<std::string> final_sequences;  ///< per fusion agent
};

DeliveryRun runWithFusionAgents(const std::string& name, int fusion_agents) {
  const auto out = scratchFolder(name);
  const std::string domain = std::to_string(privateDomain());
  std::vector<std::unique_ptr<tools::ChildProcess>> fusion;
  for (int k = 0; k < fusion_agents; ++k) {
    const std::string id = "fusion" + std::to_string(k + 1);
    fusion.push_back(startAgent("fusion_agent/fusion_agent",
                                {"--config", sourcePath("config/sim_fusion.yaml"), "--domain",
                                 domain, "--out", (out / id).string(), "--max-runtime", "90"},
                                (out / (id + ".log")).string()));
  }
  auto robot =
      startAgent("robot_agent/robot_agent",
                 {"--config", robotConfig(out), "--domain", domain, "--delivery-readers", "2"},
                 (out / "robot1.log").string());
  DeliveryRun run;
  run.robot_exit = finish(*robot, 60.0);
  run.robot_log = fileText(out / "robot1.log");
  for (int k = 0; k < fusion_agents; ++k) {
    const std::string id = "fusion" + std::to_string(k + 1);
    waitForLog(out / (id + ".log"), "final map", 1, 10.0);
    run.final_sequences.push_back(finalSequence(out / (id + ".log")));
    fusion[static_cast<std::size_t>(k)]->stop(5.0);
  }
  return run;
}

TEST(MapDeliveryTest, ARobotWaitingForTwoFusionAgentsLeavesOnceBothHoldItsFinalMap) {
  const DeliveryRun run = runWithFusionAgents("two_fusion_agents", 2);
  EXPECT_EQ(run.robot_exit, 0) << run.robot_log;
  EXPECT_NE(run.robot_log.find("for 2 fusion agent(s) to hold the final map"), std::string::npos)
      << run.robot_log;
  ASSERT_EQ(run.final_sequences.size(), 2u);
  EXPECT_FALSE(run.final_sequences[0].empty());
  EXPECT_EQ(run.final_sequences[0], run.final_sequences[1]) << "both hold the same final map";
}

TEST(MapDeliveryTest, ARobotWaitingForTwoFusionAgentsReportsWhenOnlyOneTookItsFinalMap) {
  const DeliveryRun run = runWithFusionAgents("one_fusion_agent", 1);
  EXPECT_EQ(run.robot_exit, 3) << run.robot_log;
  EXPECT_NE(run.robot_log.find(
                "fewer than 2 fusion agent(s) took the final map and sightings within 6 s"),
            std::string::npos)
      << run.robot_log;
  ASSERT_EQ(run.final_sequences.size(), 1u);
  EXPECT_FALSE(run.final_sequences[0].empty()) << "the one fusion agent did get it";
}

// The sightings (mrslam/rendezvous) reach the fusion agent on readers that match apart from its
// map reader: a robot that left once its final map was taken could take its sightings with it
// (the demo's fusion agent then never heard robot1 see anyone). A fusion agent that joins only
// after the robot's run must get all of them before the robot leaves.
TEST(MapDeliveryTest, ARobotLeavesOnceTheFusionAgentHoldsItsSightingsToo) {
  const auto out = scratchFolder("late_fusion_agent");
  const std::string domain = std::to_string(privateDomain());
  auto robot =
      startAgent("robot_agent/robot_agent",
                 {"--config", robotConfig(out), "--domain", domain, "--delivery-readers", "1"},
                 (out / "robot1.log").string());
  ASSERT_TRUE(waitForLog(out / "robot1.log", "sightings written", 1, 30.0)) << logOf(*robot);
  std::smatch written;
  const std::string robot_log = fileText(out / "robot1.log");
  ASSERT_TRUE(std::regex_search(robot_log, written, std::regex("the ([0-9]+) sightings written")));
  const int sightings = std::stoi(written[1].str());
  ASSERT_GT(sightings, 0) << "the simulated robot1 sees the others' routes";
  auto fusion = startAgent("fusion_agent/fusion_agent",
                           {"--config", sourcePath("config/sim_fusion.yaml"), "--domain", domain,
                            "--out", (out / "fusion").string(), "--max-runtime", "60"},
                           (out / "fusion.log").string());
  EXPECT_EQ(finish(*robot, 30.0), 0) << logOf(*robot);
  // Logged as the fusion agent takes each sighting.
  EXPECT_TRUE(waitForLog(out / "fusion.log", "robot1 saw", sightings, 5.0)) << logOf(*fusion);
  EXPECT_EQ(occurrencesIn(out / "fusion.log", "robot1 saw"), sightings) << logOf(*fusion);
  fusion->stop(5.0);
}

}  // namespace
}  // namespace mrslam::test
