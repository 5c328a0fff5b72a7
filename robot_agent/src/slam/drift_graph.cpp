#include "mrslam/robot/slam/drift_graph.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

namespace mrslam::robot::slam {

void DriftGraph::addNode(double travelled_m) {
  travelled_m_.push_back(travelled_m);
  shortcuts_.emplace_back();
  distances_.push_back(horizon_m_);
}

void DriftGraph::addShortcut(int node_a, int node_b) {
  const int n = nodeCount();
  if (node_a == node_b || node_a < 0 || node_b < 0 || node_a >= n || node_b >= n) {
    return;
  }
  shortcuts_[static_cast<std::size_t>(node_a)].push_back(node_b);
  shortcuts_[static_cast<std::size_t>(node_b)].push_back(node_a);
}

void DriftGraph::clearShortcuts() {
  for (std::vector<int>& links : shortcuts_) {
    links.clear();
  }
}

void DriftGraph::relax(int node, double distance) {
  double& current = distances_[static_cast<std::size_t>(node)];
  if (distance >= current || distance >= horizon_m_) {
    return;
  }
  current = distance;
  heap_.emplace_back(distance, node);
  std::push_heap(heap_.begin(), heap_.end(), std::greater<>());
}

const std::vector<double>& DriftGraph::distancesFrom(int source, double horizon_m) {
  std::fill(distances_.begin(), distances_.end(), horizon_m);
  heap_.clear();
  horizon_m_ = horizon_m;
  if (source < 0 || source >= nodeCount()) {
    return distances_;
  }
  relax(source, 0.0);
  while (!heap_.empty()) {
    std::pop_heap(heap_.begin(), heap_.end(), std::greater<>());
    const auto [distance, node] = heap_.back();
    heap_.pop_back();
    if (distance > distances_[static_cast<std::size_t>(node)]) {
      continue;  // a stale entry: the node was reached by a shorter way since
    }
    const auto i = static_cast<std::size_t>(node);
    if (node > 0) {
      relax(node - 1, distance + std::abs(travelled_m_[i] - travelled_m_[i - 1]));
    }
    if (node + 1 < nodeCount()) {
      relax(node + 1, distance + std::abs(travelled_m_[i + 1] - travelled_m_[i]));
    }
    for (const int other : shortcuts_[i]) {
      relax(other, distance);
    }
  }
  return distances_;
}

}  // namespace mrslam::robot::slam
