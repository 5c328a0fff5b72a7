// Two robot agents replaying the BreezySLAM logs and one fusion agent, as separate processes
// over real Fast DDS on a private domain: the fusion agent must hold each robot's final map,
// equal cell for cell to the map built offline from the same log, and place exp2 from the maps
// alone or report it as not placed.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "agent_processes.hpp"
#include "mrslam/common/map_io.hpp"
#include "mrslam/robot/robot_config.hpp"

namespace mrslam::test {
namespace {

GridMap offlineMap(const std::string& config_path, const std::string& log_path) {
  robot::RobotConfig config = robot::loadRobotConfig(config_path);
  config.source.path = log_path;
  auto source = robot::openSource(config);
  auto pipeline = robot::makePipeline(config);
  while (auto sample = source->next()) {
    pipeline->process(*sample);
  }
  return pipeline->grid().toGridMap();
}

nlohmann::json readJson(const std::string& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

TEST(BreezySlamTeamTest, FusionAgentReceivesBothFinalMapsOverDds) {
  MRSLAM_REQUIRE_SHARED_DATA("logs/breezyslam-exp1.dat");
  MRSLAM_REQUIRE_SHARED_DATA("logs/breezyslam-exp2.dat");
  const auto out = scratchFolder("out");
  const std::string domain = std::to_string(privateDomain());
  const std::vector<std::string> robots = {"exp1", "exp2"};

  auto fusion = startAgent("fusion_agent/fusion_agent",
                           {"--config", sourcePath("config/breezyslam_fusion.yaml"), "--domain",
                            domain, "--out", out.string(), "--max-runtime", "120"},
                           (out / "fusion.log").string());
  std::vector<std::unique_ptr<tools::ChildProcess>> agents;
  for (const std::string& robot : robots) {
    agents.push_back(
        startAgent("robot_agent/robot_agent",
                   {"--config", sourcePath("config/breezyslam_" + robot + ".yaml"), "--log",
                    sharedDataPath("logs/breezyslam-" + robot + ".dat"), "--domain", domain},
                   (out / (robot + ".log")).string()));
  }
  for (auto& agent : agents) {
    ASSERT_EQ(finish(*agent, 120.0), 0) << logOf(*agent);
  }
  ASSERT_EQ(finish(*fusion, 60.0), 0) << logOf(*fusion);

  const nlohmann::json received = readJson((out / "robots.json").string());
  ASSERT_EQ(received["robots"].size(), 2u);
  for (std::size_t i = 0; i < robots.size(); ++i) {
    const nlohmann::json& robot = received["robots"][i];
    EXPECT_EQ(robot["id"], robots[i]);
    EXPECT_TRUE(robot["final"].get<bool>());
    EXPECT_EQ(robot["scans_inserted"], robots[i] == "exp1" ? 756 : 641);

    const GridMap from_dds = loadMapYaml((out / "robots" / (robots[i] + ".yaml")).string());
    const GridMap offline = offlineMap(sourcePath("config/breezyslam_" + robots[i] + ".yaml"),
                                       sharedDataPath("logs/breezyslam-" + robots[i] + ".dat"));
    EXPECT_EQ(from_dds.geometry, offline.geometry) << robots[i];
    EXPECT_TRUE(from_dds.cells == offline.cells) << robots[i] << ": the map over DDS differs";
  }

  const GridMap global = loadMapYaml((out / "global_map.yaml").string());
  EXPECT_TRUE(global.isValid());
  EXPECT_GT(global.geometry.cellCount(), 0u);
  const GridMap global_bt = loadMapOctomap((out / "global_map.bt").string(), global.geometry);
  std::size_t known = 0;
  for (std::size_t i = 0; i < global.cells.size(); ++i) {
    const std::int8_t value = global.cells[i];
    const std::int8_t expected = value == GridMap::kUnknown || value == 50 ? GridMap::kUnknown
                                 : value > 50                              ? GridMap::kOccupied
                                                                           : GridMap::kFree;
    ASSERT_EQ(global_bt.cells[i], expected) << "cell " << i;
    known += value != GridMap::kUnknown;
  }
  EXPECT_GT(known, 10000u);
  const cv::Mat picture = cv::imread((out / "global_map.png").string());
  EXPECT_EQ(picture.cols, global.geometry.width);
  EXPECT_EQ(picture.rows, global.geometry.height);
  const nlohmann::json transforms = readJson((out / "transforms.json").string());
  EXPECT_EQ(transforms["reference"], "exp1");
  ASSERT_EQ(transforms["robots"].size(), 2u);
  // Only a merge of the two maps could place exp2 (the config gives no placement), and the maps
  // these runs build are refused (exp2's is bent, docs/merge_tuning.md): exp2 is reported as not
  // placed, never guessed, and the fusion log says why.
  EXPECT_EQ(transforms["robots"][1]["id"], "exp2");
  EXPECT_FALSE(transforms["robots"][1]["placed"].get<bool>()) << transforms.dump();
  EXPECT_NE(fileText((out / "fusion.log").string()).find("exp2 → exp1 not merged"),
            std::string::npos);
}

}  // namespace
}  // namespace mrslam::test
