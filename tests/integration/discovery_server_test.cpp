// Discovery Server mode: agents as clients of a real fast-discovery-server process find each
// other through it alone — with no server they find nothing, and once it starts they do — and a
// team file with a `discovery_server:` section runs the whole team that way.

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>

#include "agent_processes.hpp"

namespace mrslam::test {
namespace {

constexpr const char* kServerProgram = "/usr/bin/fast-discovery-server";

// A UDP port of this test process alone.
int privatePort() {
  return 20000 + static_cast<int>(getpid() % 20000);
}

TEST(DiscoveryServerTest, ClientsDiscoverEachOtherOnlyThroughTheServer) {
  ASSERT_TRUE(std::filesystem::exists(kServerProgram)) << "fastdds-tools is not installed";
  const auto out = scratchFolder("clients");
  const std::string server = "127.0.0.1:" + std::to_string(privatePort());
  const std::string domain = std::to_string(privateDomain());
  const auto fusion_log = out / "fusion.log";
  auto fusion =
      startAgent("fusion_agent/fusion_agent",
                 {"--config", sourcePath("config/sim_fusion.yaml"), "--domain", domain, "--out",
                  (out / "fusion").string(), "--discovery-server", server, "--max-runtime", "120"},
                 fusion_log.string());
  auto robot = startAgent("robot_agent/robot_agent",
                          {"--config", sourcePath("config/sim_robot1.yaml"), "--domain", domain,
                           "--speed", "1", "--discovery-server", server},
                          (out / "robot1.log").string());
  // Same host, same domain, but clients: without their server they do not meet.
  EXPECT_FALSE(waitForLog(fusion_log, "first map of robot1 received", 1, 8.0)) << logOf(*fusion);

  auto discovery = std::make_unique<tools::ChildProcess>(
      std::vector<std::string>{kServerProgram, "-i", "0", "-l", "127.0.0.1", "-p",
                               std::to_string(privatePort())},
      (out / "server.log").string());
  EXPECT_TRUE(waitForLog(fusion_log, "first map of robot1 received", 1, 30.0)) << logOf(*fusion);
  robot->signal(SIGKILL);
  fusion->signal(SIGINT);
  EXPECT_EQ(finish(*fusion, 60.0), 0) << logOf(*fusion);
  discovery->stop(5.0);
}

TEST(DiscoveryServerTest, ATeamFileStartsItsServerAndEveryAgentDiscoversThroughIt) {
  ASSERT_TRUE(std::filesystem::exists(kServerProgram)) << "fastdds-tools is not installed";
  const auto out = scratchFolder("team");
  const std::string team_file = (out / "team.yaml").string();
  std::ofstream(team_file) << "discovery_server:\n  port: " << privatePort() << "\nrobots:\n"
                           << "  - config: " << sourcePath("config/sim_robot1.yaml") << "\n"
                           << "  - config: " << sourcePath("config/sim_robot2.yaml") << "\n"
                           << "fusion:\n  - config: " << sourcePath("config/sim_fusion.yaml")
                           << "\nfinal_grace_s: 5\n";
  auto team = startAgent("tools/mrslam_team",
                         {team_file, "--bin-dir", binaryPath(""), "--out", (out / "run").string(),
                          "--domain", std::to_string(privateDomain()), "--timeout", "120"},
                         (out / "team.log").string());
  ASSERT_EQ(finish(*team, 150.0), 0) << logOf(*team);
  for (const char* agent : {"sim_robot1", "sim_robot2", "sim_fusion"}) {
    EXPECT_TRUE(waitForLog(out / "run" / "logs" / (std::string(agent) + ".log"),
                           "discovery through the server at 127.0.0.1:", 1, 0.0))
        << agent;
  }
  EXPECT_TRUE(
      waitForLog(out / "run" / "logs" / "discovery_server.log", "Server is running", 1, 0.0));
  std::ifstream robots_file(out / "run" / "robots.json");
  const nlohmann::json robots = nlohmann::json::parse(robots_file);
  ASSERT_EQ(robots["robots"].size(), 2u);
  for (const nlohmann::json& robot : robots["robots"]) {
    EXPECT_TRUE(robot["final"].get<bool>()) << robot["id"];
  }
}

}  // namespace
}  // namespace mrslam::test
