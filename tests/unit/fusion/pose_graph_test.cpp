// Least-squares placement of map frames from redundant pairwise transforms.

#include "mrslam/fusion/pose_graph.hpp"

#include <gtest/gtest.h>

#include <random>

namespace mrslam::fusion {
namespace {

PoseGraphEdge measured(const std::string& from, const std::string& to,
                       const std::map<std::string, SE2>& truth, const SE2& error = SE2()) {
  return {from, to, truth.at(to).inverse() * truth.at(from) * error, 0.05, 0.01};
}

double translationError(const SE2& a, const SE2& b) {
  return (a.translation() - b.translation()).norm();
}

TEST(PoseGraphTest, ErrorIsZeroAtTheTruthAndMeasuredInTheEdgeFrame) {
  const std::map<std::string, SE2> truth = {{"a", SE2()}, {"b", SE2(2.0, 1.0, 0.5)}};
  const PoseGraphEdge edge = measured("b", "a", truth);
  EXPECT_NEAR(edgeError(edge, truth.at("b"), truth.at("a")).norm(), 0.0, 1e-12);
  // b's origin 0.1 m further along its own x axis: an error of (0.1, 0, 0).
  const Eigen::Vector3d e = edgeError(edge, truth.at("b") * SE2(0.1, 0.0, 0.0), truth.at("a"));
  EXPECT_NEAR(e.x(), 0.1, 1e-12);
  EXPECT_NEAR(e.y(), 0.0, 1e-12);
  EXPECT_NEAR(e.z(), 0.0, 1e-12);
}

TEST(PoseGraphTest, ExactLoopConvergesToTheTruthFromAPerturbedStart) {
  const std::map<std::string, SE2> truth = {
      {"r1", SE2()}, {"r2", SE2(5.0, 1.0, 1.0)}, {"r3", SE2(-2.0, 4.0, -2.5)}};
  const std::vector<PoseGraphEdge> edges = {
      measured("r2", "r1", truth), measured("r3", "r2", truth), measured("r3", "r1", truth)};
  std::map<std::string, SE2> start = truth;
  start["r2"] = truth.at("r2") * SE2(0.4, -0.3, 0.2);
  start["r3"] = truth.at("r3") * SE2(-0.5, 0.2, -0.3);
  const PoseGraphResult result = optimisePoseGraph(start, edges, {"r1"});
  for (const auto& [robot, pose] : truth) {
    EXPECT_NEAR(translationError(result.T_reference_robot.at(robot), pose), 0.0, 1e-6) << robot;
    EXPECT_NEAR(wrapAngle(result.T_reference_robot.at(robot).theta() - pose.theta()), 0.0, 1e-6)
        << robot;
  }
  EXPECT_LT(result.final_cost, 1e-9);
  EXPECT_GT(result.initial_cost, 1.0);
}

TEST(PoseGraphTest, FixedRobotsDoNotMove) {
  const std::map<std::string, SE2> truth = {{"r1", SE2()}, {"r2", SE2(3.0, 0.0, 0.0)}};
  std::map<std::string, SE2> start = truth;
  start["r2"] = SE2(3.5, 0.0, 0.0);
  const PoseGraphResult result =
      optimisePoseGraph(start, {measured("r2", "r1", truth)}, {"r1", "r2"});
  EXPECT_NEAR(result.T_reference_robot.at("r2").x(), 3.5, 1e-12);
  EXPECT_EQ(result.iterations, 0);
}

// Noisy redundant estimates: the least-squares placement beats every single path, on average.
TEST(PoseGraphTest, RedundantNoisyEdgesBeatASpanningTreeOnAverage) {
  std::mt19937 random(7);
  std::normal_distribution<double> noise_t(0.0, 0.05);
  std::normal_distribution<double> noise_r(0.0, 0.01);
  const std::map<std::string, SE2> truth = {{"r1", SE2()},
                                            {"r2", SE2(6.0, 0.0, 0.3)},
                                            {"r3", SE2(6.0, 6.0, 1.2)},
                                            {"r4", SE2(0.0, 6.0, -0.7)}};
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"r2", "r1"}, {"r3", "r2"}, {"r4", "r3"}, {"r4", "r1"}, {"r3", "r1"}};
  double tree_error = 0.0;
  double least_squares_error = 0.0;
  constexpr int kTrials = 50;
  for (int trial = 0; trial < kTrials; ++trial) {
    std::vector<PoseGraphEdge> edges;
    for (const auto& [from, to] : pairs) {
      edges.push_back(
          measured(from, to, truth, SE2(noise_t(random), noise_t(random), noise_r(random))));
    }
    // The chain r1 <- r2 <- r3 <- r4 alone places r4 through three noisy edges.
    std::map<std::string, SE2> chain = {{"r1", SE2()}};
    chain["r2"] = chain["r1"] * edges[0].T_to_from;
    chain["r3"] = chain["r2"] * edges[1].T_to_from;
    chain["r4"] = chain["r3"] * edges[2].T_to_from;
    const PoseGraphResult result = optimisePoseGraph(chain, edges, {"r1"});
    EXPECT_LE(result.final_cost, result.initial_cost + 1e-9);
    for (const char* robot : {"r2", "r3", "r4"}) {
      tree_error += translationError(chain.at(robot), truth.at(robot));
      least_squares_error += translationError(result.T_reference_robot.at(robot), truth.at(robot));
    }
  }
  EXPECT_LT(least_squares_error, 0.8 * tree_error);
}

}  // namespace
}  // namespace mrslam::fusion
