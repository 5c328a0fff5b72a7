#include "mrslam/tools/team_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include <spdlog/spdlog.h>

#include "mrslam/drivers/carmen_reader.hpp"
#include "mrslam/robot/evaluation.hpp"
#include "mrslam/robot/trajectory_io.hpp"
#include "mrslam/robot/trajectory_metrics.hpp"

namespace mrslam::tools {

namespace {

double number(const nlohmann::json& robot, const char* key, const std::string& where) {
  if (!robot.contains(key) || !robot.at(key).is_number()) {
    throw std::runtime_error(where + ": \"" + key + "\" is not a number");
  }
  return robot.at(key).get<double>();
}

RobotPlacement placementOf(const nlohmann::json& robot, const std::string& where) {
  if (!robot.is_object() || !robot.contains("id") || !robot.at("id").is_string() ||
      !robot.contains("placed") || !robot.at("placed").is_boolean()) {
    throw std::runtime_error(where + ": a robot needs a string \"id\" and a boolean \"placed\"");
  }
  RobotPlacement placement;
  placement.id = robot.at("id").get<std::string>();
  placement.placed = robot.at("placed").get<bool>();
  placement.log = robot.value("log", "");
  if (placement.placed) {
    const std::string at = where + " (" + placement.id + ")";
    const double x = number(robot, "x", at);  // in this order: the first bad field is named
    const double y = number(robot, "y", at);
    const double theta = number(robot, "theta", at);
    placement.T_reference_origin = SE2(x, y, theta);
  }
  return placement;
}

}  // namespace

const RobotPlacement* TeamPlacements::find(const std::string& id) const {
  const auto found = std::find_if(robots.begin(), robots.end(),
                                  [&](const RobotPlacement& robot) { return robot.id == id; });
  return found == robots.end() ? nullptr : &*found;
}

TeamPlacements readPlacements(const std::string& path) {
  std::ifstream file(path);
  if (!file) {
    throw std::runtime_error(path + ": cannot read");
  }
  const nlohmann::json document = nlohmann::json::parse(file, nullptr, false);
  if (document.is_discarded() || !document.is_object() || !document.contains("reference") ||
      !document.at("reference").is_string() || !document.contains("robots") ||
      !document.at("robots").is_array()) {
    throw std::runtime_error(path +
                             ": not a placements file (a \"reference\" and a \"robots\" array)");
  }
  TeamPlacements placements;
  placements.reference = document.at("reference").get<std::string>();
  for (const nlohmann::json& robot : document.at("robots")) {
    placements.robots.push_back(placementOf(robot, path));
  }
  return placements;
}

std::vector<SE2> correctedTrajectory(const std::string& carmen_log) {
  drivers::CarmenSettings settings;
  settings.path = carmen_log;
  settings.malformed_policy = drivers::MalformedPolicy::kStop;
  drivers::CarmenReader reader(settings);
  std::optional<std::vector<SE2>> trajectory = robot::groundTruth(robot::readAllSamples(reader));
  if (!trajectory) {
    throw std::runtime_error(carmen_log + ": a scan without its corrected pose");
  }
  if (!trajectory->empty()) {
    const SE2 T_origin_log = trajectory->front().inverse();
    for (SE2& pose : *trajectory) {
      pose = T_origin_log * pose;
    }
  }
  return *trajectory;
}

SE2 estimateToCorrected(const std::vector<SE2>& estimated, const std::vector<SE2>& corrected) {
  if (estimated.empty() || corrected.empty()) {
    throw std::invalid_argument("a trajectory to align is empty");
  }
  const std::size_t count = std::min(estimated.size(), corrected.size());
  return robot::alignTrajectory(
      std::vector<SE2>(estimated.begin(), estimated.begin() + static_cast<std::ptrdiff_t>(count)),
      std::vector<SE2>(corrected.begin(), corrected.begin() + static_cast<std::ptrdiff_t>(count)));
}

TeamPlacements truthInEstimatedFrames(const TeamPlacements& truth,
                                      const std::map<std::string, SE2>& T_corrected_estimated) {
  const auto alignment = [&](const std::string& id) {
    const auto found = T_corrected_estimated.find(id);
    return found == T_corrected_estimated.end() ? SE2() : found->second;
  };
  const SE2 T_e1_c1 = alignment(truth.reference).inverse();
  TeamPlacements estimated = truth;
  for (RobotPlacement& robot : estimated.robots) {
    if (robot.placed) {
      robot.T_reference_origin = T_e1_c1 * robot.T_reference_origin * alignment(robot.id);
    }
  }
  return estimated;
}

std::vector<PlacementError> comparePlacements(const TeamPlacements& found,
                                              const TeamPlacements& truth) {
  if (found.reference != truth.reference) {
    throw std::runtime_error("the placements are in " + found.reference +
                             "'s frame, the truth in " + truth.reference + "'s");
  }
  std::vector<PlacementError> errors;
  for (const RobotPlacement& true_robot : truth.robots) {
    if (true_robot.id == truth.reference || !true_robot.placed) {
      continue;
    }
    PlacementError error;
    error.id = true_robot.id;
    const RobotPlacement* robot = found.find(true_robot.id);
    error.placed = robot != nullptr && robot->placed;
    if (error.placed) {
      const SE2& T = robot->T_reference_origin;
      const SE2& T_true = true_robot.T_reference_origin;
      error.distance_m = (T.translation() - T_true.translation()).norm();
      error.angle_rad = std::abs(wrapAngle(T.theta() - T_true.theta()));
    }
    errors.push_back(error);
  }
  return errors;
}

void writePlacements(const TeamPlacements& placements, const std::string& path) {
  nlohmann::json robots = nlohmann::json::array();
  for (const RobotPlacement& robot : placements.robots) {
    const SE2& T = robot.T_reference_origin;
    const nlohmann::json none;
    robots.push_back({{"id", robot.id},
                      {"placed", robot.placed},
                      {"x", robot.placed ? nlohmann::json(T.x()) : none},
                      {"y", robot.placed ? nlohmann::json(T.y()) : none},
                      {"theta", robot.placed ? nlohmann::json(T.theta()) : none}});
  }
  std::ofstream file(path);
  file << nlohmann::json{{"reference", placements.reference}, {"robots", robots}}.dump(2) << "\n";
  if (!file) {
    throw std::runtime_error(path + ": cannot write");
  }
}

namespace {

namespace fs = std::filesystem;

/// T_c_e of every robot of `truth` whose trajectory and segment log are there.
std::map<std::string, SE2> alignments(const fs::path& out, const TeamPlacements& truth) {
  std::map<std::string, SE2> T_corrected_estimated;
  for (const RobotPlacement& robot : truth.robots) {
    const fs::path trajectory = out / "robots_local" / (robot.id + ".tum");
    if (robot.log.empty() || !fs::exists(trajectory)) {
      spdlog::warn("team: no trajectory of {} ({}): its truth stays the split's", robot.id,
                   trajectory.string());
      continue;
    }
    std::vector<SE2> estimated;
    for (const robot::StampedPose& pose : robot::readTumTrajectory(trajectory.string())) {
      estimated.push_back(pose.pose);
    }
    T_corrected_estimated[robot.id] =
        estimateToCorrected(estimated, correctedTrajectory(robot.log));
  }
  return T_corrected_estimated;
}

nlohmann::json errorJson(const PlacementError& error) {
  if (!error.placed) {
    return nullptr;
  }
  return {{"distance_m", error.distance_m}, {"angle_deg", error.angle_rad * 180.0 / M_PI}};
}

void evaluateOne(const fs::path& folder, const TeamPlacements& truth,
                 const TeamPlacements& truth_estimated) {
  const TeamPlacements found = readPlacements((folder / "transforms.json").string());
  const std::vector<PlacementError> split = comparePlacements(found, truth);
  const std::vector<PlacementError> estimated = comparePlacements(found, truth_estimated);
  nlohmann::json robots = nlohmann::json::array();
  for (std::size_t i = 0; i < split.size(); ++i) {
    robots.push_back({{"id", split[i].id},
                      {"placed", split[i].placed},
                      {"split_truth", errorJson(split[i])},
                      {"estimated_frames_truth", errorJson(estimated[i])}});
    if (split[i].placed) {
      spdlog::info(
          "team: {} placed {:.3f} m and {:.2f}° from the truth in the estimated frames "
          "({:.3f} m and {:.2f}° from the split's)",
          split[i].id, estimated[i].distance_m, estimated[i].angle_rad * 180.0 / M_PI,
          split[i].distance_m, split[i].angle_rad * 180.0 / M_PI);
    } else {
      spdlog::info("team: {} not placed", split[i].id);
    }
  }
  std::ofstream file(folder / "evaluation.json");
  file << nlohmann::json{{"reference", truth.reference}, {"robots", robots}}.dump(2) << "\n";
  if (!file) {
    throw std::runtime_error((folder / "evaluation.json").string() + ": cannot write");
  }
}

}  // namespace

bool evaluateTeamRun(const std::string& out, const std::vector<std::string>& fusion_folders) {
  const fs::path truth_path = fs::path(out) / "segments" / "truth.json";
  try {
    const TeamPlacements truth = readPlacements(truth_path.string());
    const TeamPlacements truth_estimated = truthInEstimatedFrames(truth, alignments(out, truth));
    writePlacements(truth_estimated,
                    (fs::path(out) / "segments" / "truth_estimated.json").string());
    for (const std::string& folder : fusion_folders) {
      evaluateOne(folder, truth, truth_estimated);
    }
  } catch (const std::exception& error) {
    spdlog::warn("team: no evaluation: {}", error.what());
    return false;
  }
  return true;
}

}  // namespace mrslam::tools
