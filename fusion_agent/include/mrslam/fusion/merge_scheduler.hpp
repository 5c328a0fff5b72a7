#pragma once
// Runs pairwise map merges in the background: rate-limited, re-run when a map has changed
// materially, verified results into the TeamGraph (a verified transform is kept and refined,
// never thrown away by a later refusal). A merge of maps still growing places a robot only once
// a merge of grown maps agrees with it (`confirmations`): early, small maps can fit a wrong place
// well. A merge of both robots' final maps is used at once.

#include <cmath>
#include <condition_variable>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "mrslam/fusion/merge/map_merger.hpp"
#include "mrslam/fusion/robot_map_store.hpp"
#include "mrslam/fusion/team_graph.hpp"

namespace mrslam::fusion {

struct MergeSchedulerSettings {
  double min_interval_s = 5.0;   ///< least time between two merges of one pair
  double material_change = 0.1;  ///< re-merge a pair when a map's known cells grew by this fraction
  bool refine_accepted = true;   ///< keep re-merging placed pairs as maps grow (refinement)
  int threads = 2;               ///< due pairs merged at once, each on its own thread
  /// Accepted merges of a pair, each on maps grown since the one before, that must agree before
  /// the pair places a robot (1: the first at once). A merge of both final maps counts alone, as
  /// does one that agrees with the pair's estimate in use.
  int confirmations = 2;
  double confirm_distance_m = 0.5;                ///< two merges agree: origins this close ...
  double confirm_angle_rad = 3.0 * M_PI / 180.0;  ///< ... and turned less than this
};

/// One merge that was run, for the transforms topic and the logs.
struct MergeAttempt {
  std::string from;
  std::string to;
  MergeResult result;
  SE2 T_to_from;  ///< metric, valid when accepted
  double time_ms = 0.0;
};

class MergeScheduler {
 public:
  using MergerFactory = std::function<std::unique_ptr<MapMerger>()>;
  using Clock = std::chrono::steady_clock;

  MergeScheduler(const MergeSchedulerSettings& settings, MergerFactory factory, TeamGraph& graph);
  ~MergeScheduler();
  MergeScheduler(const MergeScheduler&) = delete;
  MergeScheduler& operator=(const MergeScheduler&) = delete;

  /// Starts the background thread.
  void start();
  /// Hands the newest maps to the background thread (returns at once).
  void offer(std::vector<RobotMap> maps);
  /// Waits until the maps last offered have been considered; false on time-out.
  bool waitIdle(double timeout_s);
  /// Merges every due pair of `maps` now, `threads` pairs at a time (the calling thread one of
  /// them; the background thread's step): pairs without a verified transform first, each group
  /// in pair order, the attempts in that order.
  std::vector<MergeAttempt> runDue(const std::vector<RobotMap>& maps, Clock::time_point now);
  /// Attempts made since the last call.
  std::vector<MergeAttempt> takeAttempts();
  void stop();

 private:
  struct PairState {
    Clock::time_point last_attempt{};
    std::size_t known_from = 0;
    std::size_t known_to = 0;
    bool attempted = false;
    bool final_merged = false;  ///< the last attempt had both robots' final maps
    /// The last accepted merge not yet in use, and how many agreeing ones it closes.
    std::optional<PairwiseEstimate> pending;
    int agreeing = 0;
  };
  /// What isDue needs of the two maps of a pair.
  struct PairMaps {
    std::size_t known_from = 0;
    std::size_t known_to = 0;
    bool both_final = false;
  };

  bool isDue(const PairState& state, const PairMaps& maps, bool placed,
             Clock::time_point now) const;
  /// One merge (on any thread; `state` is this pair's alone): the attempt, and a verified result
  /// into the graph once confirmed.
  MergeAttempt mergePair(MapMerger& merger, const RobotMap& from, const RobotMap& to,
                         PairState& state);
  /// What to do with a merge just accepted.
  struct Confirmation {
    bool use = false;  ///< into the graph now (else it waits in the pair's `pending`)
    std::optional<PairwiseEstimate> replaced;  ///< the estimate in use it outweighs and replaces
    std::string note;                          ///< why it waits, or what confirmed it
  };
  Confirmation confirm(const PairwiseEstimate& estimate, PairState& state) const;
  void loop();

  MergeSchedulerSettings settings_;
  MergerFactory factory_;
  TeamGraph& graph_;
  std::map<std::pair<std::string, std::string>, PairState> pairs_;

  std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable idle_;
  std::vector<RobotMap> offered_;
  std::uint64_t offered_version_ = 0;
  std::uint64_t done_version_ = 0;
  bool stopping_ = false;
  std::vector<MergeAttempt> attempts_;
  std::thread thread_;
};

/// Known cells of a map (for the material-change rule).
std::size_t knownCellCount(const GridMap& map);
/// The material-change rule: a map's known cells grew by more than `material_change` (a fraction)
/// since `then_known`.
bool grewMaterially(std::size_t now_known, std::size_t then_known, double material_change);

}  // namespace mrslam::fusion
