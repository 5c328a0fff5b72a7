// Thinning keeps connectivity and leaves one-cell-wide skeletons on known shapes.

#include "mrslam/fusion/merge/skeleton.hpp"

#include <gtest/gtest.h>

#include <array>
#include <opencv2/imgproc.hpp>
#include <random>
#include <vector>

#include "merge_test_maps.hpp"
#include "test_data.hpp"

namespace mrslam::fusion {
namespace {

int components(const cv::Mat& binary) {
  cv::Mat labels;
  return cv::connectedComponents(binary, labels, 8) - 1;  // minus the background
}

// 2 × 2 blocks fully set: spots two cells thick.
int thickSpots(const cv::Mat& binary) {
  int spots = 0;
  for (int y = 0; y + 1 < binary.rows; ++y) {
    for (int x = 0; x + 1 < binary.cols; ++x) {
      spots += binary.at<std::uint8_t>(y, x) && binary.at<std::uint8_t>(y, x + 1) &&
                       binary.at<std::uint8_t>(y + 1, x) && binary.at<std::uint8_t>(y + 1, x + 1)
                   ? 1
                   : 0;
    }
  }
  return spots;
}

bool oneCellWide(const cv::Mat& binary) {
  return thickSpots(binary) == 0;
}

cv::Mat canvas() {
  return cv::Mat(60, 80, CV_8U, cv::Scalar(0));
}

// Zhang & Suen by their definition (skeleton.hpp): each sub-iteration looks at every cell of the
// image, marks the removable ones, then removes them; the passes repeat until neither removes one.
int thinByEveryCell(cv::Mat& image) {
  const auto set = [&image](int x, int y) {
    return x >= 0 && y >= 0 && x < image.cols && y < image.rows && image.at<std::uint8_t>(y, x) != 0
               ? 1
               : 0;
  };
  const auto sub_iteration = [&](bool first) {
    std::vector<cv::Point> removed;
    for (int y = 0; y < image.rows; ++y) {
      for (int x = 0; x < image.cols; ++x) {
        // P2 … P9, clockwise from north.
        const std::array<int, 8> p = {set(x, y - 1),     set(x + 1, y - 1), set(x + 1, y),
                                      set(x + 1, y + 1), set(x, y + 1),     set(x - 1, y + 1),
                                      set(x - 1, y),     set(x - 1, y - 1)};
        int b = 0;
        int a = 0;
        for (std::size_t i = 0; i < 8; ++i) {
          b += p[i];
          a += p[i] == 0 && p[(i + 1) % 8] == 1 ? 1 : 0;
        }
        const bool corner = first ? p[0] * p[2] * p[4] == 0 && p[2] * p[4] * p[6] == 0
                                  : p[0] * p[2] * p[6] == 0 && p[0] * p[4] * p[6] == 0;
        if (set(x, y) && b >= 2 && b <= 6 && a == 1 && corner) {
          removed.emplace_back(x, y);
        }
      }
    }
    for (const cv::Point& cell : removed) {
      image.at<std::uint8_t>(cell) = 0;
    }
    return !removed.empty();
  };
  int passes = 0;
  bool changed = true;
  while (changed) {
    changed = sub_iteration(true);
    changed = sub_iteration(false) || changed;
    ++passes;
  }
  return passes;
}

TEST(MergeSkeletonTest, ThinningEqualsTheDefinitionCellForCell) {
  // Random blobs of free space (rectangles and discs, with holes) on images of several sizes,
  // touching the edges too: the thinning, which looks only at cells beside unset ones, leaves
  // exactly the cells, in exactly the passes, of looking at every cell every time.
  std::mt19937 rng(42);
  std::uniform_int_distribution<int> size(5, 90);
  for (int trial = 0; trial < 40; ++trial) {
    cv::Mat image(size(rng), size(rng), CV_8U, cv::Scalar(0));
    std::uniform_int_distribution<int> column(-5, image.cols + 5);
    std::uniform_int_distribution<int> row(-5, image.rows + 5);
    std::uniform_int_distribution<int> extent(1, 30);
    for (int shape = 0; shape < 12; ++shape) {
      const cv::Scalar value(shape % 4 == 3 ? 0 : 255);
      if (shape % 2 == 0) {
        cv::rectangle(image, cv::Rect(column(rng), row(rng), extent(rng), extent(rng)), value,
                      cv::FILLED);
      } else {
        cv::circle(image, cv::Point(column(rng), row(rng)), extent(rng) / 2, value, cv::FILLED);
      }
    }
    cv::Mat reference = image.clone();
    const int reference_passes = thinByEveryCell(reference);
    const int passes = thinZhangSuen(image);
    EXPECT_EQ(passes, reference_passes) << "trial " << trial;
    EXPECT_EQ(cv::countNonZero(image != reference), 0) << "trial " << trial;
  }
}

TEST(MergeSkeletonTest, AThickBarBecomesALineAlongItsMiddle) {
  cv::Mat bar = canvas();
  cv::rectangle(bar, cv::Rect(10, 20, 50, 9), cv::Scalar(255), cv::FILLED);
  thinZhangSuen(bar);
  EXPECT_EQ(components(bar), 1);
  EXPECT_TRUE(oneCellWide(bar));
  std::vector<cv::Point> cells;
  cv::findNonZero(bar, cells);
  const cv::Rect box = cv::boundingRect(cells);
  EXPECT_LE(box.height, 3);                          // a line, not a band
  EXPECT_GE(box.width, 40);                          // along the bar
  EXPECT_NEAR(box.y + box.height / 2.0, 24.5, 1.5);  // in its middle
}

TEST(MergeSkeletonTest, CorridorsKeepTheirConnectionsAndLoopsStayLoops) {
  cv::Mat corridors = canvas();  // an L of two corridors and a separate ring
  cv::rectangle(corridors, cv::Rect(5, 5, 6, 40), cv::Scalar(255), cv::FILLED);
  cv::rectangle(corridors, cv::Rect(5, 40, 35, 6), cv::Scalar(255), cv::FILLED);
  cv::rectangle(corridors, cv::Rect(50, 10, 25, 25), cv::Scalar(255), cv::FILLED);
  cv::rectangle(corridors, cv::Rect(57, 17, 11, 11), cv::Scalar(0), cv::FILLED);
  ASSERT_EQ(components(corridors), 2);
  thinZhangSuen(corridors);
  EXPECT_EQ(components(corridors), 2);  // thinning neither splits nor joins
  EXPECT_TRUE(oneCellWide(corridors));
  // The ring's skeleton still encloses its hole: the hole's centre is cut off from outside.
  cv::Mat background;
  cv::bitwise_not(corridors, background);
  cv::Mat labels;
  cv::connectedComponents(background, labels, 4);
  EXPECT_NE(labels.at<int>(22, 62), labels.at<int>(0, 0));
}

TEST(MergeSkeletonTest, ARealMapsFreeSpaceThinsWithoutBreakingApart) {
  MRSLAM_REQUIRE_SHARED_DATA("maps/freiburg-intel.pgm");
  const GridMap map = merge_test::loadMap(test::sharedDataPath("maps/freiburg-intel.pgm"));
  const SimilaritySettings settings;
  cv::Mat free(map.geometry.height, map.geometry.width, CV_8U, cv::Scalar(0));
  for (int y = 0; y < map.geometry.height; ++y) {
    for (int x = 0; x < map.geometry.width; ++x) {
      const std::int8_t value = map.at(x, y);
      free.at<std::uint8_t>(y, x) = value >= 0 && value <= settings.free_threshold ? 255 : 0;
    }
  }
  const cv::Mat skeleton = freeSpaceSkeleton(map, settings);
  const int cells = cv::countNonZero(skeleton);
  EXPECT_LT(cells, cv::countNonZero(free) / 5);
  // Thin: two cells thick only where Zhang & Suen's passes leave a junction so.
  EXPECT_LT(thickSpots(skeleton), cells / 200);
  // On free cells or on the islands of at most 4 other cells taken as free, nowhere else.
  cv::Mat allowed = free.clone();
  cv::Mat labels;
  cv::Mat stats;
  cv::Mat centroids;
  cv::connectedComponentsWithStats(free == 0, labels, stats, centroids, 4);
  for (int y = 0; y < free.rows; ++y) {
    for (int x = 0; x < free.cols; ++x) {
      const int label = labels.at<int>(y, x);
      if (label > 0 && stats.at<int>(label, cv::CC_STAT_AREA) <= 4) {
        allowed.at<std::uint8_t>(y, x) = 255;
      }
    }
  }
  cv::Mat outside;
  cv::bitwise_and(skeleton, ~allowed, outside);
  EXPECT_EQ(cv::countNonZero(outside), 0);
  EXPECT_LE(components(skeleton), components(free));
}

}  // namespace
}  // namespace mrslam::fusion
