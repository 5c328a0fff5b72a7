// Several fusion agents at once (the seed paper's decentralised mode: one beside each robot):
// on the intel log cut into three robots, two fusion agents that merge the same maps from the
// maps alone agree on every robot's placement, and both are right.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>

#include "agent_processes.hpp"

namespace mrslam::test {
namespace {

nlohmann::json readJson(const std::filesystem::path& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

TEST(DecentralisedFusionTest, TwoFusionAgentsAgreeOnTheTransforms) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/carmen-intel-corrected.log.gz");
  const auto out = scratchFolder("decentralised");
  const std::string team_file = (out / "team.yaml").string();
  std::ofstream team_yaml(team_file);
  team_yaml << "split:\n  log: " << sharedDataPath("logs/carmen-intel-corrected.log.gz")
            << "\n  segments: 3\nrobots:\n";
  for (int k = 1; k <= 3; ++k) {
    team_yaml << "  - config: " << sourcePath("config/intel_team_robot.yaml") << "\n    id: robot"
              << k << "\n    segment: " << k << "\n";
  }
  team_yaml << "fusion:\n";
  for (const char* name : {"fusion_a", "fusion_b"}) {
    team_yaml << "  - config: " << sourcePath("config/intel_team_fusion.yaml")
              << "\n    name: " << name << "\n";
  }
  team_yaml << "final_grace_s: 180\n";
  team_yaml.close();
  auto team = startAgent("tools/mrslam_team",
                         {team_file, "--bin-dir", binaryPath(""), "--out", (out / "run").string(),
                          "--domain", std::to_string(privateDomain()), "--timeout", "400"},
                         (out / "team.log").string());
  ASSERT_EQ(finish(*team, 450.0), 0) << logOf(*team);

  // Each robot left only once both fusion agents held its final map.
  for (int k = 1; k <= 3; ++k) {
    const auto log = out / "run" / "logs" / ("robot" + std::to_string(k) + ".log");
    EXPECT_TRUE(waitForLog(log, "for 2 fusion agent(s) to hold the final map", 1, 0.0)) << log;
  }
  const nlohmann::json truth = readJson(out / "run" / "segments" / "truth.json");
  const nlohmann::json a = readJson(out / "run" / "fusion_a" / "transforms.json");
  const nlohmann::json b = readJson(out / "run" / "fusion_b" / "transforms.json");
  ASSERT_EQ(a["robots"].size(), 3u);
  ASSERT_EQ(b["robots"].size(), 3u);
  EXPECT_EQ(a["reference"], b["reference"]);
  for (std::size_t k = 0; k < 3; ++k) {
    const nlohmann::json& ra = a["robots"][k];
    const nlohmann::json& rb = b["robots"][k];
    ASSERT_EQ(ra["id"], rb["id"]);
    ASSERT_TRUE(ra["placed"].get<bool>()) << ra["id"];
    ASSERT_TRUE(rb["placed"].get<bool>()) << rb["id"];
    // They agree with each other within the placement goal (0.1 m, 1°): each merged the maps
    // it had when it had them, so the figures may differ by a few centimetres. Both are right.
    EXPECT_LT(std::hypot(ra["x"].get<double>() - rb["x"].get<double>(),
                         ra["y"].get<double>() - rb["y"].get<double>()),
              0.1)
        << ra["id"];
    EXPECT_LT(std::abs(ra["theta"].get<double>() - rb["theta"].get<double>()), M_PI / 180.0)
        << ra["id"];
    for (const nlohmann::json* placed : {&ra, &rb}) {
      EXPECT_LT(std::hypot((*placed)["x"].get<double>() - truth["robots"][k]["x"].get<double>(),
                           (*placed)["y"].get<double>() - truth["robots"][k]["y"].get<double>()),
                0.1)
          << ra["id"];
    }
  }
}

}  // namespace
}  // namespace mrslam::test
