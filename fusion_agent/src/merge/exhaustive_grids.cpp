#include "exhaustive_grids.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace mrslam::fusion::exhaustive {

namespace {

/// The grid's walls: 255 on a wall, else 0.
cv::Mat wallImage(const SearchGrid& grid) {
  cv::Mat walls(grid.height, grid.width, CV_8U);  // continuous: one row after the other
  std::uint8_t* const out = walls.ptr<std::uint8_t>(0);
  for (std::size_t i = 0; i < grid.classes.size(); ++i) {
    out[i] = grid.classes[i] == GridClass::kWall ? 255 : 0;
  }
  return walls;
}

/// Cells with a wall within `reach` grid cells (square, the cell itself included): 255, else 0.
cv::Mat nearWalls(const SearchGrid& grid, int reach) {
  cv::Mat walls = wallImage(grid);
  if (reach <= 0) {
    return walls;
  }
  cv::Mat near;
  cv::dilate(walls, near, cv::getStructuringElement(cv::MORPH_RECT, {2 * reach + 1, 2 * reach + 1}),
             {-1, -1}, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  return near;
}

/// Whether each cell of row `y` is of class `wanted` and, when `near` holds any, not near a wall.
void markWanted(const SearchGrid& grid, GridClass wanted, const cv::Mat& near, int y,
                std::vector<std::uint8_t>& marks) {
  const GridClass* row = grid.classes.data() + static_cast<std::size_t>(y) * grid.width;
  for (int x = 0; x < grid.width; ++x) {
    marks[static_cast<std::size_t>(x)] = row[x] == wanted ? 1 : 0;
  }
  if (!near.empty()) {
    const std::uint8_t* near_row = near.ptr<std::uint8_t>(y);
    for (int x = 0; x < grid.width; ++x) {
      marks[static_cast<std::size_t>(x)] &= near_row[x] == 0 ? 1 : 0;
    }
  }
}

/// An even sample of the cells of class `wanted`; free cells only away from walls (a cell of
/// misalignment must not put them on the other map's walls). Of the n such cells in row order,
/// the i·n/k-th for i < k = min(n, max_count).
std::vector<Eigen::Vector2d> cellsOf(const SearchGrid& grid, GridClass wanted, int max_count,
                                     int wall_margin) {
  const cv::Mat near = wanted == GridClass::kWall ? cv::Mat() : nearWalls(grid, wall_margin);
  std::vector<std::uint8_t> marks(static_cast<std::size_t>(grid.width));
  std::vector<int> per_row(static_cast<std::size_t>(grid.height), 0);
  std::size_t all = 0;
  for (int y = 0; y < grid.height; ++y) {
    markWanted(grid, wanted, near, y, marks);
    int count = 0;
    for (const std::uint8_t mark : marks) {
      count += mark;
    }
    per_row[static_cast<std::size_t>(y)] = count;
    all += static_cast<std::size_t>(count);
  }
  const std::size_t kept = std::min(all, static_cast<std::size_t>(std::max(0, max_count)));
  std::vector<Eigen::Vector2d> sample;
  sample.reserve(kept);
  std::size_t seen = 0;  // wanted cells before the row
  for (int y = 0; y < grid.height && sample.size() < kept; ++y) {
    const std::size_t in_row = static_cast<std::size_t>(per_row[static_cast<std::size_t>(y)]);
    if (sample.size() * all / kept >= seen + in_row) {
      seen += in_row;  // the next pick lies on a later row
      continue;
    }
    markWanted(grid, wanted, near, y, marks);
    std::size_t next_pick = sample.size() * all / kept;  // the wanted cell picked next
    for (int x = 0; x < grid.width && sample.size() < kept; ++x) {
      if (marks[static_cast<std::size_t>(x)] == 0) {
        continue;
      }
      if (seen == next_pick) {
        sample.emplace_back(x, y);
        next_pick = sample.size() * all / kept;
      }
      ++seen;
    }
  }
  return sample;
}

/// The distance of a squared distance as a float, as an exact distance transform gives it.
float floatDistance(int squared) {
  return std::sqrt(static_cast<float>(squared));
}

/// Marks of the cells within `reach` of each wall, each cell's least squared distance kept (on a
/// grid padded by the reach, so that no mark needs a bounds check).
std::vector<float> stampedDistances(const SearchGrid& grid, const std::vector<cv::Point>& walls,
                                    double reach) {
  const int radius = static_cast<int>(std::floor(reach));
  const int stride = grid.width + 2 * radius;
  std::vector<std::ptrdiff_t> offsets;
  std::vector<int> offset_squares;
  for (int dy = -radius; dy <= radius; ++dy) {
    for (int dx = -radius; dx <= radius; ++dx) {
      if (floatDistance(dx * dx + dy * dy) <= reach) {
        offsets.push_back(static_cast<std::ptrdiff_t>(dy) * stride + dx);
        offset_squares.push_back(dx * dx + dy * dy);
      }
    }
  }
  constexpr int kNone = std::numeric_limits<int>::max();
  std::vector<int> squared(static_cast<std::size_t>(stride) * (grid.height + 2 * radius), kNone);
  for (const cv::Point& wall : walls) {
    int* at =
        squared.data() + static_cast<std::ptrdiff_t>(wall.y + radius) * stride + wall.x + radius;
    for (std::size_t i = 0; i < offsets.size(); ++i) {
      at[offsets[i]] = std::min(at[offsets[i]], offset_squares[i]);
    }
  }
  std::vector<float> distances(grid.classes.size(), std::numeric_limits<float>::infinity());
  for (int y = 0; y < grid.height; ++y) {
    const int* row = squared.data() + static_cast<std::ptrdiff_t>(y + radius) * stride + radius;
    float* out = distances.data() + static_cast<std::size_t>(y) * grid.width;
    for (int x = 0; x < grid.width; ++x) {
      if (row[x] != kNone) {
        out[x] = floatDistance(row[x]);
      }
    }
  }
  return distances;
}

/// The exact distance transform of the whole grid, infinite beyond `reach`.
std::vector<float> transformedDistances(const SearchGrid& grid, double reach) {
  cv::Mat not_wall;
  cv::bitwise_not(wallImage(grid), not_wall);
  cv::Mat distance;
  cv::distanceTransform(not_wall, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  std::vector<float> distances(grid.classes.size(), std::numeric_limits<float>::infinity());
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      const float d = distance.at<float>(y, x);
      if (d <= reach) {
        distances[static_cast<std::size_t>(y) * grid.width + static_cast<std::size_t>(x)] = d;
      }
    }
  }
  return distances;
}

/// The cells of a padded grid that may hold a value other than 0: [x_begin, x_end) ×
/// [y_begin, y_end); 0 everywhere else.
struct ValuedArea {
  int x_begin = 0;
  int x_end = 0;
  int y_begin = 0;
  int y_end = 0;
};

/// The max over each cell's 2 × 2 corners `step` apart of `finer` (whose values are 0 outside
/// `area`); `area` becomes the coarser grid's (a window reaching into it from below or left).
/// Only the rows within `read_rows` of the new area are set (all rows when it is negative).
LevelValues maxPooled(const LevelValues& finer, int stride, int rows, int step, ValuedArea& area,
                      int read_rows) {
  area.x_begin = std::max(0, area.x_begin - step);
  area.y_begin = std::max(0, area.y_begin - step);
  LevelValues coarser(finer.size());  // unset: each row read is set below
  const int set_begin = read_rows < 0 ? 0 : std::max(0, area.y_begin - read_rows);
  const int set_end = read_rows < 0 ? rows : std::min(rows, area.y_end + read_rows);
  for (int y = set_begin; y < set_end; ++y) {
    float* row = coarser.data() + static_cast<std::size_t>(y) * stride;
    if (y < area.y_begin || y >= area.y_end) {
      std::fill(row, row + stride, 0.0f);
      continue;
    }
    std::fill(row, row + area.x_begin, 0.0f);
    std::fill(row + area.x_end, row + stride, 0.0f);
    for (int x = area.x_begin; x < area.x_end; ++x) {
      float best = finer[static_cast<std::size_t>(y) * stride + x];
      const bool right = x + step < stride;
      const bool up = y + step < rows;
      if (right) {
        best = std::max(best, finer[static_cast<std::size_t>(y) * stride + x + step]);
      }
      if (up) {
        best = std::max(best, finer[static_cast<std::size_t>(y + step) * stride + x]);
      }
      if (right && up) {
        best = std::max(best, finer[static_cast<std::size_t>(y + step) * stride + x + step]);
      }
      row[x] = best;
    }
  }
  return coarser;
}

}  // namespace

std::vector<float> distancesNearWalls(const SearchGrid& grid, double reach) {
  std::vector<cv::Point> walls;
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      if (grid.at(x, y) == GridClass::kWall) {
        walls.emplace_back(x, y);
      }
    }
  }
  const double side = 2.0 * std::floor(reach) + 1.0;
  constexpr double kMostVisitsPerCell = 8.0;
  if (static_cast<double>(walls.size()) * side * side >
      kMostVisitsPerCell * static_cast<double>(grid.classes.size())) {
    return transformedDistances(grid, reach);
  }
  return stampedDistances(grid, walls, reach);
}

SearchGrid toSearchGrid(const GridMap& map, int cell_size, const SimilaritySettings& classes) {
  SearchGrid grid;
  grid.width = (map.geometry.width + cell_size - 1) / cell_size;
  grid.height = (map.geometry.height + cell_size - 1) / cell_size;
  grid.classes.assign(static_cast<std::size_t>(grid.width) * grid.height, GridClass::kUnknown);
  for (int y = 0; y < map.geometry.height; ++y) {
    for (int x = 0; x < map.geometry.width; ++x) {
      const int value = map.at(x, y);
      GridClass& cell = grid.classes[static_cast<std::size_t>(y / cell_size) * grid.width +
                                     static_cast<std::size_t>(x / cell_size)];
      if (classes.isOccupied(value)) {
        cell = GridClass::kWall;
      } else if (classes.isFree(value) && cell == GridClass::kUnknown) {
        cell = GridClass::kFree;
      }
    }
  }
  return grid;
}

PointSet pointSet(const SearchGrid& grid, const ExhaustiveSearchSettings& settings) {
  PointSet set;
  set.walls = cellsOf(grid, GridClass::kWall, settings.max_points, 0);
  if (set.walls.empty()) {
    return set;
  }
  set.free = cellsOf(grid, GridClass::kFree, settings.max_free_points, settings.free_margin);
  for (const Eigen::Vector2d& wall : set.walls) {
    set.centroid += wall;
  }
  set.centroid = (set.centroid / static_cast<double>(set.walls.size())).array().round();
  for (std::vector<Eigen::Vector2d>* points : {&set.walls, &set.free}) {
    for (Eigen::Vector2d& point : *points) {
      point -= set.centroid;
      set.radius = std::max(set.radius, point.norm());
    }
  }
  return set;
}

LevelValues freeValueGrid(const SearchGrid& grid, int pad, int row_pad, int stride, int rows,
                          const ExhaustiveSearchSettings& settings) {
  LevelValues values(static_cast<std::size_t>(stride) * rows, 0.0f);
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      const GridClass cell = grid.at(x, y);
      values[static_cast<std::size_t>(y + row_pad) * stride + static_cast<std::size_t>(x + pad)] =
          cell == GridClass::kFree
              ? static_cast<float>(settings.free_weight)
              : (cell == GridClass::kWall ? -static_cast<float>(settings.conflict_penalty) : 0.0f);
    }
  }
  return values;
}

LevelValues valueGrid(const SearchGrid& grid, int pad, int row_pad, int stride, int rows,
                      const ExhaustiveSearchSettings& settings) {
  const std::vector<float> distances = distancesNearWalls(grid, settings.wall_reach);
  LevelValues values(static_cast<std::size_t>(stride) * rows, 0.0f);
  const double two_sigma_sq = 2.0 * settings.wall_sigma * settings.wall_sigma;
  const auto wallValue = [&](double d) {
    return static_cast<float>(std::exp(-d * d / two_sigma_sq));
  };
  // A distance is the square root of a whole number of squared cells (distancesNearWalls), so
  // few distances occur: each one's value is worked out once, by the same formula.
  constexpr int kMostSquares = 4096;
  std::vector<float> value_of_square;
  for (int k = 0; k < kMostSquares && floatDistance(k) <= settings.wall_reach; ++k) {
    value_of_square.push_back(wallValue(floatDistance(k)));
  }
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      const float distance = distances[static_cast<std::size_t>(y) * grid.width + x];
      const double d = distance;
      float value = 0.0f;
      if (d <= settings.wall_reach) {
        const long k = std::lround(d * d);
        value = k < static_cast<long>(value_of_square.size()) &&
                        floatDistance(static_cast<int>(k)) == distance
                    ? value_of_square[static_cast<std::size_t>(k)]
                    : wallValue(d);
      } else if (grid.at(x, y) == GridClass::kFree) {
        value = -static_cast<float>(settings.free_penalty);
      }
      values[static_cast<std::size_t>(y + row_pad) * stride + static_cast<std::size_t>(x + pad)] =
          value;
    }
  }
  return values;
}

ValuePyramid valuePyramid(const SearchGrid& grid, int pad,
                          const ExhaustiveSearchSettings& settings) {
  ValuePyramid pyramid;
  pyramid.pad = pad;
  pyramid.row_pad = settings.stop_early ? std::min(pad, 2 << settings.depth) : pad;
  pyramid.stride = grid.width + 2 * pad;
  pyramid.rows = grid.height + 2 * pyramid.row_pad;
  const int row_pad = pyramid.row_pad;
  pyramid.walls.push_back(valueGrid(grid, pad, row_pad, pyramid.stride, pyramid.rows, settings));
  pyramid.free.push_back(freeValueGrid(grid, pad, row_pad, pyramid.stride, pyramid.rows, settings));
  ValuedArea walls{pad, pad + grid.width, row_pad, row_pad + grid.height};
  ValuedArea free = walls;
  pyramid.first_valued_row.push_back(walls.y_begin);
  pyramid.last_valued_row = walls.y_end - 1;
  for (int h = 1; h <= settings.depth; ++h) {
    // A node reading level h sums its points' rows and the rows 2^h above them; stop_early
    // leaves out the points whose rows hold no values (offsetsOnRows).
    const int read_rows = settings.stop_early ? 1 << h : -1;
    pyramid.walls.push_back(maxPooled(pyramid.walls.back(), pyramid.stride, pyramid.rows,
                                      1 << (h - 1), walls, read_rows));
    pyramid.free.push_back(maxPooled(pyramid.free.back(), pyramid.stride, pyramid.rows,
                                     1 << (h - 1), free, read_rows));
    pyramid.first_valued_row.push_back(walls.y_begin);
  }
  return pyramid;
}

}  // namespace mrslam::fusion::exhaustive
