// The walls of two maps aligned both ways after acceptance (wall_alignment.hpp): a drawn room and
// its turned copy with a known answer, the window and the guards, and real crops whose accepted
// transform ended a cell or two and about a degree off before the alignment.

#include <gtest/gtest.h>

#include <array>
#include <cmath>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/merger_registry.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "mrslam/fusion/merge/wall_alignment.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The walls of an L-shaped room with a pillar, in room coordinates (cells).
const std::array<std::array<double, 4>, 10> kRoomWalls = {{{10, 10, 90, 10},
                                                           {90, 10, 90, 50},
                                                           {90, 50, 50, 50},
                                                           {50, 50, 50, 90},
                                                           {50, 90, 10, 90},
                                                           {10, 90, 10, 10},
                                                           {25, 25, 35, 25},
                                                           {35, 25, 35, 32},
                                                           {35, 32, 25, 32},
                                                           {25, 32, 25, 25}}};

double distanceToSegment(const Eigen::Vector2d& p, const std::array<double, 4>& wall) {
  const Eigen::Vector2d a(wall[0], wall[1]);
  const Eigen::Vector2d b(wall[2], wall[3]);
  const double along = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
  return (a + along * (b - a) - p).norm();
}

bool insideRoom(const Eigen::Vector2d& p) {
  const bool in_box = p.x() > 10 && p.x() < 90 && p.y() > 10 && p.y() < 90;
  const bool in_cut = p.x() > 50 && p.y() > 50;
  const bool in_pillar = p.x() > 25 && p.x() < 35 && p.y() > 25 && p.y() < 32;
  return in_box && !in_cut && !in_pillar;
}

// The room drawn in a 140 × 140 grid whose cell c shows room point T_grid_room⁻¹ c: walls within
// half a cell, free inside, unknown outside.
GridMap drawRoom(const GridTransform& T_grid_room) {
  GridGeometry geometry;
  geometry.width = 140;
  geometry.height = 140;
  GridMap map(geometry, GridMap::kUnknown);
  const GridTransform T_room_grid = T_grid_room.inverse();
  for (int y = 0; y < geometry.height; ++y) {
    for (int x = 0; x < geometry.width; ++x) {
      const Eigen::Vector2d p = T_room_grid.apply(Eigen::Vector2d(x, y));
      double nearest = 1e9;
      for (const auto& wall : kRoomWalls) {
        nearest = std::min(nearest, distanceToSegment(p, wall));
      }
      if (nearest <= 0.5) {
        map.at(x, y) = GridMap::kOccupied;
      } else if (insideRoom(p)) {
        map.at(x, y) = GridMap::kFree;
      }
    }
  }
  return map;
}

GridTransform transformOf(double theta_deg, double x, double y) {
  GridTransform T;
  T.theta_rad = theta_deg * kDeg;
  T.t_cells = Eigen::Vector2d(x, y);
  return T;
}

// The room's centre in the cells of `from` (drawnPair()).
const Eigen::Vector2d kRoomCentreInFrom(70.0, 70.0);

// A miss of a transform of `from`: a turn by `deg` about the room's centre, then a shift.
GridTransform missAboutTheRoom(double deg, double x, double y) {
  GridTransform turn = transformOf(deg, 0.0, 0.0);
  turn.t_cells = kRoomCentreInFrom - turn.apply(kRoomCentreInFrom) + Eigen::Vector2d(x, y);
  return turn;
}

struct Offsets {
  double cells = 0.0;
  double deg = 0.0;
};

// How far apart two transforms of `from` put the room's centre, and their turn.
Offsets apart(const GridTransform& a, const GridTransform& b) {
  return {(a.apply(kRoomCentreInFrom) - b.apply(kRoomCentreInFrom)).norm(),
          std::abs(std::remainder(a.theta_rad - b.theta_rad, 2.0 * M_PI)) / kDeg};
}

struct DrawnPair {
  GridMap from;
  GridMap to;
  GridTransform T_to_from;  // the truth
};

DrawnPair drawnPair() {
  const GridTransform T_from_room = transformOf(0.0, 20.0, 20.0);
  const GridTransform T_to_room = transformOf(23.0, 35.3, 6.6);
  return {drawRoom(T_from_room), drawRoom(T_to_room), compose(T_to_room, T_from_room.inverse())};
}

TEST(WallAlignmentTest, SettingsAreReadAndRangeChecked) {
  const SeedMergerSettings loaded = loadSeedMergerSettings(
      Config::loadString("wall_alignment: false\nwall_alignment_sigma_cells: 0.7\n"
                         "wall_alignment_turn_deg: 2\nwall_alignment_shift_cells: 3\n"
                         "wall_alignment_starts: 5\n",
                         "merge.yaml"));
  EXPECT_FALSE(loaded.wall_alignment.enabled);
  EXPECT_DOUBLE_EQ(loaded.wall_alignment.sigma_cells, 0.7);
  EXPECT_DOUBLE_EQ(loaded.wall_alignment.max_turn_deg, 2.0);
  EXPECT_DOUBLE_EQ(loaded.wall_alignment.max_shift_cells, 3.0);
  EXPECT_EQ(loaded.wall_alignment.starts, 5);
  EXPECT_TRUE(SeedMergerSettings{}.wall_alignment.enabled);
  EXPECT_TRUE(SeedMergerSettings{}.settle_alignment);
  EXPECT_FALSE(loadSeedMergerSettings(Config::loadString("settle_alignment: false\n", "merge.yaml"))
                   .settle_alignment);
  EXPECT_THROW(
      loadSeedMergerSettings(Config::loadString("wall_alignment_sigma_cells: 0\n", "merge.yaml")),
      ConfigError);
  EXPECT_THROW(
      loadSeedMergerSettings(Config::loadString("wall_alignment_turn_deg: -1\n", "merge.yaml")),
      ConfigError);
  EXPECT_THROW(
      loadSeedMergerSettings(Config::loadString("wall_alignment_starts: 0\n", "merge.yaml")),
      ConfigError);
}

TEST(WallAlignmentTest, TheFieldIsOneOnWallsFallsWithDistanceAndIsZeroOnUnknownCells) {
  const DrawnPair pair = drawnPair();
  const WallField field(pair.from, SimilaritySettings{}, WallAlignmentSettings{});
  using Level = WallField::Level;
  const double on_wall = field.fieldAt(Eigen::Vector2d(60.0, 30.0), Level::kFine);  // (40, 10)
  const double one_cell_in = field.fieldAt(Eigen::Vector2d(60.0, 31.0), Level::kFine);
  EXPECT_NEAR(on_wall, 1.0, 1e-6);
  EXPECT_NEAR(one_cell_in, std::exp(-1.0 / (2.0 * 0.25)), 1e-6);
  EXPECT_NEAR(field.fieldAt(Eigen::Vector2d(60.0, 30.5), Level::kFine),
              0.5 * (on_wall + one_cell_in), 1e-6);  // bilinear
  EXPECT_NEAR(field.fieldAt(Eigen::Vector2d(60.0, 32.0), Level::kCoarse), std::exp(-2.0), 1e-6);
  EXPECT_NEAR(field.fieldAt(Eigen::Vector2d(60.0, 32.0), Level::kFine), 0.0, 1e-3);
  // One cell outside the wall is unknown: no field there, though the wall is one cell away.
  EXPECT_EQ(field.fieldAt(Eigen::Vector2d(60.0, 29.0), Level::kCoarse), 0.0);
  EXPECT_FALSE(field.isKnown(Eigen::Vector2d(60.0, 29.0)));
  EXPECT_TRUE(field.isKnown(Eigen::Vector2d(60.2, 30.4)));
  EXPECT_TRUE(field.knownWithin(Eigen::Vector2d(60.0, 27.0), 3.0));
  EXPECT_FALSE(field.knownWithin(Eigen::Vector2d(60.0, 27.0), 2.5));
  EXPECT_EQ(field.fieldAt(Eigen::Vector2d(-3.0, 200.0), Level::kFine), 0.0);  // off the map
  EXPECT_FALSE(field.isKnown(Eigen::Vector2d(-3.0, 200.0)));
}

TEST(WallAlignmentTest, TheSumOverCellsEqualsTheFieldSummedCellByCell) {
  const DrawnPair pair = drawnPair();
  const WallField field(pair.from, SimilaritySettings{}, WallAlignmentSettings{});
  const double last_x = pair.from.geometry.width - 1.0;
  const double last_y = pair.from.geometry.height - 1.0;
  // Walls, cells between them, off the map on every side and on the last row and column (which
  // count as off the map), at a fractional shift.
  std::vector<Eigen::Vector2d> cells = {{60.0, 30.0},         {60.3, 31.7},   {-0.6, 40.0},
                                        {40.0, -0.2},         {last_x, 50.0}, {50.0, last_y},
                                        {last_x - 0.9, 50.0}, {1e6, -1e6},    {110.25, 29.5}};
  for (int i = 0; i < 200; ++i) {
    cells.emplace_back(0.37 * i - 3.0, 0.53 * i - 5.0);
  }
  const Eigen::Vector2d shift(0.625, -1.375);
  for (const WallField::Level level : {WallField::Level::kFine, WallField::Level::kCoarse}) {
    double expected = 0.0;
    for (const Eigen::Vector2d& cell : cells) {
      expected += field.fieldAt(cell + shift, level);
    }
    EXPECT_GT(expected, 1.0);
    EXPECT_EQ(field.sumAt(cells, shift, level), expected);  // the same sum, bit for bit
  }
  EXPECT_EQ(field.sumAt({}, shift, WallField::Level::kFine), 0.0);
}

TEST(WallAlignmentTest, ANearMissOfADrawnRoomIsMovedOntoTheTruth) {
  const DrawnPair pair = drawnPair();
  const SimilaritySettings classes;
  const WallAlignmentSettings settings;
  const WallField from(pair.from, classes, settings);
  const WallField to(pair.to, classes, settings);
  for (const GridTransform& miss :
       {missAboutTheRoom(1.1, 1.6, -0.9), missAboutTheRoom(-0.8, -1.2, 1.7),
        missAboutTheRoom(0.0, 2.1, 0.4)}) {
    const GridTransform start = compose(pair.T_to_from, miss);
    ASSERT_GT(apart(start, pair.T_to_from).cells, 1.0);
    const GridTransform aligned = alignWalls(from, to, start, settings);
    const Offsets error = apart(aligned, pair.T_to_from);
    EXPECT_LT(error.cells, 0.3);
    EXPECT_LT(error.deg, 0.2);
    EXPECT_GT(wallAgreement(from, to, aligned).score, wallAgreement(from, to, start).score);
  }
}

TEST(WallAlignmentTest, TheTransformStaysInsideTheWindow) {
  const DrawnPair pair = drawnPair();
  const SimilaritySettings classes;
  WallAlignmentSettings settings;
  settings.max_turn_deg = 0.5;
  settings.max_shift_cells = 1.0;
  const WallField from(pair.from, classes, settings);
  const WallField to(pair.to, classes, settings);
  // Three degrees off: the walls pull further than the window lets the transform go.
  const GridTransform start = compose(pair.T_to_from, missAboutTheRoom(3.0, 0.0, 0.0));
  const GridTransform aligned = alignWalls(from, to, start, settings);
  EXPECT_LE(std::abs(aligned.theta_rad - start.theta_rad), 0.5 * kDeg + 1e-9);
  EXPECT_LT(apart(aligned, pair.T_to_from).deg, apart(start, pair.T_to_from).deg);
}

TEST(WallAlignmentTest, TooFewWallsInTheOverlapLeaveTheTransformAsFound) {
  const DrawnPair pair = drawnPair();
  const SimilaritySettings classes;
  WallAlignmentSettings settings;
  const WallField from(pair.from, classes, settings);
  const WallField to(pair.to, classes, settings);
  const GridTransform start = compose(pair.T_to_from, missAboutTheRoom(0.7, 1.0, 1.0));
  settings.min_walls = wallAgreement(from, to, start).counted + 1;
  const GridTransform unchanged = alignWalls(from, to, start, settings);
  EXPECT_EQ(unchanged.theta_rad, start.theta_rad);
  EXPECT_EQ(unchanged.t_cells, start.t_cells);
  // Far apart, no wall of either lands on the other's known cells.
  const GridTransform away = transformOf(0.0, 500.0, 500.0);
  EXPECT_EQ(wallAgreement(from, to, away).counted, 0);
  EXPECT_EQ(alignWalls(from, to, away, WallAlignmentSettings{}).t_cells, away.t_cells);
}

TEST(WallAlignmentTest, OnlyAcceptedResultsAreAlignedAndTheirFiguresTakenAgain) {
  const DrawnPair pair = drawnPair();
  MergeResult refused;
  refused.T_to_from = compose(pair.T_to_from, missAboutTheRoom(1.0, 1.5, 0.0));
  const GridTransform found = refused.T_to_from;
  alignAccepted(pair.from, pair.to, WallAlignmentSettings{}, SimilaritySettings{}, refused);
  EXPECT_EQ(refused.T_to_from.t_cells, found.t_cells);

  MergeResult accepted = refused;
  accepted.accepted = true;
  accepted.verification = 0.0;
  WallAlignmentSettings off;
  off.enabled = false;
  alignAccepted(pair.from, pair.to, off, SimilaritySettings{}, accepted);
  EXPECT_EQ(accepted.T_to_from.t_cells, found.t_cells);

  alignAccepted(pair.from, pair.to, WallAlignmentSettings{}, SimilaritySettings{}, accepted);
  EXPECT_LT(apart(accepted.T_to_from, pair.T_to_from).cells, 0.3);
  EXPECT_GT(accepted.verification, 0.95);  // taken again at the aligned transform
  EXPECT_GT(accepted.entropy, 0.0);
}

// The seed merger's alignment of another method's result on the pair's search inputs (their wall
// fields, samples and code image, built once for the pair) gives what building them for it does.
TEST(WallAlignmentTest, AlignmentOnAPairsSearchInputsEqualsOneOnFieldsBuiltForIt) {
  const DrawnPair pair = drawnPair();
  SeedMerger judge;
  for (const double miss : {0.0, 1.0}) {
    MergeResult built;
    built.accepted = true;
    built.T_to_from = compose(pair.T_to_from, missAboutTheRoom(miss, 1.5 * miss, 0.5 * miss));
    MergeResult on_inputs = built;
    alignAccepted(pair.from, pair.to, judge.settings().wall_alignment, judge.settings().similarity,
                  built);
    judge.alignOnInputs(pair.from, pair.to, on_inputs);
    merge_test::expectTheSameDecision(on_inputs, built, "missed by " + std::to_string(miss));
    EXPECT_LT(apart(on_inputs.T_to_from, pair.T_to_from).cells, 0.3) << miss;
  }
}

// Accepted transforms of `mrslam merge-cases --seed 3` that ended 1.0-2.2 cells and 0.7-1.2° from
// the truth before the alignment (the exhaustive step's own peak, case 151 the seed step's): at
// overlaps of 27-50 %, the walls of the overlap span a short arm, so the searches' whole cells and
// quarter degrees leave the last degree. (A fourth, case 177, is refused since block 8 settles on
// aligned walls: the exhaustive search's own peak lies 2.1 cells from the judged transform.)
const merge_test::CropPair kNearMisses[] = {
    {"carpin-LongRun7.txt",
     81,
     {{149, 187}, 263, -0.1332713747391252, {13, 1}, {18, 29}},
     {{384, 279}, 161, -1.0293815047972292, {19, 14}, {22, 21}}},
    {"carpin-robot2_cast.txt",
     123,
     {{219, -95}, 215, 1.0552217685307914, {27, 23}, {37, 35}},
     {{104, -147}, 180, 2.715593182281891, {34, 40}, {15, 25}}},
    {"carpin-intel.txt",
     151,
     {{69, 47}, 187, 2.1802173914455407, {4, 12}, {8, 32}},
     {{135, 165}, 193, 2.0168056896065254, {0, 19}, {35, 0}}}};

// The exhaustive merger's own checks switched on (they are off by default).
constexpr const char* kOwnChecks =
    "exhaustive: {check_own_score: true, max_turn_ambiguity: 0.97}\n";
// The chain's V-basin check off (neighbour_basins.hpp): it refuses the near misses below as well,
// and these tests show what the alignment does.
constexpr const char* kBasinsOff = "chain: {neighbour_basin_min_v_gain: 1}\n";

TEST(WallAlignmentTest, TheChainsNearMissesOnRealCropsEndWithinACellAndHalfADegree) {
  for (const merge_test::CropPair& pair : kNearMisses) {
    MRSLAM_REQUIRE_SHARED_DATA(std::string("maps/") + pair.map);
    const MergeCase merge_case = merge_test::cut(pair);
    const auto chain = makeMerger("chain");
    const MergeResult result = chain->merge(merge_case.a, merge_case.b);
    ASSERT_TRUE(result.accepted) << "case " << pair.case_id << ": " << result.reason;
    const CaseError error = caseError(merge_case, result.T_to_from);
    EXPECT_LT(error.distance_cells, 1.0) << "case " << pair.case_id;
    EXPECT_LT(error.angle_rad, 0.5 * kDeg) << "case " << pair.case_id;
  }
}

TEST(WallAlignmentTest, WithoutItTheSameCropsEndOutsideTheTolerance) {
  // The case the alignment mends, so the test above cannot pass without it.
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-LongRun7.txt");
  const MergeCase merge_case = merge_test::cut(kNearMisses[0]);
  // With the exhaustive merger's own checks on (off by default), as when the
  // alignment was added: without them the chain now takes another hypothesis of this case.
  const Config config = Config::loadString(std::string(kOwnChecks) + kBasinsOff +
                                               "seed:\n  wall_alignment: false\n"
                                               "  settle_alignment: false\n",
                                           "merge.yaml");
  const auto chain = makeMergerFrom("chain", config);
  const MergeResult result = chain->merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(result.accepted) << result.reason;
  EXPECT_FALSE(isCorrect(caseError(merge_case, result.T_to_from)));
}

// Accepted transforms of four case sets (8, 12, 19, 35 of `mrslam merge-cases`, with the alignment
// climbing from the coarse grid's best point alone) that ended 1.3-1.7° from the truth: the walls' agreement has two
// basins there, and the coarse grid's best point lay in the one the search had found while the
// narrow field is higher in the other, near the truth (12/124: 116.0 there, 113.5 where found,
// 102 between). Climbing from the grid's three best distinct points reaches it.
const merge_test::CropPair kTwoBasins[] = {
    {"carpin-robot3_cast.txt",
     48,
     {{80, -36}, 296, 0.5582955083231531, {25, 6}, {40, 25}},
     {{-186, 35}, 293, 0.3670820300056965, {25, 32}, {9, 31}}},
    {"carpin-robot0_cast.txt",
     124,
     {{266, -17}, 177, 1.9656510987439155, {33, 19}, {35, 11}},
     {{197, 122}, 288, 0.7614946305765025, {26, 26}, {22, 31}}},
    {"carpin-robot2_cast.txt",
     30,
     {{26, -8}, 292, 0.5248036388294981, {25, 14}, {17, 5}},
     {{289, 5}, 202, 2.882974534272769, {18, 25}, {30, 39}}},
    {"carpin-robot1_cast.txt",
     135,
     {{72, 5}, 264, 0.268956467756448, {8, 14}, {3, 18}},
     {{305, 56}, 173, 1.8709811260109834, {40, 17}, {17, 13}}}};

TEST(WallAlignmentTest, ClimbingFromSeveralGridPointsReachesTheHigherOfTwoBasins) {
  for (const merge_test::CropPair& pair : kTwoBasins) {
    MRSLAM_REQUIRE_SHARED_DATA(std::string("maps/") + pair.map);
    const MergeCase merge_case = merge_test::cut(pair);
    const MergeResult result = makeMerger("chain")->merge(merge_case.a, merge_case.b);
    ASSERT_TRUE(result.accepted) << "case " << pair.case_id << ": " << result.reason;
    const CaseError error = caseError(merge_case, result.T_to_from);
    EXPECT_LT(error.distance_cells, 1.5) << "case " << pair.case_id;
    EXPECT_LT(error.angle_rad, 0.5 * kDeg) << "case " << pair.case_id;
  }
}

TEST(WallAlignmentTest, FromTheBestGridPointAloneTheSameCropsEndOutsideTheTolerance) {
  for (const merge_test::CropPair& pair : kTwoBasins) {
    MRSLAM_REQUIRE_SHARED_DATA(std::string("maps/") + pair.map);
    const MergeCase merge_case = merge_test::cut(pair);
    const MergeResult result =
        merge_test::chainFrom(std::string(kBasinsOff) + "seed: {wall_alignment_starts: 1}\n")
            ->merge(merge_case.a, merge_case.b);
    ASSERT_TRUE(result.accepted) << "case " << pair.case_id << ": " << result.reason;
    EXPECT_GT(caseError(merge_case, result.T_to_from).angle_rad, 1.0 * kDeg)
        << "case " << pair.case_id;
  }
}

// Case 60 of `--seed 6` (23 % overlap): the exhaustive step's transform lies 3.8 cells and 2.7°
// from the truth. The climb from the coarse grid's best point ends where the walls meet almost as
// well turned by 3°; the highest climb ends 1.8 cells and 1.2° off, where they do not.
const merge_test::CropPair kGuessedAtTheFirstPeak{
    "carpin-robot0_cast.txt",
    60,
    {{287, 47}, 216, 1.4912237271567248, {2, 5}, {3, 26}},
    {{101, 1}, 215, 2.0738806280125184, {38, 22}, {18, 35}}};

TEST(WallAlignmentTest, ARotationGuessedAtTheFirstClimbsPeakRefusesTheMerge) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot0_cast.txt");
  const MergeCase merge_case = merge_test::cut(kGuessedAtTheFirstPeak);
  const MergeResult found =
      merge_test::chainFrom(std::string(kBasinsOff) + "seed: {wall_alignment: false}\n")
          ->merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(found.accepted) << found.reason;
  ASSERT_FALSE(isCorrect(caseError(merge_case, found.T_to_from)));
  const WallAlignmentSettings settings;
  const WallField from(merge_case.a, SimilaritySettings{}, settings);
  const WallField to(merge_case.b, SimilaritySettings{}, settings);
  const WallPeaks peaks = wallPeaks(from, to, found.T_to_from, settings);
  EXPECT_LT(wallTurnShare(from, to, peaks.highest, settings), settings.max_turn_share);
  EXPECT_GE(wallTurnShare(from, to, peaks.first, settings), settings.max_turn_share);
  MergeResult aligned = found;
  alignAccepted(merge_case.a, merge_case.b, settings, SimilaritySettings{}, aligned);
  EXPECT_FALSE(aligned.accepted);
  EXPECT_EQ(aligned.refusal, MergeRefusal::kRotation);
  EXPECT_GE(aligned.wall_turn_share, settings.max_turn_share);
  const MergeResult chain = makeMerger("chain")->merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(chain.accepted) << caseError(merge_case, chain.T_to_from).angle_rad / kDeg
                               << " degrees from the truth";
}

// Case 153 of `--seed 2`: an overlap of one long wall and a stub, whose crops' walls (turned by
// different angles, resampled to the nearest cell) meet best 2.2 cells and 1.1° from the truth,
// where V is lower than at the transform the chain found (0.41 cells off).
const merge_test::CropPair kWallsPullOff{"carpin-robot3_cast.txt",
                                         153,
                                         {{82, -40}, 227, -0.4777359392994587, {39, 29}, {0, 11}},
                                         {{-121, -48}, 237, 2.644260060571048, {19, 16}, {3, 26}}};

TEST(WallAlignmentTest, AnAlignmentThatLowersTheVerificationIndexIsNotKept) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot3_cast.txt");
  const MergeCase merge_case = merge_test::cut(kWallsPullOff);
  const Config without = Config::loadString(
      "seed:\n  wall_alignment: false\n  settle_alignment: false\n", "merge.yaml");
  const MergeResult found = makeMergerFrom("chain", without)->merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(found.accepted) << found.reason;
  ASSERT_TRUE(isCorrect(caseError(merge_case, found.T_to_from)));
  // The walls alone pull it out of the tolerance ...
  const WallAlignmentSettings settings;
  const WallField from(merge_case.a, SimilaritySettings{}, settings);
  const WallField to(merge_case.b, SimilaritySettings{}, settings);
  EXPECT_FALSE(isCorrect(caseError(merge_case, alignWalls(from, to, found.T_to_from, settings))));
  // ... so the chain, which aligns only where V does not drop, keeps it within the tolerance.
  const MergeResult aligned = makeMerger("chain")->merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(aligned.accepted) << aligned.reason;
  EXPECT_TRUE(isCorrect(caseError(merge_case, aligned.T_to_from)));
}

// Refused by the seed merger without the alignment in block 8 and accepted within the tolerance
// with it: 169 and 166 of `--seed 3` (the translation ambiguity, taken around a transform a cell
// off, was 0.96-0.99), 189 of `--seed 2` (the global search's candidate judged 6 cells and 5°
// off).
const merge_test::CropPair kSettledByAlignment[] = {
    {"freiburg-aces.pgm",
     169,
     {{749, 474}, 173, 0.5011861854906257, {9, 14}, {10, 10}},
     {{828, 403}, 294, 2.485125072462897, {30, 23}, {15, 23}}},
    {"carpin-robot0_cast.txt",
     166,
     {{339, 95}, 173, 2.5146384133548665, {37, 23}, {15, 15}},
     {{221, -99}, 265, 2.3935537898999915, {8, 12}, {27, 21}}},
    {"carpin-robot1_cast.txt",
     189,
     {{331, 85}, 204, 0.3489613962599951, {20, 31}, {25, 10}},
     {{185, 79}, 181, 1.09184051862586, {20, 35}, {10, 27}}}};

TEST(WallAlignmentTest, SettlingOnAlignedWallsTurnsRefusalsIntoRightMerges) {
  for (const merge_test::CropPair& pair : kSettledByAlignment) {
    MRSLAM_REQUIRE_SHARED_DATA(std::string("maps/") + pair.map);
    const MergeCase merge_case = merge_test::cut(pair);
    SeedMergerSettings settings;
    settings.settle_alignment = false;
    // The cleaner bar of walls over open floor merges 166 without the settling
    // too, within the tolerance; it is off here so that the settling alone decides.
    settings.clean_walls_over_floor_min_v = 2.0;
    SeedMerger without(settings);
    EXPECT_FALSE(without.merge(merge_case.a, merge_case.b).accepted) << "case " << pair.case_id;
    SeedMerger with;
    merge_test::expectMergedWithinTwoCellsAndOneDegree(pair, with);
  }
  SeedMergerSettings clean_bar_only;
  clean_bar_only.settle_alignment = false;
  SeedMerger by_clean_bar(clean_bar_only);
  merge_test::expectMergedWithinTwoCellsAndOneDegree(kSettledByAlignment[1], by_clean_bar);
}

// A round room: turned about its centre, its wall lies on itself, so it fixes no rotation.
GridMap drawRoundRoom(const GridTransform& T_grid_world) {
  GridGeometry geometry;
  geometry.width = 100;
  geometry.height = 100;
  GridMap map(geometry, GridMap::kUnknown);
  const GridTransform T_world_grid = T_grid_world.inverse();
  const Eigen::Vector2d centre(45.0, 45.0);
  for (int y = 0; y < geometry.height; ++y) {
    for (int x = 0; x < geometry.width; ++x) {
      const double radius = (T_world_grid.apply(Eigen::Vector2d(x, y)) - centre).norm();
      if (std::abs(radius - 25.0) <= 0.5) {
        map.at(x, y) = GridMap::kOccupied;
      } else if (radius < 25.0) {
        map.at(x, y) = GridMap::kFree;
      }
    }
  }
  return map;
}

TEST(WallAlignmentTest, TheTurnCheckTellsARoundRoomFromAnLShapedOne) {
  const WallAlignmentSettings settings;
  const SimilaritySettings classes;
  const DrawnPair room = drawnPair();
  const WallField room_from(room.from, classes, settings);
  const WallField room_to(room.to, classes, settings);
  EXPECT_LT(wallTurnShare(room_from, room_to, room.T_to_from, settings), 0.8);

  // Turned and shifted between cells, as two robots' grids are: neither room's cells meet the
  // other's exactly at the truth.
  const GridTransform T_to_from = transformOf(17.0, 13.3, -8.6);
  const GridMap round_from = drawRoundRoom(GridTransform{});
  const GridMap round_to = drawRoundRoom(T_to_from);
  const WallField from(round_from, classes, settings);
  const WallField to(round_to, classes, settings);
  EXPECT_GE(wallTurnShare(from, to, T_to_from, settings), settings.max_turn_share);

  MergeResult result;
  result.accepted = true;
  result.T_to_from = T_to_from;
  alignAccepted(round_from, round_to, settings, classes, result);
  EXPECT_FALSE(result.accepted);
  EXPECT_NE(result.reason.find("do not fix the rotation"), std::string::npos) << result.reason;

  WallAlignmentSettings off = settings;
  off.max_turn_share = 1.0;
  result.accepted = true;
  alignAccepted(round_from, round_to, off, classes, result);
  EXPECT_TRUE(result.accepted);
}

// Case 165 of `--seed 3`: crop A's walls meet crop B only in a thin strip along B's window edge,
// where they are the stubs of room walls; the chain accepted a transform 2.6 cells and 1.4° off.
const merge_test::CropPair kStubsAlongAnEdge{
    "carpin-robot1_cast.txt",
    165,
    {{80, -71}, 243, -2.8966120672679008, {29, 21}, {16, 34}},
    {{84, 145}, 219, -0.02164073794931376, {22, 4}, {16, 6}}};

// With the exhaustive merger's own checks on (as when the wall-turn check was added). Without them
// (the defaults) the chain accepts this case 5.1 cells and 2.7° off,
// a false accept listed in docs/merge_tuning.md.
TEST(WallAlignmentTest, AnOverlapWhoseWallsDoNotFixTheRotationIsRefused) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-robot1_cast.txt");
  const MergeCase merge_case = merge_test::cut(kStubsAlongAnEdge);
  const MergeResult result = makeMergerFrom("chain", Config::loadString(kOwnChecks, "merge.yaml"))
                                 ->merge(merge_case.a, merge_case.b);
  EXPECT_FALSE(result.accepted) << caseError(merge_case, result.T_to_from).distance_cells
                                << " cells from the truth";
  const Config unchecked = Config::loadString(
      std::string(kOwnChecks) + "seed:\n  max_wall_turn_share: 1\n", "merge.yaml");
  const MergeResult guessed = makeMergerFrom("chain", unchecked)->merge(merge_case.a, merge_case.b);
  ASSERT_TRUE(guessed.accepted) << guessed.reason;
  EXPECT_FALSE(isCorrect(caseError(merge_case, guessed.T_to_from)));
}

}  // namespace
}  // namespace mrslam::fusion
