// The seed merger's global search with free agreement (global_search.hpp, step 5) and rivals
// refined before they refuse a candidate (`refined_rivals`). Real crops with known answers, cut
// as `mrslam merge-cases` (seed 1) cuts them, same case numbers.

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/global_search.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {
namespace {

constexpr double kDegree = M_PI / 180.0;

using merge_test::CropPair;
using merge_test::cut;

// 87 (36 % overlap): an overlap of open floor with few walls; the truth is the best peak of the
// score with free agreement and none of the walls' score.
const CropPair kOpenFloor = {"carpin-robot1_cast.txt",
                             87,
                             {{228, 89}, 308, 2.2229465075133072, {22, 36}, {2, 2}},
                             {{194, -71}, 214, 2.0153123179616026, {18, 29}, {20, 7}}};
// 45 (35 %): found by free agreement only as well.
const CropPair kOpenFloorAces = {"freiburg-aces.pgm",
                                 45,
                                 {{955, 42}, 168, 1.0057053050570479, {26, 0}, {0, 38}},
                                 {{945, 176}, 282, 1.167124205259304, {9, 8}, {4, 10}}};
// 26 (77 %): a building of two halves alike; the transform turned by 180° ranks first and is
// refused for its entropy gap, and the truth's rival is a copy of it slid 18 cells along a
// corridor, which settles back onto the truth when refined.
const CropPair kSymmetric = {"freiburg-aces.pgm",
                             26,
                             {{84, 373}, 310, 1.8761857979378886, {15, 2}, {14, 19}},
                             {{215, 411}, 238, 0.58705342757735002, {20, 33}, {17, 39}}};
// 105 (24 %): without its V bar (global_free_min_verification) the sweep with free agreement
// had a transform 2.4° off (V 0.962) accepted; the finer sweep's truth merges instead.
const CropPair kNearMiss = {"carpin-intel.txt",
                            105,
                            {{190, 412}, 309, 1.8891003524294927, {22, 29}, {1, 21}},
                            {{-101, 533}, 318, 2.2623662176167461, {8, 4}, {40, 26}}};

bool nearTruth(const GlobalHypothesis& hypothesis, const MergeCase& merge_case,
               const GlobalSearchSettings& settings) {
  const CaseError error = caseError(merge_case, hypothesis.T_to_from);
  return error.angle_rad <= 0.5 * settings.rotation_step_rad + 0.5 * kDegree &&
         error.distance_cells <= 1.5 * settings.coarse_cells + 2.0;
}

TEST(MergeSeedFreeAgreementTest, SettingsReadTheNewKeys) {
  const SeedMergerSettings defaults;
  EXPECT_DOUBLE_EQ(defaults.global.free_agreement_weight, 0.1);
  EXPECT_EQ(defaults.global.free_agreement_hypotheses, 6);
  EXPECT_DOUBLE_EQ(defaults.global_free_min_verification, 0.98);
  EXPECT_EQ(defaults.refined_rivals, 2);
  const SeedMergerSettings loaded = loadSeedMergerSettings(
      Config::loadString("global_free_agreement_weight: 0.2\nglobal_free_agreement_hypotheses: 0\n"
                         "global_free_min_verification: 0.95\nrefined_rivals: 0\n",
                         "merge.yaml"));
  EXPECT_DOUBLE_EQ(loaded.global.free_agreement_weight, 0.2);
  EXPECT_EQ(loaded.global.free_agreement_hypotheses, 0);
  EXPECT_DOUBLE_EQ(loaded.global_free_min_verification, 0.95);
  EXPECT_EQ(loaded.refined_rivals, 0);
  EXPECT_THROW(loadSeedMergerSettings(
                   Config::loadString("global_free_agreement_weight: -1\n", "merge.yaml")),
               std::exception);
  EXPECT_THROW(loadSeedMergerSettings(Config::loadString("refined_rivals: 11\n", "merge.yaml")),
               std::exception);
}

TEST(MergeSeedFreeAgreementTest, TheScoreWithFreeAgreementFindsAnOverlapOfOpenFloor) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  const MergeCase merge_case = cut(kOpenFloor);
  const GlobalSearchSettings settings;
  const std::vector<GlobalHypothesis> hypotheses =
      globalSearch(merge_case.a, merge_case.b, settings, SimilaritySettings{});
  int by_walls = 0;
  int by_free = 0;
  bool walls_find_it = false;
  bool free_finds_it = false;
  for (std::size_t i = 0; i < hypotheses.size(); ++i) {
    const GlobalHypothesis& hypothesis = hypotheses[i];
    if (i > 0 && hypotheses[i - 1].by_free_agreement == hypothesis.by_free_agreement) {
      EXPECT_GE(hypotheses[i - 1].score, hypothesis.score);  // best first within each score
    }
    (hypothesis.by_free_agreement ? by_free : by_walls) += 1;
    (hypothesis.by_free_agreement ? free_finds_it : walls_find_it) |=
        nearTruth(hypothesis, merge_case, settings);
  }
  EXPECT_EQ(by_walls, settings.kept_hypotheses);
  EXPECT_EQ(by_free, settings.free_agreement_hypotheses);
  EXPECT_FALSE(walls_find_it);
  EXPECT_TRUE(free_finds_it);

  GlobalSearchSettings walls_only = settings;
  walls_only.free_agreement_hypotheses = 0;
  for (const GlobalHypothesis& hypothesis :
       globalSearch(merge_case.a, merge_case.b, walls_only, SimilaritySettings{})) {
    EXPECT_FALSE(hypothesis.by_free_agreement);
  }
}

TEST(MergeSeedFreeAgreementTest, CropsFoundByFreeAgreementMergeWithinTwoCellsAndOneDegree) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  for (const CropPair& pair : {kOpenFloor, kOpenFloorAces}) {
    SeedMerger merger;
    const MergeResult result = merge_test::expectMergedWithinTwoCellsAndOneDegree(pair, merger);
    EXPECT_EQ(result.method, "seed/global-search-free") << "case " << pair.case_id;
    const MergeCase merge_case = cut(pair);

    SeedMergerSettings off;
    off.global.free_agreement_hypotheses = 0;
    SeedMerger without(off);
    EXPECT_FALSE(without.merge(merge_case.a, merge_case.b).accepted) << "case " << pair.case_id;
  }
}

TEST(MergeSeedFreeAgreementTest, ARivalThatSettlesOntoTheTruthDoesNotRefuseIt) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  const MergeCase merge_case = cut(kSymmetric);
  SeedMerger merger;
  const MergeResult result = merger.merge(merge_case.a, merge_case.b);
  const CaseError error = caseError(merge_case, result.T_to_from);
  EXPECT_TRUE(result.accepted) << result.reason;
  EXPECT_TRUE(isCorrect(error)) << error.distance_cells << " cells, " << error.angle_rad / kDegree
                                << "°";

  SeedMergerSettings unrefined;
  unrefined.refined_rivals = 0;
  SeedMerger before(unrefined);
  const MergeResult refused = before.merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(refused.accepted);
}

TEST(MergeSeedFreeAgreementTest, ANearMissOfTheFreeAgreementSweepIsNotAccepted) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const MergeCase merge_case = cut(kNearMiss);
  SeedMerger merger;
  const MergeResult result = merger.merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_TRUE(isCorrect(caseError(merge_case, result.T_to_from)));
}

}  // namespace
}  // namespace mrslam::fusion
