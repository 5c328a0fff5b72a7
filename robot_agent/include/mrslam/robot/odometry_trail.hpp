#pragma once
// The dead-reckoned poses of the last few seconds, by stamp: what a delayed measurement (a scan
// taken before its stamp says) needs to be brought forward to the newest odometry.

#include <deque>
#include <optional>
#include <utility>

#include "mrslam/common/se2.hpp"
#include "mrslam/common/stamp.hpp"

namespace mrslam::robot {

class OdometryTrail {
 public:
  /// Keeps poses no older than `span_s` before the newest one (and always the newest two).
  explicit OdometryTrail(double span_s = 2.0) : span_s_(span_s) {}

  /// Appends T_odom_robot at `stamp`. Poses must come in arrival order; a stamp older than the
  /// newest one is stored as the newest stamp (arrival order wins).
  void add(Stamp stamp, const SE2& T_odom_robot);

  bool empty() const { return poses_.empty(); }
  /// The newest pose.
  const SE2& latest() const { return poses_.back().second; }

  /// T_odom_robot at `stamp`, interpolated linearly (x, y and the wrapped angle) between the two
  /// poses around it; the oldest kept pose for an older stamp, the newest for a newer one.
  /// Nothing when the trail is empty.
  std::optional<SE2> poseAt(Stamp stamp) const;

 private:
  double span_s_;
  std::deque<std::pair<Stamp, SE2>> poses_;
};

}  // namespace mrslam::robot
