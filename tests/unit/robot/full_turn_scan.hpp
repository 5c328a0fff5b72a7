#pragma once
// A simulated laser scan for the robot tests: 360 beams over the full turn.

#include <cmath>
#include <cstddef>

#include "mrslam/common/samples.hpp"

namespace mrslam::robot::test {

constexpr double kFullTurnRangeMaxM = 30.0;  ///< range_max_m of fullTurnScan()

/// One beam a degree from −π, ranges 0.02 m to kFullTurnRangeMaxM; each beam's range (a float,
/// or LaserScan::kNoReturn) is `range_of(angle)`.
template <typename RangeOf>
LaserScan fullTurnScan(RangeOf range_of) {
  LaserScan scan;
  scan.angle_min_rad = -M_PI;
  scan.angle_increment_rad = M_PI / 180.0;
  scan.range_min_m = 0.02;
  scan.range_max_m = kFullTurnRangeMaxM;
  for (std::size_t i = 0; i < 360; ++i) {
    scan.ranges_m.push_back(range_of(scan.beamAngle(i)));
  }
  return scan;
}

}  // namespace mrslam::robot::test
