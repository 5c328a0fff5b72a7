#pragma once
// The virtual robot's likelihood field as its particles read it (virtual_robot.hpp): a scan point
// that lands on cell c of `to` costs d(c)² / (2σ²), d(c) the distance from c to `to`'s nearest
// wall capped at `cap` (a point off the map costs as if at the cap).
//
// The distances of an exact Euclidean distance transform are square roots of integers, so a
// capped field holds few distinct values (at a cap of 4.5 cells, 14). Each cell keeps the index
// of its cost in a table of those values (one byte a cell, a quarter of the float field), and a
// point's cost is one byte and one table read instead of a float read, a minimum, a product and
// a division. The table's costs are computed by the same operations as from the field, so every
// sum of costs is the same, bit for bit. A field of more than 256 distinct capped values keeps
// each cell's cost itself.

#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core.hpp>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {

/// The exact Euclidean distance (cells, CV_32F) from every cell of `map` to the nearest cell of
/// at least `wall_occupancy` percent.
cv::Mat wallDistance(const GridMap& map, int wall_occupancy);

class HitCosts {
 public:
  /// The costs of `distance` (CV_32F, cells to the nearest wall) capped at `cap`, with σ `sigma`.
  HitCosts(const cv::Mat& distance, double cap, double sigma);

  /// The cost of a point on cell (x, y); off the map, the cap's.
  double at(int x, int y) const {
    if (static_cast<unsigned>(x) >= static_cast<unsigned>(cols_) ||
        static_cast<unsigned>(y) >= static_cast<unsigned>(rows_)) {
      return off_map_cost_;
    }
    const std::size_t cell =
        static_cast<std::size_t>(y) * static_cast<std::size_t>(cols_) + static_cast<std::size_t>(x);
    return indexed() ? table_[index_[cell]] : cell_costs_[cell];
  }

  /// The log-likelihood of a scan from `pose`: minus the sum of its points' costs, each point
  /// (robot frame, cells) turned and shifted by `pose` and rounded to its cell.
  double scanLogLikelihood(const std::vector<Eigen::Vector2d>& points, const SE2& pose) const;

  /// Whether the costs are kept as indices into a table of distinct values.
  bool indexed() const { return !table_.empty(); }
  /// The distinct costs (empty when not indexed()).
  const std::vector<double>& table() const { return table_; }

 private:
  template <typename CostOfCell>
  double minusSumOfCosts(const std::vector<Eigen::Vector2d>& points, const SE2& pose,
                         CostOfCell cost_of_cell) const;

  int cols_ = 0;
  int rows_ = 0;
  double off_map_cost_ = 0.0;
  std::vector<double> table_;
  std::vector<std::uint8_t> index_;
  std::vector<double> cell_costs_;  // when there are more distinct costs than a byte indexes
};

}  // namespace mrslam::fusion
