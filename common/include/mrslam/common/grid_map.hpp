#pragma once
// GridMap: an occupancy grid as int8 values, the form maps take on the wire and in files.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace mrslam {

/// Where a grid lies: cell (cx, cy) covers [origin + (cx, cy) * resolution, + resolution) on each
/// axis of the map frame. Cells are row-major with row 0 at the bottom (smallest y).
struct GridGeometry {
  double resolution_m = 0.05;
  int width = 0;                                       ///< cells along x
  int height = 0;                                      ///< cells along y
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  ///< map-frame corner of cell (0, 0)

  std::size_t cellCount() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  bool contains(int cx, int cy) const { return cx >= 0 && cy >= 0 && cx < width && cy < height; }
  std::size_t index(int cx, int cy) const {
    return static_cast<std::size_t>(cy) * static_cast<std::size_t>(width) +
           static_cast<std::size_t>(cx);
  }
  /// Map-frame centre of a cell.
  Eigen::Vector2d cellCenter(int cx, int cy) const {
    return origin_m + Eigen::Vector2d((cx + 0.5) * resolution_m, (cy + 0.5) * resolution_m);
  }
  bool operator==(const GridGeometry& other) const {
    return resolution_m == other.resolution_m && width == other.width && height == other.height &&
           origin_m == other.origin_m;
  }
  bool operator!=(const GridGeometry& other) const { return !(*this == other); }
};

/// Occupancy values: -1 unknown, 0 (free) … 100 (occupied), in percent.
struct GridMap {
  static constexpr std::int8_t kUnknown = -1;
  static constexpr std::int8_t kFree = 0;
  static constexpr std::int8_t kOccupied = 100;

  GridGeometry geometry;
  std::vector<std::int8_t> cells;  ///< geometry.cellCount() values

  GridMap() = default;
  GridMap(const GridGeometry& g, std::int8_t fill) : geometry(g), cells(g.cellCount(), fill) {}

  std::int8_t at(int cx, int cy) const { return cells[geometry.index(cx, cy)]; }
  std::int8_t& at(int cx, int cy) { return cells[geometry.index(cx, cy)]; }
  /// True when the header and the data agree (size) and every value is -1 or in 0..100.
  bool isValid() const;
  bool operator==(const GridMap& other) const {
    return geometry == other.geometry && cells == other.cells;
  }
  bool operator!=(const GridMap& other) const { return !(*this == other); }
};

}  // namespace mrslam
