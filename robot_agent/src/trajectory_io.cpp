#include "mrslam/robot/trajectory_io.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace mrslam::robot {

void writeTumTrajectory(const std::vector<TrajectoryPoint>& trajectory, const std::string& path) {
  std::ofstream file(path);
  if (!file) {
    throw std::runtime_error(path + ": cannot write the trajectory");
  }
  char line[256];
  for (const TrajectoryPoint& point : trajectory) {
    const double half = 0.5 * point.T_map_robot.theta();
    std::snprintf(line, sizeof(line), "%s %.9f %.9f 0 0 0 %.9f %.9f\n",
                  point.stamp.toString().c_str(), point.T_map_robot.x(), point.T_map_robot.y(),
                  std::sin(half), std::cos(half));
    file << line;
  }
  if (!file) {
    throw std::runtime_error(path + ": cannot write the trajectory");
  }
}

}  // namespace mrslam::robot
