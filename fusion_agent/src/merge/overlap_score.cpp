#include "mrslam/fusion/merge/overlap_score.hpp"

#include <array>
#include <cmath>
#include <vector>

#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion {
namespace {

/// Binary entropy (bits) of p = sum / 200, for a sum of two values 0..100 (or twice one value).
const std::array<double, 201>& entropyOfSum() {
  static const std::array<double, 201> table = [] {
    std::array<double, 201> entropy{};
    for (std::size_t sum = 1; sum < 200; ++sum) {
      const double p = static_cast<double>(sum) / 200.0;
      entropy[sum] = -p * std::log2(p) - (1.0 - p) * std::log2(1.0 - p);
    }
    return entropy;
  }();
  return table;
}

double entropyOf(int value_sum) {
  return entropyOfSum()[static_cast<std::size_t>(value_sum)];
}

void countPair(std::int8_t from_value, std::int8_t to_value, OverlapScore& score) {
  const CellClass a = classOf(from_value);
  const CellClass b = classOf(to_value);
  if (a == CellClass::kNone || b == CellClass::kNone) {
    return;
  }
  if (a == b) {
    ++score.agreement;
  } else {
    ++score.disagreement;
  }
}

}  // namespace

CellClass classOf(std::int8_t value) {
  if (value < 0 || value == 50) {
    return CellClass::kNone;
  }
  return value < 50 ? CellClass::kFree : CellClass::kOccupied;
}

OverlapScore scoreOverlap(const GridMap& from, const GridMap& to, const GridTransform& T_to_from) {
  OverlapScore score;
  const GridGeometry& gf = from.geometry;
  const GridGeometry& gt = to.geometry;
  std::vector<bool> hit(gt.cellCount(), false);
  double entropy_sum = 0.0;
  std::size_t merged_cells = 0;
  const double c = std::cos(T_to_from.theta_rad);
  const double s = std::sin(T_to_from.theta_rad);
  for (int y = 0; y < gf.height; ++y) {
    for (int x = 0; x < gf.width; ++x) {
      const std::int8_t value = from.at(x, y);
      if (value < 0) {
        continue;
      }
      ++merged_cells;
      const int tx = roundToInt(c * x - s * y + T_to_from.t_cells.x());
      const int ty = roundToInt(s * x + c * y + T_to_from.t_cells.y());
      const std::int8_t other = gt.contains(tx, ty) ? to.at(tx, ty) : GridMap::kUnknown;
      if (other < 0) {
        entropy_sum += entropyOf(2 * value);
        continue;
      }
      hit[gt.index(tx, ty)] = true;
      entropy_sum += entropyOf(value + other);
      countPair(value, other, score);
    }
  }
  for (std::size_t i = 0; i < to.cells.size(); ++i) {
    if (to.cells[i] >= 0 && !hit[i]) {
      ++merged_cells;
      entropy_sum += entropyOf(2 * to.cells[i]);
    }
  }
  score.entropy_bits = merged_cells == 0 ? 0.0 : entropy_sum / static_cast<double>(merged_cells);
  return score;
}

ImageAffine gridTransformToImageAffine(const GridTransform& T_to_from, int from_height,
                                       int to_height) {
  const double c = std::cos(T_to_from.theta_rad);
  const double s = std::sin(T_to_from.theta_rad);
  // p_grid = F p_image + (0, hf - 1); q_image = F q_grid + (0, ht - 1); F R F = R(-theta).
  const Eigen::Vector2d from_offset(0.0, from_height - 1.0);
  const Eigen::Vector2d moved = Eigen::Vector2d(c * from_offset.x() - s * from_offset.y(),
                                                s * from_offset.x() + c * from_offset.y()) +
                                T_to_from.t_cells;
  ImageAffine affine;
  affine << c, s, moved.x(), -s, c, -moved.y() + (to_height - 1.0);
  return affine;
}

GridTransform imageAffineToGridTransform(const ImageAffine& affine, int from_height,
                                         int to_height) {
  // The same relation read backwards: theta from A = R(-theta), t from b.
  GridTransform transform;
  transform.theta_rad = std::atan2(-affine(1, 0), affine(0, 0));
  const double c = std::cos(transform.theta_rad);
  const double s = std::sin(transform.theta_rad);
  const Eigen::Vector2d moved(affine(0, 2), (to_height - 1.0) - affine(1, 2));
  const Eigen::Vector2d from_offset(0.0, from_height - 1.0);
  transform.t_cells = moved - Eigen::Vector2d(c * from_offset.x() - s * from_offset.y(),
                                              s * from_offset.x() + c * from_offset.y());
  return transform;
}

}  // namespace mrslam::fusion
