// The bound that lets the chain's turn check leave out turns that cannot refuse
// (SeedMerger::placedFits with a least share, seed::mostSimilarity): it never drops a placement
// that reaches the share, on hand-built grids and on real crops.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/seed_merger.hpp"
#include "seed_stages.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::unknownMap;

TEST(MergePlacedFitsTest, CellsWithinReachOfAKnownCellAreReachable) {
  GridMap map = unknownMap(20, 20);
  map.cells[map.geometry.index(5, 5)] = 0;
  const ComparisonTables tables{SimilaritySettings{}};
  const seed::ReachableKnown reachable(codeImage(map, 2, tables), 3);
  EXPECT_TRUE(reachable.at({5, 5}));
  EXPECT_TRUE(reachable.at({8, 8})) << "Chebyshev: the box's corner";
  EXPECT_TRUE(reachable.at({2, 2}));
  EXPECT_FALSE(reachable.at({9, 5}));
  EXPECT_FALSE(reachable.at({5, 1}));
  EXPECT_FALSE(reachable.at({-30, 5})) << "far off the map";
}

TEST(MergePlacedFitsTest, OffThePaddedImageOnlyTheMapsOwnReachCounts) {
  GridMap map = unknownMap(10, 10);
  std::fill(map.cells.begin(), map.cells.end(), std::int8_t{0});
  const ComparisonTables tables{SimilaritySettings{}};
  const seed::ReachableKnown reachable(codeImage(map, 1, tables), 5);
  EXPECT_TRUE(reachable.at({-1, 0})) << "in the pad, beside a known cell";
  EXPECT_TRUE(reachable.at({-5, 0})) << "off the padded image, within reach of the map";
  EXPECT_FALSE(reachable.at({-6, 0}));
  EXPECT_TRUE(reachable.at({14, 14}));
  EXPECT_FALSE(reachable.at({15, 3}));
}

TEST(MergePlacedFitsTest, TheMostSimilarityCountsTheSamplesThatCanLandOnKnownCells) {
  GridMap to = unknownMap(30, 30);
  for (int x = 10; x < 20; ++x) {
    to.cells[to.geometry.index(x, 15)] = 0;  // a row of free cells
  }
  const ComparisonTables tables{SimilaritySettings{}};
  const seed::ReachableKnown reachable(codeImage(to, 4, tables), 3);
  std::vector<CellSample> samples;
  for (int y = 0; y < 30; y += 3) {
    samples.push_back({15, y, 0});  // one column of known cells of `from`
  }
  // At the identity the samples at y 12, 15 and 18 lie within 3 of the row.
  EXPECT_EQ(seed::mostSimilarity(GridTransform{}, samples, reachable), 3);
  GridTransform shifted;
  shifted.t_cells = Eigen::Vector2d(0.0, -6.0);  // then those at y 18, 21 and 24
  EXPECT_EQ(seed::mostSimilarity(shifted, samples, reachable), 3);
  shifted.t_cells = Eigen::Vector2d(12.0, 0.0);  // 8 cells beside the row's end
  EXPECT_EQ(seed::mostSimilarity(shifted, samples, reachable), 0);
}

// Transforms about the accepted one: turned by quarters about the crop's centre and shifted.
std::vector<GridTransform> othersAround(const GridTransform& accepted, const Eigen::Vector2d& pivot,
                                        std::mt19937& random) {
  std::uniform_real_distribution<double> shift(-25.0, 25.0);
  std::uniform_real_distribution<double> turn(-0.2, 0.2);
  std::vector<GridTransform> others;
  for (int k = 0; k < 24; ++k) {
    GridTransform other;
    other.theta_rad = accepted.theta_rad + (k % 4) * M_PI / 2.0 + (k < 4 ? 0.0 : turn(random));
    const Eigen::Vector2d landed = accepted.apply(pivot);
    GridTransform turn_only;
    turn_only.theta_rad = other.theta_rad;
    other.t_cells =
        landed - turn_only.apply(pivot) +
        (k < 4 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(shift(random), shift(random)));
    others.push_back(other);
  }
  return others;
}

bool holds(const std::vector<PlacedFit>& fits, const PlacedFit& fit) {
  for (const PlacedFit& kept : fits) {
    if (kept.T_to_from.theta_rad == fit.T_to_from.theta_rad &&
        kept.T_to_from.t_cells == fit.T_to_from.t_cells) {
      EXPECT_EQ(kept.similarity, fit.similarity);
      EXPECT_EQ(kept.disagreement_rate, fit.disagreement_rate);
      return true;
    }
  }
  return false;
}

TEST(MergePlacedFitsTest, ALeastShareDropsNoPlacementThatReachesIt) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/carpin-intel.txt");
  const MergeCase merge_case = merge_test::cut(merge_test::kIntelCaseZeroOfSeedOne);
  SeedMerger judge;
  const Eigen::Vector2d pivot(0.5 * merge_case.a.geometry.width,
                              0.5 * merge_case.a.geometry.height);
  std::mt19937 random(3);
  const std::vector<GridTransform> others = othersAround(merge_case.T_b_a, pivot, random);
  const std::vector<PlacedFit> all =
      judge.placedFits(merge_case.a, merge_case.b, merge_case.T_b_a, others);
  ASSERT_EQ(all.size(), others.size() + 1);
  ASSERT_GT(all.front().similarity, 0);
  for (const double share : {0.2, 0.5, 1.0, 1.5}) {
    const std::vector<PlacedFit> kept =
        judge.placedFits(merge_case.a, merge_case.b, merge_case.T_b_a, others, share);
    ASSERT_FALSE(kept.empty());
    EXPECT_EQ(kept.front().similarity, all.front().similarity) << "share " << share;
    int reaching = 0;
    for (std::size_t i = 1; i < all.size(); ++i) {
      const double ratio =
          static_cast<double>(all[i].similarity) / static_cast<double>(all.front().similarity);
      if (ratio >= share) {
        ++reaching;
        EXPECT_TRUE(holds(kept, all[i])) << "share " << share << ", placement " << i;
      }
    }
    for (const PlacedFit& fit : kept) {
      EXPECT_TRUE(holds(all, fit))
          << "share " << share << ": a kept placement is one of all, alike";
    }
    if (share == 0.2) {
      EXPECT_GT(reaching, 0) << "some placements reach the lowest share";
    }
    if (share == 1.5) {
      EXPECT_LT(kept.size(), all.size()) << "the bound leaves out some that cannot reach it";
    }
  }
}

}  // namespace
}  // namespace mrslam::fusion
