#include "mrslam/robot/slam/map_renderer.hpp"

#include <cmath>
#include <limits>

namespace mrslam::robot::slam {

namespace {

// The corners of a submap's grid in the map frame, for the box of cells it can touch.
void extendByCorners(const PlacedSubmap& placed, Eigen::Vector2d& low, Eigen::Vector2d& high) {
  const ProbabilityGrid& grid = placed.submap->grid;
  const double r = grid.resolution();
  const Eigen::Vector2d min_m = grid.originCell().cast<double>() * r;
  const Eigen::Vector2d max_m = min_m + Eigen::Vector2d(grid.width(), grid.height()) * r;
  for (const Eigen::Vector2d& corner : {min_m, max_m, Eigen::Vector2d(min_m.x(), max_m.y()),
                                        Eigen::Vector2d(max_m.x(), min_m.y())}) {
    const Eigen::Vector2d p = placed.T_map_submap * corner;
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
}

float logOddsOf(float probability) {
  return std::log(probability / (1.0f - probability));
}

void drawSubmap(const PlacedSubmap& placed, OccupancyGrid& map) {
  const ProbabilityGrid& grid = placed.submap->grid;
  if (grid.width() == 0) {
    return;
  }
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d high = -low;
  extendByCorners(placed, low, high);
  const Eigen::Vector2i first = map.cellOf(low);
  const Eigen::Vector2i last = map.cellOf(high);
  const double r = map.geometry().resolution_m;
  const Eigen::Vector2d origin = map.geometry().origin_m;
  const SE2 T_submap_map = placed.T_map_submap.inverse();
  const Eigen::Matrix2d R = T_submap_map.rotation();
  const Eigen::Vector2d t = T_submap_map.translation();
  const Eigen::Vector2d step_x = R.col(0) * r;  // the submap-frame step of one map cell in x
  for (int cy = std::max(first.y(), 0); cy <= last.y() && cy < map.geometry().height; ++cy) {
    const int cx_first = std::max(first.x(), 0);
    const Eigen::Vector2d row_start =
        origin + (Eigen::Vector2d(cx_first, cy) + Eigen::Vector2d::Constant(0.5)) * r;
    Eigen::Vector2d p_submap = R * row_start + t;
    for (int cx = cx_first; cx <= last.x() && cx < map.geometry().width; ++cx) {
      const Eigen::Vector2i cell = grid.cellOf(p_submap);
      if (grid.isKnown(cell)) {
        map.addLogOdds(cx, cy, logOddsOf(grid.probability(cell)));
      }
      p_submap += step_x;
    }
  }
}

}  // namespace

OccupancyGrid renderSubmaps(const std::vector<PlacedSubmap>& submaps, double resolution_m,
                            const LogOddsParams& params) {
  OccupancyGrid map(resolution_m, params);
  Eigen::Vector2d low = Eigen::Vector2d::Constant(std::numeric_limits<double>::max());
  Eigen::Vector2d high = -low;
  bool any = false;
  for (const PlacedSubmap& placed : submaps) {
    if (placed.submap->grid.width() > 0) {
      extendByCorners(placed, low, high);
      any = true;
    }
  }
  if (!any) {
    return map;
  }
  map.ensureContains(low, high);
  for (const PlacedSubmap& placed : submaps) {
    drawSubmap(placed, map);
  }
  return map;
}

}  // namespace mrslam::robot::slam
