#pragma once
// The pose graph of the robot's SLAM (Hess et al., ICRA 2016, section V): scan nodes and submap
// nodes in the global (map) frame, tied by relative poses measured in the submap's frame:
//  - intra-submap constraints: where local SLAM inserted a scan into a submap;
//  - loop closures: a scan matched against a finished submap (branch and bound, then least
//    squares), under a Huber loss so one wrong match cannot pull the graph far;
//  - local-SLAM edges between consecutive scan nodes (their local poses' difference).
// Each constraint's error, in the first frame, is e = (R(θ_a)ᵀ(t_b − t_a) − t_ab, θ_b − θ_a −
// θ_ab), weighted by 1/σ of translation and rotation. Solved by Ceres (sparse normal Cholesky); the
// first submap is held fixed. After a solve, a loop closure whose error is still beyond
// max_closure_error_{m,rad} is refused and the graph solved again without it.

#include <cstdint>
#include <vector>

#include "mrslam/common/se2.hpp"

namespace mrslam::robot::slam {

struct PoseGraphSettings {
  double local_sigma_m = 0.01;       ///< σ of a local-SLAM edge's translation
  double local_sigma_rad = 0.002;    ///< ... and rotation
  double intra_sigma_m = 0.05;       ///< σ of an intra-submap constraint's translation
  double intra_sigma_rad = 0.01;     ///< ... and rotation
  double closure_sigma_m = 0.01;     ///< σ of a loop closure's translation
  double closure_sigma_rad = 0.002;  ///< ... and rotation (as firm as local SLAM's edges)
  /// Huber loss of loop closures, in σ: a closure off by more than 10 σ (10 cm, 1°) pulls with a
  /// constant force, so one wrong match among the many right ones cannot drag the graph.
  double closure_huber_scale = 10.0;
  double max_closure_error_m = 0.5;    ///< after a solve, a closure this far off is refused
  double max_closure_error_rad = 0.1;  ///< ... or turned this far
  int max_iterations = 50;             ///< Ceres iterations per solve
};

struct PoseGraphConstraint {
  enum class Kind { kIntraSubmap, kLoopClosure };
  int submap = 0;
  int node = 0;
  SE2 T_submap_node;
  Kind kind = Kind::kIntraSubmap;
  bool active = true;  ///< false once refused by its residual
};

struct PoseGraphCounters {
  std::uint64_t solves = 0;
  std::uint64_t closures_refused = 0;  ///< by their residual after a solve
};

class PoseGraph {
 public:
  explicit PoseGraph(const PoseGraphSettings& settings);

  /// A scan node at its first guess of T_map_node; returns its index. Consecutive nodes are tied
  /// by T_previous_node, the difference of their local poses (none for the first node).
  int addNode(const SE2& T_map_node, const SE2& T_local_node);
  /// A submap at its first guess of T_map_submap; returns its index.
  int addSubmap(const SE2& T_map_submap);
  void addConstraint(const PoseGraphConstraint& constraint);

  /// Solves, refuses loop closures left beyond the error bars and solves again without them.
  void optimise();

  const SE2& nodePose(int node) const { return nodes_[static_cast<std::size_t>(node)].T_map; }
  const SE2& submapPose(int submap) const { return submaps_[static_cast<std::size_t>(submap)]; }
  int nodeCount() const { return static_cast<int>(nodes_.size()); }
  int submapCount() const { return static_cast<int>(submaps_.size()); }
  const std::vector<PoseGraphConstraint>& constraints() const { return constraints_; }
  const PoseGraphCounters& counters() const { return counters_; }
  /// Translation and rotation error of a constraint at the current poses.
  std::pair<double, double> errorOf(const PoseGraphConstraint& constraint) const;

 private:
  struct Node {
    SE2 T_map;
    SE2 T_local;
  };
  void solve();
  /// Deactivates closures beyond the error bars; true when any was.
  bool refuseClosuresOffTheSolution();

  const PoseGraphSettings settings_;
  std::vector<Node> nodes_;
  std::vector<SE2> submaps_;
  std::vector<PoseGraphConstraint> constraints_;
  PoseGraphCounters counters_;
};

}  // namespace mrslam::robot::slam
