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
  beams_.clear();
  Eigen::Vector2d low = origin;
  Eigen::Vector2d high = origin;
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
    low = low.cwiseMin(end);
    high = high.cwiseMax(end);
    beams_.push_back({end, hit});
  }
  // The grid grows once per scan, to the box of the cells this scan touches.
  grid_.ensureContains(low, high);
  for (const Beam& beam : beams_) {
    grid_.insertRay(origin, beam.end, beam.hit);
  }
}

}  // namespace mrslam::robot
