// The structure bar off the frontier (min_structure_off_frontier): a robot's free space often
// ends at a wall it never marked (seen at a grazing angle or at long range), and the other
// robot's walls land there on free cells next to unknown ones. Those walls say nothing against
// the transform; walls on open floor still do.

#include <gtest/gtest.h>

#include "merge_test_maps.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"

namespace mrslam::fusion {
namespace {

// The same rooms seen by a robot that never marked the outer wall along the top (and with
// `and_left`, the one along the left): its free space runs up to it and the map ends there.
GridMap roomsWithUnmarkedOuterWalls(bool and_left) {
  GridMap map = merge_test::handBuiltRooms();
  for (int x = 0; x < 80; ++x) {
    map.at(x, 59) = GridMap::kFree;
  }
  for (int y = 0; y < 60 && and_left; ++y) {
    map.at(0, y) = GridMap::kFree;
  }
  return map;
}

// The same rooms where the inner walls lie in open floor (a wrong map of them).
GridMap roomsWithoutInnerWalls() {
  GridMap map = merge_test::handBuiltRooms();
  for (int y = 1; y < 59; ++y) {
    for (int x = 1; x < 79; ++x) {
      map.at(x, y) = GridMap::kFree;
    }
  }
  return map;
}

MergeResult judgeIdentity(const GridMap& from, const GridMap& to,
                          const SeedMergerSettings& settings) {
  SeedMerger judge(settings);
  return judge.judgeHypotheses(from, to, {GridTransform{}});
}

TEST(MergeFrontierStructureTest, TheBarsAreReadAndRangeChecked) {
  EXPECT_DOUBLE_EQ(SeedMergerSettings{}.min_structure_off_frontier, 0.88);
  EXPECT_DOUBLE_EQ(SeedMergerSettings{}.min_v_off_frontier, 0.98);
  const SeedMergerSettings loaded = loadSeedMergerSettings(Config::loadString(
      "min_structure_off_frontier: 2\nmin_v_off_frontier: 0.95\n", "merge.yaml"));
  EXPECT_DOUBLE_EQ(loaded.min_structure_off_frontier, 2.0);
  EXPECT_DOUBLE_EQ(loaded.min_v_off_frontier, 0.95);
  EXPECT_THROW(
      loadSeedMergerSettings(Config::loadString("min_structure_off_frontier: -1\n", "merge.yaml")),
      ConfigError);
  EXPECT_THROW(loadSeedMergerSettings(Config::loadString("min_v_off_frontier: 3\n", "merge.yaml")),
               ConfigError);
}

TEST(MergeFrontierStructureTest, WallsTheOtherRobotNeverMarkedDoNotRefuseTheTruth) {
  // 80 of `from`'s 343 walls land on `to`'s free cells along its top edge: 0.77 meet walls, all
  // of them off the frontier; V 0.983.
  const GridMap from = merge_test::handBuiltRooms();
  const GridMap to = roomsWithUnmarkedOuterWalls(false);
  const MergeResult merged = judgeIdentity(from, to, SeedMergerSettings{});
  ASSERT_TRUE(merged.accepted) << merged.reason;
  EXPECT_LT(merged.T_to_from.t_cells.norm(), 1.0);
  EXPECT_LT(std::abs(merged.T_to_from.theta_rad), 0.01);
  SeedMergerSettings without;
  without.min_structure_off_frontier = 2.0;
  const MergeResult refused = judgeIdentity(from, to, without);
  EXPECT_FALSE(refused.accepted);
  EXPECT_EQ(refused.refusal, MergeRefusal::kStructure) << refused.reason;
  EXPECT_NE(refused.reason.find("meet walls (below 0.89; 1 off the other map's frontier)"),
            std::string::npos)
      << refused.reason;
}

TEST(MergeFrontierStructureTest, TheFrontierExcusesWallsOnlyWhereTheCellsAgreeCleanly) {
  // With the left wall unmarked too, 140 walls fall on free cells: V 0.971, below 0.98.
  const GridMap from = merge_test::handBuiltRooms();
  const GridMap to = roomsWithUnmarkedOuterWalls(true);
  const MergeResult refused = judgeIdentity(from, to, SeedMergerSettings{});
  EXPECT_FALSE(refused.accepted);
  EXPECT_EQ(refused.refusal, MergeRefusal::kStructure) << refused.reason;
  SeedMergerSettings lower;
  lower.min_v_off_frontier = 0.95;
  const MergeResult merged = judgeIdentity(from, to, lower);
  EXPECT_TRUE(merged.accepted) << merged.reason;
}

TEST(MergeFrontierStructureTest, WallsOnOpenFloorStillRefuse) {
  // The inner walls land on open floor, far from any unknown cell: none of them is excused.
  SeedMergerSettings lower;
  lower.min_v_off_frontier = 0.9;
  const MergeResult refused =
      judgeIdentity(merge_test::handBuiltRooms(), roomsWithoutInnerWalls(), lower);
  EXPECT_FALSE(refused.accepted);
  EXPECT_EQ(refused.refusal, MergeRefusal::kStructure) << refused.reason;
  EXPECT_NE(refused.reason.find("only 0.807 of the overlapping walls meet walls (below 0.89; 0.807 "
                                "off the other map's frontier)"),
            std::string::npos)
      << refused.reason;
}

}  // namespace
}  // namespace mrslam::fusion
