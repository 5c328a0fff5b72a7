#pragma once
// A team scored as one robot is: the benchmark's relations (robot/relations.hpp) on the team's
// trajectory, each placed robot's own trajectory carried into the reference robot's map frame
// by its placement, T_reference_robot(t) = T_reference_origin · T_origin_robot(t). The segments
// keep the log's stamps, so every relation names scans of the team: within one robot, across
// two, or with a scan of a robot that was not placed (not scored, counted).

#include <cstddef>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "mrslam/robot/relations.hpp"
#include "mrslam/tools/team_evaluation.hpp"

namespace mrslam::tools {

struct TeamRelationReport {
  robot::RelationReport within;  ///< both scans of one robot
  robot::RelationReport across;  ///< the scans of two placed robots
  robot::RelationReport all;     ///< every relation whose robots are placed
  std::size_t unscored = 0;      ///< a scan of an unplaced robot, or of none of the team
  /// Across relations by robot: each counts for both of its robots.
  std::map<std::string, robot::RelationErrorStats> across_by_robot;
};

/// The figures of a set of relations as JSON (count, translation and rotation mean and σ).
nlohmann::json relationStatsJson(const robot::RelationErrorStats& stats);

/// Each placed robot's trajectory in the reference frame (its id → poses), from the robots'
/// own trajectories (`local` by id, in their map frames) and the placements.
std::map<std::string, std::vector<robot::StampedPose>> globalTrajectories(
    const TeamPlacements& placements,
    const std::map<std::string, std::vector<robot::StampedPose>>& local);

/// The relations scored on the team's global trajectories (above).
TeamRelationReport scoreTeam(const std::map<std::string, std::vector<robot::StampedPose>>& global,
                             const std::map<std::string, std::vector<robot::StampedPose>>& local,
                             const std::vector<robot::Relation>& relations);

/// After a team run: for each fusion output folder, writes global_trajectories/ID.tum (placed
/// robots, the log's stamps) and relations.json (the report), and logs it. The robots' own
/// trajectories are `out`/robots_local/ID.tum. Returns false (and logs why) when something it
/// needs is missing or bad.
bool scoreTeamRun(const std::string& out, const std::vector<std::string>& fusion_folders,
                  const std::string& relations_path);

}  // namespace mrslam::tools
