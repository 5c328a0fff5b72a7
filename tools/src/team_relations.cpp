#include "mrslam/tools/team_relations.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>

#include "mrslam/robot/trajectory_io.hpp"

namespace mrslam::tools {

namespace {

namespace fs = std::filesystem;
using robot::Relation;
using robot::StampedPose;
using Trajectories = std::map<std::string, std::vector<StampedPose>>;

// The robot whose trajectory holds a pose stamped `stamp` (within the relations' tolerance).
class StampOwners {
 public:
  explicit StampOwners(const Trajectories& trajectories) {
    std::vector<std::pair<StampedPose, const std::string*>> owned;
    for (const auto& [id, poses] : trajectories) {
      for (const StampedPose& pose : poses) {
        owned.emplace_back(pose, &id);
      }
    }
    std::sort(owned.begin(), owned.end(),
              [](const auto& a, const auto& b) { return a.first.stamp < b.first.stamp; });
    for (const auto& [pose, id] : owned) {
      poses_.push_back(pose);
      owners_.push_back(*id);
    }
  }

  std::optional<std::string> ownerOf(Stamp stamp) const {
    const std::optional<std::size_t> index = robot::nearestStampIndex(poses_, stamp);
    return index ? std::optional<std::string>(owners_[*index]) : std::nullopt;
  }

 private:
  std::vector<StampedPose> poses_;   ///< by stamp
  std::vector<std::string> owners_;  ///< the robot of each
};

std::vector<StampedPose> merged(const Trajectories& trajectories) {
  std::vector<StampedPose> poses;
  for (const auto& entry : trajectories) {
    poses.insert(poses.end(), entry.second.begin(), entry.second.end());
  }
  std::sort(poses.begin(), poses.end(),
            [](const StampedPose& a, const StampedPose& b) { return a.stamp < b.stamp; });
  return poses;
}

nlohmann::json reportJson(const robot::RelationReport& report) {
  return {{"all", relationStatsJson(report.all)},
          {"near", relationStatsJson(report.near)},
          {"far", relationStatsJson(report.far)}};
}

void logStats(const char* what, const robot::RelationErrorStats& stats) {
  spdlog::info("team: relations {}: {} of them, {:.4f} ± {:.4f} m, {:.3f} ± {:.3f}°", what,
               stats.count, stats.translation_mean_m, stats.translation_sigma_m,
               stats.rotation_mean_deg, stats.rotation_sigma_deg);
}

}  // namespace

nlohmann::json relationStatsJson(const robot::RelationErrorStats& stats) {
  return {{"count", stats.count},
          {"translation_mean_m", stats.translation_mean_m},
          {"translation_sigma_m", stats.translation_sigma_m},
          {"rotation_mean_deg", stats.rotation_mean_deg},
          {"rotation_sigma_deg", stats.rotation_sigma_deg}};
}

Trajectories globalTrajectories(const TeamPlacements& placements, const Trajectories& local) {
  Trajectories global;
  for (const RobotPlacement& robot : placements.robots) {
    const auto trajectory = local.find(robot.id);
    if (!robot.placed || trajectory == local.end()) {
      continue;
    }
    std::vector<StampedPose>& poses = global[robot.id];
    for (const StampedPose& pose : trajectory->second) {
      poses.push_back({pose.stamp, robot.T_reference_origin * pose.pose});
    }
  }
  return global;
}

TeamRelationReport scoreTeam(const Trajectories& global, const Trajectories& local,
                             const std::vector<Relation>& relations) {
  const StampOwners placed(global);
  const StampOwners anyone(local);
  std::vector<Relation> within;
  std::vector<Relation> across;
  std::map<std::string, std::vector<Relation>> by_robot;
  TeamRelationReport report;
  for (const Relation& relation : relations) {
    const std::optional<std::string> from = placed.ownerOf(relation.from);
    const std::optional<std::string> to = placed.ownerOf(relation.to);
    if (!from || !to) {
      // Scans of the team whose robot was not placed; relations beyond the team's scans (a
      // log cut short) are no concern of the team's.
      const bool of_the_team = anyone.ownerOf(relation.from) && anyone.ownerOf(relation.to);
      report.unscored += of_the_team ? 1 : 0;
      continue;
    }
    if (*from == *to) {
      within.push_back(relation);
    } else {
      across.push_back(relation);
      by_robot[*from].push_back(relation);
      by_robot[*to].push_back(relation);
    }
  }
  const std::vector<StampedPose> trajectory = merged(global);
  report.within = robot::evaluateRelations(trajectory, within);
  report.across = robot::evaluateRelations(trajectory, across);
  std::vector<Relation> scored = within;
  scored.insert(scored.end(), across.begin(), across.end());
  report.all = robot::evaluateRelations(trajectory, scored);
  for (const auto& [id, robot_relations] : by_robot) {
    report.across_by_robot[id] = robot::evaluateRelations(trajectory, robot_relations).all;
  }
  return report;
}

bool scoreTeamRun(const std::string& out, const std::vector<std::string>& fusion_folders,
                  const std::string& relations_path) {
  try {
    const std::vector<Relation> relations = robot::readRelations(relations_path);
    Trajectories local;
    for (const auto& entry : fs::directory_iterator(fs::path(out) / "robots_local")) {
      if (entry.path().extension() == ".tum") {
        local[entry.path().stem().string()] = robot::readTumTrajectory(entry.path().string());
      }
    }
    for (const std::string& folder : fusion_folders) {
      const TeamPlacements placements =
          readPlacements((fs::path(folder) / "transforms.json").string());
      const Trajectories global = globalTrajectories(placements, local);
      fs::create_directories(fs::path(folder) / "global_trajectories");
      for (const auto& [id, poses] : global) {
        std::vector<robot::TrajectoryPoint> points;
        for (const StampedPose& pose : poses) {
          points.push_back({pose.stamp, pose.pose});
        }
        robot::writeTumTrajectory(
            points, (fs::path(folder) / "global_trajectories" / (id + ".tum")).string());
      }
      const TeamRelationReport report = scoreTeam(global, local, relations);
      logStats("within one robot", report.within.all);
      logStats("across two robots", report.across.all);
      logStats("all", report.all.all);
      spdlog::info("team: {} relations not scored (a robot not placed)", report.unscored);
      nlohmann::json by_robot = nlohmann::json::object();
      for (const auto& [id, stats] : report.across_by_robot) {
        by_robot[id] = relationStatsJson(stats);
      }
      std::ofstream file(fs::path(folder) / "relations.json");
      file << nlohmann::json{{"relations", relations_path},
                             {"within", reportJson(report.within)},
                             {"across", reportJson(report.across)},
                             {"all", reportJson(report.all)},
                             {"unscored", report.unscored},
                             {"across_by_robot", by_robot}}
                  .dump(2)
           << "\n";
      if (!file) {
        throw std::runtime_error((fs::path(folder) / "relations.json").string() + ": cannot write");
      }
    }
  } catch (const std::exception& error) {
    spdlog::warn("team: no relation scores: {}", error.what());
    return false;
  }
  return true;
}

}  // namespace mrslam::tools
