#pragma once
// The grids of the exhaustive search (exhaustive_search.hpp, steps 1, 2 and the bounds of step 4):
// a map on the search grid, the points of `from`, and the value pyramids of `to` that the
// branch and bound reads.

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <utility>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/fusion/merge/exhaustive_search.hpp"
#include "mrslam/fusion/merge/similarity.hpp"

namespace mrslam::fusion::exhaustive {

/// The class of a search-grid cell.
enum class GridClass : std::uint8_t { kUnknown = 0, kFree = 1, kWall = 2 };

/// A map on the search grid: one class per grid cell, row-major.
struct SearchGrid {
  int width = 0;
  int height = 0;
  std::vector<GridClass> classes;
  GridClass at(int x, int y) const {
    return classes[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                   static_cast<std::size_t>(x)];
  }
};

/// `map` on a grid of `cell_size` cells (step 1 of exhaustive_search.hpp).
SearchGrid toSearchGrid(const GridMap& map, int cell_size, const SimilaritySettings& classes);

/// Step 2: the walls and the free cells of `from` about the walls' centroid, each an even
/// sample.
struct PointSet {
  std::vector<Eigen::Vector2d> walls;  ///< grid cells relative to `centroid`
  std::vector<Eigen::Vector2d> free;   ///< the same
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double radius = 0.0;
};

/// The wall and free points of a map on the search grid (step 2).
PointSet pointSet(const SearchGrid& grid, const ExhaustiveSearchSettings& settings);

/// An allocator that leaves the values it makes room for unset (std::vector's resize and size
/// constructor would zero them): the pyramid's coarser levels set only the rows that are read.
template <typename T>
struct UnsetAllocator : std::allocator<T> {
  template <typename U>
  struct rebind {
    using other = UnsetAllocator<U>;
  };
  UnsetAllocator() = default;
  template <typename U>
  explicit UnsetAllocator(const UnsetAllocator<U>& /*other*/) noexcept {}
  template <typename U>
  void construct(U* at) noexcept {
    ::new (static_cast<void*>(at)) U;  // default-initialised: a float stays unset
  }
  template <typename U, typename... Args>
  void construct(U* at, Args&&... args) {
    ::new (static_cast<void*>(at)) U(std::forward<Args>(args)...);
  }
};

/// The values of one grid of a pyramid, row-major.
using LevelValues = std::vector<float, UnsetAllocator<float>>;

/// Step 1 and the bounds of step 4: the value grid of `to` padded with unknown cells, and its
/// max-pooled versions. Padded by `pad` columns left and right and `row_pad` rows above and below:
/// `pad` too when the search sums every point; 2^(depth+1) when it leaves out the points whose
/// rows hold no values (offsetsOnRows), as the rows it reads then lie that near the grid's.
struct ValuePyramid {
  int pad = 0;      ///< columns of padding on each side
  int row_pad = 0;  ///< rows of padding on each side
  int stride = 0;
  int rows = 0;
  std::vector<LevelValues> walls;  ///< level h: max over 2^h × 2^h windows (low corner)
  std::vector<LevelValues> free;   ///< the same for `from`'s free cells
  /// Level h is 0 on every row outside [first_valued_row[h], last_valued_row] (both grids). With
  /// stop_early, level h ≥ 1 is set only on the rows the search reads: those within 2^h of them.
  std::vector<int> first_valued_row;
  int last_valued_row = 0;
};

/// Each grid cell's Euclidean distance (grid cells) to the nearest wall where it is at most
/// `reach`, else infinite (row-major). Sparse walls mark the cells within `reach` of them; where
/// that would visit more than 8 cells per cell of the grid (dense walls, a long reach), the whole
/// grid's exact distance transform is taken. Either way a distance is the float square root of
/// an integer, as OpenCV's exact transform (DIST_MASK_PRECISE) gives it.
std::vector<float> distancesNearWalls(const SearchGrid& grid, double reach);

/// What a free cell of `from` scores on each cell of `to`.
LevelValues freeValueGrid(const SearchGrid& grid, int pad, int row_pad, int stride, int rows,
                          const ExhaustiveSearchSettings& settings);

/// What a wall of `from` scores on each cell of `to`.
LevelValues valueGrid(const SearchGrid& grid, int pad, int row_pad, int stride, int rows,
                      const ExhaustiveSearchSettings& settings);

/// The value grids of `to` on its search grid, padded by `pad` columns, and their pyramids.
ValuePyramid valuePyramid(const SearchGrid& grid, int pad,
                          const ExhaustiveSearchSettings& settings);

}  // namespace mrslam::fusion::exhaustive
