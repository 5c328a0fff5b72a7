// The seed merger's second, finer global sweep near the first's rotations, the translation fixed by
// decisive walls, rivals that must pass the overlap bar and small overlaps whose walls all meet:
// real crops with known answers, cut as `mrslam merge-cases` (seed 1) cuts them, same numbers.

#include <gtest/gtest.h>

#include <cmath>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/global_search.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {
namespace {

constexpr double kDegree = M_PI / 180.0;

using merge_test::CropPair;
using merge_test::cut;

// Case 109: only the finer sweep proposes the truth (below).
const CropPair kOnlyTheFinerSweepFindsIt{
    "carpin-robot2_cast.txt",
    109,
    {{268, 61}, 228, 3.041856795968136, {23, 16}, {9, 3}},
    {{176, 115}, 170, -1.7351036680437453, {37, 32}, {20, 22}}};

void expectMergedWithinTwoCellsAndOneDegree(const CropPair& pair) {
  SeedMerger merger;
  merge_test::expectMergedWithinTwoCellsAndOneDegree(pair, merger);
}

// Cases 181 and 127 are found right by the rules tested here, but their overlap's walls meet as
// well turned by 3° (0.967 and 0.966 of the best): the turn check after the alignment refuses
// them, and merges them right only when it is off.
void expectRightButRefusedForTheRotation(const CropPair& pair) {
  SeedMergerSettings unchecked;
  unchecked.wall_alignment.max_turn_share = 1.0;
  SeedMerger without_turn_check(unchecked);
  merge_test::expectMergedWithinTwoCellsAndOneDegree(pair, without_turn_check);
  const MergeCase merge_case = cut(pair);
  const MergeResult result = SeedMerger().merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(result.accepted) << "case " << pair.case_id;
  EXPECT_NE(result.reason.find("do not fix the rotation"), std::string::npos) << result.reason;
}

TEST(MergeSeedGlobalFineTest, SettingsReadTheNewKeys) {
  const SeedMergerSettings defaults;
  EXPECT_EQ(defaults.global_fine_cells, 2);
  EXPECT_TRUE(defaults.rank_by_overlap);
  const SeedMergerSettings loaded = loadSeedMergerSettings(Config::loadString(
      "global_fine_cells: 0\nrank_by_overlap: false\ndecisive_wall_ambiguity: 0.5\n"
      "max_open_floor_ambiguity: 0.9\nsmall_overlap_cells: 1000\nsmall_overlap_structure: 0.95\n"
      "global_fine_min_verification: 0.97\n",
      "merge.yaml"));
  EXPECT_EQ(loaded.global_fine_cells, 0);
  EXPECT_FALSE(loaded.rank_by_overlap);
  EXPECT_DOUBLE_EQ(loaded.decisive_wall_ambiguity, 0.5);
  EXPECT_DOUBLE_EQ(loaded.max_open_floor_ambiguity, 0.9);
  EXPECT_EQ(loaded.small_overlap_cells, 1000);
  EXPECT_DOUBLE_EQ(loaded.small_overlap_structure, 0.95);
  EXPECT_DOUBLE_EQ(loaded.global_fine_min_verification, 0.97);
}

TEST(MergeSeedGlobalFineTest, TheSweepTurnsOnlyNearTheWantedRotations) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot2_cast.txt");
  const MergeCase merge_case = cut(kOnlyTheFinerSweepFindsIt);
  GlobalSearchSettings settings;
  settings.only_rotations_rad = {merge_case.T_b_a.theta_rad};
  const std::vector<GlobalHypothesis> hypotheses =
      globalSearch(merge_case.a, merge_case.b, settings, SimilaritySettings{});
  ASSERT_FALSE(hypotheses.empty());
  for (const GlobalHypothesis& hypothesis : hypotheses) {
    EXPECT_LE(std::abs(std::remainder(hypothesis.T_to_from.theta_rad - merge_case.T_b_a.theta_rad,
                                      2.0 * M_PI)),
              1.01 * settings.rotation_step_rad);
  }
}

// 109: only the finer sweep proposes the truth, where agr - dis slides along a corridor (runner-up
// 0.97 of the best) while the walls fix the shift (0.82). 181: the truth's only rival overlapped
// by 164 known cells, far below the overlap bar, and refused it by its wall balance.
TEST(MergeSeedGlobalFineTest, ExactRotationsTurnByThoseAnglesAlone) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot2_cast.txt");
  const MergeCase merge_case = cut(kOnlyTheFinerSweepFindsIt);
  // The truth's rotation and its half turn, neither on the sweep's grid of 3°.
  const double truth = merge_case.T_b_a.theta_rad;
  GlobalSearchSettings settings;
  settings.only_rotations_rad = {truth, truth + M_PI};
  settings.exact_rotations = true;
  settings.kept_hypotheses = 24;
  const std::vector<GlobalHypothesis> hypotheses =
      globalSearch(merge_case.a, merge_case.b, settings, SimilaritySettings{});
  ASSERT_FALSE(hypotheses.empty());
  bool near_truth = false;
  for (const GlobalHypothesis& hypothesis : hypotheses) {
    const double from_truth =
        std::abs(std::remainder(hypothesis.T_to_from.theta_rad - truth, M_PI));
    EXPECT_LT(from_truth, 1e-9);
    const CaseError error = caseError(merge_case, hypothesis.T_to_from);
    near_truth = near_truth ||
                 (error.distance_cells <= 2.0 * settings.coarse_cells && error.angle_rad < 1e-9);
  }
  EXPECT_TRUE(near_truth) << "no peak within two coarse cells of the truth";
}

TEST(MergeSeedGlobalFineTest, CropsFoundByTheFinerSweepMergeWithinTwoCellsAndOneDegree) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  expectMergedWithinTwoCellsAndOneDegree(kOnlyTheFinerSweepFindsIt);
  expectRightButRefusedForTheRotation({"carpin-robot3_cast.txt",
                                       181,
                                       {{354, -21}, 165, -2.1637519441764286, {37, 9}, {9, 12}},
                                       {{364, 97}, 285, -1.7947365947830762, {16, 12}, {18, 24}}});
}

// Found at the truth with 1373 and 1190 known cells in the overlap, every wall meeting a wall.
TEST(MergeSeedGlobalFineTest, SmallOverlapsWhoseWallsAllMeetMerge) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  expectMergedWithinTwoCellsAndOneDegree(
      {"carpin-robot3_cast.txt",
       46,
       {{-8, 151}, 161, -1.8686059804937816, {1, 13}, {29, 38}},
       {{-144, 72}, 267, -2.2195259095345286, {16, 9}, {24, 6}}});
  expectRightButRefusedForTheRotation({"carpin-robot2_cast.txt",
                                       127,
                                       {{357, -18}, 161, -0.22061754069182227, {21, 18}, {34, 17}},
                                       {{194, -7}, 193, 1.4017371789285145, {15, 40}, {7, 27}}});
}

// With the overlap bar lowered to 800, case 90 was accepted turned by 90° (structure 0.92, a rival
// at 0.90) and case 192 5° off (structure 0.98): the small-overlap rule must refuse both.
TEST(MergeSeedGlobalFineTest, SmallOverlapsOfWrongTransformsAreNotAccepted) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  const CropPair pairs[] = {
      {"carpin-robot0_cast.txt",
       90,
       {{-92, 50}, 208, 2.0176683855641322, {2, 24}, {19, 6}},
       {{-69, -176}, 234, -0.90974621183850157, {4, 14}, {20, 7}}},
      {"carpin-robot0_cast.txt",
       192,
       {{168, 81}, 260, 2.1367438153851701, {4, 34}, {20, 36}},
       {{-41, 151}, 233, 0.70068010051579321, {11, 26}, {16, 20}}},
  };
  SeedMerger merger;
  for (const CropPair& pair : pairs) {
    merge_test::expectNoWrongAccept(pair, merger);
  }
}

}  // namespace
}  // namespace mrslam::fusion
