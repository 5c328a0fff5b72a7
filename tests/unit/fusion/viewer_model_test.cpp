// The live viewer's model: the state document (robots, placements, poses and trajectories in the
// reference frame, health, pairs) and the pictures it serves.

#include "mrslam/fusion/viewer_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

namespace mrslam::fusion {
namespace {

using nlohmann::json;

RobotMap robotMap(const std::string& id, int trajectory_length) {
  GridGeometry geometry;
  geometry.resolution_m = 0.1;
  geometry.width = 20;
  geometry.height = 10;
  RobotMap map;
  map.robot_id = id;
  map.sequence = 7;
  map.scans_inserted = 42;
  map.map = GridMap(geometry, GridMap::kFree);
  map.map.at(3, 4) = GridMap::kOccupied;
  for (int i = 0; i < trajectory_length; ++i) {
    map.trajectory.emplace_back(0.01 * i, 0.0, 0.0);
  }
  return map;
}

Placement placed(const std::string& id, const SE2& T_reference_robot, double verification) {
  Placement placement;
  placement.robot_id = id;
  placement.placed = true;
  placement.T_reference_robot = T_reference_robot;
  placement.verification = verification;
  placement.source = "merge";
  return placement;
}

Placement notPlaced(const std::string& id) {
  Placement placement;
  placement.robot_id = id;
  placement.source = "no verified merge";
  return placement;
}

/// A two-robot global map: robot1 is the reference, robot2 sits at (1, 2) turned by 90°.
struct TwoRobots {
  std::vector<RobotMap> maps = {robotMap("robot1", 5), robotMap("robot2", 3)};
  GlobalMapResult result;
  TwoRobots() {
    result.reference_robot = "robot1";
    result.placements = {placed("robot1", SE2(), 1.0),
                         placed("robot2", SE2(1.0, 2.0, M_PI / 2), 0.93)};
    result.map = maps[0].map;
  }
};

const json& robotOf(const json& state, const std::string& id) {
  for (const json& robot : state["robots"]) {
    if (robot["id"] == id) {
      return robot;
    }
  }
  throw std::runtime_error("no robot " + id + " in the state");
}

TEST(ViewerModelTest, EmptyModelHasNoMapNoRobotsAndNoPicture) {
  const ViewerModel model;
  const json state = json::parse(model.stateJson());
  EXPECT_TRUE(state["map"].is_null());
  EXPECT_TRUE(state["robots"].empty());
  EXPECT_TRUE(state["pairs"].empty());
  EXPECT_TRUE(model.globalMapPng().empty());
  EXPECT_FALSE(model.robotMapPng("robot1").has_value());
}

TEST(ViewerModelTest, PlacedRobotsCarryPoseAndTrajectoryInTheReferenceFrame) {
  TwoRobots team;
  ViewerModel model;
  model.setGlobalMap(team.result, team.maps);
  const json state = json::parse(model.stateJson());
  EXPECT_EQ(state["reference"], "robot1");
  EXPECT_EQ(state["map"]["width"], 20);
  EXPECT_NEAR(state["map"]["resolution"].get<double>(), 0.1, 1e-12);
  ASSERT_EQ(state["robots"].size(), 2u);

  const json& robot2 = robotOf(state, "robot2");
  EXPECT_TRUE(robot2["placed"].get<bool>());
  EXPECT_NEAR(robot2["verification"].get<double>(), 0.93, 1e-12);
  EXPECT_NEAR(robot2["origin"]["x"].get<double>(), 1.0, 1e-12);
  EXPECT_NEAR(robot2["origin"]["theta"].get<double>(), M_PI / 2, 1e-12);
  // Its last pose (0.02, 0) in its own frame is (1, 2.02) in the reference frame, facing +y.
  EXPECT_NEAR(robot2["pose"]["x"].get<double>(), 1.0, 1e-9);
  EXPECT_NEAR(robot2["pose"]["y"].get<double>(), 2.02, 1e-9);
  EXPECT_NEAR(robot2["pose"]["theta"].get<double>(), M_PI / 2, 1e-9);
  ASSERT_EQ(robot2["trajectory"].size(), 3u);
  EXPECT_NEAR(robot2["trajectory"][1][1].get<double>(), 2.01, 1e-9);
  EXPECT_EQ(robot2["map"]["sequence"], 7);
  EXPECT_EQ(robot2["map"]["scans_inserted"], 42);
  EXPECT_NE(robotOf(state, "robot1")["colour"], robot2["colour"]);
}

TEST(ViewerModelTest, UnplacedRobotHasNoPoseAndSaysWhy) {
  TwoRobots team;
  team.result.placements[1] = notPlaced("robot2");
  ViewerModel model;
  model.setGlobalMap(team.result, team.maps);
  const json robot2 = robotOf(json::parse(model.stateJson()), "robot2");
  EXPECT_FALSE(robot2["placed"].get<bool>());
  EXPECT_TRUE(robot2["pose"].is_null());
  EXPECT_TRUE(robot2["trajectory"].empty());
  EXPECT_EQ(robot2["source"], "no verified merge");
}

TEST(ViewerModelTest, LongTrajectoriesAreThinnedKeepingTheLastPose) {
  TwoRobots team;
  team.maps[0] = robotMap("robot1", 1001);
  ViewerModel model(ViewerLimits{100});
  model.setGlobalMap(team.result, team.maps);
  const json trajectory = robotOf(json::parse(model.stateJson()), "robot1")["trajectory"];
  EXPECT_LE(trajectory.size(), 101u);
  EXPECT_GE(trajectory.size(), 90u);
  EXPECT_NEAR(trajectory.back()[0].get<double>(), 10.0, 1e-9);
  EXPECT_NEAR(trajectory.front()[0].get<double>(), 0.0, 1e-9);
}

TEST(ViewerModelTest, HealthOfARobotWithoutAMapMakesItKnown) {
  ViewerModel model;
  RobotHealth health;
  health.state = "running";
  health.scans_processed = 12;
  health.sensors.push_back({"laser", "device", true, 10.0, 120, 3});
  model.setHealth("robot9", health);
  const json state = json::parse(model.stateJson());
  ASSERT_EQ(state["robots"].size(), 1u);
  const json& robot9 = state["robots"][0];
  EXPECT_EQ(robot9["id"], "robot9");
  EXPECT_FALSE(robot9["placed"].get<bool>());
  EXPECT_EQ(robot9["health"]["state"], "running");
  EXPECT_EQ(robot9["health"]["scans_processed"], 12);
  EXPECT_EQ(robot9["health"]["sensors"][0]["errors"], 3);
  EXPECT_EQ(robot9["health"]["sensors"][0]["source"], "device");
}

TEST(ViewerModelTest, NewestAttemptOfAPairReplacesTheOlderOne) {
  ViewerModel model;
  MergeAttempt attempt;
  attempt.from = "robot2";
  attempt.to = "robot1";
  attempt.result.method = "seed";
  attempt.result.reason = "V below threshold";
  model.addAttempt(attempt);
  attempt.result.accepted = true;
  attempt.result.reason.clear();
  attempt.result.verification = 0.97;
  attempt.result.entropy = 0.31;
  attempt.T_to_from = SE2(0.5, -0.25, 0.1);
  model.addAttempt(attempt);
  const json pairs = json::parse(model.stateJson())["pairs"];
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_TRUE(pairs[0]["accepted"].get<bool>());
  EXPECT_NEAR(pairs[0]["verification"].get<double>(), 0.97, 1e-12);
  EXPECT_NEAR(pairs[0]["entropy"].get<double>(), 0.31, 1e-12);
  EXPECT_NEAR(pairs[0]["transform"]["y"].get<double>(), -0.25, 1e-12);
}

TEST(ViewerModelTest, EveryChangeRaisesTheRevision) {
  TwoRobots team;
  ViewerModel model;
  const std::uint64_t before = model.revision();
  model.setGlobalMap(team.result, team.maps);
  const std::uint64_t after_map = model.revision();
  model.setHealth("robot1", RobotHealth{});
  EXPECT_GT(after_map, before);
  EXPECT_GT(model.revision(), after_map);
  EXPECT_EQ(json::parse(model.stateJson())["revision"].get<std::uint64_t>(), model.revision());
}

TEST(ViewerModelTest, PicturesDecodeToTheMapsSize) {
  TwoRobots team;
  ViewerModel model;
  model.setGlobalMap(team.result, team.maps);
  const std::vector<std::uint8_t> global = model.globalMapPng();
  ASSERT_FALSE(global.empty());
  const cv::Mat image = cv::imdecode(global, cv::IMREAD_COLOR);
  EXPECT_EQ(image.cols, 20);
  EXPECT_EQ(image.rows, 10);
  const auto robot2 = model.robotMapPng("robot2");
  ASSERT_TRUE(robot2.has_value());
  EXPECT_EQ(cv::imdecode(*robot2, cv::IMREAD_COLOR).cols, 20);
  EXPECT_FALSE(model.robotMapPng("robot3").has_value());
}

}  // namespace
}  // namespace mrslam::fusion
