#include "mrslam/fusion/merge/skeleton.hpp"

#include <array>
#include <opencv2/imgproc.hpp>
#include <utility>
#include <vector>

namespace mrslam::fusion {

namespace {

bool isSet(const cv::Mat& image, int x, int y) {
  return x >= 0 && y >= 0 && x < image.cols && y < image.rows && image.at<std::uint8_t>(y, x) != 0;
}

// P2…P9 of the cell at (x, y) (outside the image: not set), clockwise from north.
std::array<int, 8> neighbours(const cv::Mat& image, int x, int y) {
  static constexpr std::array<int, 8> kDx = {0, 1, 1, 1, 0, -1, -1, -1};
  static constexpr std::array<int, 8> kDy = {-1, -1, 0, 1, 1, 1, 0, -1};
  std::array<int, 8> p{};
  for (std::size_t i = 0; i < 8; ++i) {
    p[i] = isSet(image, x + kDx[i], y + kDy[i]) ? 1 : 0;
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

// The set cells a sub-iteration may remove: those with an unset neighbour (outside the image
// counts as unset). A cell whose eight neighbours are all set has B(P) = 8 and stays; it can
// only become removable once a neighbour is removed. `listed` marks the cells listed.
class BorderCells {
 public:
  explicit BorderCells(const cv::Mat& image) : listed_(cv::Mat::zeros(image.size(), CV_8U)) {
    for (int y = 0; y < image.rows; ++y) {
      for (int x = 0; x < image.cols; ++x) {
        if (image.at<std::uint8_t>(y, x) != 0 && hasUnsetNeighbour(image, x, y)) {
          add(x, y);
        }
      }
    }
  }

  const std::vector<cv::Point>& cells() const { return cells_; }

  /// After `removed` were unset: drops them and lists their set neighbours.
  void update(const cv::Mat& image, const std::vector<cv::Point>& removed) {
    std::vector<cv::Point> kept;
    kept.reserve(cells_.size());
    for (const cv::Point& cell : cells_) {
      if (image.at<std::uint8_t>(cell) != 0) {
        kept.push_back(cell);
      }
    }
    cells_ = std::move(kept);
    for (const cv::Point& cell : removed) {
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int x = cell.x + dx;
          const int y = cell.y + dy;
          if (isSet(image, x, y) && listed_.at<std::uint8_t>(y, x) == 0) {
            add(x, y);
          }
        }
      }
    }
  }

 private:
  static bool hasUnsetNeighbour(const cv::Mat& image, int x, int y) {
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        if (!isSet(image, x + dx, y + dy)) {
          return true;
        }
      }
    }
    return false;
  }
  void add(int x, int y) {
    listed_.at<std::uint8_t>(y, x) = 1;
    cells_.emplace_back(x, y);
  }

  cv::Mat listed_;
  std::vector<cv::Point> cells_;
};

// One sub-iteration: marks every removable cell first, then removes them all (in parallel).
// Only border cells can be removable, so only they are looked at.
bool thinPass(cv::Mat& image, bool first_pass, BorderCells& border) {
  std::vector<cv::Point> removed;
  for (const cv::Point& cell : border.cells()) {
    if (removable(neighbours(image, cell.x, cell.y), first_pass)) {
      removed.push_back(cell);
    }
  }
  for (const cv::Point& cell : removed) {
    image.at<std::uint8_t>(cell) = 0;
  }
  border.update(image, removed);
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
  BorderCells border(binary);
  int passes = 0;
  bool changed = true;
  while (changed) {
    changed = thinPass(binary, true, border);
    changed = thinPass(binary, false, border) || changed;
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
