#pragma once
// The rendezvous the fusion agent holds: each is checked against the two robots' maps when both
// have arrived, again whenever they change while it still waits for overlap, then again when
// either map has grown materially, and once more on both robots' final maps, verified or refused
// before. A fit on early, partial maps can slide along a corridor that has nothing to stop it (its
// V stays high, the overlap being small), and early maps can refuse a right one; the final maps
// hold every scan, so their check is the one that counts, whatever the earlier checks saw.

#include <cstdint>
#include <vector>

#include "mrslam/fusion/rendezvous.hpp"
#include "mrslam/fusion/robot_map_store.hpp"

namespace mrslam::fusion {

/// One check of a rendezvous against the maps.
struct RendezvousOutcome {
  RendezvousHypothesis hypothesis;
  RendezvousCheck check;
  bool on_final_maps = false;  ///< both robots' maps were final
  /// The rendezvous had been verified before, at `previous_T_to_from` (refused now: that
  /// estimate is no longer backed by the maps).
  bool was_verified = false;
  SE2 previous_T_to_from;
  /// Fewer known cells overlap than the check needs: a rendezvous not yet verified then waits
  /// for the maps to grow (unless they are final).
  bool short_of_overlap = false;
  double time_ms = 0.0;
};

class RendezvousTracker {
 public:
  /// `material_change`: a verified rendezvous is checked again when either map's known cells
  /// grew by this fraction since its last check.
  RendezvousTracker(RendezvousSettings settings, double material_change, std::size_t max_held)
      : settings_(settings), material_change_(material_change), max_held_(max_held) {}

  /// Holds new hypotheses (the oldest are dropped beyond max_held).
  void add(const std::vector<RendezvousHypothesis>& hypotheses);
  /// Whether checkDue could check anything: rendezvous are held and either they or the maps
  /// (the store's `version`) changed since the last checkDue.
  bool needsCheck(std::uint64_t version) const {
    return !held_.empty() && (version != seen_version_ || added_since_seen_);
  }
  /// Checks every held rendezvous that is due against `maps` (the store at `version`).
  std::vector<RendezvousOutcome> checkDue(const std::vector<RobotMap>& maps, std::uint64_t version);
  std::size_t held() const { return held_.size(); }

 private:
  struct Held {
    RendezvousHypothesis hypothesis;
    std::uint64_t checked_at_version = 0;
    bool verified = false;            ///< accepted at its last check
    bool waiting_for_overlap = true;  ///< not checked yet, or short of overlap at its last check
    SE2 T_to_from;                    ///< the last verified fit
    std::size_t known_from = 0;
    std::size_t known_to = 0;
  };
  struct MapsOfPair {
    const RobotMap* from = nullptr;
    const RobotMap* to = nullptr;
    std::size_t known_from = 0;
    std::size_t known_to = 0;
    bool both_final() const { return from->is_final && to->is_final; }
  };

  bool isDue(const Held& held, const MapsOfPair& maps, std::uint64_t version) const;
  /// Checks `held` and says whether it stays held.
  bool check(Held& held, const MapsOfPair& maps, std::uint64_t version,
             std::vector<RendezvousOutcome>& outcomes) const;

  RendezvousSettings settings_;
  double material_change_;
  std::size_t max_held_;
  std::vector<Held> held_;
  std::uint64_t seen_version_ = 0;  ///< the store's version at the last checkDue
  bool added_since_seen_ = false;
};

}  // namespace mrslam::fusion
