#pragma once
// The newest local map of every robot, as received (thread-safe: DDS listeners write, the
// fusion loop reads).

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <vector>

#include "mrslam/common/grid_map.hpp"
#include "mrslam/common/se2.hpp"
#include "mrslam/common/stamp.hpp"

namespace mrslam::fusion {

struct RobotMap {
  std::string robot_id;
  Stamp stamp;
  std::uint64_t sequence = 0;
  std::uint64_t scans_inserted = 0;
  bool is_final = false;
  std::uint64_t sightings_published = 0;  ///< the robot's sightings written before this map
  bool stale = false;  ///< its agent fell silent (lease ran out): the last map is kept, flagged
  GridMap map;
  std::vector<SE2> trajectory;                       ///< robot poses in its own map frame
  std::chrono::steady_clock::time_point received{};  ///< when the store took it
};

class RobotMapStore {
 public:
  enum class Outcome { kStored, kOutdated };

  /// Keeps `map` unless the store holds a newer one of that robot (higher sequence number). A
  /// map from a new agent of the robot (`restarted`: its numbering starts again) replaces the
  /// old one whatever its number. A stored map is not stale.
  Outcome update(RobotMap map, bool restarted = false);
  /// Flags (or unflags) a robot's map as stale; true when that changed the flag (false when it
  /// was already so, or the store has no map of the robot).
  bool setStale(const std::string& robot_id, bool stale);

  /// A copy of every robot's newest map, ordered by robot id.
  std::vector<RobotMap> snapshot() const;
  /// Increases on every stored map.
  std::uint64_t version() const;
  /// Waits up to `timeout` for the version to move past `seen`; true when it has.
  bool waitForChange(std::uint64_t seen, std::chrono::milliseconds timeout) const;
  bool has(const std::string& robot_id) const;
  /// Robots whose map is flagged stale.
  std::size_t staleCount() const;
  bool isFinal(const std::string& robot_id) const;
  /// The sightings the robot wrote before its newest map (0 without a map).
  std::uint64_t sightingsPublished(const std::string& robot_id) const;

 private:
  mutable std::mutex mutex_;
  mutable std::condition_variable changed_;
  std::map<std::string, RobotMap> maps_;
  std::uint64_t version_ = 0;
};

}  // namespace mrslam::fusion
