#include "mrslam/fusion/merge/floor_crossing.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mrslam::fusion {

namespace {

using Cell = Eigen::Vector2i;

// The offsets within `radius` cells of a cell (centre to centre), the cell itself included.
std::vector<Cell> offsetsWithin(double radius) {
  std::vector<Cell> offsets;
  const int reach = static_cast<int>(std::floor(radius));
  for (int dy = -reach; dy <= reach; ++dy) {
    for (int dx = -reach; dx <= reach; ++dx) {
      if (dx * dx + dy * dy <= radius * radius) {
        offsets.emplace_back(dx, dy);
      }
    }
  }
  return offsets;
}

// Whether the cells within the clearance of `cell` (`offsets`) hold no wall of `map` and, with
// `known_around`, no unknown cell and none off the map either.
bool clearFloorAround(const GridMap& map, const Cell& cell, const std::vector<Cell>& offsets,
                      const SimilaritySettings& classes, bool known_around) {
  for (const Cell& offset : offsets) {
    const Cell near = cell + offset;
    if (!map.geometry.contains(near.x(), near.y())) {
      if (known_around) {
        return false;
      }
      continue;
    }
    const int value = map.at(near.x(), near.y());
    if (classes.isOccupied(value) || (known_around && !classes.isKnown(value))) {
      return false;
    }
  }
  return true;
}

bool before(const Cell& a, const Cell& b) {
  return a.y() != b.y() ? a.y() < b.y() : a.x() < b.x();
}

// The largest 8-connected group of `cells` (sorted by `before`, without repeats).
int largestRun(const std::vector<Cell>& cells) {
  std::vector<bool> reached(cells.size(), false);
  std::vector<std::size_t> stack;
  int largest = 0;
  for (std::size_t start = 0; start < cells.size(); ++start) {
    if (reached[start]) {
      continue;
    }
    reached[start] = true;
    stack.assign(1, start);
    int run = 0;
    while (!stack.empty()) {
      const Cell cell = cells[stack.back()];
      stack.pop_back();
      ++run;
      for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
          const Cell near = cell + Cell(dx, dy);
          const auto found = std::lower_bound(cells.begin(), cells.end(), near, before);
          const auto index = static_cast<std::size_t>(found - cells.begin());
          if (found != cells.end() && *found == near && !reached[index]) {
            reached[index] = true;
            stack.push_back(index);
          }
        }
      }
    }
    largest = std::max(largest, run);
  }
  return largest;
}

}  // namespace

FloorCrossing floorCrossing(const GridMap& own, const GridMap& other,
                            const GridTransform& T_other_own, const SimilaritySettings& classes,
                            const FloorCrossingSettings& settings) {
  FloorCrossing result;
  const std::vector<Cell> near_offsets = offsetsWithin(settings.clearance_cells);
  std::vector<Cell> crossing;
  for (int y = 0; y < own.geometry.height; ++y) {
    for (int x = 0; x < own.geometry.width; ++x) {
      if (!classes.isOccupied(own.at(x, y))) {
        continue;
      }
      const Eigen::Vector2d landed = T_other_own.apply(Eigen::Vector2d(x, y));
      const Cell cell(static_cast<int>(std::floor(landed.x() + 0.5)),
                      static_cast<int>(std::floor(landed.y() + 0.5)));
      if (!other.geometry.contains(cell.x(), cell.y())) {
        continue;
      }
      const int value = other.at(cell.x(), cell.y());
      if (!classes.isKnown(value)) {
        continue;
      }
      ++result.walls_on_known;
      if (value >= 0 && value <= settings.floor_max_occupancy &&
          clearFloorAround(other, cell, near_offsets, classes, settings.known_around)) {
        crossing.push_back(cell);
      }
    }
  }
  std::sort(crossing.begin(), crossing.end(), before);
  crossing.erase(std::unique(crossing.begin(), crossing.end()), crossing.end());
  result.crossing_cells = static_cast<int>(crossing.size());
  result.run_cells = largestRun(crossing);
  return result;
}

}  // namespace mrslam::fusion
