#include "mrslam/tools/team_spec.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

#include "mrslam/common/config.hpp"
#include "test_data.hpp"

namespace mrslam::tools {
namespace {

using ::testing::HasSubstr;

std::string writeTeam(const std::string& text) {
  const auto folder = test::scratchFolder("team");
  const std::string path = (folder / "team.yaml").string();
  std::ofstream(path) << text;
  return path;
}

std::string loadError(const std::string& text) {
  try {
    loadTeamSpec(writeTeam(text));
  } catch (const ConfigError& error) {
    return error.what();
  }
  return "no error";
}

TEST(TeamSpecTest, ReadsRobotsFusionAndTheSplitWithPathsFromTheFilesFolder) {
  const std::string path = writeTeam(
      "domain_id: 44\nsplit:\n  log: logs/intel.log\n  segments: 3\nrobots:\n"
      "  - config: robot.yaml\n    id: robot1\n    segment: 1\n"
      "  - config: /abs/robot.yaml\n    id: robot2\n    log: two.log\n"
      "  - config: sim_robot3.yaml\nfusion:\n  - config: fusion.yaml\nfinal_grace_s: 5\n");
  const TeamSpec team = loadTeamSpec(path);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  ASSERT_TRUE(team.domain_id.has_value());
  EXPECT_EQ(*team.domain_id, 44);
  ASSERT_TRUE(team.split.has_value());
  EXPECT_EQ(team.split->segments, 3);
  EXPECT_EQ(std::filesystem::path(team.split->log), folder / "logs/intel.log");
  ASSERT_EQ(team.robots.size(), 3u);
  EXPECT_EQ(std::filesystem::path(team.robots[0].config), folder / "robot.yaml");
  EXPECT_EQ(team.robots[0].segment, 1);
  EXPECT_EQ(team.robots[0].name, "robot1");
  EXPECT_EQ(team.robots[1].config, "/abs/robot.yaml");
  EXPECT_EQ(std::filesystem::path(team.robots[1].log), folder / "two.log");
  EXPECT_FALSE(team.robots[1].segment.has_value());
  EXPECT_EQ(team.robots[2].name, "sim_robot3");  // no id: the config's name
  ASSERT_EQ(team.fusion.size(), 1u);
  EXPECT_EQ(team.fusion[0].name, "fusion");
  EXPECT_DOUBLE_EQ(team.final_grace_s, 5.0);
}

TEST(TeamSpecTest, ARobotOnEmulatedDevicesNamesWhatTheyPlay) {
  const std::string path = writeTeam(
      "robots:\n  - config: emulated_robot.yaml\n    id: robot1\n    emulate: sim_robot1.yaml\n"
      "    emulate_log: logs/intel.log\n    emulate_duration_s: 40\n"
      "  - config: sim_robot2.yaml\n");
  const TeamSpec team = loadTeamSpec(path);
  const std::filesystem::path folder = std::filesystem::path(path).parent_path();
  ASSERT_EQ(team.robots.size(), 2u);
  EXPECT_EQ(std::filesystem::path(team.robots[0].emulate), folder / "sim_robot1.yaml");
  EXPECT_EQ(std::filesystem::path(team.robots[0].emulate_log), folder / "logs/intel.log");
  EXPECT_DOUBLE_EQ(team.robots[0].emulate_duration_s, 40.0);
  EXPECT_TRUE(team.robots[1].emulate.empty());
  EXPECT_THAT(loadError("robots:\n  - config: a.yaml\n    emulate_log: x.log\n"),
              HasSubstr("team.yaml:3: robots[0].emulate_log: needs `emulate:`"));
  EXPECT_THAT(loadError("robots:\n  - config: a.yaml\n    emulate: s.yaml\n    log: x.log\n"),
              HasSubstr("robots[0].emulate: a robot on emulated devices replays no log"));
  EXPECT_THAT(loadError("robots:\n  - config: a.yaml\n    emulate: s.yaml\n"
                        "    emulate_duration_s: -1\n"),
              HasSubstr("robots[0].emulate_duration_s: -1 is out of range"));
}

TEST(TeamSpecTest, ATeamMayBringItsDiscoveryServer) {
  const TeamSpec team =
      loadTeamSpec(writeTeam("discovery_server:\n  address: 10.0.0.5\n  port: 12000\nrobots:\n"
                             "  - config: a.yaml\n"));
  ASSERT_TRUE(team.discovery_server.has_value());
  EXPECT_EQ(team.discovery_server->address, "10.0.0.5");
  EXPECT_EQ(team.discovery_server->port, 12000);
  const TeamSpec defaults =
      loadTeamSpec(writeTeam("discovery_server: {}\nrobots:\n  - config: a.yaml\n"));
  ASSERT_TRUE(defaults.discovery_server.has_value());
  EXPECT_EQ(defaults.discovery_server->address, "127.0.0.1");
  EXPECT_EQ(defaults.discovery_server->port, 11811);
  EXPECT_FALSE(loadTeamSpec(writeTeam("robots:\n  - config: a.yaml\n")).discovery_server);
  const std::string secured = writeTeam("security_dir: pki\nrobots:\n  - config: a.yaml\n");
  EXPECT_EQ(std::filesystem::path(loadTeamSpec(secured).security_dir),
            std::filesystem::path(secured).parent_path() / "pki");
  EXPECT_THAT(loadError("discovery_server:\n  address: host\nrobots:\n  - config: a.yaml\n"),
              HasSubstr("team.yaml:2: discovery_server.address: 'host' is not an IPv4 address"));
  EXPECT_THAT(loadError("discovery_server:\n  port: 0\nrobots:\n  - config: a.yaml\n"),
              HasSubstr("discovery_server.port: 0 is out of range"));
}

TEST(TeamSpecTest, MistakesNameFileLineAndKey) {
  EXPECT_THAT(loadError("robots:\n  - config: a.yaml\n    segment: 1\n"),
              HasSubstr("team.yaml:3: robots[0].segment: needs a `split:` section"));
  EXPECT_THAT(loadError("split:\n  log: x.log\n  segments: 2\nrobots:\n  - config: a.yaml\n"
                        "    segment: 3\n"),
              HasSubstr("team.yaml:6: robots[0].segment: 3 is out of range"));
  EXPECT_THAT(loadError("robots:\n  - id: r1\n"), HasSubstr("robots[0].config: every robot"));
  EXPECT_THAT(loadError("robots:\n  - config: a.yaml\n  - config: b/a.yaml\n"),
              HasSubstr("two robots are named 'a'"));
  EXPECT_THAT(loadError("robots:\n  - config: a.yaml\n    id: ../x\n"),
              HasSubstr("robots[0].id: '../x' is not a robot id"));
  EXPECT_THAT(loadError("robot:\n  - config: a.yaml\n"), HasSubstr("the team has no agent"));
  EXPECT_THAT(loadError("robots:\n  - config: a.yaml\ndomain: 3\n"),
              HasSubstr("team.yaml:3: domain: unknown key"));
  EXPECT_THAT(loadError("domain_id: 300\nrobots:\n  - config: a.yaml\n"),
              HasSubstr("team.yaml:1: domain_id: 300 is out of range"));
}

}  // namespace
}  // namespace mrslam::tools
