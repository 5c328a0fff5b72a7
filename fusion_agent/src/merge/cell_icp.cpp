// Step 9 of seed_merger.hpp: the chosen transform refined below the cell and the polish step by
// point-to-point ICP between the two maps' occupied cells. The discrete searches of blocks 7-8
// move in whole cells and quarter degrees over a similarity score that is flat near its top;
// walls fitted to walls settle the last cell and degree.

#include <opencv2/imgproc.hpp>

#include "mrslam/fusion/merge/similarity.hpp"
#include "seed_stages.hpp"

namespace mrslam::fusion::seed {

namespace {

constexpr int kMargin = 8;  // cells around `to`'s walls where nearest walls are looked up

// The rigid transform (rotation, translation) that best maps `from` onto `to` (least squares).
GridTransform fitRigid(const std::vector<Eigen::Vector2d>& from,
                       const std::vector<Eigen::Vector2d>& to) {
  Eigen::Vector2d mean_from = Eigen::Vector2d::Zero();
  Eigen::Vector2d mean_to = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < from.size(); ++i) {
    mean_from += from[i];
    mean_to += to[i];
  }
  mean_from /= static_cast<double>(from.size());
  mean_to /= static_cast<double>(to.size());
  double cross = 0.0;
  double dot = 0.0;
  for (std::size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector2d a = from[i] - mean_from;
    const Eigen::Vector2d b = to[i] - mean_to;
    dot += a.dot(b);
    cross += a.x() * b.y() - a.y() * b.x();
  }
  GridTransform fit;
  fit.theta_rad = std::atan2(cross, dot);
  const double c = std::cos(fit.theta_rad);
  const double s = std::sin(fit.theta_rad);
  fit.t_cells = mean_to - Eigen::Vector2d(c * mean_from.x() - s * mean_from.y(),
                                          s * mean_from.x() + c * mean_from.y());
  return fit;
}

}  // namespace

NearestWall::NearestWall(const std::vector<CellSample>& walls) {
  if (walls.empty()) {
    return;
  }
  cv::Point low(walls.front().x, walls.front().y);
  cv::Point high = low;
  for (const CellSample& wall : walls) {
    low = {std::min(low.x, wall.x), std::min(low.y, wall.y)};
    high = {std::max(high.x, wall.x), std::max(high.y, wall.y)};
  }
  origin_ = low - cv::Point(kMargin, kMargin);
  cv::Mat free(high.y - low.y + 1 + 2 * kMargin, high.x - low.x + 1 + 2 * kMargin, CV_8U,
               cv::Scalar(1));
  for (const CellSample& wall : walls) {
    free.at<std::uint8_t>(wall.y - origin_.y, wall.x - origin_.x) = 0;
  }
  cv::Mat distance;  // only the labels are looked up
  cv::distanceTransform(free, distance, labels_, cv::DIST_L2, cv::DIST_MASK_5,
                        cv::DIST_LABEL_PIXEL);
  wall_of_label_.assign(static_cast<std::size_t>(walls.size()) + 1, cv::Point());
  for (int y = 0; y < free.rows; ++y) {
    for (int x = 0; x < free.cols; ++x) {
      if (free.at<std::uint8_t>(y, x) == 0) {
        const int label = labels_.at<int>(y, x);
        if (label >= 0 && static_cast<std::size_t>(label) < wall_of_label_.size()) {
          wall_of_label_[static_cast<std::size_t>(label)] = cv::Point(x, y) + origin_;
        }
      }
    }
  }
}

std::vector<Eigen::Vector2d> occupiedCells(const std::vector<CellSample>& samples,
                                           const ComparisonTables& tables) {
  std::vector<Eigen::Vector2d> occupied;
  for (const CellSample& sample : samples) {
    if (tables.isOccupied(sample.code)) {
      occupied.emplace_back(sample.x, sample.y);
    }
  }
  return occupied;
}

std::optional<Eigen::Vector2d> NearestWall::near(const Eigen::Vector2d& point,
                                                 double max_distance) const {
  const int x = roundToInt(point.x()) - origin_.x;
  const int y = roundToInt(point.y()) - origin_.y;
  if (labels_.empty() || x < 0 || y < 0 || x >= labels_.cols || y >= labels_.rows) {
    return std::nullopt;
  }
  const int label = labels_.ptr<int>(y)[x];
  if (label < 0 || static_cast<std::size_t>(label) >= wall_of_label_.size()) {
    return std::nullopt;
  }
  const cv::Point wall = wall_of_label_[static_cast<std::size_t>(label)];
  const Eigen::Vector2d nearest(wall.x, wall.y);
  if ((nearest - point).norm() > max_distance) {
    return std::nullopt;
  }
  return nearest;
}

GridTransform refineOnWalls(const GridTransform& T_to_from, const SearchInputs& inputs,
                            const SeedMergerSettings& settings) {
  if (!inputs.nearest_wall_to) {
    return T_to_from;  // the inputs were prepared without the wall ICP
  }
  const std::vector<Eigen::Vector2d>& walls_from = inputs.occupied_from;
  const NearestWall& nearest = *inputs.nearest_wall_to;
  GridTransform estimate = T_to_from;
  for (int iteration = 0; iteration < settings.wall_icp_iterations; ++iteration) {
    std::vector<Eigen::Vector2d> matched_from;
    std::vector<Eigen::Vector2d> matched_to;
    matched_from.reserve(walls_from.size());
    matched_to.reserve(walls_from.size());
    const CellMapping to_of(estimate);
    for (const Eigen::Vector2d& wall : walls_from) {
      if (const auto target = nearest.near(to_of(wall), settings.wall_icp_distance_cells)) {
        matched_from.push_back(wall);
        matched_to.push_back(*target);
      }
    }
    if (matched_from.size() < 10) {
      return T_to_from;  // too little overlap of walls to refine on
    }
    const GridTransform next = fitRigid(matched_from, matched_to);
    const double moved = (next.t_cells - estimate.t_cells).norm() +
                         std::abs(next.theta_rad - estimate.theta_rad) * 100.0;
    estimate = next;
    if (moved < 1e-3) {
      break;
    }
  }
  return estimate;
}

}  // namespace mrslam::fusion::seed
