// The wall balances of block 8's anchoring at every shift (wall_balance.hpp) against one
// structureAgreement() per shift, on hand-built grids with a known answer and on a real crop
// pair turned and shifted by fractions of a cell, as candidates are.

#include <gtest/gtest.h>

#include <random>
#include <utility>

#include "merge_crop_pairs.hpp"
#include "mrslam/fusion/merge/wall_balance.hpp"

namespace mrslam::fusion {
namespace {

using merge_test::CropPair;
using merge_test::cut;

GridMap mapOf(int width, int height, std::int8_t fill) {
  GridGeometry geometry;
  geometry.width = width;
  geometry.height = height;
  return GridMap(geometry, fill);
}

std::vector<CellSample> wallsOf(const GridMap& map, const ComparisonTables& tables) {
  std::vector<CellSample> walls;
  for (const CellSample& cell : knownCells(map, tables)) {
    if (tables.isOccupied(cell.code)) {
      walls.push_back(cell);
    }
  }
  return walls;
}

long long balanceOf(const StructureAgreement& sums) {
  return sums.near - sums.far;
}

// Both directions at every shift within ±reach, each against its own structureAgreement() on
// `from` padded by one cell. The balances the other way round read `from` padded by
// `from_pad` (the search inputs pad both maps alike): cells in a pad are unknown and count as
// nothing, as cells off the image do.
void expectEqualToOneCallPerShift(const GridMap& from, const GridMap& to,
                                  const GridTransform& T_to_from, int reach, int from_pad) {
  const ComparisonTables tables{SimilaritySettings{}};
  const CodeImage image_to = codeImage(to, reach + 2, tables);
  const CodeImage one_cell_pad = codeImage(from, 1, tables);
  const CodeImage image_from = codeImage(from, from_pad, tables);
  const std::vector<CellSample> walls_from = wallsOf(from, tables);
  const std::vector<CellSample> walls_to = wallsOf(to, tables);
  const std::vector<long long> forward = wallBalancesAfterShifts(
      walls_from, image_to, wallBalanceImage(image_to), T_to_from, reach, tables);
  const std::vector<long long> backward = wallBalancesOfInverseShifts(
      walls_to, image_from, wallBalanceImage(image_from), T_to_from, reach, tables);
  const int side = 2 * reach + 1;
  ASSERT_EQ(forward.size(), static_cast<std::size_t>(side * side));
  ASSERT_EQ(backward.size(), forward.size());
  long long walls_met = 0;
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      GridTransform shifted = T_to_from;
      shifted.t_cells += Eigen::Vector2d(dx, dy);
      const std::size_t k = static_cast<std::size_t>((dy + reach) * side + dx + reach);
      const StructureAgreement onto_to = structureAgreement(walls_from, image_to, shifted, tables);
      EXPECT_EQ(forward[k], balanceOf(onto_to)) << dx << ", " << dy;
      const StructureAgreement onto_from =
          structureAgreement(walls_to, one_cell_pad, shifted.inverse(), tables);
      EXPECT_EQ(backward[k], balanceOf(onto_from)) << dx << ", " << dy;
      const StructureAgreement padded =
          structureAgreement(walls_to, image_from, shifted.inverse(), tables);
      EXPECT_EQ(padded.near, onto_from.near) << dx << ", " << dy;
      EXPECT_EQ(padded.far, onto_from.far) << dx << ", " << dy;
      EXPECT_EQ(padded.frontier, onto_from.frontier) << dx << ", " << dy;
      walls_met += onto_to.near;
    }
  }
  EXPECT_GT(walls_met, 0);  // not a comparison of empty sums
}

// One wall cell of `from` against a wall of `to` two cells to its right: the balance is +1 where
// the shift lays it within a cell of that wall, -1 on free cells, 0 off the map.
TEST(MergeWallBalanceTest, OneWallCellMeetsTheWallOnlyAtShiftsNearIt) {
  GridMap from = mapOf(5, 5, GridMap::kFree);
  from.at(2, 2) = GridMap::kOccupied;
  GridMap to = mapOf(5, 5, GridMap::kFree);
  to.at(4, 2) = GridMap::kOccupied;
  const ComparisonTables tables{SimilaritySettings{}};
  const CodeImage image_to = codeImage(to, 4, tables);
  const std::vector<long long> balances = wallBalancesAfterShifts(
      wallsOf(from, tables), image_to, wallBalanceImage(image_to), GridTransform{}, 3, tables);
  ASSERT_EQ(balances.size(), 49u);
  const auto at = [&](int dx, int dy) {
    return balances[static_cast<std::size_t>((dy + 3) * 7 + dx + 3)];
  };
  EXPECT_EQ(at(2, 0), 1);   // on the wall
  EXPECT_EQ(at(1, 1), 1);   // diagonal to it
  EXPECT_EQ(at(0, 0), -1);  // on free floor two cells away
  EXPECT_EQ(at(3, 0), 0);   // off the map's right edge
  EXPECT_EQ(at(-3, -3), 0);
}

// Window sums in steps, centres inside, across and beyond the border, against cell-by-cell sums.
TEST(MergeWallBalanceTest, WindowSumsInStepsEqualCellByCellSums) {
  std::mt19937 random(7);
  std::uniform_int_distribution<int> value(-1, 1);
  cv::Mat values(20, 30, CV_8S);
  for (int y = 0; y < values.rows; ++y) {
    for (int x = 0; x < values.cols; ++x) {
      values.at<std::int8_t>(y, x) = static_cast<std::int8_t>(value(random));
    }
  }
  // {20, 10} and {22, 10} with reach 6: 16 columns from the window's left fit on the image for
  // the first and not for the second (the 16-column sums of steps of 1 and the cell-by-cell ones).
  const std::vector<cv::Point> centres = {{15, 10}, {2, 3},   {29, 19}, {-4, 8},
                                          {40, 40}, {10, 18}, {20, 10}, {22, 10}};
  for (const auto& [reach, step] : {std::pair{5, 2}, std::pair{3, 1}, std::pair{4, 3},
                                    std::pair{6, 1}, std::pair{7, 1}, std::pair{8, 1}}) {
    const std::vector<long long> sums = windowSums(values, centres, reach, step);
    const int count = 2 * reach / step + 1;
    ASSERT_EQ(sums.size(), static_cast<std::size_t>(count * count));
    for (int row = 0; row < count; ++row) {
      for (int column = 0; column < count; ++column) {
        long long expected = 0;
        for (const cv::Point& centre : centres) {
          const int x = centre.x - reach + column * step;
          const int y = centre.y - reach + row * step;
          if (x >= 0 && y >= 0 && x < values.cols && y < values.rows) {
            expected += values.at<std::int8_t>(y, x);
          }
        }
        EXPECT_EQ(sums[static_cast<std::size_t>(row * count + column)], expected)
            << "reach " << reach << ", step " << step << ", offset " << column << ", " << row;
      }
    }
  }
  EXPECT_EQ(windowSums(values, {}, 2, 1), std::vector<long long>(25, 0));
}

TEST(MergeWallBalanceTest, HandBuiltRoomsAtEveryShiftEqualOneCallEach) {
  GridMap map = mapOf(60, 40, GridMap::kFree);
  for (int x = 0; x < 60; ++x) {
    map.at(x, 0) = map.at(x, 39) = GridMap::kOccupied;
  }
  for (int y = 0; y < 40; ++y) {
    map.at(0, y) = map.at(59, y) = map.at(25, y / 2 + 10) = GridMap::kOccupied;
  }
  GridTransform T;
  T.theta_rad = 0.05;
  T.t_cells = Eigen::Vector2d(1.37, -0.62);
  for (const int from_pad : {1, 8}) {
    expectEqualToOneCallPerShift(map, map, T, 6, from_pad);
  }
  T.theta_rad = -2.9;  // turned far: most walls land off the map at most shifts
  T.t_cells = Eigen::Vector2d(61.2, 35.8);
  for (const int from_pad : {1, 6}) {
    expectEqualToOneCallPerShift(map, map, T, 4, from_pad);
  }
}

TEST(MergeWallBalanceTest, RealCropsAtEveryShiftEqualOneCallEach) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const CropPair pair{"freiburg-intel.pgm",
                      101,
                      {{675, 458}, 170, 3.1322967191310953, {37, 17}, {22, 6}},
                      {{625, 306}, 222, -2.6799880310701418, {13, 25}, {21, 20}}};
  const MergeCase merge_case = cut(pair);
  GridTransform near_truth = merge_case.T_b_a;  // a candidate's error: a little turned and slid
  near_truth.theta_rad += 0.013;
  near_truth.t_cells += Eigen::Vector2d(2.31, -1.74);
  for (const int from_pad : {1, 8}) {
    expectEqualToOneCallPerShift(merge_case.a, merge_case.b, near_truth, 6, from_pad);
  }
}

}  // namespace
}  // namespace mrslam::fusion
