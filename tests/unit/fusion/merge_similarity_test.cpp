#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "merge_test_maps.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {
namespace {

double binaryEntropy(double p) {
  return -p * std::log2(p) - (1.0 - p) * std::log2(1.0 - p);
}

GridMap mapOf(int width, int height, std::int8_t fill = GridMap::kUnknown) {
  GridGeometry geometry;
  geometry.width = width;
  geometry.height = height;
  return GridMap(geometry, fill);
}

GridMap shiftedMap(const GridMap& map, int dx, int dy) {
  GridMap shifted = mapOf(map.geometry.width, map.geometry.height);
  for (int y = 0; y < map.geometry.height; ++y) {
    for (int x = 0; x < map.geometry.width; ++x) {
      if (shifted.geometry.contains(x + dx, y + dy)) {
        shifted.at(x + dx, y + dy) = map.at(x, y);
      }
    }
  }
  return shifted;
}

TEST(MergeSimilarityTest, TablesCompareClassesAndFuseEntropy) {
  const ComparisonTables tables{SimilaritySettings{}};
  EXPECT_EQ(tables.similarity(0, 10), 1);    // free, free
  EXPECT_EQ(tables.similarity(100, 90), 1);  // occupied, occupied
  EXPECT_EQ(tables.similarity(0, 100), -1);  // free, occupied
  EXPECT_EQ(tables.similarity(50, 0), 0);    // uncertain counts as unknown
  EXPECT_EQ(tables.similarity(kUnknownCode, 0), 0);
  EXPECT_NEAR(tables.cellEntropy(0), binaryEntropy(0.05), 1e-12);  // clamped to c = 0.95
  EXPECT_NEAR(tables.cellEntropy(50), 1.0, 1e-12);
  EXPECT_EQ(tables.cellEntropy(kUnknownCode), 0.0);
  EXPECT_LT(tables.entropyChange(0, 0), 0.0);    // agreeing cells become surer
  EXPECT_GT(tables.entropyChange(0, 100), 0.0);  // contradicting cells become 0.5
  EXPECT_NEAR(tables.entropyChange(0, 100), 1.0 - 2.0 * binaryEntropy(0.05), 1e-6);
  EXPECT_EQ(tables.entropyChange(kUnknownCode, 100), 0.0);
}

TEST(MergeSimilarityTest, VerificationIndexAndEntropyOfAHandCase) {
  GridMap from = mapOf(3, 1);
  from.at(0, 0) = GridMap::kFree;
  from.at(1, 0) = GridMap::kOccupied;
  GridMap to = mapOf(3, 1);
  to.at(0, 0) = GridMap::kFree;
  to.at(1, 0) = GridMap::kFree;
  to.at(2, 0) = GridMap::kOccupied;
  const ComparisonTables tables{SimilaritySettings{}};
  const Agreement sums =
      compareAt(knownCells(from, tables), codeImage(to, 1, tables), GridTransform{}, tables);
  EXPECT_EQ(sums.agreement, 1);
  EXPECT_EQ(sums.disagreement, 1);
  EXPECT_EQ(sums.similarity(), 0);
  EXPECT_DOUBLE_EQ(verificationIndex(sums), 0.5);
  const double h = binaryEntropy(0.05);
  EXPECT_NEAR(mapEntropy(from, tables), 2.0 * h, 1e-12);
  EXPECT_NEAR(mapEntropy(to, tables), 3.0 * h, 1e-12);
  const double fused_free = binaryEntropy(1.0 / (1.0 + 19.0 * 19.0));  // odds 1:19 twice
  // Merged: the agreeing free cell fused, the contradicting one at 0.5, to's last cell as it is.
  EXPECT_NEAR(mergedEntropy(mapEntropy(from, tables), mapEntropy(to, tables), sums),
              fused_free + 1.0 + h, 1e-6);
  EXPECT_EQ(verificationIndex(Agreement{}), 0.0);
}

TEST(MergeSimilarityTest, ExhaustiveSearchFindsAKnownShift) {
  const GridMap from = merge_test::handBuiltRooms();
  const GridMap to = shiftedMap(from, 3, -2);
  const ComparisonTables tables{SimilaritySettings{}};
  const TranslationSearch search = searchTranslation(
      knownCells(from, tables), codeImage(to, 7, tables), GridTransform{}, 5, tables);
  EXPECT_NEAR((search.best_similarity.t_cells - Eigen::Vector2d(3.0, -2.0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(search.at_best_similarity.disagreement, 0);
  EXPECT_DOUBLE_EQ(verificationIndex(search.at_best_similarity), 1.0);
  EXPECT_NEAR((search.least_entropy.t_cells - Eigen::Vector2d(3.0, -2.0)).norm(), 0.0, 1e-12);
  EXPECT_LT(search.runner_up_similarity, 0.9 * search.at_best_similarity.similarity());
}

TEST(MergeSimilarityTest, ACorridorSeenAlongItsLengthLeavesTheShiftOpen) {
  GridMap corridor = mapOf(120, 20, GridMap::kFree);
  for (int x = 0; x < 120; ++x) {
    corridor.at(x, 2) = corridor.at(x, 17) = GridMap::kOccupied;
  }
  const ComparisonTables tables{SimilaritySettings{}};
  const TranslationSearch search =
      searchTranslation(knownCells(corridor, tables), codeImage(corridor, 8, tables),
                        GridTransform{}, 6, tables, false);
  EXPECT_GT(search.runner_up_similarity, 0.9 * search.at_best_similarity.similarity());
}

TEST(MergeSimilarityTest, StructureAgreementCountsWallsLandingNearWalls) {
  GridMap from = mapOf(10, 10, GridMap::kFree);
  GridMap to = mapOf(10, 10, GridMap::kFree);
  from.at(2, 2) = from.at(5, 5) = from.at(8, 8) = GridMap::kOccupied;
  to.at(3, 2) = GridMap::kOccupied;  // one cell beside (2, 2): near
  to.at(5, 5) = GridMap::kOccupied;  // on (5, 5): near
  to.at(8, 8) = GridMap::kUnknown;   // (8, 8) lands on unknown: not counted
  const ComparisonTables tables{SimilaritySettings{}};
  StructureAgreement sums = structureAgreement(knownCells(from, tables), codeImage(to, 1, tables),
                                               GridTransform{}, tables);
  EXPECT_EQ(sums.near, 2);
  EXPECT_EQ(sums.far, 0);
  to.at(5, 5) = GridMap::kFree;
  sums = structureAgreement(knownCells(from, tables), codeImage(to, 1, tables), GridTransform{},
                            tables);
  EXPECT_EQ(sums.near, 1);
  EXPECT_EQ(sums.far, 1);
  EXPECT_DOUBLE_EQ(sums.index(), 0.5);
}

TEST(MergeSimilarityTest, StructureAgreementSetsApartWallsOnTheOtherMapsFrontier) {
  // `to` saw free space up to column 8 and nothing beyond: a wall there it never marked.
  GridMap from = mapOf(12, 12, GridMap::kFree);
  GridMap to = mapOf(12, 12, GridMap::kFree);
  for (int y = 0; y < 12; ++y) {
    for (int x = 9; x < 12; ++x) {
      to.at(x, y) = GridMap::kUnknown;
    }
  }
  from.at(2, 5) = from.at(5, 5) = from.at(8, 5) = GridMap::kOccupied;
  to.at(2, 6) = GridMap::kOccupied;  // beside (2, 5): near
  // (5, 5) lands on open floor, (8, 5) on the free cell next to the unknown column 9.
  const ComparisonTables tables{SimilaritySettings{}};
  const StructureAgreement sums = structureAgreement(
      knownCells(from, tables), codeImage(to, 1, tables), GridTransform{}, tables);
  EXPECT_EQ(sums.near, 1);
  EXPECT_EQ(sums.far, 2);
  EXPECT_EQ(sums.frontier, 1);
  EXPECT_DOUBLE_EQ(sums.index(), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(sums.indexOffFrontier(), 0.5);
  // Beyond the map's edge is unknown too: a wall landing on the first column is on the frontier.
  GridMap edge_wall = mapOf(12, 12, GridMap::kFree);
  edge_wall.at(0, 3) = GridMap::kOccupied;
  const StructureAgreement at_edge = structureAgreement(
      knownCells(edge_wall, tables), codeImage(to, 1, tables), GridTransform{}, tables);
  EXPECT_EQ(at_edge.far, 1);
  EXPECT_EQ(at_edge.frontier, 1);
  EXPECT_DOUBLE_EQ(at_edge.indexOffFrontier(), 0.0);
}

TEST(MergeSimilarityTest, SampleTakesEvenShareOfEachClass) {
  const GridMap map = merge_test::handBuiltRooms();
  const ComparisonTables tables{SimilaritySettings{}};
  const std::vector<CellSample> known = knownCells(map, tables);
  ASSERT_EQ(known.size(), map.cells.size());
  const std::vector<CellSample> sample = sampleKnownCells(known, tables, 50, 200);
  long long occupied = 0;
  for (const CellSample& cell : sample) {
    occupied += tables.isOccupied(cell.code) ? 1 : 0;
  }
  EXPECT_NEAR(static_cast<double>(occupied), 50.0, 1.0);
  EXPECT_NEAR(static_cast<double>(sample.size() - static_cast<std::size_t>(occupied)), 200.0, 1.0);
}

// Each class is taken on its own even grid: the j-th pick of a class is its cell number
// ceil(j · step), step = (its cells) / (its count), whatever the other class does between them.
TEST(MergeSimilarityTest, SampleTakesEachClassAtItsOwnEvenSteps) {
  GridMap map = mapOf(30, 1, GridMap::kFree);
  for (const int x : {1, 2, 5, 9, 10, 11, 17, 23, 28}) {  // 9 occupied, 21 free
    map.at(x, 0) = GridMap::kOccupied;
  }
  const ComparisonTables tables{SimilaritySettings{}};
  const std::vector<CellSample> sample = sampleKnownCells(knownCells(map, tables), tables, 4, 6);
  std::vector<int> occupied_columns;
  std::vector<int> free_columns;
  for (const CellSample& cell : sample) {
    (tables.isOccupied(cell.code) ? occupied_columns : free_columns).push_back(cell.x);
  }
  // Occupied: step 9 / 4 = 2.25, cells 0, 3, 5, 7 of the nine (columns 1, 9, 11, 23).
  EXPECT_EQ(occupied_columns, (std::vector<int>{1, 9, 11, 23}));
  // Free: step 21 / 6 = 3.5, cells 0, 4, 7, 11, 14, 18 of the 21 free columns
  // 0 3 4 6 7 8 12 13 14 15 16 18 19 20 21 22 24 25 26 27 29.
  EXPECT_EQ(free_columns, (std::vector<int>{0, 7, 13, 18, 21, 26}));
  // In the map's order, the classes interleaved.
  for (std::size_t i = 1; i < sample.size(); ++i) {
    EXPECT_LT(sample[i - 1].x, sample[i].x);
  }
  // Asking for more cells than a class has takes all of it.
  EXPECT_EQ(sampleKnownCells(knownCells(map, tables), tables, 100, 100).size(), 30u);
}

// The sampler of several samples from one list picks what a walk over every cell picks: a cell
// of a class is taken when the class's cells seen before it reach the running share, which then
// grows by one step.
std::vector<CellSample> walkedSample(const std::vector<CellSample>& known,
                                     const ComparisonTables& tables, int occupied_count,
                                     int free_count) {
  double cells[2] = {0.0, 0.0};  // [0] free, [1] occupied
  for (const CellSample& cell : known) {
    cells[tables.isOccupied(cell.code) ? 1 : 0] += 1.0;
  }
  const double step[2] = {std::max(1.0, cells[0] / std::max(1, free_count)),
                          std::max(1.0, cells[1] / std::max(1, occupied_count))};
  double seen[2] = {0.0, 0.0};
  double share[2] = {0.0, 0.0};
  std::vector<CellSample> sample;
  for (const CellSample& cell : known) {
    const int kind = tables.isOccupied(cell.code) ? 1 : 0;
    if (seen[kind] >= share[kind]) {
      sample.push_back(cell);
      share[kind] += step[kind];
    }
    seen[kind] += 1.0;
  }
  return sample;
}

TEST(MergeSimilarityTest, SamplerPicksWhatAWalkOverEveryCellPicks) {
  const ComparisonTables tables{SimilaritySettings{}};
  std::mt19937 random(11);
  for (const double occupied_share : {0.0, 0.03, 0.2, 0.5, 1.0}) {
    GridMap map = mapOf(97, 61);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    for (std::int8_t& cell : map.cells) {
      const double known = unit(random);
      cell = known < 0.3 ? GridMap::kUnknown
                         : (unit(random) < occupied_share ? GridMap::kOccupied : GridMap::kFree);
    }
    const std::vector<CellSample> known = knownCells(map, tables);
    const KnownCellSampler sampler(known, tables);
    for (const auto& [occupied, free] : std::vector<std::pair<int, int>>{
             {0, 0}, {1, 1}, {7, 300}, {150, 0}, {333, 1234}, {4000, 4000}, {-3, 5}}) {
      const std::vector<CellSample> expected = walkedSample(known, tables, occupied, free);
      const std::vector<CellSample> sampled = sampler.sample(occupied, free);
      ASSERT_EQ(sampled.size(), expected.size())
          << "share " << occupied_share << ", counts " << occupied << " and " << free;
      for (std::size_t i = 0; i < expected.size(); ++i) {
        EXPECT_EQ(sampled[i].x, expected[i].x) << i;
        EXPECT_EQ(sampled[i].y, expected[i].y) << i;
        EXPECT_EQ(sampled[i].code, expected[i].code) << i;
      }
      EXPECT_FALSE(expected.empty() && !known.empty()) << "a class always gives its first cell";
    }
  }
}

TEST(MergeSimilarityTest, RotatedSamplesLandOnTheirRoundedCells) {
  GridMap from = mapOf(5, 5, GridMap::kFree);
  from.at(4, 0) = GridMap::kOccupied;
  GridMap to = mapOf(5, 5, GridMap::kFree);
  to.at(0, 4) = GridMap::kOccupied;  // (4, 0) turned by 90° about the origin is (0, 4)
  GridTransform T;
  T.theta_rad = M_PI / 2.0;
  T.t_cells = Eigen::Vector2d(0.0, 0.0);
  const ComparisonTables tables{SimilaritySettings{}};
  const Agreement sums = compareAt(knownCells(from, tables), codeImage(to, 1, tables), T, tables);
  EXPECT_EQ(sums.disagreement, 0);
  EXPECT_EQ(sums.agreement, 5);  // only the column x = 0 of `from` lands inside `to`
}

// compareAt against its definition, one sample at a time: each known cell of `from` lands on the
// cell floor(T p + 0.5) of `to`; cells known in both count as agreeing when their classes are
// equal and disagreeing otherwise, and add their entropy change. Random maps, turned and shifted
// so that some cells land off `to` and on its padding.
TEST(MergeSimilarityTest, CompareAtEqualsOneSampleAtATime) {
  std::mt19937 random(11);
  std::uniform_int_distribution<int> value(-1, 100);
  GridMap from = mapOf(37, 29);
  GridMap to = mapOf(41, 33);
  for (GridMap* map : {&from, &to}) {
    for (int y = 0; y < map->geometry.height; ++y) {
      for (int x = 0; x < map->geometry.width; ++x) {
        map->at(x, y) = static_cast<std::int8_t>(value(random));
      }
    }
  }
  const ComparisonTables tables{SimilaritySettings{}};
  const std::vector<CellSample> cells = knownCells(from, tables);
  std::uniform_real_distribution<double> turn(-M_PI, M_PI);
  std::uniform_real_distribution<double> shift(-12.0, 12.0);
  for (int trial = 0; trial < 20; ++trial) {
    GridTransform T;
    T.theta_rad = turn(random);
    T.t_cells = Eigen::Vector2d(20.0 + shift(random), 16.0 + shift(random));
    Agreement expected;
    for (const CellSample& cell : cells) {
      const Eigen::Vector2d landed = T.apply(Eigen::Vector2d(cell.x, cell.y));
      const int x = static_cast<int>(std::floor(landed.x() + 0.5));
      const int y = static_cast<int>(std::floor(landed.y() + 0.5));
      if (x < 0 || y < 0 || x >= to.geometry.width || y >= to.geometry.height || to.at(x, y) < 0) {
        continue;
      }
      const auto other = static_cast<std::uint8_t>(to.at(x, y));
      const int from_class = tables.classOf(cell.code);
      const int to_class = tables.classOf(other);
      if (from_class != 0 && to_class != 0) {
        (from_class == to_class ? expected.agreement : expected.disagreement) += 1;
      }
      expected.entropy_change += tables.entropyChange(cell.code, other);
    }
    for (const int pad : {1, 5}) {
      const Agreement sums = compareAt(cells, codeImage(to, pad, tables), T, tables);
      EXPECT_EQ(sums.agreement, expected.agreement) << "trial " << trial << ", pad " << pad;
      EXPECT_EQ(sums.disagreement, expected.disagreement) << "trial " << trial;
      EXPECT_NEAR(sums.entropy_change, expected.entropy_change, 1e-9) << "trial " << trial;
      const Agreement counts = compareAt(cells, codeImage(to, pad, tables), T, tables, false);
      EXPECT_EQ(counts.agreement, expected.agreement);
      EXPECT_EQ(counts.disagreement, expected.disagreement);
      EXPECT_EQ(counts.entropy_change, 0.0);
    }
  }
}

// The early-stopping test of the disagreement rate answers as compareAt's counts do, on maps
// large enough to stop early (rooms of walls and floor), at the truth (rate 0), near it and far
// from it, for bars below, at and above each rate.
TEST(MergeSimilarityTest, DisagreementRateExceedsAnswersAsTheFullCountDoes) {
  std::mt19937 random(5);
  GridMap from = mapOf(160, 140, GridMap::kFree);
  std::uniform_int_distribution<int> corner(0, 150);
  std::uniform_int_distribution<int> side(3, 40);
  for (int room = 0; room < 40; ++room) {
    const int x0 = corner(random);
    const int y0 = corner(random);
    const int w = side(random);
    const int h = side(random);
    for (int y = y0; y < std::min(140, y0 + h); ++y) {
      for (int x = x0; x < std::min(160, x0 + w); ++x) {
        const bool wall = x == x0 || y == y0 || x == x0 + w - 1 || y == y0 + h - 1;
        from.at(x, y) = wall ? 100 : (room % 7 == 0 ? GridMap::kUnknown : GridMap::kFree);
      }
    }
  }
  const GridMap to = shiftedMap(from, 9, -6);
  const ComparisonTables tables{SimilaritySettings{}};
  const std::vector<CellSample> cells = knownCells(from, tables);
  ASSERT_GT(cells.size(), 10000u);
  const CodeImage codes = codeImage(to, 1, tables);
  std::uniform_real_distribution<double> turn(-0.2, 0.2);
  std::uniform_real_distribution<double> shift(-15.0, 15.0);
  int exceeded = 0;
  int kept = 0;
  for (int trial = 0; trial < 30; ++trial) {
    GridTransform T;
    T.t_cells = Eigen::Vector2d(9.0, -6.0);
    if (trial > 0) {
      T.theta_rad = trial < 10 ? 0.01 * turn(random) : turn(random);
      T.t_cells +=
          trial < 10 ? Eigen::Vector2d(1.0, 0.0) : Eigen::Vector2d(shift(random), shift(random));
    }
    const double rate = 1.0 - verificationIndex(compareAt(cells, codes, T, tables, false));
    if (trial == 0) {
      EXPECT_EQ(rate, 0.0) << "the truth";
    }
    for (const double bar : {0.0, 0.5 * rate, rate, 1.5 * rate, 0.02, 0.1, 0.3, 0.6, 1.0}) {
      const bool expected = rate > bar;
      EXPECT_EQ(disagreementRateExceeds(cells, codes, T, tables, bar), expected)
          << "trial " << trial << ": rate " << rate << ", bar " << bar;
      (expected ? exceeded : kept) += 1;
    }
  }
  EXPECT_GT(exceeded, 50);
  EXPECT_GT(kept, 50);
  const GridMap elsewhere = mapOf(40, 40, GridMap::kFree);
  EXPECT_TRUE(disagreementRateExceeds(cells, codeImage(elsewhere, 1, tables),
                                      GridTransform{0.0, Eigen::Vector2d(500.0, 500.0)}, tables,
                                      0.99))
      << "no overlap: a rate of 1";
}

// The search's rounding is std::lround's (halves away from zero), bit for bit, without the call.
TEST(MergeSimilarityTest, RoundToIntRoundsAsLround) {
  std::vector<double> values = {0.0,
                                -0.0,
                                0.5,
                                -0.5,
                                1.5,
                                -1.5,
                                2.5,
                                -2.5,
                                0.49999999999999994,
                                -0.49999999999999994,
                                1e9 + 0.5,
                                -1e9 - 0.5};
  for (int k = -1000; k <= 1000; ++k) {
    const double half = k + 0.5;
    values.insert(values.end(), {half, std::nextafter(half, -1e18), std::nextafter(half, 1e18),
                                 static_cast<double>(k)});
  }
  std::mt19937 random(3);
  std::uniform_real_distribution<double> any(-5e8, 5e8);
  for (int i = 0; i < 100000; ++i) {
    values.push_back(any(random));
    values.push_back(any(random) * 1e-6);
  }
  for (const double v : values) {
    ASSERT_EQ(roundToInt(v), std::lround(v)) << std::hexfloat << v;
  }
  EXPECT_EQ(roundToInt(std::nan("")), std::numeric_limits<int>::min()) << "off every grid";
  EXPECT_EQ(roundToInt(3e9), std::numeric_limits<int>::min());
  EXPECT_EQ(roundToInt(-3e9), std::numeric_limits<int>::min());
}

}  // namespace
}  // namespace mrslam::fusion
