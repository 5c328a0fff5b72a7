// The pose graph: a corridor loop whose odometry drifts is straightened by its closure, and a
// wrong closure is refused by its residual and moves no pose beyond a tolerance.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mrslam/robot/slam/pose_graph.hpp"

namespace mrslam::robot::slam {
namespace {

// A square loop of corridors, 10 m a side: the true node poses every 0.25 m, turning 90° at
// each corner.
std::vector<SE2> squareLoop() {
  std::vector<SE2> poses;
  SE2 pose;
  for (int side = 0; side < 4; ++side) {
    for (int step = 0; step < 40; ++step) {
      poses.push_back(pose);
      pose = pose * SE2(0.25, 0.0, step == 39 ? M_PI / 2 : 0.0);
    }
  }
  return poses;
}

// The loop as local SLAM sees it: each step's turn off by a little, so the heading drifts.
std::vector<SE2> driftedLoop(const std::vector<SE2>& truth, double turn_error_rad) {
  std::vector<SE2> local{truth.front()};
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const SE2 step = truth[i - 1].inverse() * truth[i];
    local.push_back(local.back() * SE2(step.x(), step.y(), step.theta() + turn_error_rad));
  }
  return local;
}

// A graph with one submap per 20 nodes (at its first node), intra constraints from the local
// poses, and the given closures of node → submap 0.
struct LoopGraph {
  PoseGraph graph;
  std::vector<SE2> local;

  explicit LoopGraph(const std::vector<SE2>& local_poses,
                     const PoseGraphSettings& settings = PoseGraphSettings{})
      : graph(settings), local(local_poses) {
    constexpr int kNodesPerSubmap = 20;
    for (std::size_t i = 0; i < local.size(); ++i) {
      if (i % kNodesPerSubmap == 0) {
        graph.addSubmap(local[i]);
      }
      const int node = graph.addNode(local[i], local[i]);
      const int submap = static_cast<int>(i / kNodesPerSubmap);
      graph.addConstraint(
          {submap, node,
           local[static_cast<std::size_t>(submap) * kNodesPerSubmap].inverse() * local[i],
           PoseGraphConstraint::Kind::kIntraSubmap, true});
    }
  }
  void close(int node, const SE2& T_submap0_node) {
    graph.addConstraint({0, node, T_submap0_node, PoseGraphConstraint::Kind::kLoopClosure, true});
  }
};

double worstError(const PoseGraph& graph, const std::vector<SE2>& truth) {
  double worst = 0.0;
  for (int i = 0; i < graph.nodeCount(); ++i) {
    worst = std::max(
        worst, (graph.nodePose(i).translation() - truth[static_cast<std::size_t>(i)].translation())
                   .norm());
  }
  return worst;
}

TEST(PoseGraphTest, ACorridorLoopIsStraightenedByItsClosures) {
  const std::vector<SE2> truth = squareLoop();
  LoopGraph loop(driftedLoop(truth, 0.002));
  const double drifted = worstError(loop.graph, truth);
  ASSERT_GT(drifted, 1.0);  // the drift bends the loop by more than a metre
  // The last nodes see the first submap again, where they truly are.
  for (int node = 150; node < 160; ++node) {
    loop.close(node, truth.front().inverse() * truth[static_cast<std::size_t>(node)]);
  }
  loop.graph.optimise();
  EXPECT_LT(worstError(loop.graph, truth), 0.25 * drifted);
  EXPECT_LT((loop.graph.nodePose(159).translation() - truth[159].translation()).norm(), 0.05);
  EXPECT_EQ(loop.graph.counters().closures_refused, 0u);
}

TEST(PoseGraphTest, AWrongClosureIsRefusedAndBendsNothing) {
  const std::vector<SE2> truth = squareLoop();
  // Closures under a Huber loss from 3 σ: with the default 10 σ one wrong closure in a graph
  // this sparse (ten right closures on one submap) pulls the loop metres before it is judged.
  PoseGraphSettings settings;
  settings.closure_huber_scale = 3.0;
  LoopGraph right(driftedLoop(truth, 0.0005), settings);
  LoopGraph wrong(driftedLoop(truth, 0.0005), settings);
  for (LoopGraph* loop : {&right, &wrong}) {
    for (int node = 150; node < 160; ++node) {
      loop->close(node, truth.front().inverse() * truth[static_cast<std::size_t>(node)]);
    }
  }
  // Node 80 (the far corner) "seen" in submap 0 at 3 m from where it is: a corridor that looks
  // alike.
  wrong.close(80, truth.front().inverse() * truth[80] * SE2(3.0, 0.0, 0.2));
  right.graph.optimise();
  wrong.graph.optimise();
  EXPECT_EQ(wrong.graph.counters().closures_refused, 1u);
  EXPECT_FALSE(wrong.graph.constraints().back().active);
  double moved = 0.0;
  for (int i = 0; i < right.graph.nodeCount(); ++i) {
    moved = std::max(
        moved,
        (wrong.graph.nodePose(i).translation() - right.graph.nodePose(i).translation()).norm());
  }
  EXPECT_LT(moved, 0.01);  // once refused, the solution is the one without it
}

TEST(PoseGraphTest, ConstraintsOnUnknownNodesAndBadSettingsAreRefused) {
  PoseGraph graph{PoseGraphSettings{}};
  graph.addSubmap(SE2());
  EXPECT_THROW(graph.addConstraint({0, 3, SE2(), PoseGraphConstraint::Kind::kIntraSubmap, true}),
               std::out_of_range);
  PoseGraphSettings bad;
  bad.closure_sigma_m = 0.0;
  EXPECT_THROW(PoseGraph{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace mrslam::robot::slam
