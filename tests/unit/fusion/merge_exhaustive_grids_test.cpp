// The exhaustive search's grids (exhaustive_grids.hpp): the walls' value grid against one built
// from OpenCV's exact distance transform, and the even sample of a map's cells against the
// sample taken from the list of all of them.

#include "exhaustive_grids.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>
#include <random>

namespace mrslam::fusion::exhaustive {
namespace {

/// A grid of random classes: walls with probability `wall_share`, the rest free or unknown.
SearchGrid randomGrid(int width, int height, double wall_share, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> draw(0.0, 1.0);
  SearchGrid grid;
  grid.width = width;
  grid.height = height;
  for (int i = 0; i < width * height; ++i) {
    const double value = draw(random);
    grid.classes.push_back(value < wall_share
                               ? GridClass::kWall
                               : (value < 0.7 ? GridClass::kFree : GridClass::kUnknown));
  }
  return grid;
}

/// valueGrid() as it was built on cv::distanceTransform (exact Euclidean distances).
std::vector<float> referenceValueGrid(const SearchGrid& grid, int pad, int row_pad, int stride,
                                      int rows, const ExhaustiveSearchSettings& settings) {
  cv::Mat not_wall(grid.height, grid.width, CV_8U);
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      not_wall.at<std::uint8_t>(y, x) = grid.at(x, y) == GridClass::kWall ? 0 : 255;
    }
  }
  cv::Mat distance;
  cv::distanceTransform(not_wall, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  std::vector<float> values(static_cast<std::size_t>(stride) * rows, 0.0f);
  const double two_sigma_sq = 2.0 * settings.wall_sigma * settings.wall_sigma;
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      const double d = distance.at<float>(y, x);
      float value = 0.0f;
      if (d <= settings.wall_reach) {
        value = static_cast<float>(std::exp(-d * d / two_sigma_sq));
      } else if (grid.at(x, y) == GridClass::kFree) {
        value = -static_cast<float>(settings.free_penalty);
      }
      values[static_cast<std::size_t>(y + row_pad) * stride + static_cast<std::size_t>(x + pad)] =
          value;
    }
  }
  return values;
}

// Sparse walls mark only the cells within the reach of them; dense walls or a long reach take
// the distance transform of the whole grid. Either way every value must equal, bit for bit, the
// one the exact distance transform gives: reaches that are whole, fractional and none, padded or
// not. (On this 61 × 47 grid, the last two variants take the transform, the others the marks.)
TEST(ExhaustiveGridsTest, WallValuesEqualThoseOfAnExactDistanceTransform) {
  struct Variant {
    double wall_share;
    double reach;
    double sigma;
    int pad;
    int row_pad;
  };
  const Variant variants[] = {{0.002, 2.0, 1.0, 0, 0}, {0.02, 4.0, 2.0, 3, 1},
                              {0.1, 2.5, 1.0, 5, 2},   {0.05, 0.0, 1.0, 2, 2},
                              {0.0, 2.0, 1.0, 1, 1},   {0.3, 3.7, 1.5, 0, 4},
                              {0.15, 6.0, 2.0, 2, 0}};
  unsigned seed = 1;
  for (const Variant& variant : variants) {
    SCOPED_TRACE(testing::Message()
                 << "walls " << variant.wall_share << ", reach " << variant.reach);
    const SearchGrid grid = randomGrid(61, 47, variant.wall_share, seed++);
    ExhaustiveSearchSettings settings;
    settings.wall_reach = variant.reach;
    settings.wall_sigma = variant.sigma;
    const int stride = grid.width + 2 * variant.pad;
    const int rows = grid.height + 2 * variant.row_pad;
    const std::vector<float> values =
        valueGrid(grid, variant.pad, variant.row_pad, stride, rows, settings);
    const std::vector<float> reference =
        referenceValueGrid(grid, variant.pad, variant.row_pad, stride, rows, settings);
    ASSERT_EQ(values.size(), reference.size());
    int differing = 0;
    for (std::size_t i = 0; i < values.size(); ++i) {
      differing += values[i] != reference[i];
    }
    EXPECT_EQ(differing, 0);
  }
}

// The sample of a class is the i·n/k-th of its n cells in row order (k = the most kept): every
// cell when there are few, evenly spread when there are many; free cells next to walls left out.
TEST(ExhaustiveGridsTest, PointsAreAnEvenSampleOfTheirCells) {
  const SearchGrid grid = randomGrid(53, 41, 0.08, 7);
  ExhaustiveSearchSettings settings;
  settings.free_margin = 1;
  std::vector<Eigen::Vector2d> walls;
  std::vector<Eigen::Vector2d> free;
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      if (grid.at(x, y) == GridClass::kWall) {
        walls.emplace_back(x, y);
        continue;
      }
      bool near_wall = false;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const int nx = x + dx;
          const int ny = y + dy;
          near_wall |= nx >= 0 && ny >= 0 && nx < grid.width && ny < grid.height &&
                       grid.at(nx, ny) == GridClass::kWall;
        }
      }
      if (grid.at(x, y) == GridClass::kFree && !near_wall) {
        free.emplace_back(x, y);
      }
    }
  }
  ASSERT_GT(walls.size(), 100u);
  ASSERT_GT(free.size(), 50u);
  for (const int kept : {10, 97, 100000}) {
    SCOPED_TRACE(testing::Message() << "at most " << kept);
    settings.max_points = kept;
    settings.max_free_points = kept;
    const PointSet set = pointSet(grid, settings);
    const auto expectSample = [&](const std::vector<Eigen::Vector2d>& all,
                                  const std::vector<Eigen::Vector2d>& sample) {
      const std::size_t count = std::min(all.size(), static_cast<std::size_t>(kept));
      ASSERT_EQ(sample.size(), count);
      for (std::size_t i = 0; i < count; ++i) {
        EXPECT_EQ(sample[i] + set.centroid, all[i * all.size() / count]) << i;
      }
    };
    expectSample(walls, set.walls);
    expectSample(free, set.free);
  }
}

}  // namespace
}  // namespace mrslam::fusion::exhaustive
