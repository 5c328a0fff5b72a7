#include <algorithm>
#include <cmath>

#include "mrslam/fusion/merge/map_merger.hpp"

namespace mrslam::fusion {

// Cell centre (i, j) of a grid lies at origin + (i + 0.5, j + 0.5) · resolution in its frame.
SE2 gridTransformToMetric(const GridTransform& T_to_from_cells, const GridGeometry& from,
                          const GridGeometry& to) {
  const double r = to.resolution_m;
  // p_from (metres) → cell: (p - o_from)/r - 0.5; cell map; back: r · (c + 0.5) + o_to.
  const Eigen::Vector2d half(0.5, 0.5);
  const double c = std::cos(T_to_from_cells.theta_rad);
  const double s = std::sin(T_to_from_cells.theta_rad);
  Eigen::Matrix2d rotation;
  rotation << c, -s, s, c;
  const Eigen::Vector2d cell_of_frame_origin = -from.origin_m / from.resolution_m - half;
  const Eigen::Vector2d mapped = rotation * cell_of_frame_origin + T_to_from_cells.t_cells;
  const Eigen::Vector2d translation = r * (mapped + half) + to.origin_m;
  return SE2(translation.x(), translation.y(), T_to_from_cells.theta_rad);
}

GridTransform metricToGridTransform(const SE2& T_to_from, const GridGeometry& from,
                                    const GridGeometry& to) {
  // cell_to = (T · (r_f (cell_from + ½) + o_from) − o_to) / r_to − ½.
  const Eigen::Vector2d half(0.5, 0.5);
  GridTransform transform;
  transform.theta_rad = T_to_from.theta();
  const Eigen::Vector2d image_of_zero = T_to_from * (from.resolution_m * half + from.origin_m);
  const Eigen::Vector2d zero_cell = (image_of_zero - to.origin_m) / to.resolution_m - half;
  transform.t_cells = zero_cell;
  return transform;
}

int blockCellsForSize(const GridMap& from, const GridMap& to, int block_cells, int max_blocks) {
  const int block = std::max(1, block_cells);
  if (max_blocks <= 0) {
    return block;
  }
  const int side =
      std::max({from.geometry.width, from.geometry.height, to.geometry.width, to.geometry.height});
  return std::max(block, (side + max_blocks - 1) / max_blocks);
}

}  // namespace mrslam::fusion
