// Walls of one map across the other's open floor (floor_crossing.hpp) and the chain's check on
// them (ChainSettings::floor_crossing_min_cells): hand-built rooms with known runs, and real crops
// cut as `mrslam merge-cases` cuts them whose default merge, without the check, places a room of
// Carpin's robot maps that looks alike.

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <random>
#include <vector>

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

const FloorCrossingSettings kBars{};  // a clearance of 2.5 cells, floor of occupancy ≤ 12

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

// Cells x0 ≤ x < x1, y0 ≤ y < y1 of `map` set to `value`.
void fill(GridMap& map, int x0, int x1, int y0, int y1, std::int8_t value) {
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      map.at(x, y) = value;
    }
  }
}

// The room with a wall of 12 cells through its middle (row 15, x = 10..21) that room() lacks.
GridMap roomWithInnerWall() {
  GridMap map = room();
  fill(map, 10, 22, 15, 16, GridMap::kOccupied);
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
  return floorCrossing(own, other, GridTransform{}, SimilaritySettings{}, kBars);
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
  GridMap own = roomWithInnerWall();
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
  const GridMap own = roomWithInnerWall();
  GridMap other = room();
  fill(other, 5, 30, 10, 20, GridMap::kUnknown);  // the other robot never saw the room's middle
  const FloorCrossing crossing = crossingAtIdentity(own, other);
  EXPECT_EQ(crossing.run_cells, 0);
  EXPECT_EQ(crossing.walls_on_known, wallCount(own) - 12);
}

TEST(FloorCrossingTest, AShiftedPlacementIsMeasuredWhereItLands) {
  // The room shifted by 3 cells: its left wall lands 3 cells inside the other's, its right wall
  // beside the other map.
  const GridTransform T_other_own{0.0, Eigen::Vector2d(3.0, 0.0)};
  const FloorCrossing crossing =
      floorCrossing(room(), room(), T_other_own, SimilaritySettings{}, kBars);
  // The left wall's cells y = 3..26 lie on open floor; y = 1, 2, 27 and 28 lie within the
  // clearance of the bottom and top walls.
  EXPECT_EQ(crossing.run_cells, 24);
  EXPECT_GT(crossing.share(), 0.0);
}

TEST(FloorCrossingTest, FloorThatFewBeamsCrossedDoesNotCount) {
  const GridMap own = roomWithInnerWall();
  GridMap other = room();
  fill(other, 1, 39, 1, 29, 17);  // free class, but four misses more than hits: a door, a person
  const FloorCrossing few_beams = crossingAtIdentity(own, other);
  EXPECT_EQ(few_beams.run_cells, 0);
  EXPECT_EQ(few_beams.walls_on_known, wallCount(own));  // still known cells
  FloorCrossingSettings looser = kBars;
  looser.floor_max_occupancy = 17;
  EXPECT_EQ(floorCrossing(own, other, GridTransform{}, SimilaritySettings{}, looser).run_cells, 12);
  fill(other, 10, 22, 15, 16,
       static_cast<std::int8_t>(kBars.floor_max_occupancy));  // the bar counts
  EXPECT_EQ(crossingAtIdentity(own, other).run_cells, 12);
}

// Whether every cell within `radius` of `cell` is on `map` and known.
bool knownAround(const GridMap& map, const Eigen::Vector2i& cell, double radius) {
  const SimilaritySettings classes;
  for (int y = cell.y() - 10; y <= cell.y() + 10; ++y) {
    for (int x = cell.x() - 10; x <= cell.x() + 10; ++x) {
      const double distance = (Eigen::Vector2i(x, y) - cell).cast<double>().norm();
      if (distance <= radius && (!map.geometry.contains(x, y) || !classes.isKnown(map.at(x, y)))) {
        return false;
      }
    }
  }
  return true;
}

TEST(FloorCrossingTest, FloorAtTheOtherMapsFrontierDoesNotCount) {
  GridMap own = roomWithInnerWall();
  GridMap other = room();
  fill(other, 1, 39, 17, 29, GridMap::kUnknown);  // the other robot saw the room up to row 16
  // Row 15 lies 2 cells from the unknown cells of row 17, within the clearance: the inner wall may
  // be one the other robot never saw.
  EXPECT_EQ(crossingAtIdentity(own, other).run_cells, 0);
  FloorCrossingSettings anywhere = kBars;
  anywhere.known_around = false;
  EXPECT_EQ(floorCrossing(own, other, GridTransform{}, SimilaritySettings{}, anywhere).run_cells,
            12);
  for (int x = 10; x < 22; ++x) {
    own.at(x, 15) = GridMap::kFree;
    own.at(x, 12) = GridMap::kOccupied;  // 5 cells from the unknown ones: inside what it saw
  }
  EXPECT_EQ(crossingAtIdentity(own, other).run_cells, 12);
}

// The measure as its definition reads: every wall against every wall for the clearance, and
// runs grown by repeated passes over all crossing cells.
FloorCrossing bruteForceCrossing(const GridMap& own, const GridMap& other,
                                 const GridTransform& T_other_own,
                                 const FloorCrossingSettings& bars) {
  const SimilaritySettings classes;
  std::vector<Eigen::Vector2i> other_walls;
  for (int y = 0; y < other.geometry.height; ++y) {
    for (int x = 0; x < other.geometry.width; ++x) {
      if (other.at(x, y) >= classes.occupied_threshold) {
        other_walls.emplace_back(x, y);
      }
    }
  }
  FloorCrossing result;
  std::vector<Eigen::Vector2i> crossing;
  for (int y = 0; y < own.geometry.height; ++y) {
    for (int x = 0; x < own.geometry.width; ++x) {
      if (own.at(x, y) < classes.occupied_threshold) {
        continue;
      }
      const Eigen::Vector2d landed = T_other_own.apply(Eigen::Vector2d(x, y));
      const Eigen::Vector2i cell(static_cast<int>(std::floor(landed.x() + 0.5)),
                                 static_cast<int>(std::floor(landed.y() + 0.5)));
      if (!other.geometry.contains(cell.x(), cell.y())) {
        continue;
      }
      const int value = other.at(cell.x(), cell.y());
      const bool is_free = value >= 0 && value <= classes.free_threshold;
      if (!is_free && value < classes.occupied_threshold) {
        continue;
      }
      ++result.walls_on_known;
      double nearest = 1e9;
      for (const Eigen::Vector2i& wall : other_walls) {
        nearest = std::min(nearest, (wall - cell).cast<double>().norm());
      }
      const bool counted = std::find(crossing.begin(), crossing.end(), cell) != crossing.end();
      if (is_free && value <= bars.floor_max_occupancy && nearest > bars.clearance_cells &&
          (!bars.known_around || knownAround(other, cell, bars.clearance_cells)) && !counted) {
        crossing.push_back(cell);
      }
    }
  }
  result.crossing_cells = static_cast<int>(crossing.size());
  std::vector<int> label(crossing.size());
  for (std::size_t i = 0; i < crossing.size(); ++i) {
    label[i] = static_cast<int>(i);
  }
  for (bool changed = true; changed;) {
    changed = false;
    for (std::size_t i = 0; i < crossing.size(); ++i) {
      for (std::size_t j = 0; j < crossing.size(); ++j) {
        const Eigen::Vector2i step = crossing[i] - crossing[j];
        if (std::abs(step.x()) <= 1 && std::abs(step.y()) <= 1 && label[j] < label[i]) {
          label[i] = label[j];
          changed = true;
        }
      }
    }
  }
  for (const int l : label) {
    result.run_cells =
        std::max(result.run_cells, static_cast<int>(std::count(label.begin(), label.end(), l)));
  }
  return result;
}

GridMap randomMap(std::mt19937& random, int width, int height, double wall_share) {
  static constexpr std::int8_t kValues[] = {-1, 0, 0, 0, 0, 0, 0, 0, 5, 12, 13, 30, 35, 36, 50, 65};
  std::uniform_int_distribution<int> pick(0, static_cast<int>(std::size(kValues)) - 1);
  std::bernoulli_distribution walled(wall_share);
  GridMap map = merge_test::unknownMap(width, height);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      map.at(x, y) = walled(random) ? GridMap::kOccupied : kValues[pick(random)];
    }
  }
  return map;
}

TEST(FloorCrossingTest, EqualsABruteForceReferenceOnRandomGrids) {
  std::mt19937 random(47);
  std::uniform_real_distribution<double> turn(-M_PI, M_PI);
  std::uniform_real_distribution<double> shift(-4.0, 4.0);
  const double clearances[] = {0.0, 1.0, 1.5, 2.5, 3.2};
  int crossing_trials = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const GridMap own = randomMap(random, 26, 21, 0.3);     // walls to land
    const GridMap other = randomMap(random, 23, 28, 0.02);  // floor for them to cross
    const GridTransform T_other_own{turn(random), Eigen::Vector2d(shift(random), shift(random))};
    FloorCrossingSettings bars;
    bars.clearance_cells = clearances[trial % std::size(clearances)];
    bars.floor_max_occupancy = trial % 2 == 0 ? 12 : 35;
    bars.known_around = trial % 3 != 0;
    const FloorCrossing fast = floorCrossing(own, other, T_other_own, SimilaritySettings{}, bars);
    const FloorCrossing reference = bruteForceCrossing(own, other, T_other_own, bars);
    EXPECT_EQ(fast.walls_on_known, reference.walls_on_known) << "trial " << trial;
    EXPECT_EQ(fast.crossing_cells, reference.crossing_cells) << "trial " << trial;
    EXPECT_EQ(fast.run_cells, reference.run_cells) << "trial " << trial;
    crossing_trials += reference.run_cells > 1 ? 1 : 0;
  }
  EXPECT_GE(crossing_trials, 20);  // the trials hold runs to compare, not only empty crossings
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

const std::string kWithoutTheCheck = "chain: {floor_crossing_min_cells: 0}\n";
// The bars measured in the forty-sixth and forty-seventh sessions (docs/merge_tuning.md): the
// defaults.
const std::string kWithTheCheck = "";

TEST(MergeChainFloorCrossingTest, TheSettingsAreReadAndRangeChecked) {
  const ChainSettings defaults;
  EXPECT_EQ(defaults.floor_crossing_min_cells, 4);  // on: see docs/merge_tuning.md
  EXPECT_DOUBLE_EQ(defaults.floor_crossing_min_share, 0.015);
  EXPECT_DOUBLE_EQ(defaults.floor_crossing.clearance_cells, 2.5);
  EXPECT_EQ(defaults.floor_crossing.floor_max_occupancy, 12);
  EXPECT_TRUE(defaults.floor_crossing.known_around);
  const Config config = Config::loadString(
      "floor_crossing_min_cells: 8\nfloor_crossing_min_share: 0.02\n"
      "floor_crossing_clearance_cells: 1.5\nfloor_crossing_floor_max_occupancy: 30\n"
      "floor_crossing_known_around: false\n",
      "chain.yaml");
  const ChainSettings read = loadChainSettings(config);
  EXPECT_EQ(read.floor_crossing_min_cells, 8);
  EXPECT_DOUBLE_EQ(read.floor_crossing_min_share, 0.02);
  EXPECT_DOUBLE_EQ(read.floor_crossing.clearance_cells, 1.5);
  EXPECT_EQ(read.floor_crossing.floor_max_occupancy, 30);
  EXPECT_FALSE(read.floor_crossing.known_around);
  EXPECT_THROW(
      loadChainSettings(Config::loadString("floor_crossing_floor_max_occupancy: 101\n", "c.yaml")),
      ConfigError);
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
      floorCrossing(merge_case.a, merge_case.b, without.T_to_from, SimilaritySettings{}, kBars);
  const FloorCrossing back = floorCrossing(merge_case.b, merge_case.a, without.T_to_from.inverse(),
                                           SimilaritySettings{}, kBars);
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
  const auto turned_off = chainFrom(kWithoutTheCheck);
  ASSERT_TRUE(turned_off->merge(merge_case.a, merge_case.b).accepted);
  const BlockTimes off_times = turned_off->lastBlockTimes();
  EXPECT_FALSE(std::any_of(off_times.begin(), off_times.end(), is_check));
}

}  // namespace
}  // namespace mrslam::fusion
