// The intel team: carmen-intel-corrected cut into three segments, each replayed by its own robot
// agent from its own origin, and one fusion agent that finds the transforms from the maps alone
// (the seed merger), as separate processes over real Fast DDS. Every robot must be placed within
// 0.1 m and 1° of the true transform written by the splitter.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "agent_processes.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/tools/carmen_split.hpp"

namespace mrslam::test {
namespace {

constexpr int kRobots = 3;

nlohmann::json readJson(const std::string& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

TEST(IntelTeamTest, FusionAgentPlacesEveryRobotFromTheMapsAlone) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-intel-corrected.log.gz");
  const auto out = scratchFolder("out");
  tools::SplitSettings split;
  split.segments = kRobots;
  const std::vector<tools::LogSegment> segments = tools::splitCarmenLog(
      sharedDataPath("logs/carmen-intel-corrected.log.gz"), (out / "segments").string(), split);
  ASSERT_EQ(segments.size(), static_cast<std::size_t>(kRobots));
  std::vector<std::string> ids;
  for (int k = 1; k <= kRobots; ++k) {
    ids.push_back("robot" + std::to_string(k));
  }
  tools::writeSplitTruth(segments, ids, (out / "truth.json").string());

  const std::string domain = std::to_string(privateDomain());
  auto fusion = startAgent("fusion_agent/fusion_agent",
                           {"--config", sourcePath("config/intel_team_fusion.yaml"), "--domain",
                            domain, "--out", (out / "fusion").string(), "--max-runtime", "300"},
                           (out / "fusion.log").string());
  std::vector<std::unique_ptr<tools::ChildProcess>> agents;
  for (int k = 0; k < kRobots; ++k) {
    agents.push_back(
        startAgent("robot_agent/robot_agent",
                   {"--robot-config", sourcePath("config/intel_team_robot.yaml"), "--robot-id",
                    ids[k], "--log", segments[k].path, "--domain", domain},
                   (out / (ids[k] + ".log")).string()));
  }
  for (auto& agent : agents) {
    ASSERT_EQ(finish(*agent, 200.0), 0) << logOf(*agent);
  }
  ASSERT_EQ(finish(*fusion, 200.0), 0) << logOf(*fusion);

  const nlohmann::json placed = readJson((out / "fusion" / "transforms.json").string());
  const nlohmann::json truth = readJson((out / "truth.json").string());
  EXPECT_EQ(placed["reference"], "robot1");
  ASSERT_EQ(placed["robots"].size(), static_cast<std::size_t>(kRobots));
  for (int k = 0; k < kRobots; ++k) {
    const nlohmann::json& robot = placed["robots"][k];
    const nlohmann::json& expected = truth["robots"][k];
    ASSERT_EQ(robot["id"], expected["id"]);
    ASSERT_TRUE(robot["placed"].get<bool>()) << ids[k] << ": " << robot["source"] << "\n"
                                             << logOf(*fusion);
    const double dx = robot["x"].get<double>() - expected["x"].get<double>();
    const double dy = robot["y"].get<double>() - expected["y"].get<double>();
    const double dtheta = wrapAngle(robot["theta"].get<double>() - expected["theta"].get<double>());
    EXPECT_LT(std::hypot(dx, dy), 0.1) << ids[k];
    EXPECT_LT(std::abs(dtheta), M_PI / 180.0) << ids[k];
    if (k > 0) {
      EXPECT_GE(robot["verification"].get<double>(), 0.9) << ids[k];
    }
  }
}

}  // namespace
}  // namespace mrslam::test
