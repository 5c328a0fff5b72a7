// Seeded merges of crops of real maps (../shared/data/maps) with known answers, and refusals of
// crops from different buildings. MRSLAM_MERGE_CASES=<n> runs n cases per map and overlap band in
// the sweep (default 4) and prints the success rate of every band.

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "merge_test_maps.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

struct Tally {
  int cases = 0;
  int successes = 0;
  int wrong_accepts = 0;
};

Tally runCases(const GridMap& map, int size, double low, double high, int count,
               std::uint32_t seed) {
  std::mt19937 random(seed);
  SeedMerger merger;
  Tally tally;
  for (int i = 0; i < count; ++i) {
    const merge_test::KnownCase known = merge_test::randomCase(map, size, low, high, random);
    if (known.overlap == 0.0) {
      continue;
    }
    ++tally.cases;
    const MergeResult result = merger.merge(known.from, known.to);
    const bool right = merge_test::isSuccess(merge_test::poseError(result.T_to_from, known));
    tally.successes += result.accepted && right ? 1 : 0;
    tally.wrong_accepts += result.accepted && !right ? 1 : 0;
  }
  return tally;
}

GridMap loadShared(const std::string& name) {
  return merge_test::loadMap(test::sharedDataPath("maps/" + name));
}

class MergeKnownAnswerTest : public ::testing::TestWithParam<const char*> {};

TEST_P(MergeKnownAnswerTest, CropsOverlappingByHalfOrMoreMergeWithinTwoCellsAndOneDegree) {
  MRSLAM_REQUIRE_SHARED_DATA(std::string("maps/") + GetParam());
  const GridMap map = loadShared(GetParam());
  ASSERT_GT(map.cells.size(), 0u);
  const Tally tally = runCases(map, 300, 0.5, 1.01, 10, 2024);
  ASSERT_GE(tally.cases, 8);
  EXPECT_EQ(tally.wrong_accepts, 0);
  EXPECT_GE(tally.successes, tally.cases - 1) << tally.successes << " of " << tally.cases;
}

// The walls-onto-walls refinements (ICP in block 8 on an even sample of `wall_icp_samples` walls,
// the two-way alignment after acceptance) take accepted merges below the cell and the polish step.
TEST(MergeKnownAnswerPrecisionTest, AcceptedMergesLandWithinAFractionOfACell) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const GridMap map = loadShared("freiburg-intel.pgm");
  std::vector<double> distances;
  std::vector<double> angles;
  for (const bool refined : {true, false}) {  // refined, then the discrete search alone
    SeedMergerSettings settings;
    settings.wall_icp_iterations = refined ? 30 : 0;
    settings.wall_alignment.enabled = refined;
    SeedMerger merger(settings);
    std::mt19937 cases(11);
    std::vector<double> distance_errors;
    std::vector<double> angle_errors;
    for (int i = 0; i < 12; ++i) {
      const merge_test::KnownCase known = merge_test::randomCase(map, 300, 0.5, 1.01, cases);
      const MergeResult result = merger.merge(known.from, known.to);
      if (known.overlap > 0.0 && result.accepted) {
        const merge_test::PoseError error = merge_test::poseError(result.T_to_from, known);
        distance_errors.push_back(error.translation_cells);
        angle_errors.push_back(error.rotation_rad * 180.0 / M_PI);
      }
    }
    ASSERT_GE(distance_errors.size(), 8u) << refined;
    std::nth_element(distance_errors.begin(), distance_errors.begin() + distance_errors.size() / 2,
                     distance_errors.end());
    std::nth_element(angle_errors.begin(), angle_errors.begin() + angle_errors.size() / 2,
                     angle_errors.end());
    distances.push_back(distance_errors[distance_errors.size() / 2]);
    angles.push_back(angle_errors[angle_errors.size() / 2]);
    std::printf("refined %d: median error %.3f cells, %.3f deg\n", refined ? 1 : 0,
                distances.back(), angles.back());
  }
  EXPECT_LE(distances[0], 0.5);
  EXPECT_LE(angles[0], 0.25);
  EXPECT_LT(distances[0], distances[1]);  // better than the discrete search alone
  EXPECT_LT(angles[0], angles[1]);
}

INSTANTIATE_TEST_SUITE_P(RealMaps, MergeKnownAnswerTest,
                         ::testing::Values("carpin-intel.txt", "freiburg-intel.pgm",
                                           "freiburg-aces.pgm", "carpin-LongRun6.txt"));

TEST(MergeKnownAnswerSweepTest, SuccessRatePerOverlapBand) {
  const std::vector<std::string> names = {"carpin-intel.txt", "freiburg-intel.pgm",
                                          "freiburg-aces.pgm", "carpin-LongRun6.txt",
                                          "carpin-LongRun7.txt"};
  for (const std::string& name : names) {
    MRSLAM_REQUIRE_SHARED_DATA("maps/" + name);
  }
  const char* override_count = std::getenv("MRSLAM_MERGE_CASES");
  const int count = override_count != nullptr ? std::max(1, std::atoi(override_count)) : 4;
  const double bands[][2] = {{0.2, 0.4}, {0.4, 0.6}, {0.6, 1.01}};
  for (std::size_t b = 0; b < std::size(bands); ++b) {
    Tally total;
    for (std::size_t m = 0; m < names.size(); ++m) {
      const Tally tally = runCases(loadShared(names[m]), 400, bands[b][0], bands[b][1], count,
                                   static_cast<std::uint32_t>(100 * b + m));
      total.cases += tally.cases;
      total.successes += tally.successes;
      total.wrong_accepts += tally.wrong_accepts;
    }
    std::printf("overlap [%.1f, %.1f): %d of %d within 2 cells and 1 degree, %d wrong accepts\n",
                bands[b][0], std::min(1.0, bands[b][1]), total.successes, total.cases,
                total.wrong_accepts);
    ASSERT_GT(total.cases, 0);
    EXPECT_EQ(total.wrong_accepts, 0) << "band " << b;
    if (bands[b][0] >= 0.4) {
      EXPECT_GE(total.successes, 0.9 * total.cases) << "band " << b;
    }
  }
}

TEST(MergeKnownAnswerTest, RefusesCropsOfDifferentBuildings) {
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {"carpin-intel.txt", "freiburg-aces.pgm"},
      {"freiburg-intel.pgm", "carpin-LongRun6.txt"},
      {"freiburg-aces.pgm", "carpin-LongRun7.txt"},
      {"carpin-LongRun6.txt", "carpin-intel.txt"}};
  std::mt19937 random(99);
  SeedMerger merger;
  int refused = 0;
  int tried = 0;
  for (const auto& [name_a, name_b] : pairs) {
    MRSLAM_REQUIRE_SHARED_DATA("maps/" + name_a);
    MRSLAM_REQUIRE_SHARED_DATA("maps/" + name_b);
    const GridMap a = loadShared(name_a);
    const GridMap b = loadShared(name_b);
    for (int i = 0; i < 5; ++i) {
      // Each crop: a random window with structure, turned; the other building's crop as `to`.
      const merge_test::KnownCase from = merge_test::randomCase(a, 300, 0.5, 1.01, random);
      const merge_test::KnownCase to = merge_test::randomCase(b, 300, 0.5, 1.01, random);
      ASSERT_GT(from.overlap, 0.0);
      ASSERT_GT(to.overlap, 0.0);
      const MergeResult result = merger.merge(from.from, to.to);
      ++tried;
      refused += result.accepted ? 0 : 1;
      EXPECT_FALSE(result.accepted)
          << name_a << " → " << name_b << " #" << i << ": V = " << result.verification;
      if (!result.accepted) {
        EXPECT_FALSE(result.reason.empty());
      }
    }
  }
  EXPECT_EQ(refused, tried);
}

}  // namespace
}  // namespace mrslam::fusion
