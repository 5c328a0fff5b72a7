#include "mrslam/fusion/team_graph.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <set>

#include "mrslam/fusion/pose_graph.hpp"

namespace mrslam::fusion {

namespace {

PairwiseEstimate inverted(const PairwiseEstimate& estimate) {
  PairwiseEstimate inverse = estimate;
  inverse.from = estimate.to;
  inverse.to = estimate.from;
  inverse.T_to_from = estimate.T_to_from.inverse();
  return inverse;
}

// The estimate as the pair `key` stores it: from the key's first robot.
PairwiseEstimate storedAs(const std::pair<std::string, std::string>& key,
                          const PairwiseEstimate& estimate) {
  return key.first == estimate.from ? estimate : inverted(estimate);
}

// Cost of an edge on a path: −log V, so the cheapest path has the largest product of V.
double edgeCost(const PairwiseEstimate& estimate) {
  return -std::log(std::max(estimate.verification, 1e-12));
}

// Robots joined by the edges taken so far: each group's robots with their pose in the group's
// frame (the first robot's).
class ConnectedGroups {
 public:
  /// T_group_robot, and the group, of a robot (a robot not seen yet is a group of its own).
  std::pair<int, SE2> locate(const std::string& robot) {
    const auto found = where_.find(robot);
    if (found != where_.end()) {
      return found->second;
    }
    const int group = next_group_++;
    where_[robot] = {group, SE2()};
    return where_[robot];
  }
  /// Joins the group of `from` into that of `to` through T_to_from.
  void join(const std::string& from, const std::string& to, const SE2& T_to_from) {
    const auto [group_to, T_gto_to] = locate(to);
    const auto [group_from, T_gfrom_from] = locate(from);
    // Every robot r of from's group: T_gto_r = T_gto_to · T_to_from · T_from_gfrom · T_gfrom_r.
    const SE2 T_gto_gfrom = T_gto_to * T_to_from * T_gfrom_from.inverse();
    for (auto& entry : where_) {
      if (entry.second.first == group_from) {
        entry.second = {group_to, T_gto_gfrom * entry.second.second};
      }
    }
  }

 private:
  std::map<std::string, std::pair<int, SE2>> where_;
  int next_group_ = 0;
};

PoseGraphEdge poseGraphEdge(const PairwiseEstimate& estimate, const PlacementWeights& weights) {
  PoseGraphEdge edge{estimate.from, estimate.to, estimate.T_to_from};
  if (estimate.configured) {
    edge.sigma_translation_m = weights.sigma_config_translation_m;
    edge.sigma_rotation_rad = weights.sigma_config_rotation_rad;
  } else {
    const double v = std::max(estimate.verification, 1e-3);
    edge.sigma_translation_m = weights.sigma_translation_m / v;
    edge.sigma_rotation_rad = weights.sigma_rotation_rad / v;
  }
  return edge;
}

}  // namespace

std::optional<std::map<std::string, SE2>> TeamGraph::leastSquares(
    const std::string& reference, const std::map<std::string, SE2>& initial,
    const std::vector<PairwiseEstimate>& kept) const {
  std::vector<PoseGraphEdge> edges;
  for (const PairwiseEstimate& estimate : kept) {
    if (initial.count(estimate.from) && initial.count(estimate.to)) {
      edges.push_back(poseGraphEdge(estimate, weights_));
    }
  }
  // A spanning tree has one edge fewer than robots: only more than that makes a loop.
  if (edges.size() + 1 <= initial.size()) {
    return std::nullopt;
  }
  return optimisePoseGraph(initial, edges, {reference}).T_reference_robot;
}

std::vector<PairwiseEstimate> TeamGraph::consistentEdges(std::vector<DroppedEdge>* dropped) const {
  std::vector<PairwiseEstimate> ordered;
  for (const auto& entry : edges_) {
    ordered.push_back(entry.second);
  }
  std::stable_sort(ordered.begin(), ordered.end(),
                   [](const PairwiseEstimate& a, const PairwiseEstimate& b) {
                     if (a.configured != b.configured) {
                       return a.configured;
                     }
                     return a.verification > b.verification;
                   });
  ConnectedGroups groups;
  std::vector<PairwiseEstimate> kept;
  for (const PairwiseEstimate& edge : ordered) {
    const auto [group_from, T_g_from] = groups.locate(edge.from);
    const auto [group_to, T_g_to] = groups.locate(edge.to);
    if (group_from != group_to) {
      groups.join(edge.from, edge.to, edge.T_to_from);
      kept.push_back(edge);
      continue;
    }
    // A loop: the edge against the path of the edges already taken.
    const SE2 along_loop = T_g_to.inverse() * T_g_from;
    const double translation = (along_loop.translation() - edge.T_to_from.translation()).norm();
    const double rotation = std::abs(wrapAngle(along_loop.theta() - edge.T_to_from.theta()));
    if (edge.configured ||
        (translation <= tolerance_.translation_m && rotation <= tolerance_.rotation_rad)) {
      kept.push_back(edge);
    } else if (dropped != nullptr) {
      dropped->push_back({edge, translation, rotation});
    }
  }
  return kept;
}

std::vector<DroppedEdge> TeamGraph::dropped() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<DroppedEdge> dropped;
  consistentEdges(&dropped);
  return dropped;
}

TeamGraph::PairKey TeamGraph::keyOf(const std::string& a, const std::string& b) {
  return a < b ? PairKey{a, b} : PairKey{b, a};
}

void TeamGraph::addConfigured(const std::string& from, const std::string& to,
                              const SE2& T_to_from) {
  PairwiseEstimate estimate;
  estimate.from = from;
  estimate.to = to;
  estimate.T_to_from = T_to_from;
  estimate.verification = 1.0;
  estimate.method = "config";
  estimate.configured = true;
  std::lock_guard<std::mutex> lock(mutex_);
  const PairKey key = keyOf(from, to);
  edges_[key] = storedAs(key, estimate);
}

bool TeamGraph::addVerified(const PairwiseEstimate& estimate) {
  std::lock_guard<std::mutex> lock(mutex_);
  return storeUnlessBetterHeld(keyOf(estimate.from, estimate.to), estimate);
}

bool TeamGraph::storeUnlessBetterHeld(const PairKey& key, const PairwiseEstimate& estimate) {
  const auto found = edges_.find(key);
  if (found != edges_.end()) {
    const PairwiseEstimate& held = found->second;
    const bool held_is_better = held.configured ||
                                (held.from_final_maps && !estimate.from_final_maps) ||
                                (held.from_final_maps == estimate.from_final_maps &&
                                 held.verification > estimate.verification);
    if (held_is_better) {
      return false;
    }
  }
  edges_[key] = storedAs(key, estimate);
  return true;
}

std::map<TeamGraph::PairKey, PairwiseEstimate>::iterator TeamGraph::heldEstimate(
    const PairKey& key, const std::string& from, const SE2& T_to_from) {
  const auto found = edges_.find(key);
  if (found == edges_.end() || found->second.configured) {
    return edges_.end();
  }
  const SE2 held =
      found->second.from == from ? found->second.T_to_from : found->second.T_to_from.inverse();
  constexpr double kSame = 1e-9;  // the very estimate given, not merely a close one
  const bool same = (held.translation() - T_to_from.translation()).norm() < kSame &&
                    std::abs(wrapAngle(held.theta() - T_to_from.theta())) < kSame;
  return same ? found : edges_.end();
}

bool TeamGraph::withdraw(const std::string& from, const std::string& to, const SE2& T_to_from) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto held = heldEstimate(keyOf(from, to), from, T_to_from);
  if (held == edges_.end()) {
    return false;
  }
  edges_.erase(held);
  return true;
}

bool TeamGraph::replaceVerified(const PairwiseEstimate& estimate, const SE2& T_to_from_replaced) {
  std::lock_guard<std::mutex> lock(mutex_);
  const PairKey key = keyOf(estimate.from, estimate.to);
  const auto held = heldEstimate(key, estimate.from, T_to_from_replaced);
  if (held == edges_.end()) {
    return storeUnlessBetterHeld(key, estimate);
  }
  held->second = storedAs(key, estimate);
  return true;
}

std::optional<PairwiseEstimate> TeamGraph::estimate(const std::string& from,
                                                    const std::string& to) const {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto found = edges_.find(keyOf(from, to));
  if (found == edges_.end()) {
    return std::nullopt;
  }
  return found->second.from == from ? found->second : inverted(found->second);
}

std::vector<PairwiseEstimate> TeamGraph::estimates() const {
  std::lock_guard<std::mutex> lock(mutex_);
  std::vector<PairwiseEstimate> all;
  for (const auto& entry : edges_) {
    all.push_back(entry.second);
  }
  return all;
}

std::vector<Placement> TeamGraph::place(const std::string& reference,
                                        const std::vector<std::string>& robots) const {
  std::lock_guard<std::mutex> lock(mutex_);
  // Dijkstra from the reference over −log V; each robot keeps its pose and weakest V on the way.
  struct Reached {
    double cost = std::numeric_limits<double>::infinity();
    SE2 T_reference_robot;
    double weakest_verification = 1.0;
    bool through_estimates = false;
    std::string methods;  ///< of the estimates on the path, "+"-joined, each once
  };
  std::map<std::string, Reached> reached;
  reached[reference].cost = 0.0;
  using Entry = std::pair<double, std::string>;
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> frontier;
  frontier.push({0.0, reference});
  std::set<std::string> done;
  const std::vector<PairwiseEstimate> kept = consistentEdges(nullptr);
  while (!frontier.empty()) {
    const auto [cost, robot] = frontier.top();
    frontier.pop();
    if (!done.insert(robot).second) {
      continue;
    }
    const Reached here = reached[robot];
    for (const PairwiseEstimate& edge : kept) {
      if (edge.from != robot && edge.to != robot) {
        continue;
      }
      // T_robot_next from the edge, whichever way it was stored.
      const bool forward = edge.to == robot;  // edge maps `from` into `robot`
      const std::string next = forward ? edge.from : edge.to;
      const SE2 T_robot_next = forward ? edge.T_to_from : edge.T_to_from.inverse();
      const double next_cost = cost + edgeCost(edge);
      Reached& there = reached[next];
      if (next_cost < there.cost) {
        there.cost = next_cost;
        there.T_reference_robot = here.T_reference_robot * T_robot_next;
        there.weakest_verification = std::min(here.weakest_verification, edge.verification);
        there.through_estimates = here.through_estimates || !edge.configured;
        there.methods = here.methods;
        if (!edge.configured &&
            ("+" + there.methods + "+").find("+" + edge.method + "+") == std::string::npos) {
          there.methods += (there.methods.empty() ? "" : "+") + edge.method;
        }
        frontier.push({next_cost, next});
      }
    }
  }
  std::map<std::string, SE2> initial;
  for (const auto& entry : reached) {
    if (std::isfinite(entry.second.cost)) {
      initial[entry.first] = entry.second.T_reference_robot;
    }
  }
  // With loops, every placed robot's pose is the least-squares one; else its path's.
  const std::optional<std::map<std::string, SE2>> adjusted = leastSquares(reference, initial, kept);
  std::vector<Placement> placements;
  for (const std::string& robot : robots) {
    Placement placement;
    placement.robot_id = robot;
    const auto found = reached.find(robot);
    if (robot == reference) {
      placement.placed = true;
      placement.source = "reference";
    } else if (found != reached.end() && std::isfinite(found->second.cost)) {
      placement.placed = true;
      placement.T_reference_robot =
          adjusted ? adjusted->at(robot) : found->second.T_reference_robot;
      placement.least_squares = adjusted.has_value() && found->second.through_estimates;
      if (found->second.through_estimates) {
        placement.verification = found->second.weakest_verification;
        placement.methods = found->second.methods;
        placement.source = "merge";
      } else {
        placement.source = "config";
      }
    } else {
      placement.source = "no verified transform to " + reference + " yet";
    }
    placements.push_back(placement);
  }
  return placements;
}

}  // namespace mrslam::fusion
