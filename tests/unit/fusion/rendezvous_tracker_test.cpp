// When the fusion agent checks a rendezvous against the maps: on arrival, again when the maps
// have grown, once more on the final maps whatever the earlier checks said; and what it reports
// when grown maps refuse one that the early maps let through.

#include "mrslam/fusion/rendezvous_tracker.hpp"

#include <gtest/gtest.h>

namespace mrslam::fusion {
namespace {

constexpr int kWidth = 240;
constexpr int kHeight = 120;
constexpr int kCorridorSouthWall = 40;  // rows of the corridor's walls
constexpr int kCorridorNorthWall = 60;

void fill(GridMap& map, int x0, int x1, int y0, int y1, std::int8_t value) {
  for (int y = y0; y <= y1; ++y) {
    for (int x = x0; x <= x1; ++x) {
      map.at(x, y) = value;
    }
  }
}

/// A stretch of corridor: two straight walls and the free floor between them, nothing that tells
/// one place along it from another.
void addCorridor(GridMap& map, int x0, int x1) {
  fill(map, x0, x1, kCorridorSouthWall + 1, kCorridorNorthWall - 1, GridMap::kFree);
  fill(map, x0, x1, kCorridorSouthWall, kCorridorSouthWall, GridMap::kOccupied);
  fill(map, x0, x1, kCorridorNorthWall, kCorridorNorthWall, GridMap::kOccupied);
}

/// Rooms of unequal widths between y0 and y1, walled at `walls` (x), each with a door onto the
/// corridor wall at `door_row` (their far sides lie beyond the map: deep rooms).
void addRooms(GridMap& map, const std::vector<int>& walls, int y0, int y1, int door_row) {
  fill(map, walls.front(), walls.back(), y0, y1, GridMap::kFree);
  for (std::size_t i = 0; i < walls.size(); ++i) {
    fill(map, walls[i], walls[i], y0, y1, GridMap::kOccupied);
    if (i + 1 < walls.size()) {
      const int door = (walls[i] + walls[i + 1]) / 2;
      fill(map, door - 2, door + 2, door_row, door_row, GridMap::kFree);
    }
  }
}

/// The building as a robot has mapped it: early on only the corridor's middle, at the end the
/// corridor with its ends and the rooms on both sides.
GridMap building(bool mapped_in_full) {
  GridGeometry geometry;
  geometry.resolution_m = 0.05;
  geometry.width = kWidth;
  geometry.height = kHeight;
  GridMap map(geometry, GridMap::kUnknown);
  if (!mapped_in_full) {
    addCorridor(map, 40, 200);
    return map;
  }
  addCorridor(map, 10, 230);
  addRooms(map, {10, 27, 49, 63, 88, 104, 131, 147, 170, 186, 209, 230}, 5, kCorridorSouthWall,
           kCorridorSouthWall);
  addRooms(map, {10, 33, 51, 78, 95, 118, 139, 160, 183, 201, 230}, kCorridorNorthWall, 115,
           kCorridorNorthWall);
  fill(map, 10, 10, kCorridorSouthWall, kCorridorNorthWall, GridMap::kOccupied);
  fill(map, 230, 230, kCorridorSouthWall, kCorridorNorthWall, GridMap::kOccupied);
  return map;
}

RobotMap robotMap(const std::string& id, const GridMap& map, bool is_final) {
  RobotMap robot;
  robot.robot_id = id;
  robot.map = map;
  robot.is_final = is_final;
  return robot;
}

/// Both robots' maps, in the same frame (the truth is the identity).
std::vector<RobotMap> teamMaps(bool mapped_in_full, bool is_final) {
  const GridMap map = building(mapped_in_full);
  return {robotMap("a", map, is_final), robotMap("b", map, is_final)};
}

RendezvousTracker tracker() {
  return RendezvousTracker(RendezvousSettings{}, 0.1, 8);
}

TEST(RendezvousTrackerTest, ARightRendezvousIsCheckedOnArrivalAfterGrowthAndOnTheFinalMaps) {
  RendezvousTracker held = tracker();
  held.add({{"b", "a", SE2(0.1, -0.05, 0.01), {}}});  // 11 cm and 0.6° off
  std::vector<RendezvousOutcome> outcomes = held.checkDue(teamMaps(false, false), 1);
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_TRUE(outcomes[0].check.accepted) << outcomes[0].check.reason;
  EXPECT_FALSE(outcomes[0].on_final_maps);
  EXPECT_FALSE(outcomes[0].was_verified);
  EXPECT_EQ(held.held(), 1u) << "kept, to be checked again";

  EXPECT_FALSE(held.needsCheck(1));
  EXPECT_TRUE(held.checkDue(teamMaps(false, false), 2).empty()) << "the maps have not grown";

  outcomes = held.checkDue(teamMaps(true, false), 3);
  ASSERT_EQ(outcomes.size(), 1u) << "the maps grew materially";
  EXPECT_TRUE(outcomes[0].check.accepted) << outcomes[0].check.reason;
  EXPECT_TRUE(outcomes[0].was_verified);
  EXPECT_FALSE(outcomes[0].on_final_maps);

  outcomes = held.checkDue(teamMaps(true, true), 4);
  ASSERT_EQ(outcomes.size(), 1u) << "once more on the final maps, though they did not grow";
  const RendezvousCheck& last = outcomes[0].check;
  ASSERT_TRUE(last.accepted) << last.reason;
  EXPECT_TRUE(outcomes[0].on_final_maps);
  EXPECT_NEAR(last.T_to_from.x(), 0.0, 0.05);
  EXPECT_NEAR(last.T_to_from.y(), 0.0, 0.05);
  EXPECT_NEAR(last.T_to_from.theta(), 0.0, 0.5 * M_PI / 180.0);
  EXPECT_EQ(held.held(), 0u) << "nothing is left to learn after the final maps";
  EXPECT_TRUE(held.checkDue(teamMaps(true, true), 5).empty());
}

TEST(RendezvousTrackerTest, AFitThatSlidAlongTheCorridorIsRefusedByTheFinalMapsAndReported) {
  RendezvousTracker held = tracker();
  held.add({{"b", "a", SE2(1.0, 0.0, 0.0), {}}});  // 1 m along the corridor: a bad sighting
  std::vector<RendezvousOutcome> outcomes = held.checkDue(teamMaps(false, false), 1);
  ASSERT_EQ(outcomes.size(), 1u);
  ASSERT_TRUE(outcomes[0].check.accepted)
      << "the corridor alone cannot tell: " << outcomes[0].check.reason;
  const SE2 early_fit = outcomes[0].check.T_to_from;
  EXPECT_GT(std::abs(early_fit.x()), 0.4) << "the early fit is off along the corridor";

  outcomes = held.checkDue(teamMaps(true, true), 2);
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_FALSE(outcomes[0].check.accepted)
      << "V " << outcomes[0].check.verification << ", structure " << outcomes[0].check.structure;
  EXPECT_NE(outcomes[0].check.reason.find("rendezvous refused by the maps"), std::string::npos);
  EXPECT_TRUE(outcomes[0].was_verified);
  EXPECT_EQ(outcomes[0].previous_T_to_from.x(), early_fit.x()) << "to withdraw what it placed";
  EXPECT_EQ(outcomes[0].previous_T_to_from.y(), early_fit.y());
  EXPECT_EQ(held.held(), 0u);
}

/// b's early map with something across the corridor that a's map has as free floor (a door
/// closed then, people standing): `width` cells of wall across it at `x`.
std::vector<RobotMap> teamMapsWithCorridorBlockedInB(bool mapped_in_full, int x, int width) {
  const GridMap map = building(mapped_in_full);
  GridMap blocked = map;
  fill(blocked, x, x + width - 1, kCorridorSouthWall + 1, kCorridorNorthWall - 1,
       GridMap::kOccupied);
  return {robotMap("a", map, false), robotMap("b", blocked, false)};
}

TEST(RendezvousTrackerTest, ARightRendezvousRefusedByTheEarlyMapsIsVerifiedByTheFinalMaps) {
  RendezvousTracker held = tracker();
  held.add({{"b", "a", SE2(0.05, 0.0, 0.0), {}}});
  std::vector<RendezvousOutcome> outcomes =
      held.checkDue(teamMapsWithCorridorBlockedInB(false, 100, 40), 1);
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_FALSE(outcomes[0].check.accepted) << "V " << outcomes[0].check.verification;
  EXPECT_NE(outcomes[0].check.reason.find("V"), std::string::npos) << outcomes[0].check.reason;
  EXPECT_FALSE(outcomes[0].short_of_overlap);
  EXPECT_EQ(held.held(), 1u) << "refused by early maps, held for grown and final ones";
  EXPECT_TRUE(held.checkDue(teamMapsWithCorridorBlockedInB(false, 100, 40), 2).empty())
      << "no change of the maps is material: not checked again";

  outcomes = held.checkDue(teamMaps(true, true), 3);
  ASSERT_EQ(outcomes.size(), 1u);
  ASSERT_TRUE(outcomes[0].check.accepted) << outcomes[0].check.reason;
  EXPECT_TRUE(outcomes[0].on_final_maps);
  EXPECT_FALSE(outcomes[0].was_verified) << "nothing of it to withdraw";
  EXPECT_NEAR(outcomes[0].check.T_to_from.x(), 0.0, 0.05);
  EXPECT_EQ(held.held(), 0u);
}

TEST(RendezvousTrackerTest, OneRefusedByGrownMapsIsStillCheckedOnTheFinalMaps) {
  RendezvousTracker held = tracker();
  held.add({{"b", "a", SE2(0.0, 0.05, 0.0), {}}});
  ASSERT_TRUE(held.checkDue(teamMaps(false, false), 1).at(0).check.accepted);
  std::vector<RendezvousOutcome> outcomes =
      held.checkDue(teamMapsWithCorridorBlockedInB(true, 60, 120), 2);
  ASSERT_EQ(outcomes.size(), 1u) << "the maps grew materially";
  EXPECT_FALSE(outcomes[0].check.accepted);
  EXPECT_TRUE(outcomes[0].was_verified) << "its placement is to be withdrawn";
  EXPECT_EQ(held.held(), 1u);

  outcomes = held.checkDue(teamMaps(true, true), 3);
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_TRUE(outcomes[0].check.accepted) << outcomes[0].check.reason;
  EXPECT_FALSE(outcomes[0].was_verified) << "withdrawn at the refusal, not twice";
  EXPECT_EQ(held.held(), 0u);
}

TEST(RendezvousTrackerTest, ARendezvousWaitsForBothMapsAndForOverlap) {
  RendezvousTracker held = tracker();
  // b's map placed 9 m east of a's corridor stretch: no overlap yet.
  held.add({{"b", "a", SE2(9.0, 0.0, 0.0), {}}});
  EXPECT_TRUE(held.checkDue({robotMap("a", building(false), false)}, 1).empty());
  EXPECT_EQ(held.held(), 1u) << "b's map has not arrived";
  std::vector<RendezvousOutcome> outcomes = held.checkDue(teamMaps(false, false), 2);
  ASSERT_EQ(outcomes.size(), 1u);
  EXPECT_FALSE(outcomes[0].check.accepted);
  EXPECT_LT(outcomes[0].check.overlap_cells, RendezvousSettings{}.min_overlap_cells);
  EXPECT_EQ(held.held(), 1u) << "the maps may grow into each other";
  EXPECT_FALSE(held.needsCheck(2));
  EXPECT_EQ(held.checkDue(teamMaps(false, false), 3).size(), 1u) << "checked at every change";
  EXPECT_EQ(held.checkDue(teamMaps(false, true), 4).size(), 1u);
  EXPECT_EQ(held.held(), 0u) << "final maps that do not overlap never will";
}

TEST(RendezvousTrackerTest, KeepsTheNewestRendezvousUpToItsBound) {
  RendezvousTracker held(RendezvousSettings{}, 0.1, 2);
  held.add({{"b", "a", SE2(9.0, 0.0, 0.0), {}}, {"b", "a", SE2(9.5, 0.0, 0.0), {}}});
  held.add({{"b", "a", SE2(0.0, 0.0, 0.0), {}}});
  EXPECT_EQ(held.held(), 2u);
  const std::vector<RendezvousOutcome> outcomes = held.checkDue(teamMaps(false, false), 1);
  ASSERT_EQ(outcomes.size(), 2u);
  EXPECT_EQ(outcomes[0].hypothesis.T_to_from.x(), 9.5) << "the oldest was dropped";
  EXPECT_EQ(outcomes[1].hypothesis.T_to_from.x(), 0.0);
}

}  // namespace
}  // namespace mrslam::fusion
