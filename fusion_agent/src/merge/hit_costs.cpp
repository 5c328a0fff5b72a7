// The virtual robot's likelihood field as a table of distinct costs (hit_costs.hpp).

#include "mrslam/fusion/merge/hit_costs.hpp"

#include <algorithm>
#include <map>
#include <opencv2/imgproc.hpp>

namespace mrslam::fusion {

namespace {

constexpr std::size_t kMostIndexedCosts = 256;  ///< distinct costs a byte indexes

/// A point's cost at distance d (cells) from the nearest wall: d² / (2σ²).
double costAt(double d, double sigma) {
  return d * d / (2.0 * sigma * sigma);
}

}  // namespace

cv::Mat wallDistance(const GridMap& map, int wall_occupancy) {
  cv::Mat not_wall(map.geometry.height, map.geometry.width, CV_8U, cv::Scalar(255));
  for (int y = 0; y < map.geometry.height; ++y) {
    for (int x = 0; x < map.geometry.width; ++x) {
      if (map.at(x, y) >= wall_occupancy) {
        not_wall.at<std::uint8_t>(y, x) = 0;
      }
    }
  }
  cv::Mat distance;
  cv::distanceTransform(not_wall, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return distance;
}

HitCosts::HitCosts(const cv::Mat& distance, double cap, double sigma)
    : cols_(distance.cols), rows_(distance.rows), off_map_cost_(costAt(cap, sigma)) {
  CV_Assert(distance.empty() || distance.type() == CV_32F);
  const std::size_t cells = static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_);
  std::vector<double> capped;
  capped.reserve(cells);
  for (int y = 0; y < rows_; ++y) {
    const float* row = distance.ptr<float>(y);
    for (int x = 0; x < cols_; ++x) {
      capped.push_back(std::min(cap, static_cast<double>(row[x])));
    }
  }
  std::map<double, std::uint8_t> slots;
  index_.reserve(cells);
  for (const double d : capped) {
    const auto [slot, added] = slots.try_emplace(d, static_cast<std::uint8_t>(table_.size()));
    if (added) {
      if (table_.size() == kMostIndexedCosts) {
        break;  // too many distinct costs for a byte
      }
      table_.push_back(costAt(d, sigma));
    }
    index_.push_back(slot->second);
  }
  if (index_.size() == cells) {
    return;
  }
  table_.clear();
  index_.clear();
  cell_costs_.reserve(cells);
  for (const double d : capped) {
    cell_costs_.push_back(costAt(d, sigma));
  }
}

template <typename CostOfCell>
double HitCosts::minusSumOfCosts(const std::vector<Eigen::Vector2d>& points, const SE2& pose,
                                 CostOfCell cost_of_cell) const {
  // As SE2 turns a point: (c x - s y + t_x, s x + c y + t_y). The members are read once, not
  // at every point.
  const double c = std::cos(pose.theta());
  const double s = std::sin(pose.theta());
  const double t_x = pose.x();
  const double t_y = pose.y();
  const auto cols = static_cast<unsigned>(cols_);
  const auto rows = static_cast<unsigned>(rows_);
  const double off_map = off_map_cost_;
  double sum = 0.0;
  for (const Eigen::Vector2d& point : points) {
    const int x = roundToInt(c * point.x() - s * point.y() + t_x);
    const int y = roundToInt(s * point.x() + c * point.y() + t_y);
    if (static_cast<unsigned>(x) < cols && static_cast<unsigned>(y) < rows) {
      sum -= cost_of_cell(static_cast<std::size_t>(y) * cols + static_cast<std::size_t>(x));
    } else {
      sum -= off_map;
    }
  }
  return sum;
}

double HitCosts::scanLogLikelihood(const std::vector<Eigen::Vector2d>& points,
                                   const SE2& pose) const {
  if (indexed()) {
    const double* table = table_.data();
    const std::uint8_t* index = index_.data();
    return minusSumOfCosts(points, pose, [=](std::size_t cell) { return table[index[cell]]; });
  }
  const double* costs = cell_costs_.data();
  return minusSumOfCosts(points, pose, [=](std::size_t cell) { return costs[cell]; });
}

}  // namespace mrslam::fusion
