// The demo: three simulated robot agents and a fusion agent as separate processes over DDS.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "agent_processes.hpp"
#include "mrslam/common/map_io.hpp"
#include "mrslam/drivers/simulator.hpp"
#include "mrslam/fusion/fusion_config.hpp"

namespace mrslam::test {
namespace {

TEST(SimulatorDemoTest, SimulatedTeamConfigPlacesRobotsAtTheirTrueStarts) {
  const fusion::FusionConfig config =
      fusion::loadFusionConfig(sourcePath("config/sim_fusion.yaml"));
  const SE2 T_world_reference = drivers::builtInStartPose(0);
  for (int robot = 1; robot < 3; ++robot) {
    const std::string id = "robot" + std::to_string(robot + 1);
    ASSERT_EQ(config.fixed_transforms.count(id), 1u) << id;
    const SE2 truth = T_world_reference.inverse() * drivers::builtInStartPose(robot);
    const SE2& configured = config.fixed_transforms.at(id);
    EXPECT_NEAR(configured.x(), truth.x(), 1e-9) << id;
    EXPECT_NEAR(configured.y(), truth.y(), 1e-9) << id;
    EXPECT_NEAR(wrapAngle(configured.theta() - truth.theta()), 0.0, 1e-9) << id;
  }
}

TEST(SimulatorDemoTest, ThreeRobotsAndAFusionAgentProduceTheGlobalMap) {
  const auto out = scratchFolder("demo");
  auto demo =
      startAgent("tools/mrslam_demo",
                 {"--config-dir", sourcePath("config"), "--bin-dir", binaryPath(""), "--out",
                  out.string(), "--domain", std::to_string(privateDomain()), "--timeout", "120"},
                 (out / "demo.log").string());
  ASSERT_EQ(finish(*demo, 180.0), 0) << logOf(*demo);
  std::ifstream file(out / "robots.json");
  const nlohmann::json received = nlohmann::json::parse(file);
  ASSERT_EQ(received["robots"].size(), 3u);
  for (const auto& robot : received["robots"]) {
    EXPECT_TRUE(robot["final"].get<bool>()) << robot["id"];
    EXPECT_EQ(robot["scans_inserted"], 600) << robot["id"];  // 60 s at 10 Hz
  }
  const GridMap global = loadMapYaml((out / "global_map.yaml").string());
  EXPECT_TRUE(global.isValid());
  // The three routes together cover most of the 17 × 10 m building (at 0.05 m per cell).
  std::size_t known = 0;
  for (const std::int8_t value : global.cells) {
    known += value != GridMap::kUnknown;
  }
  EXPECT_GT(known * 0.05 * 0.05, 60.0);
  EXPECT_LT(global.geometry.width * 0.05, 30.0);
  // Nobody gave the demo the robots' starts: it placed them by their rendezvous.
  std::ifstream transforms_file(out / "transforms.json");
  const nlohmann::json transforms = nlohmann::json::parse(transforms_file);
  const SE2 T_world_reference = drivers::builtInStartPose(0);
  for (const auto& robot : transforms["robots"]) {
    const std::string id = robot["id"];
    ASSERT_TRUE(robot["placed"].get<bool>()) << id;
    const int route = std::stoi(id.substr(5)) - 1;  // robotN drives route N-1
    const SE2 truth = T_world_reference.inverse() * drivers::builtInStartPose(route);
    EXPECT_NEAR(robot["x"].get<double>(), truth.x(), 0.15) << id;
    EXPECT_NEAR(robot["y"].get<double>(), truth.y(), 0.15) << id;
    EXPECT_NEAR(wrapAngle(robot["theta"].get<double>() - truth.theta()), 0.0, 1.5 * M_PI / 180.0)
        << id;
  }
  EXPECT_TRUE(std::filesystem::exists(out / "global_map.bt"));
  EXPECT_TRUE(std::filesystem::exists(out / "global_map.png"));
}

}  // namespace
}  // namespace mrslam::test
