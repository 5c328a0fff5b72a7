#pragma once
// Trajectories in TUM format: `timestamp x y z qx qy qz qw`, one pose per line.

#include <string>
#include <vector>

#include "mrslam/robot/robot_pipeline.hpp"

namespace mrslam::robot {

/// Writes one line per trajectory point (z = 0, rotation about z as a quaternion), time stamps
/// with nine decimals. Throws std::runtime_error when the file cannot be written.
void writeTumTrajectory(const std::vector<TrajectoryPoint>& trajectory, const std::string& path);

}  // namespace mrslam::robot
