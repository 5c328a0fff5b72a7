#include "mrslam/robot/trajectory_io.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
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

std::vector<StampedPose> readTumTrajectory(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    throw std::runtime_error(path + ": cannot open the trajectory");
  }
  std::vector<StampedPose> poses;
  std::string line;
  for (int number = 1; std::getline(file, line); ++number) {
    std::istringstream fields(line);
    std::string stamp_text;
    if (!(fields >> stamp_text) || stamp_text.front() == '#') {
      continue;
    }
    double x = 0.0, y = 0.0, z = 0.0, qx = 0.0, qy = 0.0, qz = 0.0, qw = 0.0;
    const std::optional<Stamp> stamp = Stamp::parseSeconds(stamp_text);
    if (!stamp || !(fields >> x >> y >> z >> qx >> qy >> qz >> qw)) {
      throw std::runtime_error(path + ":" + std::to_string(number) +
                               ": not a TUM pose (timestamp x y z qx qy qz qw)");
    }
    poses.push_back({*stamp, SE2(x, y, 2.0 * std::atan2(qz, qw))});
  }
  return poses;
}

}  // namespace mrslam::robot
