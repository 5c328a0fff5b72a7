// The structure bar of block 9 (min_structure_agreement): a transform is accepted only when at
// least that share of the overlapping walls meets walls, both ways. Real crops with known answers,
// cut as `mrslam merge-cases` cuts them (the crops from its --json --details output).

#include <gtest/gtest.h>

#include <cmath>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::CropPair;
using merge_test::cut;

// Case 118 of `--seed 2`: crop A is an open room with one wall and a short corridor, and the room
// lies in open floor of crop B, so no wall of the overlap fixes the truth. The seed pipeline finds
// A's wall and corridor laid along B's walls turned by 90°: V 0.972, but 14 % of the overlapping
// walls land on the other map's open floor (structure 0.86).
const CropPair kOpenRoomInOpenFloor{"carpin-robot1_cast.txt",
                                    118,
                                    {{281, 131}, 274, -2.7915393879404835, {38, 2}, {22, 9}},
                                    {{325, 26}, 161, 2.0852850809280445, {22, 24}, {10, 29}}};

// Case 74 of `--seed 1`: a strip of a room whose walls meet crop B's corner; at the old bar the
// seed step's turned candidate (structure 0.841) was judged before the exhaustive step's truth.
const CropPair kStripOnACorner{"carpin-robot1_cast.txt",
                               74,
                               {{201, 149}, 232, -0.9441782183212069, {24, 9}, {13, 25}},
                               {{277, -14}, 219, 0.2692130197000089, {2, 0}, {19, 9}}};

TEST(MergeStructureBarTest, TheDefaultBarIsReadAndRangeChecked) {
  EXPECT_DOUBLE_EQ(SeedMergerSettings{}.min_structure_agreement, 0.88);
  const SeedMergerSettings loaded =
      loadSeedMergerSettings(Config::loadString("min_structure_agreement: 0.8\n", "merge.yaml"));
  EXPECT_DOUBLE_EQ(loaded.min_structure_agreement, 0.8);
  EXPECT_THROW(
      loadSeedMergerSettings(Config::loadString("min_structure_agreement: 1.5\n", "merge.yaml")),
      ConfigError);
}

TEST(MergeStructureBarTest, AWallTurnedOntoOpenFloorIsRefusedAtTheBar) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  const MergeCase merge_case = cut(kOpenRoomInOpenFloor);
  SeedMerger merger;
  const MergeResult result = merger.merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(result.accepted) << "accepted " << caseError(merge_case, result.T_to_from).angle_rad
                                << " rad from the truth";
  EXPECT_NE(result.reason.find("of the overlapping walls meet walls (below 0.88)"),
            std::string::npos)
      << result.reason;
  // At a bar of 0.85 the turned transform passes: this case is decided by the bar.
  SeedMergerSettings old_bar;
  old_bar.min_structure_agreement = 0.85;
  SeedMerger old_merger(old_bar);
  const MergeResult old_result = old_merger.merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(old_result.accepted) << old_result.reason;
  EXPECT_GT(caseError(merge_case, old_result.T_to_from).angle_rad, 80.0 * M_PI / 180.0);
}

TEST(MergeStructureBarTest, TheDefaultChainRefusesTheOpenRoomAndMergesTheStrip) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  const std::unique_ptr<MapMerger> chain = makeMerger(defaultMergerName());
  const MergeCase open_room = cut(kOpenRoomInOpenFloor);
  const MergeResult refused = chain->merge(open_room.a, open_room.b);
  EXPECT_FALSE(refused.accepted) << refused.method;
  merge_test::expectMergedWithinTwoCellsAndOneDegree(kStripOnACorner, *chain);
}

}  // namespace
}  // namespace mrslam::fusion
