// Distance maps and ψ against brute-force references on small random grids; the random walk of
// ψ from perturbed truths on real crops.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "merge_test_maps.hpp"
#include "mrslam/fusion/merge/dissimilarity.hpp"
#include "mrslam/fusion/merge/random_walk.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

GridMap randomGrid(int width, int height, std::mt19937& random) {
  GridGeometry geometry;
  geometry.resolution_m = 0.05;
  geometry.width = width;
  geometry.height = height;
  GridMap map(geometry, GridMap::kUnknown);
  const std::int8_t values[] = {GridMap::kUnknown, 0, 10, 50, 80, 100};
  for (std::int8_t& cell : map.cells) {
    cell = values[random() % 6];
  }
  return map;
}

bool ofClass(std::int8_t value, PsiClass cell_class, const SimilaritySettings& settings) {
  return value >= 0 && (cell_class == PsiClass::kOccupied ? value >= settings.occupied_threshold
                                                          : value <= settings.free_threshold);
}

// The Manhattan distance from (x, y) to the nearest cell of the class, by looking at all.
std::int32_t bruteDistance(const GridMap& map, int x, int y, PsiClass cell_class,
                           const SimilaritySettings& settings) {
  std::int32_t best = DistanceMap::kFar;
  for (int v = 0; v < map.geometry.height; ++v) {
    for (int u = 0; u < map.geometry.width; ++u) {
      if (ofClass(map.at(u, v), cell_class, settings)) {
        best = std::min(best, std::abs(u - x) + std::abs(v - y));
      }
    }
  }
  return best;
}

// d(m1, m2, c) by brute force: every cell of class c of m1, mapped and rounded, inside m2 (and,
// with `on_known`, on a known cell of m2).
void bruteMean(const GridMap& m1, const GridMap& m2, const GridTransform& T, PsiClass c,
               const SimilaritySettings& settings, double& psi, bool& landed,
               bool on_known = false) {
  double sum = 0.0;
  long long count = 0;
  for (int y = 0; y < m1.geometry.height; ++y) {
    for (int x = 0; x < m1.geometry.width; ++x) {
      if (!ofClass(m1.at(x, y), c, settings)) {
        continue;
      }
      const Eigen::Vector2d p = T.apply(Eigen::Vector2d(x, y));
      const int u = static_cast<int>(std::lround(p.x()));
      const int v = static_cast<int>(std::lround(p.y()));
      if (!m2.geometry.contains(u, v) || (on_known && m2.at(u, v) == GridMap::kUnknown)) {
        continue;
      }
      const std::int32_t d = bruteDistance(m2, u, v, c, settings);
      if (d < DistanceMap::kFar) {
        sum += d;
        ++count;
      }
    }
  }
  landed = landed || count > 0;
  psi += count > 0 ? sum / static_cast<double>(count) : 0.0;
}

TEST(MergeDissimilarityTest, DistanceMapsEqualTheBruteForceReference) {
  std::mt19937 random(3);
  const SimilaritySettings settings;
  for (int trial = 0; trial < 20; ++trial) {
    const GridMap map = randomGrid(3 + static_cast<int>(random() % 14),
                                   3 + static_cast<int>(random() % 11), random);
    for (const PsiClass c : {PsiClass::kOccupied, PsiClass::kFree}) {
      const DistanceMap distances = distanceMap(map, c, settings);
      for (int y = 0; y < map.geometry.height; ++y) {
        for (int x = 0; x < map.geometry.width; ++x) {
          ASSERT_EQ(distances.at(x, y), bruteDistance(map, x, y, c, settings))
              << "trial " << trial << " at " << x << "," << y;
        }
      }
    }
  }
}

// ψ by brute force over both classes and both ways (over the overlap with `on_known`).
double brutePsi(const GridMap& from, const GridMap& to, const GridTransform& T,
                const SimilaritySettings& settings, bool on_known, bool& landed) {
  double psi = 0.0;
  for (const PsiClass c : {PsiClass::kOccupied, PsiClass::kFree}) {
    bruteMean(from, to, T, c, settings, psi, landed, on_known);
    bruteMean(to, from, T.inverse(), c, settings, psi, landed, on_known);
  }
  return psi;
}

// Two random grids and a random transform between them.
struct RandomPair {
  GridMap from;
  GridMap to;
  GridTransform T;
};

RandomPair randomPair(std::mt19937& random) {
  RandomPair pair{randomGrid(12, 10, random), randomGrid(14, 9, random), GridTransform{}};
  pair.T.theta_rad = std::uniform_real_distribution<double>(-0.5, 0.5)(random);
  pair.T.t_cells = Eigen::Vector2d(std::uniform_real_distribution<double>(-3.0, 3.0)(random),
                                   std::uniform_real_distribution<double>(-3.0, 3.0)(random));
  return pair;
}

TEST(MergeDissimilarityTest, PsiEqualsTheBruteForceReference) {
  std::mt19937 random(5);
  const SimilaritySettings settings;
  for (int trial = 0; trial < 20; ++trial) {
    const RandomPair pair = randomPair(random);
    bool landed = false;
    const double expected = brutePsi(pair.from, pair.to, pair.T, settings, false, landed);
    const double psi = dissimilarity(prepareDissimilarity(pair.from, settings),
                                     prepareDissimilarity(pair.to, settings), pair.T);
    ASSERT_TRUE(landed);
    EXPECT_NEAR(psi, expected, 1e-9) << "trial " << trial;
  }
}

TEST(MergeDissimilarityTest, PsiOverTheOverlapEqualsTheBruteForceReference) {
  std::mt19937 random(6);
  const SimilaritySettings settings;
  for (int trial = 0; trial < 20; ++trial) {
    const RandomPair pair = randomPair(random);
    bool landed = false;
    const double expected = brutePsi(pair.from, pair.to, pair.T, settings, true, landed);
    const DissimilarityMap from = prepareDissimilarity(pair.from, settings);
    const DissimilarityMap to = prepareDissimilarity(pair.to, settings);
    ASSERT_TRUE(landed);
    EXPECT_NEAR(overlapDissimilarity(from, to, pair.T), expected, 1e-9) << "trial " << trial;
    EXPECT_NE(overlapDissimilarity(from, to, pair.T), dissimilarity(from, to, pair.T))
        << "trial " << trial << ": a sixth of the cells are unknown";
  }
}

// Two crops of one room that agree where both are known: ψ over the overlap is 0 however much of
// either lies outside the other, while plain ψ counts the walls that only one of them saw.
TEST(MergeDissimilarityTest, PsiOverTheOverlapLeavesOutWhatTheOtherMapDidNotSee) {
  GridGeometry geometry;
  geometry.resolution_m = 0.05;
  geometry.width = 30;
  geometry.height = 20;
  GridMap left(geometry, 0);
  for (int x = 0; x < 30; ++x) {  // a corridor: walls on rows 0 and 19, a post at column 25
    left.at(x, 0) = 100;
    left.at(x, 19) = 100;
  }
  for (int y = 5; y < 15; ++y) {
    left.at(25, y) = 100;
  }
  GridMap right = left;
  for (int y = 0; y < 20; ++y) {
    for (int x = 20; x < 30; ++x) {
      left.at(x, y) = GridMap::kUnknown;  // `left` never saw the post
    }
    for (int x = 0; x < 10; ++x) {
      right.at(x, y) = GridMap::kUnknown;
    }
  }
  const SimilaritySettings settings;
  const DissimilarityMap a = prepareDissimilarity(left, settings);
  const DissimilarityMap b = prepareDissimilarity(right, settings);
  EXPECT_DOUBLE_EQ(overlapDissimilarity(a, b, GridTransform{}), 0.0);
  EXPECT_GT(dissimilarity(a, b, GridTransform{}), 0.0);
  GridTransform slid;  // the same crops one cell apart across the corridor
  slid.t_cells = Eigen::Vector2d(0.0, 1.0);
  EXPECT_GT(overlapDissimilarity(a, b, slid), 0.0);
  GridMap far_left = left;  // known on columns 0-9 only, where `right` is unknown
  for (int y = 0; y < 20; ++y) {
    for (int x = 10; x < 20; ++x) {
      far_left.at(x, y) = GridMap::kUnknown;
    }
  }
  const DissimilarityMap c = prepareDissimilarity(far_left, settings);
  EXPECT_TRUE(std::isinf(overlapDissimilarity(c, b, GridTransform{})));
  EXPECT_TRUE(std::isfinite(dissimilarity(c, b, GridTransform{})));
}

TEST(MergeDissimilarityTest, AMapAgreesWithItselfAndNotWithAShiftedSelf) {
  std::mt19937 random(9);
  const GridMap map = randomGrid(30, 20, random);
  const DissimilarityMap prepared = prepareDissimilarity(map, SimilaritySettings{});
  EXPECT_DOUBLE_EQ(dissimilarity(prepared, prepared, GridTransform{}), 0.0);
  GridTransform shifted;
  shifted.t_cells = Eigen::Vector2d(2.0, 1.0);
  EXPECT_GT(dissimilarity(prepared, prepared, shifted), 0.0);
  GridTransform away;
  away.t_cells = Eigen::Vector2d(500.0, 0.0);  // nothing lands inside
  EXPECT_TRUE(std::isinf(dissimilarity(prepared, prepared, away)));
}

TEST(MergeRandomWalkTest, ConvergesFromPerturbedTruthsOnRealCrops) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const GridMap map = merge_test::loadMap(test::sharedDataPath("maps/freiburg-intel.pgm"));
  std::mt19937 cases(21);
  std::mt19937 perturb(22);
  std::uniform_real_distribution<double> shift(-3.0, 3.0);
  std::uniform_real_distribution<double> turn(-3.0 * M_PI / 180.0, 3.0 * M_PI / 180.0);
  const SimilaritySettings settings;
  int converged = 0;
  int trials = 0;
  while (trials < 50) {
    const merge_test::KnownCase known = merge_test::randomCase(map, 160, 0.5, 1.01, cases);
    if (known.overlap == 0.0) {
      continue;
    }
    ++trials;
    GridTransform start = known.T_to_from;
    start.theta_rad += turn(perturb);
    start.t_cells += Eigen::Vector2d(shift(perturb), shift(perturb));
    RandomWalkSettings walk;
    walk.seed = static_cast<std::uint64_t>(trials);
    const RandomWalkResult result =
        randomWalk(prepareDissimilarity(known.from, settings),
                   prepareDissimilarity(known.to, settings), start, walk);
    EXPECT_LE(result.psi, result.start_psi);
    converged += merge_test::isSuccess(merge_test::poseError(result.T_to_from, known)) ? 1 : 0;
  }
  std::printf("random walk: %d of %d perturbed truths back within 2 cells and 1 deg\n", converged,
              trials);
  EXPECT_GE(converged, 45);
}

}  // namespace
}  // namespace mrslam::fusion
