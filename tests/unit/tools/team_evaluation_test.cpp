// A team run's placements against the split's truth and the truth in the robots' estimated
// frames (team_evaluation.hpp): the files read and checked, the algebra against hand-made frames,
// the corrected trajectory of a small CARMEN log and the alignment of a turned copy of it.

#include "mrslam/tools/team_evaluation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

#include "test_data.hpp"

namespace mrslam::tools {
namespace {

void expectNear(const SE2& a, const SE2& b, double tolerance) {
  EXPECT_NEAR(a.x(), b.x(), tolerance);
  EXPECT_NEAR(a.y(), b.y(), tolerance);
  EXPECT_NEAR(std::abs(wrapAngle(a.theta() - b.theta())), 0.0, tolerance);
}

std::string writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path) << text;
  return path.string();
}

TEST(TeamEvaluationTest, PlacementsFilesAreReadAndBadOnesNamed) {
  const auto folder = test::scratchFolder("team_evaluation_files");
  const TeamPlacements read = readPlacements(writeFile(
      folder / "ok.json",
      R"({"reference": "robot1", "robots": [{"id": "robot1", "placed": true, "x": 0, "y": 0,
          "theta": 0}, {"id": "robot2", "placed": true, "x": 1.5, "y": -2, "theta": 0.3},
          {"id": "robot3", "placed": false, "x": null, "y": null, "theta": null}]})"));
  EXPECT_EQ(read.reference, "robot1");
  ASSERT_EQ(read.robots.size(), 3u);
  ASSERT_NE(read.find("robot2"), nullptr);
  expectNear(read.find("robot2")->T_reference_origin, SE2(1.5, -2.0, 0.3), 1e-12);
  EXPECT_FALSE(read.find("robot3")->placed);
  EXPECT_EQ(read.find("robot4"), nullptr);

  const auto failure = [&](const std::string& name, const std::string& text) {
    try {
      readPlacements(writeFile(folder / name, text));
    } catch (const std::runtime_error& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(failure("bad.json", "{not json").find("bad.json: not a placements file"),
            std::string::npos);
  EXPECT_NE(failure("null_pose.json",
                    R"({"reference": "r1", "robots": [{"id": "r2", "placed": true, "x": null}]})")
                .find("(r2): \"x\" is not a number"),
            std::string::npos);
  EXPECT_NE(failure("no_id.json", R"({"reference": "r1", "robots": [{"placed": true}]})")
                .find("a robot needs a string \"id\""),
            std::string::npos);
  EXPECT_THROW(readPlacements((folder / "missing.json").string()), std::runtime_error);
}

TEST(TeamEvaluationTest, ErrorsAreMeasuredForEveryRobotButTheReference) {
  TeamPlacements truth{"robot1",
                       {{"robot1", true, SE2(), ""},
                        {"robot2", true, SE2(4.0, 1.0, 3.1), ""},
                        {"robot3", true, SE2(-2.0, 5.0, 0.5), ""}}};
  TeamPlacements found{"robot1",
                       {{"robot1", true, SE2(), ""},
                        {"robot2", true, SE2(4.03, 0.96, -3.1), ""},
                        {"robot3", false, SE2(), ""}}};
  const std::vector<PlacementError> errors = comparePlacements(found, truth);
  ASSERT_EQ(errors.size(), 2u);
  EXPECT_EQ(errors[0].id, "robot2");
  EXPECT_TRUE(errors[0].placed);
  EXPECT_NEAR(errors[0].distance_m, 0.05, 1e-9);
  EXPECT_NEAR(errors[0].angle_rad, 2.0 * M_PI - 6.2, 1e-9);  // across ±π
  EXPECT_EQ(errors[1].id, "robot3");
  EXPECT_FALSE(errors[1].placed);
  found.reference = "robot2";
  EXPECT_THROW(comparePlacements(found, truth), std::runtime_error);
}

// Robot i's estimated frame e_i lies at T_c_e(i) in its corrected frame c_i; a point of robot 2's
// estimated map must land on the same spot of the building through either chain of frames.
TEST(TeamEvaluationTest, TheTruthInEstimatedFramesComposesTheAlignments) {
  const SE2 T_c1_c2(6.0, -1.0, 2.0);
  const SE2 T_c1_e1(0.3, 0.2, 0.25);
  const SE2 T_c2_e2(-0.4, 0.1, -0.1);
  const TeamPlacements truth{"robot1",
                             {{"robot1", true, SE2(), ""}, {"robot2", true, T_c1_c2, ""}}};
  const TeamPlacements estimated =
      truthInEstimatedFrames(truth, {{"robot1", T_c1_e1}, {"robot2", T_c2_e2}});
  const SE2& T_e1_e2 = estimated.find("robot2")->T_reference_origin;
  const Eigen::Vector2d point_e2(2.0, 3.0);
  const Eigen::Vector2d through_estimated = T_c1_e1 * (T_e1_e2 * point_e2);
  const Eigen::Vector2d through_corrected = T_c1_c2 * (T_c2_e2 * point_e2);
  EXPECT_NEAR((through_estimated - through_corrected).norm(), 0.0, 1e-12);
  expectNear(estimated.find("robot1")->T_reference_origin, SE2(), 1e-12);
  // Without alignments the split's truth stays.
  expectNear(truthInEstimatedFrames(truth, {}).find("robot2")->T_reference_origin, T_c1_c2, 1e-12);
}

TEST(TeamEvaluationTest, ACarmenLogsCorrectedTrajectoryStartsAtItsOrigin) {
  const auto folder = test::scratchFolder("team_evaluation_log");
  const std::string beams = "3 1.0 1.0 1.0";
  const std::string log = writeFile(
      folder / "segment.log",
      "FLASER " + beams + " 10 5 1.5707963267948966 10 5 1.5707963267948966 100.0 h 100.0\n" +
          "FLASER " + beams + " 10 6 1.5707963267948966 10 6 1.5707963267948966 101.0 h 101.0\n" +
          "FLASER " + beams + " 9 6 3.141592653589793 9 6 3.141592653589793 102.0 h 102.0\n");
  const std::vector<SE2> trajectory = correctedTrajectory(log);
  ASSERT_EQ(trajectory.size(), 3u);
  expectNear(trajectory[0], SE2(), 1e-12);
  expectNear(trajectory[1], SE2(1.0, 0.0, 0.0), 1e-12);  // one metre ahead (it faced +y)
  expectNear(trajectory[2], SE2(1.0, 1.0, M_PI / 2.0), 1e-12);
}

TEST(TeamEvaluationTest, AnEstimateInATurnedFrameIsLaidOnTheCorrectedTrajectory) {
  const std::vector<SE2> corrected = {SE2(), SE2(1.0, 0.0, 0.0), SE2(2.0, 0.5, 0.4),
                                      SE2(2.5, 1.5, 1.2), SE2(2.0, 2.5, 2.0)};
  const SE2 T_c_e(0.2, -0.3, 0.15);  // the filter's frame, turned and shifted
  std::vector<SE2> estimated;
  for (const SE2& pose : corrected) {
    estimated.push_back(T_c_e.inverse() * pose);
  }
  expectNear(estimateToCorrected(estimated, corrected), T_c_e, 1e-9);
  EXPECT_THROW(estimateToCorrected({}, corrected), std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::tools
