// Block 9's bars measured on every judged transform of the case sets: the structure bar
// (min_structure_agreement), the structure that lets a smaller overlap do (small_overlap_structure)
// and the cleaner rival (cleaner_rival_rate). Real crops with known answers, cut as
// `mrslam merge-cases` cuts them (the crops from its --json --details output).

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

// Case 59 of `--seed 3`: crop A shows ACES's round hall with corridors on two opposite sides, crop
// B the hall and one of them. Turned by 180°, A's other corridor lies on B's and the overlap is
// larger (19000 known cells against 13000 at the truth), but 2.7 % of its cells disagree against
// 0.8 % at the truth, whose walls all meet walls.
const CropPair kHallTurnedByAHalf{"freiburg-aces.pgm",
                                  59,
                                  {{437, 443}, 244, 2.0659661519656796, {23, 27}, {38, 12}},
                                  {{499, 603}, 187, -0.27239699214238433, {23, 21}, {29, 34}}};

// Rooms of Carpin's robot maps repeated about 90 cells over: at the structure bar of 0.88 the
// default chain accepted each slid by a room (V 0.951-0.968), 0.876-0.887 of the overlapping walls
// meeting walls. Case 69 and case 135 of `--seed 31`, case 123 of `--seed 14` (27 %, 32 % and 26 %
// overlap); their truths overlap fewer than 1500 known cells.
const CropPair kRoomsSlidByARoom[] = {{"carpin-robot3_cast.txt",
                                       69,
                                       {{38, 19}, 185, -1.1844028374865483, {9, 19}, {21, 12}},
                                       {{-175, -49}, 226, 2.1513571966625857, {20, 36}, {38, 40}}},
                                      {"carpin-robot0_cast.txt",
                                       135,
                                       {{35, -40}, 229, -0.11092416439097175, {31, 11}, {5, 35}},
                                       {{-222, -56}, 271, -2.6006615469179537, {28, 22}, {5, 21}}},
                                      {"carpin-robot3_cast.txt",
                                       123,
                                       {{45, -77}, 315, 2.8222505544524124, {27, 23}, {20, 30}},
                                       {{-248, -173}, 308, 2.384084590349822, {2, 22}, {3, 27}}}};

// Overlaps below min_overlap_cells whose walls meet walls 0.988 and 0.985 of the time at the
// truth, with no rival: case 96 of `--seed 2` and case 189 of `--seed 1`.
const CropPair kSmallOverlaps[] = {{"carpin-LongRun6.txt",
                                    96,
                                    {{212, 48}, 208, -0.7101078746147125, {14, 30}, {3, 35}},
                                    {{337, 215}, 164, 1.41292553836288, {36, 38}, {29, 19}}},
                                   {"carpin-LongRun7.txt",
                                    189,
                                    {{351, 345}, 164, 0.5975313427902904, {11, 6}, {25, 12}},
                                    {{202, 205}, 194, -1.699050956063579, {31, 38}, {29, 9}}}};

// Overlaps of 400-900 known cells whose walls all meet walls, with no rival: case 21 of
// `--seed 1` (ACES, 671 cells) and case 144 of `--seed 4` (LongRun6).
const CropPair kSmallerOverlaps[] = {{"freiburg-aces.pgm",
                                      21,
                                      {{-156, 453}, 315, 0.7830764012238771, {7, 16}, {2, 18}},
                                      {{-31, 713}, 182, -1.1218512253322546, {11, 32}, {21, 30}}},
                                     {"carpin-LongRun6.txt",
                                      144,
                                      {{235, 369}, 185, 1.7574650862522843, {32, 40}, {15, 24}},
                                      {{364, 468}, 187, 3.1324989295196843, {39, 10}, {22, 29}}}};

TEST(MergeAcceptanceBarsTest, TheBarsAreReadAndRangeChecked) {
  const SeedMergerSettings defaults;
  EXPECT_DOUBLE_EQ(defaults.min_structure_agreement, 0.89);
  EXPECT_DOUBLE_EQ(defaults.small_overlap_structure, 0.98);
  EXPECT_EQ(defaults.small_overlap_cells, 400);
  EXPECT_DOUBLE_EQ(defaults.cleaner_rival_rate, 0.5);
  const SeedMergerSettings loaded = loadSeedMergerSettings(
      Config::loadString("min_structure_agreement: 0.8\ncleaner_rival_rate: 0\n", "merge.yaml"));
  EXPECT_DOUBLE_EQ(loaded.min_structure_agreement, 0.8);
  EXPECT_DOUBLE_EQ(loaded.cleaner_rival_rate, 0.0);
  EXPECT_THROW(
      loadSeedMergerSettings(Config::loadString("min_structure_agreement: 1.5\n", "merge.yaml")),
      ConfigError);
  EXPECT_THROW(
      loadSeedMergerSettings(Config::loadString("cleaner_rival_rate: -0.1\n", "merge.yaml")),
      ConfigError);
}

TEST(MergeAcceptanceBarsTest, AWallTurnedOntoOpenFloorIsRefusedAtTheBar) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  const MergeCase merge_case = cut(kOpenRoomInOpenFloor);
  SeedMerger merger;
  const MergeResult result = merger.merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(result.accepted) << "accepted " << caseError(merge_case, result.T_to_from).angle_rad
                                << " rad from the truth";
  EXPECT_NE(result.reason.find("of the overlapping walls meet walls (below 0.89;"),
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

TEST(MergeAcceptanceBarsTest, TheDefaultChainRefusesTheOpenRoomAndMergesTheStrip) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  const std::unique_ptr<MapMerger> chain = makeMerger(defaultMergerName());
  const MergeCase open_room = cut(kOpenRoomInOpenFloor);
  const MergeResult refused = chain->merge(open_room.a, open_room.b);
  EXPECT_FALSE(refused.accepted) << refused.method;
  merge_test::expectMergedWithinTwoCellsAndOneDegree(kStripOnACorner, *chain);
}

TEST(MergeAcceptanceBarsTest, RoomsSlidByARoomAreRefusedAtTheBar) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  const std::unique_ptr<MapMerger> chain = makeMerger(defaultMergerName());
  // The old bar (the floor-crossing check off, as by default), and with that check on: it refuses
  // the slid rooms too.
  const std::unique_ptr<MapMerger> old_bar =
      merge_test::chainFrom("chain: {floor_crossing_min_cells: 0}\nseed: {" +
                            std::string(merge_test::kStructureBarAt088) + "}\n");
  const std::unique_ptr<MapMerger> old_bar_crossing =
      merge_test::chainFrom("chain: {floor_crossing_min_cells: 4}\nseed: {" +
                            std::string(merge_test::kStructureBarAt088) + "}\n");
  for (const CropPair& pair : kRoomsSlidByARoom) {
    const MergeCase merge_case = cut(pair);
    const MergeResult refused = chain->merge(merge_case.a, merge_case.b);
    EXPECT_FALSE(refused.accepted) << "case " << pair.case_id;
    EXPECT_NE(refused.reason.find("of the overlapping walls meet walls (below 0.89;"),
              std::string::npos)
        << "case " << pair.case_id << ": " << refused.reason;
    // The bar decides: at 0.88 the slid room passes every test.
    const MergeResult slid = old_bar->merge(merge_case.a, merge_case.b);
    ASSERT_TRUE(slid.accepted) << "case " << pair.case_id << ": " << slid.reason;
    EXPECT_GT(caseError(merge_case, slid.T_to_from).distance_cells, 80.0)
        << "case " << pair.case_id;
    EXPECT_FALSE(old_bar_crossing->merge(merge_case.a, merge_case.b).accepted)
        << "case " << pair.case_id << ": the slid room's walls cross the other's open floor";
  }
}

TEST(MergeAcceptanceBarsTest, AHallTurnedByAHalfIsRefusedForItsCleanerRival) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  const MergeCase merge_case = cut(kHallTurnedByAHalf);
  for (const char* method : {"seed", "chain"}) {
    const std::unique_ptr<MapMerger> merger = makeMerger(method);
    const MergeResult result = merger->merge(merge_case.a, merge_case.b);
    if (result.accepted) {
      EXPECT_TRUE(isCorrect(caseError(merge_case, result.T_to_from))) << method;
    }
  }
  // Without the cleaner rival and the chain's cleaner alternatives the chain takes the half turn:
  // either rule alone decides this case.
  const std::unique_ptr<MapMerger> without = makeMergerFrom(
      "chain",
      Config::loadString("seed:\n  cleaner_rival_rate: 0\nchain:\n  cleaner_alternative_rate: 0\n",
                         "merge.yaml"));
  const MergeResult turned = without->merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(turned.accepted) << turned.reason;
  EXPECT_GT(caseError(merge_case, turned.T_to_from).angle_rad, 170.0 * M_PI / 180.0);
  const std::unique_ptr<MapMerger> alternatives_only =
      makeMergerFrom("chain", Config::loadString("seed:\n  cleaner_rival_rate: 0\n", "merge.yaml"));
  const MergeResult weighed = alternatives_only->merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(weighed.accepted);
  EXPECT_NE(weighed.reason.find("another placement"), std::string::npos) << weighed.reason;
}

TEST(MergeAcceptanceBarsTest, SmallOverlapsWhoseWallsMeetAtTheNewBarMerge) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-LongRun7.txt");
  const std::unique_ptr<MapMerger> chain = makeMerger(defaultMergerName());
  for (const CropPair& pair : kSmallOverlaps) {
    merge_test::expectMergedWithinTwoCellsAndOneDegree(pair, *chain);
  }
}

TEST(MergeAcceptanceBarsTest, SmallerOverlapsWhoseWallsAllMeetMergeAndTheBarDecides) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-aces.pgm");
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-LongRun6.txt");
  // Without the unwalled alternatives (chain.walls_alternative_rate): case 144 of set 4 has one
  // over open floor, cleaner and larger, that refuses it (a right merge that rule loses).
  const std::string no_walls_alternatives = "chain: {walls_alternative_rate: 0}\n";
  const std::unique_ptr<MapMerger> chain =
      makeMergerFrom("chain", Config::loadString(no_walls_alternatives, "m.yaml"));
  const std::unique_ptr<MapMerger> old_bar = makeMergerFrom(
      "chain",
      Config::loadString(no_walls_alternatives + "seed: {small_overlap_cells: 900}\n", "m.yaml"));
  for (const CropPair& pair : kSmallerOverlaps) {
    const MergeCase merge_case = cut(pair);
    merge_test::expectMergedWithinTwoCellsAndOneDegree(merge_case, *chain);
    const MergeResult refused = old_bar->merge(merge_case.a, merge_case.b);
    EXPECT_FALSE(refused.accepted) << "case " << pair.case_id << " at the old bar of 900 cells";
  }
}

}  // namespace
}  // namespace mrslam::fusion
