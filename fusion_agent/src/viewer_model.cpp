#include "mrslam/fusion/viewer_model.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>

#include "mrslam/common/map_io.hpp"

namespace mrslam::fusion {

namespace {

using nlohmann::json;

/// Every robot the viewer knows (a map or a status), in id order: its index picks its colour.
std::vector<std::string> knownRobots(const std::vector<RobotMap>& maps,
                                     const std::map<std::string, RobotHealth>& health) {
  std::set<std::string> ids;
  for (const RobotMap& map : maps) {
    ids.insert(map.robot_id);
  }
  for (const auto& entry : health) {
    ids.insert(entry.first);
  }
  return {ids.begin(), ids.end()};
}

std::size_t indexOf(const std::vector<std::string>& ids, const std::string& id) {
  for (std::size_t i = 0; i < ids.size(); ++i) {
    if (ids[i] == id) {
      return i;
    }
  }
  return ids.size();
}

std::string cssColour(const Eigen::Vector3i& bgr) {
  char text[8];
  std::snprintf(text, sizeof(text), "#%02x%02x%02x", bgr.z() & 0xff, bgr.y() & 0xff,
                bgr.x() & 0xff);
  return text;
}

json poseJson(const SE2& pose) {
  return {{"x", pose.x()}, {"y", pose.y()}, {"theta", pose.theta()}};
}

double secondsSince(ViewerModel::Clock::time_point then) {
  return std::chrono::duration<double>(ViewerModel::Clock::now() - then).count();
}

/// At most `limit` poses of the trajectory (the last always kept), mapped by T.
json trajectoryJson(const std::vector<SE2>& trajectory, const SE2& T, std::size_t limit) {
  json points = json::array();
  if (trajectory.empty() || limit == 0) {
    return points;
  }
  const std::size_t step = (trajectory.size() + limit - 1) / limit;
  for (std::size_t i = 0; i < trajectory.size(); i += step) {
    const Eigen::Vector2d p = T * trajectory[i].translation();
    points.push_back({p.x(), p.y()});
  }
  if ((trajectory.size() - 1) % step != 0) {
    const Eigen::Vector2d p = T * trajectory.back().translation();
    points.push_back({p.x(), p.y()});
  }
  return points;
}

json healthJson(const RobotHealth& health) {
  json sensors = json::array();
  for (const SensorReport& sensor : health.sensors) {
    sensors.push_back({{"name", sensor.name},
                       {"source", sensor.source},
                       {"healthy", sensor.healthy},
                       {"rate_hz", sensor.rate_hz},
                       {"samples", sensor.samples},
                       {"errors", sensor.errors}});
  }
  return {{"state", health.state},
          {"message", health.message},
          {"scans_processed", health.scans_processed},
          {"malformed_records", health.malformed_records},
          {"maps_published", health.maps_published},
          {"seconds_since_status", secondsSince(health.received)},
          {"sensors", sensors}};
}

json mapJson(const RobotMap& map) {
  const GridGeometry& g = map.map.geometry;
  return {{"sequence", map.sequence},
          {"scans_inserted", map.scans_inserted},
          {"final", map.is_final},
          {"stale", map.stale},
          {"width", g.width},
          {"height", g.height},
          {"seconds_since_map", secondsSince(map.received)}};
}

json geometryJson(const GridMap& map) {
  const GridGeometry& g = map.geometry;
  if (g.cellCount() == 0) {
    return nullptr;
  }
  return {{"width", g.width},
          {"height", g.height},
          {"resolution", g.resolution_m},
          {"origin", {g.origin_m.x(), g.origin_m.y()}}};
}

json attemptJson(const MergeAttempt& attempt) {
  const MergeResult& result = attempt.result;
  json pair = {{"from", attempt.from},
               {"to", attempt.to},
               {"accepted", result.accepted},
               {"method", result.method},
               {"verification", result.verification},
               {"entropy", result.entropy},
               {"trials", result.trials},
               {"time_ms", attempt.time_ms},
               {"reason", result.reason}};
  pair["transform"] = result.accepted ? poseJson(attempt.T_to_from) : json();
  return pair;
}

}  // namespace

void ViewerModel::setGlobalMap(const GlobalMapResult& result, const std::vector<RobotMap>& maps) {
  std::lock_guard<std::mutex> lock(mutex_);
  result_ = result;
  maps_ = maps;
  ++revision_;
}

void ViewerModel::addAttempt(const MergeAttempt& attempt) {
  std::lock_guard<std::mutex> lock(mutex_);
  attempts_[{attempt.from, attempt.to}] = attempt;
  ++revision_;
}

void ViewerModel::setHealth(const std::string& robot_id, RobotHealth health) {
  std::lock_guard<std::mutex> lock(mutex_);
  health.received = Clock::now();
  health_[robot_id] = std::move(health);
  ++revision_;
}

std::uint64_t ViewerModel::revision() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return revision_;
}

std::string ViewerModel::stateJson() const {
  std::lock_guard<std::mutex> lock(mutex_);
  const std::vector<std::string> ids = knownRobots(maps_, health_);
  json robots = json::array();
  for (std::size_t index = 0; index < ids.size(); ++index) {
    json robot = {{"id", ids[index]}, {"colour", cssColour(robotColour(index))}};
    robot["placed"] = false;
    robot["source"] = "no map yet";
    robot["pose"] = nullptr;
    robot["map"] = nullptr;
    robot["trajectory"] = json::array();
    for (std::size_t i = 0; i < maps_.size() && i < result_.placements.size(); ++i) {
      if (maps_[i].robot_id != ids[index]) {
        continue;
      }
      const Placement& placement = result_.placements[i];
      robot["placed"] = placement.placed;
      robot["source"] = placement.source;
      robot["verification"] = placement.verification ? json(*placement.verification) : json();
      robot["map"] = mapJson(maps_[i]);
      if (placement.placed) {
        const SE2& T = placement.T_reference_robot;
        robot["origin"] = poseJson(T);
        if (!maps_[i].trajectory.empty()) {
          robot["pose"] = poseJson(T * maps_[i].trajectory.back());
        }
        robot["trajectory"] = trajectoryJson(maps_[i].trajectory, T, limits_.max_trajectory_points);
      }
    }
    const auto health = health_.find(ids[index]);
    robot["health"] = health == health_.end() ? json() : healthJson(health->second);
    robots.push_back(robot);
  }
  json pairs = json::array();
  for (const auto& entry : attempts_) {
    pairs.push_back(attemptJson(entry.second));
  }
  const json state = {{"revision", revision_},
                      {"reference", result_.reference_robot},
                      {"map", geometryJson(result_.map)},
                      {"robots", robots},
                      {"pairs", pairs}};
  return state.dump();
}

std::vector<std::uint8_t> ViewerModel::globalMapPng() const {
  std::lock_guard<std::mutex> lock(mutex_);
  if (result_.map.geometry.cellCount() == 0) {
    return {};
  }
  if (global_png_revision_ != revision_ || global_png_.empty()) {
    const std::vector<std::string> ids = knownRobots(maps_, health_);
    std::vector<MapOverlay> overlays = robotOverlays(result_, maps_);
    std::size_t overlay = 0;
    for (std::size_t i = 0; i < result_.placements.size() && overlay < overlays.size(); ++i) {
      if (result_.placements[i].placed) {
        overlays[overlay++].bgr = robotColour(indexOf(ids, result_.placements[i].robot_id));
      }
    }
    global_png_ = encodeMapPng(result_.map, overlays);
    global_png_revision_ = revision_;
  }
  return global_png_;
}

std::optional<std::vector<std::uint8_t>> ViewerModel::robotMapPng(
    const std::string& robot_id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const RobotMap& map : maps_) {
    if (map.robot_id == robot_id && map.map.geometry.cellCount() > 0) {
      return encodeMapPng(map.map);
    }
  }
  return std::nullopt;
}

}  // namespace mrslam::fusion
