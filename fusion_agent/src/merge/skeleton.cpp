#include "mrslam/fusion/merge/skeleton.hpp"

#include <array>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace mrslam::fusion {

namespace {

// P2…P9 of the cell at (x, y) (outside the image: not set), clockwise from north.
std::array<int, 8> neighbours(const cv::Mat& image, int x, int y) {
  static constexpr std::array<int, 8> kDx = {0, 1, 1, 1, 0, -1, -1, -1};
  static constexpr std::array<int, 8> kDy = {-1, -1, 0, 1, 1, 1, 0, -1};
  std::array<int, 8> p{};
  for (std::size_t i = 0; i < 8; ++i) {
    const int u = x + kDx[i];
    const int v = y + kDy[i];
    p[i] = u >= 0 && v >= 0 && u < image.cols && v < image.rows && image.at<std::uint8_t>(v, u) != 0
               ? 1
               : 0;
  }
  return p;
}

bool removable(const std::array<int, 8>& p, bool first_pass) {
  int set = 0;
  int transitions = 0;
  for (std::size_t i = 0; i < 8; ++i) {
    set += p[i];
    transitions += (p[i] == 0 && p[(i + 1) % 8] == 1) ? 1 : 0;
  }
  if (set < 2 || set > 6 || transitions != 1) {
    return false;
  }
  // p[0] = P2, p[2] = P4, p[4] = P6, p[6] = P8.
  if (first_pass) {
    return p[0] * p[2] * p[4] == 0 && p[2] * p[4] * p[6] == 0;
  }
  return p[0] * p[2] * p[6] == 0 && p[0] * p[4] * p[6] == 0;
}

// One sub-iteration: marks every removable cell first, then removes them all (in parallel).
bool thinPass(cv::Mat& image, bool first_pass) {
  std::vector<cv::Point> removed;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      if (image.at<std::uint8_t>(y, x) != 0 && removable(neighbours(image, x, y), first_pass)) {
        removed.emplace_back(x, y);
      }
    }
  }
  for (const cv::Point& cell : removed) {
    image.at<std::uint8_t>(cell) = 0;
  }
  return !removed.empty();
}

// Sets the 4-connected islands of unset cells of at most `max_cells` cells.
void fillSmallHoles(cv::Mat& binary, int max_cells) {
  if (max_cells <= 0) {
    return;
  }
  cv::Mat holes = binary == 0;
  cv::Mat labels;
  cv::Mat stats;
  cv::Mat centroids;
  const int count = cv::connectedComponentsWithStats(holes, labels, stats, centroids, 4);
  for (int y = 0; y < binary.rows; ++y) {
    for (int x = 0; x < binary.cols; ++x) {
      const int label = labels.at<int>(y, x);
      if (label > 0 && label < count && stats.at<int>(label, cv::CC_STAT_AREA) <= max_cells) {
        binary.at<std::uint8_t>(y, x) = 255;
      }
    }
  }
}

}  // namespace

int thinZhangSuen(cv::Mat& binary) {
  int passes = 0;
  bool changed = true;
  while (changed) {
    changed = thinPass(binary, true);
    changed = thinPass(binary, false) || changed;
    ++passes;
  }
  return passes;
}

cv::Mat freeSpaceSkeleton(const GridMap& map, const SimilaritySettings& settings,
                          int max_hole_cells) {
  cv::Mat free(map.geometry.height, map.geometry.width, CV_8U, cv::Scalar(0));
  for (int y = 0; y < map.geometry.height; ++y) {
    for (int x = 0; x < map.geometry.width; ++x) {
      const std::int8_t value = map.at(x, y);
      if (value >= 0 && value <= settings.free_threshold) {
        free.at<std::uint8_t>(y, x) = 255;
      }
    }
  }
  fillSmallHoles(free, max_hole_cells);
  thinZhangSuen(free);
  return free;
}

}  // namespace mrslam::fusion
