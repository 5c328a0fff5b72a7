// The team launcher (mrslam_team) as a user runs it: one team file → robot and fusion agents as
// separate processes over DDS; its exit code's bits say what failed.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "agent_processes.hpp"

namespace mrslam::test {
namespace {

nlohmann::json readJson(const std::string& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

int runTeam(const std::string& team_file, const std::filesystem::path& out, std::string& log) {
  auto team = startAgent("tools/mrslam_team",
                         {team_file, "--bin-dir", binaryPath(""), "--out", out.string(), "--domain",
                          std::to_string(privateDomain()), "--timeout", "240"},
                         (out.string() + ".log"));
  const int code = finish(*team, 300.0);
  log = logOf(*team);
  return code;
}

// Runs a team file of three robots on a corrected CARMEN log (the intel team's agent configs):
// every robot must be placed from the maps alone within 0.1 m and 1° of the splitter's truth,
// the launcher's evaluation says so too, and each agent leaves its log.
void expectEveryRobotPlaced(const std::string& team_file, const std::filesystem::path& out) {
  std::string log;
  ASSERT_EQ(runTeam(sourcePath(team_file), out / "team", log), 0) << log;
  const nlohmann::json truth = readJson((out / "team" / "segments" / "truth.json").string());
  const nlohmann::json placed = readJson((out / "team" / "transforms.json").string());
  ASSERT_EQ(truth["robots"].size(), 3u);
  ASSERT_EQ(placed["robots"].size(), 3u);
  for (std::size_t k = 0; k < 3; ++k) {
    const nlohmann::json& robot = placed["robots"][k];
    const nlohmann::json& expected = truth["robots"][k];
    EXPECT_EQ(robot["id"], expected["id"]);
    ASSERT_TRUE(robot["placed"].get<bool>()) << robot["id"] << ": " << robot["source"];
    EXPECT_LT(std::hypot(robot["x"].get<double>() - expected["x"].get<double>(),
                         robot["y"].get<double>() - expected["y"].get<double>()),
              0.1)
        << robot["id"];
    EXPECT_LT(std::abs(std::remainder(
                  robot["theta"].get<double>() - expected["theta"].get<double>(), 2.0 * M_PI)),
              M_PI / 180.0)
        << robot["id"];
  }
  // The launcher's evaluation: the same errors, and on the corrected poses the truth in the
  // robots' estimated frames is the split's.
  const nlohmann::json evaluation = readJson((out / "team" / "evaluation.json").string());
  const nlohmann::json estimated =
      readJson((out / "team" / "segments" / "truth_estimated.json").string());
  ASSERT_EQ(evaluation["robots"].size(), 2u);  // all but the reference
  for (std::size_t k = 1; k < 3; ++k) {
    const nlohmann::json& error = evaluation["robots"][k - 1];
    EXPECT_EQ(error["id"], truth["robots"][k]["id"]);
    EXPECT_NEAR(
        error["split_truth"]["distance_m"].get<double>(),
        std::hypot(placed["robots"][k]["x"].get<double>() - truth["robots"][k]["x"].get<double>(),
                   placed["robots"][k]["y"].get<double>() - truth["robots"][k]["y"].get<double>()),
        1e-9);
    EXPECT_LT(error["estimated_frames_truth"]["distance_m"].get<double>(), 0.1);
    EXPECT_LT(error["estimated_frames_truth"]["angle_deg"].get<double>(), 1.0);
    for (const char* field : {"x", "y", "theta"}) {
      EXPECT_NEAR(estimated["robots"][k][field].get<double>(),
                  truth["robots"][k][field].get<double>(), 1e-3)
          << field;
    }
  }
  EXPECT_NE(log.find("robot2 placed"), std::string::npos) << log;
  for (const char* agent : {"robot1", "robot2", "robot3", "intel_team_fusion"}) {
    EXPECT_TRUE(std::filesystem::exists(out / "team" / "logs" / (std::string(agent) + ".log")))
        << agent;
  }
}

TEST(TeamLauncherTest, TheIntelTeamFileRunsSplitsAndPlacesEveryRobot) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-intel-corrected.log.gz");
  const auto out = scratchFolder("intel");
  expectEveryRobotPlaced("config/intel_team.yaml", out);
  // --evaluate-only starts nothing and evaluates the finished run again.
  const auto evaluation = out / "team" / "evaluation.json";
  const nlohmann::json first = readJson(evaluation.string());
  std::filesystem::remove(evaluation);
  auto again = startAgent("tools/mrslam_team",
                          {sourcePath("config/intel_team.yaml"), "--bin-dir", binaryPath(""),
                           "--out", (out / "team").string(), "--evaluate-only"},
                          (out / "evaluate.log").string());
  EXPECT_EQ(finish(*again, 60.0), 0) << logOf(*again);
  EXPECT_EQ(readJson(evaluation.string()), first);
  EXPECT_EQ(logOf(*again).find("started"), std::string::npos) << "no agent started";
}

// Two more buildings with the same configs. Their robots' maps show walls one robot never
// marked (seen at a grazing angle or from far) where the other's walls are: the structure bar
// leaves out walls on the other map's frontier (min_structure_off_frontier).
TEST(TeamLauncherTest, TheAcesTeamFilePlacesEveryRobot) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-aces-corrected.log.gz");
  expectEveryRobotPlaced("config/aces_team.yaml", scratchFolder("aces"));
}

TEST(TeamLauncherTest, TheCsailTeamFilePlacesEveryRobot) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-csail-corrected.log.gz");
  expectEveryRobotPlaced("config/csail_team.yaml", scratchFolder("csail"));
}

TEST(TeamLauncherTest, AFailedRobotSetsItsBitAndTheFusionAgentStopsAfterTheGrace) {
  const auto out = scratchFolder("failing");
  const std::string team_file = (out / "team.yaml").string();
  std::ofstream(team_file) << "robots:\n  - config: " << sourcePath("config/sim_robot1.yaml")
                           << "\n    log: " << (out / "missing.log").string()
                           << "\nfusion:\n  - config: " << sourcePath("config/sim_fusion.yaml")
                           << "\nfinal_grace_s: 1\n";
  std::string log;
  EXPECT_EQ(runTeam(team_file, out / "team", log), 1) << log;  // the robot bit alone
  EXPECT_NE(log.find("sim_robot1 ended with exit code"), std::string::npos) << log;
  // Asked to stop, the fusion agent still wrote its files.
  EXPECT_TRUE(std::filesystem::exists(out / "team" / "transforms.json")) << log;
}

TEST(TeamLauncherTest, AMistakeInTheTeamFileIsALaunchFailureNamingTheLine) {
  const auto out = scratchFolder("bad");
  const std::string team_file = (out / "team.yaml").string();
  std::ofstream(team_file) << "robots:\n  - config: x.yaml\n    segment: 2\n";
  std::string log;
  EXPECT_EQ(runTeam(team_file, out / "team", log), 4) << log;
  EXPECT_NE(log.find("team.yaml:3: robots[0].segment: needs a `split:` section"), std::string::npos)
      << log;
}

}  // namespace
}  // namespace mrslam::test
