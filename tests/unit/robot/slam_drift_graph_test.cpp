#include "mrslam/robot/slam/drift_graph.hpp"

#include <gtest/gtest.h>

namespace mrslam::robot::slam {
namespace {

// Nodes 1 m apart along the path: node i has travelled i metres.
DriftGraph straightPath(int nodes) {
  DriftGraph graph;
  for (int i = 0; i < nodes; ++i) {
    graph.addNode(static_cast<double>(i));
  }
  return graph;
}

TEST(DriftGraphTest, WithoutClosuresTheDriftIsThePathBetween) {
  DriftGraph graph = straightPath(10);
  const std::vector<double>& drift = graph.distancesFrom(7, 100.0);
  ASSERT_EQ(drift.size(), 10u);
  EXPECT_DOUBLE_EQ(drift[7], 0.0);
  EXPECT_DOUBLE_EQ(drift[0], 7.0);
  EXPECT_DOUBLE_EQ(drift[9], 2.0);
}

TEST(DriftGraphTest, AClosureIsAShortcutOfNoLength) {
  DriftGraph graph = straightPath(100);
  graph.addShortcut(90, 10);  // the loop closed: node 90 is back at node 10
  const std::vector<double>& drift = graph.distancesFrom(95, 1000.0);
  EXPECT_DOUBLE_EQ(drift[90], 5.0);
  EXPECT_DOUBLE_EQ(drift[10], 5.0);  // through the closure, not 85 m of path
  EXPECT_DOUBLE_EQ(drift[0], 15.0);
  EXPECT_DOUBLE_EQ(drift[30], 25.0);  // back through the closure: 5 + 20, not 65
  EXPECT_DOUBLE_EQ(drift[50], 45.0);  // the loop's far side: as far either way round
}

TEST(DriftGraphTest, AClosureElsewhereDoesNotShrinkTheDriftToAPlaceNeverRevisited) {
  DriftGraph graph = straightPath(100);
  graph.addShortcut(80, 60);  // a small loop late in the run
  const std::vector<double>& drift = graph.distancesFrom(99, 1000.0);
  EXPECT_DOUBLE_EQ(drift[60], 19.0);
  EXPECT_DOUBLE_EQ(drift[5], 74.0);  // the start: the path less the small loop, not 19 m
}

TEST(DriftGraphTest, NothingIsExploredBeyondTheHorizon) {
  DriftGraph graph = straightPath(50);
  const std::vector<double>& drift = graph.distancesFrom(0, 10.0);
  EXPECT_DOUBLE_EQ(drift[9], 9.0);
  EXPECT_DOUBLE_EQ(drift[10], 10.0);
  EXPECT_DOUBLE_EQ(drift[49], 10.0);
}

TEST(DriftGraphTest, ClearedShortcutsAndBadNodesChangeNothing) {
  DriftGraph graph = straightPath(20);
  graph.addShortcut(19, 0);
  graph.addShortcut(-1, 3);  // unknown nodes and a node with itself are ignored
  graph.addShortcut(3, 20);
  graph.addShortcut(4, 4);
  EXPECT_DOUBLE_EQ(graph.distancesFrom(19, 100.0)[1], 1.0);
  graph.clearShortcuts();
  EXPECT_DOUBLE_EQ(graph.distancesFrom(19, 100.0)[1], 18.0);
  EXPECT_DOUBLE_EQ(graph.distancesFrom(25, 100.0)[0], 100.0);  // no such source: all capped
}

}  // namespace
}  // namespace mrslam::robot::slam
