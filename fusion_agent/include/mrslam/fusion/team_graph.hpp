#pragma once
// The team's pairwise transforms and the placement of every robot in one frame.
//
// Edges are verified pairwise estimates T_to_from (the pose of robot `from`'s map origin in robot
// `to`'s map frame) or transforms fixed by configuration. A verified edge is kept until a
// better-verified estimate of the same pair replaces it; a later refusal never removes it.
// Robots are placed through the best path from the reference robot: the path whose product of
// verification indices is largest (configured edges count as V = 1). A robot with no path to the
// reference is reported as not placed, never guessed.
//
// Loops (three or more robots): edges are taken in order of confidence (configured first, then
// by V); an edge that joins two robots already connected by the edges taken must agree with the
// transform along them within the loop tolerance, or it is dropped and reported — one wrong
// merge in a loop of right ones cannot move a robot. With redundant edges left (loops), the
// placement is the least-squares one over all of them (pose_graph.hpp), each edge weighted by
// its V: the errors of the pairwise estimates are spread over the loop instead of being piled
// on the robots at its far end.

#include <cmath>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mrslam/common/se2.hpp"
#include "mrslam/common/stamp.hpp"
#include "mrslam/fusion/placement.hpp"

namespace mrslam::fusion {

struct PairwiseEstimate {
  std::string from;
  std::string to;
  SE2 T_to_from;
  double verification = 1.0;  ///< V of the merge (1 for configured transforms)
  double entropy = 0.0;
  std::string method;  ///< "config", "seed", "feature", ...
  bool configured = false;
  bool from_final_maps = false;  ///< merged from both robots' final maps (every scan in them)
};

/// An edge the loop check dropped, and why.
struct DroppedEdge {
  PairwiseEstimate estimate;
  /// Where it and the loop's other edges put `from`'s map origin in `to`'s frame: the distance
  /// between the two, and the difference of their headings.
  double translation_error_m = 0.0;
  double rotation_error_rad = 0.0;
};

struct LoopTolerance {
  double translation_m = 0.25;  ///< largest disagreement of an edge with a loop, in translation
  double rotation_rad = 2.0 * M_PI / 180.0;  ///< ... and in rotation
};

/// Weights of the least-squares placement: an estimate with verification V counts with standard
/// deviations σ / V; a configured transform with σ_config (it does not move).
struct PlacementWeights {
  double sigma_translation_m = 0.05;         ///< an estimate's translation σ at V = 1
  double sigma_rotation_rad = M_PI / 360.0;  ///< an estimate's rotation σ at V = 1 (0.5°)
  double sigma_config_translation_m = 1e-4;  ///< a configured transform's translation σ
  double sigma_config_rotation_rad = 1e-5;   ///< a configured transform's rotation σ
};

class TeamGraph {
 public:
  explicit TeamGraph(LoopTolerance tolerance = {}, PlacementWeights weights = {})
      : tolerance_(tolerance), weights_(weights) {}
  /// A transform fixed by configuration (never replaced by estimates).
  void addConfigured(const std::string& from, const std::string& to, const SE2& T_to_from);
  /// Stores a verified estimate unless the pair already holds a better one: a configured one,
  /// one from final maps when this one is not (final maps hold every scan: their merge is the
  /// best informed, whatever an earlier, smaller overlap's V), or one of the same kind with a
  /// higher V. Returns whether it was stored.
  bool addVerified(const PairwiseEstimate& estimate);
  /// Removes the pair's estimate when it is the one given (T_to_from equal, not configured):
  /// the maps no longer back it. Returns whether it was removed.
  bool withdraw(const std::string& from, const std::string& to, const SE2& T_to_from);
  /// In one step (a reader never sees the pair without an edge): when the pair holds the
  /// estimate `T_to_from_replaced` (as withdraw() matches it), `estimate` takes its place
  /// whatever the V of either; otherwise this is addVerified(estimate). Returns whether it was
  /// stored.
  bool replaceVerified(const PairwiseEstimate& estimate, const SE2& T_to_from_replaced);

  /// The stored estimate between two robots, expressed as T_to_from (inverted when stored the
  /// other way round).
  std::optional<PairwiseEstimate> estimate(const std::string& from, const std::string& to) const;
  std::vector<PairwiseEstimate> estimates() const;

  /// Placement of each of `robots` in the frame of `reference` (through the edges the loop
  /// check keeps).
  std::vector<Placement> place(const std::string& reference,
                               const std::vector<std::string>& robots) const;
  /// The edges the loop check drops now.
  std::vector<DroppedEdge> dropped() const;

 private:
  /// Splits the edges into those that agree with the loops they close and those that do not.
  std::vector<PairwiseEstimate> consistentEdges(std::vector<DroppedEdge>* dropped) const;
  /// The least-squares poses of the robots in `initial` over the kept edges between them (the
  /// reference held fixed); none when the edges form no loop (the paths' poses stand).
  std::optional<std::map<std::string, SE2>> leastSquares(
      const std::string& reference, const std::map<std::string, SE2>& initial,
      const std::vector<PairwiseEstimate>& kept) const;
  LoopTolerance tolerance_;
  PlacementWeights weights_;
  using PairKey = std::pair<std::string, std::string>;  // ordered (smaller id first)
  static PairKey keyOf(const std::string& a, const std::string& b);
  /// addVerified() with mutex_ held.
  bool storeUnlessBetterHeld(const PairKey& key, const PairwiseEstimate& estimate);
  /// The held, not configured edge of `key` when it is the estimate T_to_from of from's pair.
  std::map<PairKey, PairwiseEstimate>::iterator heldEstimate(const PairKey& key,
                                                             const std::string& from,
                                                             const SE2& T_to_from);

  mutable std::mutex mutex_;
  std::map<PairKey, PairwiseEstimate> edges_;
};

}  // namespace mrslam::fusion
