// The default chain's third step: the virtual robot of seed 002 runs where both searches refuse.
// Real crops with known answers, cut as `mrslam merge-cases` cuts them (the crops from its --json
// --details output), that the exhaustive and seed steps refuse and the virtual robot places.

#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::CropPair;

// Case 115 of `--seed 16` (Carpin's robot 3, 49 % overlap) and case 16 of `--seed 15` (ACES, 45 %):
// both searches refuse them; the virtual robot places them 0.07 and 0.06 cells from the truth.
const CropPair kPlacedByTheVirtualRobot[] = {
    {"carpin-robot3_cast.txt",
     115,
     {{252, -70}, 293, 1.8804182832664624, {3, 14}, {10, 27}},
     {{399, 141}, 295, -1.6135813775354237, {14, 30}, {35, 36}}},
    {"freiburg-aces.pgm",
     16,
     {{489, 619}, 278, 0.9176564995508789, {38, 27}, {35, 19}},
     {{356, 762}, 239, -0.5191376942030193, {11, 9}, {14, 31}}}};

TEST(MergeChainVirtualStepTest, TheDefaultStepsEndWithTheVirtualRobot) {
  EXPECT_EQ(parseChainSteps(kDefaultChainSteps),
            (std::vector<std::string>{"exhaustive", "exhaustive_strict", "seed", "virtual"}));
}

TEST(MergeChainVirtualStepTest, TheVirtualRobotPlacesWhatBothSearchesRefuse) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  // The strict search (the default's second step) places case 16 itself; the virtual robot is
  // weighed here behind the other two steps alone.
  const std::unique_ptr<MapMerger> chain =
      merge_test::chainFrom("chain: {" + merge_test::kWithoutTheStrictSearch + "}\n");
  const std::unique_ptr<MapMerger> two_steps = merge_test::chainOfTwoSteps();
  const std::unique_ptr<MapMerger> by_default = makeMerger(defaultMergerName());
  for (const CropPair& pair : kPlacedByTheVirtualRobot) {
    const MergeCase merge_case = merge_test::cut(pair);
    const MergeResult refused = two_steps->merge(merge_case.a, merge_case.b);
    EXPECT_FALSE(refused.accepted) << "case " << pair.case_id;
    const MergeResult placed =
        merge_test::expectMergedWithinTwoCellsAndOneDegree(merge_case, *chain);
    EXPECT_EQ(placed.method, "virtual") << "case " << pair.case_id;
    EXPECT_GE(placed.verification, 0.9) << "case " << pair.case_id;
    merge_test::expectMergedWithinTwoCellsAndOneDegree(merge_case, *by_default);
  }
}

}  // namespace
}  // namespace mrslam::fusion
