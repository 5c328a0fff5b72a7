#pragma once
// The fusion agent's main loop: hands new maps to the merge scheduler, places the robots,
// publishes the global map when something changed, writes files when due, and stops when the
// expected robots are done, on time-out or on Ctrl-C.

#include <chrono>
#include <memory>
#include <optional>
#include <set>

#include "fusion_node.hpp"
#include "live_viewer.hpp"
#include "mrslam/fusion/merge_scheduler.hpp"
#include "mrslam/fusion/rendezvous_tracker.hpp"
#include "mrslam/fusion/team_graph.hpp"

namespace mrslam::fusion {

class FusionLoop {
 public:
  explicit FusionLoop(const FusionConfig& config);

  /// Runs until done; the exit code: 0 done, 2 gave up waiting for expected robots.
  int run(const std::atomic<bool>& shutdown);

 private:
  using Clock = std::chrono::steady_clock;

  bool allExpectedFinal() const;
  std::string missingRobots() const;
  /// The expected robots whose final map counts sightings not yet received ("robot2 (1 of 3)").
  std::string sightingsOutstanding() const;
  /// Whether the sightings the final maps count are in, or waited for long enough.
  bool finalSightingsHeld();
  /// Rebuilds and publishes the global map from the newest maps and placements.
  void publish();
  /// Logs (once each) the merges the loop check drops.
  void reportDroppedEdges();
  void writeFiles();
  void publishAttempts();
  void finalMerges();
  /// Checks the rendezvous received, and those held, against the maps when due
  /// (rendezvous_tracker.hpp); a verified one becomes a pairwise estimate of the team graph.
  void checkRendezvous();
  /// Publishes a check's attempt and updates the team graph with it.
  void useRendezvousOutcome(const RendezvousOutcome& outcome);

  const FusionConfig& config_;
  RobotMapStore store_;
  TeamGraph graph_;
  std::set<std::string> reported_drops_;       ///< "from>to" of edges the loop check dropped
  std::unique_ptr<ViewerModel> viewer_model_;  ///< set when the live viewer is on
  FusionNode node_;
  std::unique_ptr<LiveViewer> viewer_;
  std::unique_ptr<MergeScheduler> scheduler_;
  std::vector<RobotMap> maps_;
  GlobalMapResult result_;
  std::uint64_t sequence_ = 0;
  std::uint64_t offered_version_ = 0;
  bool changed_ = false;
  bool written_ = false;
  std::optional<Clock::time_point> final_maps_since_;  ///< when sightings were first missed
  RendezvousTracker rendezvous_;  ///< held rendezvous, checked against the maps when due
};

}  // namespace mrslam::fusion
