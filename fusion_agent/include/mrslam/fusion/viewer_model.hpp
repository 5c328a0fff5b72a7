#pragma once
// What the live viewer shows, kept up to date by the fusion agent and read by the HTTP server's
// threads: the global map and placements, each robot's map, pose, trajectory and health, and the
// newest merge of every robot pair. Thread-safe; pictures are encoded on request and cached per
// revision.

#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mrslam/fusion/global_map_builder.hpp"
#include "mrslam/fusion/merge_scheduler.hpp"

namespace mrslam::fusion {

/// One sensor of a robot as its status reports it.
struct SensorReport {
  std::string name;    ///< "laser", "imu", "encoders", "odometry"
  std::string source;  ///< "device", "replay", "simulator", "absent"
  bool healthy = false;
  double rate_hz = 0.0;
  std::uint64_t samples = 0;
  std::uint64_t errors = 0;
};

/// A robot's newest status message.
struct RobotHealth {
  std::string state;  ///< "starting", "running", "finished", "failed"
  std::string message;
  std::vector<SensorReport> sensors;
  std::uint64_t scans_processed = 0;
  std::uint64_t malformed_records = 0;
  std::uint64_t maps_published = 0;
  std::chrono::steady_clock::time_point received{};
};

/// Bounds of what the state document carries.
struct ViewerLimits {
  std::size_t max_trajectory_points = 400;  ///< per robot, evenly thinned
};

class ViewerModel {
 public:
  using Clock = std::chrono::steady_clock;

  explicit ViewerModel(ViewerLimits limits = {}) : limits_(limits) {}

  /// The newest global map with the maps it was built from (one placement per map, same order).
  void setGlobalMap(const GlobalMapResult& result, const std::vector<RobotMap>& maps);
  /// The newest merge of the pair (from, to) replaces the one before.
  void addAttempt(const MergeAttempt& attempt);
  void setHealth(const std::string& robot_id, RobotHealth health);

  /// Increases on every change.
  std::uint64_t revision() const;
  /// The state document (JSON text): revision, reference, map geometry, robots (every robot with
  /// a map or a status: colour, placed, pose and trajectory in the reference frame, health) and
  /// pairs (method, accepted, V, entropy, reason).
  std::string stateJson() const;
  /// PNG of the global map with each robot's cells and trajectory in its colour; empty when
  /// there is no global map yet.
  std::vector<std::uint8_t> globalMapPng() const;
  /// PNG of one robot's own map; none when the robot has no map.
  std::optional<std::vector<std::uint8_t>> robotMapPng(const std::string& robot_id) const;

 private:
  const ViewerLimits limits_;
  mutable std::mutex mutex_;
  std::uint64_t revision_ = 0;
  GlobalMapResult result_;
  std::vector<RobotMap> maps_;
  std::map<std::pair<std::string, std::string>, MergeAttempt> attempts_;
  std::map<std::string, RobotHealth> health_;
  mutable std::uint64_t global_png_revision_ = 0;
  mutable std::vector<std::uint8_t> global_png_;
};

}  // namespace mrslam::fusion
