// The chain's second opinion (ChainSettings::second_opinion_*): after the exhaustive step accepts a
// transform whose turn check came near its bar, the seed step runs as well; where it refuses
// because the walls do not fix the rotation at a placement within the wall alignment's window of
// the accepted one, the chain refuses too. Real crops with known answers, cut as `mrslam
// merge-cases` cuts them (the crops from its --json --details output).

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/exhaustive_merger.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::CropPair;

// Small overlaps (26-32 %) that the exhaustive step alone places 1.0-2.7° from the truth, its 3°
// turns keeping 0.91-0.94 of the walls' agreement (the turn check's bar is 0.95), while the seed
// step alone ends 0.2-1.8 cells and 0.8-2.4° from that placement and refuses it for the turn check
// (0.962-1.08): case 165 of `--seed 3`, 186 of `--seed 30` (ap_hill) and 15 of `--seed 40`
// (intel). With the wall alignment climbing from three starts, the
// exhaustive step alone ends within the tolerance in 186, and refuses case 105 of `--seed 14`
// (listed here before) by its own turn check at the first climb's peak.
const CropPair kNearMissesWithAnUnfixedTurn[] = {
    {"carpin-robot1_cast.txt",
     165,
     {{80, -71}, 243, -2.8966120672679008, {29, 21}, {16, 34}},
     {{84, 145}, 219, -0.02164073794931376, {22, 4}, {16, 6}}},
    {"carpin-robot1_cast.txt",
     186,
     {{142, 49}, 167, -1.8069782742524487, {16, 30}, {39, 14}},
     {{271, -76}, 306, 1.1212263091534158, {40, 39}, {30, 1}}},
    {"carpin-intel.txt",
     15,
     {{202, 24}, 190, -1.5888528306007572, {25, 4}, {19, 26}},
     {{72, 35}, 162, 2.1949646121721926, {39, 9}, {10, 34}}}};

// A truth the exhaustive step places within 0.07 cells and 0.16° (its 3° turns keep 0.879 of the
// walls' agreement: the seed step is not asked), while the seed step alone ends 1.87° from it
// (2.0° from the truth) and refuses its own placement for the turn check: case 84 of `--seed 5`
// (34 % overlap).
const CropPair kTruthFarFromTheBar{"carpin-robot3_cast.txt",
                                   84,
                                   {{-58, 154}, 257, 0.21723016411970564, {37, 18}, {37, 19}},
                                   {{169, 115}, 277, -2.9064925984202543, {37, 16}, {21, 0}}};

// A truth the exhaustive step places within 0.2 cells and 0.2° whose 3° turns keep 0.905 of the
// walls' agreement (the seed step is asked), while the seed step alone ends 1.26 cells and 3.59°
// from it (3.8° from the truth, beyond the windows) and refuses its own placement for the turn
// check: case 156 of `--seed 33` (27 % overlap).
const CropPair kTruthWithAFartherSeedPlacement{
    "carpin-robot3_cast.txt",
    156,
    {{296, -50}, 182, 0.37159408190505516, {36, 7}, {7, 31}},
    {{63, -163}, 269, 1.485364112657404, {29, 14}, {22, 13}}};

bool refusedByTheSecondOpinion(const MergeResult& result) {
  return !result.accepted &&
         result.reason.find("the seed step places the overlap") != std::string::npos &&
         result.refusal == MergeRefusal::kRotation;
}

// The real seed merger, counting how often the chain runs it.
class CountedSeedMerger : public MapMerger {
 public:
  explicit CountedSeedMerger(int& runs) : runs_(runs) {}
  MergeResult merge(const GridMap& from, const GridMap& to) override {
    ++runs_;
    return seed_.merge(from, to);
  }
  std::string name() const override { return "seed"; }

 private:
  SeedMerger seed_;
  int& runs_;
};

ChainMerger exhaustiveThenCountedSeed(int& seed_runs) {
  std::vector<std::unique_ptr<MapMerger>> steps;
  steps.push_back(std::make_unique<ExhaustiveMerger>());
  steps.push_back(std::make_unique<CountedSeedMerger>(seed_runs));
  return ChainMerger(std::move(steps));
}

// The default chain's result on `pair` and how often it ran the seed step.
std::pair<MergeResult, int> mergeCountingSeedRuns(const CropPair& pair) {
  const MergeCase merge_case = merge_test::cut(pair);
  int runs = 0;
  ChainMerger chain = exhaustiveThenCountedSeed(runs);
  MergeResult result = chain.merge(merge_case.a, merge_case.b);
  return {std::move(result), runs};
}

TEST(MergeChainSecondOpinionTest, TheSettingsAreReadAndRangeChecked) {
  const ChainSettings defaults;
  EXPECT_EQ(defaults.second_opinion_step, "seed");
  EXPECT_DOUBLE_EQ(defaults.second_opinion_cells, 5.0);
  EXPECT_DOUBLE_EQ(defaults.second_opinion_deg, 3.0);
  EXPECT_DOUBLE_EQ(defaults.second_opinion_turn_share, 0.9);
  const ChainSettings loaded = loadChainSettings(
      Config::loadString("second_opinion_step: virtual\nsecond_opinion_cells: 4\n"
                         "second_opinion_deg: 2\nsecond_opinion_turn_share: 0.8\n",
                         "merge.yaml"));
  EXPECT_EQ(loaded.second_opinion_step, "virtual");
  EXPECT_DOUBLE_EQ(loaded.second_opinion_cells, 4.0);
  EXPECT_DOUBLE_EQ(loaded.second_opinion_deg, 2.0);
  EXPECT_DOUBLE_EQ(loaded.second_opinion_turn_share, 0.8);
  EXPECT_THROW(loadChainSettings(Config::loadString("second_opinion_cells: -1\n", "merge.yaml")),
               ConfigError);
  EXPECT_THROW(loadChainSettings(Config::loadString("second_opinion_deg: 181\n", "merge.yaml")),
               ConfigError);
  EXPECT_THROW(
      loadChainSettings(Config::loadString("second_opinion_turn_share: 1.5\n", "merge.yaml")),
      ConfigError);
}

TEST(MergeChainSecondOpinionTest, ATurnTheSeedStepFindsUnfixedNearByIsRefused) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const std::unique_ptr<MapMerger> chain = makeMerger(defaultMergerName());
  const std::unique_ptr<MapMerger> two_steps = merge_test::chainOfTwoSteps();
  const std::unique_ptr<MapMerger> without =
      merge_test::chainFrom("chain: {second_opinion_step: \"\"}\n");
  for (const CropPair& pair : kNearMissesWithAnUnfixedTurn) {
    const MergeCase merge_case = merge_test::cut(pair);
    const MergeResult refused = two_steps->merge(merge_case.a, merge_case.b);
    EXPECT_TRUE(refusedByTheSecondOpinion(refused))
        << "case " << pair.case_id << ": " << refused.reason;
    // The virtual robot after them takes no wrong transform either.
    merge_test::expectNoWrongAccept(merge_case, *chain);
    if (pair.case_id == 186) {
      continue;  // placed right without it (above)
    }
    // Without the second opinion the exhaustive step's near miss is accepted: a false accept.
    const MergeResult wrong = without->merge(merge_case.a, merge_case.b);
    EXPECT_TRUE(wrong.accepted) << "case " << pair.case_id << ": " << wrong.reason;
    EXPECT_FALSE(isCorrect(caseError(merge_case, wrong.T_to_from))) << "case " << pair.case_id;
  }
}

TEST(MergeChainSecondOpinionTest, ATurnFarFromTheBarIsNotQuestioned) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  // Asked at any share, the seed step's placement 1.87° away refuses the truth.
  const MergeResult refused = merge_test::mergedRightByDefaultThenWith(
      kTruthFarFromTheBar,
      "chain: {" + merge_test::kFirstTwoSteps + ", second_opinion_turn_share: 0}\n");
  EXPECT_TRUE(refusedByTheSecondOpinion(refused)) << refused.reason;
}

TEST(MergeChainSecondOpinionTest, ASeedPlacementBeyondTheWindowsSaysNothing) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  // With windows that meet up to 4° apart, the seed step's placement 3.59° away refuses it.
  const MergeResult refused = merge_test::mergedRightByDefaultThenWith(
      kTruthWithAFartherSeedPlacement,
      "chain: {" + merge_test::kFirstTwoSteps + ", second_opinion_deg: 4}\n");
  EXPECT_TRUE(refusedByTheSecondOpinion(refused)) << refused.reason;
}

TEST(MergeChainSecondOpinionTest, TheSeedStepRunsOnlyWhereAskedOrReachedAndOnce) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  // Asked after the exhaustive step accepted, refused by it, then reached as the next step: once.
  const auto [refused, asked_then_reached] = mergeCountingSeedRuns(kNearMissesWithAnUnfixedTurn[1]);
  EXPECT_TRUE(!refused.accepted && refused.refusal == MergeRefusal::kRotation) << refused.reason;
  EXPECT_EQ(asked_then_reached, 1);
  // An accepted turn far from the turn check's bar: the seed step is not run.
  const auto [accepted, not_asked] = mergeCountingSeedRuns(kTruthFarFromTheBar);
  EXPECT_TRUE(accepted.accepted) << accepted.reason;
  EXPECT_GT(accepted.wall_turn_share, 0.8);
  EXPECT_LT(accepted.wall_turn_share, 0.9);
  EXPECT_EQ(not_asked, 0);
  // A turn near the bar: asked, it runs once, and the acceptance is kept.
  const auto [kept, asked] = mergeCountingSeedRuns(kTruthWithAFartherSeedPlacement);
  EXPECT_TRUE(kept.accepted) << kept.reason;
  EXPECT_GE(kept.wall_turn_share, 0.9);
  EXPECT_EQ(asked, 1);
}

}  // namespace
}  // namespace mrslam::fusion
