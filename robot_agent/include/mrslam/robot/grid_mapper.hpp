#pragma once
// Inserts laser scans into the robot's log-odds occupancy grid at the estimated pose.

#include <vector>

#include "mrslam/common/occupancy_grid.hpp"
#include "mrslam/common/platform.hpp"
#include "mrslam/common/samples.hpp"

namespace mrslam::robot {

struct MappingSettings {
  double resolution_m = 0.05;  ///< grid cell size
  LogOddsParams log_odds;      ///< inverse sensor model
  double max_range_m = 0.0;    ///< hits beyond are not trusted (no return); 0: the scan's range_max
  double clearing_range_m =
      0.0;  ///< beams with no return clear free space up to this range; 0: off
};

class GridMapper {
 public:
  GridMapper(const MappingSettings& settings, const SensorMounting& mounting);

  /// Ray-traces every beam of `scan` from the laser's pose in the map frame.
  void insertScan(const LaserScan& scan, const SE2& T_map_robot);

  const OccupancyGrid& grid() const { return grid_; }

 private:
  struct Beam {
    Eigen::Vector2d end;  ///< where the beam ends in the map frame
    bool hit = false;     ///< it ends on an obstacle (else it only clears free space)
  };

  MappingSettings settings_;
  SensorMounting mounting_;
  OccupancyGrid grid_;
  std::vector<Beam> beams_;  ///< scratch of insertScan
};

}  // namespace mrslam::robot
