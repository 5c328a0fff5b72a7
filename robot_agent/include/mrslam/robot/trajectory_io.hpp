#pragma once
// Trajectories in TUM format: `timestamp x y z qx qy qz qw`, one pose per line.

#include <string>
#include <vector>

#include "mrslam/robot/robot_pipeline.hpp"

namespace mrslam::robot {

/// Writes one line per trajectory point (z = 0, rotation about z as a quaternion), time stamps
/// with nine decimals. Throws std::runtime_error when the file cannot be written.
void writeTumTrajectory(const std::vector<TrajectoryPoint>& trajectory, const std::string& path);

struct StampedPose {
  Stamp stamp;
  SE2 pose;
};
/// Reads a planar TUM trajectory (heading from the quaternion's rotation about z). Throws
/// std::runtime_error naming `file:line` at a line that is no pose; `#` lines are comments.
std::vector<StampedPose> readTumTrajectory(const std::string& path);

}  // namespace mrslam::robot
