#include "mrslam/fusion/merge_scheduler.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace mrslam::fusion {
namespace {

// A merger whose answer the test sets; it counts its calls (from any merge thread).
class ScriptedMerger : public MapMerger {
 public:
  /// `shift_cells`: the accepted transform's shift along x.
  ScriptedMerger(std::atomic<int>& calls, bool accept, double shift_cells = 10.0)
      : calls_(calls), accept_(accept), shift_cells_(shift_cells) {}
  MergeResult merge(const GridMap&, const GridMap&) override {
    ++calls_;
    MergeResult result;
    result.accepted = accept_;
    result.method = "scripted";
    result.verification = 0.9;
    result.T_to_from.t_cells = Eigen::Vector2d(shift_cells_, 0.0);
    result.reason = accept_ ? "" : "no match";
    return result;
  }
  std::string name() const override { return "scripted"; }

 private:
  std::atomic<int>& calls_;
  bool accept_;
  double shift_cells_;
};

// A merger that waits (up to 10 s) until `wanted` merges are running at once, and records the
// most it saw; it refuses with the pair's size in its reason.
class MeetingMerger : public MapMerger {
 public:
  MeetingMerger(std::atomic<int>& running, std::atomic<int>& most, int wanted)
      : running_(running), most_(most), wanted_(wanted) {}
  MergeResult merge(const GridMap& from, const GridMap& to) override {
    const int now = ++running_;
    int seen = most_.load();
    while (now > seen && !most_.compare_exchange_weak(seen, now)) {
    }
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (most_.load() < wanted_ && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    --running_;
    MergeResult result;
    result.reason =
        std::to_string(knownCellCount(from)) + " onto " + std::to_string(knownCellCount(to));
    return result;
  }
  std::string name() const override { return "meeting"; }

 private:
  std::atomic<int>& running_;
  std::atomic<int>& most_;
  int wanted_;
};

RobotMap mapOf(const std::string& id, int known_cells) {
  RobotMap map;
  map.robot_id = id;
  GridGeometry geometry;
  geometry.resolution_m = 0.1;
  geometry.width = 100;
  geometry.height = 100;
  map.map = GridMap(geometry, GridMap::kUnknown);
  for (int i = 0; i < known_cells; ++i) {
    map.map.cells[static_cast<std::size_t>(i)] = 0;
  }
  return map;
}

/// A verified estimate of b's origin in a's frame.
PairwiseEstimate verifiedBOntoA(const SE2& T_a_b, double verification) {
  PairwiseEstimate estimate;
  estimate.from = "b";
  estimate.to = "a";
  estimate.T_to_from = T_a_b;
  estimate.verification = verification;
  estimate.method = "scripted";
  return estimate;
}

/// Settings that merge a pair again in every round whose maps grew.
MergeSchedulerSettings everyRound() {
  MergeSchedulerSettings settings;
  settings.min_interval_s = 0.0;
  return settings;
}

TEST(MergeSchedulerTest, MergesNewPairsThenOnlyAfterTheIntervalAndMaterialChange) {
  TeamGraph graph;
  std::atomic<int> calls{0};
  MergeSchedulerSettings settings;
  settings.min_interval_s = 10.0;
  settings.material_change = 0.1;
  settings.confirmations = 1;  // the first accepted merge is used at once
  MergeScheduler scheduler(
      settings, [&] { return std::make_unique<ScriptedMerger>(calls, true); }, graph);
  const auto t0 = MergeScheduler::Clock::now();
  std::vector<RobotMap> maps = {mapOf("a", 1000), mapOf("b", 1000), mapOf("c", 0)};
  // a-b merged; c knows nothing yet.
  auto attempts = scheduler.runDue(maps, t0);
  ASSERT_EQ(attempts.size(), 1u);
  EXPECT_EQ(attempts[0].from, "b");
  EXPECT_EQ(attempts[0].to, "a");
  EXPECT_TRUE(attempts[0].result.accepted);
  EXPECT_NEAR(attempts[0].T_to_from.x(), 1.0, 1e-9);  // 10 cells of 0.1 m
  ASSERT_TRUE(graph.estimate("b", "a").has_value());
  // Too soon, and too little change.
  EXPECT_TRUE(scheduler.runDue(maps, t0 + std::chrono::seconds(1)).empty());
  maps[0] = mapOf("a", 1050);
  EXPECT_TRUE(scheduler.runDue(maps, t0 + std::chrono::seconds(20)).empty());
  maps[0] = mapOf("a", 1200);
  EXPECT_TRUE(scheduler.runDue(maps, t0 + std::chrono::seconds(5)).empty());
  EXPECT_EQ(scheduler.runDue(maps, t0 + std::chrono::seconds(20)).size(), 1u);
  // c learns something: its pairs are due at once.
  maps[2] = mapOf("c", 500);
  EXPECT_EQ(scheduler.runDue(maps, t0 + std::chrono::seconds(21)).size(), 2u);
  EXPECT_EQ(calls, 4);
}

TEST(MergeSchedulerTest, FinalMapsAreMergedOnceMoreWhateverTheInterval) {
  TeamGraph graph;
  std::atomic<int> calls{0};
  MergeSchedulerSettings settings;
  settings.min_interval_s = 100.0;
  MergeScheduler scheduler(
      settings, [&] { return std::make_unique<ScriptedMerger>(calls, false); }, graph);
  const auto t0 = MergeScheduler::Clock::now();
  std::vector<RobotMap> maps = {mapOf("a", 1000), mapOf("b", 1000)};
  ASSERT_EQ(scheduler.runDue(maps, t0).size(), 1u);
  // Only a's map is final: the interval still holds.
  maps[0].is_final = true;
  EXPECT_TRUE(scheduler.runDue(maps, t0 + std::chrono::seconds(1)).empty());
  // Both final (with no material change): merged at once, and only once.
  maps[1].is_final = true;
  EXPECT_EQ(scheduler.runDue(maps, t0 + std::chrono::seconds(2)).size(), 1u);
  EXPECT_TRUE(scheduler.runDue(maps, t0 + std::chrono::seconds(3)).empty());
  EXPECT_EQ(calls, 2);
}

TEST(MergeSchedulerTest, RefusalsLeaveVerifiedTransformsInPlace) {
  TeamGraph graph;
  graph.addVerified(verifiedBOntoA(SE2(3, 0, 0), 0.9));
  std::atomic<int> calls{0};
  MergeScheduler scheduler(
      MergeSchedulerSettings{}, [&] { return std::make_unique<ScriptedMerger>(calls, false); },
      graph);
  const auto attempts =
      scheduler.runDue({mapOf("a", 10), mapOf("b", 10)}, MergeScheduler::Clock::now());
  ASSERT_EQ(attempts.size(), 1u);
  EXPECT_FALSE(attempts[0].result.accepted);
  EXPECT_EQ(attempts[0].result.reason, "no match");
  EXPECT_NEAR(graph.estimate("b", "a")->T_to_from.x(), 3.0, 1e-12);
}

TEST(MergeSchedulerTest, BackgroundThreadMergesOfferedMaps) {
  TeamGraph graph;
  std::atomic<int> calls{0};
  MergeScheduler scheduler(
      MergeSchedulerSettings{}, [&] { return std::make_unique<ScriptedMerger>(calls, true); },
      graph);
  scheduler.start();
  scheduler.offer({mapOf("a", 10), mapOf("b", 10)});
  ASSERT_TRUE(scheduler.waitIdle(30.0));
  EXPECT_EQ(scheduler.takeAttempts().size(), 1u);
  EXPECT_TRUE(scheduler.takeAttempts().empty());
  scheduler.stop();
  EXPECT_EQ(calls, 1);
}

// Three robots' maps: their three pairs merged two at a time with `threads` 2, one at a time with
// 1; either way the attempts come in pair order.
TEST(MergeSchedulerTest, DuePairsAreMergedOnTheConfiguredThreadsInPairOrder) {
  for (const int threads : {2, 1}) {
    TeamGraph graph;
    std::atomic<int> running{0};
    std::atomic<int> most{0};
    MergeSchedulerSettings settings;
    settings.threads = threads;
    MergeScheduler scheduler(
        settings, [&] { return std::make_unique<MeetingMerger>(running, most, threads); }, graph);
    const auto attempts = scheduler.runDue({mapOf("a", 10), mapOf("b", 20), mapOf("c", 30)},
                                           MergeScheduler::Clock::now());
    EXPECT_EQ(most.load(), threads) << "merges running at once";
    ASSERT_EQ(attempts.size(), 3u);
    EXPECT_EQ(attempts[0].from + attempts[0].to + attempts[0].result.reason, "ba20 onto 10");
    EXPECT_EQ(attempts[1].from + attempts[1].to + attempts[1].result.reason, "ca30 onto 10");
    EXPECT_EQ(attempts[2].from + attempts[2].to + attempts[2].result.reason, "cb30 onto 20");
  }
}

TEST(MergeSchedulerTest, PairsWithoutAVerifiedTransformAreMergedBeforeRefinements) {
  TeamGraph graph;
  ASSERT_TRUE(graph.addVerified(verifiedBOntoA(SE2(), 0.95)));
  std::atomic<int> running{0};
  std::atomic<int> most{0};
  MergeSchedulerSettings settings;
  settings.threads = 1;
  MergeScheduler scheduler(
      settings, [&] { return std::make_unique<MeetingMerger>(running, most, 1); }, graph);
  const auto attempts = scheduler.runDue({mapOf("a", 10), mapOf("b", 20), mapOf("c", 30)},
                                         MergeScheduler::Clock::now());
  ASSERT_EQ(attempts.size(), 3u);
  EXPECT_EQ(attempts[0].from + attempts[0].to, "ca") << "c is not placed: its pairs first";
  EXPECT_EQ(attempts[1].from + attempts[1].to, "cb");
  EXPECT_EQ(attempts[2].from + attempts[2].to, "ba") << "the refinement of a placed pair last";
}

/// Maps of a and b with `known` cells each, final or not.
std::vector<RobotMap> pairOfMaps(int known, bool is_final) {
  std::vector<RobotMap> maps = {mapOf("a", known), mapOf("b", known)};
  maps[0].is_final = maps[1].is_final = is_final;
  return maps;
}

TEST(MergeSchedulerTest, AMergeOfGrowingMapsIsUsedOnceASecondOneAgrees) {
  TeamGraph graph;
  std::atomic<int> calls{0};
  double shift_cells = 10.0;  // 1 m: the merger's answer, changed between rounds
  MergeScheduler scheduler(
      everyRound(), [&] { return std::make_unique<ScriptedMerger>(calls, true, shift_cells); },
      graph);
  const auto t0 = MergeScheduler::Clock::now();
  const auto first = scheduler.runDue(pairOfMaps(100, false), t0);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_TRUE(first[0].result.accepted);
  EXPECT_EQ(first[0].result.reason,
            "held back; not used until 1 more merge(s) of grown maps agree");
  EXPECT_FALSE(graph.estimate("b", "a").has_value()) << "one accepted merge is not yet used";
  shift_cells = 40.0;  // the grown maps put b 3 m away: no agreement
  ASSERT_EQ(scheduler.runDue(pairOfMaps(200, false), t0).size(), 1u);
  EXPECT_FALSE(graph.estimate("b", "a").has_value()) << "two merges that disagree";
  shift_cells = 42.0;  // 20 cm from the last: it confirms that one
  ASSERT_EQ(scheduler.runDue(pairOfMaps(300, false), t0).size(), 1u);
  ASSERT_TRUE(graph.estimate("b", "a").has_value());
  EXPECT_NEAR(graph.estimate("b", "a")->T_to_from.x(), 4.2, 1e-9) << "the latest is used";
  shift_cells = 43.0;  // it agrees with the estimate in use: a refinement, used at once
  ASSERT_EQ(scheduler.runDue(pairOfMaps(400, false), t0).size(), 1u);
  EXPECT_NEAR(graph.estimate("b", "a")->T_to_from.x(), 4.3, 1e-9)
      << "the refinement is used (V as high)";
  EXPECT_EQ(calls, 4);
}

TEST(MergeSchedulerTest, TwoAgreeingMergesOfGrownMapsReplaceADisagreeingEstimateInUse) {
  TeamGraph graph;
  // In use, with a V the later merges do not reach.
  ASSERT_TRUE(graph.addVerified(verifiedBOntoA(SE2(-3.0, 0.5, 3.1), 0.997)));
  std::atomic<int> calls{0};
  MergeScheduler scheduler(
      everyRound(), [&] { return std::make_unique<ScriptedMerger>(calls, true); }, graph);
  const auto t0 = MergeScheduler::Clock::now();
  const auto first = scheduler.runDue(pairOfMaps(100, false), t0);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0].result.reason,
            "held back; not used until 1 more merge(s) of grown maps agree (it disagrees with the "
            "estimate in use)");
  EXPECT_NEAR(graph.estimate("b", "a")->T_to_from.x(), -3.0, 1e-9);
  ASSERT_EQ(scheduler.runDue(pairOfMaps(200, false), t0).size(), 1u);
  const std::optional<PairwiseEstimate> now = graph.estimate("b", "a");
  ASSERT_TRUE(now.has_value());
  EXPECT_NEAR(now->T_to_from.x(), 1.0, 1e-9) << "the two agreeing merges (V 0.9) replaced it";
  EXPECT_NEAR(now->verification, 0.9, 1e-12);
}

TEST(MergeSchedulerTest, AMergeOfBothFinalMapsIsUsedAtOnce) {
  TeamGraph graph;
  std::atomic<int> calls{0};
  MergeScheduler scheduler(
      MergeSchedulerSettings{}, [&] { return std::make_unique<ScriptedMerger>(calls, true); },
      graph);
  ASSERT_EQ(scheduler.runDue(pairOfMaps(100, true), MergeScheduler::Clock::now()).size(), 1u);
  ASSERT_TRUE(graph.estimate("b", "a").has_value());
  EXPECT_TRUE(graph.estimate("b", "a")->from_final_maps);
}

TEST(MergeSchedulerTest, AWrongEarlyMergeIsNeverUsedWhenTheGrownMapsRefuseThePair) {
  TeamGraph graph;
  std::atomic<int> calls{0};
  bool accept = true;
  MergeScheduler scheduler(
      everyRound(), [&] { return std::make_unique<ScriptedMerger>(calls, accept); }, graph);
  const auto t0 = MergeScheduler::Clock::now();
  const auto first = scheduler.runDue(pairOfMaps(100, false), t0);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_TRUE(first[0].result.accepted) << "the attempt still says what the merger found";
  accept = false;
  scheduler.runDue(pairOfMaps(200, false), t0);
  scheduler.runDue(pairOfMaps(300, true), t0);
  EXPECT_FALSE(graph.estimate("b", "a").has_value());
  EXPECT_EQ(calls, 3);
}

// A merger that throws on a merge thread: the attempt says so and nothing stops.
TEST(MergeSchedulerTest, AMergeThatThrowsIsAFailedAttempt) {
  class ThrowingMerger : public MapMerger {
   public:
    MergeResult merge(const GridMap&, const GridMap&) override {
      throw std::runtime_error("out of memory");
    }
    std::string name() const override { return "throwing"; }
  };
  TeamGraph graph;
  MergeScheduler scheduler(
      MergeSchedulerSettings{}, [] { return std::make_unique<ThrowingMerger>(); }, graph);
  const auto attempts = scheduler.runDue({mapOf("a", 10), mapOf("b", 10), mapOf("c", 10)},
                                         MergeScheduler::Clock::now());
  ASSERT_EQ(attempts.size(), 3u);
  for (const MergeAttempt& attempt : attempts) {
    EXPECT_FALSE(attempt.result.accepted);
    EXPECT_EQ(attempt.result.reason, "the merge failed: out of memory");
  }
}

}  // namespace
}  // namespace mrslam::fusion
