// The exhaustive search's grids (exhaustive_grids.hpp): the distances to the walls against
// OpenCV's exact distance transform, and the even sample of a map's cells against the sample
// taken from the list of all of them.

#include "exhaustive_grids.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
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

/// Each cell's distance to the nearest wall by brute force over every wall (the float square root
/// of the least squared distance, as OpenCV's exact transform gives it), infinite beyond `reach`.
std::vector<float> bruteForceDistances(const SearchGrid& grid, double reach) {
  std::vector<float> distances;
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      int least = std::numeric_limits<int>::max();
      for (int wy = 0; wy < grid.height; ++wy) {
        for (int wx = 0; wx < grid.width; ++wx) {
          if (grid.at(wx, wy) == GridClass::kWall) {
            least = std::min(least, (wx - x) * (wx - x) + (wy - y) * (wy - y));
          }
        }
      }
      const float d = least == std::numeric_limits<int>::max()
                          ? std::numeric_limits<float>::infinity()
                          : std::sqrt(static_cast<float>(least));
      distances.push_back(d <= reach ? d : std::numeric_limits<float>::infinity());
    }
  }
  return distances;
}

// Sparse walls mark only the cells within the reach of them; dense walls or a long reach take
// OpenCV's exact distance transform of the whole grid. Either way every distance must equal, bit
// for bit, the one found by brute force: reaches that are whole, fractional and none, no walls at
// all. (On this 61 × 47 grid, the last two take the transform, the others the marks.) The value
// grid, built on these distances, gives a wall's value where it is within reach and the open
// floor's penalty beyond.
TEST(ExhaustiveGridsTest, DistancesNearWallsAreTheExactDistances) {
  struct Variant {
    double wall_share;
    double reach;
  };
  const Variant variants[] = {{0.002, 2.0}, {0.02, 4.0}, {0.1, 2.5}, {0.05, 0.0},
                              {0.0, 2.0},   {0.3, 3.7},  {0.15, 6.0}};
  unsigned seed = 1;
  for (const Variant& variant : variants) {
    SCOPED_TRACE(testing::Message()
                 << "walls " << variant.wall_share << ", reach " << variant.reach);
    const SearchGrid grid = randomGrid(61, 47, variant.wall_share, seed++);
    const std::vector<float> distances = distancesNearWalls(grid, variant.reach);
    const std::vector<float> reference = bruteForceDistances(grid, variant.reach);
    ASSERT_EQ(distances.size(), reference.size());
    int differing = 0;
    for (std::size_t i = 0; i < distances.size(); ++i) {
      differing += distances[i] != reference[i];
    }
    EXPECT_EQ(differing, 0);

    ExhaustiveSearchSettings settings;
    settings.wall_reach = variant.reach;
    const int pad = 2;
    const LevelValues values =
        valueGrid(grid, pad, pad, grid.width + 2 * pad, grid.height + 2 * pad, settings);
    for (int y = 0; y < grid.height; ++y) {
      for (int x = 0; x < grid.width; ++x) {
        const double d = reference[static_cast<std::size_t>(y) * grid.width + x];
        const float value =
            values[static_cast<std::size_t>(y + pad) * (grid.width + 2 * pad) + x + pad];
        if (d <= variant.reach) {
          ASSERT_EQ(value, static_cast<float>(std::exp(-d * d / 2.0))) << x << ", " << y;
        } else if (grid.at(x, y) == GridClass::kFree) {
          ASSERT_EQ(value, -static_cast<float>(settings.free_penalty)) << x << ", " << y;
        } else {
          ASSERT_EQ(value, 0.0f) << x << ", " << y;
        }
      }
    }
  }
}

// Level h of a pyramid is the max of level 0 over the 2^h × 2^h window at each cell's low corner
// (0 beyond the grid). With stop_early, level h is set only on the rows the search can read:
// those within 2^h of the rows that hold values, every column of them.
TEST(ExhaustiveGridsTest, PyramidLevelsAreWindowMaximaOnEveryRowTheSearchReads) {
  for (const bool stop_early : {true, false}) {
    SCOPED_TRACE(stop_early ? "stop_early" : "every point summed");
    const SearchGrid grid = randomGrid(37, 29, 0.05, 3);
    ExhaustiveSearchSettings settings;
    settings.stop_early = stop_early;
    settings.depth = 4;
    const int pad = 40;
    {
      // Freed memory of NaNs, of each size a level can have, that the levels' unset values are
      // likely to be made from: a row the search reads but the pyramid left unset shows.
      std::vector<std::vector<float>> dirt;
      for (const int row_pad : {pad, 2 << settings.depth}) {
        const auto size =
            static_cast<std::size_t>((grid.width + 2 * pad) * (grid.height + 2 * row_pad));
        for (int i = 0; i < 12; ++i) {
          dirt.emplace_back(size, std::numeric_limits<float>::quiet_NaN());
        }
      }
    }
    const ValuePyramid pyramid = valuePyramid(grid, pad, settings);
    ASSERT_EQ(pyramid.walls.size(), 5u);
    const auto at = [&](const LevelValues& level, int x, int y) {
      return x < pyramid.stride && y < pyramid.rows
                 ? level[static_cast<std::size_t>(y) * pyramid.stride + x]
                 : 0.0f;
    };
    for (int h = 1; h <= settings.depth; ++h) {
      const int side = 1 << h;
      const int first_read = stop_early ? pyramid.first_valued_row[h] - side : 0;
      const int last_read = stop_early ? pyramid.last_valued_row + side : pyramid.rows - 1;
      ASSERT_GE(first_read, 0);
      ASSERT_LT(last_read, pyramid.rows);
      for (const bool walls : {true, false}) {
        const std::vector<LevelValues>& levels = walls ? pyramid.walls : pyramid.free;
        int differing = 0;
        for (int y = first_read; y <= last_read; ++y) {
          for (int x = 0; x < pyramid.stride; ++x) {
            float most = -std::numeric_limits<float>::infinity();
            for (int dy = 0; dy < side; ++dy) {
              for (int dx = 0; dx < side; ++dx) {
                most = std::max(most, at(levels[0], x + dx, y + dy));
              }
            }
            differing += at(levels[static_cast<std::size_t>(h)], x, y) != most;
          }
        }
        EXPECT_EQ(differing, 0) << "level " << h << (walls ? " walls" : " free");
      }
    }
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
