#include "mrslam/robot/grid_mapper.hpp"

#include <algorithm>
#include <cmath>

namespace mrslam::robot {

GridMapper::GridMapper(const MappingSettings& settings, const SensorMounting& mounting)
    : settings_(settings), mounting_(mounting), grid_(settings.resolution_m, settings.log_odds) {}

void GridMapper::insertScan(const LaserScan& scan, const SE2& T_map_robot) {
  const SE2 T_map_laser = T_map_robot * mounting_.T_robot_laser;
  const Eigen::Vector2d origin = T_map_laser.translation();
  const double max_range = settings_.max_range_m > 0.0 ? settings_.max_range_m : scan.range_max_m;
  const double reach = std::max(max_range, settings_.clearing_range_m);
  grid_.ensureContains(origin - Eigen::Vector2d::Constant(reach),
                       origin + Eigen::Vector2d::Constant(reach));
  for (std::size_t i = 0; i < scan.ranges_m.size(); ++i) {
    const double range = scan.ranges_m[i];
    if (std::isnan(range) || range < scan.range_min_m) {
      continue;  // invalid reading: says nothing
    }
    const bool hit = std::isfinite(range) && range <= max_range;
    const double length = hit ? range : settings_.clearing_range_m;
    if (length <= 0.0) {
      continue;
    }
    const double angle = scan.beamAngle(i);
    const Eigen::Vector2d end =
        T_map_laser * Eigen::Vector2d(length * std::cos(angle), length * std::sin(angle));
    grid_.insertRay(origin, end, hit);
  }
}

}  // namespace mrslam::robot
