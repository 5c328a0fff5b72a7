#include "mrslam/common/occupancy_grid.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <stdexcept>
#include <string>

namespace mrslam {
namespace {

constexpr int kMinGrowthCells = 64;             ///< smallest margin added on a side that grows
constexpr double kMaxLatticeIndex = 1 << 28;    ///< |lattice index| limit, keeps int maths safe
constexpr double kAlignmentTolerance = 1e-6;    ///< cells
constexpr std::int64_t kSubcells = 1 << 10;     ///< ray end points are taken to 1/1024 of a cell
constexpr std::int64_t kMaxRayCells = 1 << 20;  ///< keeps the ray's integer maths within int64

inline float clampf(float value, float low, float high) {
  return std::min(std::max(value, low), high);
}

/// round(100 p) with p = 1 - 1 / (1 + exp(l)), the defining formula.
int exactOccupancy(float log_odds) {
  return static_cast<int>(std::lround(100.0 * logOddsToProbability(log_odds)));
}

/// The same value as exactOccupancy() for every float, without exp: the formula steps up by one
/// at 100 float log-odds (threshold v: the smallest float whose value is v or more). Log-odds in
/// [-8, 8) fall in bins of 1/64, narrower than the gap between two thresholds (>= 0.04), so a
/// bin's value is its value at the bin's start plus one past the single threshold it may hold.
class OccupancyTable {
 public:
  OccupancyTable() {
    thresholds_[0] = -std::numeric_limits<float>::infinity();
    for (int v = 1; v <= 100; ++v) {
      float l = probabilityToLogOdds((v - 0.5) / 100.0);
      while (exactOccupancy(l) >= v) {
        l = std::nextafter(l, -std::numeric_limits<float>::infinity());
      }
      while (exactOccupancy(l) < v) {
        l = std::nextafter(l, std::numeric_limits<float>::infinity());
      }
      thresholds_[v] = l;
    }
    thresholds_[101] = thresholds_[102] = std::numeric_limits<float>::infinity();
    int value = 0;
    for (int bin = 0; bin < kBins; ++bin) {
      const float bin_start = kLow + static_cast<float>(bin) / kBinsPerUnit;
      while (thresholds_[value + 1] <= bin_start) {
        ++value;
      }
      if (thresholds_[value + 2] < bin_start + 1.0f / kBinsPerUnit) {
        throw std::logic_error("OccupancyTable: two thresholds in one bin");
      }
      base_[bin] = static_cast<std::int8_t>(value);
      next_[bin] = thresholds_[value + 1];
    }
  }

  std::int8_t operator()(float log_odds) const {
    // Exact in double: a float below 2^4 in magnitude, plus 8, times 64.
    const double position = (static_cast<double>(log_odds) - kLow) * kBinsPerUnit;
    if (!(position >= 0.0)) {
      return GridMap::kFree;
    }
    if (position >= kBins) {
      return GridMap::kOccupied;
    }
    const auto bin = static_cast<std::size_t>(position);
    return static_cast<std::int8_t>(base_[bin] + (log_odds >= next_[bin] ? 1 : 0));
  }

 private:
  static constexpr float kLow = -8.0f;
  static constexpr int kBinsPerUnit = 64;
  static constexpr int kBins = 16 * kBinsPerUnit;

  std::array<float, 103> thresholds_{};  ///< -inf, the 100 thresholds, +inf, +inf
  std::array<std::int8_t, kBins> base_{};
  std::array<float, kBins> next_{};
};

const OccupancyTable& occupancyTable() {
  static const OccupancyTable table;
  return table;
}

}  // namespace

float probabilityToLogOdds(double probability) {
  return static_cast<float>(std::log(probability / (1.0 - probability)));
}

double logOddsToProbability(float log_odds) {
  return 1.0 - 1.0 / (1.0 + std::exp(static_cast<double>(log_odds)));
}

float occupancyToLogOdds(std::int8_t occupancy) {
  if (occupancy < 0) {
    return 0.0f;
  }
  const double p = std::clamp(static_cast<double>(occupancy) / 100.0, 0.001, 0.999);
  return probabilityToLogOdds(p);
}

OccupancyGrid::OccupancyGrid(double resolution_m, LogOddsParams params) : params_(params) {
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m)) {
    throw std::invalid_argument("OccupancyGrid: resolution must be > 0, got " +
                                std::to_string(resolution_m));
  }
  if (!std::isfinite(params.hit) || !std::isfinite(params.miss) ||
      !std::isfinite(params.clamp_min) || !std::isfinite(params.clamp_max) ||
      !(params.clamp_min < params.clamp_max)) {
    throw std::invalid_argument(
        "OccupancyGrid: log-odds params must be finite with clamp_min < clamp_max");
  }
  geometry_.resolution_m = resolution_m;
}

Eigen::Vector2i OccupancyGrid::cellOf(const Eigen::Vector2d& point_m) const {
  const double res = geometry_.resolution_m;
  return Eigen::Vector2i(static_cast<int>(std::floor(point_m.x() / res)) - origin_cell_.x(),
                         static_cast<int>(std::floor(point_m.y() / res)) - origin_cell_.y());
}

Eigen::Vector2i OccupancyGrid::latticeCellOf(const Eigen::Vector2d& point_m) const {
  const double res = geometry_.resolution_m;
  const double x = std::floor(point_m.x() / res);
  const double y = std::floor(point_m.y() / res);
  if (!(std::abs(x) <= kMaxLatticeIndex) || !(std::abs(y) <= kMaxLatticeIndex)) {
    throw std::out_of_range("OccupancyGrid: point (" + std::to_string(point_m.x()) + ", " +
                            std::to_string(point_m.y()) + ") is not finite or too far away");
  }
  return Eigen::Vector2i(static_cast<int>(x), static_cast<int>(y));
}

void OccupancyGrid::ensureContains(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m) {
  const Eigen::Vector2i low = latticeCellOf(min_m.cwiseMin(max_m));
  const Eigen::Vector2i high = latticeCellOf(min_m.cwiseMax(max_m));
  const Eigen::Vector2i size(geometry_.width, geometry_.height);
  if (size.x() == 0 || size.y() == 0) {
    resize(low.x() - kMinGrowthCells, low.y() - kMinGrowthCells, high.x() + kMinGrowthCells,
           high.y() + kMinGrowthCells);
    return;
  }
  const Eigen::Vector2i first = origin_cell_;
  const Eigen::Vector2i last = origin_cell_ + size - Eigen::Vector2i::Ones();
  if ((low.array() >= first.array()).all() && (high.array() <= last.array()).all()) {
    return;
  }
  // Each side that must grow gets a margin proportional to the size: amortised O(1) per cell.
  Eigen::Vector2i new_first = first;
  Eigen::Vector2i new_last = last;
  for (int axis = 0; axis < 2; ++axis) {
    const int margin = std::max(kMinGrowthCells, size[axis] / 2);
    if (low[axis] < first[axis]) {
      new_first[axis] = low[axis] - margin;
    }
    if (high[axis] > last[axis]) {
      new_last[axis] = high[axis] + margin;
    }
  }
  resize(new_first.x(), new_first.y(), new_last.x(), new_last.y());
}

void OccupancyGrid::resize(int min_cx, int min_cy, int max_cx, int max_cy) {
  const int new_width = max_cx - min_cx + 1;
  const int new_height = max_cy - min_cy + 1;
  GridGeometry next = geometry_;
  next.width = std::max(new_width, 0);
  next.height = std::max(new_height, 0);
  next.origin_m = Eigen::Vector2d(min_cx * geometry_.resolution_m, min_cy * geometry_.resolution_m);
  std::vector<float> log_odds(next.cellCount(), 0.0f);
  std::vector<std::uint8_t> known(next.cellCount(), 0);
  // Old cell (cx, cy) lies at lattice origin_cell_ + (cx, cy), i.e. new cell (cx, cy) + shift.
  const int shift_x = origin_cell_.x() - min_cx;
  const int shift_y = origin_cell_.y() - min_cy;
  for (int cy = 0; geometry_.width > 0 && cy < geometry_.height; ++cy) {
    const std::size_t from = geometry_.index(0, cy);
    const std::size_t to = next.index(shift_x, cy + shift_y);
    const auto width = static_cast<std::ptrdiff_t>(geometry_.width);
    std::copy_n(log_odds_.begin() + static_cast<std::ptrdiff_t>(from), width,
                log_odds.begin() + static_cast<std::ptrdiff_t>(to));
    std::copy_n(known_.begin() + static_cast<std::ptrdiff_t>(from), width,
                known.begin() + static_cast<std::ptrdiff_t>(to));
  }
  geometry_ = next;
  origin_cell_ = Eigen::Vector2i(min_cx, min_cy);
  log_odds_.swap(log_odds);
  known_.swap(known);
}

void OccupancyGrid::insertRay(const Eigen::Vector2d& from_m, const Eigen::Vector2d& to_m,
                              bool hit) {
  if (!from_m.allFinite() || !to_m.allFinite()) {
    return;
  }
  if (((to_m - from_m) / geometry_.resolution_m).cwiseAbs().maxCoeff() >= kMaxRayCells - 1) {
    throw std::out_of_range("OccupancyGrid::insertRay: ray longer than 2^20 cells");
  }
  ensureContains(from_m.cwiseMin(to_m), from_m.cwiseMax(to_m));

  // Amanatides & Woo (1987) in exact integer arithmetic. Positions are in 1/kSubcells of a cell,
  // relative to the start cell's corner. With D the ray's extent and b the distance from the start
  // to the next cell boundary on each axis, the x boundary comes first when b_x / |D_x| <
  // b_y / |D_y|, i.e. when e = b_x |D_y| - b_y |D_x| < 0; a step on x adds kSubcells to b_x, so
  // kSubcells |D_y| to e. The step counts come from the end cell, so the walk always ends there.
  const double res = geometry_.resolution_m;
  std::int64_t extent[2];
  std::int64_t to_boundary[2];
  int steps[2];
  std::ptrdiff_t index_step[2];
  const std::ptrdiff_t stride[2] = {1, static_cast<std::ptrdiff_t>(geometry_.width)};
  int start_cell[2];
  for (int axis = 0; axis < 2; ++axis) {
    const double start = from_m[axis] / res;
    const double end = to_m[axis] / res;
    const double start_floor = std::floor(start);
    const double end_floor = std::floor(end);
    const auto cells = static_cast<std::int64_t>(end_floor - start_floor);
    const auto start_sub = static_cast<std::int64_t>(std::floor((start - start_floor) * kSubcells));
    const auto end_sub = static_cast<std::int64_t>(std::floor((end - end_floor) * kSubcells));
    const std::int64_t d = cells * kSubcells + end_sub - start_sub;
    extent[axis] = std::abs(d);
    to_boundary[axis] = d > 0 ? kSubcells - start_sub : start_sub;
    steps[axis] = static_cast<int>(std::abs(cells));
    index_step[axis] = d < 0 ? -stride[axis] : stride[axis];
    start_cell[axis] = static_cast<int>(start_floor) - origin_cell_[axis];
  }

  std::ptrdiff_t index = static_cast<std::ptrdiff_t>(geometry_.index(start_cell[0], start_cell[1]));
  float* const log_odds = log_odds_.data();
  std::uint8_t* const known = known_.data();
  const float miss = params_.miss;
  const float low = params_.clamp_min;
  const float high = params_.clamp_max;
  const auto cross = [&](std::ptrdiff_t i) {
    log_odds[i] = clampf(log_odds[i] + miss, low, high);
    known[i] = 1;
  };
  int x_left = steps[0];
  int y_left = steps[1];
  std::int64_t e = to_boundary[0] * extent[1] - to_boundary[1] * extent[0];
  const std::int64_t e_step_x = kSubcells * extent[1];
  const std::int64_t e_step_y = kSubcells * extent[0];
  // Through a corner (e == 0) the walk steps on both axes: the side cells are only touched at a
  // point. (Branches measured faster here than masks: the pattern along a ray is regular enough
  // for the predictor, while masks put the whole decision on the loop's dependency chain.)
  while (x_left > 0 && y_left > 0) {
    cross(index);
    const bool step_x = e <= 0;
    const bool step_y = e >= 0;
    if (step_x) {
      index += index_step[0];
      e += e_step_x;
      --x_left;
    }
    if (step_y) {
      index += index_step[1];
      e -= e_step_y;
      --y_left;
    }
  }
  for (; x_left > 0; --x_left, index += index_step[0]) {
    cross(index);
  }
  for (; y_left > 0; --y_left, index += index_step[1]) {
    cross(index);
  }
  log_odds[index] = clampf(log_odds[index] + (hit ? params_.hit : miss), low, high);
  known[index] = 1;
}

void OccupancyGrid::addLogOdds(int cx, int cy, float delta) {
  const std::size_t index = geometry_.index(cx, cy);
  log_odds_[index] = clampf(log_odds_[index] + delta, params_.clamp_min, params_.clamp_max);
  known_[index] = 1;
}

float OccupancyGrid::logOdds(int cx, int cy) const {
  return geometry_.contains(cx, cy) ? log_odds_[geometry_.index(cx, cy)] : 0.0f;
}

bool OccupancyGrid::isKnown(int cx, int cy) const {
  return geometry_.contains(cx, cy) && known_[geometry_.index(cx, cy)] != 0;
}

std::int8_t OccupancyGrid::occupancy(int cx, int cy) const {
  if (!isKnown(cx, cy)) {
    return GridMap::kUnknown;
  }
  return occupancyTable()(log_odds_[geometry_.index(cx, cy)]);
}

GridMap OccupancyGrid::toGridMap() const {
  GridMap map(geometry_, GridMap::kUnknown);
  const OccupancyTable& table = occupancyTable();
  for (std::size_t i = 0; i < map.cells.size(); ++i) {
    if (known_[i] != 0) {
      map.cells[i] = table(log_odds_[i]);
    }
  }
  return map;
}

OccupancyGrid OccupancyGrid::fromGridMap(const GridMap& map, LogOddsParams params) {
  if (!map.isValid()) {
    throw std::invalid_argument("OccupancyGrid::fromGridMap: invalid map (size or values)");
  }
  OccupancyGrid grid(map.geometry.resolution_m, params);
  const Eigen::Vector2d origin_cells = map.geometry.origin_m / map.geometry.resolution_m;
  const Eigen::Vector2d rounded = origin_cells.array().round();
  if ((origin_cells - rounded).cwiseAbs().maxCoeff() > kAlignmentTolerance ||
      rounded.cwiseAbs().maxCoeff() > kMaxLatticeIndex) {
    throw std::invalid_argument(
        "OccupancyGrid::fromGridMap: origin is not a whole number of cells from the frame origin");
  }
  const int min_cx = static_cast<int>(rounded.x());
  const int min_cy = static_cast<int>(rounded.y());
  grid.resize(min_cx, min_cy, min_cx + map.geometry.width - 1, min_cy + map.geometry.height - 1);
  for (std::size_t i = 0; i < map.cells.size(); ++i) {
    if (map.cells[i] != GridMap::kUnknown) {
      grid.log_odds_[i] =
          clampf(occupancyToLogOdds(map.cells[i]), params.clamp_min, params.clamp_max);
      grid.known_[i] = 1;
    }
  }
  return grid;
}

std::size_t OccupancyGrid::knownCellCount() const {
  return static_cast<std::size_t>(std::count(known_.begin(), known_.end(), std::uint8_t{1}));
}

}  // namespace mrslam
