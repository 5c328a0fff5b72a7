// Carpin's ψ random walk as a merger of its own: walks from the exhaustive search's hypotheses,
// judged by the seed acceptance; its sampled ψ and its settings.

#include "mrslam/fusion/merge/psi_walk_merger.hpp"

#include <gtest/gtest.h>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::CropPair;
using merge_test::cut;
using merge_test::TwoBuildings;

// Cases 2 and 6 of `mrslam merge-cases --seed 1 --cases 12`: Carpin's robot 3 at 63 % overlap,
// and the Intel lab at 32 %.
const CropPair kWideOverlap{"carpin-robot3_cast.txt",
                            2,
                            {{-21, 43}, 274, -1.6900799518023857, {35, 39}, {3, 0}},
                            {{125, 65}, 305, -0.04360786023670249, {16, 10}, {40, 23}}};
const CropPair kSmallOverlap{"carpin-intel.txt",
                             6,
                             {{290, 156}, 297, -3.084993748726794, {3, 36}, {28, 37}},
                             {{212, 240}, 233, 1.6624841512636692, {38, 0}, {26, 34}}};

TEST(PsiWalkMergerTest, WalksFromTheSearchesHypothesesToTheTruth) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  const MergeCase merge_case = cut(kWideOverlap);
  PsiWalkMerger merger;
  const std::vector<GridTransform> walked = merger.walkedHypotheses(merge_case.a, merge_case.b);
  ASSERT_FALSE(walked.empty());
  EXPECT_LE(walked.size(), 4u);  // one walk from each of the first `starts` hypotheses
  const MergeResult result = merger.merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_EQ(result.method, "psi_walk");
  const CaseError error = caseError(merge_case, result.T_to_from);
  EXPECT_LT(error.distance_cells, 1.0);
  EXPECT_LT(error.angle_rad, 0.5 * M_PI / 180.0);
}

TEST(PsiWalkMergerTest, AWalkThatShrinksTheOverlapIsRefusedByTheAcceptance) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  // ψ leaves out the cells that land off the other map, so at a small overlap the walk drifts
  // towards an even smaller one that fits; the seed acceptance refuses what it ends on.
  const MergeCase merge_case = cut(kSmallOverlap);
  const MergeResult result = PsiWalkMerger().merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(result.accepted);
  EXPECT_EQ(result.reason.rfind("psi random walk: ", 0), 0u) << result.reason;
}

TEST(PsiWalkMergerTest, RefusesCropsOfTwoBuildings) {
  // Negative cases 12 and 13 of the same run.
  const TwoBuildings pairs[] = {{"carpin-robot3_cast.txt",
                                 {{109, 108}, 189, -2.3105328568191763, {13, 12}, {0, 21}},
                                 "freiburg-aces.pgm",
                                 {{-24, 605}, 216, -2.542055859310113, {40, 11}, {37, 7}}},
                                {"carpin-robot0_cast.txt",
                                 {{-66, 64}, 260, 2.708134099466866, {27, 18}, {38, 13}},
                                 "carpin-LongRun6.txt",
                                 {{385, 582}, 237, -1.102589063443038, {29, 26}, {37, 28}}}};
  for (const TwoBuildings& pair : pairs) {
    MRSLAM_REQUIRE_SHARED_DATA(std::string("maps/") + pair.map_a);
    MRSLAM_REQUIRE_SHARED_DATA(std::string("maps/") + pair.map_b);
    const MergeCase merge_case = cut(pair);
    const MergeResult result = PsiWalkMerger().merge(merge_case.a, merge_case.b);
    EXPECT_FALSE(result.accepted) << pair.map_a << " onto " << pair.map_b;
  }
}

TEST(PsiWalkMergerTest, PsiTakesAnEvenSampleOfEachClass) {
  GridMap map(GridGeometry{0.05, 60, 40, Eigen::Vector2d::Zero()}, GridMap::kUnknown);
  for (int y = 0; y < 40; ++y) {
    for (int x = 0; x < 60; ++x) {
      map.at(x, y) = (x == 0 || y == 0) ? 100 : 0;  // two walls, free elsewhere
    }
  }
  const SimilaritySettings classes;
  const DissimilarityMap whole = prepareDissimilarity(map, classes);
  ASSERT_EQ(whole.occupied_cells.size(), 99u);
  ASSERT_EQ(whole.free_cells.size(), 59u * 39u);
  const DissimilarityMap sampled = sampledDissimilarity(map, classes, 50);
  EXPECT_EQ(sampled.occupied_cells.size(), 50u);  // every 2nd of 99
  EXPECT_EQ(sampled.free_cells.size(), 49u);      // every 47th of 2301
  EXPECT_EQ(sampled.free_cells[1], whole.free_cells[47]);
  EXPECT_EQ(sampled.occupied.distance, whole.occupied.distance);  // the distance maps stay whole
  const DissimilarityMap all = sampledDissimilarity(map, classes, 100000);
  EXPECT_EQ(all.free_cells, whole.free_cells);
}

TEST(PsiWalkMergerTest, SettingsAreReadAndChecked) {
  const Config section = Config::loadString(
      "psi_walk: {starts: 2, max_cells: 500, iterations: 100, step_deg: 1, seed: 7}\n",
      "merge.yaml");
  const PsiWalkSettings read = loadPsiWalkSettings(section.section("psi_walk"));
  EXPECT_EQ(read.starts, 2);
  EXPECT_EQ(read.max_cells, 500);
  EXPECT_EQ(read.walk.iterations, 100);
  EXPECT_DOUBLE_EQ(read.walk.step_rad, M_PI / 180.0);
  EXPECT_EQ(read.walk.seed, 7u);
  EXPECT_EQ(makeMergerFrom("psi_walk", section)->name(), "psi_walk");
  EXPECT_THROW(makeMergerFrom("psi_walk", Config::loadString("psi_walk: {starts: 0}\n", "m.yaml")),
               ConfigError);
  EXPECT_THROW(makeMergerFrom("psi_walk", Config::loadString("psi_walk: {shrink: 2}\n", "m.yaml")),
               ConfigError);
}

}  // namespace
}  // namespace mrslam::fusion
