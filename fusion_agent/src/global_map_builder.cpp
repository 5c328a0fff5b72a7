#include "mrslam/fusion/global_map_builder.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "mrslam/common/map_io.hpp"

namespace mrslam::fusion {

namespace {

void writeTransformsJson(const GlobalMapResult& result, const std::string& path) {
  nlohmann::json robots = nlohmann::json::array();
  for (const Placement& placement : result.placements) {
    nlohmann::json robot;
    robot["id"] = placement.robot_id;
    robot["placed"] = placement.placed;
    if (placement.placed) {
      robot["x"] = placement.T_reference_robot.x();
      robot["y"] = placement.T_reference_robot.y();
      robot["theta"] = placement.T_reference_robot.theta();
    } else {
      robot["x"] = nullptr;
      robot["y"] = nullptr;
      robot["theta"] = nullptr;
    }
    robot["verification"] =
        placement.verification ? nlohmann::json(*placement.verification) : nlohmann::json();
    robot["source"] = placement.source;
    robot["least_squares"] = placement.least_squares;
    robot["methods"] = placement.methods;
    robots.push_back(robot);
  }
  const nlohmann::json document = {{"reference", result.reference_robot}, {"robots", robots}};
  std::ofstream file(path);
  file << document.dump(2) << "\n";
  if (!file) {
    throw MapIoError(path + ": cannot write");
  }
}

void writeReceivedJson(const std::vector<RobotMap>& maps, const std::string& path) {
  nlohmann::json robots = nlohmann::json::array();
  for (const RobotMap& map : maps) {
    robots.push_back({{"id", map.robot_id},
                      {"sequence", map.sequence},
                      {"scans_inserted", map.scans_inserted},
                      {"final", map.is_final},
                      {"stale", map.stale},
                      {"stamp", map.stamp.toString()},
                      {"width", map.map.geometry.width},
                      {"height", map.map.geometry.height},
                      {"resolution", map.map.geometry.resolution_m}});
  }
  std::ofstream file(path);
  file << nlohmann::json{{"robots", robots}}.dump(2) << "\n";
  if (!file) {
    throw MapIoError(path + ": cannot write");
  }
}

}  // namespace

Eigen::Vector3i robotColour(std::size_t index) {
  static const Eigen::Vector3i kPalette[] = {{0, 0, 230},   {0, 160, 0},   {230, 80, 0},
                                             {0, 170, 230}, {200, 0, 200}, {120, 120, 0}};
  return kPalette[index % (sizeof(kPalette) / sizeof(kPalette[0]))];
}

std::vector<MapOverlay> robotOverlays(const GlobalMapResult& result,
                                      const std::vector<RobotMap>& maps) {
  std::vector<MapOverlay> overlays;
  for (std::size_t i = 0; i < result.placements.size() && i < maps.size(); ++i) {
    const Placement& placement = result.placements[i];
    if (!placement.placed) {
      continue;
    }
    MapOverlay overlay;
    overlay.bgr = robotColour(i);
    overlay.cells = occupiedCellsOf({&maps[i].map, placement.T_reference_robot}, result.map);
    for (const SE2& pose : maps[i].trajectory) {
      overlay.trajectory_m.push_back(placement.T_reference_robot * pose.translation());
    }
    overlays.push_back(std::move(overlay));
  }
  return overlays;
}

std::string chooseReference(const std::vector<RobotMap>& maps, const FusionConfig& config) {
  if (!config.reference_robot.empty()) {
    return config.reference_robot;
  }
  return maps.empty() ? std::string() : maps.front().robot_id;
}

GlobalMapResult buildGlobalMap(const std::vector<RobotMap>& maps, const std::string& reference,
                               const std::vector<Placement>& placements,
                               const ComposerSettings& composer) {
  GlobalMapResult result;
  result.reference_robot = reference;
  result.placements = placements;
  std::vector<PlacedMap> placed_maps;
  for (std::size_t i = 0; i < maps.size() && i < placements.size(); ++i) {
    result.stamp = std::max(result.stamp, maps[i].stamp);
    if (placements[i].placed) {
      placed_maps.push_back({&maps[i].map, placements[i].T_reference_robot});
    }
  }
  result.map = composeGlobalMap(placed_maps, composer);
  return result;
}

void writeFusionOutputs(const GlobalMapResult& result, const std::vector<RobotMap>& maps,
                        const std::string& folder, bool write_robot_maps) {
  const std::filesystem::path out(folder);
  std::filesystem::create_directories(out);
  writeTransformsJson(result, (out / "transforms.json").string());
  if (result.map.geometry.cellCount() > 0) {
    const std::vector<MapOverlay> overlays = robotOverlays(result, maps);
    saveMapYaml(result.map, (out / "global_map.yaml").string());
    saveMapPng(result.map, (out / "global_map.png").string(), overlays);
    saveMapOctomap(result.map, (out / "global_map.bt").string());
  }
  writeReceivedJson(maps, (out / "robots.json").string());
  if (write_robot_maps) {
    std::filesystem::create_directories(out / "robots");
    for (const RobotMap& map : maps) {
      saveMapYaml(map.map, (out / "robots" / (map.robot_id + ".yaml")).string());
    }
  }
}

}  // namespace mrslam::fusion
