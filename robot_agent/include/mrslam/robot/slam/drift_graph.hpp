#pragma once
// How far two scan nodes have drifted apart: the length of the shortest way between them along
// the trajectory, where every accepted loop closure is a shortcut of length zero (it ties its
// node to its submap's frame, the submap stood for by its middle node). Loop closure windows
// grow with it: a node and a submap tied through other places by closures have drifted apart
// only by the path from those ties, and a place the robot never closed a loop with keeps the
// whole path's drift, however many closures happened elsewhere since.

#include <cstddef>
#include <vector>

namespace mrslam::robot::slam {

class DriftGraph {
 public:
  /// The next node, `travelled_m` along the path from the start (never less than the last).
  void addNode(double travelled_m);
  /// A closure between two nodes (no-op for an unknown node or a node with itself).
  void addShortcut(int node_a, int node_b);
  /// Forgets every shortcut (before re-adding those of the closures still accepted).
  void clearShortcuts();

  /// The drift distance from `source` to every node, capped at `horizon_m`: beyond it nothing
  /// is explored (every farther node reads horizon_m). Valid until the next call.
  const std::vector<double>& distancesFrom(int source, double horizon_m);

  int nodeCount() const { return static_cast<int>(travelled_m_.size()); }

 private:
  void relax(int node, double distance);

  std::vector<double> travelled_m_;
  std::vector<std::vector<int>> shortcuts_;  ///< by node
  std::vector<double> distances_;
  std::vector<std::pair<double, int>> heap_;
  double horizon_m_ = 0.0;
};

}  // namespace mrslam::robot::slam
