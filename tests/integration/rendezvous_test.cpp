// Rendezvous between simulated robots: the sightings the simulator makes against its truth, and
// a team placed by rendezvous alone (no map merging) over DDS, checked against the maps.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "agent_processes.hpp"
#include "mrslam/drivers/sighting_simulator.hpp"
#include "mrslam/fusion/rendezvous.hpp"
#include "mrslam/robot/robot_config.hpp"

namespace mrslam::test {
namespace {

namespace fs = std::filesystem;

/// A sighting with the observer's TRUE pose in its own map frame (its start pose is the origin).
struct TrueSighting {
  fusion::Sighting sighting;
  int route = 0;
};

std::vector<TrueSighting> sightingsOf(const std::string& robot) {
  const robot::RobotConfig config =
      robot::loadRobotConfig(sourcePath("config/sim_" + robot + ".yaml"));
  drivers::SightingSimulator simulator(config.simulator, config.sightings, config.platform,
                                       config.mounting);
  const SE2 T_world_start = drivers::builtInStartPose(config.simulator.robot_index);
  std::vector<TrueSighting> sightings;
  while (const std::optional<Sample> sample = simulator.next()) {
    if (const auto* seen = std::get_if<RobotSighting>(&*sample)) {
      fusion::Sighting sighting;
      sighting.observer = config.robot_id;
      sighting.observed = seen->observed_id;
      sighting.stamp = seen->stamp;
      sighting.range_m = seen->range_m;
      sighting.bearing_rad = seen->bearing_rad;
      sighting.T_map_observer = T_world_start.inverse() * simulator.truePose();
      sightings.push_back({sighting, config.simulator.robot_index});
    }
  }
  return sightings;
}

TEST(RendezvousSimulatorTest, MutualSightingsGiveTheTrueTransformBetweenStarts) {
  std::vector<TrueSighting> all;
  for (const char* robot : {"robot1", "robot2", "robot3"}) {
    const std::vector<TrueSighting> sightings = sightingsOf(robot);
    all.insert(all.end(), sightings.begin(), sightings.end());
  }
  int rendezvous = 0;
  for (const TrueSighting& a : all) {
    for (const TrueSighting& b : all) {
      if (a.sighting.observer != b.sighting.observed ||
          a.sighting.observed != b.sighting.observer || !(a.sighting.stamp == b.sighting.stamp) ||
          a.sighting.observer > b.sighting.observer) {
        continue;
      }
      ++rendezvous;
      // Sightings are mutual: the same distance seen from both ends (range noise σ 2 cm).
      EXPECT_NEAR(a.sighting.range_m, b.sighting.range_m, 0.1);
      const SE2 truth =
          drivers::builtInStartPose(a.route).inverse() * drivers::builtInStartPose(b.route);
      const SE2 estimate = fusion::rendezvousTransform(a.sighting, b.sighting);
      // Bearing noise σ 0.01 rad on both ends, at up to 4 m, moved to the map origins.
      EXPECT_NEAR((estimate.translation() - truth.translation()).norm(), 0.0, 0.3)
          << a.sighting.observer << " and " << b.sighting.observer << " at "
          << a.sighting.stamp.seconds();
      EXPECT_NEAR(wrapAngle(estimate.theta() - truth.theta()), 0.0, 3.0 * M_PI / 180.0);
    }
  }
  EXPECT_GE(rendezvous, 2) << "the built-in routes meet";
}

fs::path rendezvousFusionConfig(const fs::path& out) {
  const fs::path path = out / "fusion.yaml";
  std::ofstream(path) << "fusion_id: fusion\n"
                         "reference_robot: robot1\n"
                         "expected_robots:\n  - id: robot1\n  - id: robot2\n  - id: robot3\n"
                         "exit_when_final: true\n"
                         "publish_period_s: 0.5\n"
                         "merge:\n  method: none\n"
                         "dds:\n  profiles_file: "
                      << sourcePath("config/dds/profiles.xml") << "\n";
  return path;
}

TEST(RendezvousTeamTest, RobotsArePlacedByTheirRendezvousAloneOverDds) {
  const fs::path out = scratchFolder("team");
  const std::string domain = std::to_string(privateDomain());
  auto fusion = startAgent("fusion_agent/fusion_agent",
                           {"--config", rendezvousFusionConfig(out).string(), "--domain", domain,
                            "--out", (out / "fusion").string(), "--max-runtime", "150"},
                           (out / "fusion.log").string());
  std::vector<std::unique_ptr<tools::ChildProcess>> robots;
  for (const char* robot : {"robot1", "robot2", "robot3"}) {
    robots.push_back(startAgent(
        "robot_agent/robot_agent",
        {"--config", sourcePath(std::string("config/sim_") + robot + ".yaml"), "--domain", domain},
        (out / (std::string(robot) + ".log")).string()));
  }
  for (auto& robot : robots) {
    ASSERT_EQ(finish(*robot, 150.0), 0) << logOf(*robot);
  }
  ASSERT_EQ(finish(*fusion, 150.0), 0) << logOf(*fusion);
  std::ifstream file(out / "fusion" / "transforms.json");
  const nlohmann::json transforms = nlohmann::json::parse(file);
  const SE2 T_world_reference = drivers::builtInStartPose(0);
  int placed = 0;
  for (const auto& robot : transforms["robots"]) {
    const std::string id = robot["id"];
    if (id == "robot1" || !robot["placed"].get<bool>()) {
      continue;
    }
    ++placed;
    EXPECT_EQ(robot["source"], "merge") << id;
    EXPECT_EQ(robot["methods"], "rendezvous") << id;
    const int route = id == "robot2" ? 1 : 2;
    const SE2 truth = T_world_reference.inverse() * drivers::builtInStartPose(route);
    EXPECT_NEAR(robot["x"].get<double>(), truth.x(), 0.1) << id;
    EXPECT_NEAR(robot["y"].get<double>(), truth.y(), 0.1) << id;
    EXPECT_NEAR(wrapAngle(robot["theta"].get<double>() - truth.theta()), 0.0, M_PI / 180.0) << id;
  }
  EXPECT_EQ(placed, 2) << "robot2 and robot3 placed by rendezvous:\n" << logOf(*fusion);
  EXPECT_TRUE(waitForLog(out / "fusion.log", "verified by the maps", 1, 1.0)) << logOf(*fusion);
}

}  // namespace
}  // namespace mrslam::test
