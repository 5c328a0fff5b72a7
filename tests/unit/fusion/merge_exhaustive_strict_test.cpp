// The strict exhaustive search (the default chain's second step): conflicts cost more, so that
// placements whose known cells fit cleanly rank above ones that overlap more and conflict.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/exhaustive_merger.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::CropPair;
using merge_test::cut;

// Case 55 of `--seed 295` (ACES, 51 % overlap): the default search's 16 hypotheses are all
// placements along the corridors that cover more known cells than the truth and conflict more
// (its nearest 22 cells from the truth); the exact truth passes the acceptance alone.
const CropPair kAcesCorridors{"freiburg-aces.pgm",
                              55,
                              {{708, 46}, 228, 1.0023944551925759, {38, 6}, {39, 21}},
                              {{606, 15}, 230, 0.08651284539012183, {3, 26}, {17, 33}}};

/// How far the hypothesis nearest the truth puts crop A's known centre from it, cells (among
/// those turned less than `deg` from the truth).
double nearestToTheTruth(const MergeCase& merge_case, const std::vector<GridTransform>& found,
                         double deg) {
  double nearest = INFINITY;
  for (const GridTransform& T_b_a : found) {
    const CaseError error = caseError(merge_case, T_b_a);
    if (error.angle_rad * 180.0 / M_PI <= deg) {
      nearest = std::min(nearest, error.distance_cells);
    }
  }
  return nearest;
}

TEST(ExhaustiveStrictTest, ItsDefaultsAreTheSearchsWithConflictsCostingMore) {
  const ExhaustiveMergerSettings defaults;
  const ExhaustiveMergerSettings strict = strictExhaustiveMergerSettings();
  EXPECT_EQ(strict.search.conflict_penalty, 20.0);
  EXPECT_EQ(strict.search.free_penalty, 20.0);
  EXPECT_EQ(strict.search.free_margin, 2);
  EXPECT_EQ(defaults.search.conflict_penalty, 6.0);
  EXPECT_EQ(defaults.search.free_penalty, 6.0);
  EXPECT_EQ(defaults.search.free_margin, 1);
  EXPECT_EQ(strict.search.free_weight, defaults.search.free_weight);
  EXPECT_EQ(strict.search.hypotheses, defaults.search.hypotheses);
  EXPECT_EQ(strict.judged_hypotheses, defaults.judged_hypotheses);
  EXPECT_EQ(strict.check_both_ways, defaults.check_both_ways);
}

TEST(ExhaustiveStrictTest, ItsSectionIsReadOverItsOwnDefaults) {
  const ExhaustiveMergerSettings read = loadExhaustiveMergerSettings(
      Config::loadString("conflict_penalty: 9\nhypotheses: 8\n", "strict.yaml"),
      strictExhaustiveMergerSettings());
  EXPECT_EQ(read.search.conflict_penalty, 9.0);
  EXPECT_EQ(read.search.hypotheses, 8);
  EXPECT_EQ(read.search.free_penalty, 20.0);  // left out: the strict default
  EXPECT_EQ(read.search.free_margin, 2);
  EXPECT_THROW(makeMergerFrom(
                   "chain", Config::loadString("exhaustive_strict: {free_margin: -1}\n", "m.yaml")),
               ConfigError);
  EXPECT_EQ(makeMerger("exhaustive_strict")->name(), "exhaustive_strict");
  EXPECT_EQ(makeMerger("exhaustive")->name(), "exhaustive");
}

TEST(ExhaustiveStrictTest, ProposesAndMergesTheCleanTruthTheDefaultSearchMisses) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  const MergeCase merge_case = cut(kAcesCorridors);
  // Each merge's result holds the hypotheses its search handed to the judge.
  ExhaustiveMerger default_step;
  const MergeResult refused = default_step.merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(refused.accepted);
  EXPECT_GT(nearestToTheTruth(merge_case, refused.hypotheses, 3.0), 10.0);
  ExhaustiveMerger strict_step(strictExhaustiveMergerSettings(), {}, "exhaustive_strict");
  const MergeResult placed =
      merge_test::expectMergedWithinTwoCellsAndOneDegree(merge_case, strict_step);
  EXPECT_LT(nearestToTheTruth(merge_case, placed.hypotheses, 3.0), 6.0);
  EXPECT_EQ(placed.method, "exhaustive_strict");
  const MergeResult chained = merge_test::expectMergedWithinTwoCellsAndOneDegree(
      merge_case, *makeMerger(defaultMergerName()));
  EXPECT_EQ(chained.method, "exhaustive_strict");
}

}  // namespace
}  // namespace mrslam::fusion
