#pragma once
// A log-odds occupancy grid that grows as the robot explores (no fixed size limit).
//
// Cells sit on a fixed lattice of the map frame: lattice cell (i, j) covers
// [i * resolution, (i + 1) * resolution) × [j * resolution, (j + 1) * resolution). The grid's
// origin is always a lattice corner (origin_m = originCell() * resolution), so cell centres lie on
// OctoMap's voxel lattice and a map-frame point keeps its cell when the grid grows.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "mrslam/common/grid_map.hpp"

namespace mrslam {

/// Log-odds increments of the inverse sensor model, and the clamping bounds.
struct LogOddsParams {
  float hit = 0.85f;        ///< added at a beam's end point: logit(0.7)
  float miss = -0.4f;       ///< added on cells a beam crosses: logit(0.4)
  float clamp_min = -4.0f;  ///< lower bound, keeps a cell able to change (p ≈ 0.018)
  float clamp_max = 4.0f;   ///< upper bound (p ≈ 0.982)
};

class OccupancyGrid {
 public:
  /// An empty grid at `resolution_m`; it takes cells as ensureContains() asks for them.
  /// Throws std::invalid_argument when the resolution is not > 0 or the params are not finite
  /// with clamp_min < clamp_max.
  explicit OccupancyGrid(double resolution_m, LogOddsParams params = {});

  const GridGeometry& geometry() const { return geometry_; }
  const LogOddsParams& params() const { return params_; }
  /// The lattice index of cell (0, 0): geometry().origin_m == originCell() * resolution.
  const Eigen::Vector2i& originCell() const { return origin_cell_; }

  /// The cell holding a map-frame point (it may lie outside the grid):
  /// floor(point / resolution) - originCell().
  Eigen::Vector2i cellOf(const Eigen::Vector2d& point_m) const;

  /// Grows the grid (in chunks, keeping existing cells and keeping the origin a whole number of
  /// cells from the map frame's origin) so that the box [min_m, max_m] lies inside it.
  /// A chunk adds max(64, half the current size) cells on each side that needs to grow.
  /// Throws std::out_of_range for non-finite corners or ones beyond ±2^28 cells.
  void ensureContains(const Eigen::Vector2d& min_m, const Eigen::Vector2d& max_m);

  /// One beam from `from_m` to `to_m` (map frame): every cell it crosses gets a miss; the end cell
  /// gets a hit when `hit` is true, a miss otherwise. Each cell is updated once per ray; a cell the
  /// beam only touches at a corner is not crossed. The traversal is exact (integer arithmetic)
  /// for the segment whose end points are rounded down to 1/1024 of a cell; the start and end
  /// cells are always cellOf(from_m) and cellOf(to_m). Grows the grid as needed. A ray with a
  /// non-finite end is ignored (callers filter and count invalid beams); one longer than 2^20
  /// cells throws std::out_of_range.
  void insertRay(const Eigen::Vector2d& from_m, const Eigen::Vector2d& to_m, bool hit);

  /// Adds `delta` to a cell's log-odds, clamped. The cell must be inside the grid.
  void addLogOdds(int cx, int cy, float delta);

  /// Log-odds of a cell (0 when unknown or outside the grid).
  float logOdds(int cx, int cy) const;
  /// True when the cell has been observed at least once.
  bool isKnown(int cx, int cy) const;
  /// -1 unknown, otherwise round(100 * p) with p = 1 - 1 / (1 + exp(l)).
  std::int8_t occupancy(int cx, int cy) const;

  /// The int8 form of the whole grid.
  GridMap toGridMap() const;
  /// A grid holding a GridMap's values as log-odds (the inverse of toGridMap up to rounding),
  /// clamped to the params' bounds; -1 cells stay unknown. The map's origin must be a whole number
  /// of cells from the frame origin (within 1e-6 cells; the stored origin is then
  /// originCell() * resolution) and the map must be valid, else std::invalid_argument.
  static OccupancyGrid fromGridMap(const GridMap& map, LogOddsParams params = {});

  /// Number of cells observed at least once.
  std::size_t knownCellCount() const;

 private:
  /// Reallocates to cover lattice cells [min_cx, max_cx] × [min_cy, max_cy] (inclusive, a
  /// superset of the current grid), copying the existing cells to their lattice places.
  void resize(int min_cx, int min_cy, int max_cx, int max_cy);
  /// The lattice cell holding a point, with the range checks of ensureContains().
  Eigen::Vector2i latticeCellOf(const Eigen::Vector2d& point_m) const;

  LogOddsParams params_;
  GridGeometry geometry_;
  Eigen::Vector2i origin_cell_{0, 0};  ///< origin_m / resolution, an exact integer
  std::vector<float> log_odds_;
  std::vector<std::uint8_t> known_;
};

/// Probability (0..1) ↔ log-odds.
float probabilityToLogOdds(double probability);
double logOddsToProbability(float log_odds);
/// An int8 occupancy value (0..100) as log-odds, with p = value / 100 clamped into
/// [0.001, 0.999] so 0 and 100 stay finite. A negative value (unknown) gives 0 (p = 0.5).
float occupancyToLogOdds(std::int8_t occupancy);

}  // namespace mrslam
