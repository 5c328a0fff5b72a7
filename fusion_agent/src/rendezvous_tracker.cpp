// The rendezvous held by the fusion agent and when each is checked (rendezvous_tracker.hpp).

#include "mrslam/fusion/rendezvous_tracker.hpp"

#include <chrono>
#include <map>

#include "mrslam/fusion/merge_scheduler.hpp"

namespace mrslam::fusion {

namespace {

const RobotMap* mapOf(const std::vector<RobotMap>& maps, const std::string& robot_id) {
  for (const RobotMap& map : maps) {
    if (map.robot_id == robot_id) {
      return &map;
    }
  }
  return nullptr;
}

}  // namespace

void RendezvousTracker::add(const std::vector<RendezvousHypothesis>& hypotheses) {
  for (const RendezvousHypothesis& hypothesis : hypotheses) {
    held_.push_back({hypothesis, 0, false, true, SE2(), 0, 0});
    added_since_seen_ = true;
  }
  if (held_.size() > max_held_) {
    held_.erase(held_.begin(), held_.end() - static_cast<std::ptrdiff_t>(max_held_));
  }
}

bool RendezvousTracker::isDue(const Held& held, const MapsOfPair& maps,
                              std::uint64_t version) const {
  if (held.checked_at_version == version) {
    return false;
  }
  if (held.waiting_for_overlap) {
    return true;  // not checked yet, or short of overlap: every change of the maps may bring it
  }
  if (maps.both_final()) {
    return true;  // every rendezvous is checked once on the final maps, then dropped
  }
  return grewMaterially(maps.known_from, held.known_from, material_change_) ||
         grewMaterially(maps.known_to, held.known_to, material_change_);
}

bool RendezvousTracker::check(Held& held, const MapsOfPair& maps, std::uint64_t version,
                              std::vector<RendezvousOutcome>& outcomes) const {
  const auto started = std::chrono::steady_clock::now();
  RendezvousOutcome outcome;
  outcome.hypothesis = held.hypothesis;
  outcome.check = checkRendezvous(held.hypothesis, maps.from->map, maps.to->map, settings_);
  outcome.time_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  outcome.on_final_maps = maps.both_final();
  outcome.was_verified = held.verified;
  outcome.previous_T_to_from = held.T_to_from;
  outcome.short_of_overlap = outcome.check.overlap_cells < settings_.min_overlap_cells;
  outcomes.push_back(outcome);

  held.checked_at_version = version;
  held.known_from = maps.known_from;
  held.known_to = maps.known_to;
  held.verified = outcome.check.accepted;
  held.waiting_for_overlap = !held.verified && outcome.short_of_overlap;
  if (held.verified) {
    held.T_to_from = outcome.check.T_to_from;
  }
  // Refused or not, a rendezvous stays until the final maps' check, the one that counts: early
  // maps can refuse a right one (a door closed then, a person in the way) as they can let a
  // wrong one through, and which early maps a check sees depends on when the messages came.
  return !outcome.on_final_maps;
}

std::vector<RendezvousOutcome> RendezvousTracker::checkDue(const std::vector<RobotMap>& maps,
                                                           std::uint64_t version) {
  std::vector<RendezvousOutcome> outcomes;
  if (!needsCheck(version)) {
    return outcomes;  // the loop asks often: neither the maps nor the rendezvous changed
  }
  seen_version_ = version;
  added_since_seen_ = false;
  std::map<std::string, std::size_t> known;  // per robot, counted once
  const auto knownOf = [&known](const RobotMap& map) {
    const auto [entry, added] = known.try_emplace(map.robot_id, 0);
    if (added) {
      entry->second = knownCellCount(map.map);
    }
    return entry->second;
  };
  std::vector<Held> still_held;
  for (Held& held : held_) {
    MapsOfPair pair{mapOf(maps, held.hypothesis.from), mapOf(maps, held.hypothesis.to), 0, 0};
    if (pair.from == nullptr || pair.to == nullptr) {
      still_held.push_back(held);  // wait for both maps
      continue;
    }
    pair.known_from = knownOf(*pair.from);
    pair.known_to = knownOf(*pair.to);
    if (!isDue(held, pair, version) || check(held, pair, version, outcomes)) {
      still_held.push_back(held);
    }
  }
  held_ = std::move(still_held);
  return outcomes;
}

}  // namespace mrslam::fusion
