#include "mrslam/fusion/merge/overlap_score.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace mrslam::fusion {
namespace {

constexpr std::int8_t kOcc = GridMap::kOccupied;
constexpr std::int8_t kFree = GridMap::kFree;
constexpr std::int8_t kUnk = GridMap::kUnknown;
constexpr double kPi = 3.14159265358979323846;

/// A map from rows written top row first (as it would look in a picture).
GridMap mapOf(const std::vector<std::vector<std::int8_t>>& rows_top_first) {
  GridGeometry geometry;
  geometry.width = static_cast<int>(rows_top_first.front().size());
  geometry.height = static_cast<int>(rows_top_first.size());
  GridMap map(geometry, kUnk);
  for (int row = 0; row < geometry.height; ++row) {
    for (int x = 0; x < geometry.width; ++x) {
      map.at(x, geometry.height - 1 - row) =
          rows_top_first[static_cast<std::size_t>(row)][static_cast<std::size_t>(x)];
    }
  }
  return map;
}

GridTransform transformOf(double theta_rad, double tx, double ty) {
  GridTransform transform;
  transform.theta_rad = theta_rad;
  transform.t_cells = Eigen::Vector2d(tx, ty);
  return transform;
}

TEST(OverlapScoreTest, ClassesSplitAtFifty) {
  EXPECT_EQ(classOf(kUnk), CellClass::kNone);
  EXPECT_EQ(classOf(50), CellClass::kNone);
  EXPECT_EQ(classOf(0), CellClass::kFree);
  EXPECT_EQ(classOf(49), CellClass::kFree);
  EXPECT_EQ(classOf(51), CellClass::kOccupied);
  EXPECT_EQ(classOf(100), CellClass::kOccupied);
}

TEST(OverlapScoreTest, CountsAgreementsAndDisagreementsOfCellsKnownInBoth) {
  const GridMap from = mapOf({{kOcc, kFree, kUnk}, {kFree, 50, kOcc}});
  const GridMap to = mapOf({{kOcc, kOcc, kFree}, {kUnk, kFree, kFree}});
  const OverlapScore score = scoreOverlap(from, to, GridTransform());
  // Top row: occ/occ agree, free/occ disagree, unknown skipped. Bottom: free/unknown skipped,
  // 50 has no class, occ/free disagree.
  EXPECT_EQ(score.agreement, 1u);
  EXPECT_EQ(score.disagreement, 2u);
  EXPECT_NEAR(score.verification(), 1.0 / 3.0, 1e-12);
}

TEST(OverlapScoreTest, MovesTheFromCellsThroughTheTransform) {
  const GridMap from = mapOf({{kOcc, kFree}});
  const GridMap to = mapOf({{kFree, kFree, kOcc, kFree}});
  // Shifted by two columns, from's occupied cell lands on to's occupied cell.
  const OverlapScore shifted = scoreOverlap(from, to, transformOf(0.0, 2.0, 0.0));
  EXPECT_EQ(shifted.agreement, 2u);
  EXPECT_EQ(shifted.disagreement, 0u);
  EXPECT_EQ(scoreOverlap(from, to, GridTransform()).disagreement, 1u);
  // Turned by 180° about the origin and moved back in: columns 0, 1 land on 3, 2.
  const GridMap mirrored = mapOf({{kFree, kFree, kFree, kOcc}});
  const OverlapScore turned = scoreOverlap(from, mirrored, transformOf(kPi, 3.0, 0.0));
  EXPECT_EQ(turned.agreement, 2u);
  EXPECT_EQ(turned.disagreement, 0u);
  EXPECT_EQ(scoreOverlap(from, to, transformOf(kPi, 3.0, 0.0)).disagreement, 2u);
}

TEST(OverlapScoreTest, ARotationByAQuarterTurnCarriesColumnsOntoRows) {
  // from: one occupied cell at (2, 0). Turned by +90°: (x, y) → (2 − y, x), so (2, 0) → (2, 2),
  // and every cell of the 3 × 3 square lands on one of `to`.
  GridGeometry geometry;
  geometry.width = 3;
  geometry.height = 3;
  GridMap from(geometry, kFree);
  from.at(2, 0) = kOcc;
  GridMap to(geometry, kFree);
  to.at(2, 2) = kOcc;
  const OverlapScore score = scoreOverlap(from, to, transformOf(kPi / 2.0, 2.0, 0.0));
  EXPECT_EQ(score.disagreement, 0u);
  EXPECT_EQ(score.agreement, 9u);
  // Turned the other way, (x, y) → (y, 2 − x): the occupied cells miss each other.
  const OverlapScore wrong = scoreOverlap(from, to, transformOf(-kPi / 2.0, 0.0, 2.0));
  EXPECT_EQ(wrong.disagreement, 2u);
  EXPECT_EQ(wrong.agreement, 7u);
}

TEST(OverlapScoreTest, NoOverlapGivesZeroVerification) {
  const GridMap map = mapOf({{kOcc, kFree}});
  const OverlapScore score = scoreOverlap(map, map, transformOf(0.0, 10.0, 0.0));
  EXPECT_EQ(score.overlap(), 0u);
  EXPECT_EQ(score.verification(), 0.0);
}

TEST(OverlapScoreTest, EntropyIsZeroForACrispMergeAndOneBitForAContradiction) {
  const GridMap map = mapOf({{kOcc, kFree}, {kFree, kOcc}});
  EXPECT_NEAR(scoreOverlap(map, map, GridTransform()).entropy_bits, 0.0, 1e-12);
  const GridMap flipped = mapOf({{kFree, kOcc}, {kOcc, kFree}});
  EXPECT_NEAR(scoreOverlap(map, flipped, GridTransform()).entropy_bits, 1.0, 1e-12);
  // Two contradicting cells among 4 merged cells (the other two known in one map only).
  const GridMap half = mapOf({{kFree, kOcc}, {kUnk, kUnk}});
  const GridMap other = mapOf({{kOcc, kFree}, {kFree, kOcc}});
  EXPECT_NEAR(scoreOverlap(half, other, GridTransform()).entropy_bits, 0.5, 1e-12);
  // A cell of 50 known in one map only: one bit.
  EXPECT_NEAR(scoreOverlap(mapOf({{50}}), mapOf({{kUnk}}), GridTransform()).entropy_bits, 1.0,
              1e-12);
}

// Pixel (column, row from the top) ↔ cell (column, row from the bottom) of a map of `height`.
Eigen::Vector2d flip(const Eigen::Vector2d& p, int height) {
  return Eigen::Vector2d(p.x(), height - 1.0 - p.y());
}

TEST(ImageAffineTest, AShiftMovesRowsTheOtherWayInImageCoordinates) {
  const ImageAffine affine = gridTransformToImageAffine(transformOf(0.0, 3.0, 2.0), 10, 20);
  // pixel (c, r) → cell (c, 9 − r) → cell (c + 3, 11 − r) → pixel (c + 3, 8 + r).
  ImageAffine expected;
  expected << 1, 0, 3, 0, 1, 8;
  EXPECT_NEAR((affine - expected).norm(), 0.0, 1e-12);
}

TEST(ImageAffineTest, AgreesWithTheGridTransformOnEveryPixelAndRoundTrips) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> angle(-kPi, kPi);
  std::uniform_real_distribution<double> shift(-300.0, 300.0);
  std::uniform_int_distribution<int> height(1, 900);
  for (int trial = 0; trial < 50; ++trial) {
    const GridTransform T = transformOf(angle(rng), shift(rng), shift(rng));
    const int from_height = height(rng);
    const int to_height = height(rng);
    const ImageAffine affine = gridTransformToImageAffine(T, from_height, to_height);
    for (const Eigen::Vector2d& pixel : {Eigen::Vector2d(0, 0), Eigen::Vector2d(17, 250)}) {
      const Eigen::Vector2d expected = flip(T.apply(flip(pixel, from_height)), to_height);
      const Eigen::Vector2d mapped = affine.leftCols<2>() * pixel + affine.col(2);
      EXPECT_NEAR((mapped - expected).norm(), 0.0, 1e-9) << trial;
    }
    const GridTransform back = imageAffineToGridTransform(affine, from_height, to_height);
    EXPECT_NEAR(std::remainder(back.theta_rad - T.theta_rad, 2 * kPi), 0.0, 1e-12) << trial;
    EXPECT_NEAR((back.t_cells - T.t_cells).norm(), 0.0, 1e-9) << trial;
  }
}

TEST(ImageAffineTest, APositiveTurnInTheGridIsANegativeTurnInThePicture) {
  const ImageAffine affine = gridTransformToImageAffine(transformOf(kPi / 6, 0.0, 0.0), 5, 5);
  EXPECT_NEAR(affine(0, 0), std::cos(kPi / 6), 1e-12);
  EXPECT_NEAR(affine(0, 1), std::sin(kPi / 6), 1e-12);
  EXPECT_NEAR(affine(1, 0), -std::sin(kPi / 6), 1e-12);
}

}  // namespace
}  // namespace mrslam::fusion
