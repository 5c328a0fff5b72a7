#pragma once
// A square window of a grid map as a map of its own (a robot's map in its own frame: cell (0, 0)
// of the window at the frame's origin), for tests that need two overlapping maps with a known
// shift between them.

#include "mrslam/common/grid_map.hpp"

namespace mrslam::test {

/// The `size` × `size` cells of `source` from cell (x0, y0) up, at `source`'s resolution.
inline GridMap cropWindow(const GridMap& source, int x0, int y0, int size) {
  GridGeometry geometry;
  geometry.resolution_m = source.geometry.resolution_m;
  geometry.width = size;
  geometry.height = size;
  GridMap map(geometry, GridMap::kUnknown);
  for (int y = 0; y < size; ++y) {
    for (int x = 0; x < size; ++x) {
      map.at(x, y) = source.at(x0 + x, y0 + y);
    }
  }
  return map;
}

}  // namespace mrslam::test
