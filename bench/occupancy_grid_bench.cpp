// Occupancy grid costs: one laser scan inserted by ray tracing, and the int8 conversion.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "mrslam/common/occupancy_grid.hpp"

namespace mrslam {
namespace {

constexpr double kResolution = 0.05;
constexpr int kBeams = 682;  ///< a Hokuyo URG-04LX scan
constexpr double kFieldOfView = 240.0 * M_PI / 180.0;
constexpr double kRange = 4.0;

/// End points of a synthetic scan from `origin`: 682 beams over 240°, all 4 m long.
std::vector<Eigen::Vector2d> scanEnds(const Eigen::Vector2d& origin) {
  std::vector<Eigen::Vector2d> ends;
  ends.reserve(kBeams);
  for (int i = 0; i < kBeams; ++i) {
    const double angle = -0.5 * kFieldOfView + kFieldOfView * i / (kBeams - 1);
    ends.push_back(origin + kRange * Eigen::Vector2d(std::cos(angle), std::sin(angle)));
  }
  return ends;
}

/// Cells one scan updates (each beam counted on its own).
double cellUpdatesPerScan(const Eigen::Vector2d& origin, const std::vector<Eigen::Vector2d>& ends) {
  double cells = 0.0;
  for (const Eigen::Vector2d& end : ends) {
    OccupancyGrid grid(kResolution);
    grid.insertRay(origin, end, true);
    cells += static_cast<double>(grid.knownCellCount());
  }
  return cells;
}

void BM_InsertScan(benchmark::State& state) {
  const Eigen::Vector2d origin(0.013, -0.021);
  const std::vector<Eigen::Vector2d> ends = scanEnds(origin);
  OccupancyGrid grid(kResolution);
  grid.ensureContains(origin - Eigen::Vector2d::Constant(kRange),
                      origin + Eigen::Vector2d::Constant(kRange));
  for (auto _ : state) {
    for (const Eigen::Vector2d& end : ends) {
      grid.insertRay(origin, end, true);
    }
    benchmark::ClobberMemory();
  }
  const double cells = cellUpdatesPerScan(origin, ends);
  state.counters["cells_per_scan"] = cells;
  state.counters["cells/s"] = benchmark::Counter(cells * static_cast<double>(state.iterations()),
                                                 benchmark::Counter::kIsRate);
}
BENCHMARK(BM_InsertScan)->Unit(benchmark::kMicrosecond);

void BM_InsertScanIntoEmptyGrid(benchmark::State& state) {
  const Eigen::Vector2d origin(0.013, -0.021);
  const std::vector<Eigen::Vector2d> ends = scanEnds(origin);
  for (auto _ : state) {
    OccupancyGrid grid(kResolution);  // includes the growth the first scan causes
    for (const Eigen::Vector2d& end : ends) {
      grid.insertRay(origin, end, true);
    }
    benchmark::DoNotOptimize(grid.knownCellCount());
  }
}
BENCHMARK(BM_InsertScanIntoEmptyGrid)->Unit(benchmark::kMicrosecond);

void BM_ToGridMap(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  GridGeometry geometry;
  geometry.resolution_m = kResolution;
  geometry.width = side;
  geometry.height = side;
  GridMap map(geometry, GridMap::kUnknown);
  std::mt19937 random(42);
  std::uniform_int_distribution<int> value(-1, 100);
  for (auto& cell : map.cells) {
    cell = static_cast<std::int8_t>(value(random));
  }
  const OccupancyGrid grid = OccupancyGrid::fromGridMap(map);
  for (auto _ : state) {
    GridMap converted = grid.toGridMap();
    benchmark::DoNotOptimize(converted.cells.data());
  }
  state.counters["cells/s"] = benchmark::Counter(
      static_cast<double>(geometry.cellCount()) * static_cast<double>(state.iterations()),
      benchmark::Counter::kIsRate);
}
BENCHMARK(BM_ToGridMap)->Arg(800)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace mrslam

BENCHMARK_MAIN();
