// The exhaustive search restricted to the turns the walls suggest (`rotation_peaks`): the turns
// hold the truth's and its quarter turns, the restricted search finds the truth, and every
// hypothesis lies near a suggested turn (merge_exhaustive_test.cpp: it keeps what scoring every
// translation of those rotations keeps).

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "merge_crop_pairs.hpp"
#include "mrslam/common/config.hpp"
#include "mrslam/fusion/merge/exhaustive_merger.hpp"
#include "mrslam/fusion/merge/exhaustive_search.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::CropPair;
using merge_test::cut;

/// Two crops of the Intel lab turned by 0.4 and -1.1 rad (the truth turns by -1.5 rad).
const CropPair kTurnedPair = {"freiburg-intel.pgm",
                              0,
                              {{380, 500}, 240, 0.4, {10, 20}, {30, 5}},
                              {{380, 500}, 240, -1.1, {25, 3}, {4, 18}}};

double degreesApart(double a_rad, double b_rad) {
  return std::abs(std::remainder(a_rad - b_rad, 2.0 * M_PI)) * 180.0 / M_PI;
}

/// The least turn (degrees) between `theta` and any of `turns`.
double nearestTurnDeg(double theta, const std::vector<double>& turns) {
  double nearest = 360.0;
  for (const double turn : turns) {
    nearest = std::min(nearest, degreesApart(theta, turn));
  }
  return nearest;
}

TEST(ExhaustiveTurnsTest, TheSuggestedTurnsHoldTheTruthAndItsHalfTurn) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const MergeCase merge_case = cut(kTurnedPair);
  ExhaustiveSearchSettings settings;
  settings.rotation_peaks = 0;
  EXPECT_TRUE(suggestedTurns(merge_case.a, merge_case.b, settings, {}).empty())
      << "rotation_peaks 0: every rotation is searched";
  settings.rotation_peaks = 2;
  const std::vector<double> turns = suggestedTurns(merge_case.a, merge_case.b, settings, {});
  ASSERT_EQ(turns.size(), 8u) << "two peaks, each with its quarter turns";
  const double truth = merge_case.T_b_a.theta_rad;
  EXPECT_LT(nearestTurnDeg(truth, turns), 2.0) << "the truth's turn is suggested";
  for (const double quarter : {M_PI / 2.0, M_PI, 1.5 * M_PI}) {
    EXPECT_LT(nearestTurnDeg(truth + quarter, turns), 2.0) << "and its quarter turns";
  }
  for (std::size_t i = 0; i < turns.size(); i += 4) {
    EXPECT_NEAR(degreesApart(turns[i + 1], turns[i]), 90.0, 1e-9) << "each peak's quarters";
    EXPECT_NEAR(degreesApart(turns[i + 2], turns[i]), 180.0, 1e-9);
  }
}

TEST(ExhaustiveTurnsTest, NoTurnIsSuggestedForAMapWithoutWalls) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const MergeCase merge_case = cut(kTurnedPair);
  GridMap open_floor = merge_case.a;
  for (std::int8_t& cell : open_floor.cells) {
    cell = cell == GridMap::kUnknown ? cell : std::int8_t{0};
  }
  ExhaustiveSearchSettings settings;
  settings.rotation_peaks = 2;
  EXPECT_TRUE(suggestedTurns(open_floor, merge_case.b, settings, {}).empty());
  EXPECT_TRUE(exhaustiveSearch(open_floor, merge_case.b, settings, {}).empty())
      << "nothing to search with";
}

TEST(ExhaustiveTurnsTest, TheSearchNearTheSuggestedTurnsFindsTheTruthAndStaysNearThem) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const MergeCase merge_case = cut(kTurnedPair);
  ExhaustiveSearchSettings settings;
  settings.rotation_peaks = 2;
  const std::vector<double> turns = suggestedTurns(merge_case.a, merge_case.b, settings, {});
  const std::vector<ExhaustiveHypothesis> found =
      exhaustiveSearch(merge_case.a, merge_case.b, settings, {});
  ASSERT_FALSE(found.empty());
  const CaseError error = caseError(merge_case, found.front().T_to_from);
  EXPECT_LE(error.distance_cells, 2.0);
  EXPECT_LE(error.angle_rad * 180.0 / M_PI, 1.0);
  for (const ExhaustiveHypothesis& hypothesis : found) {
    // the window plus step 6's refinement (one rotation step, about 1.2° here, and a quarter)
    EXPECT_LT(nearestTurnDeg(hypothesis.T_to_from.theta_rad, turns),
              settings.rotation_window_deg + 2.0)
        << hypothesis.T_to_from.theta_rad;
  }
}

TEST(ExhaustiveTurnsTest, SettingsAreReadWithRangeChecks) {
  const ExhaustiveSearchSettings read = loadExhaustiveSearchSettings(
      Config::loadString("rotation_peaks: 3\nrotation_window_deg: 4.5\n", "exhaustive.yaml"));
  EXPECT_EQ(read.rotation_peaks, 3);
  EXPECT_EQ(read.rotation_window_deg, 4.5);
  EXPECT_THROW(loadExhaustiveSearchSettings(Config::loadString("rotation_peaks: -1\n", "x.yaml")),
               ConfigError);
  EXPECT_THROW(
      loadExhaustiveSearchSettings(Config::loadString("rotation_window_deg: 100\n", "x.yaml")),
      ConfigError);
}

}  // namespace
}  // namespace mrslam::fusion
