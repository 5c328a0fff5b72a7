#include "mrslam/common/occupancy_grid.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <set>
#include <stdexcept>
#include <utility>

namespace mrslam {
namespace {

using Cell = std::pair<int, int>;  ///< lattice cell (i, j) of the map frame
using CellSet = std::set<Cell>;

constexpr double kRes = 0.05;

/// A map-frame point given in lattice units (cells).
Eigen::Vector2d at(double i, double j) {
  return Eigen::Vector2d(i * kRes, j * kRes);
}

/// The lattice cells the grid has observed.
CellSet knownCells(const OccupancyGrid& grid) {
  CellSet cells;
  const GridGeometry& g = grid.geometry();
  for (int cy = 0; cy < g.height; ++cy) {
    for (int cx = 0; cx < g.width; ++cx) {
      if (grid.isKnown(cx, cy)) {
        cells.emplace(cx + grid.originCell().x(), cy + grid.originCell().y());
      }
    }
  }
  return cells;
}

CellSet rayCells(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  OccupancyGrid grid(kRes);
  grid.insertRay(from, to, true);
  return knownCells(grid);
}

float logOddsAt(const OccupancyGrid& grid, const Eigen::Vector2d& point) {
  const Eigen::Vector2i cell = grid.cellOf(point);
  return grid.logOdds(cell.x(), cell.y());
}

/// Length (in cells) of the part of the segment a-b (lattice units) inside cell (i, j).
double lengthInCell(const Eigen::Vector2d& a, const Eigen::Vector2d& b, int i, int j) {
  double t0 = 0.0;
  double t1 = 1.0;  // Liang-Barsky: clip a + t (b - a) to [i, i + 1] x [j, j + 1]
  const Eigen::Vector2d d = b - a;
  const double box_low[2] = {static_cast<double>(i), static_cast<double>(j)};
  for (int axis = 0; axis < 2; ++axis) {
    if (d[axis] == 0.0) {
      if (a[axis] < box_low[axis] || a[axis] > box_low[axis] + 1.0) {
        return 0.0;
      }
      continue;
    }
    double ta = (box_low[axis] - a[axis]) / d[axis];
    double tb = (box_low[axis] + 1.0 - a[axis]) / d[axis];
    if (ta > tb) {
      std::swap(ta, tb);
    }
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  return std::max(0.0, t1 - t0) * d.norm();
}

Cell floorCell(const Eigen::Vector2d& p) {
  return {static_cast<int>(std::floor(p.x())), static_cast<int>(std::floor(p.y()))};
}

/// Brute force: the cells in which the segment a-b (lattice units) runs longer than `min_length`,
/// plus the cells of its two end points.
CellSet bruteForceCells(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double min_length) {
  CellSet cells{floorCell(a), floorCell(b)};
  const Cell low = floorCell(a.cwiseMin(b));
  const Cell high = floorCell(a.cwiseMax(b));
  for (int i = low.first; i <= high.first; ++i) {
    for (int j = low.second; j <= high.second; ++j) {
      if (lengthInCell(a, b, i, j) > min_length) {
        cells.emplace(i, j);
      }
    }
  }
  return cells;
}

double pointToBox(const Eigen::Vector2d& p, int i, int j) {
  return std::hypot(std::max({i - p.x(), 0.0, p.x() - (i + 1)}),
                    std::max({j - p.y(), 0.0, p.y() - (j + 1)}));
}

double pointToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                      const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const double t =
      d.squaredNorm() > 0.0 ? std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
  return (a + t * d - p).norm();
}

/// Distance (lattice units) from the segment a-b to cell (i, j).
double distanceToCell(const Eigen::Vector2d& a, const Eigen::Vector2d& b, int i, int j) {
  if (lengthInCell(a, b, i, j) > 0.0) {
    return 0.0;
  }
  // Apart, the closest points are an end of the segment or a corner of the cell.
  double best = std::min(pointToBox(a, i, j), pointToBox(b, i, j));
  for (const int ci : {i, i + 1}) {
    for (const int cj : {j, j + 1}) {
      best = std::min(best, pointToSegment(Eigen::Vector2d(ci, cj), a, b));
    }
  }
  return best;
}

/// Every crossed cell holds exactly one miss; the end cell holds `end_value`.
void expectOneUpdatePerCell(const OccupancyGrid& grid, const CellSet& cells, const Cell& end,
                            float end_value) {
  for (const Cell& cell : cells) {
    const int cx = cell.first - grid.originCell().x();
    const int cy = cell.second - grid.originCell().y();
    EXPECT_EQ(grid.logOdds(cx, cy), cell == end ? end_value : grid.params().miss);
  }
}

TEST(OccupancyGridRayTest, HorizontalRayCrossesEveryCellOfItsRow) {
  EXPECT_EQ(rayCells(at(0.5, 0.5), at(5.5, 0.5)),
            (CellSet{{0, 0}, {1, 0}, {2, 0}, {3, 0}, {4, 0}, {5, 0}}));
  EXPECT_EQ(rayCells(at(2.5, 2.5), at(-2.5, 2.5)),
            (CellSet{{-3, 2}, {-2, 2}, {-1, 2}, {0, 2}, {1, 2}, {2, 2}}));
}

TEST(OccupancyGridRayTest, VerticalRayCrossesEveryCellOfItsColumn) {
  EXPECT_EQ(rayCells(at(1.5, -3.5), at(1.5, 2.2)),
            (CellSet{{1, -4}, {1, -3}, {1, -2}, {1, -1}, {1, 0}, {1, 1}, {1, 2}}));
  EXPECT_EQ(rayCells(at(-0.3, 1.9), at(-0.3, -1.1)),
            (CellSet{{-1, 1}, {-1, 0}, {-1, -1}, {-1, -2}}));
}

TEST(OccupancyGridRayTest, DiagonalThroughCornersStepsDiagonally) {
  // A 45° ray through the cell corners only touches the side cells at a point.
  EXPECT_EQ(rayCells(at(0.5, 0.5), at(3.5, 3.5)), (CellSet{{0, 0}, {1, 1}, {2, 2}, {3, 3}}));
  EXPECT_EQ(rayCells(at(3.5, -0.5), at(0.5, -3.5)), (CellSet{{3, -1}, {2, -2}, {1, -3}, {0, -4}}));
}

TEST(OccupancyGridRayTest, SlopedRayCrossesTheExactCells) {
  // Slope 2/3: x boundaries at t = 1/6, 1/2, 5/6; y boundaries at t = 1/4, 3/4.
  EXPECT_EQ(rayCells(at(0.5, 0.5), at(3.5, 2.5)),
            (CellSet{{0, 0}, {1, 0}, {1, 1}, {2, 1}, {2, 2}, {3, 2}}));
}

TEST(OccupancyGridRayTest, ShallowRayChangesRowOnce) {
  // Slope 1/10: the row changes at x = 5.5, inside column 5.
  CellSet expected;
  for (int i = 0; i <= 5; ++i) {
    expected.emplace(i, 0);
  }
  for (int i = 5; i <= 10; ++i) {
    expected.emplace(i, 1);
  }
  EXPECT_EQ(rayCells(at(0.5, 0.5), at(10.5, 1.5)), expected);
  // The same ray walked backwards crosses the same cells.
  EXPECT_EQ(rayCells(at(10.5, 1.5), at(0.5, 0.5)), expected);
}

TEST(OccupancyGridRayTest, RandomRaysOnTheSubcellLatticeMatchBruteForceExactly) {
  // End points on the 1/1024-cell lattice and a power-of-two resolution: the traversal is exact,
  // so it must give exactly the cells the segment runs through over a positive length.
  constexpr double kBinaryRes = 0.25;
  std::mt19937 random(42);
  std::uniform_int_distribution<int> subcell(-40 * 1024, 40 * 1024);
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Vector2d a(subcell(random) / 1024.0, subcell(random) / 1024.0);
    const Eigen::Vector2d b = a + Eigen::Vector2d(subcell(random), subcell(random)) / 2048.0;
    OccupancyGrid grid(kBinaryRes);
    grid.insertRay(a * kBinaryRes, b * kBinaryRes, true);
    const CellSet cells = knownCells(grid);
    ASSERT_EQ(cells, bruteForceCells(a, b, 1e-12)) << "trial " << trial;
    expectOneUpdatePerCell(grid, cells, floorCell(b), grid.params().hit);
  }
}

TEST(OccupancyGridRayTest, RandomRaysAtRobotResolutionFollowTheSegment) {
  // Arbitrary end points: every cell the segment really runs through is crossed, and every
  // crossed cell lies on the segment (up to the 1/1024-cell rounding of the end points).
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-4.0, 4.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Eigen::Vector2d from(coordinate(random), coordinate(random));
    const Eigen::Vector2d to = from + Eigen::Vector2d(coordinate(random), coordinate(random)) * 0.2;
    OccupancyGrid grid(kRes);
    grid.insertRay(from, to, false);
    const CellSet cells = knownCells(grid);
    const Eigen::Vector2d a = from / kRes;
    const Eigen::Vector2d b = to / kRes;
    for (const Cell& cell : bruteForceCells(a, b, 1e-2)) {
      ASSERT_EQ(cells.count(cell), 1u) << "trial " << trial << " misses a crossed cell";
    }
    for (const Cell& cell : cells) {
      ASSERT_LT(distanceToCell(a, b, cell.first, cell.second), 2e-3) << "trial " << trial;
    }
    EXPECT_EQ(cells.count(floorCell(a)), 1u);
    EXPECT_EQ(cells.count(floorCell(b)), 1u);
    expectOneUpdatePerCell(grid, cells, floorCell(b), grid.params().miss);
  }
}

TEST(OccupancyGridRayTest, EndCellGetsHitOrMissNeverBoth) {
  const LogOddsParams params;
  OccupancyGrid hit_grid(kRes);
  hit_grid.insertRay(at(0.5, 0.5), at(4.5, 0.5), true);
  EXPECT_FLOAT_EQ(logOddsAt(hit_grid, at(4.5, 0.5)), params.hit);
  EXPECT_FLOAT_EQ(logOddsAt(hit_grid, at(3.5, 0.5)), params.miss);
  EXPECT_FLOAT_EQ(logOddsAt(hit_grid, at(0.5, 0.5)), params.miss);

  OccupancyGrid miss_grid(kRes);
  miss_grid.insertRay(at(0.5, 0.5), at(4.5, 0.5), false);
  EXPECT_FLOAT_EQ(logOddsAt(miss_grid, at(4.5, 0.5)), params.miss);
  EXPECT_EQ(miss_grid.knownCellCount(), 5u);

  // A ray inside one cell: that cell only gets the hit.
  OccupancyGrid short_grid(kRes);
  short_grid.insertRay(at(2.1, 2.1), at(2.8, 2.9), true);
  EXPECT_EQ(short_grid.knownCellCount(), 1u);
  EXPECT_FLOAT_EQ(logOddsAt(short_grid, at(2.5, 2.5)), params.hit);
}

TEST(OccupancyGridRayTest, NonFiniteRayIsIgnored) {
  OccupancyGrid grid(kRes);
  grid.insertRay(at(0.5, 0.5), Eigen::Vector2d(std::numeric_limits<double>::quiet_NaN(), 1.0),
                 true);
  grid.insertRay(Eigen::Vector2d(std::numeric_limits<double>::infinity(), 0.0), at(0.5, 0.5), true);
  EXPECT_EQ(grid.knownCellCount(), 0u);
}

TEST(OccupancyGridTest, ValuesClampAfterManyHitsAndMisses) {
  LogOddsParams params;
  params.clamp_min = -2.0f;
  params.clamp_max = 3.0f;
  OccupancyGrid grid(kRes, params);
  for (int i = 0; i < 100; ++i) {
    grid.insertRay(at(0.5, 0.5), at(3.5, 0.5), true);
  }
  EXPECT_FLOAT_EQ(logOddsAt(grid, at(3.5, 0.5)), 3.0f);
  EXPECT_FLOAT_EQ(logOddsAt(grid, at(1.5, 0.5)), -2.0f);
  // Clamped cells still respond at once to the other kind of evidence.
  grid.insertRay(at(0.5, 0.5), at(3.5, 0.5), false);
  EXPECT_FLOAT_EQ(logOddsAt(grid, at(3.5, 0.5)), 3.0f + params.miss);
  const Eigen::Vector2i cell = grid.cellOf(at(1.5, 0.5));
  grid.addLogOdds(cell.x(), cell.y(), -50.0f);
  EXPECT_FLOAT_EQ(grid.logOdds(cell.x(), cell.y()), -2.0f);
  grid.addLogOdds(cell.x(), cell.y(), 50.0f);
  EXPECT_FLOAT_EQ(grid.logOdds(cell.x(), cell.y()), 3.0f);
}

TEST(OccupancyGridTest, Int8ConversionValues) {
  OccupancyGrid grid(kRes);
  grid.ensureContains(at(0, 0), at(5, 0));
  const Eigen::Vector2i c = grid.cellOf(at(0.5, 0.5));
  EXPECT_EQ(grid.occupancy(c.x(), c.y()), GridMap::kUnknown);
  EXPECT_FLOAT_EQ(grid.logOdds(c.x(), c.y()), 0.0f);
  grid.addLogOdds(c.x(), c.y(), 0.0f);  // observed, log-odds 0
  EXPECT_EQ(grid.occupancy(c.x(), c.y()), 50);
  grid.addLogOdds(c.x() + 1, c.y(), grid.params().hit);  // p = 0.7006
  EXPECT_EQ(grid.occupancy(c.x() + 1, c.y()), 70);
  grid.addLogOdds(c.x() + 2, c.y(), grid.params().miss);  // p = 0.4013
  EXPECT_EQ(grid.occupancy(c.x() + 2, c.y()), 40);
  grid.addLogOdds(c.x() + 3, c.y(), 100.0f);  // clamp_max 4: p = 0.982
  EXPECT_EQ(grid.occupancy(c.x() + 3, c.y()), 98);
  grid.addLogOdds(c.x() + 4, c.y(), -100.0f);
  EXPECT_EQ(grid.occupancy(c.x() + 4, c.y()), 2);
  EXPECT_EQ(grid.occupancy(-100000, 7), GridMap::kUnknown);  // outside the grid
  const GridMap map = grid.toGridMap();
  EXPECT_EQ(map.at(c.x(), c.y()), 50);
  EXPECT_EQ(map.at(c.x() + 1, c.y()), 70);
  EXPECT_EQ(map.at(c.x() + 4, c.y()), 2);
  EXPECT_EQ(std::count(map.cells.begin(), map.cells.end(), GridMap::kUnknown),
            static_cast<long>(map.cells.size()) - 5);
}

TEST(OccupancyGridTest, ProbabilityConversions) {
  EXPECT_DOUBLE_EQ(logOddsToProbability(0.0f), 0.5);
  EXPECT_NEAR(probabilityToLogOdds(0.7), 0.8473, 1e-4);
  EXPECT_NEAR(logOddsToProbability(probabilityToLogOdds(0.3)), 0.3, 1e-6);
  EXPECT_FLOAT_EQ(occupancyToLogOdds(50), 0.0f);
  EXPECT_FLOAT_EQ(occupancyToLogOdds(-1), 0.0f);
  EXPECT_NEAR(occupancyToLogOdds(0), std::log(0.001 / 0.999), 1e-5);
  EXPECT_NEAR(occupancyToLogOdds(100), std::log(0.999 / 0.001), 1e-5);
  for (int v = 1; v <= 99; ++v) {
    const double p = logOddsToProbability(occupancyToLogOdds(static_cast<std::int8_t>(v)));
    EXPECT_EQ(std::lround(100.0 * p), v);
  }
}

TEST(OccupancyGridTest, Int8ValueFollowsTheFormulaForEveryLogOdds) {
  // toGridMap and occupancy() must give round(100 p) exactly, at the rounding steps too.
  LogOddsParams wide;
  wide.clamp_min = -30.0f;
  wide.clamp_max = 30.0f;
  std::vector<float> samples;
  for (int v = 0; v < 100; ++v) {  // the value steps from v to v + 1 at p = (v + 0.5) / 100
    float l = probabilityToLogOdds((v + 0.5) / 100.0);
    for (int k = 0; k < 40; ++k) {
      l = std::nextafter(l, -1e9f);
    }
    for (int k = 0; k < 80; ++k) {
      samples.push_back(l);
      l = std::nextafter(l, 1e9f);
    }
  }
  std::mt19937 random(11);
  std::uniform_real_distribution<float> any(-12.0f, 12.0f);
  for (int i = 0; i < 20000; ++i) {
    samples.push_back(any(random));
  }
  for (const float extreme : {-29.0f, -8.0f, -7.99f, 7.99f, 8.0f, 29.0f, 0.0f, -0.0f}) {
    samples.push_back(extreme);
  }
  OccupancyGrid grid(kRes, wide);
  grid.ensureContains(at(0, 0), at(static_cast<double>(samples.size()) / 200.0, 199.0));
  ASSERT_GE(grid.geometry().cellCount(), samples.size());
  std::vector<Eigen::Vector2i> cells;
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const Eigen::Vector2i cell(static_cast<int>(i / 200), static_cast<int>(i % 200));
    grid.addLogOdds(cell.x(), cell.y(), samples[i]);
    ASSERT_EQ(grid.logOdds(cell.x(), cell.y()), samples[i]);
    cells.push_back(cell);
  }
  const GridMap map = grid.toGridMap();
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const long expected = std::lround(100.0 * logOddsToProbability(samples[i]));
    ASSERT_EQ(grid.occupancy(cells[i].x(), cells[i].y()), expected) << samples[i];
    ASSERT_EQ(map.at(cells[i].x(), cells[i].y()), expected) << samples[i];
  }
}

TEST(OccupancyGridTest, GrowthInEveryDirectionKeepsValuesAtMapPoints) {
  OccupancyGrid grid(kRes);
  const std::vector<Eigen::Vector2d> points = {at(0.5, 0.5), at(-3.2, 7.7), at(10.9, -4.1)};
  grid.ensureContains(at(-4, -5), at(11, 8));
  std::vector<Eigen::Vector2i> lattice;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector2i cell = grid.cellOf(points[i]);
    grid.addLogOdds(cell.x(), cell.y(), 0.5f * static_cast<float>(i + 1));
    lattice.push_back(cell + grid.originCell());
  }
  const std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> boxes = {
      {at(500, 0), at(501, 1)},     // +x
      {at(-700, 0), at(-699, 1)},   // -x
      {at(0, 900), at(1, 901)},     // +y
      {at(0, -1000), at(1, -999)},  // -y
      {at(-1200, -1200), at(1200, 1200)}};
  for (const auto& [low, high] : boxes) {
    const GridGeometry before = grid.geometry();
    grid.ensureContains(low, high);
    EXPECT_NE(grid.geometry(), before);
    for (const Eigen::Vector2d& corner : {low, high}) {
      const Eigen::Vector2i cell = grid.cellOf(corner);
      EXPECT_TRUE(grid.geometry().contains(cell.x(), cell.y()));
    }
    for (std::size_t i = 0; i < points.size(); ++i) {
      EXPECT_EQ(grid.cellOf(points[i]) + grid.originCell(), lattice[i]);
      EXPECT_FLOAT_EQ(logOddsAt(grid, points[i]), 0.5f * static_cast<float>(i + 1));
    }
    EXPECT_EQ(grid.knownCellCount(), points.size());
    // The origin stays on the lattice: an exact whole number of cells.
    EXPECT_EQ(grid.geometry().origin_m.x(), grid.originCell().x() * kRes);
    EXPECT_EQ(grid.geometry().origin_m.y(), grid.originCell().y() * kRes);
    const Eigen::Vector2d centre = grid.geometry().cellCenter(3, 4) / kRes;
    EXPECT_NEAR(centre.x() - std::floor(centre.x()), 0.5, 1e-9);
    EXPECT_NEAR(centre.y() - std::floor(centre.y()), 0.5, 1e-9);
  }
}

TEST(OccupancyGridTest, GrowsInChunksWithAMargin) {
  OccupancyGrid grid(kRes);
  grid.ensureContains(at(0.5, 0.5), at(0.5, 0.5));
  const Eigen::Vector2i cell = grid.cellOf(at(0.5, 0.5));
  EXPECT_GE(cell.x(), 64);
  EXPECT_GE(cell.y(), 64);
  EXPECT_GE(grid.geometry().width - cell.x() - 1, 64);
  EXPECT_GE(grid.geometry().height - cell.y() - 1, 64);
  // Walking one cell at a time for 5000 cells reallocates only a few times (amortised growth).
  int resizes = 0;
  for (int i = 0; i < 5000; ++i) {
    const GridGeometry before = grid.geometry();
    grid.ensureContains(at(i + 0.5, 0.5), at(i + 0.5, 0.5));
    resizes += grid.geometry() != before ? 1 : 0;
  }
  EXPECT_LE(resizes, 12);  // geometric growth; fixed 64-cell chunks would take ~78
  EXPECT_GE(resizes, 1);
}

TEST(OccupancyGridTest, CellOfIsTheLatticeCell) {
  OccupancyGrid grid(kRes);
  grid.ensureContains(at(-3, -3), at(3, 3));
  EXPECT_EQ(grid.cellOf(at(0.5, 0.5)) + grid.originCell(), Eigen::Vector2i(0, 0));
  EXPECT_EQ(grid.cellOf(at(-0.5, -1.5)) + grid.originCell(), Eigen::Vector2i(-1, -2));
  const Eigen::Vector2i cell = grid.cellOf(at(1.5, -2.5));
  EXPECT_EQ(grid.cellOf(grid.geometry().cellCenter(cell.x(), cell.y())), cell);
}

TEST(OccupancyGridTest, GridMapRoundTrip) {
  OccupancyGrid grid(kRes);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  std::uniform_real_distribution<double> range(0.2, 4.0);
  for (int beam = 0; beam < 400; ++beam) {
    const double a = angle(random);
    const double r = range(random);
    grid.insertRay(Eigen::Vector2d(0.3, -0.2),
                   Eigen::Vector2d(0.3 + r * std::cos(a), -0.2 + r * std::sin(a)), beam % 3 != 0);
  }
  const GridMap map = grid.toGridMap();
  ASSERT_TRUE(map.isValid());
  const OccupancyGrid restored = OccupancyGrid::fromGridMap(map);
  EXPECT_EQ(restored.geometry(), grid.geometry());
  EXPECT_EQ(restored.originCell(), grid.originCell());
  EXPECT_EQ(restored.knownCellCount(), grid.knownCellCount());
  EXPECT_EQ(restored.toGridMap(), map);
}

TEST(OccupancyGridTest, FromGridMapClampsAndKeepsUnknown) {
  GridGeometry geometry;
  geometry.resolution_m = kRes;
  geometry.width = 4;
  geometry.height = 1;
  geometry.origin_m = Eigen::Vector2d(-12 * kRes, 3 * kRes);
  GridMap map(geometry, GridMap::kUnknown);
  map.cells = {-1, 0, 37, 100};
  const OccupancyGrid grid = OccupancyGrid::fromGridMap(map);
  EXPECT_EQ(grid.originCell(), Eigen::Vector2i(-12, 3));
  EXPECT_FALSE(grid.isKnown(0, 0));
  EXPECT_FLOAT_EQ(grid.logOdds(1, 0), grid.params().clamp_min);
  EXPECT_FLOAT_EQ(grid.logOdds(3, 0), grid.params().clamp_max);
  EXPECT_EQ(grid.toGridMap().cells, (std::vector<std::int8_t>{-1, 2, 37, 98}));
  EXPECT_EQ(grid.knownCellCount(), 3u);
}

TEST(OccupancyGridTest, FromGridMapRejectsMisalignedOrInvalidMaps) {
  GridGeometry geometry;
  geometry.resolution_m = kRes;
  geometry.width = 2;
  geometry.height = 2;
  geometry.origin_m = Eigen::Vector2d(0.01, 0.0);
  EXPECT_THROW(OccupancyGrid::fromGridMap(GridMap(geometry, 0)), std::invalid_argument);
  geometry.origin_m = Eigen::Vector2d(0.0, 0.0);
  GridMap bad(geometry, 0);
  bad.cells.pop_back();
  EXPECT_THROW(OccupancyGrid::fromGridMap(bad), std::invalid_argument);
  EXPECT_THROW(OccupancyGrid(0.0), std::invalid_argument);
  EXPECT_THROW(OccupancyGrid(kRes, LogOddsParams{0.85f, -0.4f, 1.0f, -1.0f}),
               std::invalid_argument);
}

TEST(OccupancyGridTest, KnownCellCountCountsObservedCellsOnce) {
  OccupancyGrid grid(kRes);
  EXPECT_EQ(grid.knownCellCount(), 0u);
  grid.insertRay(at(0.5, 0.5), at(9.5, 0.5), true);
  EXPECT_EQ(grid.knownCellCount(), 10u);
  grid.insertRay(at(0.5, 0.5), at(9.5, 0.5), false);
  EXPECT_EQ(grid.knownCellCount(), 10u);
  grid.insertRay(at(0.5, 1.5), at(0.5, 3.5), true);
  EXPECT_EQ(grid.knownCellCount(), 13u);
}

}  // namespace
}  // namespace mrslam
