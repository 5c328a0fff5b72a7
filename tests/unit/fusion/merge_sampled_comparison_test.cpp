// The chain's prefilter of many placements (sampled_comparison.hpp): its tiles of samples leave
// out only samples that cannot land on a known cell of `to`, so its figures are those of every
// sample, on hand-built grids and on real crops at many placements.

#include "sampled_comparison.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "merge_crop_pairs.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::unknownMap;

void fill(GridMap& map, int x0, int y0, int x1, int y1, std::int8_t value) {
  for (int y = y0; y < y1; ++y) {
    for (int x = x0; x < x1; ++x) {
      map.cells[map.geometry.index(x, y)] = value;
    }
  }
}

TEST(MergeSampledComparisonTest, TilesLandingFarFromKnownCellsAreLeftOut) {
  GridMap from = unknownMap(100, 100);
  fill(from, 0, 0, 20, 20, 0);      // a free corner ...
  fill(from, 70, 70, 100, 100, 0);  // ... and another, far from it
  GridMap to = unknownMap(100, 100);
  fill(to, 0, 0, 25, 25, 0);  // `to` knows only the first corner
  const SampledComparison sampled(from, to, SimilaritySettings{});
  const std::vector<CellSample>& landing = sampled.landingSamples(GridTransform{});
  ASSERT_FALSE(landing.empty());
  EXPECT_LT(landing.size(), sampled.samples().size());
  for (const CellSample& sample : landing) {
    EXPECT_LT(sample.x, 48) << "only tiles within a tile of `to`'s known tiles";
    EXPECT_LT(sample.y, 48);
  }
  EXPECT_DOUBLE_EQ(sampled.disagreementRate(GridTransform{}), 0.0) << "free on free";
  GridTransform away;
  away.t_cells = Eigen::Vector2d(500.0, 0.0);
  EXPECT_TRUE(sampled.landingSamples(away).empty());
  EXPECT_DOUBLE_EQ(sampled.disagreementRate(away), 1.0) << "no overlap";
}

TEST(MergeSampledComparisonTest, FiguresEqualThoseOfEverySampleOnRealCrops) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const MergeCase merge_case = merge_test::cut(merge_test::kIntelCaseZeroOfSeedOne);
  const SimilaritySettings classes;
  const SampledComparison sampled(merge_case.a, merge_case.b, classes);
  const ComparisonTables tables(classes);
  const CodeImage to = codeImage(merge_case.b, 0, tables);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> shift(-150.0, 150.0);
  std::uniform_real_distribution<double> turn(-M_PI, M_PI);
  int left_out = 0;
  for (int k = 0; k < 80; ++k) {
    GridTransform T = merge_case.T_b_a;
    if (k > 0) {
      T.theta_rad += k < 40 ? 0.05 * turn(random) : turn(random);
      T.t_cells += Eigen::Vector2d(shift(random), shift(random));
    }
    const Agreement every = compareAt(sampled.samples(), to, T, tables, false);
    EXPECT_EQ(sampled.disagreementRate(T), 1.0 - verificationIndex(every)) << "placement " << k;
    const double rate = 1.0 - verificationIndex(every);
    for (const double bar : {0.5 * rate, rate, 1.5 * rate + 0.01, 0.02, 0.3}) {
      EXPECT_EQ(sampled.disagreesMoreThan(T, bar),
                disagreementRateExceeds(sampled.samples(), to, T, tables, bar))
          << "placement " << k << ", bar " << bar;
    }
    left_out += sampled.landingSamples(T).size() < sampled.samples().size() ? 1 : 0;
  }
  EXPECT_GT(left_out, 40) << "far placements leave tiles out";
}

}  // namespace
}  // namespace mrslam::fusion
