#include "exhaustive_grids.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace mrslam::fusion::exhaustive {

namespace {

/// Cells with a wall within `reach` grid cells (square, the cell itself included): 255, else 0.
cv::Mat nearWalls(const SearchGrid& grid, int reach) {
  cv::Mat walls(grid.height, grid.width, CV_8U);
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      walls.at<std::uint8_t>(y, x) = grid.at(x, y) == GridClass::kWall ? 255 : 0;
    }
  }
  if (reach <= 0) {
    return walls;
  }
  cv::Mat near;
  cv::dilate(walls, near, cv::getStructuringElement(cv::MORPH_RECT, {2 * reach + 1, 2 * reach + 1}),
             {-1, -1}, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
  return near;
}

/// An even sample of the cells of class `wanted`; free cells only away from walls (a cell of
/// misalignment must not put them on the other map's walls).
std::vector<Eigen::Vector2d> cellsOf(const SearchGrid& grid, GridClass wanted, int max_count,
                                     int wall_margin) {
  const cv::Mat near = wanted == GridClass::kWall ? cv::Mat() : nearWalls(grid, wall_margin);
  std::vector<Eigen::Vector2d> all;
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      if (grid.at(x, y) == wanted && (near.empty() || near.at<std::uint8_t>(y, x) == 0)) {
        all.emplace_back(x, y);
      }
    }
  }
  const std::size_t kept = std::min(all.size(), static_cast<std::size_t>(max_count));
  std::vector<Eigen::Vector2d> sample;
  for (std::size_t i = 0; i < kept; ++i) {
    sample.push_back(all[i * all.size() / kept]);
  }
  return sample;
}

/// Each grid cell's distance (grid cells) to the nearest wall.
cv::Mat distanceToWalls(const SearchGrid& grid) {
  cv::Mat not_wall(grid.height, grid.width, CV_8U);
  for (int y = 0; y < grid.height; ++y) {
    for (int x = 0; x < grid.width; ++x) {
      not_wall.at<std::uint8_t>(y, x) = grid.at(x, y) == GridClass::kWall ? 0 : 255;
    }
  }
  cv::Mat distance;
  cv::distanceTransform(not_wall, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
  return distance;
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
std::vector<float> maxPooled(const std::vector<float>& finer, int stride, int rows, int step,
                             ValuedArea& area) {
  area.x_begin = std::max(0, area.x_begin - step);
  area.y_begin = std::max(0, area.y_begin - step);
  std::vector<float> coarser(finer.size(), 0.0f);
  for (int y = area.y_begin; y < area.y_end; ++y) {
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
      coarser[static_cast<std::size_t>(y) * stride + x] = best;
    }
  }
  return coarser;
}

}  // namespace

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
      if (value >= classes.occupied_threshold) {
        cell = GridClass::kWall;
      } else if (value >= 0 && value <= classes.free_threshold && cell == GridClass::kUnknown) {
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

std::vector<float> freeValueGrid(const SearchGrid& grid, int pad, int row_pad, int stride, int rows,
                                 const ExhaustiveSearchSettings& settings) {
  std::vector<float> values(static_cast<std::size_t>(stride) * rows, 0.0f);
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

std::vector<float> valueGrid(const SearchGrid& grid, int pad, int row_pad, int stride, int rows,
                             const ExhaustiveSearchSettings& settings) {
  const cv::Mat distance = distanceToWalls(grid);
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
    pyramid.walls.push_back(
        maxPooled(pyramid.walls.back(), pyramid.stride, pyramid.rows, 1 << (h - 1), walls));
    pyramid.free.push_back(
        maxPooled(pyramid.free.back(), pyramid.stride, pyramid.rows, 1 << (h - 1), free));
    pyramid.first_valued_row.push_back(walls.y_begin);
  }
  return pyramid;
}

}  // namespace mrslam::fusion::exhaustive
