#include "mrslam/fusion/robot_map_store.hpp"

namespace mrslam::fusion {

RobotMapStore::Outcome RobotMapStore::update(RobotMap map, bool restarted) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto found = maps_.find(map.robot_id);
  if (!restarted && found != maps_.end() && found->second.sequence >= map.sequence) {
    return Outcome::kOutdated;
  }
  map.stale = false;
  map.received = std::chrono::steady_clock::now();
  const std::string robot_id = map.robot_id;
  maps_[robot_id] = std::move(map);
  ++version_;
  changed_.notify_all();
  return Outcome::kStored;
}

bool RobotMapStore::setStale(const std::string& robot_id, bool stale) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto found = maps_.find(robot_id);
  if (found == maps_.end()) {
    return false;
  }
  if (found->second.stale == stale) {
    return false;
  }
  found->second.stale = stale;
  ++version_;  // the outputs change
  changed_.notify_all();
  return true;
}

std::vector<RobotMap> RobotMapStore::snapshot() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<RobotMap> maps;
  maps.reserve(maps_.size());
  for (const auto& entry : maps_) {
    maps.push_back(entry.second);
  }
  return maps;
}

std::uint64_t RobotMapStore::version() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return version_;
}

bool RobotMapStore::waitForChange(std::uint64_t seen, std::chrono::milliseconds timeout) const {
  std::unique_lock<std::mutex> lock(mutex_);
  return changed_.wait_for(lock, timeout, [&] { return version_ != seen; });
}

std::size_t RobotMapStore::staleCount() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::size_t stale = 0;
  for (const auto& entry : maps_) {
    stale += entry.second.stale ? 1 : 0;
  }
  return stale;
}

bool RobotMapStore::has(const std::string& robot_id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return maps_.count(robot_id) != 0;
}

bool RobotMapStore::isFinal(const std::string& robot_id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto found = maps_.find(robot_id);
  return found != maps_.end() && found->second.is_final;
}

std::uint64_t RobotMapStore::sightingsPublished(const std::string& robot_id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto found = maps_.find(robot_id);
  return found == maps_.end() ? 0 : found->second.sightings_published;
}

}  // namespace mrslam::fusion
