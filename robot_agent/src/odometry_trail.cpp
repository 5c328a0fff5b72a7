#include "mrslam/robot/odometry_trail.hpp"

#include <algorithm>

namespace mrslam::robot {

void OdometryTrail::add(Stamp stamp, const SE2& T_odom_robot) {
  if (!poses_.empty() && stamp < poses_.back().first) {
    stamp = poses_.back().first;
  }
  poses_.emplace_back(stamp, T_odom_robot);
  while (poses_.size() > 2 && secondsBetween(poses_[1].first, stamp) > span_s_) {
    poses_.pop_front();
  }
}

std::optional<SE2> OdometryTrail::poseAt(Stamp stamp) const {
  if (poses_.empty()) {
    return std::nullopt;
  }
  if (stamp <= poses_.front().first) {
    return poses_.front().second;
  }
  if (stamp >= poses_.back().first) {
    return poses_.back().second;
  }
  // The first pose not older than the stamp, and the one before it.
  const auto after =
      std::lower_bound(poses_.begin(), poses_.end(), stamp,
                       [](const std::pair<Stamp, SE2>& entry, Stamp s) { return entry.first < s; });
  const auto before = std::prev(after);
  const double span = secondsBetween(before->first, after->first);
  const double f = span > 0.0 ? secondsBetween(before->first, stamp) / span : 1.0;
  const SE2& a = before->second;
  const SE2& b = after->second;
  return SE2(a.x() + f * (b.x() - a.x()), a.y() + f * (b.y() - a.y()),
             a.theta() + f * wrapAngle(b.theta() - a.theta()));
}

}  // namespace mrslam::robot
