// DDS Security (PKI-DH, Access-Permissions, AES-GCM-GMAC) with the credentials of
// scripts/make_test_pki.sh: a robot and a fusion agent of one PKI exchange maps; participants
// without credentials, or with credentials from another CA, read none of the team's maps, and
// the grids they publish never reach its global map. The agents log whom they authenticated and
// whose authentication failed.

#include <gtest/gtest.h>

#include <csignal>
#include <fstream>
#include <nlohmann/json.hpp>

#include "agent_processes.hpp"

namespace mrslam::test {
namespace {

void makePki(const std::filesystem::path& dir, const std::vector<std::string>& identities) {
  std::vector<std::string> argv = {"/bin/bash", sourcePath("scripts/make_test_pki.sh"),
                                   dir.string()};
  argv.insert(argv.end(), identities.begin(), identities.end());
  tools::ChildProcess script(argv, dir.string() + ".log");
  const auto code = script.waitFor(60.0);
  ASSERT_TRUE(code.has_value());
  ASSERT_EQ(*code, 0) << tools::tailOfFile(dir.string() + ".log", 10);
}

nlohmann::json robotsOf(const std::filesystem::path& out) {
  std::ifstream file(out / "robots.json");
  return nlohmann::json::parse(file);
}

TEST(SecurityTest, OnlyParticipantsWithValidCredentialsExchangeMaps) {
  const auto out = scratchFolder("security");
  makePki(out / "pki", {"robot1", "fusion"});
  makePki(out / "rogue", {"robot2", "fusion"});  // well-formed, but another CA
  const std::string domain = std::to_string(privateDomain());
  const auto fusion = [&](const std::string& name, std::vector<std::string> security) {
    std::vector<std::string> arguments = {"--config",      sourcePath("config/sim_fusion.yaml"),
                                          "--domain",      domain,
                                          "--out",         (out / name).string(),
                                          "--max-runtime", "120"};
    arguments.insert(arguments.end(), security.begin(), security.end());
    return startAgent("fusion_agent/fusion_agent", arguments, (out / (name + ".log")).string());
  };
  auto secure = fusion("secure", {"--security-dir", (out / "pki").string()});
  auto plain = fusion("plain", {});
  auto rogue = fusion("rogue", {"--security-dir", (out / "rogue").string()});
  const auto robot = [&](int index, std::vector<std::string> security) {
    const std::string id = "robot" + std::to_string(index);
    std::vector<std::string> arguments = {
        "--config", sourcePath("config/sim_robot" + std::to_string(index) + ".yaml"), "--domain",
        domain};
    arguments.insert(arguments.end(), security.begin(), security.end());
    return startAgent("robot_agent/robot_agent", arguments, (out / (id + ".log")).string());
  };
  auto robot1 = robot(1, {"--security-dir", (out / "pki").string()});
  auto robot2 = robot(2, {"--security-dir", (out / "rogue").string()});
  auto robot3 = robot(3, {});

  ASSERT_TRUE(waitForLog(out / "secure.log", "final map 60 of robot1 received"))
      << logOf(*secure) << logOf(*robot1);
  EXPECT_EQ(finish(*robot1, 60.0), 0) << logOf(*robot1);  // its final map was acknowledged
  // robot2 and robot3 have published their whole runs by now, and wait for a reader.
  ASSERT_TRUE(waitForLog(out / "robot2.log", "maps published", 1, 30.0)) << logOf(*robot2);
  ASSERT_TRUE(waitForLog(out / "robot3.log", "maps published", 1, 30.0)) << logOf(*robot3);
  EXPECT_FALSE(waitForLog(out / "secure.log", "of robot2", 1, 3.0)) << logOf(*secure);
  EXPECT_FALSE(waitForLog(out / "secure.log", "of robot3", 1, 0.0)) << logOf(*secure);
  // Each outsider reads its own kind (the rogue robot2, the plain robot3) before it is stopped:
  // the rogue's handshake with robot2 may still be under way on a loaded machine.
  EXPECT_TRUE(waitForLog(out / "rogue.log", "first map of robot2", 1, 60.0)) << logOf(*rogue);
  EXPECT_TRUE(waitForLog(out / "plain.log", "first map of robot3", 1, 60.0)) << logOf(*plain);
  for (auto* agent : {secure.get(), plain.get(), rogue.get()}) {
    agent->signal(SIGINT);
    EXPECT_EQ(finish(*agent, 60.0), 0) << logOf(*agent);
  }
  for (auto* agent : {robot2.get(), robot3.get()}) {
    agent->signal(SIGKILL);
  }
  // Each secured agent logs the participants it authenticated and those it refused. The secure
  // fusion agent, started first, hears every other participant: it refuses at least the two
  // without credentials (the rogues' handshakes fail on one side or both). Participants
  // without security log neither.
  EXPECT_TRUE(waitForLog(out / "robot1.log", "authenticated", 1, 0.0)) << logOf(*robot1);
  EXPECT_TRUE(waitForLog(out / "robot2.log", "authenticated", 1, 0.0)) << logOf(*robot2);
  EXPECT_TRUE(waitForLog(out / "secure.log", "failed authentication", 2, 0.0)) << logOf(*secure);
  // Its last word counts them: robot1 is the only other participant of its CA.
  EXPECT_TRUE(
      waitForLog(out / "secure.log", "DDS Security: 1 participant(s) authenticated", 1, 0.0))
      << logOf(*secure);
  for (const char* plain_log : {"plain.log", "robot3.log"}) {
    EXPECT_FALSE(waitForLog(out / plain_log, "DDS Security: participant", 1, 0.0)) << plain_log;
  }
  const nlohmann::json global = robotsOf(out / "secure");
  ASSERT_EQ(global["robots"].size(), 1u) << global.dump();
  EXPECT_EQ(global["robots"][0]["id"], "robot1");
  // Without credentials, or with another CA's: nothing of the team discovered, no map of it
  // read (each outsider sees only its own kind: the plain robot3, the rogue robot2).
  const std::vector<std::pair<std::string, std::string>> outsiders = {{"plain", "robot3"},
                                                                      {"rogue", "robot2"}};
  for (const auto& [outsider, its_own] : outsiders) {
    const nlohmann::json seen = robotsOf(out / outsider);
    ASSERT_EQ(seen["robots"].size(), 1u) << outsider << ": " << seen.dump();
    EXPECT_EQ(seen["robots"][0]["id"], its_own) << outsider;
    EXPECT_FALSE(waitForLog(out / (outsider + ".log"), "of robot1", 1, 0.0)) << outsider;
  }
}

TEST(SecurityTest, ATeamFileRunsItsAgentsWithTheirCredentials) {
  const auto out = scratchFolder("team");
  makePki(out / "pki", {"robot1", "robot2", "sim_fusion"});
  const std::string team_file = (out / "team.yaml").string();
  std::ofstream(team_file) << "security_dir: pki\nrobots:\n"
                           << "  - config: " << sourcePath("config/sim_robot1.yaml") << "\n"
                           << "  - config: " << sourcePath("config/sim_robot2.yaml") << "\n"
                           << "    id: robot2\n"
                           << "fusion:\n  - config: " << sourcePath("config/sim_fusion.yaml")
                           << "\nfinal_grace_s: 5\n";
  auto team = startAgent("tools/mrslam_team",
                         {team_file, "--bin-dir", binaryPath(""), "--out", (out / "run").string(),
                          "--domain", std::to_string(privateDomain()), "--timeout", "120"},
                         (out / "team.log").string());
  ASSERT_EQ(finish(*team, 150.0), 0) << logOf(*team);
  for (const auto& [agent, identity] : std::vector<std::pair<std::string, std::string>>{
           {"sim_robot1", "robot1"}, {"robot2", "robot2"}, {"sim_fusion", "sim_fusion"}}) {
    EXPECT_TRUE(waitForLog(out / "run" / "logs" / (agent + ".log"),
                           "DDS Security as '" + identity + "'", 1, 0.0))
        << agent;
  }
  const nlohmann::json robots = robotsOf(out / "run");
  ASSERT_EQ(robots["robots"].size(), 2u) << robots.dump();
  for (const nlohmann::json& robot : robots["robots"]) {
    EXPECT_TRUE(robot["final"].get<bool>()) << robot["id"];
  }
}

}  // namespace
}  // namespace mrslam::test
