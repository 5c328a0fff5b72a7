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
  matchScan(points);
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

void SlamEstimator::matchScan(const std::vector<Eigen::Vector2d>& points) {
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
  // The fit's covariance is in the submap frame, which is the local frame shifted: same axes.
  const Correction correction =
      ekf_.updateWithScanPose(submap->T_local_submap * fine->T_submap_robot, fine->covariance);
  if (!correction.accepted) {
    ++counters_.match_rejections;
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
      submap_travelled_m_.push_back(travelled_m_);
      graph_.addSubmap(T_map_local_ * submap->T_local_submap);
      ++counters_.submaps;
    }
  }
  const int node = graph_.addNode(T_map_local_ * T_local_node, T_local_node);
  nodes_.push_back({T_local_node, std::move(points), travelled_m_, stamp});
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
  for (const auto& submap : submaps_) {
    if (closer_.isSearchable(submap->id)) {
      tryClosure(submap->id, node);
    }
  }
}

void SlamEstimator::searchClosuresInSubmap(int submap) {
  for (int node = 0; node < static_cast<int>(nodes_.size()); ++node) {
    tryClosure(submap, node);
  }
}

void SlamEstimator::tryClosure(int submap, int node) {
  const SE2 T_submap_node = graph_.submapPose(submap).inverse() * graph_.nodePose(node);
  if (T_submap_node.translation().norm() > settings_.loop_closure.max_constraint_distance_m) {
    return;
  }
  // The search window grows with the local drift the node and the submap may hold between
  // them: the path from one to the other, unless a closure over a long path since then has
  // tied the current pose to the rest of the map.
  const double path_gap_m = std::abs(nodes_[static_cast<std::size_t>(node)].travelled_m -
                                     submap_travelled_m_[static_cast<std::size_t>(submap)]);
  const double since_long_closure_m = std::max(0.0, travelled_m_ - last_closure_travelled_m_);
  const double travelled = std::min(path_gap_m, since_long_closure_m);
  const std::optional<LoopClosure> closure = closer_.search(
      submap, T_submap_node, nodes_[static_cast<std::size_t>(node)].points, travelled);
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
  if (path_gap_m >= settings_.loop_closure.window_reset_path_m) {
    last_closure_travelled_m_ = travelled_m_;
  }
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
