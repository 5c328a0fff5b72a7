#pragma once
// The relation metric of Kümmerle et al. ("On measuring the accuracy of SLAM algorithms",
// Autonomous Robots 27(4), 2009): for every ground-truth relation (the true pose of the scan
// stamped t2 in the frame of the scan stamped t1), the error of the estimated relation; the
// mean and σ of its translation and rotation over all relations.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "mrslam/common/se2.hpp"
#include "mrslam/common/stamp.hpp"
#include "mrslam/robot/trajectory_io.hpp"

namespace mrslam::robot {

struct Relation {
  Stamp from;     ///< t1: the scan whose frame the relation is in
  Stamp to;       ///< t2
  SE2 T_from_to;  ///< the true pose of scan t2 in the frame of scan t1
};

/// Reads a relations file: lines `t1 t2 x y z roll pitch yaw` (z, roll and pitch ignored), `#`
/// lines and blank lines skipped. Throws std::runtime_error naming `file:line` at a line that is
/// no relation, and when the file cannot be read.
std::vector<Relation> readRelations(const std::string& path);

/// Mean and standard deviation of the absolute errors of a set of relations.
struct RelationErrorStats {
  std::size_t count = 0;
  double translation_mean_m = 0.0;
  double translation_sigma_m = 0.0;
  double rotation_mean_deg = 0.0;
  double rotation_sigma_deg = 0.0;
};

struct RelationReport {
  RelationErrorStats all;
  RelationErrorStats near;  ///< relations whose scans are less than kNearSeconds apart
  RelationErrorStats far;   ///< the others
  /// Relations with a stamp that matches no pose of the trajectory (within kStampToleranceS):
  /// left out of the figures, and counted so a short or broken trajectory shows.
  std::size_t unmatched = 0;
};

/// Relations of scans closer in time than this are "near" (local accuracy), others "far"
/// (what loop closure keeps right).
constexpr double kNearSeconds = 60.0;
/// A relation stamp matches the trajectory pose nearest in time when it is within this: the
/// logs' stamps are to the microsecond, a scan period is 0.2 s.
constexpr double kStampToleranceS = 1e-3;

/// The index of the pose of `by_stamp` (sorted by stamp) stamped nearest `stamp`, when within
/// kStampToleranceS.
std::optional<std::size_t> nearestStampIndex(const std::vector<StampedPose>& by_stamp, Stamp stamp);

/// The metric of `trajectory` (poses of the frame the relations are of, usually the laser's) on
/// `relations`. The error of a relation is T_true⁻¹ · T_estimated: its translation's norm and its
/// rotation's absolute angle.
RelationReport evaluateRelations(const std::vector<StampedPose>& trajectory,
                                 const std::vector<Relation>& relations);

}  // namespace mrslam::robot
