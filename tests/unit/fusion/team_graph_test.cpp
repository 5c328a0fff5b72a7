#include "mrslam/fusion/team_graph.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>

namespace mrslam::fusion {
namespace {

PairwiseEstimate estimateOf(const std::string& from, const std::string& to, const SE2& T,
                            double verification) {
  PairwiseEstimate estimate;
  estimate.from = from;
  estimate.to = to;
  estimate.T_to_from = T;
  estimate.verification = verification;
  estimate.method = "test";
  return estimate;
}

void expectPose(const SE2& actual, const SE2& expected) {
  EXPECT_NEAR(actual.x(), expected.x(), 1e-9);
  EXPECT_NEAR(actual.y(), expected.y(), 1e-9);
  EXPECT_NEAR(wrapAngle(actual.theta() - expected.theta()), 0.0, 1e-9);
}

TEST(TeamGraphTest, ChainsTransformsAndInvertsEdgesStoredTheOtherWay) {
  TeamGraph graph;
  const SE2 T_a_b(2.0, 0.0, M_PI / 2);
  const SE2 T_c_b(0.0, 1.0, -0.3);  // stored as b → c: placing c needs its inverse
  ASSERT_TRUE(graph.addVerified(estimateOf("b", "a", T_a_b, 0.9)));
  ASSERT_TRUE(graph.addVerified(estimateOf("b", "c", T_c_b, 0.8)));
  const auto placements = graph.place("a", {"a", "b", "c", "d"});
  ASSERT_EQ(placements.size(), 4u);
  EXPECT_TRUE(placements[0].placed);
  expectPose(placements[1].T_reference_robot, T_a_b);
  EXPECT_DOUBLE_EQ(*placements[1].verification, 0.9);
  expectPose(placements[2].T_reference_robot, T_a_b * T_c_b.inverse());
  EXPECT_DOUBLE_EQ(*placements[2].verification, 0.8);  // the weakest link of the path
  EXPECT_FALSE(placements[3].placed);
  const auto reverse = graph.estimate("a", "b");
  ASSERT_TRUE(reverse.has_value());
  expectPose(reverse->T_to_from, T_a_b.inverse());
}

TEST(TeamGraphTest, KeepsTheBetterVerifiedEstimateAndNeverReplacesConfiguredOnes) {
  TeamGraph graph;
  EXPECT_TRUE(graph.addVerified(estimateOf("b", "a", SE2(1, 0, 0), 0.8)));
  EXPECT_FALSE(graph.addVerified(estimateOf("b", "a", SE2(5, 0, 0), 0.7)));
  EXPECT_TRUE(graph.addVerified(estimateOf("a", "b", SE2(-1.1, 0, 0), 0.85)));
  expectPose(graph.estimate("b", "a")->T_to_from, SE2(1.1, 0, 0));
  graph.addConfigured("c", "a", SE2(0, 3, 0));
  EXPECT_FALSE(graph.addVerified(estimateOf("c", "a", SE2(0, 4, 0), 0.99)));
  const auto placements = graph.place("a", {"c"});
  EXPECT_EQ(placements[0].source, "config");
  EXPECT_FALSE(placements[0].verification.has_value());
}

TEST(TeamGraphTest, AMergeOfFinalMapsReplacesEarlierOnesWhateverTheirV) {
  TeamGraph graph;
  EXPECT_TRUE(graph.addVerified(estimateOf("b", "a", SE2(1.0, 0, 0), 0.99)));  // early, small
  PairwiseEstimate final_merge = estimateOf("b", "a", SE2(1.05, 0, 0), 0.95);
  final_merge.from_final_maps = true;
  EXPECT_TRUE(graph.addVerified(final_merge));
  expectPose(graph.estimate("b", "a")->T_to_from, SE2(1.05, 0, 0));
  EXPECT_FALSE(graph.addVerified(estimateOf("b", "a", SE2(0.9, 0, 0), 0.999)));  // not final
  PairwiseEstimate better_final = estimateOf("b", "a", SE2(1.04, 0, 0), 0.96);
  better_final.from_final_maps = true;
  EXPECT_TRUE(graph.addVerified(better_final));  // among final merges, V decides
  expectPose(graph.estimate("b", "a")->T_to_from, SE2(1.04, 0, 0));
}

TEST(TeamGraphTest, WithdrawsOnlyTheEstimateGivenAndNeverAConfiguredOne) {
  TeamGraph graph;
  const SE2 T_a_b(1.0, 2.0, 0.4);
  ASSERT_TRUE(graph.addVerified(estimateOf("b", "a", T_a_b, 0.9)));
  EXPECT_FALSE(graph.withdraw("b", "a", SE2(1.0, 2.0 + 1e-6, 0.4))) << "another estimate";
  EXPECT_FALSE(graph.withdraw("b", "c", T_a_b)) << "another pair";
  ASSERT_TRUE(graph.estimate("b", "a").has_value());
  EXPECT_TRUE(graph.withdraw("a", "b", T_a_b.inverse())) << "the same one, named the other way";
  EXPECT_FALSE(graph.estimate("b", "a").has_value());
  EXPECT_FALSE(graph.place("a", {"b"})[0].placed) << "b is no longer placed";
  EXPECT_FALSE(graph.withdraw("b", "a", T_a_b)) << "already gone";
  graph.addConfigured("c", "a", SE2(0, 3, 0));
  EXPECT_FALSE(graph.withdraw("c", "a", SE2(0, 3, 0)));
  EXPECT_TRUE(graph.place("a", {"c"})[0].placed);
}

TEST(TeamGraphTest, ReplacesTheEstimateNamedWhateverItsVAndOtherwiseKeepsTheBetter) {
  TeamGraph graph;
  const SE2 T_early(1.0, 2.0, 0.4);
  ASSERT_TRUE(graph.addVerified(estimateOf("b", "a", T_early, 0.99)));
  // Named the other way round, the held estimate is still the one replaced, at a lower V.
  EXPECT_TRUE(graph.replaceVerified(estimateOf("a", "b", SE2(-3, 0, 0), 0.9), T_early.inverse()));
  expectPose(graph.estimate("b", "a")->T_to_from, SE2(3, 0, 0));
  EXPECT_DOUBLE_EQ(graph.estimate("b", "a")->verification, 0.9);
  // Naming an estimate not held: addVerified's rule, so a lower V does not replace.
  EXPECT_FALSE(graph.replaceVerified(estimateOf("b", "a", SE2(7, 0, 0), 0.8), T_early));
  expectPose(graph.estimate("b", "a")->T_to_from, SE2(3, 0, 0));
  EXPECT_TRUE(graph.replaceVerified(estimateOf("b", "a", SE2(8, 0, 0), 0.95), T_early));
  expectPose(graph.estimate("b", "a")->T_to_from, SE2(8, 0, 0));
  // A configured transform is never replaced.
  graph.addConfigured("c", "a", SE2(0, 3, 0));
  EXPECT_FALSE(graph.replaceVerified(estimateOf("c", "a", SE2(0, 4, 0), 0.99), SE2(0, 3, 0)));
  expectPose(graph.estimate("c", "a")->T_to_from, SE2(0, 3, 0));
}

TEST(TeamGraphTest, AReaderNeverSeesAPairWithoutAnEdgeWhileItsEstimateIsReplaced) {
  TeamGraph graph;
  const SE2 T_one(1.0, 0.0, 0.1);
  const SE2 T_two(2.0, 0.0, 0.2);
  ASSERT_TRUE(graph.addVerified(estimateOf("b", "a", T_one, 0.9)));
  std::atomic<bool> done{false};
  std::atomic<int> reads{0};
  std::atomic<int> unplaced{0};
  std::thread reader([&] {
    while (!done.load() || reads.load() == 0) {
      unplaced += graph.estimate("b", "a").has_value() ? 0 : 1;
      ++reads;
    }
  });
  int not_stored = 0;  // counted, not asserted here: the reader thread must be joined first
  for (int i = 0; i < 20000; ++i) {
    const bool odd = i % 2 == 1;
    not_stored +=
        graph.replaceVerified(estimateOf("b", "a", odd ? T_one : T_two, 0.9), odd ? T_two : T_one)
            ? 0
            : 1;
  }
  done = true;
  reader.join();
  EXPECT_EQ(not_stored, 0) << "every replacement is stored";
  EXPECT_GT(reads.load(), 0);
  EXPECT_EQ(unplaced.load(), 0) << "of " << reads.load() << " reads";
  expectPose(graph.estimate("b", "a")->T_to_from, T_one);
}

TEST(TeamGraphTest, PlacesThroughThePathWithTheLargestProductOfV) {
  TeamGraph graph;
  // a-b direct but weak (0.6); a-c-b strong (0.95 · 0.95 = 0.90).
  graph.addVerified(estimateOf("b", "a", SE2(10, 0, 0), 0.6));
  graph.addVerified(estimateOf("c", "a", SE2(1, 0, 0), 0.95));
  graph.addVerified(estimateOf("b", "c", SE2(1, 0, 0), 0.95));
  const auto placements = graph.place("a", {"b"});
  expectPose(placements[0].T_reference_robot, SE2(2, 0, 0));
  EXPECT_DOUBLE_EQ(*placements[0].verification, 0.95);
}

TEST(TeamGraphTest, AnEdgeThatBreaksALoopIsDroppedAndReported) {
  // Three robots: a-b and b-c right, a-c a wrong merge (2 m and 20° off), less well verified.
  const SE2 T_a_b(4.0, 1.0, 0.5);
  const SE2 T_b_c(3.0, -2.0, -1.0);
  const SE2 wrong_T_a_c = T_a_b * T_b_c * SE2(2.0, 0.0, 20.0 * M_PI / 180.0);
  TeamGraph graph;
  graph.addVerified(estimateOf("b", "a", T_a_b, 0.97));
  graph.addVerified(estimateOf("c", "b", T_b_c, 0.96));
  graph.addVerified(estimateOf("c", "a", wrong_T_a_c, 0.93));
  const std::vector<DroppedEdge> dropped = graph.dropped();
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].estimate.verification, 0.93);
  // In the direction it is reported: the origin of `from` as the loop and the edge put it.
  const SE2 T_c_a = (T_a_b * T_b_c).inverse();
  const bool c_in_a = dropped[0].estimate.to == "a";
  const SE2 by_loop = c_in_a ? T_c_a.inverse() : T_c_a;
  const SE2 by_edge = c_in_a ? wrong_T_a_c : wrong_T_a_c.inverse();
  EXPECT_NEAR(dropped[0].translation_error_m,
              (by_loop.translation() - by_edge.translation()).norm(), 1e-9);
  EXPECT_GT(dropped[0].translation_error_m, 1.0);
  EXPECT_NEAR(dropped[0].rotation_error_rad, 20.0 * M_PI / 180.0, 1e-9);
  // c is placed through b, not through the wrong edge.
  const auto placements = graph.place("a", {"c"});
  ASSERT_TRUE(placements[0].placed);
  expectPose(placements[0].T_reference_robot, T_a_b * T_b_c);
  EXPECT_DOUBLE_EQ(*placements[0].verification, 0.96);
}

TEST(TeamGraphTest, EdgesThatCloseALoopWithinTheToleranceAreAllKept) {
  const SE2 T_a_b(4.0, 1.0, 0.5);
  const SE2 T_b_c(3.0, -2.0, -1.0);
  TeamGraph graph;
  graph.addVerified(estimateOf("b", "a", T_a_b, 0.97));
  graph.addVerified(estimateOf("c", "b", T_b_c, 0.96));
  // 5 cm and 0.5° off the loop: map noise, not a wrong merge.
  graph.addVerified(estimateOf("c", "a", T_a_b * T_b_c * SE2(0.05, 0.0, 0.5 * M_PI / 180.0), 0.99));
  EXPECT_TRUE(graph.dropped().empty());
  // With a looser V on a-b, the loop is still whole; c goes through the best path (a-c).
  const auto placements = graph.place("a", {"b", "c"});
  EXPECT_TRUE(placements[0].placed);
  EXPECT_TRUE(placements[1].placed);
  EXPECT_DOUBLE_EQ(*placements[1].verification, 0.99);
}

TEST(TeamGraphTest, RedundantPairsPlaceRobotsByLeastSquaresBetweenThePaths) {
  const SE2 T_a_b(4.0, 1.0, 0.5);
  const SE2 T_b_c(3.0, -2.0, -1.0);
  const SE2 T_a_c = T_a_b * T_b_c;
  TeamGraph graph;
  graph.addVerified(estimateOf("b", "a", T_a_b, 0.97));
  graph.addVerified(estimateOf("c", "b", T_b_c, 0.97));
  // The direct estimate puts c 0.1 m off (along a's x): within the loop tolerance.
  graph.addVerified(estimateOf("c", "a", SE2(0.1, 0.0, 0.0) * T_a_c, 0.97));
  ASSERT_TRUE(graph.dropped().empty());
  const auto placements = graph.place("a", {"a", "b", "c"});
  EXPECT_FALSE(placements[0].least_squares) << "the reference stays where it is";
  EXPECT_TRUE(placements[1].least_squares);
  EXPECT_TRUE(placements[2].least_squares);
  EXPECT_EQ(placements[2].methods, "test");
  // Equal weights: c lands between its two paths, not on either.
  const double c_x = placements[2].T_reference_robot.x();
  EXPECT_GT(c_x, T_a_c.x() + 0.02);
  EXPECT_LT(c_x, T_a_c.x() + 0.08);
  EXPECT_NEAR(placements[2].T_reference_robot.y(), T_a_c.y(), 0.02);
}

TEST(TeamGraphTest, WithoutALoopPlacementsAreThePathsExactly) {
  const SE2 T_a_b(4.0, 1.0, 0.5);
  TeamGraph graph;
  graph.addVerified(estimateOf("b", "a", T_a_b, 0.97));
  const auto placements = graph.place("a", {"b"});
  EXPECT_FALSE(placements[0].least_squares);
  expectPose(placements[0].T_reference_robot, T_a_b);
}

TEST(TeamGraphTest, AConfiguredTransformIsNeverDroppedByALoop) {
  TeamGraph graph;
  graph.addConfigured("b", "a", SE2(4.0, 0.0, 0.0));
  graph.addConfigured("c", "b", SE2(4.0, 0.0, 0.0));
  graph.addVerified(estimateOf("c", "a", SE2(1.0, 0.0, 0.0), 0.99));  // disagrees with config
  const std::vector<DroppedEdge> dropped = graph.dropped();
  ASSERT_EQ(dropped.size(), 1u);
  EXPECT_EQ(dropped[0].estimate.method, "test");
  expectPose(graph.place("a", {"c"})[0].T_reference_robot, SE2(8.0, 0.0, 0.0));
}

}  // namespace
}  // namespace mrslam::fusion
