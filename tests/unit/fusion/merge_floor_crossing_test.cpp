// Walls of one map across the other's open floor (floor_crossing.hpp) and the chain's check on
// them (ChainSettings::floor_crossing_min_cells): hand-built rooms with known runs, and real crops
// cut as `mrslam merge-cases` cuts them whose default merge, without the check, places a room of
// Carpin's robot maps that looks alike.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "merge_crop_pairs.hpp"
#include "merge_test_maps.hpp"
#include "mrslam/common/config.hpp"
#include "mrslam/fusion/merge/chain_merger.hpp"
#include "mrslam/fusion/merge/floor_crossing.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::chainFrom;
using merge_test::CropPair;
using merge_test::cut;

constexpr double kClearance = 2.5;

// A 40 × 30 room: walls on the border, free inside.
GridMap room() {
  GridMap map = merge_test::unknownMap(40, 30);
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) {
      const bool border = x == 0 || y == 0 || x == 39 || y == 29;
      map.at(x, y) = border ? GridMap::kOccupied : GridMap::kFree;
    }
  }
  return map;
}

int wallCount(const GridMap& map) {
  int walls = 0;
  for (int y = 0; y < map.geometry.height; ++y) {
    for (int x = 0; x < map.geometry.width; ++x) {
      walls += map.at(x, y) >= SimilaritySettings{}.occupied_threshold ? 1 : 0;
    }
  }
  return walls;
}

FloorCrossing crossingAtIdentity(const GridMap& own, const GridMap& other) {
  return floorCrossing(own, other, GridTransform{}, SimilaritySettings{}, kClearance);
}

TEST(FloorCrossingTest, TheSameRoomCrossesNoFloor) {
  const GridMap map = room();
  const FloorCrossing crossing = crossingAtIdentity(map, map);
  EXPECT_EQ(crossing.run_cells, 0);
  EXPECT_EQ(crossing.crossing_cells, 0);
  EXPECT_EQ(crossing.walls_on_known, wallCount(map));
  EXPECT_DOUBLE_EQ(crossing.share(), 0.0);
}

TEST(FloorCrossingTest, AnInnerWallTheOtherRoomLacksIsOneRun) {
  GridMap own = room();
  for (int x = 10; x < 22; ++x) {
    own.at(x, 15) = GridMap::kOccupied;  // 12 cells through the middle of the room
  }
  for (int y = 5; y < 9; ++y) {
    own.at(30, y) = GridMap::kOccupied;  // and a post of 4 cells apart from it
  }
  const FloorCrossing crossing = crossingAtIdentity(own, room());
  EXPECT_EQ(crossing.run_cells, 12);
  EXPECT_EQ(crossing.crossing_cells, 16);
  EXPECT_EQ(crossing.walls_on_known, wallCount(own));
  EXPECT_DOUBLE_EQ(crossing.share(), 12.0 / wallCount(own));
  // The other way round, no wall of the plain room lies on the inner wall's room's open floor.
  EXPECT_EQ(crossingAtIdentity(room(), own).run_cells, 0);
}

TEST(FloorCrossingTest, WallsWithinTheClearanceOfTheOtherWallsDoNotCount) {
  GridMap own = room();
  for (int x = 5; x < 35; ++x) {
    own.at(x, 2) = GridMap::kOccupied;   // 2 cells inside the bottom wall: within the clearance
    own.at(x, 26) = GridMap::kOccupied;  // 3 cells inside the top wall: beyond it
  }
  const FloorCrossing crossing = crossingAtIdentity(own, room());
  EXPECT_EQ(crossing.crossing_cells, 30);
  EXPECT_EQ(crossing.run_cells, 30);
}

TEST(FloorCrossingTest, WallsOnTheOtherMapsUnknownCellsAreNotCounted) {
  GridMap own = room();
  for (int x = 10; x < 22; ++x) {
    own.at(x, 15) = GridMap::kOccupied;
  }
  GridMap other = room();
  for (int y = 10; y < 20; ++y) {
    for (int x = 5; x < 30; ++x) {
      other.at(x, y) = GridMap::kUnknown;  // the other robot never saw the room's middle
    }
  }
  const FloorCrossing crossing = crossingAtIdentity(own, other);
  EXPECT_EQ(crossing.run_cells, 0);
  EXPECT_EQ(crossing.walls_on_known, wallCount(own) - 12);
}

TEST(FloorCrossingTest, AShiftedPlacementIsMeasuredWhereItLands) {
  // The room shifted by 3 cells: its left wall lands 3 cells inside the other's, its right wall
  // beside the other map.
  const GridTransform T_other_own{0.0, Eigen::Vector2d(3.0, 0.0)};
  const FloorCrossing crossing =
      floorCrossing(room(), room(), T_other_own, SimilaritySettings{}, kClearance);
  // The left wall's cells y = 3..26 lie on open floor; y = 1, 2, 27 and 28 lie within the
  // clearance of the bottom and top walls.
  EXPECT_EQ(crossing.run_cells, 24);
  EXPECT_GT(crossing.share(), 0.0);
}

// Case 82 of `--seed 170` (carpin-robot0_cast, 58 % overlap): without the check the default chain
// accepts a room of Carpin's robot 0 turned by a quarter (69 cells and 89.7° from the truth).
const CropPair kRoomTurnedByAQuarter{"carpin-robot0_cast.txt",
                                     82,
                                     {{-72, 30}, 197, 0.9029448584548332, {9, 24}, {7, 18}},
                                     {{-227, -226}, 286, -1.0096010047000035, {39, 29}, {18, 19}}};

// Case 118 of `--seed 184` (carpin-robot0_cast, 41 % overlap): without it, the room next along
// the corridor (93 cells from the truth).
const CropPair kRoomAlong{"carpin-robot0_cast.txt",
                          118,
                          {{31, -11}, 293, -0.6726739441412519, {10, 23}, {18, 21}},
                          {{-220, -17}, 270, -2.3955907994581875, {13, 13}, {40, 23}}};

const std::string kWithoutTheCheck = "chain: {floor_crossing_min_cells: 0}\n";  // the default
// The bars measured in the forty-sixth session (docs/merge_tuning.md).
const std::string kWithTheCheck =
    "chain: {floor_crossing_min_cells: 4, floor_crossing_min_share: 0.015}\n";

TEST(MergeChainFloorCrossingTest, TheSettingsAreReadAndRangeChecked) {
  const ChainSettings defaults;
  EXPECT_EQ(defaults.floor_crossing_min_cells, 0);  // off: see docs/merge_tuning.md
  EXPECT_DOUBLE_EQ(defaults.floor_crossing_min_share, 0.015);
  EXPECT_DOUBLE_EQ(defaults.floor_crossing_clearance_cells, 2.5);
  const Config config = Config::loadString(
      "floor_crossing_min_cells: 8\nfloor_crossing_min_share: 0.02\n"
      "floor_crossing_clearance_cells: 1.5\n",
      "chain.yaml");
  const ChainSettings read = loadChainSettings(config);
  EXPECT_EQ(read.floor_crossing_min_cells, 8);
  EXPECT_DOUBLE_EQ(read.floor_crossing_min_share, 0.02);
  EXPECT_DOUBLE_EQ(read.floor_crossing_clearance_cells, 1.5);
  EXPECT_THROW(loadChainSettings(Config::loadString("floor_crossing_min_cells: -1\n", "c.yaml")),
               ConfigError);
  EXPECT_THROW(loadChainSettings(Config::loadString("floor_crossing_min_share: 2\n", "c.yaml")),
               ConfigError);
}

void expectRefusedOnlyByTheCheck(const CropPair& pair) {
  const MergeCase merge_case = cut(pair);
  const MergeResult without = chainFrom(kWithoutTheCheck)->merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(without.accepted) << without.reason;
  const CaseError error = caseError(merge_case, without.T_to_from);
  EXPECT_GT(error.distance_cells, 50.0);  // a room that looks alike, far from the truth
  const FloorCrossing crossing =
      floorCrossing(merge_case.a, merge_case.b, without.T_to_from, SimilaritySettings{}, 2.5);
  const FloorCrossing back = floorCrossing(merge_case.b, merge_case.a, without.T_to_from.inverse(),
                                           SimilaritySettings{}, 2.5);
  EXPECT_GE(std::max(crossing.run_cells, back.run_cells), 10);

  const MergeResult with = chainFrom(kWithTheCheck)->merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(with.accepted);
  EXPECT_EQ(with.refusal, MergeRefusal::kStructure);
  EXPECT_THAT(with.reason, ::testing::HasSubstr("exhaustive: a run of "));
  EXPECT_THAT(with.reason, ::testing::HasSubstr("crosses the other's open floor"));
}

TEST(MergeChainFloorCrossingTest, ARoomTurnedByAQuarterIsRefused) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  expectRefusedOnlyByTheCheck(kRoomTurnedByAQuarter);
}

TEST(MergeChainFloorCrossingTest, TheRoomNextAlongTheCorridorIsRefused) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  expectRefusedOnlyByTheCheck(kRoomAlong);
}

TEST(MergeChainFloorCrossingTest, ARightMergeIsKeptAndTheCheckIsTimedWhenOn) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const MergeCase merge_case = cut(merge_test::kIntelCaseZeroOfSeedOne);
  const auto chain = chainFrom(kWithTheCheck);
  const MergeResult result = chain->merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_TRUE(isCorrect(caseError(merge_case, result.T_to_from)));
  const BlockTimes times = chain->lastBlockTimes();
  const auto is_check = [](const auto& block) { return block.name == "chain/floor_crossing"; };
  EXPECT_TRUE(std::any_of(times.begin(), times.end(), is_check));
  const auto by_default = chainFrom("");
  ASSERT_TRUE(by_default->merge(merge_case.a, merge_case.b).accepted);
  const BlockTimes default_times = by_default->lastBlockTimes();
  EXPECT_FALSE(std::any_of(default_times.begin(), default_times.end(), is_check));
}

}  // namespace
}  // namespace mrslam::fusion
