#pragma once
// How well a team run placed its robots: the fusion agent's transforms.json against the split's
// truth (segments/truth.json), both {"reference": ID, "robots": [{"id", "placed", "x", "y",
// "theta"}]} with (x, y, theta) the pose of a robot's map origin in the reference robot's map.
//
// The split's truth holds for maps built on the corrected poses. A robot whose filter drifts
// builds its map in a frame turned and shifted from its corrected one; its map belongs where
// its estimated trajectory lies on the corrected one. With T_c_e the rigid transform that best
// lays robot i's estimated trajectory on its corrected one (least squares over the positions,
// robot::alignTrajectory), the truth in the estimated frames is
//   T_e1_ei = T_c1_e1⁻¹ · T_c1_ci · T_ci_ei,
// which equals the split's truth when each robot's estimate is its corrected trajectory.

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "mrslam/common/se2.hpp"

namespace mrslam::tools {

struct RobotPlacement {
  std::string id;
  bool placed = false;
  SE2 T_reference_origin;  ///< valid when placed
  std::string log;         ///< the segment it replayed (truth.json's "log"; empty elsewhere)
};

struct TeamPlacements {
  std::string reference;
  std::vector<RobotPlacement> robots;
  const RobotPlacement* find(const std::string& id) const;
};

/// Reads a truth.json or transforms.json. Throws std::runtime_error naming the file when it is
/// missing, not JSON or lacks a field; a placed robot with a null pose is an error too.
TeamPlacements readPlacements(const std::string& path);

/// The corrected pose of each scan of a CARMEN log (its FLASER laser pose) in the frame of its
/// first scan: the trajectory a robot agent replaying it from its origin would follow.
std::vector<SE2> correctedTrajectory(const std::string& carmen_log);

/// T_c_e: the estimated trajectory laid on the corrected one (pose k with pose k; the shorter
/// decides). Throws std::invalid_argument when either is empty.
SE2 estimateToCorrected(const std::vector<SE2>& estimated, const std::vector<SE2>& corrected);

/// The truth in the estimated frames (above). `T_corrected_estimated` by robot id; a robot
/// without one keeps the split's truth (T_c_e = identity).
TeamPlacements truthInEstimatedFrames(const TeamPlacements& truth,
                                      const std::map<std::string, SE2>& T_corrected_estimated);

struct PlacementError {
  std::string id;
  bool placed = false;  ///< by the fusion agent
  double distance_m = 0.0;
  double angle_rad = 0.0;  ///< |wrapped difference|
};

/// Each robot of `truth` but its reference: placed or not by `found`, and how far from the truth
/// its placement lies. Throws std::runtime_error when the references differ.
std::vector<PlacementError> comparePlacements(const TeamPlacements& found,
                                              const TeamPlacements& truth);

/// Writes `placements` as truth.json is written (pose, not placed robots with null poses).
void writePlacements(const TeamPlacements& placements, const std::string& path);

/// After a team run on a split log (`out`/segments/truth.json, each robot's trajectory in
/// `out`/robots_local/ID.tum): writes `out`/segments/truth_estimated.json and, for each fusion
/// output folder, evaluation.json with every robot's error against both truths, and logs one
/// line per robot. Returns false (and logs why) when something it needs is missing or bad.
bool evaluateTeamRun(const std::string& out, const std::vector<std::string>& fusion_folders);

}  // namespace mrslam::tools
