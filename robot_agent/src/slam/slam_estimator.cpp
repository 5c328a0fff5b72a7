#include "mrslam/robot/slam/slam_estimator.hpp"

#include <cmath>

#include <spdlog/spdlog.h>

#include "mrslam/robot/slam/map_renderer.hpp"

namespace mrslam::robot::slam {

namespace {

EkfSettings frontEndSettings(EkfSettings ekf) {
  ekf.scan_matching.enabled = false;  // the submap match is its scan update
  return ekf;
}

}  // namespace

SlamEstimator::SlamEstimator(const DiffDriveParams& platform, const SensorMounting& mounting,
                             const SlamSettings& settings)
    : mounting_(mounting),
      settings_(settings),
      ekf_(platform, mounting, frontEndSettings(settings.ekf)),
      active_(settings.submaps),
      local_matcher_(settings.local_matching),
      correlative_matcher_(settings.correlative),
      graph_(settings.pose_graph),
      closer_(settings.loop_closure) {}

void SlamEstimator::addScan(const LaserScan& scan, const OccupancyGrid& map) {
  ++counters_.scans;
  ekf_.addScan(scan, map);  // predicts up to the scan
  const RangeData data = rangeDataOf(scan, mounting_.T_robot_laser, settings_.range_data);
  std::vector<Eigen::Vector2d> points = matchingPoints(data.hits, settings_.range_data);
  matchScan(points, scan.stamp);
  const SE2 T_local_robot = ekf_.pose();
  if (passesMotionFilter(T_local_robot, scan.stamp)) {
    addNode(data, std::move(points), scan.stamp);
  }
  if (nodes_.empty()) {
    scans_.push_back({-1, T_local_robot});
  } else {
    scans_.push_back({static_cast<int>(nodes_.size()) - 1,
                      nodes_.back().T_local_node.inverse() * T_local_robot});
  }
}

void SlamEstimator::matchScan(const std::vector<Eigen::Vector2d>& points, Stamp stamp) {
  const std::shared_ptr<const Submap> submap = active_.matchingSubmap();
  if (!submap || points.empty()) {
    return;
  }
  const SE2 T_submap_local = submap->T_local_submap.inverse();
  SE2 T_submap_start = T_submap_local * ekf_.pose();
  const Eigen::Matrix3d P = ekf_.covariance();
  const double sigma_xy = std::sqrt(std::max(P(0, 0), P(1, 1)));
  const double sigma_theta = std::sqrt(P(2, 2));
  if (sigma_xy > settings_.correlative_sigma_xy_m ||
      sigma_theta > settings_.correlative_sigma_theta_rad) {
    ++counters_.correlative_searches;
    const std::optional<CorrelativeMatch> coarse =
        correlative_matcher_.match(submap->grid, T_submap_start, points);
    if (coarse) {
      T_submap_start = coarse->T_submap_robot;
    }
  }
  const std::optional<CeresMatch> fine = local_matcher_.match(submap->grid, T_submap_start, points);
  if (!fine) {
    ++counters_.match_failures;
    return;
  }
  ++counters_.matches;
  const SE2 T_local_predicted = ekf_.pose();
  const SE2 T_local_matched = submap->T_local_submap * fine->T_submap_robot;
  // The fit's covariance is in the submap frame, which is the local frame shifted: same axes.
  const Correction correction =
      ekf_.updateWithScanPose(T_local_matched, fine->covariance, settings_.gate_matches);
  if (!correction.accepted) {
    ++counters_.match_rejections;
    const SE2 disagreement = T_local_predicted.inverse() * T_local_matched;
    spdlog::debug(
        "slam: scan at {:.2f} s: match gated out (d² {:.1f}): {:.3f} m {:.2f} deg from "
        "the prediction",
        stamp.seconds(), correction.mahalanobis_sq, disagreement.translation().norm(),
        disagreement.theta() * 180 / M_PI);
  }
}

bool SlamEstimator::passesMotionFilter(const SE2& T_local_robot, Stamp stamp) const {
  if (nodes_.empty()) {
    return true;
  }
  const NodeData& last = nodes_.back();
  const SE2 moved = last.T_local_node.inverse() * T_local_robot;
  const MotionFilterSettings& filter = settings_.motion_filter;
  return moved.translation().norm() >= filter.max_distance_m ||
         std::abs(moved.theta()) >= filter.max_angle_rad ||
         std::abs(secondsBetween(last.stamp, stamp)) >= filter.max_time_s;
}

void SlamEstimator::addNode(const RangeData& data_robot, std::vector<Eigen::Vector2d> points,
                            Stamp stamp) {
  const SE2 T_local_node = ekf_.pose();
  if (!nodes_.empty()) {
    travelled_m_ += (nodes_.back().T_local_node.inverse() * T_local_node).translation().norm();
  }
  const std::vector<std::shared_ptr<Submap>> inserted =
      active_.insert(transformed(data_robot, T_local_node));
  for (const auto& submap : inserted) {
    if (submap->id >= graph_.submapCount()) {
      submaps_.push_back(submap);
      submap_first_node_.push_back(static_cast<int>(nodes_.size()));
      graph_.addSubmap(T_map_local_ * submap->T_local_submap);
      ++counters_.submaps;
    }
  }
  const int node = graph_.addNode(T_map_local_ * T_local_node, T_local_node);
  nodes_.push_back({T_local_node, std::move(points), stamp});
  drift_.addNode(travelled_m_);
  ++counters_.nodes;
  ++version_;
  for (const auto& submap : inserted) {
    PoseGraphConstraint constraint;
    constraint.submap = submap->id;
    constraint.node = node;
    constraint.T_submap_node = submap->T_local_submap.inverse() * T_local_node;
    graph_.addConstraint(constraint);
  }
  if (settings_.loop_closure.enabled) {
    searchClosuresOfNode(node);
    if (const std::shared_ptr<Submap>& finished = active_.finishedByLastInsert()) {
      closer_.addFinishedSubmap(finished);
      searchClosuresInSubmap(finished->id);
    }
  }
  ++nodes_since_solve_;
  optimiseIfDue();
}

void SlamEstimator::searchClosuresOfNode(int node) {
  const std::vector<double>& drift_m = drift_.distancesFrom(node, closer_.saturatingDrift());
  for (const auto& submap : submaps_) {
    if (closer_.isSearchable(submap->id)) {
      tryClosure(submap->id, node, drift_m[static_cast<std::size_t>(middleNodeOf(submap->id))]);
    }
  }
}

void SlamEstimator::searchClosuresInSubmap(int submap) {
  const std::vector<double>& drift_m =
      drift_.distancesFrom(middleNodeOf(submap), closer_.saturatingDrift());
  for (int node = 0; node < static_cast<int>(nodes_.size()); ++node) {
    tryClosure(submap, node, drift_m[static_cast<std::size_t>(node)]);
  }
}

int SlamEstimator::middleNodeOf(int submap) const {
  const int middle =
      submap_first_node_[static_cast<std::size_t>(submap)] + settings_.submaps.num_range_data;
  return std::min(middle, static_cast<int>(nodes_.size()) - 1);
}

void SlamEstimator::resetDriftShortcuts() {
  drift_.clearShortcuts();
  for (const PoseGraphConstraint& c : graph_.constraints()) {
    if (c.active && c.kind == PoseGraphConstraint::Kind::kLoopClosure) {
      drift_.addShortcut(c.node, middleNodeOf(c.submap));
    }
  }
}

void SlamEstimator::tryClosure(int submap, int node, double drift_m) {
  const SE2 T_submap_node = graph_.submapPose(submap).inverse() * graph_.nodePose(node);
  if (T_submap_node.translation().norm() > settings_.loop_closure.max_constraint_distance_m) {
    return;
  }
  const std::optional<LoopClosure> closure =
      closer_.search(submap, T_submap_node, nodes_[static_cast<std::size_t>(node)].points, drift_m);
  if (!closure) {
    return;
  }
  PoseGraphConstraint constraint;
  constraint.submap = submap;
  constraint.node = node;
  constraint.T_submap_node = closure->T_submap_node;
  constraint.kind = PoseGraphConstraint::Kind::kLoopClosure;
  graph_.addConstraint(constraint);
  ++counters_.closures;
  const SE2 correction = T_submap_node.inverse() * closure->T_submap_node;
  spdlog::debug(
      "slam: closure of node {} ({:.2f} s) in submap {}: score {:.2f}, {:.3f} m {:.2f} "
      "deg from the estimate",
      node, nodes_[static_cast<std::size_t>(node)].stamp.seconds(), submap, closure->score,
      correction.translation().norm(), correction.theta() * 180 / M_PI);
  drift_.addShortcut(node, middleNodeOf(submap));
}

void SlamEstimator::optimiseIfDue() {
  if (nodes_since_solve_ < settings_.optimise_every_n_nodes ||
      counters_.closures == closures_at_solve_) {
    return;
  }
  optimise();
}

void SlamEstimator::optimise() {
  const SE2 before = graph_.nodePose(graph_.nodeCount() - 1);
  graph_.optimise();
  resetDriftShortcuts();
  const SE2 after = graph_.nodePose(graph_.nodeCount() - 1);
  spdlog::debug("slam: solve {}: {} closures ({} refused), newest node moved {:.3f} m {:.2f} deg",
                graph_.counters().solves, counters_.closures, graph_.counters().closures_refused,
                (before.inverse() * after).translation().norm(),
                (before.inverse() * after).theta() * 180 / M_PI);
  nodes_since_solve_ = 0;
  closures_at_solve_ = counters_.closures;
  const NodeData& last = nodes_.back();
  T_map_local_ = graph_.nodePose(graph_.nodeCount() - 1) * last.T_local_node.inverse();
  ++version_;
}

void SlamEstimator::finish() {
  if (!nodes_.empty() && counters_.closures != closures_at_solve_) {
    optimise();
  }
}

const OccupancyGrid* SlamEstimator::map() const {
  if (!map_ || map_version_ != version_) {
    std::vector<PlacedSubmap> placed;
    placed.reserve(submaps_.size());
    for (const auto& submap : submaps_) {
      placed.push_back({submap, graph_.submapPose(submap->id)});
    }
    map_ = renderSubmaps(placed, settings_.map_resolution_m, LogOddsParams{});
    map_version_ = version_;
  }
  return &*map_;
}

std::vector<SE2> SlamEstimator::revisedScanPoses() const {
  std::vector<SE2> poses;
  poses.reserve(scans_.size());
  for (const ScanRecord& scan : scans_) {
    poses.push_back(scan.node < 0 ? T_map_local_ * scan.T_node_scan
                                  : graph_.nodePose(scan.node) * scan.T_node_scan);
  }
  return poses;
}

}  // namespace mrslam::robot::slam
