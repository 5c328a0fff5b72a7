// Where a merge spends its time, block by block (block_times.hpp, MapMerger::lastBlockTimes):
// the names and order of the blocks that ran, and that their times add up within the merge's
// own. No test here bounds a time: the benchmarks measure them (BM_MergeBlocks400).

#include "mrslam/fusion/merge/block_times.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/exhaustive_merger.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::TwoBuildings;

// Negative case 200 of `--seed 1` (Carpin's robot 3 and the Intel lab): every step refuses it.
const TwoBuildings kRefusedByEveryStep{"carpin-robot3_cast.txt",
                                       {{24, -38}, 166, 1.6983886038110922, {15, 34}, {4, 4}},
                                       "carpin-intel.txt",
                                       {{222, 138}, 301, -0.05105007560627328, {0, 9}, {28, 14}}};

std::vector<std::string> namesOf(const BlockTimes& times) {
  std::vector<std::string> names;
  for (const BlockTime& time : times) {
    names.push_back(time.name);
  }
  return names;
}

// The merge's result and its wall-clock time, ms.
struct TimedResult {
  MergeResult result;
  double ms = 0.0;
};

TimedResult timedMerge(MapMerger& merger, const MergeCase& merge_case) {
  const auto start = std::chrono::steady_clock::now();
  TimedResult timed{merger.merge(merge_case.a, merge_case.b), 0.0};
  timed.ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return timed;
}

// Every block took a time of its own, and all of them no more than the merge.
void expectWithinTheMerge(const BlockTimes& times, double merge_ms) {
  for (const BlockTime& time : times) {
    EXPECT_GE(time.ms, 0.0) << time.name;
  }
  EXPECT_LE(totalMs(times), merge_ms);
}

TEST(BlockTimesTest, ABlockThatRunsTwiceIsOneEntryInTheOrderBlocksFirstRan) {
  BlockTimes times;
  addBlockTime(times, "search", 2.0);
  addBlockTime(times, "judge", 1.0);
  addBlockTime(times, "search", 0.5);
  ASSERT_EQ(namesOf(times), (std::vector<std::string>{"search", "judge"}));
  EXPECT_DOUBLE_EQ(times[0].ms, 2.5);
  EXPECT_DOUBLE_EQ(totalMs(times), 3.5);
  addBlockTimes(times, "exhaustive", {{"search", 1.0}, {"judge", 4.0}});
  EXPECT_EQ(namesOf(times),
            (std::vector<std::string>{"search", "judge", "exhaustive/search", "exhaustive/judge"}));
  EXPECT_DOUBLE_EQ(totalMs(times), 8.5);
}

TEST(BlockTimesTest, ATimedBlockReturnsItsResultAndAddsItsTime) {
  BlockTimes times;
  EXPECT_EQ(timeBlock(times, "answer", [] { return 42; }), 42);
  int runs = 0;
  timeBlock(times, "void", [&] { ++runs; });
  EXPECT_EQ(runs, 1);
  EXPECT_EQ(namesOf(times), (std::vector<std::string>{"answer", "void"}));
  expectWithinTheMerge(times, 1000.0);
}

TEST(BlockTimesTest, AClockLapIsTheTimeSinceTheLastLap) {
  BlockClock outer;
  BlockClock clock;
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double first = clock.lapMs();
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double second = clock.lapMs();
  const double both = outer.lapMs();
  // sleep_for blocks at least as long on the steady clock; a lap that did not restart would
  // count the first sleep twice.
  EXPECT_GE(first, 20.0);
  EXPECT_GE(second, 20.0);
  EXPECT_LE(first + second, both + 1e-9) << "each lap starts where the last one ended";
}

/// A step with a fixed answer that reports `blocks` as its last merge's.
class FixedStep : public MapMerger {
 public:
  FixedStep(std::string name, bool accept, BlockTimes blocks)
      : name_(std::move(name)), accept_(accept), blocks_(std::move(blocks)) {}
  MergeResult merge(const GridMap&, const GridMap&) override {
    MergeResult result;
    result.accepted = accept_;
    result.method = name_;
    result.reason = accept_ ? "" : "nothing";
    return result;
  }
  std::string name() const override { return name_; }
  BlockTimes lastBlockTimes() const override { return blocks_; }

 private:
  std::string name_;
  bool accept_;
  BlockTimes blocks_;
};

TEST(BlockTimesTest, AChainNamesEachStepByItsBlocksOrAsOneBlock) {
  std::vector<std::unique_ptr<MapMerger>> steps;
  steps.push_back(std::make_unique<FixedStep>("plain", false, BlockTimes{}));
  steps.push_back(std::make_unique<FixedStep>("timed", false, BlockTimes{{"inner", 0.0}}));
  ChainMerger chain(std::move(steps));
  for (int merge = 0; merge < 2; ++merge) {  // each merge's own blocks, none carried over
    EXPECT_FALSE(chain.merge(GridMap(), GridMap()).accepted);
    EXPECT_EQ(namesOf(chain.lastBlockTimes()),
              (std::vector<std::string>{"plain", "timed/inner", "timed/rest"}))
        << "merge " << merge;
  }
}

TEST(BlockTimesTest, TheExhaustiveMergerTimesItsBlocksInTurn) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  ExhaustiveMerger merger;
  const TimedResult placed =
      timedMerge(merger, merge_test::cut(merge_test::kIntelCaseZeroOfSeedOne));
  EXPECT_TRUE(placed.result.accepted) << placed.result.reason;
  EXPECT_EQ(namesOf(merger.lastBlockTimes()),
            (std::vector<std::string>{"prepare", "search", "judge", "other_way", "alignment"}));
  expectWithinTheMerge(merger.lastBlockTimes(), placed.ms);
  const TimedResult refused = timedMerge(merger, merge_test::cut(kRefusedByEveryStep));
  EXPECT_FALSE(refused.result.accepted);
  EXPECT_EQ(namesOf(merger.lastBlockTimes()),
            (std::vector<std::string>{"prepare", "search", "judge"}))
      << "the checks of an accepted transform do not run on a refusal";
  expectWithinTheMerge(merger.lastBlockTimes(), refused.ms);
}

TEST(BlockTimesTest, TheDefaultChainTimesItsStepsAndItsChecks) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  const std::unique_ptr<MapMerger> chain = makeMerger(defaultMergerName());
  const TimedResult placed =
      timedMerge(*chain, merge_test::cut(merge_test::kIntelCaseZeroOfSeedOne));
  EXPECT_TRUE(placed.result.accepted) << placed.result.reason;
  EXPECT_EQ(placed.result.method, "exhaustive");
  EXPECT_EQ(
      namesOf(chain->lastBlockTimes()),
      (std::vector<std::string>{
          "exhaustive/prepare", "exhaustive/search", "exhaustive/judge", "exhaustive/other_way",
          "exhaustive/alignment", "exhaustive/rest", "chain/floor_crossing", "chain/sweep",
          "chain/turns", "chain/alternatives", "chain/second_opinion", "chain/neighbour_basins"}));
  expectWithinTheMerge(chain->lastBlockTimes(), placed.ms);
  const TimedResult refused = timedMerge(*chain, merge_test::cut(kRefusedByEveryStep));
  EXPECT_FALSE(refused.result.accepted);
  const std::vector<std::string> names = namesOf(chain->lastBlockTimes());
  EXPECT_EQ(names.front(), "exhaustive/prepare");
  EXPECT_EQ(names.back(), "virtual") << "the virtual robot times no blocks of its own";
  EXPECT_NE(std::find(names.begin(), names.end(), "seed/edges"), names.end());
  EXPECT_EQ(std::find_if(names.begin(), names.end(),
                         [](const std::string& name) { return name.rfind("chain/", 0) == 0; }),
            names.end())
      << "no check runs where no step accepts";
  expectWithinTheMerge(chain->lastBlockTimes(), refused.ms);
}

}  // namespace
}  // namespace mrslam::fusion
