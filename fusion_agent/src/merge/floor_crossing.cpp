#include "mrslam/fusion/merge/floor_crossing.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <opencv2/imgproc.hpp>

namespace mrslam::fusion {

namespace {

// Distance of each cell of `map` to its nearest wall (cells; large on a map without walls).
cv::Mat distanceToWalls(const GridMap& map, const SimilaritySettings& classes) {
  cv::Mat not_wall(map.geometry.height, map.geometry.width, CV_8U, cv::Scalar(255));
  for (int y = 0; y < map.geometry.height; ++y) {
    std::uint8_t* row = not_wall.ptr<std::uint8_t>(y);
    for (int x = 0; x < map.geometry.width; ++x) {
      if (map.at(x, y) >= classes.occupied_threshold) {
        row[x] = 0;
      }
    }
  }
  cv::Mat distance;
  cv::distanceTransform(not_wall, distance, cv::DIST_L2, cv::DIST_MASK_5);
  return distance;
}

bool isFree(int value, const SimilaritySettings& classes) {
  return value >= 0 && value <= classes.free_threshold;
}

bool isKnown(int value, const SimilaritySettings& classes) {
  return isFree(value, classes) || value >= classes.occupied_threshold;
}

int largestRun(const cv::Mat& crossing) {
  cv::Mat labels;
  cv::Mat stats;
  cv::Mat centroids;
  const int count = cv::connectedComponentsWithStats(crossing, labels, stats, centroids, 8);
  int largest = 0;
  for (int label = 1; label < count; ++label) {
    largest = std::max(largest, stats.at<int>(label, cv::CC_STAT_AREA));
  }
  return largest;
}

}  // namespace

FloorCrossing floorCrossing(const GridMap& own, const GridMap& other,
                            const GridTransform& T_other_own, const SimilaritySettings& classes,
                            double clearance_cells) {
  FloorCrossing result;
  if (own.geometry.width <= 0 || other.geometry.width <= 0 || other.geometry.height <= 0) {
    return result;
  }
  const cv::Mat distance = distanceToWalls(other, classes);
  cv::Mat crossing(other.geometry.height, other.geometry.width, CV_8U, cv::Scalar(0));
  for (int y = 0; y < own.geometry.height; ++y) {
    for (int x = 0; x < own.geometry.width; ++x) {
      if (own.at(x, y) < classes.occupied_threshold) {
        continue;
      }
      const Eigen::Vector2d landed = T_other_own.apply(Eigen::Vector2d(x, y));
      const int u = static_cast<int>(std::floor(landed.x() + 0.5));
      const int v = static_cast<int>(std::floor(landed.y() + 0.5));
      if (u < 0 || v < 0 || u >= other.geometry.width || v >= other.geometry.height ||
          !isKnown(other.at(u, v), classes)) {
        continue;
      }
      ++result.walls_on_known;
      std::uint8_t& cell = crossing.ptr<std::uint8_t>(v)[u];
      if (cell == 0 && isFree(other.at(u, v), classes) &&
          distance.ptr<float>(v)[u] > clearance_cells) {
        cell = 255;
        ++result.crossing_cells;
      }
    }
  }
  result.run_cells = result.crossing_cells > 0 ? largestRun(crossing) : 0;
  return result;
}

}  // namespace mrslam::fusion
